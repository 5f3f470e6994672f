//! Inverse square roots: seed tables and Newton steps in integer arithmetic
//! (the fixed tiers, and the shading kernels' `1/|N|`), a bit-trick seed and
//! Newton steps in `f32`.
//!
//! With `s = s′ · 2^(W − k)`, `s′ ∈ [¼, 1)`, `k` even (W = 32 or 64), the
//! mantissa functions return `y = 1/√s′ ∈ (1, 2]` and `k`:
//! `1/√s = y · 2^((k − W)/2)`. Relative error of `y` (unit tests below): seed
//! ≤ 1.6·10⁻², one Newton step ≤ 4·10⁻⁴, two at the output's resolution;
//! [`rsqrt_q15`] (`|N|²` near 1, no split), finer seeds: ≤ 7·10⁻⁵ after one.

/// Seed `1/√s′` in Q14 for `s′ ∈ [i/64, (i+1)/64)`, taken at the bin centre:
/// `2^14 / √((i + ½)/64) = √(2^35 / (2i + 1))`. Only `i = 16..64` is reached for a
/// split mantissa; the low entries exist so that the index is a mask, not a bound
/// check.
static SEED_Q14: [u16; 64] = {
    let mut t = [0u16; 64];
    let mut i = 16;
    while i < 64 {
        let bin = 2 * i as u64 + 1;
        t[i] = ((1u64 << 35) / bin).isqrt() as u16;
        i += 1;
    }
    t
};

/// The seeds of [`rsqrt_q15`]: `1/√s` in Q15 at the centres of `2^22`-wide
/// bins over `[2^28, 2^31)` (relative error ≤ 0.4 %); not [`SEED_Q14`] read
/// finer (other bin centres, and the kernels' pixels depend on the seeds).
static SEED_Q15: [u16; 448] = {
    let mut t = [0u16; 448];
    let mut i = 0;
    while i < 448 {
        let centre = (1u64 << 28) + ((2 * i as u64 + 1) << 21);
        let r = ((1u64 << 60) / centre).isqrt();
        t[i] = if r > 65535 { 65535 } else { r as u16 };
        i += 1;
    }
    t
};

/// The mantissa seed of bin `bin` (bins of 1/64 of `s′`), Q14.
#[inline(always)]
fn mantissa_seed(bin: u32) -> u32 {
    u32::from(SEED_Q14[(bin & 63) as usize])
}

/// `y ≈ 1/√(t/2^16)` in Q14 for `t ∈ [2^14, 2^16)`, with `newton` Newton steps,
/// all products within 32 bits.
#[inline(always)]
pub(crate) fn rsqrt_q14_mantissa(t: u32, newton: u8) -> u32 {
    let mut y = mantissa_seed(t >> 10);
    let mut i = 0;
    while i < newton {
        // y ← y·(3 − t·y²)/2
        let y2 = (y * y) >> 14; // Q14, ≤ 2^16
        let ty2 = (t * y2) >> 16; // Q14, ≈ 2^14
        y = (y * 49152u32.saturating_sub(ty2)) >> 15;
        i += 1;
    }
    y
}

/// `y ≈ 1/√(t/2^32)` in Q30 for `t ∈ [2^30, 2^32)`, with `newton` Newton steps,
/// products within 64 bits.
#[inline(always)]
pub(crate) fn rsqrt_q30_mantissa(t: u32, newton: u8) -> u64 {
    let mut y = u64::from(mantissa_seed(t >> 26)) << 16;
    let t = t as u64;
    let mut i = 0;
    while i < newton {
        // y ← y·(3 − t·y²)/2
        let y2 = (y * y) >> 30; // Q30, ≤ 2^32
        let ty2 = (t * y2) >> 32; // Q30, ≈ 2^30
        y = (y * (3u64 << 30).saturating_sub(ty2)) >> 31;
        i += 1;
    }
    y
}

/// Splits `s > 0` (u32) into `(t, k)`: `t = (s << k) >> 16 ∈ [2^14, 2^16)`, `k` even.
#[inline(always)]
pub(crate) fn split_u32(s: u32) -> (u32, u32) {
    let k = s.leading_zeros() & !1;
    ((s << k) >> 16, k)
}

/// Splits `s > 0` (u64) into `(t, k)`: `t = (s << k) >> 32 ∈ [2^30, 2^32)`, `k` even.
#[inline(always)]
pub(crate) fn split_u64(s: u64) -> (u32, u32) {
    let k = s.leading_zeros() & !1;
    (((s << k) >> 32) as u32, k)
}

/// `1/√(s/2^28)` in Q14 for `s > 0` in Q28 (a squared length whose components are
/// Q14): the mantissa with two Newton steps, about the Q14 resolution.
#[inline(always)]
pub(crate) fn rsqrt_q28_q14(s: u32) -> i32 {
    let (t, k) = split_u32(s);
    // 1/√s = y·2^((k − 4)/2) / 2^14, k even and y ≤ 2^15: the shift left first
    // loses nothing
    ((rsqrt_q14_mantissa(t, 2) << (k / 2)) >> 2) as i32
}

/// `1/|v|` in Q14 for `|v|² = s` in Q28, any `s` (below `2^20`, i.e. `|v| < 1/16`,
/// taken as `2^20`).
#[inline]
pub(crate) fn inv_len_q14(s: i32) -> i32 {
    rsqrt_q28_q14(s.max(1 << 20) as u32)
}

/// `1/√s` in Q15 for `s` in `[2^28, 2^31)` (Q30: `|N|` in `[½, √2)`): the
/// [`SEED_Q15`] seed of its bin and one Newton step ([`newton_q15`]), relative
/// error below 7·10⁻⁵ (below 5·10⁻⁵ for `|N| > 0.7`: the rounding of the Q15
/// arithmetic). An `s` outside the range gives a wrong value, never a panic.
#[inline(always)]
pub(crate) fn rsqrt_q15(s: u32) -> u32 {
    let y = u32::from(SEED_Q15[((s.wrapping_sub(1 << 28) >> 22) as usize).min(447)]);
    // the seed is within 0.4 %
    newton_q15(y, s)
}

/// One Newton step of `1/√s` (Q15) from `y` (Q15, within a few percent), `s` in
/// Q30 as for [`rsqrt_q15`].
#[inline(always)]
pub(crate) fn newton_q15(y: u32, s: u32) -> u32 {
    // y ← y + y·(1 − s·y²)/2; s·y² ≈ 1: no overflow
    let y2 = (y * y + (1 << 14)) >> 15;
    let sy2 = ((s >> 15) * y2 + (1 << 14)) >> 15;
    let corr = (1i32 << 15) - sy2 as i32;
    (y as i32 + ((y as i32 * corr + (1 << 15)) >> 16)) as u32
}

/// `1/√x` in `f32` with `libm` (exact to an ulp).
#[inline(always)]
pub(crate) fn rsqrt_exact(x: f32) -> f32 {
    1.0 / libm::sqrtf(x)
}

/// One Newton step `y ← y·(1.5 − ½·x·y²)` of `1/√x` in `f32`.
#[inline(always)]
pub(crate) fn newton_f32(y: f32, x: f32) -> f32 {
    y * (1.5 - 0.5 * x * y * y)
}

/// micromath's bit-trick seed refined by `N` Newton steps (no `libm`, no
/// division): relative error about 10⁻⁷ with three steps.
#[inline(always)]
pub(crate) fn rsqrt_micromath<const N: u8>(x: f32) -> f32 {
    let mut y = micromath::F32Ext::invsqrt(x);
    let mut i = 0;
    while i < N {
        y = newton_f32(y, x);
        i += 1;
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    fn worst_q14(newton: u8) -> f64 {
        let mut worst = 0.0f64;
        for t in (1u32 << 14)..(1u32 << 16) {
            let y = rsqrt_q14_mantissa(t, newton) as f64 / 16384.0;
            let want = 1.0 / libm::sqrt(t as f64 / 65536.0);
            worst = worst.max((y - want).abs() / want);
        }
        worst
    }

    fn worst_q30(newton: u8) -> f64 {
        let mut worst = 0.0f64;
        let mut t = 1u64 << 30;
        while t < 1u64 << 32 {
            let y = rsqrt_q30_mantissa(t as u32, newton) as f64 / (1u64 << 30) as f64;
            let want = 1.0 / libm::sqrt(t as f64 / 4294967296.0);
            worst = worst.max((y - want).abs() / want);
            t += 40_009;
        }
        worst
    }

    #[test]
    fn seed_and_newton_error_bounds() {
        assert!(worst_q14(0) < 1.6e-2, "{}", worst_q14(0));
        assert!(worst_q14(1) < 4.0e-4, "{}", worst_q14(1));
        // two steps: limited by Q14 output resolution (2^-14 on values up to 2)
        assert!(worst_q14(2) < 1.5e-4, "{}", worst_q14(2));
        assert!(worst_q30(0) < 1.6e-2);
        assert!(worst_q30(1) < 4.0e-4);
        assert!(worst_q30(2) < 2.0e-7, "{}", worst_q30(2));
        assert!(worst_q30(3) < 5.0e-9, "{}", worst_q30(3));
    }

    #[test]
    fn split_ranges() {
        for s in [1u32, 2, 3, 255, 1 << 20, u32::MAX] {
            let (t, k) = split_u32(s);
            assert!((1 << 14..1 << 16).contains(&t) && k % 2 == 0, "{s}");
        }
        for s in [1u64, 7, 1 << 40, u64::MAX] {
            let (t, k) = split_u64(s);
            assert!(t >= 1 << 30 && k % 2 == 0, "{s}");
        }
    }
    /// The mantissa seeds are the bin centres', `⌊√(2^35/(2i + 1))⌋`.
    #[test]
    fn mantissa_seeds_are_the_bin_centres() {
        for i in 16..64u32 {
            let want = ((1u64 << 35) / u64::from(2 * i + 1)).isqrt() as u32;
            assert_eq!(mantissa_seed(i), want, "{i}");
        }
    }

    #[test]
    fn rsqrt_seed_and_step() {
        let (mut worst, mut worst_07) = (0.0f64, 0.0f64);
        let mut s = 1u32 << 28;
        while s < (1u32 << 31) - 1000 {
            let y = f64::from(rsqrt_q15(s)) / 32768.0;
            let x = f64::from(s) / f64::from(1u32 << 30);
            let want = 1.0 / x.sqrt();
            let e = (y - want).abs() / want;
            worst = worst.max(e);
            if x > 0.49 {
                worst_07 = worst_07.max(e);
            }
            // one step of `newton_q15` from the seed at the centre of the bin
            let bin = ((s - (1 << 28)) >> 22).min(447);
            let centre = (1u64 << 28) + ((2 * u64::from(bin) + 1) << 21);
            let seed = ((1u64 << 60) / centre).isqrt() as u32;
            assert_eq!(rsqrt_q15(s), newton_q15(seed, s), "{s}");
            s += 99_991;
        }
        // measured 6.1e-5 (at |N| ≈ 0.52, where the seed bins are widest) and
        // 4.7e-5 for |N| > 0.7 (the rounding of the Q15 arithmetic)
        assert!(worst < 7.0e-5, "{worst}");
        assert!(worst_07 < 5.0e-5, "{worst_07}");
        for s in [0, 1, 1 << 27, 1 << 31, u32::MAX - (1 << 20), u32::MAX] {
            let _ = rsqrt_q15(s); // no panic, no overflow
        }
    }

    #[test]
    fn inverse_lengths() {
        for s in (0..=31).flat_map(|b| [1i32 << b, (1i32 << b) + 12345, i32::MAX >> (31 - b)]) {
            let s = s.max(1);
            let got = f64::from(inv_len_q14(s)) / 16384.0;
            let want = 1.0 / (f64::from(s.max(1 << 20)) / f64::from(1 << 28)).sqrt();
            assert!(
                (got - want).abs() < 1.5e-4 * want + 1.0 / 16384.0,
                "{s}: {got} {want}"
            );
            // the former formula of the normal-map kernel
            let (t, k) = split_u32(s.max(1 << 20) as u32);
            let y = rsqrt_q14_mantissa(t, 2) as i32;
            let old = if k >= 4 {
                y << ((k - 4) / 2)
            } else {
                y >> ((4 - k) / 2)
            };
            assert_eq!(inv_len_q14(s), old, "{s}");
        }
        assert_eq!(inv_len_q14(0), inv_len_q14(1 << 20));
        assert_eq!(inv_len_q14(-5), inv_len_q14(1 << 20));
    }

    #[test]
    fn f32_rsqrt() {
        for x in [0.25f32, 0.3, 0.5, 0.999, 1.0, 1.7, 1.999] {
            let want = 1.0 / f64::from(x).sqrt();
            let got = f64::from(rsqrt_micromath::<3>(x));
            assert!((got - want).abs() < 2.0e-7 * want, "{x}: {got}");
            assert!((f64::from(rsqrt_exact(x)) - want).abs() < 1.2e-7 * want);
        }
    }
}
