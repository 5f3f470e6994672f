//! Normal-mapped Phong shading: per-pixel lighting with the normal of a
//! [`NormalMap`] in the tangent frame of the surface.

use super::phong::PhongTriangle;
use super::{eye_point, unit_q14, Encoder, Kernel};
use crate::color::{OutputColor, Rgb};
use crate::lighting::{Illuminate, Specular};
use crate::texture::{NormalMap, NormalTexel, Wrap};
use crate::num::rsqrt::{rsqrt_q14_mantissa, split_u32};
use crate::num::{Scalar, Q14};
use crate::raster::ATTR_FRAC;
use crate::num::{Point3, Vec3};
use core::marker::PhantomData;

use super::incremental::{channel_units, DirectionalLighting, IncrementalModel, PowTable};

/// The general normal-mapped shader: every tier, every light kind, every
/// reflection model, any [`Encoder`] (see [`NormalMapShading`](super::NormalMapShading)).
pub struct NormalMapShader<'l, 'm, I: Illuminate, E, C> {
    lighting: &'l I,
    encoder: E,
    map: NormalMap<'m>,
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
        Self {
            lighting,
            encoder,
            map,
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

/// Clamps an `i32` to `i16`.
#[inline]
fn sat16(v: i32) -> i16 {
    v.clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16
}

/// A normal-mapped triangle (general path): the handedness of its tangent
/// frame and the origin of its interpolated positions.
#[derive(Clone, Copy, Debug, Default)]
pub struct NormalMapTriangle {
    pos: PhongTriangle,
    hand: i32,
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Kernel
    for NormalMapShader<'_, '_, I, E, C>
{
    type Color = C;
    type Vertex = NormalMapPayload;
    /// Normal (3), tangent (3) (Q14), `u`, `v` (Q12), then the position (see
    /// [`PhongTriangle`]) when the lighting reads it.
    type Varyings = [i32; 11];
    type Triangle = NormalMapTriangle;
    const USED: usize = if I::NEEDS_POSITION { 11 } else { 8 };
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
        v: [&NormalMapPayload; 3],
        eye: &[[i32; 3]; 3],
    ) -> (NormalMapTriangle, [[i32; 11]; 3]) {
        let (pos, p) = if I::NEEDS_POSITION {
            PhongTriangle::new(eye)
        } else {
            (PhongTriangle::default(), [[0; 3]; 3])
        };
        let var = core::array::from_fn(|k| {
            let q = v[k];
            let p = p[k];
            [
                i32::from(q.n[0]),
                i32::from(q.n[1]),
                i32::from(q.n[2]),
                i32::from(q.t[0]),
                i32::from(q.t[1]),
                i32::from(q.t[2]),
                i32::from(q.uv[0]),
                i32::from(q.uv[1]),
                p[0],
                p[1],
                p[2],
            ]
        });
        let tri = NormalMapTriangle {
            pos,
            hand: majority(v.map(|q| i32::from(q.hand))),
        };
        (tri, var)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        // the normal and tangent within [−1, 1] in Q14 (Q28 with ATTR_FRAC bits)
        let one = 1 << (14 + ATTR_FRAC);
        if i < 6 {
            (-one, one)
        } else {
            (-(1 << 30), 1 << 30)
        }
    }

    fn span(
        &self,
        t: &NormalMapTriangle,
        a: &[i32; 11],
        d: &[i32; 11],
        x: i32,
        y: i32,
        color: &mut [C],
    ) {
        let (mut a, d) = (*a, *d);
        let used = <Self as Kernel>::USED;
        for (x, c) in (x..).zip(color.iter_mut()) {
            let pos = if I::NEEDS_POSITION {
                eye_point::<S>(t.pos.position([a[8], a[9], a[10]]))
            } else {
                eye_point::<S>([0; 3])
            };
            // Q12 with ATTR_FRAC bits
            let m = sample2(&self.map, a[6], UV_FRAC, a[7], UV_FRAC);
            // Q14 with ATTR_FRAC bits (Q28) → the tier's attribute (Q26)
            let lit = self.pixel(
                [a[0] >> 2, a[1] >> 2, a[2] >> 2],
                [a[3] >> 2, a[4] >> 2, a[5] >> 2],
                t.hand,
                m,
                &pos,
            );
            *c = self.encoder.encode(lit, x, y);
            for (a, d) in a.iter_mut().zip(d).take(used) {
                // the values after the last pixel are not used: wrapping is harmless
                *a = a.wrapping_add(d);
            }
        }
    }
}

/// Fraction bits of interpolated texture coordinates: Q12 with
/// [`ATTR_FRAC`] bits.
const UV_FRAC: u32 = 12 + ATTR_FRAC;

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
/// use fixshade::texture::{NormalMap, Wrap, FLAT_NORMAL};
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
            kd: channel_units::<C, Q14<NW>>(pre.diffuse),
            ks: channel_units::<C, Q14<NW>>(pre.specular),
            base: channel_units::<C, Q14<NW>>(lighting.base()).map(|v| v + 128),
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

    /// Shades one span: `lh`/`dlh` are `L` and `H` in Q24 with their steps,
    /// `uv`/`duv` the texture coordinates with `uvf` fraction bits.
    #[inline(always)]
    fn shade_run(
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
                .unwrap_or(crate::texture::FLAT_NORMAL)
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
                    // r ← r·(3 − s·r²)/2, seeded with the previous pixel's r
                    let r2 = (r[j] * r[j]) >> 14;
                    let sr2 = ((s[j] >> 14) * r2) >> 14;
                    r[j] = (r[j] * (49152 - sr2)) >> 15;
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

impl<const NW: u8, M: IncrementalModel, C: OutputColor> Kernel
    for FastNormalMapShader<'_, '_, NW, M, C>
{
    type Color = C;
    type Vertex = TangentLightPayload;
    /// `L`, `H` in the tangent frame (Q14), `u`, `v` (Q12).
    type Varyings = [i32; 8];
    type Triangle = ();
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

    #[inline(always)]
    fn triangle(&self, v: [&TangentLightPayload; 3], _eye: &[[i32; 3]; 3]) -> ((), [[i32; 8]; 3]) {
        let var = v.map(|q| {
            let mut a = [0i32; 8];
            for (a, &c) in a.iter_mut().zip(q.lh.iter().chain(q.uv.iter())) {
                *a = i32::from(c);
            }
            a
        });
        ((), var)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        let one = 1 << (14 + ATTR_FRAC);
        if i < 6 {
            (-one, one)
        } else {
            (-(1 << 30), 1 << 30)
        }
    }

    fn span(&self, _t: &(), a: &[i32; 8], d: &[i32; 8], _x: i32, _y: i32, color: &mut [C]) {
        // Q28 → Q24
        let lh = core::array::from_fn(|i| a[i] >> 4);
        let dlh = core::array::from_fn(|i| d[i] >> 4);
        self.shade_run(lh, dlh, [a[6], a[7]], [d[6], d[7]], [UV_FRAC; 2], color)
    }
}
