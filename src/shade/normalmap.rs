//! Normal-mapped Phong shading: per-pixel lighting with the normal of a
//! [`NormalMap`] in the tangent frame of the surface.

use super::{eye_point, raster_draw, unit_q14, Encoder, Kernel, ShadeVertex};
use crate::color::{OutputColor, Rgb};
use crate::lighting::{Illuminate, Specular};
use crate::normal_map::{NormalMap, NormalTexel, Wrap};
use crate::num::rsqrt::{rsqrt_q14_mantissa, split_u32};
use crate::num::{Scalar, Q14};
use crate::raster::setup::{at3, bit_length};
use crate::raster::{DrawStats, Plane, RasterOptions, Setup, SpanShader, ATTR_FRAC, ATTR_LIMIT};
use crate::render::Lerp;
use crate::target::{DepthBuffer, Framebuffer};
use crate::vector::{Point3, Vec3};
use core::marker::PhantomData;

use super::incremental::{channel_units, DirectionalLighting, IncrementalModel, PowTable};

/// One vertex of a normal-mapped triangle for the per-triangle API
/// ([`NormalMapShader::draw`], [`FastNormalMapShader::draw`]): a
/// [`ShadeVertex`] with texture coordinates and a tangent frame.
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::shade::NormalMapVertex;
/// let v = ShadeVertex::<Q14>::new([0, 0], 0, 1, [0.0; 3], [0.0, 0.0, 1.0]);
/// let nv = NormalMapVertex::new(v, [0.25, 0.5], [1.0, 0.0, 0.0, -1.0]);
/// assert_eq!(nv.uv, [1024, 2048]);
/// assert_eq!(nv.handedness, -1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalMapVertex<S: Scalar> {
    /// Screen position, depth, `1/w`, eye position and unit normal.
    pub vertex: ShadeVertex<S>,
    /// Texture coordinates with [`TEXCOORD_FRAC`](crate::mesh::TEXCOORD_FRAC)
    /// (12) fraction bits; `|u|, |v| < 8`.
    pub uv: [i32; 2],
    /// Eye-space unit tangent (along increasing `u`, orthogonal to the normal).
    pub tangent: Vec3<S>,
    /// `+1` or `−1`: the bitangent is `handedness · N × T` (`−1` where the
    /// texture is mirrored; see [`vertex_tangents`](crate::mesh::vertex_tangents)).
    pub handedness: i8,
}

impl<S: Scalar> NormalMapVertex<S> {
    /// A vertex from `f32` texture coordinates and an `f32` tangent
    /// `[tx, ty, tz, w]` (normalised here; `w < 0` is handedness −1), as
    /// [`vertex_tangents`](crate::mesh::vertex_tangents) produces.
    pub fn new(vertex: ShadeVertex<S>, uv: [f32; 2], tangent: [f32; 4]) -> Self {
        let q = |c: f32| libm::roundf(c.clamp(-8.0, 8.0) * 4096.0) as i32;
        Self {
            vertex,
            uv: [q(uv[0]), q(uv[1])],
            tangent: Vec3::from_f32([tangent[0], tangent[1], tangent[2]]).normalize(),
            handedness: if tangent[3] < 0.0 { -1 } else { 1 },
        }
    }
}

/// Texture coordinate fraction bits in the per-triangle API's attributes
/// (`Q12 << 12`).
const TRI_UV_FRAC: u32 = 24;

// ---- the general path -------------------------------------------------------------

/// The general normal-mapped shader: every tier, every light kind, every
/// reflection model, any [`Encoder`] (see [`NormalMapShading`](super::NormalMapShading)).
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::normal_map::{NormalMap, Wrap, FLAT_NORMAL};
/// use fixshade::shade::{NormalMapShader, NormalMapVertex};
/// use fixshade::raster::SUBPIXEL_BITS;
///
/// static MAP: [[i16; 3]; 4] = [FLAT_NORMAL, [0, 11585, 11585], FLAT_NORMAL, [11585, 0, 11585]];
/// let map = NormalMap::new(&MAP, 1, 1, Wrap::Repeat).unwrap();
/// let light = PointLight::<f32>::new([0.0, 0.0, 2.0], Attenuation::none::<f32>(), LightColors::white()).unwrap();
/// let mat = Material::new(&MaterialDesc::classic([0.2, 0.6, 1.0], AmbientSource::Object, 0.1, 0.7, 0.4, 16.0)).unwrap();
/// let lighting = Lighting::<f32, _, BlinnPhong>::new(light, mat);
/// let v = |x: i32, y: i32, uv: [f32; 2]| NormalMapVertex::new(
///     ShadeVertex::new([x << SUBPIXEL_BITS, y << SUBPIXEL_BITS], 0, 1, [x as f32 / 16.0, -y as f32 / 16.0, -1.0], [0.0, 0.0, 1.0]),
///     uv, [1.0, 0.0, 0.0, 1.0]);
/// let tri = [v(0, 0, [0.0, 0.0]), v(0, 32, [0.0, 4.0]), v(32, 0, [4.0, 0.0])];
/// let mut pixels = [Rgb565::BLACK; 32 * 32];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 32, 32).unwrap();
/// let mut shader = NormalMapShader::new(&lighting, map, Linear);
/// let stats = shader.draw(&mut fb, None, &tri, &RasterOptions::default())?;
/// assert!(stats.pixels > 400);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub struct NormalMapShader<'l, 'm, I: Illuminate, E, C> {
    lighting: &'l I,
    encoder: E,
    map: NormalMap<'m>,
    /// Per-triangle API: the position origin, the shift of the position
    /// attributes and the handedness of the triangle being drawn.
    origin: Point3<I::Scalar>,
    shift: u32,
    hand: i32,
    color: PhantomData<C>,
}

impl<I: Illuminate, E: Copy, C> Clone for NormalMapShader<'_, '_, I, E, C> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<I: Illuminate, E: Copy, C> Copy for NormalMapShader<'_, '_, I, E, C> {}

impl<I: Illuminate, E: core::fmt::Debug, C> core::fmt::Debug for NormalMapShader<'_, '_, I, E, C> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("NormalMapShader")
            .field("encoder", &self.encoder)
            .field("map", &self.map)
            .finish_non_exhaustive()
    }
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

impl<'l, 'm, S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>
    NormalMapShader<'l, 'm, I, E, C>
{
    /// A shader lighting with `lighting`, the surface detail from `map`, writing
    /// pixels through `encoder`.
    pub fn new(lighting: &'l I, map: NormalMap<'m>, encoder: E) -> Self {
        let z = S::geo_from_f32(0.0);
        Self {
            lighting,
            encoder,
            map,
            origin: Vec3::new(z, z, z),
            shift: 0,
            hand: 1,
            color: PhantomData,
        }
    }

    /// The normal map.
    pub fn map(&self) -> NormalMap<'m> {
        self.map
    }

    /// The colour of one pixel: interpolated normal `n` and tangent `t` (the
    /// tier's attribute scale, not normalised), handedness `hand`, map texel
    /// `m`, position `p`.
    #[inline(always)]
    fn pixel(&self, n: [i32; 3], t: [i32; 3], hand: i32, m: NormalTexel, p: &Point3<S>) -> Rgb<S> {
        let v = |a: [i32; 3]| Vec3::new(S::from_attr(a[0]), S::from_attr(a[1]), S::from_attr(a[2]));
        let (n, t) = (v(n), v(t));
        // the texel (Q14) in the attribute scale (Q26); the bitangent's weight
        // carries the handedness
        let c = |x: i32| S::from_attr(x << 12);
        let (mx, my, mz) = (
            c(i32::from(m[0])),
            c(i32::from(m[1]) * hand),
            c(i32::from(m[2])),
        );
        // B = N × T
        let b = Vec3::new(
            S::sub(S::mul(n.y, t.z), S::mul(n.z, t.y)),
            S::sub(S::mul(n.z, t.x), S::mul(n.x, t.z)),
            S::sub(S::mul(n.x, t.y), S::mul(n.y, t.x)),
        );
        let np = t.scale(mx).add(b.scale(my)).add(n.scale(mz));
        self.lighting.shade(p, S::normalize_interpolated(np))
    }

    fn draw_any<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[NormalMapVertex<S>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        self.hand = majority(tri.map(|v| i32::from(v.handedness)));
        let a = |t: &NormalMapVertex<S>| {
            let (n, g) = (t.vertex.normal, t.tangent);
            [
                n.x.to_attr(),
                n.y.to_attr(),
                n.z.to_attr(),
                g.x.to_attr(),
                g.y.to_attr(),
                g.z.to_attr(),
                t.uv[0] << (TRI_UV_FRAC - 12),
                t.uv[1] << (TRI_UV_FRAC - 12),
            ]
        };
        if !I::NEEDS_POSITION {
            let v = tri.map(|t| t.vertex.raster(a(&t)));
            return raster_draw(fb, depth, &v, opts, self, perspective);
        }
        // positions relative to the first vertex, as in PhongShading
        let o = tri[0].vertex.position;
        let rel = tri.map(|t| {
            let p = t.vertex.position;
            [
                S::geo_to_attr(S::geo_sub(p.x, o.x)),
                S::geo_to_attr(S::geo_sub(p.y, o.y)),
                S::geo_to_attr(S::geo_sub(p.z, o.z)),
            ]
        });
        let big = rel
            .iter()
            .flatten()
            .fold(0u32, |m, v| m.max(v.unsigned_abs()));
        let limit_bits = bit_length(ATTR_LIMIT as u32) - 1;
        self.shift = bit_length(big).saturating_sub(limit_bits);
        self.origin = o;
        let shift = self.shift;
        let v = core::array::from_fn(|i| {
            let b = a(&tri[i]);
            let r = rel[i].map(|v| v >> shift);
            let mut x = [0i32; 11];
            x[..8].copy_from_slice(&b);
            x[8..].copy_from_slice(&r);
            tri[i].vertex.raster(x)
        });
        raster_draw(fb, depth, &v, opts, self, perspective)
    }

    /// Rasterizes and shades one triangle (per-triangle API), attributes
    /// (normal, tangent, texture coordinates, position) interpolated linearly
    /// in screen space. Never panics; returns the framebuffer's first error.
    pub fn draw<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[NormalMapVertex<S>; 3],
        opts: &RasterOptions,
    ) -> Result<DrawStats, F::Error> {
        self.draw_any(fb, depth, tri, opts, false)
    }

    /// [`NormalMapShader::draw`] with perspective-correct attributes
    /// (texture coordinates included).
    pub fn draw_perspective<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[NormalMapVertex<S>; 3],
        opts: &RasterOptions,
    ) -> Result<DrawStats, F::Error> {
        self.draw_any(fb, depth, tri, opts, true)
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor, const N: usize>
    SpanShader<N> for NormalMapShader<'_, '_, I, E, C>
{
    type Color = C;
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; N], step: &[i32; N], out: &mut [C]) {
        if N < 8 {
            return;
        }
        let mut a = *start;
        let g = |v: i32| S::geo_from_attr(v << self.shift);
        for (x, p) in (x..).zip(out.iter_mut()) {
            let pos = if N >= 11 {
                Vec3::new(
                    S::geo_add(self.origin.x, g(a[8])),
                    S::geo_add(self.origin.y, g(a[9])),
                    S::geo_add(self.origin.z, g(a[10])),
                )
            } else {
                self.origin
            };
            let m = self.map.sample_fixed(a[6], a[7], TRI_UV_FRAC);
            let c = self.pixel([a[0], a[1], a[2]], [a[3], a[4], a[5]], self.hand, m, &pos);
            *p = self.encoder.encode(c, x, y);
            for i in 0..N {
                a[i] = a[i].wrapping_add(step[i]);
            }
        }
    }
}

/// What the vertex cache holds per vertex for the general path: the Q14
/// eye-space unit normal and tangent, the handedness (±1) and the Q12 texture
/// coordinates (18 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NormalMapPayload {
    n: [i16; 3],
    t: [i16; 3],
    hand: i16,
    uv: [i16; 2],
}

/// `a + (b − a)·num/den` rounded toward `a`, for `num ≤ den`.
#[inline]
fn lerp16(a: i16, b: i16, num: u32, den: u32) -> i16 {
    if den == 0 {
        return a;
    }
    let d = i64::from(b) - i64::from(a);
    let v = i64::from(a) + d * i64::from(num.min(den)) / i64::from(den);
    v.clamp(i64::from(i16::MIN), i64::from(i16::MAX)) as i16
}

impl Lerp for NormalMapPayload {
    fn lerp(&self, o: &Self, num: u32, den: u32) -> Self {
        let l3 = |a: [i16; 3], b: [i16; 3]| core::array::from_fn(|i| lerp16(a[i], b[i], num, den));
        Self {
            n: l3(self.n, o.n),
            t: l3(self.t, o.t),
            hand: if u64::from(num) * 2 <= u64::from(den) {
                self.hand
            } else {
                o.hand
            },
            uv: [
                lerp16(self.uv[0], o.uv[0], num, den),
                lerp16(self.uv[1], o.uv[1], num, den),
            ],
        }
    }
}

/// Clamps an `i32` to `i16`.
#[inline]
fn sat16(v: i32) -> i16 {
    v.clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16
}

/// The planes of a normal-mapped triangle in the mesh renderer (general path):
/// normal, tangent, texture coordinates and, when needed, position.
#[derive(Clone, Copy, Debug)]
pub struct NormalMapTriangle {
    /// normal (3), tangent (3), u, v
    planes: [Plane; 8],
    base: [i32; 8],
    p: [Plane; 3],
    p_base: [i32; 3],
    hand: i32,
}

/// The texture coordinate planes' base (relative to the top vertex) and fraction
/// bits: `(top >> sa) << ATTR_FRAC`, with `12 + ATTR_FRAC − sa` bits.
#[inline]
fn uv_base(top: i32, p: &Plane) -> (i32, u32) {
    let sa = p.sa.min(ATTR_FRAC);
    ((top >> sa) << ATTR_FRAC, 12 + ATTR_FRAC - sa)
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Kernel
    for NormalMapShader<'_, '_, I, E, C>
{
    type Color = C;
    type Vertex = NormalMapPayload;
    type Triangle = NormalMapTriangle;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;
    const NEEDS_TEXCOORD: bool = true;
    const NEEDS_TANGENT: bool = true;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> NormalMapPayload {
        NormalMapPayload {
            n: unit_q14(v.normal),
            t: unit_q14([v.tangent[0], v.tangent[1], v.tangent[2]]),
            hand: if v.tangent[3] < 0 { -1 } else { 1 },
            uv: [sat16(v.uv[0]), sat16(v.uv[1])],
        }
    }

    fn triangle(
        &self,
        s: &Setup,
        v: [&NormalMapPayload; 3],
        p: [[i32; 3]; 3],
    ) -> (NormalMapTriangle, bool) {
        let attrs = v.map(|q| {
            [
                q.n[0], q.n[1], q.n[2], q.t[0], q.t[1], q.t[2], q.uv[0], q.uv[1],
            ]
            .map(i32::from)
        });
        let t = s.tmb[0];
        let planes: [Plane; 8] =
            core::array::from_fn(|i| s.plane([attrs[0][i], attrs[1][i], attrs[2][i]]));
        let top = at3(&attrs, t);
        let base = core::array::from_fn(|i| {
            if i < 6 {
                top[i] << ATTR_FRAC
            } else {
                uv_base(top[i], &planes[i]).0
            }
        });
        let (pp, p_base) = if I::NEEDS_POSITION {
            (
                core::array::from_fn(|i| s.plane([p[0][i], p[1][i], p[2][i]])),
                at3(&p, t),
            )
        } else {
            ([Plane::default(); 3], [0; 3])
        };
        let one = 1 << (14 + ATTR_FRAC);
        let clamp = (0..6).any(|i| !super::within(s, &planes[i], base[i], (-one, one)));
        let tri = NormalMapTriangle {
            planes,
            base,
            p: pp,
            p_base,
            hand: majority(v.map(|q| i32::from(q.hand))),
        };
        (tri, clamp)
    }

    fn skip_rows(t: &mut NormalMapTriangle, rows: i32) {
        for p in t.planes.iter_mut() {
            p.skip_rows(rows);
        }
        if I::NEEDS_POSITION {
            for p in t.p.iter_mut() {
                p.skip_rows(rows);
            }
        }
    }

    fn next_row(t: &mut NormalMapTriangle) {
        for p in t.planes.iter_mut() {
            p.next_row();
        }
        if I::NEEDS_POSITION {
            for p in t.p.iter_mut() {
                p.next_row();
            }
        }
    }

    fn shade<const CLAMP: bool>(&self, t: &NormalMapTriangle, x: i32, y: i32, color: &mut [C]) {
        let len = color.len();
        let mut a = [0i32; 11];
        let mut d = [0i32; 11];
        for i in 0..8 {
            let (s, st) = super::start::<CLAMP>(&t.planes[i], x, len);
            a[i] = t.base[i].wrapping_add(s);
            d[i] = st;
        }
        if I::NEEDS_POSITION {
            for i in 0..3 {
                let (s, st) = super::start::<CLAMP>(&t.p[i], x, len);
                a[8 + i] = s;
                d[8 + i] = st;
            }
        }
        let uf = uv_base(0, &t.planes[6]).1;
        let vf = uv_base(0, &t.planes[7]).1;
        let psh: [u32; 3] = core::array::from_fn(|i| ATTR_FRAC - t.p[i].sa.min(ATTR_FRAC));
        let m_len = if I::NEEDS_POSITION { 11 } else { 8 };
        for (x, c) in (x..).zip(color.iter_mut()) {
            let pos = if I::NEEDS_POSITION {
                // exactly as PhongShading's kernel
                let q = |i: usize| {
                    let sh = psh[i];
                    let r = if sh == 0 {
                        a[8 + i]
                    } else {
                        ((a[8 + i] >> (sh - 1)) + 1) >> 1
                    };
                    t.p_base[i].wrapping_add(r)
                };
                eye_point::<S>([q(0), q(1), q(2)])
            } else {
                eye_point::<S>([0; 3])
            };
            let m = sample2(&self.map, a[6], uf, a[7], vf);
            // Q14 with ATTR_FRAC bits (Q28) → the tier's attribute (Q26)
            let lit = self.pixel(
                [a[0] >> 2, a[1] >> 2, a[2] >> 2],
                [a[3] >> 2, a[4] >> 2, a[5] >> 2],
                t.hand,
                m,
                &pos,
            );
            *c = self.encoder.encode(lit, x, y);
            for (a, d) in a.iter_mut().zip(d).take(m_len) {
                // the values after the last pixel are not used: wrapping is harmless
                *a = a.wrapping_add(d);
            }
        }
    }
}

/// The texel at `(u, v)` with `uf`, `vf` fraction bits.
#[inline(always)]
fn sample2(map: &NormalMap<'_>, u: i32, uf: u32, v: i32, vf: u32) -> NormalTexel {
    let (wl, hl) = map.size_log2();
    let su = uf.saturating_sub(u32::from(wl)).min(31);
    let sv = vf.saturating_sub(u32::from(hl)).min(31);
    map.texel(u >> su, v >> sv)
}

// ---- the fast Q14 path ------------------------------------------------------------

/// The Q14 fast path of normal mapping for one directional light, a viewer at
/// infinity and the [`Lambert`](crate::lighting::Lambert) or
/// [`BlinnPhong`](crate::lighting::BlinnPhong) model (see
/// [`NormalMapShading`](super::NormalMapShading)).
///
/// Per vertex, `L` and `H` are transformed into the vertex's tangent frame
/// `(T, B = w·N × T, N)`; the rasterizer interpolates them (6 attributes,
/// plus `u`, `v`). Per pixel: the texel (a Q14 unit normal, used as stored),
/// `n·L` and `n·H` as three multiply-adds each, both divided by the length
/// of the interpolated `L` and `H` (`1/|L|`, `1/|H|` by one Newton step each
/// from the previous pixel's value, `|L|²`, `|H|²` by forward differences,
/// exact at every span start), `(n·H)^shininess` from the 65-entry table of
/// [`IncrementalPhongShading`](super::IncrementalPhongShading), the colour
/// accumulated in output channel units (rounded like [`Linear`](super::Linear)). Spans whose
/// interpolated `L` or `H` is shorter than ½, or changes length by more than
/// 2^-4 per pixel, are shaded with an exact inverse square root per pixel
/// (same result within the bound, slower). Texture coordinates are
/// screen-affine per triangle.
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::normal_map::{NormalMap, Wrap, FLAT_NORMAL};
/// use fixshade::shade::{FastNormalMapShader, NormalMapVertex};
/// use fixshade::raster::SUBPIXEL_BITS;
///
/// static MAP: [[i16; 3]; 1] = [FLAT_NORMAL];
/// let map = NormalMap::new(&MAP, 0, 0, Wrap::Repeat).unwrap();
/// let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// let mat = Material::new(&MaterialDesc::classic([1.0, 0.2, 0.2], AmbientSource::Object, 0.1, 0.7, 0.5, 32.0)).unwrap();
/// let lighting = Lighting::<Q14, _, BlinnPhong>::new([light], mat);
/// let v = |x: i32, y: i32, n: [f32; 3]| NormalMapVertex::new(
///     ShadeVertex::new([x << SUBPIXEL_BITS, y << SUBPIXEL_BITS], 0, 1, [0.0; 3], n),
///     [0.0, 0.0], [1.0, 0.0, 0.0, 1.0]);
/// let tri = [v(0, 0, [0.0, 0.0, 1.0]), v(0, 32, [0.0, 0.0, 1.0]), v(32, 16, [0.0, 0.0, 1.0])];
/// let mut pixels = [Rgb565::BLACK; 32 * 32];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 32, 32).unwrap();
/// let mut shader = FastNormalMapShader::<_, _, Rgb565>::new(&lighting, map);
/// let stats = shader.draw(&mut fb, None, &tri, &RasterOptions::default())?;
/// assert!(stats.pixels > 400);
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FastNormalMapShader<'l, 'm, const NW: u8, M: IncrementalModel, C> {
    lighting: &'l DirectionalLighting<NW, 1, M>,
    map: NormalMap<'m>,
    /// Direction to the light and halfway vector, Q14.
    l: [i32; 3],
    h: [i32; 3],
    /// `Ld∘Kd`, `Ls∘Ks` and the constant part (+ ½) per channel, channel units · 2^8.
    kd: [i32; 3],
    ks: [i32; 3],
    base: [i32; 3],
    pow: PowTable,
    color: PhantomData<C>,
}

/// What the vertex cache holds per vertex for the fast path: `L` and `H` in
/// the vertex's tangent frame (Q14) and the Q12 texture coordinates (16 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TangentLightPayload {
    lh: [i16; 6],
    uv: [i16; 2],
}

impl Lerp for TangentLightPayload {
    fn lerp(&self, o: &Self, num: u32, den: u32) -> Self {
        Self {
            lh: core::array::from_fn(|i| lerp16(self.lh[i], o.lh[i], num, den)),
            uv: [
                lerp16(self.uv[0], o.uv[0], num, den),
                lerp16(self.uv[1], o.uv[1], num, den),
            ],
        }
    }
}

/// `L` and `H` (Q14) in the tangent frame of Q14 normal `n` (any length),
/// tangent `t` (any length, made orthogonal to `n` here) and handedness `hand`.
fn tangent_space(n: [i32; 3], t: [i32; 3], hand: i32, l: &[i32; 3], h: &[i32; 3]) -> [i16; 6] {
    let n = unit_q14(n).map(i32::from);
    let t = unit_q14(t).map(i32::from);
    // Gram–Schmidt: t − (t·n)n, |t·n| ≤ 2^14
    // products rounded to nearest (a floor would bias n·H low: 2^-14 is
    // 1.3 % of a highlight of exponent 128)
    let q = |v: i32| (v + 8192) >> 14;
    let tn = q(t[0] * n[0] + t[1] * n[1] + t[2] * n[2]);
    let t = unit_q14(core::array::from_fn(|i| t[i] - q(tn * n[i]))).map(i32::from);
    let s = if hand < 0 { -1 } else { 1 };
    let b = [
        s * q(n[1] * t[2] - n[2] * t[1]),
        s * q(n[2] * t[0] - n[0] * t[2]),
        s * q(n[0] * t[1] - n[1] * t[0]),
    ];
    let dot = |a: &[i32; 3], d: &[i32; 3]| sat16(q(a[0] * d[0] + a[1] * d[1] + a[2] * d[2]));
    [
        dot(&t, l),
        dot(&b, l),
        dot(&n, l),
        dot(&t, h),
        dot(&b, h),
        dot(&n, h),
    ]
}

/// `1/√(s/2^28)` in Q14 for `s > 0` (Q28; below `2^20` treated as `2^20`).
#[inline]
fn inv_len_q14(s: i32) -> i32 {
    let s = s.max(1 << 20) as u32;
    let (t, k) = split_u32(s);
    let y = rsqrt_q14_mantissa(t, 2) as i32;
    // 1/√s = y·2^((k − 4)/2) / 2^14, k even, 2 ≤ k ≤ 10
    if k >= 4 {
        y << ((k - 4) / 2)
    } else {
        y >> ((4 - k) / 2)
    }
}

/// `|v|²` (Q28) of a Q24 vector, its first and second forward differences
/// along a span with Q24 step `d`: `(s0, ds0, dds)` as `i64`.
#[inline]
fn length_squared_diffs(v: [i32; 3], d: [i32; 3]) -> (i64, i64, i64) {
    let s0 = v.iter().map(|&c| i64::from(c) * i64::from(c)).sum::<i64>() >> 20;
    let nd = v
        .iter()
        .zip(d)
        .map(|(&a, b)| i64::from(a) * i64::from(b))
        .sum::<i64>()
        >> 20;
    let dd = d.iter().map(|&b| i64::from(b) * i64::from(b)).sum::<i64>() >> 20;
    (s0, 2 * nd + dd, 2 * dd)
}

/// How many Newton steps per pixel keep `1/|v|` at the Q14 resolution for
/// the quadratic `|v(k)|²` (first value `s0`, differences `ds0`, `dds`, Q28)
/// over `n` pixels: one step from the previous pixel's value leaves a
/// relative error of `1.5·e²`, `e` the relative change of `|v|` per pixel.
/// 1 when `|v|²` stays in `[¼, 1.07]` and changes by at most 2^-6 of its
/// smallest value per pixel (`e ≤ 2^-7`: `1.5·e² < 2^-13`, 1.5 Q14 steps),
/// 2 up to 2^-4 (`1.5·(1.5·e²)² < 2^-20`), else 0 (an exact inverse square
/// root per pixel).
fn newton_steps(s0: i64, ds0: i64, dds: i64, n: i64) -> u32 {
    let k = (n - 1).max(0);
    // s(k) = s0 + k·ds0 + k(k−1)/2·dds
    let s_end = s0 + k * ds0 + k * (k - 1) / 2 * dds;
    let dd = dds / 2;
    // the vertex of the parabola: s'(k) = ds0 − dd + 2k·dd = 0
    let nd2 = ds0 - dd; // = 2·(v·d)
    let interior = dd > 0 && nd2 < 0 && nd2 + 2 * k * dd > 0;
    let ends = s0.min(s_end);
    let hi = s0.max(s_end);
    let ds_max = ds0.abs().max((ds0 + k * dds).abs());
    // min s ≥ m, without a division: at the ends, and at the vertex
    // (min = s0 − (v·d)²/|d|², i.e. s0·dd − (v·d)² ≥ m·dd)
    let nd = nd2 / 2;
    let vertex_excess = s0.saturating_mul(dd).saturating_sub(nd.saturating_mul(nd));
    let min_at_least = |m: i64| ends >= m && (!interior || vertex_excess >= m.saturating_mul(dd));
    if !min_at_least(1 << 26) || hi > (1 << 28) + (1 << 24) || dd > 1 << 24 {
        0
    } else if min_at_least(ds_max.saturating_mul(64)) {
        1
    } else if min_at_least(ds_max.saturating_mul(16)) {
        2
    } else {
        0
    }
}

impl<'l, 'm, const NW: u8, M: IncrementalModel, C: OutputColor>
    FastNormalMapShader<'l, 'm, NW, M, C>
{
    /// The fast shader for `lighting` and `map` (the tables are built here,
    /// in `f32`: once per material, not per frame).
    pub fn new(lighting: &'l DirectionalLighting<NW, 1, M>, map: NormalMap<'m>) -> Self {
        let light = &lighting.lights()[0];
        let pre = light.prepared();
        let d = light.direction();
        let h = pre.half.unwrap_or(d);
        Self {
            lighting,
            map,
            l: [d.x.raw(), d.y.raw(), d.z.raw()],
            h: [h.x.raw(), h.y.raw(), h.z.raw()],
            kd: channel_units::<C, NW>(pre.diffuse),
            ks: channel_units::<C, NW>(pre.specular),
            base: channel_units::<C, NW>(lighting.base()).map(|v| v + 128),
            pow: PowTable::new(lighting.material().shininess.to_f32()),
            color: PhantomData,
        }
    }

    /// The normal map.
    pub fn map(&self) -> NormalMap<'m> {
        self.map
    }

    /// The lighting.
    pub fn lighting(&self) -> &'l DirectionalLighting<NW, 1, M> {
        self.lighting
    }

    /// The payload of a vertex with Q14 normal `n`, tangent `t`, handedness
    /// `hand` and Q12 texture coordinates `uv`.
    fn payload(&self, n: [i32; 3], t: [i32; 3], hand: i32, uv: [i32; 2]) -> TangentLightPayload {
        TangentLightPayload {
            lh: tangent_space(n, t, hand, &self.l, &self.h),
            uv: [sat16(uv[0]), sat16(uv[1])],
        }
    }

    /// Rasterizes and shades one triangle (per-triangle API). Never panics;
    /// returns the framebuffer's first error.
    pub fn draw<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[NormalMapVertex<Q14<NW>>; 3],
        opts: &RasterOptions,
    ) -> Result<DrawStats, F::Error> {
        self.draw_any(fb, depth, tri, opts, false)
    }

    /// [`FastNormalMapShader::draw`] with perspective-correct attributes.
    pub fn draw_perspective<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[NormalMapVertex<Q14<NW>>; 3],
        opts: &RasterOptions,
    ) -> Result<DrawStats, F::Error> {
        self.draw_any(fb, depth, tri, opts, true)
    }

    fn draw_any<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[NormalMapVertex<Q14<NW>>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        let v = tri.map(|t| {
            let q = |v: Vec3<Q14<NW>>| [v.x.raw(), v.y.raw(), v.z.raw()];
            let p = self.payload(
                q(t.vertex.normal),
                q(t.tangent),
                i32::from(t.handedness),
                t.uv,
            );
            // Q14 → Q26, Q12 → Q24
            let mut a = [0i32; 8];
            for (a, &c) in a.iter_mut().zip(p.lh.iter()) {
                *a = i32::from(c) << 12;
            }
            a[6] = t.uv[0] << (TRI_UV_FRAC - 12);
            a[7] = t.uv[1] << (TRI_UV_FRAC - 12);
            t.vertex.raster(a)
        });
        raster_draw(fb, depth, &v, opts, self, perspective)
    }

    /// Shades one span: `lh`/`dlh` are `L` and `H` in Q24 with their steps,
    /// `uv`/`duv` the texture coordinates with `uvf` fraction bits.
    #[inline(always)]
    fn span(
        &self,
        lh: [i32; 6],
        dlh: [i32; 6],
        uv: [i32; 2],
        duv: [i32; 2],
        uvf: [u32; 2],
        out: &mut [C],
    ) {
        let n = out.len() as i64;
        let l = length_squared_diffs([lh[0], lh[1], lh[2]], [dlh[0], dlh[1], dlh[2]]);
        let h = length_squared_diffs([lh[3], lh[4], lh[5]], [dlh[3], dlh[4], dlh[5]]);
        let spec = M::SPECULAR == Specular::BlinnPhong;
        let steps = newton_steps(l.0, l.1, l.2, n).max(if spec {
            newton_steps(h.0, h.1, h.2, n)
        } else {
            0
        });
        let (wl, hl) = self.map.size_log2();
        let st = Span {
            lh,
            dlh,
            uv,
            duv,
            su: uvf[0].saturating_sub(u32::from(wl)).min(31),
            sv: uvf[1].saturating_sub(u32::from(hl)).min(31),
            wm: (1 << wl) - 1,
            hm: (1 << hl) - 1,
            wl: u32::from(wl),
            s: [l.0 as i32, h.0 as i32],
            ds: [l.1 as i32, h.1 as i32],
            dds: [l.2 as i32, h.2 as i32],
        };
        match (steps, self.map.wrap()) {
            (1, Wrap::Repeat) => self.run::<1, true>(st, out),
            (1, Wrap::Clamp) => self.run::<1, false>(st, out),
            (2, Wrap::Repeat) => self.run::<2, true>(st, out),
            (2, Wrap::Clamp) => self.run::<2, false>(st, out),
            (_, Wrap::Repeat) => self.run::<0, true>(st, out),
            (_, Wrap::Clamp) => self.run::<0, false>(st, out),
        }
    }

    /// The per-pixel loop: `NEWTON` = 1 or 2 tracks `1/|L|`, `1/|H|` by that
    /// many Newton steps per pixel from the previous pixel's value (0: an
    /// exact inverse square root per pixel), `REPEAT` wraps the texture
    /// coordinates (else clamps).
    #[inline(always)]
    fn run<const NEWTON: u32, const REPEAT: bool>(&self, st: Span, out: &mut [C]) {
        let Span {
            mut lh,
            dlh,
            mut uv,
            duv,
            su,
            sv,
            wm,
            hm,
            wl,
            mut s,
            mut ds,
            dds,
        } = st;
        let spec = M::SPECULAR == Specular::BlinnPhong;
        let max = C::CHANNEL_MAX.map(|m| m as i32);
        let texels = self.map.texels();
        // exact 1/|L|, 1/|H| at the span start (when FAST: refined per pixel)
        let mut r = [inv_len_q14(s[0]), inv_len_q14(s[1])];
        for p in out.iter_mut() {
            let (x, y) = if REPEAT {
                ((uv[0] >> su) & wm, (uv[1] >> sv) & hm)
            } else {
                ((uv[0] >> su).clamp(0, wm), (uv[1] >> sv).clamp(0, hm))
            };
            let m = texels
                .get(((y << wl) | x) as usize)
                .copied()
                .unwrap_or(crate::normal_map::FLAT_NORMAL)
                .map(i32::from);
            let mut acc = self.base;
            // n·L/|L|: Q14 · (Q24 ≫ 8 = Q16) = Q30, ≫ 14 = Q16; |n·L| ≤ |L|, and
            // (n·L)·(1/|L|) ≤ |n| ≈ 1: the Q30 product fits, rounded to Q14
            let dl = (m[0] * (lh[0] >> 8) + m[1] * (lh[1] >> 8) + m[2] * (lh[2] >> 8)) >> 14;
            let d = (dl * r[0] + (1 << 15)) >> 16;
            if d > 0 {
                let d = d.min(16384);
                acc[0] += (d * self.kd[0]) >> 14;
                acc[1] += (d * self.kd[1]) >> 14;
                acc[2] += (d * self.kd[2]) >> 14;
                if spec {
                    let dh =
                        (m[0] * (lh[3] >> 8) + m[1] * (lh[4] >> 8) + m[2] * (lh[5] >> 8)) >> 14;
                    let sp = self.pow.get((dh * r[1] + (1 << 15)) >> 16);
                    acc[0] += (sp * self.ks[0]) >> 14;
                    acc[1] += (sp * self.ks[1]) >> 14;
                    acc[2] += (sp * self.ks[2]) >> 14;
                }
            }
            *p = C::from_channels([
                (acc[0] >> 8).max(0).min(max[0]) as u32,
                (acc[1] >> 8).max(0).min(max[1]) as u32,
                (acc[2] >> 8).max(0).min(max[2]) as u32,
            ]);
            // next pixel (the values after the last pixel are not used: wrapping
            // is harmless)
            for (a, d) in lh.iter_mut().zip(dlh) {
                *a = a.wrapping_add(d);
            }
            uv[0] = uv[0].wrapping_add(duv[0]);
            uv[1] = uv[1].wrapping_add(duv[1]);
            let k = if spec { 2 } else { 1 };
            for j in 0..k {
                s[j] = s[j].wrapping_add(ds[j]);
                ds[j] = ds[j].wrapping_add(dds[j]);
                if NEWTON == 0 {
                    r[j] = inv_len_q14(s[j]);
                }
                for _ in 0..NEWTON {
                    // r ← r·(3 − s·r²)/2, seeded with the previous pixel's r;
                    // in range over the span (`newton_steps`), wrapping after
                    // its last pixel, where `s` leaves it and `r` is not used
                    let r2 = r[j].wrapping_mul(r[j]) >> 14;
                    let sr2 = (s[j] >> 14).wrapping_mul(r2) >> 14;
                    r[j] = r[j].wrapping_mul(49152i32.wrapping_sub(sr2)) >> 15;
                }
            }
            super::no_unroll();
        }
    }
}

/// A span's running state in the fast path.
#[derive(Clone, Copy, Debug)]
struct Span {
    lh: [i32; 6],
    dlh: [i32; 6],
    uv: [i32; 2],
    duv: [i32; 2],
    su: u32,
    sv: u32,
    wm: i32,
    hm: i32,
    wl: u32,
    /// `|L|²`, `|H|²` (Q28) and their forward differences.
    s: [i32; 2],
    ds: [i32; 2],
    dds: [i32; 2],
}

impl<const NW: u8, M: IncrementalModel, C: OutputColor> SpanShader<8>
    for FastNormalMapShader<'_, '_, NW, M, C>
{
    type Color = C;
    /// `start`/`step`: `L`, `H` (Q26), `u`, `v` (Q24).
    fn shade_span(&mut self, _x: i32, _y: i32, start: &[i32; 8], step: &[i32; 8], out: &mut [C]) {
        let lh = core::array::from_fn(|i| start[i] >> 2);
        let dlh = core::array::from_fn(|i| step[i] >> 2);
        self.span(
            lh,
            dlh,
            [start[6], start[7]],
            [step[6], step[7]],
            [TRI_UV_FRAC; 2],
            out,
        )
    }
}

/// A fast-path triangle in the mesh renderer: planes of `L`, `H` (tangent
/// space) and the texture coordinates.
#[derive(Clone, Copy, Debug)]
pub struct TangentLightTriangle {
    planes: [Plane; 8],
    base: [i32; 8],
}

impl<const NW: u8, M: IncrementalModel, C: OutputColor> Kernel
    for FastNormalMapShader<'_, '_, NW, M, C>
{
    type Color = C;
    type Vertex = TangentLightPayload;
    type Triangle = TangentLightTriangle;
    const NEEDS_POSITION: bool = false;
    const NEEDS_TEXCOORD: bool = true;
    const NEEDS_TANGENT: bool = true;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> TangentLightPayload {
        self.payload(
            v.normal,
            [v.tangent[0], v.tangent[1], v.tangent[2]],
            v.tangent[3],
            v.uv,
        )
    }

    fn triangle(
        &self,
        s: &Setup,
        v: [&TangentLightPayload; 3],
        _p: [[i32; 3]; 3],
    ) -> (TangentLightTriangle, bool) {
        let attrs = v.map(|q| {
            let mut a = [0i32; 8];
            for (a, &c) in a.iter_mut().zip(q.lh.iter().chain(q.uv.iter())) {
                *a = i32::from(c);
            }
            a
        });
        let t = s.tmb[0];
        let planes: [Plane; 8] =
            core::array::from_fn(|i| s.plane([attrs[0][i], attrs[1][i], attrs[2][i]]));
        let top = at3(&attrs, t);
        let base = core::array::from_fn(|i| {
            if i < 6 {
                top[i] << ATTR_FRAC
            } else {
                uv_base(top[i], &planes[i]).0
            }
        });
        let one = 1 << (14 + ATTR_FRAC);
        let clamp = (0..6).any(|i| !super::within(s, &planes[i], base[i], (-one, one)));
        (TangentLightTriangle { planes, base }, clamp)
    }

    fn skip_rows(t: &mut TangentLightTriangle, rows: i32) {
        for p in t.planes.iter_mut() {
            p.skip_rows(rows);
        }
    }

    fn next_row(t: &mut TangentLightTriangle) {
        for p in t.planes.iter_mut() {
            p.next_row();
        }
    }

    fn shade<const CLAMP: bool>(&self, t: &TangentLightTriangle, x: i32, _y: i32, color: &mut [C]) {
        let len = color.len();
        let mut a = [0i32; 8];
        let mut d = [0i32; 8];
        for i in 0..8 {
            let (s0, st) = super::start::<CLAMP>(&t.planes[i], x, len);
            a[i] = t.base[i].wrapping_add(s0);
            d[i] = st;
        }
        // Q28 → Q24
        let lh = core::array::from_fn(|i| a[i] >> 4);
        let dlh = core::array::from_fn(|i| d[i] >> 4);
        let uf = uv_base(0, &t.planes[6]).1;
        let vf = uv_base(0, &t.planes[7]).1;
        self.span(lh, dlh, [a[6], a[7]], [d[6], d[7]], [uf, vf], color)
    }
}
