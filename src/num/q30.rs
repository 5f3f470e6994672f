//! The accurate fixed tier: Q2.30 values with 64-bit products.

use super::geo::{shift_u64, InvQuadratic16, RampParts};
use super::q14::{geo16_direction, geo16_ops};
use super::rsqrt::{rsqrt_q30_mantissa, split_u64};
use super::{round_shr, Geo16, Scalar};
use crate::num::Vec3;

/// The accurate fixed tier: a Q2.30 fixed-point value in an `i32`, range [−2, 2),
/// resolution 2⁻³⁰, every operation saturating to [−2, 2 − 2⁻³⁰].
///
/// Products are 32×32→64 bit (`__aeabi_lmul` on a Cortex-M0, `SMULL` on a
/// Cortex-M3/M4). `NEWTON` (0–4) is the inverse square root's Newton step count:
/// relative error about 1.6·10⁻² with 0, 4·10⁻⁴ with 1, 2·10⁻⁷ with 2 and
/// the Q30 resolution with 3.
///
/// ```
/// use fixshade::num::{Q30, Scalar};
/// let a = Q30::<3>::from_f32(0.1);
/// assert!((a.powi(4).to_f32() - 1.0e-4).abs() < 1.0e-9);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Q30<const NEWTON: u8 = 3>(i32);

const FRAC: u32 = 30;

impl<const NEWTON: u8> Q30<NEWTON> {
    /// The value `raw · 2⁻³⁰` (every `i32` is in range).
    #[inline(always)]
    pub const fn from_raw(raw: i32) -> Self {
        Self(raw)
    }

    /// The raw Q2.30 integer.
    #[inline(always)]
    pub const fn raw(self) -> i32 {
        self.0
    }

    #[inline(always)]
    fn from_wide(v: i64) -> Self {
        // `max`/`min`, not `clamp`: its `min <= max` assertion can survive at opt-level s
        Self(v.max(i32::MIN as i64).min(i32::MAX as i64) as i32)
    }
}

/// `a + b·d + c·d²` in Q32.32 (saturated) for the Q16.16 distance `d`, as
/// `geo_inv_quadratic` below describes; negative distances count as 0.
#[inline(always)]
fn inv_quadratic_sum(k: &InvQuadratic16, d: Geo16) -> u64 {
    let d = d.to_bits().max(0) as u32;
    let z = d.leading_zeros().wrapping_sub(1) & 31;
    let dn = (d << z) as u64; // [2^30, 2^31), or 0
    let z = z as i32;
    let b = shift_u64(k.m24[0] as u64 * dn, k.k30[0] - z);
    let d2 = (dn * dn + (1 << 30)) >> 31; // ≤ 2^31
    let c = shift_u64(k.m24[1] as u64 * d2, k.k30[1] - 2 * z);
    k.a32.saturating_add(b).saturating_add(c)
}

/// The linear fog ramp of the `Q30` tier (see [`Scalar::ramp`]): `f = 0` beyond the
/// raw distance `d0`, else `min(1, g0 + (d0 − D)·mi ≫ sh)` with a 64-bit product and
/// a 32-bit mantissa `mi` of the slope, and `f = 1` without a product beyond `full`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RampQ30 {
    d0: i32,
    g0: u32,
    full: u32,
    mi: u32,
    sh: u32,
}

impl<const NEWTON: u8> Scalar for Q30<NEWTON> {
    type Geo = Geo16;
    type Ramp = RampQ30;
    const ZERO: Self = Self(0);
    const ONE: Self = Self(1 << FRAC);
    const MAX: Self = Self(i32::MAX);
    const FLOAT: bool = false;
    const NAME: &'static str = match NEWTON {
        0 => "Q30 (seed only)",
        1 => "Q30 (1 Newton)",
        2 => "Q30 (2 Newton)",
        _ => "Q30 (3+ Newton)",
    };

    #[inline]
    fn from_f32(v: f32) -> Self {
        // v·2^30 is exact in f32 (a power of two only moves the exponent), so no
        // f64 is needed; `as` saturates and maps NaN to 0.
        Self::from_wide(libm::roundf(v * (1u64 << FRAC) as f32) as i64)
    }
    #[inline]
    fn to_f32(self) -> f32 {
        (self.0 as f64 / (1u64 << FRAC) as f64) as f32
    }
    #[inline(always)]
    fn add(self, rhs: Self) -> Self {
        Self(self.0.saturating_add(rhs.0))
    }
    #[inline(always)]
    fn sub(self, rhs: Self) -> Self {
        Self(self.0.saturating_sub(rhs.0))
    }
    #[inline(always)]
    fn mul(self, rhs: Self) -> Self {
        // |a·b| ≤ 2^62: fits in i64.
        Self::from_wide(round_shr(self.0 as i64 * rhs.0 as i64, FRAC))
    }
    #[inline(always)]
    fn twice_mul_sub(self, b: Self, c: Self) -> Self {
        // |a·b| ≤ 2^62: 2ab in Q30 is a·b / 2^29 (≤ 2^33), minus c
        Self::from_wide(round_shr(self.0 as i64 * b.0 as i64, FRAC - 1) - c.0 as i64)
    }
    #[inline]
    fn div(self, rhs: Self) -> Self {
        if rhs.0 <= 0 {
            return if self.0 > 0 { Self::MAX } else { Self::ZERO };
        }
        Self::from_wide(((self.0 as i64) << FRAC) / rhs.0 as i64)
    }
    #[inline]
    fn sqrt(self) -> Self {
        if self.0 <= 0 {
            return Self::ZERO;
        }
        // x in Q60 is s = raw·2^30; √x = x·(1/√x)
        let (t, k) = split_u64((self.0 as u64) << FRAC);
        let y = rsqrt_q30_mantissa(t, NEWTON.max(3)) as i64;
        // x = s′·2^(4−k), 1/√x = y·2^-30·2^((k−4)/2): raw·y ≫ (32 − k/2)
        Self::from_wide(round_shr(self.0 as i64 * y, 32 - k / 2))
    }
    #[inline]
    fn pow_frac(self, f: u16) -> Self {
        Self(super::pow::pow_frac_q30(self.0, f))
    }
    #[inline]
    fn to_unorm(self, bits: u32) -> u32 {
        let x = self.0.max(0).min(1 << FRAC) as u64;
        let max = (1u64 << bits.max(1).min(16)) - 1;
        ((x * max + (1 << (FRAC - 1))) >> FRAC) as u32
    }
    #[inline]
    fn normalize(v: Vec3<Self>) -> Vec3<Self> {
        let (x, y, z) = (v.x.0 as i64, v.y.0 as i64, v.z.0 as i64);
        // |v|² in Q60: each square ≤ 2^62, the sum < 2^64.
        let s = (x * x) as u64 + (y * y) as u64 + (z * z) as u64;
        if s == 0 {
            return Vec3::new(Self::ZERO, Self::ZERO, Self::ZERO);
        }
        let (t, k) = split_u64(s);
        let r = rsqrt_q30_mantissa(t, NEWTON) as i64;
        // |v|² = s′·2^(4−k), 1/|v| = r·2^-30·2^((k−4)/2): c/|v| = c·r ≫ (32 − k/2)
        let sh = 32 - k / 2;
        Vec3::new(
            Self::from_wide(round_shr(x * r, sh)),
            Self::from_wide(round_shr(y * r, sh)),
            Self::from_wide(round_shr(z * r, sh)),
        )
    }

    const ATTR_FRAC: u32 = 26;
    #[inline(always)]
    fn to_attr(self) -> i32 {
        // round(raw / 16)
        ((self.0 >> 3) + 1) >> 1
    }
    #[inline(always)]
    fn from_attr(a: i32) -> Self {
        Self::from_wide((a as i64) << 4)
    }

    #[inline]
    fn normalize_precise(v: Vec3<Self>) -> Vec3<Self> {
        let n = Q30::<3>::normalize(Vec3::new(Q30(v.x.0), Q30(v.y.0), Q30(v.z.0)));
        Vec3::new(Self(n.x.0), Self(n.y.0), Self(n.z.0))
    }

    geo16_ops!();

    /// In 64-bit arithmetic: the distance `D` (Q16.16) is normalised to 31 bits,
    /// `Dn = D ≪ z` (`d = Dn·2^(−16−z)`), the terms are the products of the exact
    /// 24-bit mantissas with `Dn` and `Dn² ≫ 31` shifted into Q32.32 (rounded,
    /// saturated), and the sum is inverted by one 64-bit division: relative error
    /// below 2⁻³⁰.
    #[inline]
    fn geo_inv_quadratic(k: &InvQuadratic16, d: Geo16) -> Self {
        let q = inv_quadratic_sum(k, d);
        if q <= 1 << 31 {
            return Self::MAX;
        }
        // 1/q in Q30 = 2^62 / q (Q32.32), rounded
        Self::from_wide((((1u64 << 62) + (q >> 1)) / q) as i64)
    }

    /// As [`Scalar::geo_inv_quadratic`]; beyond the range, `q = a + b·d + c·d²`
    /// (Q32.32, in `[1, 2^31]`) is shifted to `q' = q·2^s` in `[2^31, 2^32)` and
    /// the factor is `(2^62/q')·2^s` (the same 64-bit division).
    #[inline]
    fn geo_inv_quadratic_exp(k: &InvQuadratic16, d: Geo16) -> (Self, u32) {
        let q = inv_quadratic_sum(k, d);
        if q > 1 << 31 {
            return (Self::from_wide((((1u64 << 62) + (q >> 1)) / q) as i64), 0);
        }
        if q == 0 {
            return (Self::ONE, u32::MAX);
        }
        // q ≤ 2^31: 32 ≤ leading zeros ≤ 63
        let s = q.leading_zeros() - 32;
        let q = q << s;
        // 2^62/q' in [2^30, 2^31]
        let m = ((1u64 << 62) + (q >> 1)) / q;
        if m >= 1 << 31 {
            (Self::ONE, s + 1)
        } else {
            (Self(m as i32), s)
        }
    }

    /// A saturating shift of the raw value.
    #[inline]
    fn mul_pow2(self, e: u32) -> Self {
        let r = self.0;
        if e == 0 || r == 0 {
            self
        } else if e >= 31 || r.unsigned_abs() > (i32::MAX as u32) >> e {
            if r > 0 {
                Self::MAX
            } else {
                Self(i32::MIN)
            }
        } else {
            Self(r << e)
        }
    }

    fn ramp(start: f32, end: f32) -> RampQ30 {
        let p = RampParts::new(start, end);
        // one unit of d0 − D is 2^(14 − re)/rm in Q30: mi = 2^31/rm in [2^31, 2^32),
        // sh = 17 + re
        let mut mi = libm::roundf(2_147_483_648.0 / p.rm) as u64;
        let mut sh = 17 + p.re;
        if mi >= 1 << 32 {
            mi >>= 1;
            sh -= 1;
        }
        if !(0..=63).contains(&sh) || p.g0 >= 1.0 {
            (mi, sh) = (0, 0);
        }
        RampQ30 {
            d0: p.d0,
            g0: libm::roundf(p.g0 * 1_073_741_824.0) as u32,
            full: p.full,
            mi: mi as u32,
            sh: sh as u32,
        }
    }

    #[inline]
    fn ramp_at(r: &RampQ30, d: Geo16) -> Self {
        let d = d.to_bits();
        if d > r.d0 {
            return Self::ZERO;
        }
        let y = (r.d0 as u32).wrapping_sub(d as u32);
        if y > r.full {
            return Self::ONE;
        }
        // g0 ≤ 2^30 and p ≤ 2^30: the sum fits a u32
        let p = shift_u64(y as u64 * r.mi as u64, -(r.sh as i32)).min(1 << FRAC) as u32;
        Self((r.g0 + p).min(1 << FRAC) as i32)
    }
    #[inline]
    fn geo_to_unit(g: Geo16) -> Self {
        Self(g.to_bits().max(0).min(1 << 16) << 14)
    }
    #[inline]
    fn geo_recip(g: Geo16) -> Self {
        let d = g.to_bits();
        if d <= 0 {
            return Self::MAX;
        }
        // 1/g in Q30 = 2^46 / raw(Q16)
        Self::from_wide((((1u64 << 46) + d as u64 / 2) / d as u64) as i64)
    }
    #[inline]
    fn geo_direction(v: Vec3<Geo16>) -> (Vec3<Self>, Geo16) {
        let (u, len) = geo16_direction(v, NEWTON.max(3));
        (Vec3::new(Self(u.x), Self(u.y), Self(u.z)), len)
    }
}
