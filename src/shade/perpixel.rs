//! The per-pixel core: one loop, the full lighting model for every tier,
//! light kind, model and [`Encoder`], serves [`PhongShading`](super::PhongShading)
//! and its normal-mapped and textured forms; the surface's [`Features`]
//! decide what is interpolated and read. Each mode's `Kernel` is written by
//! [`per_pixel_kernel!`] in its own file.
//!
//! The values interpolated, in this order (only what the surface has):
//! the normal (3, Q14), the texture coordinates (2, Q12), the tangent (3,
//! Q14; normal maps), the eye-space position (3, see [`Positions`]; when the
//! lighting reads it).

use super::{eye_point, unit_q14, Encoder, VertexIn};
use crate::color::{OutputColor, Rgb};
use crate::lighting::{Illuminate, LitColor};
use crate::num::ATTR_FRAC;
use crate::num::{Point3, Scalar, Vec3};
use crate::raster::interp::{Varyings, VARYING_LIMIT};
use crate::raster::ClampTo;
use crate::texture::{Filter, NormalMap, TexCoord, Texture, Wrap, TEX_FRAC};

/// Fraction bits of interpolated texture coordinates: Q12 with
/// [`ATTR_FRAC`] bits.
pub(crate) const UV_FRAC: u32 = 12 + ATTR_FRAC;

/// Where a triangle's interpolated eye-space positions are measured from
/// (vertex 0, Q16.16) and their shift (the values hold `(eye − origin) >>
/// shift`, within ±[`VARYING_LIMIT`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Positions {
    origin: [i32; 3],
    shift: u32,
}

impl Positions {
    /// The positions of a triangle of eye positions `eye` and the values of
    /// its corners.
    #[inline]
    pub(crate) fn new(eye: &[[i32; 3]; 3]) -> (Positions, [[i32; 3]; 3]) {
        let o = eye[0];
        let rel = eye.map(|e| core::array::from_fn(|i| i64::from(e[i]) - i64::from(o[i])));
        let big = rel
            .iter()
            .flatten()
            .fold(0u64, |m: u64, v: &i64| m.max(v.unsigned_abs()));
        let mut shift = 0;
        while big >> shift > (VARYING_LIMIT as u64) {
            shift += 1;
        }
        let v = rel.map(|r: [i64; 3]| r.map(|c| (c >> shift) as i32));
        (Positions { origin: o, shift }, v)
    }

    /// The eye position (Q16.16) of interpolated values `a` (with
    /// [`ATTR_FRAC`] bits).
    #[inline(always)]
    pub(crate) fn at(&self, a: [i32; 3]) -> [i32; 3] {
        let sh = ATTR_FRAC as i32 - self.shift as i32;
        core::array::from_fn(|i| {
            let r = if sh > 0 {
                ((a[i] >> (sh - 1)) + 1) >> 1
            } else {
                a[i].wrapping_shl((-sh) as u32)
            };
            self.origin[i].wrapping_add(r)
        })
    }
}

/// A triangle of a per-pixel kernel: its [`Positions`] and the handedness of
/// its tangent frame (normal maps; the majority of its vertices').
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelTriangle {
    pos: Positions,
    hand: i32,
}

/// What a per-pixel surface has: a normal map (the tangent and handedness
/// are carried), a colour texture (`texel × primary + secondary`). A
/// constant of each kernel: the branches on it fold away.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Features {
    pub map: bool,
    pub tex: bool,
}

impl Features {
    /// Lit per pixel with nothing else (payload 3, values 6).
    pub const PLAIN: Features = Features {
        map: false,
        tex: false,
    };
    /// A colour texture (payload 5, values 8).
    pub const TEX: Features = Features {
        map: false,
        tex: true,
    };
    /// A normal map (payload 9, values 11).
    pub const MAPPED: Features = Features {
        map: true,
        tex: false,
    };
    /// A normal map and a colour texture (payload 9, values 11).
    pub const MAPPED_TEX: Features = Features {
        map: true,
        tex: true,
    };

    /// Where the position starts.
    const fn position(self) -> usize {
        3 + if self.map || self.tex { 2 } else { 0 } + if self.map { 3 } else { 0 }
    }

    /// How many values are interpolated (`pos`: the lighting reads the
    /// position).
    pub const fn used(self, pos: bool) -> usize {
        self.position() + if pos { 3 } else { 0 }
    }
}

/// Where the texture coordinates start.
const UV: usize = 3;

/// Where the tangent starts.
const TANGENT: usize = 5;

/// Clamps an `i32` to `i16`.
#[inline]
pub(crate) fn sat16(v: i32) -> i16 {
    v.clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16
}

/// The payload of vertex `v` on surface `f`: the unit normal (Q14), then
/// the texture coordinates (Q12), then the unit tangent and the handedness.
#[inline]
pub(crate) fn vertex<V: Default + AsMut<[i16]>>(f: Features, v: &VertexIn) -> V {
    let mut out = V::default();
    let o = out.as_mut();
    let n = unit_q14(v.normal);
    o.iter_mut().zip(n).for_each(|(o, n)| *o = n);
    if f.map || f.tex {
        if let Some(uv) = o.get_mut(UV..UV + 2) {
            uv[0] = sat16(v.uv[0]);
            uv[1] = sat16(v.uv[1]);
        }
    }
    if f.map {
        let t = unit_q14([v.tangent[0], v.tangent[1], v.tangent[2]]);
        if let Some(tt) = o.get_mut(TANGENT..TANGENT + 4) {
            tt[..3].copy_from_slice(&t);
            tt[3] = if v.tangent[3] < 0 { -1 } else { 1 };
        }
    }
    out
}

/// The handedness of three vertices: the sign of their sum (`+1` on ties and
/// zeros).
#[inline]
fn majority(h: [i32; 3]) -> i32 {
    if h.iter().map(|v| v.signum()).sum::<i32>() < 0 {
        -1
    } else {
        1
    }
}

/// The triangle of payloads `v` and eye positions `eye` on surface `f` (the
/// positions when `pos`) and the values at its corners.
#[inline(always)]
pub(crate) fn triangle<V: AsRef<[i16]>, A: Varyings>(
    f: Features,
    pos: bool,
    v: [&V; 3],
    eye: &[[i32; 3]; 3],
) -> (PixelTriangle, [A; 3]) {
    let (pos, p) = if pos {
        Positions::new(eye)
    } else {
        (Positions::default(), [[0; 3]; 3])
    };
    // (each corner by a constant index or by value: an index taken from an
    // array inside the closure kept a bounds check, a panic path, in the frame)
    let at = |vk: &V, i: usize| vk.as_ref().get(i).copied().map_or(0, i32::from);
    let pp = f.position();
    let corner = |vk: &V, pk: [i32; 3]| {
        A::from_fn(|i| {
            if i < pp {
                at(vk, i)
            } else {
                pk.get(i - pp).copied().unwrap_or(0)
            }
        })
    };
    let [v0, v1, v2] = v;
    let [p0, p1, p2] = p;
    let var = [corner(v0, p0), corner(v1, p1), corner(v2, p2)];
    let hand = if f.map {
        majority([v0, v1, v2].map(|vk| at(vk, TANGENT + 3)))
    } else {
        1
    };
    (PixelTriangle { pos, hand }, var)
}

/// The range of value `i`: the normal and the tangent within [−1, 1] in Q14
/// (Q28 with [`ATTR_FRAC`] bits), the others anywhere.
#[inline(always)]
pub(crate) fn safe(f: Features, i: usize) -> (i32, i32) {
    let one = 1 << (14 + ATTR_FRAC);
    let unit = i < UV || (f.map && (TANGENT..TANGENT + 3).contains(&i));
    if unit {
        (-one, one)
    } else {
        (-(1 << 30), 1 << 30)
    }
}

/// The texture and filter a [`Textured`](super::Textured) shader samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureBinding<'t> {
    pub(crate) texture: Texture<'t>,
    pub(crate) filter: Filter,
}

impl TextureBinding<'_> {
    /// The primary (without the encoder's rounding offset) and secondary
    /// (with it) parts of `lit` in encoder values (each below 2^15).
    #[inline(always)]
    pub(crate) fn parts<S: Scalar, E: Encoder<C>, C: OutputColor>(
        encoder: &E,
        lit: LitColor<S>,
    ) -> ([i32; 3], [i32; 3]) {
        let black = encoder.vertex(Rgb::<S>::BLACK);
        let p = encoder.vertex(lit.primary);
        let s = encoder.vertex(lit.secondary);
        (
            core::array::from_fn(|i| (p[i] - black[i]).clamp(0, 0x7FFF)),
            s.map(|v| v.clamp(0, 0x7FFF)),
        )
    }

    /// The pixel `texel × primary + secondary` at `c` of the lit colour
    /// `lit` (a per-pixel kernel's).
    #[inline(always)]
    pub(crate) fn modulate<S: Scalar, E: Encoder<C>, C: OutputColor>(
        &self,
        encoder: &E,
        lit: LitColor<S>,
        c: TexCoord,
        x: i32,
        y: i32,
    ) -> C {
        let (p, s) = Self::parts(encoder, lit);
        self.pixel(
            encoder,
            p.map(|v| v << ATTR_FRAC),
            s.map(|v| v << ATTR_FRAC),
            c,
            x,
            y,
        )
    }

    /// The pixel `texel × primary + secondary` on encoder values `p`, `s`
    /// (with [`ATTR_FRAC`] bits), clamped to the encoder's range.
    #[inline(always)]
    pub(crate) fn pixel<E: Encoder<C>, C: OutputColor>(
        &self,
        encoder: &E,
        p: [i32; 3],
        s: [i32; 3],
        c: TexCoord,
        x: i32,
        y: i32,
    ) -> C {
        let t = self.texture.sample(c, self.filter);
        let a = core::array::from_fn(|i| {
            let t = i32::from(t[i]);
            let w = t + (t >> 7);
            let (lo, hi) = E::safe(i);
            (p[i] >> 8)
                .wrapping_mul(w)
                .wrapping_add(s[i])
                .clamp_to(lo, hi)
        });
        encoder.pixel(a, x, y)
    }
}

/// What a surface samples: its normal map and its colour texture.
#[derive(Clone, Copy, Debug)]
pub struct Sources<'m, 't> {
    pub(crate) map: Option<NormalMap<'m>>,
    pub(crate) tex: Option<TextureBinding<'t>>,
}

impl Sources<'_, '_> {
    /// Nothing sampled.
    pub(crate) const NONE: Sources<'static, 'static> = Sources {
        map: None,
        tex: None,
    };
}

/// Whether value `i` is a texture coordinate (interpolated exactly: see
/// [`Kernel::exact`](super::Kernel::exact)).
#[inline(always)]
pub(crate) fn exact(f: Features, i: usize) -> bool {
    (f.map || f.tex) && (UV..UV + 2).contains(&i)
}

/// The normal `T·mx + B·my + N·mz` of map texel `m` (Q14) in the frame of
/// interpolated normal `n` and tangent `t` (the tier's attribute scale),
/// `B = hand · N × T`.
#[inline(always)]
fn perturb<S: Scalar>(n: Vec3<S>, t: Vec3<S>, hand: i32, m: [i16; 3]) -> Vec3<S> {
    // the texel (Q14) in the attribute scale (Q26); the bitangent's weight
    // carries the handedness
    let c = |x: i32| S::from_attr(x << 12);
    let (mx, my, mz) = (
        c(i32::from(m[0])),
        c(i32::from(m[1]) * hand),
        c(i32::from(m[2])),
    );
    let b = Vec3::new(
        S::sub(S::mul(n.y, t.z), S::mul(n.z, t.y)),
        S::sub(S::mul(n.z, t.x), S::mul(n.x, t.z)),
        S::sub(S::mul(n.x, t.y), S::mul(n.y, t.x)),
    );
    t.scale(mx).add(b.scale(my)).add(n.scale(mz))
}

/// Shades a span on surface `f` (the positions when `pos`): values `a`
/// stepping by `d`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn span<A: Varyings, I: Illuminate, E: Encoder<C>, C: OutputColor>(
    (f, pos): (Features, bool),
    lighting: &I,
    encoder: &E,
    src: &Sources<'_, '_>,
    t: &PixelTriangle,
    a: &A,
    d: &A,
    x: i32,
    y: i32,
    out: &mut [C],
) {
    let repeat = src.map.is_none_or(|m| m.wrap() == Wrap::Repeat);
    if repeat {
        run::<A, I, E, C, true>((f, pos), lighting, encoder, src, t, *a, d, x, y, out)
    } else {
        run::<A, I, E, C, false>((f, pos), lighting, encoder, src, t, *a, d, x, y, out)
    }
}

/// [`span`] with the normal map's wrap mode a constant (`REPEAT`, else
/// clamped).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn run<A: Varyings, I: Illuminate, E: Encoder<C>, C: OutputColor, const REPEAT: bool>(
    (f, pos): (Features, bool),
    lighting: &I,
    encoder: &E,
    src: &Sources<'_, '_>,
    t: &PixelTriangle,
    mut a: A,
    d: &A,
    x: i32,
    y: i32,
    out: &mut [C],
) {
    type S<I> = <I as Illuminate>::Scalar;
    let n_used = f.used(pos);
    let map = if f.map {
        src.map.map(|m| m.nearest(UV_FRAC))
    } else {
        None
    };
    let tex = if f.tex { src.tex } else { None };
    for (x, c) in (x..).zip(out.iter_mut()) {
        let v = a.values();
        let at = |i: usize| v.get(i).copied().unwrap_or(0);
        // Q14 with ATTR_FRAC bits (Q28) → the tier's attribute (Q26)
        let q = |i: usize| {
            Vec3::new(
                S::<I>::from_attr(at(i) >> 2),
                S::<I>::from_attr(at(i + 1) >> 2),
                S::<I>::from_attr(at(i + 2) >> 2),
            )
        };
        let (u, w) = (at(UV), at(UV + 1));
        let mut n = q(0);
        if let Some(m) = &map {
            n = perturb(n, q(TANGENT), t.hand, m.get::<REPEAT>(u, w));
        }
        let n = S::<I>::normalize_interpolated(n);
        let p: Point3<S<I>> = if pos {
            let p = f.position();
            eye_point::<S<I>>(t.pos.at([at(p), at(p + 1), at(p + 2)]))
        } else {
            eye_point::<S<I>>([0; 3])
        };
        *c = match &tex {
            Some(b) => {
                let tc = TexCoord {
                    u: u >> (UV_FRAC - TEX_FRAC),
                    v: w >> (UV_FRAC - TEX_FRAC),
                };
                b.modulate(encoder, lighting.shade_parts(&p, n, None), tc, x, y)
            }
            None => encoder.encode(lighting.shade(&p, n), x, y),
        };
        // the values after the last pixel are not used: wrapping is harmless
        for (a, d) in a.values_mut().iter_mut().zip(d.values()).take(n_used) {
            *a = a.wrapping_add(*d);
        }
        crate::num::no_unroll();
    }
}

/// The `Kernel` of a per-pixel mode over this core: `Shader<'_, $mode, I, E,
/// C>` with the surface's [`Features`], its payload and value counts, and the
/// [`Sources`] of its shader's state (`|state| sources`).
macro_rules! per_pixel_kernel {
    ([$($g:lifetime),*] $mode:ty, $features:expr, [i16; $v:literal], [i32; $n:literal], |$st:ident| $sources:expr) => {
        impl<$($g,)* I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel
            for Shader<'_, $mode, I, E, C>
        {
            type Color = C;
            type Vertex = [i16; $v];
            type Varyings = [i32; $n];
            type Triangle = PixelTriangle;
            const USED: usize = $features.used(I::NEEDS_POSITION);
            const NEEDS_POSITION: bool = I::NEEDS_POSITION;
            const NEEDS_TEXCOORD: bool = $features.map || $features.tex;
            const NEEDS_TANGENT: bool = $features.map;

            #[inline]
            fn vertex(&self, v: &VertexIn) -> [i16; $v] {
                perpixel::vertex($features, v)
            }

            #[inline(always)]
            fn triangle(
                &self,
                v: [&[i16; $v]; 3],
                eye: &[[i32; 3]; 3],
            ) -> (PixelTriangle, [[i32; $n]; 3]) {
                perpixel::triangle($features, I::NEEDS_POSITION, v, eye)
            }

            #[inline(always)]
            fn safe(&self, i: usize) -> (i32, i32) {
                perpixel::safe($features, i)
            }

            /// The texture coordinates.
            #[inline(always)]
            fn exact(&self, i: usize) -> bool {
                perpixel::exact($features, i)
            }

            #[inline(always)]
            fn span(
                &self,
                t: &PixelTriangle,
                a: &[i32; $n],
                d: &[i32; $n],
                x: i32,
                y: i32,
                out: &mut [C],
            ) {
                let $st = &self.state;
                let src: Sources<'_, '_> = $sources;
                let mode = ($features, I::NEEDS_POSITION);
                perpixel::span(mode, self.lighting, &self.encoder, &src, t, a, d, x, y, out)
            }
        }
    };
}
pub(crate) use per_pixel_kernel;
