//! Reciprocals in integer arithmetic: a 256-entry seed table and one Newton
//! step, 32-bit products only (no division instruction, no library divide on
//! a Cortex-M0).
//!
//! Relative error of [`recip16`] below 2^−15 for every input (the unit test
//! checks all of them).

/// `2^31 / ((256 + i)·128 + 64)` rounded: the reciprocal seed of `q` in
/// `[2^15, 2^16)` by its top 9 bits (relative error below 2^−9).
const SEED: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let d = ((256 + i as u64) << 7) + 64;
        t[i] = (((1u64 << 31) + d / 2) / d) as u16;
        i += 1;
    }
    t
};

/// `≈ 2^31 / q` for `q` in `[2^15, 2^16)` (a result in `(2^15, 2^16]`): the
/// seed and one Newton step.
#[inline(always)]
pub(crate) fn recip16(q: u32) -> u32 {
    let i = ((q >> 7).wrapping_sub(256) as usize).min(255);
    let r0 = u32::from(SEED[i]);
    // q·r0 ≈ 2^31 within 2^22; d·r0/2^31 is the Newton correction
    let d = (1u32 << 31).wrapping_sub(q.wrapping_mul(r0)) as i32;
    (r0 as i32).wrapping_add(((d >> 8).wrapping_mul(r0 as i32).wrapping_add(1 << 22)) >> 23) as u32
}

/// `⌊2^31 / q⌋` for `q` in `[2^15, 2^16)` (a result in `(2^15, 2^16]`):
/// [`recip16`] (within 2 of it) and two correction steps each way, exact
/// where a library division would be (the unit test checks every input).
#[inline(always)]
pub(crate) fn recip16_floor(q: u32) -> u32 {
    let one = 1u32 << 31;
    let mut r = recip16(q);
    // q < 2^16 and r ≤ 2^16 + 2: q·r < 2^32
    for _ in 0..2 {
        if q.wrapping_mul(r) > one {
            r -= 1;
        }
    }
    for _ in 0..2 {
        if one - q.wrapping_mul(r) >= q {
            r += 1;
        }
    }
    r
}

/// `⌊2^31 / q⌋` for `q` in `[2^15, 2^16)` (others clamped into it on ARMv6-M,
/// to 1 elsewhere), the same on every target: [`recip16_floor`] on ARMv6-M (a
/// library division costs about a hundred instructions), else the division
/// (one instruction on a Cortex-M4 or an RV32IMC).
#[inline(always)]
pub(crate) fn div_2p31(q: u32) -> u32 {
    // ARMv6-M, told apart on stable Rust by its lack of 32-bit atomics (the
    // Arm target features are not stable in `cfg`)
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        recip16_floor(q.clamp(1 << 15, (1 << 16) - 1))
    } else {
        (1u32 << 31) / q.max(1)
    }
}

/// `⌊2^16 / n⌋` for `n` in `0..=8` (0 for 0).
const SMALL: [u32; 9] = [0, 65536, 32768, 21845, 16384, 13107, 10922, 9362, 8192];

/// `d / n` rounded toward zero for `1 ≤ n ≤ 8` (0 for `n = 0`, `n` above 8
/// taken as 8), by `⌊2^16 / n⌋` in two 16-bit halves of `|d|`: 32-bit
/// products, no division; never larger in magnitude than the exact quotient,
/// smaller by less than `|d|·2^−16 + 1`.
#[inline(always)]
pub(crate) fn div_small(d: i32, n: u32) -> i32 {
    let r = SMALL.get(n as usize).copied().unwrap_or(8192);
    let m = d.unsigned_abs();
    // (m >> 16)·r ≤ 2^15·2^16 and (m & 0xFFFF)·r < 2^32
    let q = (m >> 16) * r + (((m & 0xFFFF) * r) >> 16);
    let q = q.min(i32::MAX as u32) as i32;
    if d < 0 {
        -q
    } else {
        q
    }
}

/// `(v·2^m, m)` with `v·2^m` in `[2^top, 2^(top + 1))` for `v ≥ 1` and
/// `15 ≤ top ≤ 30` (0 gives `(0, 0)`), without a count-leading-zeros call.
#[inline(always)]
pub(crate) fn normalise(v: u32, top: u32) -> (u32, i32) {
    if v == 0 {
        return (0, 0);
    }
    let top = top.clamp(15, 30);
    let mut v = v;
    let mut m = 0i32;
    while v >= 2 << top {
        v >>= 1;
        m -= 1;
    }
    let mut step = 16;
    while step > 0 {
        if v < 1 << (top + 1 - step) {
            v <<= step;
            m += step as i32;
        }
        step >>= 1;
    }
    (v, m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recip16_is_within_2_pow_minus_15() {
        for q in (1u32 << 15)..(1u32 << 16) {
            let r = f64::from(recip16(q));
            let want = 2f64.powi(31) / f64::from(q);
            assert!((r - want).abs() / want < 2f64.powi(-15), "{q}: {r} {want}");
        }
    }

    #[test]
    fn recip16_floor_is_the_quotient() {
        for q in (1u32 << 15)..(1u32 << 16) {
            assert_eq!(recip16_floor(q), (1u32 << 31) / q, "{q}");
            assert_eq!(div_2p31(q), (1u32 << 31) / q, "{q}");
        }
    }

    #[test]
    fn div_small_is_below_and_near_the_quotient() {
        let mut x = 0x1234_5678u32;
        for k in 0..200_000u32 {
            // an LCG with the extremes mixed in
            x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let d = match k % 50 {
                0 => i32::MAX,
                1 => i32::MIN + 1,
                2 => (k as i32) - 100,
                _ => x as i32 >> (k % 31),
            };
            for n in 1..=8u32 {
                let q = div_small(d, n);
                let exact = f64::from(d) / f64::from(n);
                assert!(f64::from(q).abs() <= exact.abs(), "{d} / {n} = {q}");
                let bound = f64::from(d).abs() * 2f64.powi(-16) + 1.0;
                assert!(exact.abs() - f64::from(q).abs() < bound, "{d} / {n} = {q}");
            }
        }
        assert_eq!(div_small(5, 0), 0);
    }

    #[test]
    fn normalise_hits_the_interval() {
        for v in [1u32, 2, 3, 255, 1 << 20, u32::MAX, 0x8000_0001] {
            for top in [15, 16, 28, 30] {
                let (n, m) = normalise(v, top);
                assert!((1 << top..2u64 << top).contains(&u64::from(n)), "{v} {top}");
                let back = if m >= 0 {
                    u64::from(v) << m
                } else {
                    u64::from(v) >> -m
                };
                assert_eq!(back, u64::from(n), "{v} {top}");
            }
        }
    }
}
