//! 64-bit results from 32-bit operations for the rare paths (clipping,
//! perspective sub-span ends) and the incremental kernel's span set-up: on a
//! Cortex-M0 only 32 × 32 → 32-bit products, 64-bit additions, shifts and a
//! bit-serial division, so no `__aeabi_lmul` or `__aeabi_uldivmod` is linked;
//! cores with a widening multiply (Armv7-M, RV32IM) use it, same values.

/// ARMv6-M, told apart on stable Rust by its lack of 32-bit atomics (as
/// `recip::div_2p31`; the Arm target features are not stable in `cfg`).
const ARMV6M: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// `a · b` exactly: on ARMv6-M (no 32 × 32 → 64-bit multiply instruction)
/// from four 16 × 16 → 32-bit products ([`mul_u32_halves`]), elsewhere the
/// core's own widening multiply (`UMULL` on Armv7-M, `MUL` + `MULHU` on
/// RV32IM).
#[inline(always)]
pub(crate) fn mul_u32(a: u32, b: u32) -> u64 {
    if ARMV6M {
        mul_u32_halves(a, b)
    } else {
        u64::from(a) * u64::from(b)
    }
}

/// `a · b` exactly, from four 16 × 16 → 32-bit products.
#[inline(always)]
fn mul_u32_halves(a: u32, b: u32) -> u64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // each partial product < 2^32
    let hh = u64::from(ah * bh);
    let hl = u64::from(ah * bl);
    let lh = u64::from(al * bh);
    let ll = u64::from(al * bl);
    (hh << 32) + (hl << 16) + (lh << 16) + ll
}

/// `a·b` exactly: the core's widening multiply, on ARMv6-M from 32-bit
/// multiplications ([`mul_u32`]: no 64-bit multiply helper on the M0).
#[inline]
pub(crate) fn mul_i32(a: i32, b: i32) -> i64 {
    if !ARMV6M {
        return i64::from(a) * i64::from(b);
    }
    // |a·b| ≤ 2^62
    let m = mul_u32(a.unsigned_abs(), b.unsigned_abs()) as i64;
    if (a < 0) != (b < 0) {
        -m
    } else {
        m
    }
}

/// `x·k` for `|x·k| < 2^63`, from 32-bit multiplications (saturating beyond).
#[inline(always)]
pub(crate) fn mul_i64_u32(x: i64, k: u32) -> i64 {
    let u = x.unsigned_abs();
    let hi = mul_u32((u >> 32) as u32, k);
    let m = if hi >> 31 != 0 {
        i64::MAX
    } else {
        (hi << 32)
            .saturating_add(mul_u32(u as u32, k))
            .min(i64::MAX as u64) as i64
    };
    if x < 0 {
        -m
    } else {
        m
    }
}

/// `(⌊n / d⌋, n mod d)` for `d > 0` and a quotient below 2^32 (`n >> 32 < d`),
/// by restoring division (32 steps). A zero `d` or a quotient that does not fit
/// gives `(u32::MAX, 0)`.
// not inlined: its 32 steps unrolled at every cut of the clipper (four per
// cut) were 3.7 KiB of the M4F's O3 image; the call is nothing beside them
#[inline(never)]
pub(crate) fn div_u64_u32(n: u64, d: u32) -> (u32, u32) {
    if d == 0 || (n >> 32) >= u64::from(d) {
        return (u32::MAX, 0);
    }
    if n >> 32 == 0 {
        let n = n as u32;
        return (n / d, n % d);
    }
    let d = u64::from(d);
    let mut rem = n >> 32; // < d
    let mut lo = n as u32;
    let mut q = 0u32;
    for _ in 0..32 {
        rem = (rem << 1) | u64::from(lo >> 31);
        lo <<= 1;
        q <<= 1;
        if rem >= d {
            rem -= d;
            q |= 1;
        }
    }
    (q, rem as u32)
}

/// `round(a · b / c)` for `b ≤ c`, `c > 0` (the result is at most `a`; ties up).
#[inline]
pub(crate) fn mul_div_round(a: u32, b: u32, c: u32) -> u32 {
    if c == 0 {
        return 0;
    }
    let (q, r) = div_u64_u32(mul_u32(a, b.min(c)), c);
    // r ≥ c − r  ⇔  the fraction is ≥ ½
    if r >= c - r {
        q.saturating_add(1)
    } else {
        q
    }
}

/// `p + round((q − p) · num / den)` for `num ≤ den`, `den > 0`: a point of the
/// segment from `p` to `q`, exact to rounding (ties away from `p`), without
/// overflow for any `i32` ends (the result lies between them).
#[inline]
pub(crate) fn lerp_i32(p: i32, q: i32, num: u32, den: u32) -> i32 {
    let diff = q.wrapping_sub(p) as u32; // |q − p| < 2^32 as the right sign below
    if q >= p {
        p.wrapping_add(mul_div_round(diff, num, den) as i32)
    } else {
        let mag = (p.wrapping_sub(q)) as u32;
        p.wrapping_sub(mul_div_round(mag, num, den) as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul_is_exact() {
        for (a, b) in [
            (0u32, 0u32),
            (u32::MAX, u32::MAX),
            (0xFFFF, 0x10000),
            (123_456_789, 987_654_321),
            (1 << 31, 3),
        ] {
            assert_eq!(mul_u32_halves(a, b), u64::from(a) * u64::from(b), "{a} {b}");
            assert_eq!(mul_u32(a, b), u64::from(a) * u64::from(b), "{a} {b}");
        }
    }

    #[test]
    fn signed_products_are_exact() {
        let edges = [
            0,
            1,
            -1,
            7,
            -7,
            0xFFFF,
            -0x10000,
            i32::MAX,
            i32::MIN,
            123_456_789,
            -987_654_321,
        ];
        for a in edges {
            for b in edges {
                assert_eq!(mul_i32(a, b), i64::from(a) * i64::from(b), "{a} {b}");
            }
        }
        let wide = [
            0i64,
            1,
            -1,
            (1 << 40) + 12_345,
            -(1 << 52) - 3,
            i64::from(i32::MIN),
            1 << 32,
        ];
        for x in wide {
            for k in [0u32, 1, 4095, 1 << 11, 65_535] {
                let want = (i128::from(x) * i128::from(k))
                    .clamp(-i128::from(i64::MAX), i128::from(i64::MAX));
                assert_eq!(i128::from(mul_i64_u32(x, k)), want, "{x} {k}");
            }
        }
        // beyond i64: saturated, never wrapped
        assert_eq!(mul_i64_u32(i64::MAX, 2), i64::MAX);
        assert_eq!(mul_i64_u32(-(1 << 62), 4), -i64::MAX);
        assert_eq!(mul_i64_u32(1 << 33, u32::MAX), i64::MAX);
    }

    #[test]
    fn division_is_exact() {
        for (n, d) in [
            (0u64, 1u32),
            (u64::from(u32::MAX) * 7 + 5, 7),
            ((1u64 << 63) + 12345, u32::MAX),
            (1u64 << 40, 1 << 9),
            (999, 1000),
        ] {
            let (q, r) = div_u64_u32(n, d);
            assert_eq!(u64::from(q), n / u64::from(d), "{n} {d}");
            assert_eq!(u64::from(r), n % u64::from(d), "{n} {d}");
        }
        assert_eq!(div_u64_u32(1 << 40, 1 << 8), (u32::MAX, 0)); // quotient too big
        assert_eq!(div_u64_u32(5, 0), (u32::MAX, 0));
    }

    #[test]
    fn lerp_rounds_and_stays_between() {
        assert_eq!(lerp_i32(0, 10, 1, 4), 3); // 2.5 → 3
        assert_eq!(lerp_i32(10, 0, 1, 4), 7); // 7.5 → 7 (ties away from p)
        assert_eq!(lerp_i32(i32::MIN, i32::MAX, 1, 2), 0);
        assert_eq!(lerp_i32(i32::MAX, i32::MIN, 0, 7), i32::MAX);
        assert_eq!(lerp_i32(i32::MAX, i32::MIN, 7, 7), i32::MIN);
        let mut state = 0x1234_5678u32;
        for _ in 0..2000 {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let p = state as i32;
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let q = state as i32;
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let den = state | 1;
            let num = state.wrapping_mul(7) % den;
            let want = i64::from(p)
                + ((i128::from(q) - i128::from(p)) * i128::from(num) * 2 + i128::from(den))
                    .div_euclid(2 * i128::from(den)) as i64;
            let got = lerp_i32(p, q, num, den);
            // ties may round either way depending on the direction
            assert!(
                (i64::from(got) - want).abs() <= 1,
                "{p} {q} {num}/{den}: {got} {want}"
            );
            assert!(i64::from(got) >= i64::from(p.min(q)) && i64::from(got) <= i64::from(p.max(q)));
        }
    }
}
