//! Normal-mapped Phong shading: per-pixel lighting with the normal of a
//! [`NormalMap`] in the tangent frame of the surface.

use super::incremental::{channel_units, PowTable};
use super::phong::PhongTriangle;
use super::{eye_point, unit_q14, Encoder, GeneralPhongShading, Kernel, Mode, ModeState};
use super::{PhongShading, Shader, VertexIn};
use crate::color::{OutputColor, Rgb};
use crate::lighting::{DirectionalTerms, Illuminate};
use crate::num::rsqrt::inv_len_q14;
use crate::num::{Flag, Off, On, Point3, Scalar, Vec3};
use crate::raster::interp::Varyings;
use crate::raster::ATTR_FRAC;
use crate::texture::{NormalMap, NormalTexel, Wrap};

/// A per-pixel mode with surface detail from a normal map (made by
/// [`PhongShading::normal_mapped`] or [`GeneralPhongShading::normal_mapped`]):
/// per-pixel lighting with the normal of a [`NormalMap`] in the surface's
/// tangent frame. The mesh needs texture coordinates and tangents
/// ([`Kernel::NEEDS_TEXCOORD`], [`Kernel::NEEDS_TANGENT`]).
///
/// Two kernels; [`PhongShading`] lets the lighting choose, as for plain
/// per-pixel lighting ([`GeneralPhongShading`] always takes the general one):
/// - **general**: every tier, light kind and model, any [`Encoder`]. The
///   normal and the tangent are interpolated (and the position when the
///   lighting needs it); per pixel `N' = T·nx + B·ny + N·nz`
///   (`B = w · N × T`) is renormalised with
///   [`Scalar::normalize_interpolated`] and lit with the full model. A map of
///   the flat normal gives exactly the plain kernel's pixels.
/// - **fast** (`Q14`, one directional light, a viewer at infinity, no fog,
///   Lambert or Blinn-Phong): `L` and `H` are transformed into the tangent
///   frame per vertex and interpolated; per pixel the texel (a Q14 unit
///   normal, used as stored), `n·L` and `n·H` as three multiply-adds each,
///   both divided by the length of the interpolated `L` and `H` (`1/|L|`,
///   `1/|H|` by one Newton step each from the previous pixel's value, `|L|²`,
///   `|H|²` by forward differences, exact at every span start),
///   `(n·H)^shininess` from the power table of [`IncrementalPhongShading`],
///   the colour accumulated in output channel units (rounded like
///   [`Linear`](super::Linear)). Spans whose interpolated `L` or `H` is
///   shorter than ½, or changes length by more than 2^-4 per pixel, take an
///   exact inverse square root per pixel (same result within the bound,
///   slower).
///
/// Texture coordinates are interpolated like every other value (screen-linear
/// or perspective-correct: [`crate::raster::interp`]); the map is sampled at
/// the nearest texel. Error bounds and costs: `docs/tradeoff.md` ("Normal
/// mapping").
#[derive(Clone, Copy, Debug)]
pub struct NormalMapped<'m, M> {
    mode: M,
    map: NormalMap<'m>,
}

impl<M: Mode> Mode for NormalMapped<'_, M> {
    const NAME: &'static str = "normal_mapped";
}

impl PhongShading {
    /// Per-pixel lighting with the normals of `map` (see [`NormalMapped`]);
    /// the lighting picks the kernel.
    pub fn normal_mapped(self, map: NormalMap<'_>) -> NormalMapped<'_, Self> {
        NormalMapped { mode: self, map }
    }
}

impl GeneralPhongShading {
    /// Per-pixel lighting with the normals of `map`, the general kernel (see
    /// [`NormalMapped`]).
    pub fn normal_mapped(self, map: NormalMap<'_>) -> NormalMapped<'_, Self> {
        NormalMapped { mode: self, map }
    }
}

impl<'m, I: Illuminate, C> ModeState<I, C> for NormalMapped<'m, GeneralPhongShading> {
    type State = NormalMap<'m>;
    fn state(self, _: &I) -> NormalMap<'m> {
        let _ = self.mode;
        self.map
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

/// The colour of one pixel: interpolated normal `n` and tangent `t` (the
/// tier's attribute scale, not normalised), handedness `hand`, map texel `m`,
/// position `p`.
#[inline(always)]
fn general_pixel<S: Scalar, I: Illuminate<Scalar = S>>(
    lighting: &I,
    n: [i32; 3],
    t: [i32; 3],
    hand: i32,
    m: NormalTexel,
    p: &Point3<S>,
) -> Rgb<S> {
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
    lighting.shade(p, S::normalize_interpolated(np))
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

/// The general kernel's vertex payload.
#[inline]
fn general_vertex(v: &VertexIn) -> NormalMapPayload {
    NormalMapPayload {
        n: unit_q14(v.normal),
        t: unit_q14([v.tangent[0], v.tangent[1], v.tangent[2]]),
        hand: if v.tangent[3] < 0 { -1 } else { 1 },
        uv: [sat16(v.uv[0]), sat16(v.uv[1])],
    }
}

/// The general kernel's triangle: normal (3), tangent (3) (Q14), `u`, `v`
/// (Q12), then the position (see [`PhongTriangle`]) when `position`.
#[inline]
fn general_triangle(
    v: [&NormalMapPayload; 3],
    eye: &[[i32; 3]; 3],
    position: bool,
) -> (NormalMapTriangle, [[i32; 11]; 3]) {
    let (pos, p) = if position {
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

/// The general kernel's range of value `i`: the normal and tangent within
/// [−1, 1] in Q14 (Q28 with ATTR_FRAC bits).
#[inline(always)]
fn general_safe(i: usize) -> (i32, i32) {
    let one = 1 << (14 + ATTR_FRAC);
    if i < 6 {
        (-one, one)
    } else {
        (-(1 << 30), 1 << 30)
    }
}

/// The general kernel's span.
#[allow(clippy::too_many_arguments)]
fn general_span<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>(
    lighting: &I,
    encoder: &E,
    map: &NormalMap<'_>,
    t: &NormalMapTriangle,
    a: &[i32; 11],
    d: &[i32; 11],
    x: i32,
    y: i32,
    color: &mut [C],
) {
    // the values the lighting reads, in an array of their own length; the
    // map's wrap mode as a constant
    let eight = |v: &[i32; 11]| core::array::from_fn(|i| v[i]);
    match (I::NEEDS_POSITION, map.wrap()) {
        (true, Wrap::Repeat) => {
            general_run::<_, _, _, _, 11, true>(lighting, encoder, map, t, *a, *d, x, y, color)
        }
        (true, Wrap::Clamp) => {
            general_run::<_, _, _, _, 11, false>(lighting, encoder, map, t, *a, *d, x, y, color)
        }
        (false, Wrap::Repeat) => general_run::<_, _, _, _, 8, true>(
            lighting, encoder, map, t, eight(a), eight(d), x, y, color,
        ),
        (false, Wrap::Clamp) => general_run::<_, _, _, _, 8, false>(
            lighting, encoder, map, t, eight(a), eight(d), x, y, color,
        ),
    }
}

/// [`general_span`] over the first `N` values (8: no position); `REPEAT`
/// wraps the texture coordinates (else clamps).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn general_run<
    S: Scalar,
    I: Illuminate<Scalar = S>,
    E: Encoder<C>,
    C: OutputColor,
    const N: usize,
    const REPEAT: bool,
>(
    lighting: &I,
    encoder: &E,
    map: &NormalMap<'_>,
    t: &NormalMapTriangle,
    mut a: [i32; N],
    d: [i32; N],
    x: i32,
    y: i32,
    color: &mut [C],
) {
    let at = |a: &[i32; N], i: usize| a.get(i).copied().unwrap_or(0);
    // texture coordinates (Q12 with ATTR_FRAC bits) to texels: shifts per span
    let (wl, hl) = map.size_log2();
    let su = UV_FRAC.saturating_sub(u32::from(wl)).min(31);
    let sv = UV_FRAC.saturating_sub(u32::from(hl)).min(31);
    let (wm, hm, wl) = ((1i32 << wl) - 1, (1i32 << hl) - 1, u32::from(wl));
    let texels = map.texels();
    for (x, c) in (x..).zip(color.iter_mut()) {
        let pos = if N > 8 {
            eye_point::<S>(t.pos.position([at(&a, 8), at(&a, 9), at(&a, 10)]))
        } else {
            eye_point::<S>([0; 3])
        };
        let (u, v) = (at(&a, 6) >> su, at(&a, 7) >> sv);
        let (u, v) = if REPEAT {
            (u & wm, v & hm)
        } else {
            (u.clamp(0, wm), v.clamp(0, hm))
        };
        let m = texels
            .get(((v << wl) | u) as usize)
            .copied()
            .unwrap_or(crate::texture::FLAT_NORMAL);
        // Q14 with ATTR_FRAC bits (Q28) → the tier's attribute (Q26)
        let lit = general_pixel(
            lighting,
            [at(&a, 0) >> 2, at(&a, 1) >> 2, at(&a, 2) >> 2],
            [at(&a, 3) >> 2, at(&a, 4) >> 2, at(&a, 5) >> 2],
            t.hand,
            m,
            &pos,
        );
        *c = encoder.encode(lit, x, y);
        for (a, d) in a.iter_mut().zip(d) {
            // the values after the last pixel are not used: wrapping is harmless
            *a = a.wrapping_add(d);
        }
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, NormalMapped<'_, GeneralPhongShading>, I, E, C>
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
    fn vertex(&self, v: &VertexIn) -> NormalMapPayload {
        general_vertex(v)
    }

    fn triangle(
        &self,
        v: [&NormalMapPayload; 3],
        eye: &[[i32; 3]; 3],
    ) -> (NormalMapTriangle, [[i32; 11]; 3]) {
        general_triangle(v, eye, I::NEEDS_POSITION)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        general_safe(i)
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
        general_span(self.lighting, &self.encoder, &self.state, t, a, d, x, y, color)
    }
}

/// Fraction bits of interpolated texture coordinates: Q12 with
/// [`ATTR_FRAC`] bits.
const UV_FRAC: u32 = 12 + ATTR_FRAC;

// ---- the fast Q14 path ------------------------------------------------------------

/// The fast kernel's constants (see [`NormalMapped`]): the map, the light's
/// direction and halfway vector (Q14), `Ld∘Kd`, `Ls∘Ks` and the constant
/// part (+ ½) per channel in channel units · 2^8, the power table.
#[derive(Clone, Copy, Debug)]
pub struct FastNormal<'m> {
    map: NormalMap<'m>,
    l: [i32; 3],
    h: [i32; 3],
    kd: [i32; 3],
    ks: [i32; 3],
    base: [i32; 3],
    pow: PowTable,
    spec: bool,
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

impl<'m> FastNormal<'m> {
    /// The constants for one directional light `t` and `map` (in `f32`: once
    /// per shader).
    fn new<C: OutputColor, S: Scalar>(t: &DirectionalTerms<S>, map: NormalMap<'m>) -> Self {
        let q14 = |v: Vec3<S>| {
            let q = |c: S| (c.to_attr() + (1 << 11)) >> 12;
            [q(v.x), q(v.y), q(v.z)]
        };
        let ks = channel_units::<C, S>(t.specular);
        FastNormal {
            map,
            l: q14(t.dir),
            h: q14(t.half),
            kd: channel_units::<C, S>(t.diffuse),
            ks,
            base: channel_units::<C, S>(t.base).map(|v| v + 128),
            pow: PowTable::new(t.shininess),
            spec: ks != [0; 3],
        }
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
    fn shade_run<C: OutputColor>(
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
        let spec = self.spec;
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
        match (steps, self.map.wrap(), spec) {
            (1, Wrap::Repeat, true) => self.run::<C, 1, true, true>(st, out),
            (1, Wrap::Clamp, true) => self.run::<C, 1, false, true>(st, out),
            (2, Wrap::Repeat, true) => self.run::<C, 2, true, true>(st, out),
            (2, Wrap::Clamp, true) => self.run::<C, 2, false, true>(st, out),
            (_, Wrap::Repeat, true) => self.run::<C, 0, true, true>(st, out),
            (_, Wrap::Clamp, true) => self.run::<C, 0, false, true>(st, out),
            (1, Wrap::Repeat, false) => self.run::<C, 1, true, false>(st, out),
            (1, Wrap::Clamp, false) => self.run::<C, 1, false, false>(st, out),
            (2, Wrap::Repeat, false) => self.run::<C, 2, true, false>(st, out),
            (2, Wrap::Clamp, false) => self.run::<C, 2, false, false>(st, out),
            (_, Wrap::Repeat, false) => self.run::<C, 0, true, false>(st, out),
            (_, Wrap::Clamp, false) => self.run::<C, 0, false, false>(st, out),
        }
    }

    /// The per-pixel loop: `NEWTON` = 1 or 2 tracks `1/|L|`, `1/|H|` by that
    /// many Newton steps per pixel from the previous pixel's value (0: an
    /// exact inverse square root per pixel), `REPEAT` wraps the texture
    /// coordinates (else clamps).
    #[inline(always)]
    fn run<C: OutputColor, const NEWTON: u32, const REPEAT: bool, const SPEC: bool>(
        &self,
        st: Span,
        out: &mut [C],
    ) {
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
        let spec = SPEC;
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

/// How a [`NormalMapped`] [`PhongShading`] shader lights the pixels of a
/// lighting `I`: the general kernel ([`Off`]) or the fast one ([`On`]).
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "`PhongShading::normal_mapped` cannot choose a kernel for the lighting `{I}`",
    note = "every `Lighting` of this crate is served; a lighting of your own implements `Illuminate` with `type Fast = fixshade::num::Off`"
)]
pub trait NormalMapPath<'m, I: Illuminate, C: OutputColor>: Flag {
    /// The vertex payload.
    type Vertex: Copy + Default + core::fmt::Debug;
    /// The values interpolated.
    type Varyings: Varyings;
    /// The triangle constants.
    type Triangle: Copy + core::fmt::Debug;
    /// What the shader precomputes.
    type State: Copy + core::fmt::Debug;
    /// How many values are used.
    const USED: usize;
    /// Precomputes it.
    fn state(lighting: &I, map: NormalMap<'m>) -> Self::State;
    /// The payload of a vertex.
    fn vertex(state: &Self::State, v: &VertexIn) -> Self::Vertex;
    /// The triangle.
    fn triangle(v: [&Self::Vertex; 3], eye: &[[i32; 3]; 3]) -> (Self::Triangle, [Self::Varyings; 3]);
    /// The range of value `i`.
    fn safe(i: usize) -> (i32, i32);
    /// Shades a span.
    #[allow(clippy::too_many_arguments)]
    fn span<E: Encoder<C>>(
        state: &Self::State,
        lighting: &I,
        encoder: &E,
        t: &Self::Triangle,
        a: &Self::Varyings,
        d: &Self::Varyings,
        x: i32,
        y: i32,
        out: &mut [C],
    );
}

impl<'m, I: Illuminate, C: OutputColor> NormalMapPath<'m, I, C> for Off {
    type Vertex = NormalMapPayload;
    type Varyings = [i32; 11];
    type Triangle = NormalMapTriangle;
    type State = NormalMap<'m>;
    const USED: usize = if I::NEEDS_POSITION { 11 } else { 8 };
    fn state(_: &I, map: NormalMap<'m>) -> NormalMap<'m> {
        map
    }
    #[inline]
    fn vertex(_: &NormalMap<'m>, v: &VertexIn) -> NormalMapPayload {
        general_vertex(v)
    }
    fn triangle(
        v: [&NormalMapPayload; 3],
        eye: &[[i32; 3]; 3],
    ) -> (NormalMapTriangle, [[i32; 11]; 3]) {
        general_triangle(v, eye, I::NEEDS_POSITION)
    }
    #[inline(always)]
    fn safe(i: usize) -> (i32, i32) {
        general_safe(i)
    }
    fn span<E: Encoder<C>>(
        map: &NormalMap<'m>,
        lighting: &I,
        encoder: &E,
        t: &NormalMapTriangle,
        a: &[i32; 11],
        d: &[i32; 11],
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        general_span(lighting, encoder, map, t, a, d, x, y, out)
    }
}

/// The fast kernel's constants, or the map alone for a lighting whose model
/// the fast kernel does not evaluate (then the general pixel, from the
/// interpolated normal, tangent and handedness carried in the payload).
#[derive(Clone, Copy, Debug)]
pub enum FastNormalState<'m> {
    /// The fast kernel.
    Fast(FastNormal<'m>),
    /// The general kernel.
    General(NormalMap<'m>),
}

impl<'m, I: Illuminate, C: OutputColor> NormalMapPath<'m, I, C> for On {
    type Vertex = NormalMapPayload;
    /// `L`, `H` in the tangent frame (Q14), `u`, `v` (Q12) for the fast
    /// kernel; the general kernel's first 8 values otherwise.
    type Varyings = [i32; 8];
    type Triangle = NormalMapTriangle;
    type State = FastNormalState<'m>;
    const USED: usize = 8;
    fn state(lighting: &I, map: NormalMap<'m>) -> FastNormalState<'m> {
        match lighting.directional() {
            Some(t) => FastNormalState::Fast(FastNormal::new::<C, I::Scalar>(&t, map)),
            None => FastNormalState::General(map),
        }
    }
    #[inline]
    fn vertex(state: &FastNormalState<'m>, v: &VertexIn) -> NormalMapPayload {
        match state {
            FastNormalState::Fast(f) => {
                let p = f.payload(
                    v.normal,
                    [v.tangent[0], v.tangent[1], v.tangent[2]],
                    v.tangent[3],
                    v.uv,
                );
                // L and H in the normal's and tangent's places
                NormalMapPayload {
                    n: [p.lh[0], p.lh[1], p.lh[2]],
                    t: [p.lh[3], p.lh[4], p.lh[5]],
                    hand: 1,
                    uv: p.uv,
                }
            }
            FastNormalState::General(_) => general_vertex(v),
        }
    }
    fn triangle(v: [&NormalMapPayload; 3], eye: &[[i32; 3]; 3]) -> (NormalMapTriangle, [[i32; 8]; 3]) {
        let (t, var) = general_triangle(v, eye, false);
        (t, var.map(|a| core::array::from_fn(|i| a[i])))
    }
    #[inline(always)]
    fn safe(i: usize) -> (i32, i32) {
        general_safe(i)
    }
    fn span<E: Encoder<C>>(
        state: &FastNormalState<'m>,
        lighting: &I,
        encoder: &E,
        t: &NormalMapTriangle,
        a: &[i32; 8],
        d: &[i32; 8],
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        match state {
            FastNormalState::Fast(f) => {
                // Q28 → Q24
                let lh = core::array::from_fn(|i| a[i] >> 4);
                let dlh = core::array::from_fn(|i| d[i] >> 4);
                f.shade_run(lh, dlh, [a[6], a[7]], [d[6], d[7]], [UV_FRAC; 2], out)
            }
            FastNormalState::General(map) => {
                let wide = |v: &[i32; 8]| core::array::from_fn(|i| v.get(i).copied().unwrap_or(0));
                general_span(lighting, encoder, map, t, &wide(a), &wide(d), x, y, out)
            }
        }
    }
}

impl<'m, I: Illuminate, C: OutputColor> ModeState<I, C> for NormalMapped<'m, PhongShading>
where
    I::Fast: NormalMapPath<'m, I, C>,
{
    type State = <I::Fast as NormalMapPath<'m, I, C>>::State;
    fn state(self, lighting: &I) -> Self::State {
        <I::Fast as NormalMapPath<'m, I, C>>::state(lighting, self.map)
    }
}

impl<'m, I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, NormalMapped<'m, PhongShading>, I, E, C>
where
    I::Fast: NormalMapPath<'m, I, C>,
{
    type Color = C;
    type Vertex = <I::Fast as NormalMapPath<'m, I, C>>::Vertex;
    type Varyings = <I::Fast as NormalMapPath<'m, I, C>>::Varyings;
    type Triangle = <I::Fast as NormalMapPath<'m, I, C>>::Triangle;
    const USED: usize = <I::Fast as NormalMapPath<'m, I, C>>::USED;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;
    const NEEDS_TEXCOORD: bool = true;
    const NEEDS_TANGENT: bool = true;

    #[inline]
    fn vertex(&self, v: &VertexIn) -> Self::Vertex {
        <I::Fast as NormalMapPath<'m, I, C>>::vertex(&self.state, v)
    }

    fn triangle(
        &self,
        v: [&Self::Vertex; 3],
        eye: &[[i32; 3]; 3],
    ) -> (Self::Triangle, [Self::Varyings; 3]) {
        <I::Fast as NormalMapPath<'m, I, C>>::triangle(v, eye)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        <I::Fast as NormalMapPath<'m, I, C>>::safe(i)
    }

    fn span(
        &self,
        t: &Self::Triangle,
        a: &Self::Varyings,
        d: &Self::Varyings,
        x: i32,
        y: i32,
        out: &mut [C],
    ) {
        <I::Fast as NormalMapPath<'m, I, C>>::span(
            &self.state,
            self.lighting,
            &self.encoder,
            t,
            a,
            d,
            x,
            y,
            out,
        )
    }
}
