//! The anchors of [`QuadraticPhongShading`](crate::shade::QuadraticPhongShading):
//! the lighting of one span evaluated exactly at single pixels, in 32-bit integer
//! arithmetic ([`Q14Probe`], the `Q14` tiers) or in `f32` ([`F32Probe`], the FPU
//! tiers), and the specular power at every pixel of a segment.
// the probes index several per-light and per-channel arrays at once
#![allow(clippy::needless_range_loop)]

use super::segment::{self, Anchor, Probe, DFRAC};
use super::{Coeffs, QuadraticModel, QuadraticState};
use crate::lighting::Specular;
use crate::num::rsqrt::{newton_f32, newton_q15, rsqrt_micromath, rsqrt_q15};

/// `|N|²` in Q30 of a normal with Q15 components below 2 in magnitude (each
/// square below 2^32: exact as `u32`).
#[inline(always)]
fn len2_q30(c: [i32; 3]) -> u32 {
    (c[0].wrapping_mul(c[0]) as u32)
        .wrapping_add(c[1].wrapping_mul(c[1]) as u32)
        .wrapping_add(c[2].wrapping_mul(c[2]) as u32)
}

/// `1/|N|` (Q15) of the Q26 normal `n0 + x·dn` at pixel `x`, where `|N|` is in
/// `[½, √2)` (else `None`: the general path).
#[inline(always)]
pub(super) fn inv_len_at(n0: &[i32; 3], dn: &[i32; 3], x: i32) -> Option<u32> {
    let s = len2_q30(core::array::from_fn(|i| {
        n0[i].wrapping_add(x.wrapping_mul(dn[i])) >> 11
    }));
    if (1 << 28..1 << 31).contains(&s) {
        Some(rsqrt_q15(s))
    } else {
        None
    }
}

/// `|dN|²` per pixel² (Q30, the normal in units of `N·N = 1`), rounded up, of
/// the Q26 step `dn`.
#[inline(always)]
pub(super) fn turn2(dn: &[i32; 3]) -> u32 {
    dn.iter()
        .map(|d| {
            let c = (d.unsigned_abs() >> 11) + 1;
            c * c
        })
        .sum::<u32>()
}

/// Evaluates the Q14 directional lighting along one span.
pub(super) struct Q14Probe<'a, const K: usize, M> {
    n0: [i32; 3],
    dn: [i32; 3],
    /// Per light: `[N·L, N·H or N·V]` at the start and their steps (Q26).
    a0: [[i32; 2]; K],
    da: [[i32; 2]; K],
    st: &'a QuadraticState<K>,
    c: Coeffs<K>,
    model: core::marker::PhantomData<M>,
}

impl<'a, const K: usize, M> Q14Probe<'a, K, M> {
    /// The probe of a span whose attributes start at `start` with steps `step`
    /// (`[Nx, Ny, Nz, N·L₁, N·H₁, …]`, Q26), colour coefficients `c`.
    pub(super) fn new(
        st: &'a QuadraticState<K>,
        c: Coeffs<K>,
        start: &[i32],
        step: &[i32],
    ) -> Self {
        Self {
            n0: [start[0], start[1], start[2]],
            dn: [step[0], step[1], step[2]],
            a0: core::array::from_fn(|k| [start[3 + 2 * k], start[4 + 2 * k]]),
            da: core::array::from_fn(|k| [step[3 + 2 * k], step[4 + 2 * k]]),
            st,
            c,
            model: core::marker::PhantomData,
        }
    }
}

impl<const K: usize, M: QuadraticModel> Probe<K> for Q14Probe<'_, K, M> {
    #[inline(never)]
    fn anchor(&self, x: i32, a: &mut Anchor<K>) {
        let r = inv_len_at(&self.n0, &self.dn, x);
        a.ok = r.is_some();
        a.v = self.c.base;
        let Some(r) = r else {
            return;
        };
        a.r = r;
        let st = self.st;
        for k in 0..K {
            let at = |i: usize| self.a0[k][i].wrapping_add(x.wrapping_mul(self.da[k][i])) >> 11;
            // |N·L| ≤ |N|: |(N·L)·r| ≤ 2^30
            let d = (at(0) * r as i32) >> DFRAC;
            a.d[k] = d;
            if d > 0 {
                for ch in 0..3 {
                    a.v[ch] = a.v[ch].saturating_add(d * self.c.kd[k][ch]);
                }
            }
            if M::SPECULAR != Specular::None {
                let e = (at(1) * r as i32) >> DFRAC;
                let x = if M::SPECULAR == Specular::Phong {
                    // R·V = 2(N̂·L)(N̂·V) − L·V
                    ((d * e) >> 14) - st.lv[k]
                } else {
                    e
                };
                // |x − x0| ≤ 2^15 and u_mul < 2^15: no overflow; far below x0
                // (x^n = 0 there) the coordinate is clamped
                let dx = x - st.pow.x0();
                a.u[k] = if dx < -(1 << 14) {
                    segment::U_FLOOR
                } else {
                    (dx * st.u_mul) >> st.u_sh
                };
            }
        }
        // the segment arithmetic wants values below 2^30
        a.ok = a.v.iter().all(|v| v.unsigned_abs() < 1 << 30);
    }

    #[inline(never)]
    fn spec(&self, x0: i32, k: usize, out: &mut [u16]) {
        let st = self.st;
        let mut n: [i32; 3] =
            core::array::from_fn(|i| self.n0[i].wrapping_add(x0.wrapping_mul(self.dn[i])));
        let at = |i: usize| self.a0[k][i].wrapping_add(x0.wrapping_mul(self.da[k][i]));
        let (mut nl, mut nh) = (at(0), at(1));
        let (dnl, dnh) = (self.da[k][0], self.da[k][1]);
        // the linear prediction of 1/|N| is off by |r''/r| ≤ 3·(|dN|/|N|)²; below
        // 3·2^−10 one Newton step leaves < 1.5·10⁻⁵; above (the normal turns by
        // more than 1/32 radian per pixel) the table seed at every pixel
        let fast = turn2(&self.dn) > 1 << 18;
        let (mut r, mut dr) = (0u32, 0i32);
        for (i, p) in out.iter_mut().enumerate() {
            let s = len2_q30(n.map(|v| v >> 11));
            // |N| is in [½, √2) on the segment (checked at its anchors)
            let r1 = if i < 2 || fast {
                rsqrt_q15(s.clamp(1 << 28, (1 << 31) - 1))
            } else {
                newton_q15((r as i32 + dr) as u32, s)
            };
            dr = r1 as i32 - r as i32;
            r = r1;
            let e = ((nh >> 11) * r as i32) >> DFRAC;
            let x = if M::SPECULAR == Specular::Phong {
                let d = ((nl >> 11) * r as i32) >> DFRAC;
                ((d * e) >> 14) - st.lv[k]
            } else {
                e
            };
            let dx = x - st.pow.x0();
            *p = if dx <= 0 {
                0
            } else {
                st.pow.at((dx * st.u_mul) >> st.u_sh) as u16
            };
            for (v, d) in n.iter_mut().zip(self.dn) {
                *v = v.wrapping_add(d);
            }
            nl = nl.wrapping_add(dnl);
            nh = nh.wrapping_add(dnh);
            crate::num::no_unroll();
        }
    }
}

// ---- the f32 probe ----------------------------------------------------------------

/// Evaluates the directional lighting along one span in `f32` (the FPU tiers).
pub(super) struct F32Probe<'a, const K: usize, M> {
    n0: [f32; 3],
    dn: [f32; 3],
    /// Per light: `[N·L, N·H or N·V]` at the start and their steps.
    a0: [[f32; 2]; K],
    da: [[f32; 2]; K],
    st: &'a QuadraticState<K>,
    /// Encoded units: the constant part, and per unit of `N̂·L̂`.
    base: [f32; 3],
    kd: [[f32; 3]; K],
    model: core::marker::PhantomData<M>,
}

/// A Q26 attribute as `f32`.
#[inline(always)]
fn q26(a: i32) -> f32 {
    a as f32 * (1.0 / (1u32 << 26) as f32)
}

impl<'a, const K: usize, M: QuadraticModel> F32Probe<'a, K, M> {
    /// The probe of a span as [`Q14Probe::new`]; `base` and `kd` are the
    /// constant part and the encoded units per unit of `N̂·L̂`.
    pub(super) fn new(
        st: &'a QuadraticState<K>,
        base: [f32; 3],
        kd: [[f32; 3]; K],
        start: &[i32],
        step: &[i32],
    ) -> Self {
        Self {
            n0: [q26(start[0]), q26(start[1]), q26(start[2])],
            dn: [q26(step[0]), q26(step[1]), q26(step[2])],
            a0: core::array::from_fn(|k| [q26(start[3 + 2 * k]), q26(start[4 + 2 * k])]),
            da: core::array::from_fn(|k| [q26(step[3 + 2 * k]), q26(step[4 + 2 * k])]),
            st,
            base,
            kd,
            model: core::marker::PhantomData,
        }
    }

    /// The table coordinate of specular base `x`.
    #[inline(always)]
    fn u(&self, x: f32) -> i32 {
        let u = (x - self.st.fl.x0) * self.st.fl.u_scale;
        if u < segment::U_FLOOR as f32 {
            segment::U_FLOOR
        } else {
            u as i32
        }
    }
}

impl<const K: usize, M: QuadraticModel> Probe<K> for F32Probe<'_, K, M> {
    #[inline(never)]
    fn anchor(&self, x: i32, a: &mut Anchor<K>) {
        let xf = x as f32;
        let n: [f32; 3] = core::array::from_fn(|i| self.n0[i] + xf * self.dn[i]);
        let s = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        a.ok = (0.25..2.0).contains(&s);
        a.v = [0; 3];
        if !a.ok {
            return;
        }
        let r = rsqrt_micromath::<3>(s);
        a.r = (r * 32768.0) as u32;
        let mut v = self.base;
        let st = self.st;
        for k in 0..K {
            let d = (self.a0[k][0] + xf * self.da[k][0]) * r;
            a.d[k] = (d * 32768.0) as i32;
            if d > 0.0 {
                for c in 0..3 {
                    v[c] += d * self.kd[k][c];
                }
            }
            if M::SPECULAR != Specular::None {
                let e = (self.a0[k][1] + xf * self.da[k][1]) * r;
                let x = if M::SPECULAR == Specular::Phong {
                    2.0 * d * e - st.fl.lv[k]
                } else {
                    e
                };
                a.u[k] = self.u(x);
            }
        }
        // the segment arithmetic wants values below 2^30
        a.ok = v.iter().all(|c| c.abs() < 1.0e9);
        a.v = v.map(|c| c as i32);
    }

    #[inline(never)]
    fn spec(&self, x0: i32, k: usize, out: &mut [u16]) {
        let st = self.st;
        let xf = x0 as f32;
        let mut n: [f32; 3] = core::array::from_fn(|i| self.n0[i] + xf * self.dn[i]);
        let (mut nl, mut nh) = (
            self.a0[k][0] + xf * self.da[k][0],
            self.a0[k][1] + xf * self.da[k][1],
        );
        // as the Q14 probe: the linear prediction and one Newton step while the
        // normal turns by less than 1/32 radian per pixel
        let fast = self.dn.iter().map(|d| d * d).sum::<f32>() > 1.0 / 1024.0 * 0.25;
        let (mut r, mut dr) = (0.0f32, 0.0f32);
        for (i, p) in out.iter_mut().enumerate() {
            let s = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            let r1 = if i < 2 || fast {
                rsqrt_micromath::<3>(s)
            } else {
                newton_f32(r + dr, s)
            };
            dr = r1 - r;
            r = r1;
            let e = nh * r;
            let x = if M::SPECULAR == Specular::Phong {
                2.0 * (nl * r) * e - st.fl.lv[k]
            } else {
                e
            };
            let u = self.u(x);
            *p = if u <= 0 { 0 } else { st.pow.at(u) as u16 };
            for (v, d) in n.iter_mut().zip(self.dn) {
                *v += d;
            }
            nl += self.da[k][0];
            nh += self.da[k][1];
            crate::num::no_unroll();
        }
    }
}
