//! Inverse square root in integer arithmetic: a 48-entry seed table and Newton steps.
//!
//! A positive integer `s` is written as `s = s′ · 2^(W − k)` with `s′ ∈ [¼, 1)` and
//! `k` even (W = 32 or 64 bits). Then `1/√s = y · 2^((k − W)/2)` with
//! `y = 1/√s′ ∈ (1, 2]`, which is what these functions return (`y` in fixed point
//! together with `k`).
//!
//! Error of `y` (relative, measured by the unit tests below):
//! seed alone ≤ 1.6·10⁻², one Newton step ≤ 4·10⁻⁴, two steps at the resolution of
//! the output format.

/// Seed `1/√s′` in Q14 for `s′ ∈ [i/64, (i+1)/64)`, taken at the bin centre:
/// `2^14 / √((i + ½)/64) = √(2^35 / (2i + 1))`. Only `i = 16..64` is reached for a
/// split mantissa; the low entries exist so that the index is a mask, not a bound check.
const SEED_Q14: [u16; 64] = {
    let mut t = [0u16; 64];
    let mut i = 16;
    while i < 64 {
        let bin = 2 * i as u64 + 1;
        t[i] = ((1u64 << 35) / bin).isqrt() as u16;
        i += 1;
    }
    t
};

/// `y ≈ 1/√(t/2^16)` in Q14 for `t ∈ [2^14, 2^16)`, with `newton` Newton steps,
/// all products within 32 bits.
#[inline(always)]
pub(crate) fn rsqrt_q14_mantissa(t: u32, newton: u8) -> u32 {
    let mut y = SEED_Q14[(t >> 10) as usize & 63] as u32;
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
    let mut y = (SEED_Q14[(t >> 26) as usize & 63] as u64) << 16;
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
}
