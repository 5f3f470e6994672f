//! Exact attribute values at pixel centres, for the per-triangle API.
//!
//! At a pixel centre `P` inside the triangle, the barycentric numerators
//! `nᵢ = A·βᵢ(P)` are exact 32-bit edge-function values. A screen-linear
//! attribute is `a = a_T + (Δa₁·n₁ + Δa₂·n₂)/A`; a perspective-correct one uses
//! the weights `wᵢ = qᵢ·nᵢ` (`q = 1/w`): `a = a_T + (Δa₁·w₁ + Δa₂·w₂)/Σwᵢ`.
//! The products and the division are done on 64-bit values built from 32-bit
//! operations ([`crate::num::wide`]), rounded once: every value is the exact
//! one rounded to a unit (perspective weights keep at least 30 significant
//! bits: within one unit).

use super::setup::{at3, bit_length, next3, Setup};
use super::{fit, ClampTo, RasterVertex, SUBPIXEL_BITS};
use crate::num::wide::{div_u64_u32, mul_u32};

/// Fraction bits of the depth values of a run.
pub(crate) const Z_FRAC: u32 = 15;

/// The exact evaluator of one triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Exact<const N: usize, const PERSP: bool> {
    /// The top vertex and the other two (in the order of `Setup::bary.other`).
    t: (i32, i32),
    d1: (i32, i32),
    d2: (i32, i32),
    /// The doubled area, `> 0`.
    area: i32,
    base: [i32; N],
    da: [[i32; 2]; N],
    lo: [i32; N],
    hi: [i32; N],
    zbase: i32,
    dz: [i32; 2],
    zlo: i32,
    zhi: i32,
    /// `1/w` of the top and the other two vertices.
    q: [u32; 3],
}

/// `|x|·|y|` with the sign of `x·y`, exactly (`|x|, |y| < 2^32`).
#[inline]
fn signed_mul(x: i32, y: u32) -> i64 {
    let m = mul_u32(x.unsigned_abs(), y) as i64;
    if x < 0 {
        -m
    } else {
        m
    }
}

/// `round(num / den)` for `den > 0` and `|num / den| < 2^31` (ties away from zero).
#[inline]
fn div_round(num: i64, den: u32) -> i32 {
    let mag = num.unsigned_abs() + u64::from(den >> 1);
    let (q, _) = div_u64_u32(mag, den);
    let q = q.min(i32::MAX as u32) as i32;
    if num < 0 {
        -q
    } else {
        q
    }
}

impl<const N: usize, const PERSP: bool> Exact<N, PERSP> {
    /// The evaluator of set-up triangle `s` with vertices `v` (input order).
    pub(crate) fn new(s: &Setup, v: &[RasterVertex<N>; 3]) -> Self {
        let t = s.tmb[0];
        let (i1, i2) = (next3(t), next3(next3(t)));
        let vt = at3(v, at3(&s.order, t));
        let v1 = at3(v, at3(&s.order, i1));
        let v2 = at3(v, at3(&s.order, i2));
        let p = |i: usize| at3(&s.xy, i);
        let d1 = (p(i1).0 - p(t).0, p(i1).1 - p(t).1);
        let d2 = (p(i2).0 - p(t).0, p(i2).1 - p(t).1);
        let area = d1.0 * d2.1 - d1.1 * d2.0;
        let range = |a: i32, b: i32, c: i32| (a.min(b).min(c), a.max(b).max(c));
        let z = [vt.z, v1.z, v2.z].map(i32::from);
        let (zlo, zhi) = range(z[0], z[1], z[2]);
        Exact {
            t: p(t),
            d1,
            d2,
            area,
            base: vt.attrs,
            da: core::array::from_fn(|i| [v1.attrs[i] - vt.attrs[i], v2.attrs[i] - vt.attrs[i]]),
            lo: core::array::from_fn(|i| range(vt.attrs[i], v1.attrs[i], v2.attrs[i]).0),
            hi: core::array::from_fn(|i| range(vt.attrs[i], v1.attrs[i], v2.attrs[i]).1),
            zbase: z[0],
            dz: [z[1] - z[0], z[2] - z[0]],
            zlo: zlo << Z_FRAC,
            // (65535 << 15) + 2^15 − 1 = i32::MAX: add the low bits as one term (no overflow)
            zhi: (zhi << Z_FRAC) + ((1 << Z_FRAC) - 1),
            q: [vt.inv_w, v1.inv_w, v2.inv_w].map(|q| q.max(1) as u32),
        }
    }

    /// `(n₁, n₂)`: the doubled-area barycentric numerators of the two non-top
    /// vertices at the centre of pixel `(x, y)` (exact; non-negative inside).
    #[inline]
    fn numerators(&self, x: i32, y: i32) -> (u32, u32) {
        let half = 1 << (SUBPIXEL_BITS - 1);
        let px = (x << SUBPIXEL_BITS) + half - self.t.0;
        let py = (y << SUBPIXEL_BITS) + half - self.t.1;
        // each product < 2^30 inside the window
        let n1 = px * self.d2.1 - py * self.d2.0;
        let n2 = self.d1.0 * py - self.d1.1 * px;
        (n1.max(0) as u32, n2.max(0) as u32)
    }

    /// The weights `(w₁, w₂, Σw)` at `(x, y)`: the numerators, or for
    /// perspective `qᵢ·nᵢ` scaled so that `Σw < 2^32`.
    #[inline]
    fn weights(&self, x: i32, y: i32) -> (u32, u32, u32) {
        let (n1, n2) = self.numerators(x, y);
        if !PERSP {
            return (n1, n2, self.area as u32);
        }
        let n0 = (self.area as u32).saturating_sub(n1).saturating_sub(n2);
        let w = [
            mul_u32(n0, self.q[0]),
            mul_u32(n1, self.q[1]),
            mul_u32(n2, self.q[2]),
        ];
        let max = w[0].max(w[1]).max(w[2]);
        let bits = 64 - max.leading_zeros_u64();
        let sh = bits.saturating_sub(30);
        let w = w.map(|v| (v >> sh) as u32);
        (w[1], w[2], (w[0] + w[1] + w[2]).max(1))
    }

    /// The attribute values at `(x, y)`, rounded, within the vertex range.
    #[inline]
    fn values(&self, x: i32, y: i32) -> [i32; N] {
        let (w1, w2, sum) = self.weights(x, y);
        core::array::from_fn(|i| {
            let num = signed_mul(self.da[i][0], w1) + signed_mul(self.da[i][1], w2);
            self.base[i]
                .wrapping_add(div_round(num, sum))
                .clamp_to(self.lo[i], self.hi[i])
        })
    }

    /// `(start, step)` of the segment of pixels `k0..=k1` of row `y`: exact
    /// values at both ends, the step rounded, clamped (see [`fit`]).
    pub(crate) fn segment(&self, k0: i32, k1: i32, y: i32) -> ([i32; N], [i32; N]) {
        let a0 = self.values(k0, y);
        if k1 <= k0 || N == 0 {
            return (a0, [0; N]);
        }
        let a1 = self.values(k1, y);
        let span = k1 - k0;
        let mut start = [0; N];
        let mut step = [0; N];
        for i in 0..N {
            // |a1 − a0| ≤ 2^30 within the attribute limit
            let d = div_round(i64::from(a1[i]) - i64::from(a0[i]), span as u32);
            (start[i], step[i]) = fit(a0[i], d, span + 1, self.lo[i], self.hi[i]);
        }
        (start, step)
    }

    /// Depth with [`Z_FRAC`] fraction bits (+½, so that `>> Z_FRAC` rounds) at
    /// the first pixel of the run `lo..=hi` of row `y`, and its step: exact at
    /// both ends, linear in screen space.
    pub(crate) fn depth_run(&self, lo: i32, hi: i32, y: i32) -> (i32, i32) {
        let z = |x: i32| {
            let (n1, n2) = self.numerators(x, y);
            // |Δz|·n < 2^47, ·2^15 < 2^62
            let num = (signed_mul(self.dz[0], n1) + signed_mul(self.dz[1], n2)) << Z_FRAC;
            ((self.zbase << Z_FRAC) + div_round(num, self.area as u32) + (1 << (Z_FRAC - 1)))
                .clamp_to(self.zlo, self.zhi)
        };
        let z0 = z(lo);
        if hi <= lo {
            return (z0, 0);
        }
        let z1 = z(hi);
        let d = div_round(i64::from(z1) - i64::from(z0), (hi - lo) as u32);
        fit(z0, d, hi - lo + 1, self.zlo, self.zhi)
    }
}

/// `leading_zeros` of a `u64` without a library call (two 32-bit halves).
trait LeadingZeros64 {
    fn leading_zeros_u64(self) -> u32;
}

impl LeadingZeros64 for u64 {
    #[inline]
    fn leading_zeros_u64(self) -> u32 {
        let hi = (self >> 32) as u32;
        if hi != 0 {
            32 - bit_length(hi)
        } else {
            64 - bit_length(self as u32)
        }
    }
}
