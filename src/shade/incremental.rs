//! Incremental Phong shading: the Cortex-M0 fast path for directional lights and a
//! viewer at infinity in the Q14 tier.

use super::perpixel::{self, Features, PixelTriangle, Sources};
use super::{IncrementalPhongShading, Kernel, Linear, Mode, Shader};
use crate::color::OutputColor;
use crate::lighting::{BlinnPhong, Directional, Lambert, Model, Specular};
use crate::lighting::{ChannelTerms, Illuminate};
use crate::num::rsqrt::rsqrt_q28_q14;
use crate::num::wide::{mul_i32, mul_i64_u32, mul_u32};
use crate::num::Q14;
use crate::raster::interp::Varyings;

/// The models [`IncrementalPhongShading`] evaluates: [`Lambert`] and [`BlinnPhong`].
pub trait IncrementalModel: Model {}
impl IncrementalModel for Lambert {}
impl IncrementalModel for BlinnPhong {}

impl<const K: usize> ChannelTerms<K> {
    /// The values to interpolate at a vertex of unit normal `n` (Q14): the
    /// normal, then `N·L` and `N·H` of every light.
    #[inline(always)]
    pub(super) fn varyings<V: Varyings>(&self, n: &[i16; 3]) -> V {
        let n = n.map(i32::from);
        let dot = |d: &[i32; 3]| (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) >> 14;
        V::from_fn(|i| match i {
            0..=2 => n[i],
            _ => {
                let j = (i - 3) / 2;
                self.lights.get(j).map_or(0, |lt| {
                    if (i - 3) % 2 == 0 {
                        dot(&lt.l)
                    } else {
                        dot(&lt.h)
                    }
                })
            }
        })
    }
}

impl<const NW: u8, const K: usize, M: IncrementalModel, C: OutputColor>
    Mode<Directional<Q14<NW>, K, M>, C> for IncrementalPhongShading
{
    const NAME: &'static str = "phong_inc";
    type State = ChannelTerms<K>;

    fn state(self, lighting: &Directional<Q14<NW>, K, M>) -> ChannelTerms<K> {
        ChannelTerms::new::<C, Q14<NW>>(lighting.directional_terms())
    }
}

/// An incremental Phong shader for `K` directional lights.
type Inc<'l, const NW: u8, const K: usize, M, E, C> =
    Shader<'l, IncrementalPhongShading, Directional<Q14<NW>, K, M>, E, C>;

/// Shades one span with the incremental constants `st`, the general path of
/// `lighting` where the span leaves the fast path's range; `a`/`d` are `[Nx,
/// Ny, Nz, N·L₁, N·H₁, …]` (Q14 with [`ATTR_FRAC`](crate::num::ATTR_FRAC)
/// bits); `SPEC`: the Blinn-Phong term.
#[allow(clippy::too_many_arguments)]
fn shade_run<I: Illuminate, C: OutputColor, const K: usize, const SPEC: bool>(
    st_c: &ChannelTerms<K>,
    lighting: &I,
    x: i32,
    y: i32,
    a: &[i32],
    d: &[i32],
    out: &mut [C],
) {
    // Q28 → Q26
    let q26 = |v: Option<&i32>| v.copied().unwrap_or(0) >> 2;
    let (n0, dn) = (
        [q26(a.first()), q26(a.get(1)), q26(a.get(2))],
        [q26(d.first()), q26(d.get(1)), q26(d.get(2))],
    );
    // |N(k)|² = s0 + k·(2·N0·dN) + k²·|dN|², in Q28 (the normal is Q26)
    let s0 = n0
        .iter()
        .map(|&c| ((c >> 12) * (c >> 12)) as u32 as i64)
        .sum::<i64>();
    let general = |out: &mut [C]| general::<I, C>(lighting, x, y, a, d, out);
    // spans lie in the set-up window (below 2^12 pixels); longer ones (none)
    // take the general path, which holds at any length
    if out.len() >= 1 << 12 {
        return general(out);
    }
    let (n, n1) = (out.len() as i64, out.len().saturating_sub(1) as u32);
    // every product from 32-bit multiplications (no 64-bit multiply helper on
    // the M0): |N0|, |dN| < 2^27 (Q26), |N0·dN| < 2^55, |dN|² < 2^54
    let nd = (0..3).map(|k| mul_i32(n0[k], dn[k])).sum::<i64>() >> 24;
    let dd = (0..3).map(|k| mul_i32(dn[k], dn[k])).sum::<i64>() >> 24;
    if dd > 1 << 24 {
        // |dN| above ¼ per pixel
        return general(out);
    }
    // the extremes of the convex |N(k)|² over the span: the ends, and the vertex
    // when it is inside (tested as s0·dd − nd² ≥ ¼·dd, i.e. min ≥ ¼, no division);
    // dd ≤ 2^24 and n < 2^12: k·dd < 2^36
    let kdd = |k: u32| mul_u32(k, dd as u32) as i64;
    let s_end = s0 + mul_i64_u32(2 * nd + kdd(n1), n1);
    let interior = nd < 0 && nd + kdd(n1) > 0;
    let (lo, hi) = (s0.min(s_end), s0.max(s_end));
    let lo = if interior { 1 << 26 } else { lo };
    // |N|² change per pixel: ds(k) = 2·N0·dN + (2k + 1)·|dN|², largest at an end
    let ds_max = (2 * nd + dd)
        .abs()
        .max((2 * nd + kdd((2 * n - 3).max(1) as u32)).abs());
    // where the product is taken (after `hi`) s0 < 2^30, so |nd| ≤ √(s0·dd) <
    // 2^28 (a larger one, impossible, would take the general path)
    let nd2 = || i32::try_from(nd).map_or(i64::MAX, |v| mul_i32(v, v));
    if lo < 1 << 26
        || hi >= 1 << 30
        || (interior && mul_u32(s0 as u32, dd as u32) as i64 - nd2() < dd << 26)
        || ds_max > lo >> 3
    {
        // |N| outside [½, 2), or changing by more than 1/8 per pixel: the general path
        return general(out);
    }
    // 1/|N| in Q14 at the span start (s ∈ [2^26, 2^30))
    let span = SpanState {
        s: s0 as i32,
        ds: (2 * nd + dd) as i32,
        dds: (2 * dd) as i32,
        r: rsqrt_q28_q14(s0 as u32),
    };
    let dots: [[i32; 4]; K] = core::array::from_fn(|j| {
        [
            q26(a.get(3 + 2 * j)),
            q26(d.get(3 + 2 * j)),
            q26(a.get(4 + 2 * j)),
            q26(d.get(4 + 2 * j)),
        ]
    });
    // One Newton step per pixel from the previous pixel's 1/|N| leaves a relative
    // error of 1.5·e², e the relative change of |N| per pixel: below 2^-8 that is
    // under the Q14 resolution; up to 2^-4 (the limit above) two steps are taken.
    if ds_max <= lo >> 8 {
        run::<C, K, 1, SPEC>(st_c, span, dots, out);
    } else {
        run::<C, K, 2, SPEC>(st_c, span, dots, out);
    }
}

/// A span of [`shade_run`] that leaves the fast path's range: `lighting` per
/// pixel. Out of line and cold (inlined, it cost the fast span set-up 27
/// instructions on the Cortex-M4F).
#[inline(never)]
#[cold]
fn general<I: Illuminate, C: OutputColor>(
    lighting: &I,
    x: i32,
    y: i32,
    a: &[i32],
    d: &[i32],
    out: &mut [C],
) {
    let g =
        |v: &[i32]| [0, 1, 2, 6, 6, 6].map(|i| v.get(i).copied().unwrap_or(0) * i32::from(i < 3));
    perpixel::span(
        (Features::PLAIN, false),
        lighting,
        &Linear,
        &Sources::NONE,
        &PixelTriangle::default(),
        &g(a),
        &g(d),
        x,
        y,
        out,
    )
}

/// The `Kernel` for `K` lights, with `N = 3 + 2K` values.
macro_rules! incremental_lights {
    ($($k:literal => $n:literal),*) => {$(
        impl<const NW: u8, M: IncrementalModel, E: super::Encoder<C>, C: OutputColor> Kernel
            for Inc<'_, NW, $k, M, E, C>
        {
            super::normal_kernel_items!($n);
            /// The normal, then `N·L` and `N·H` per light (Q14).
            type Varyings = [i32; $n];

            #[inline(always)]
            fn triangle(&self, v: [&[i16; 3]; 3], _eye: &[[i32; 3]; 3]) -> ((), [[i32; $n]; 3]) {
                // the normal and N·L, N·H per light (Q14): affine over the
                // triangle like the normal
                ((), v.map(|n| self.state.varyings(n)))
            }

            #[inline(always)]
            fn span(&self, _t: &(), a: &[i32; $n], d: &[i32; $n], x: i32, y: i32, out: &mut [C]) {
                if M::SPECULAR == Specular::BlinnPhong {
                    shade_run::<_, C, $k, true>(&self.state, self.lighting, x, y, a, d, out)
                } else {
                    shade_run::<_, C, $k, false>(&self.state, self.lighting, x, y, a, d, out)
                }
            }
        }
    )*};
}
incremental_lights!(1 => 5, 2 => 7, 3 => 9, 4 => 11);

/// `|N|²` (Q28) with its forward differences, and `1/|N|` (Q14).
#[derive(Clone, Copy, Debug)]
struct SpanState {
    s: i32,
    ds: i32,
    dds: i32,
    r: i32,
}

/// The per-pixel loop; `dots[j]` = `[N·L, step, N·H, step]` of light `j`
/// (Q26); `SPEC`: the Blinn-Phong term.
#[inline(always)]
fn run<C: OutputColor, const K: usize, const NEWTON: u32, const SPEC: bool>(
    state: &ChannelTerms<K>,
    st: SpanState,
    mut dots: [[i32; 4]; K],
    out: &mut [C],
) {
    let SpanState {
        mut s,
        mut ds,
        dds,
        mut r,
    } = st;
    for p in out.iter_mut() {
        // every light term is ≥ 0; the base may be negative (negative ambient)
        let mut acc = state.base();
        for (lt, dot) in state.lights.iter().zip(dots.iter_mut()) {
            // N·L/|N| and N·H/|N| (Q14)
            let d = ((dot[0] >> 12) * r) >> 14;
            if d > 0 {
                let h = if SPEC { ((dot[2] >> 12) * r) >> 14 } else { 0 };
                state.add::<SPEC>(&mut acc, lt, d, h);
            }
            dot[0] += dot[1];
            dot[2] += dot[3];
        }
        *p = ChannelTerms::<K>::color(acc);
        // next pixel: |N|² by forward differences, then r ← r·(3 − s·r²)/2
        // seeded with this pixel's r
        s += ds;
        ds += dds;
        for _ in 0..NEWTON {
            let r2 = (r * r) >> 14;
            let sr2 = ((s >> 14) * r2) >> 14;
            r = (r * (49152 - sr2)) >> 15;
        }
    }
}
