//! Normal-mapped Phong shading: per-pixel lighting with the normal of a
//! [`NormalMap`] in the tangent frame of the surface.

use super::incremental::IncrementalModel;
use super::perpixel::{self, per_pixel_kernel, sat16, Features, PixelTriangle, Sources, UV_FRAC};
use super::VertexIn;
use super::{unit_q14, Encoder, IncrementalPhongShading, Kernel, Mode, PhongShading, Shader};
use crate::color::OutputColor;
use crate::lighting::{ChannelTerms, Directional, Illuminate};
use crate::num::rsqrt::inv_len_q14;
use crate::num::Q14;
use crate::texture::{Nearest, NormalMap, Wrap};

/// A per-pixel mode with surface detail from a normal map (made by
/// [`PhongShading::normal_mapped`] or
/// [`IncrementalPhongShading::normal_mapped`]): per-pixel lighting with the
/// normal of a [`NormalMap`] in the surface's tangent frame. The mesh needs
/// texture coordinates and tangents ([`Kernel::NEEDS_TEXCOORD`],
/// [`Kernel::NEEDS_TANGENT`]).
///
/// Two kernels, named by the mode they extend:
/// - `PhongShading.normal_mapped(map)`: every tier, light kind and model, any
///   [`Encoder`]. The normal and the tangent are interpolated (and the
///   position when the lighting needs it); per pixel `N' = T·nx + B·ny + N·nz`
///   (`B = w · N × T`) is renormalised with
///   [`Scalar::normalize_interpolated`](crate::num::Scalar::normalize_interpolated) and lit with the full model. A map of
///   the flat normal gives exactly [`PhongShading`]'s pixels.
/// - `IncrementalPhongShading.normal_mapped(map)` (`Q14`, one directional
///   light in an array, a viewer at infinity, no fog, Lambert or
///   Blinn-Phong): `L` and `H` are transformed into the tangent frame per
///   vertex and interpolated; per pixel `n·L` and `n·H` of the texel (used as
///   stored) are three multiply-adds each, divided by `|L|`, `|H|` (one Newton
///   step each from the previous pixel, squares by forward differences,
///   exact at every span start), `(n·H)^n` from [`IncrementalPhongShading`]'s
///   table, the colour accumulated in channel units (rounded like
///   [`Linear`](super::Linear)). Spans where `L` or `H` is shorter than ½ or
///   changes length by more than 2^-4 per pixel take an exact inverse square
///   root per pixel (same bound, slower).
///
/// The map is sampled at the nearest texel. Error bounds and costs:
/// `docs/tradeoff.md` ("Normal mapping").
#[derive(Clone, Copy, Debug)]
pub struct NormalMapped<'m, M> {
    mode: M,
    pub(super) map: NormalMap<'m>,
}

impl PhongShading {
    /// Per-pixel lighting with the normals of `map` (see [`NormalMapped`]).
    pub fn normal_mapped(self, map: NormalMap<'_>) -> NormalMapped<'_, Self> {
        NormalMapped { mode: self, map }
    }
}

impl IncrementalPhongShading {
    /// Incremental per-pixel lighting with the normals of `map` (see
    /// [`NormalMapped`]).
    pub fn normal_mapped(self, map: NormalMap<'_>) -> NormalMapped<'_, Self> {
        NormalMapped { mode: self, map }
    }
}

impl<'m, I, C> Mode<I, C> for NormalMapped<'m, PhongShading> {
    const NAME: &'static str = "normal_mapped";
    type State = NormalMap<'m>;
    fn state(self, _: &I) -> NormalMap<'m> {
        let _ = self.mode;
        self.map
    }
}

per_pixel_kernel!(['m] NormalMapped<'m, PhongShading>, Features::MAPPED, [i16; 9], [i32; 11], |m| Sources {
    map: Some(*m),
    tex: None,
});

// ---- the fast Q14 path ------------------------------------------------------------

/// The incremental kernel's constants (see [`NormalMapped`]): the map and
/// the lighting's terms in channel units.
#[derive(Clone, Copy, Debug)]
pub struct FastNormal<'m> {
    map: NormalMap<'m>,
    terms: ChannelTerms<1>,
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
    /// The payload of vertex `v`: `L` in the tangent frame (Q14), the
    /// texture coordinates (Q12), `H` in the tangent frame, in the places of
    /// the general kernel's normal, coordinates and tangent.
    fn payload(&self, v: &VertexIn) -> [i16; 9] {
        let t = [v.tangent[0], v.tangent[1], v.tangent[2]];
        let [light] = &self.terms.lights;
        let lh = tangent_space(v.normal, t, v.tangent[3], &light.l, &light.h);
        let uv = v.uv.map(sat16);
        [lh[0], lh[1], lh[2], uv[0], uv[1], lh[3], lh[4], lh[5], 1]
    }

    /// Shades one span: `lh`/`dlh` are `L` and `H` in Q24 with their steps,
    /// `uv`/`duv` the texture coordinates (Q12 with `ATTR_FRAC` bits).
    #[inline(always)]
    fn shade_run<C: OutputColor>(
        &self,
        lh: [i32; 6],
        dlh: [i32; 6],
        uv: [i32; 2],
        duv: [i32; 2],
        out: &mut [C],
    ) {
        let n = out.len() as i64;
        let l = length_squared_diffs([lh[0], lh[1], lh[2]], [dlh[0], dlh[1], dlh[2]]);
        let h = length_squared_diffs([lh[3], lh[4], lh[5]], [dlh[3], dlh[4], dlh[5]]);
        let spec = self.terms.specular();
        let steps = newton_steps(l.0, l.1, l.2, n).max(if spec {
            newton_steps(h.0, h.1, h.2, n)
        } else {
            0
        });
        let st = Span {
            lh,
            dlh,
            uv,
            duv,
            map: self.map.nearest(UV_FRAC),
            s: [l.0 as i32, h.0 as i32],
            ds: [l.1 as i32, h.1 as i32],
            dds: [l.2 as i32, h.2 as i32],
        };
        match (steps, self.map.wrap(), spec) {
            (1, Wrap::Repeat, true) => self.run::<C, 1, true, true>(&st, out),
            (1, Wrap::Clamp, true) => self.run::<C, 1, false, true>(&st, out),
            (2, Wrap::Repeat, true) => self.run::<C, 2, true, true>(&st, out),
            (2, Wrap::Clamp, true) => self.run::<C, 2, false, true>(&st, out),
            (_, Wrap::Repeat, true) => self.run::<C, 0, true, true>(&st, out),
            (_, Wrap::Clamp, true) => self.run::<C, 0, false, true>(&st, out),
            (1, Wrap::Repeat, false) => self.run::<C, 1, true, false>(&st, out),
            (1, Wrap::Clamp, false) => self.run::<C, 1, false, false>(&st, out),
            (2, Wrap::Repeat, false) => self.run::<C, 2, true, false>(&st, out),
            (2, Wrap::Clamp, false) => self.run::<C, 2, false, false>(&st, out),
            (_, Wrap::Repeat, false) => self.run::<C, 0, true, false>(&st, out),
            (_, Wrap::Clamp, false) => self.run::<C, 0, false, false>(&st, out),
        }
    }

    /// The per-pixel loop: `NEWTON` = 1 or 2 tracks `1/|L|`, `1/|H|` by that
    /// many Newton steps per pixel from the previous pixel's value (0: an
    /// exact inverse square root per pixel), `REPEAT` wraps the texture
    /// coordinates (else clamps). On RV32IMC each a function of its own (its
    /// registers allocated for the one loop: 11 instructions a pixel fewer
    /// than inlined), inlined on the Arm cores (where the call costs more
    /// than it saves on the Cortex-M0).
    #[cfg_attr(target_arch = "riscv32", inline(never))]
    #[cfg_attr(not(target_arch = "riscv32"), inline(always))]
    fn run<C: OutputColor, const NEWTON: u32, const REPEAT: bool, const SPEC: bool>(
        &self,
        st: &Span<'_>,
        out: &mut [C],
    ) {
        let &Span {
            mut lh,
            dlh,
            mut uv,
            duv,
            map,
            mut s,
            mut ds,
            dds,
        } = st;
        let spec = SPEC;
        let terms = &self.terms;
        let [light] = terms.lights;
        // exact 1/|L|, 1/|H| at the span start (when FAST: refined per pixel)
        let mut r = [inv_len_q14(s[0]), inv_len_q14(s[1])];
        for p in out.iter_mut() {
            let m = map.get::<REPEAT>(uv[0], uv[1]).map(i32::from);
            let mut acc = terms.base();
            // n·L/|L|: Q14 · (Q24 ≫ 8 = Q16) = Q30, ≫ 14 = Q16; |n·L| ≤ |L|, and
            // (n·L)·(1/|L|) ≤ |n| ≈ 1: the Q30 product fits, rounded to Q14
            let dl = (m[0] * (lh[0] >> 8) + m[1] * (lh[1] >> 8) + m[2] * (lh[2] >> 8)) >> 14;
            let d = (dl * r[0] + (1 << 15)) >> 16;
            if d > 0 {
                let h = if SPEC {
                    let dh =
                        (m[0] * (lh[3] >> 8) + m[1] * (lh[4] >> 8) + m[2] * (lh[5] >> 8)) >> 14;
                    (dh * r[1] + (1 << 15)) >> 16
                } else {
                    0
                };
                terms.add::<SPEC>(&mut acc, &light, d, h);
            }
            *p = ChannelTerms::<1>::color(acc);
            // next pixel (the values after the last pixel are not used: wrapping
            // is harmless); `H` only with a specular term
            let n = if spec { 6 } else { 3 };
            for (a, d) in lh.iter_mut().zip(dlh).take(n) {
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
            crate::num::no_unroll();
        }
    }
}

/// A span's running state in the fast path.
#[derive(Clone, Copy, Debug)]
struct Span<'m> {
    lh: [i32; 6],
    dlh: [i32; 6],
    uv: [i32; 2],
    duv: [i32; 2],
    map: Nearest<'m>,
    /// `|L|²`, `|H|²` (Q28) and their forward differences.
    s: [i32; 2],
    ds: [i32; 2],
    dds: [i32; 2],
}

impl<'m, const NW: u8, M: IncrementalModel, C: OutputColor> Mode<Directional<Q14<NW>, 1, M>, C>
    for NormalMapped<'m, IncrementalPhongShading>
{
    const NAME: &'static str = "normal_mapped_inc";
    type State = FastNormal<'m>;
    fn state(self, lighting: &Directional<Q14<NW>, 1, M>) -> FastNormal<'m> {
        let _ = self.mode;
        FastNormal {
            map: self.map,
            terms: ChannelTerms::new::<C, Q14<NW>>(lighting.directional_terms()),
        }
    }
}

impl<'m, const NW: u8, M: IncrementalModel, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, NormalMapped<'m, IncrementalPhongShading>, Directional<Q14<NW>, 1, M>, E, C>
{
    type Color = C;
    /// `L` (Q14), `u`, `v` (Q12), `H` (Q14) in the tangent frame, in the
    /// places of the general kernel's normal, coordinates and tangent.
    type Vertex = [i16; 9];
    /// `L`, `u`, `v`, `H`.
    type Varyings = [i32; 8];
    type Triangle = PixelTriangle;
    const NEEDS_POSITION: bool = false;
    const NEEDS_TEXCOORD: bool = true;
    const NEEDS_TANGENT: bool = true;

    #[inline]
    fn vertex(&self, v: &VertexIn) -> [i16; 9] {
        self.state.payload(v)
    }

    fn triangle(&self, v: [&[i16; 9]; 3], eye: &[[i32; 3]; 3]) -> (PixelTriangle, [[i32; 8]; 3]) {
        perpixel::triangle(Features::MAPPED, false, v, eye)
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        perpixel::safe(Features::MAPPED, i)
    }

    /// The texture coordinates.
    #[inline(always)]
    fn exact(&self, i: usize) -> bool {
        perpixel::exact(Features::MAPPED, i)
    }

    fn span(&self, _: &PixelTriangle, a: &[i32; 8], d: &[i32; 8], _: i32, _: i32, out: &mut [C]) {
        // Q28 → Q24
        let lh = |v: &[i32; 8]| [0, 1, 2, 5, 6, 7].map(|i| v[i] >> 4);
        self.state
            .shade_run(lh(a), lh(d), [a[3], a[4]], [d[3], d[4]], out)
    }
}
