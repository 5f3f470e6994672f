//! Distance functions in the geometry types: the coefficients of the attenuation
//! `1/(a + b·d + c·d²)` and the linear fog ramp `clamp((end − d)/(end − start))`,
//! stored so that every legal `f32` parameter keeps its relative precision.
//!
//! The fixed tiers' distances are Q16.16 ([`Geo16`]), but `c = 10⁻⁶` or a fog
//! range of 10⁵ has no useful Q16.16 value: the coefficients keep their `f32`
//! mantissa and exponent, and products with the distance are formed in
//! floating-point-like integers (`Q14`/`Q30::geo_inv_quadratic`).

use super::Geo16;
use core::fmt::Debug;

/// A geometry scalar ([`Scalar::Geo`](super::Scalar::Geo)): [`Geo16`] or `f32`;
/// it decides how distance coefficients are stored. Sealed: only the bound of
/// `Scalar::Geo`.
pub trait GeoScalar: Copy + Debug + PartialEq + Default + Send + Sync + 'static {
    /// The coefficients of `1/(a + b·d + c·d²)`, in the form the tiers evaluate.
    type InvQuadratic: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// Stores `a, b, c` (finite and non-negative: validated by the caller).
    fn inv_quadratic(a: f32, b: f32, c: f32) -> Self::InvQuadratic;
}

impl GeoScalar for f32 {
    /// `[a, b, c]` as given.
    type InvQuadratic = [f32; 3];
    fn inv_quadratic(a: f32, b: f32, c: f32) -> [f32; 3] {
        [a, b, c]
    }
}

impl GeoScalar for Geo16 {
    type InvQuadratic = InvQuadratic16;
    fn inv_quadratic(a: f32, b: f32, c: f32) -> InvQuadratic16 {
        InvQuadratic16::new(a, b, c)
    }
}

/// `x = m·2^e` with `m` in [2^23, 2^24) (or `m = 0` for zero): exact for every
/// finite non-negative `f32`, subnormals included.
pub(crate) fn split_f32(x: f32) -> (u32, i32) {
    let bits = x.to_bits() & 0x7FFF_FFFF;
    let exp = (bits >> 23) as i32;
    let frac = bits & 0x7F_FFFF;
    if exp == 0 {
        if frac == 0 {
            return (0, 0);
        }
        // subnormal: frac·2^-149 with frac < 2^23
        let sh = frac.leading_zeros() - 8;
        (frac << sh, -149 - sh as i32)
    } else {
        (frac | 0x80_0000, exp - 150)
    }
}

/// `shift_u32` and `shift_u64`: `p·2^s`, rounded to nearest and saturated to the
/// unsigned type.
macro_rules! shift_uint {
    ($name:ident, $t:ty) => {
        #[doc = concat!("`p·2^s`, rounded to nearest and saturated to `", stringify!($t), "`.")]
        #[inline(always)]
        pub(crate) fn $name(p: $t, s: i32) -> $t {
            if s >= 0 {
                if p == 0 {
                    0
                } else if s >= <$t>::BITS as i32 || p > <$t>::MAX >> s {
                    <$t>::MAX
                } else {
                    p << s
                }
            } else {
                let r = s.unsigned_abs();
                if r > <$t>::BITS {
                    0
                } else {
                    // ⌊p / 2^(r−1)⌋ then halve with rounding: no overflow for any p
                    let h = p >> (r - 1);
                    (h >> 1) + (h & 1)
                }
            }
        }
    };
}
shift_uint!(shift_u32, u32);
shift_uint!(shift_u64, u64);

/// The coefficients of the attenuation `1/(a + b·d + c·d²)` for Q16.16 distances.
///
/// Every coefficient kept exactly as a 24-bit mantissa and exponent (`Q30`),
/// rounded to a 16-bit mantissa for 32-bit products (`Q14`), the exponents
/// pre-offset by the evaluation's scales; `a` also in Q16.16 and Q32.32
/// (saturated: beyond 65536 the factor is zero anyway). Evaluation and error:
/// `Q14`/`Q30::geo_inv_quadratic`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InvQuadratic16 {
    /// `a` in Q16.16 and Q32.32, saturated.
    pub(crate) a16: u32,
    pub(crate) a32: u64,
    /// `b`, `c`: 16-bit mantissas (≤ 65535) and shifts for the Q14 evaluation.
    pub(crate) m16: [u32; 2],
    pub(crate) k16: [i32; 2],
    /// `b`, `c`: exact 24-bit mantissas and shifts for the Q30 evaluation.
    pub(crate) m24: [u32; 2],
    pub(crate) k30: [i32; 2],
}

impl InvQuadratic16 {
    fn new(a: f32, b: f32, c: f32) -> Self {
        let (ma, ea) = split_f32(a);
        let (mb, eb) = split_f32(b);
        let (mc, ec) = split_f32(c);
        // 16-bit mantissas, rounded (2^16 only for a mantissa within 2^-17 of the
        // next power of two: capped, 1.5·10⁻⁵ relative)
        let m16 = |m: u32| ((m + 128) >> 8).min(0xFFFF);
        Self {
            a16: shift_u32(ma, ea + 16),
            a32: shift_u64(ma as u64, ea + 32),
            // b·d (Q16.16) = m16·Dn·2^(e + 8 + 15 − z), c·d² = m16·(Dn²≫16)·2^(e + 8 + 30 − 2z):
            // see `Q14::geo_inv_quadratic`
            m16: [m16(mb), m16(mc)],
            k16: [eb + 23, ec + 38],
            // b·d (Q32.32) = m·Dn·2^(e + 16 − z), c·d² = m·(Dn²≫31)·2^(e + 31 − 2z)
            m24: [mb, mc],
            k30: [eb + 16, ec + 31],
        }
    }
}

/// The linear fog ramp `f(d) = clamp((end − d)/(end − start), 0, 1)` over Q16.16
/// distances, in a form that holds for any finite `start < end` (either may lie far
/// beyond the geometry range): with `D` the raw distance and `d0` the raw distance
/// at (or, for `end` beyond the range, the end of the range below) `end`,
///
/// - `f = 0` for `D > d0` (beyond the end of the fog),
/// - `f = min(1, g0 + (d0 − D)·inv)` otherwise, `inv` per raw unit; `full` is the
///   largest `d0 − D` with `f < 1`, beyond which `f = 1` without a product.
///
/// The tiers store `g0` and `inv` at their precision (`Q14`: `inv` as a 16-bit
/// mantissa after shifting `d0 − D` right by `r`; `Q30`: a 32-bit mantissa).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RampParts {
    pub d0: i32,
    /// `f(d0)` in [0, 1]; 1 means full fog up to `d0`.
    pub g0: f32,
    pub full: u32,
    /// `1/(end − start) = 2^-re/rm` scene units, `rm ∈ [0.5, 1)`.
    pub rm: f32,
    pub re: i32,
}

impl RampParts {
    /// `start < end`, both finite (validated by the caller).
    pub fn new(start: f32, end: f32) -> Self {
        // the range R = rm·2^re; end − start overflows for a range beyond f32::MAX
        let r = end - start;
        let (rm, re) = if r.is_finite() {
            libm::frexpf(r)
        } else {
            let (m, e) = libm::frexpf(end * 0.5 - start * 0.5);
            (m, e + 1)
        };
        // f per raw unit (2^-16 scene units) = 2^(−re−16)/rm; f·(x raw units) below
        let per_raw = |x: f32| libm::ldexpf(x / rm, -re - 16);
        let e16 = end * 65536.0; // exact, or ±infinity
        let (d0, g0) = if e16 >= 2_147_483_648.0 {
            // end beyond the range: d0 = (2^31 − 1) raw, f(d0) = (end − d0)/R
            let beyond = if r.is_finite() {
                (end - 32768.0) / r
            } else {
                (end * 0.5 - 16384.0) / (end * 0.5 - start * 0.5)
            };
            (i32::MAX, beyond + per_raw(1.0))
        } else if e16 < -2_147_483_648.0 {
            // the fog ends before the range starts: f = 0 everywhere
            (i32::MIN, 0.0)
        } else {
            // d0 = ⌊end⌋ in raw units; the fraction below one raw unit is exact
            let fl = libm::floorf(e16);
            (fl as i32, per_raw(e16 - fl))
        };
        // full: the largest Y with g0 + Y·inv < 1, ⌈(1 − g0)·R·2^16⌉ − 1, saturated
        let (g0, full) = if g0 < 1.0 {
            let y = libm::ldexpf((1.0 - g0) * rm, re + 16);
            (g0, (libm::ceilf(y) - 1.0) as u32)
        } else {
            (1.0, u32::MAX)
        };
        Self {
            d0,
            g0,
            full,
            rm,
            re,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lighting::Attenuation;
    use crate::num::{Scalar, Q14, Q30};

    #[test]
    fn split_is_exact() {
        for x in [
            0.0f32,
            1.0e-45,
            1.1e-38,
            f32::MIN_POSITIVE,
            1.0e-6,
            2.0e-5,
            0.3,
            1.0,
            12345.678,
            3.0e38,
            f32::MAX,
        ] {
            let (m, e) = split_f32(x);
            assert!(m == 0 || (1 << 23..1 << 24).contains(&m), "{x}");
            assert_eq!(m as f64 * libm::pow(2.0, e as f64), x as f64, "{x}");
        }
    }

    #[test]
    fn shifts_round_and_saturate() {
        assert_eq!(shift_u32(3, 1), 6);
        assert_eq!(shift_u32(3, -1), 2); // 1.5 → 2
        assert_eq!(shift_u32(5, -2), 1); // 1.25 → 1
        assert_eq!(shift_u32(u32::MAX, -1), 1 << 31);
        assert_eq!(shift_u32(1 << 31, -32), 1);
        assert_eq!(shift_u32(1 << 30, -32), 0);
        assert_eq!(shift_u32(u32::MAX, -33), 0);
        assert_eq!(shift_u32(2, 31), u32::MAX);
        assert_eq!(shift_u32(1, 31), 1 << 31);
        assert_eq!(shift_u32(1, 200), u32::MAX);
        assert_eq!(shift_u32(0, 200), 0);
        assert_eq!(shift_u64(u64::MAX, -1), 1 << 63);
        assert_eq!(shift_u64(1, 64), u64::MAX);
        assert_eq!(shift_u64(1 << 63, -64), 1);
        assert_eq!(shift_u64(7, -300), 0);
    }

    /// Tiny coefficients: every decade from 10⁻⁴⁵ (a subnormal) to 10⁻³, and
    /// the smallest normal `f32` (as `tests/attenuation_unbounded.rs` sweeps).
    fn tiny() -> std::vec::Vec<f32> {
        let mut v: std::vec::Vec<f32> = (3..=45).map(|k| 10f32.powi(-k)).collect();
        v.extend([f32::MIN_POSITIVE, 1.0e-45, 3.0e-3, 0.3]);
        v.retain(|&x| x > 0.0);
        v
    }

    /// `geo_inv_quadratic_exp` beyond the range: `m·2^e` against the exact
    /// `1/(a + b·d + c·d²)` over coefficients from 10⁻⁴⁵ to 10³⁸ and every binade of
    /// the distance, within the tier's relative accuracy (`Q14` 2⁻¹³ plus the
    /// quantisation of the sum in Q16.16, `Q30` 10⁻⁶ plus Q32.32), and `mul_pow2`
    /// saturating.
    #[test]
    fn factor_beyond_the_range() {
        fn tier<S: Scalar<Geo = Geo16>>(rel: f64, q_unit: f64, round: f64) {
            let mut cs = tiny();
            cs.extend([0.0, 1.0, 7.5, 1.0e6, 1.0e38]);
            let mut checked = 0;
            for &b in &cs {
                for &c in &cs {
                    let Ok(att) = Attenuation::new::<S>(0.0, b, c) else {
                        continue;
                    };
                    let _ = att;
                    let k = Geo16::inv_quadratic(0.0, b, c);
                    for bits in (0..31).map(|k| 1i32 << k).chain([3, 5, 1000, i32::MAX]) {
                        let d = Geo16::from_bits(bits);
                        let (m, e) = S::geo_inv_quadratic_exp(&k, d);
                        let dd = f64::from(bits) / 65536.0;
                        let q = f64::from(b) * dd + f64::from(c) * dd * dd;
                        let m = f64::from(m.to_f32());
                        if e == 0 {
                            assert!(m <= 2.0, "{} {m}", S::NAME);
                        } else {
                            assert!((1.0..=2.0).contains(&m), "{} {m}", S::NAME);
                        }
                        if e == u32::MAX {
                            // the sum rounds to 0: below one unit of its fixed point
                            assert!(q < q_unit, "{} b={b:e} c={c:e} d={dd}: q={q:e}", S::NAME);
                            continue;
                        }
                        let got = m * 2f64.powi(e as i32);
                        // the sum is formed in fixed point (each term rounded to
                        // `q_unit`: one unit for both) with the tier's relative
                        // error, then inverted with `m` rounded
                        let dq = q_unit + q * rel;
                        let (lo, hi) = (1.0 / (q + dq), 1.0 / (q - dq).max(q_unit / 2.0));
                        let slack = 2f64.powi(e as i32) * round;
                        assert!(
                            got >= lo - slack && got <= hi + slack,
                            "{}: b={b:e} c={c:e} d={dd}: {got:e} vs 1/q = {:e}",
                            S::NAME,
                            1.0 / q
                        );
                        checked += 1;
                    }
                }
            }
            assert!(checked > 10_000, "{checked}");
            // saturating powers of two
            for (v, e) in [
                (0.75f32, 1u32),
                (0.75, 2),
                (-0.75, 2),
                (1.0e-4, 40),
                (0.0, 200),
            ] {
                let x = S::from_f32(v).mul_pow2(e);
                let want = (f64::from(v) * 2f64.powi(e as i32)).clamp(-2.0, 2.0);
                let max = f64::from(S::MAX.to_f32());
                assert!(
                    (f64::from(x.to_f32()) - want.clamp(-max - 1e-9, max)).abs() < 1.0e-3,
                    "{} {v}·2^{e}: {}",
                    S::NAME,
                    x.to_f32()
                );
            }
            assert_eq!(S::from_f32(1.0e-4).mul_pow2(u32::MAX), S::MAX);
        }
        tier::<Q14<2>>(1.0 / 8192.0, 1.0 / 65536.0, 1.0 / 32768.0);
        tier::<Q30<3>>(1.0e-6, 1.0 / 4294967296.0, 1.0e-9);
    }
}
