//! The fast tier: Q2.14 values whose products stay within 32 bits.

use super::geo::{shift_u32, InvQuadratic16, RampParts};
use super::rsqrt::{rsqrt_q14_mantissa, split_u32};
use super::{round_shr, Geo16, Scalar};
use crate::num::Vec3;

/// The fast 32-bit tier: a Q2.14 fixed-point value, range [−2, 2), resolution 2⁻¹⁴.
///
/// Stored in an `i32` within the `i16` range, so a product fits 32 bits (one
/// `MULS` on a Cortex-M0, no library call per pixel). `NEWTON` (0–3) is the
/// Newton step count of the inverse square root of [`Scalar::normalize`] and
/// [`Scalar::geo_direction`]: relative error about 1.6·10⁻² with 0, 4·10⁻⁴
/// with 1, the Q14 resolution with 2. Every operation saturates to
/// [−2, 2 − 2⁻¹⁴].
///
/// ```
/// use fixshade::num::{Q14, Scalar};
/// let a = Q14::<2>::from_f32(0.75);
/// assert_eq!(a.mul(a).to_f32(), 0.5625);
/// assert_eq!(a.add(Q14::from_f32(1.5)), Q14::MAX); // saturates at ≈ 2
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Q14<const NEWTON: u8 = 2>(i32);

const FRAC: u32 = 14;
const RAW_MAX: i32 = i16::MAX as i32;
const RAW_MIN: i32 = i16::MIN as i32;

impl<const NEWTON: u8> Q14<NEWTON> {
    /// The value `raw · 2⁻¹⁴`, saturated to the tier's range.
    #[inline(always)]
    pub const fn from_raw(raw: i32) -> Self {
        Self(clamp_raw(raw))
    }

    /// The raw Q2.14 integer (always within `i16` range).
    #[inline(always)]
    pub const fn raw(self) -> i32 {
        self.0
    }

    /// `v / |v|`, for a squared length in [¼, 4) by one comparison (no CLZ on a
    /// Cortex-M0), a seed lookup and `NEWTON` steps; other lengths take the
    /// general path, so the result equals [`Scalar::normalize`]'s for every input.
    #[inline(always)]
    pub fn normalize_near_unit(v: Vec3<Self>) -> Vec3<Self> {
        // |v|² in Q28: each square ≤ 2^30 fits an i32, their sum (< 3·2^30) only a u32
        // (summed as i32 it overflows for components near ±2, i.e. |v| above ≈ 2.8)
        let s = (v.x.0 * v.x.0) as u32 + (v.y.0 * v.y.0) as u32 + (v.z.0 * v.z.0) as u32;
        if !(1 << 26..1 << 30).contains(&s) {
            return Self::normalize(v);
        }
        // split |v|² = t·2^-16·2^(4−k) with k = 2 or 4 (see `normalize`)
        let (t, sh) = if s >= 1 << 28 {
            (s >> 14, 15)
        } else {
            (s >> 12, 14)
        };
        let y = rsqrt_q14_mantissa(t, NEWTON) as i32;
        Self::scale_unit(v, y, sh)
    }

    #[inline(always)]
    fn scale_unit(v: Vec3<Self>, y: i32, shift: u32) -> Vec3<Self> {
        let r = 1i32 << (shift - 1);
        Vec3::new(
            Self::from_raw((v.x.0 * y + r) >> shift),
            Self::from_raw((v.y.0 * y + r) >> shift),
            Self::from_raw((v.z.0 * y + r) >> shift),
        )
    }
}

impl<const A: u8> Vec3<Q14<A>> {
    /// The same raw values in a tier with another Newton step count.
    #[inline(always)]
    fn map_tier<const B: u8>(self) -> Vec3<Q14<B>> {
        Vec3::new(Q14(self.x.0), Q14(self.y.0), Q14(self.z.0))
    }
}

/// `a·b` in Q27 (unrounded but for the halving): each product is at most 2^30 in
/// magnitude, so three halved ones fit an `i32`.
#[inline(always)]
fn dot27<const N: u8>(a: Vec3<Q14<N>>, b: Vec3<Q14<N>>) -> i32 {
    ((a.x.0 * b.x.0) >> 1) + ((a.y.0 * b.y.0) >> 1) + ((a.z.0 * b.z.0) >> 1)
}

/// `|n|² − 1` in Q28 when it is within ±2^23 (`| |N|² − 1 | < 2⁻⁵`), else 0 (no
/// length correction).
#[inline(always)]
fn len2_dev<const N: u8>(n: Vec3<Q14<N>>) -> i32 {
    // each square ≤ 2^30, the sum < 3·2^30 fits a u32
    let s = (n.x.0 * n.x.0) as u32 + (n.y.0 * n.y.0) as u32 + (n.z.0 * n.z.0) as u32;
    // e = s − 2^28 reinterpreted; within the window iff e + 2^23 < 2^24 (unsigned):
    // one addition and one comparison
    let e = s.wrapping_sub(1 << 28);
    if e.wrapping_add(1 << 23) < 1 << 24 {
        e as i32
    } else {
        0
    }
}

#[inline(always)]
const fn clamp_raw(raw: i32) -> i32 {
    if raw > RAW_MAX {
        RAW_MAX
    } else if raw < RAW_MIN {
        RAW_MIN
    } else {
        raw
    }
}

/// `a + b·d + c·d²` in Q16.16 (saturated) for the Q16.16 distance `d` within
/// 32-bit products, as `geo_inv_quadratic` below describes; negative
/// distances count as 0.
#[inline(always)]
fn inv_quadratic_sum(k: &InvQuadratic16, d: Geo16) -> u32 {
    let d = d.to_bits().max(0) as u32;
    // z = 0..=30 for d > 0 (d < 2^31); z = 31 and dn = 0 for d = 0
    let z = d.leading_zeros().wrapping_sub(1) & 31;
    let dn = (d << z) >> 15;
    let z = z as i32;
    let b = shift_u32(k.m16[0] * dn, k.k16[0] - z);
    let c = shift_u32(k.m16[1] * ((dn * dn) >> 16), k.k16[1] - 2 * z);
    k.a16.saturating_add(b).saturating_add(c)
}

/// The linear fog ramp of the `Q14` tier (see [`Scalar::ramp`]): `f = 0` beyond the
/// raw distance `d0`, else `min(1, g0 + ((d0 − D) ≫ r)·mi ≫ sh)`, with `d0 − D`
/// shifted to 16 bits so that the product with the 16-bit mantissa `mi` of the slope
/// fits 32 bits, and `f = 1` without a product beyond `full`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RampQ14 {
    d0: i32,
    g0: i32,
    full: u32,
    r: u32,
    mi: u32,
    sh: u32,
}

impl<const NEWTON: u8> Scalar for Q14<NEWTON> {
    type Geo = Geo16;
    type Ramp = RampQ14;
    const ZERO: Self = Self(0);
    const ONE: Self = Self(1 << FRAC);
    const MAX: Self = Self(RAW_MAX);
    const FLOAT: bool = false;
    const NAME: &'static str = match NEWTON {
        0 => "Q14 (seed only)",
        1 => "Q14 (1 Newton)",
        2 => "Q14 (2 Newton)",
        _ => "Q14 (3+ Newton)",
    };

    #[inline]
    fn from_f32(v: f32) -> Self {
        // `as` saturates and maps NaN to 0.
        Self::from_raw(libm::roundf(v * (1 << FRAC) as f32) as i32)
    }
    #[inline]
    fn to_f32(self) -> f32 {
        self.0 as f32 / (1 << FRAC) as f32
    }
    #[inline(always)]
    fn add(self, rhs: Self) -> Self {
        Self::from_raw(self.0 + rhs.0)
    }
    #[inline(always)]
    fn sub(self, rhs: Self) -> Self {
        Self::from_raw(self.0 - rhs.0)
    }
    #[inline(always)]
    fn mul(self, rhs: Self) -> Self {
        // |a·b| ≤ 2^30: fits in i32.
        Self::from_raw((self.0 * rhs.0 + (1 << (FRAC - 1))) >> FRAC)
    }
    #[inline]
    fn div(self, rhs: Self) -> Self {
        if rhs.0 <= 0 {
            return if self.0 > 0 { Self::MAX } else { Self::ZERO };
        }
        Self::from_raw(((self.0 << FRAC) + rhs.0 / 2) / rhs.0)
    }
    #[inline]
    fn sqrt(self) -> Self {
        if self.0 <= 0 {
            return Self::ZERO;
        }
        // √x = x · (1/√x); x in Q14 is s = raw·2^14 in Q28.
        let (t, k) = split_u32((self.0 as u32) << FRAC);
        let y = rsqrt_q14_mantissa(t, NEWTON.max(2)) as i64;
        // x = s′·2^(4−k) (Q28 in 32 bits), 1/√x = y·2^((k−4)/2)
        Self::from_raw(round_shr(self.0 as i64 * y, 16 - k / 2) as i32)
    }
    #[inline(always)]
    fn dot3(a: Vec3<Self>, b: Vec3<Self>) -> Self {
        // |Σ| < 3·2^29 in Q27: rounded once to Q14, then saturated
        Self::from_raw((dot27(a, b) + (1 << 12)) >> 13)
    }
    #[inline(always)]
    fn twice_mul_sub(self, b: Self, c: Self) -> Self {
        // 2ab in Q14 is a·b / 2^13: |a·b| ≤ 2^30, the rounded quotient (≤ 2^17) minus c
        // fits an i32
        Self::from_raw(((self.0 * b.0 + (1 << 12)) >> 13) - c.0)
    }
    #[inline(always)]
    fn cos_normal(n: Vec3<Self>, u: Vec3<Self>) -> Self {
        let x = dot27(n, u);
        // N·U/(|N||U|) ≈ x·(1 − e/2), e = (|N|² − 1) + (|U|² − 1) in Q28 (|e| < 2^24),
        // |x| < 3·2^29: (x ≫ 12 < 2^18.6) times (e ≫ 12 < 2^12) stays below 2^31 and
        // is in units of 2^24 / 2^29 of x·e/2, hence ≫ 5. Truncations: below 2^-16 of x.
        let e = len2_dev(n) + len2_dev(u);
        let corr = ((x >> 12) * (e >> 12)) >> 5;
        Self::from_raw((x - corr + (1 << 12)) >> 13)
    }
    #[inline(always)]
    fn reflect_dot(n: Vec3<Self>, l: Vec3<Self>, v: Vec3<Self>) -> Self {
        // R̂·V̂ = (2(N·L)(N·V)/|N|² − L·V)/(|L||V|) with the dot products in Q27, unrounded
        let (a, b, c) = (dot27(n, l), dot27(n, v), dot27(l, v));
        const LIM: u32 = (1 << 27) + (1 << 24); // 1.125 in Q27
        let within = |x: i32| (x.unsigned_abs()) <= LIM;
        if !(within(a) && within(b) && within(c)) {
            return n.reflect(l).dot(v);
        }
        // P = a·b in Q28 = a·b / 2^26, by 13-bit halves: a = ah·2^13 + al (al ≥ 0).
        // |ah|, |bh| ≤ 2^14.2: ah·bh < 2^29, each cross product < 2^28; al·bl < 2^26
        // contributes below 2^-28 and is dropped.
        let (ah, al, bh, bl) = (a >> 13, a & 0x1FFF, b >> 13, b & 0x1FFF);
        let p = ah * bh + ((ah * bl + al * bh) >> 13);
        // 2P/|N|² ≈ 2P(1 − e), e = |N|² − 1 in Q28 (|e| < 2^23): (P ≫ 14 < 2^16) times
        // (e ≫ 9 < 2^14) is in units of 2^23 / 2^28 of P·e, doubled: ≫ 4.
        let corr = ((p >> 14) * (len2_dev(n) >> 9)) >> 4;
        // |2P| < 2^29.4, |2c| < 2^28.2: the sum y fits (|y| < 2^29.8, Q28)
        let y = 2 * p - corr - 2 * c;
        // y/(|L||V|) ≈ y·(1 − (eL + eV)/2): (y ≫ 14 < 2^15.8) times (e ≫ 10 < 2^14) is
        // in units of 2^24 / 2^29 of y·e/2, hence ≫ 5
        let e = len2_dev(l) + len2_dev(v);
        let x = y - (((y >> 14) * (e >> 10)) >> 5);
        Self::from_raw((x + (1 << 13)) >> 14)
    }
    #[inline]
    fn pow_frac(self, f: u16) -> Self {
        Self(super::pow::pow_frac_q14(self.0, f))
    }
    #[inline]
    fn to_unorm(self, bits: u32) -> u32 {
        // `max`/`min`, not `clamp`: its `min <= max` assertion can survive at opt-level s
        let x = self.0.max(0).min(1 << FRAC) as u32;
        let max = (1u32 << bits.max(1).min(16)) - 1;
        (x * max + (1 << (FRAC - 1))) >> FRAC
    }
    #[inline]
    fn normalize(v: Vec3<Self>) -> Vec3<Self> {
        // |v|² in Q28: each square ≤ 2^30, the sum < 2^32.
        let s = (v.x.0 * v.x.0) as u32 + (v.y.0 * v.y.0) as u32 + (v.z.0 * v.z.0) as u32;
        if s == 0 {
            return Vec3::new(Self::ZERO, Self::ZERO, Self::ZERO);
        }
        let (t, k) = split_u32(s);
        let y = rsqrt_q14_mantissa(t, NEWTON) as i32;
        // |v|² = s′·2^(4−k), 1/|v| = y·2^((k−4)/2): c/|v| = c·y ≫ (16 − k/2),
        // sh in 1..=16; |c| ≤ 2^15 and y ≤ 2^15, so c·y and the rounding fit
        // an i32 (no 64-bit multiply on a Cortex-M0)
        let sh = 16 - k / 2;
        let r = |c: i32| Self::from_raw((c * y + (1 << (sh - 1))) >> sh);
        Vec3::new(r(v.x.0), r(v.y.0), r(v.z.0))
    }

    #[inline(always)]
    fn normalize_interpolated(v: Vec3<Self>) -> Vec3<Self> {
        Self::normalize_near_unit(v)
    }
    const ATTR_FRAC: u32 = 26;
    #[inline(always)]
    fn to_attr(self) -> i32 {
        // |raw| ≤ 2^15: raw·2^12 fits
        self.0 << 12
    }
    #[inline(always)]
    fn from_attr(a: i32) -> Self {
        // round(a / 2^12) without overflow for any a
        Self::from_raw(((a >> 11) + 1) >> 1)
    }

    #[inline]
    fn normalize_precise(v: Vec3<Self>) -> Vec3<Self> {
        Q14::<3>::normalize(Vec3::new(Q14(v.x.0), Q14(v.y.0), Q14(v.z.0))).map_tier()
    }

    /// The exact direction in `f32` (`v`'s components are exact), then of the
    /// eight floor/ceiling combinations of its Q14 components the one whose
    /// squared length is nearest to `2^28` (32-bit integer squares).
    fn normalize_nearest_unit(v: Vec3<Self>) -> Vec3<Self> {
        let s = [v.x.0, v.y.0, v.z.0].map(|c| c as f32);
        let len2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
        if !(len2 > 0.0) {
            return Self::normalize_precise(v);
        }
        let k = 16384.0 / libm::sqrtf(len2);
        let fl = s.map(|c| libm::floorf(c * k) as i32);
        let mut best = (u32::MAX, [0i32; 3]);
        for m in 0..8 {
            let c: [i32; 3] =
                core::array::from_fn(|i| (fl[i] + ((m >> i) & 1)).clamp(-16384, 16384));
            // each square ≤ 2^28: the sum fits a u32
            let l2: u32 = c.iter().map(|&x| (x * x) as u32).sum();
            let e = l2.abs_diff(1 << 28);
            if e < best.0 {
                best = (e, c);
            }
        }
        let c = best.1;
        Vec3::new(Self(c[0]), Self(c[1]), Self(c[2]))
    }

    geo16_ops!();
    #[inline]
    fn geo_to_unit(g: Geo16) -> Self {
        Self((g.to_bits().max(0).min(1 << 16) + 2) >> 2)
    }

    /// Within 32-bit products: the distance `D` (Q16.16) is normalised to 16 bits,
    /// `Dn = (D ≪ z) ≫ 15` with `z` its leading zeros less one (`d = Dn·2^(−1−z)`), each
    /// term is one product of 16-bit values (`mb·Dn`, `mc·(Dn² ≫ 16)`) shifted by its
    /// exponent into Q16.16 (rounded, saturated), the sum is saturated and inverted by
    /// one 32-bit division. The 16-bit mantissas and truncations leave a relative
    /// error below 2⁻¹³ in `a + b·d + c·d²` (0.03 LSB of 8-bit output); `a` in
    /// Q16.16 adds 2⁻¹⁷ absolute, 2⁻¹⁶ relative where the factor is below 2.
    #[inline]
    fn geo_inv_quadratic(k: &InvQuadratic16, d: Geo16) -> Self {
        let q = inv_quadratic_sum(k, d);
        if q <= 1 << 15 {
            // a + b·d + c·d² ≤ ½: the factor is at least 2, beyond the range
            return Self::MAX;
        }
        // 1/q in Q14 = 2^30 / q (Q16.16), rounded: below 2^15
        Self::from_raw((((1u32 << 30) + (q >> 1)) / q) as i32)
    }

    /// As [`Scalar::geo_inv_quadratic`]; beyond the range, `q = a + b·d + c·d²`
    /// (Q16.16, in `[1, 2^15]`) is shifted to `q' = q·2^s` in `[2^15, 2^16)` and
    /// the factor is `(2^30/q')·2^s` (the same 32-bit division).
    #[inline]
    fn geo_inv_quadratic_exp(k: &InvQuadratic16, d: Geo16) -> (Self, u32) {
        let q = inv_quadratic_sum(k, d);
        if q > 1 << 15 {
            return (Self::from_raw((((1u32 << 30) + (q >> 1)) / q) as i32), 0);
        }
        if q == 0 {
            return (Self::ONE, u32::MAX);
        }
        // q ≤ 2^15: 16 ≤ leading zeros ≤ 31
        let s = q.leading_zeros() - 16;
        let q = q << s;
        // 2^30/q' in [2^14, 2^15]
        let m = ((1u32 << 30) + (q >> 1)) / q;
        if m >= 1 << 15 {
            (Self::ONE, s + 1)
        } else {
            (Self::from_raw(m as i32), s)
        }
    }

    /// A saturating shift of the raw value.
    #[inline]
    fn mul_pow2(self, e: u32) -> Self {
        if e == 0 || self.0 == 0 {
            self
        } else if e >= 16 {
            if self.0 > 0 {
                Self::MAX
            } else {
                Self(RAW_MIN)
            }
        } else {
            // |raw| ≤ 2^15, e ≤ 15: the shift stays below 2^30
            Self(clamp_raw(self.0 << e))
        }
    }

    fn ramp(start: f32, end: f32) -> RampQ14 {
        let p = RampParts::new(start, end);
        // (full ≫ r) < 2^16
        let r = (32 - p.full.leading_zeros()).saturating_sub(16);
        // one unit of (d0 − D) ≫ r is 2^(r − re − 2)/rm in Q14; 1/rm ∈ (1, 2]:
        // mi = 2^15/rm, rounded, in [2^15, 2^16), and sh = 17 + re − r
        let mut mi = libm::roundf(32768.0 / p.rm) as u32;
        let mut sh = 17 + p.re - r as i32;
        if mi >= 1 << 16 {
            mi >>= 1;
            sh -= 1;
        }
        // sh < 0 only when one raw unit already fills the ramp (full = 0, Y = 0)
        if !(0..=63).contains(&sh) || p.g0 >= 1.0 {
            (mi, sh) = (0, 0);
        }
        RampQ14 {
            d0: p.d0,
            g0: libm::roundf(p.g0 * 16384.0) as i32,
            full: p.full,
            r,
            mi,
            sh: sh as u32,
        }
    }

    #[inline]
    fn ramp_at(r: &RampQ14, d: Geo16) -> Self {
        let d = d.to_bits();
        if d > r.d0 {
            return Self::ZERO;
        }
        // d0 − d, exact: 0 ≤ d0 − d < 2^32
        let y = (r.d0 as u32).wrapping_sub(d as u32);
        if y > r.full {
            return Self::ONE;
        }
        // (y ≫ r) ≤ 2^16 and mi < 2^16: the product fits
        let p = shift_u32(shift_u32(y, -(r.r as i32)) * r.mi, -(r.sh as i32));
        Self::from_raw((r.g0 + p.min(1 << 15) as i32).min(1 << FRAC))
    }
    #[inline]
    fn geo_recip(g: Geo16) -> Self {
        let d = g.to_bits();
        if d <= 0 {
            return Self::MAX;
        }
        // 1/g in Q14 = 2^30 / raw(Q16)
        Self::from_raw(((1u32 << 30) / d as u32).min(RAW_MAX as u32) as i32)
    }
    #[inline]
    fn geo_direction(v: Vec3<Geo16>) -> (Vec3<Self>, Geo16) {
        let (u, len) = geo16_direction(v, 2);
        (
            Vec3::new(
                Self::from_raw(round_shr(u.x as i64, 16) as i32),
                Self::from_raw(round_shr(u.y as i64, 16) as i32),
                Self::from_raw(round_shr(u.z as i64, 16) as i32),
            ),
            len,
        )
    }
}

/// The geometry operations of the tiers whose geometry type is [`Geo16`]:
/// saturating Q16.16 arithmetic, Q16.16 attributes (inside an `impl Scalar`).
macro_rules! geo16_ops {
    () => {
        #[inline(always)]
        fn geo_to_attr(g: Geo16) -> i32 {
            g.to_bits()
        }
        #[inline(always)]
        fn geo_from_attr(a: i32) -> Geo16 {
            Geo16::from_bits(a)
        }
        #[inline]
        fn geo_from_f32(v: f32) -> Geo16 {
            $crate::num::q14::geo16_from_f32(v)
        }
        #[inline]
        fn geo_to_f32(g: Geo16) -> f32 {
            g.to_num::<f32>()
        }
        #[inline(always)]
        fn geo_add(a: Geo16, b: Geo16) -> Geo16 {
            a.saturating_add(b)
        }
        #[inline(always)]
        fn geo_sub(a: Geo16, b: Geo16) -> Geo16 {
            a.saturating_sub(b)
        }
        #[inline(always)]
        fn geo_mul(a: Geo16, b: Geo16) -> Geo16 {
            a.saturating_mul(b)
        }
    };
}
pub(crate) use geo16_ops;

/// Converts `f32` to [`Geo16`]: NaN → 0, saturating.
#[inline]
pub(crate) fn geo16_from_f32(v: f32) -> Geo16 {
    // `as` saturates and maps NaN to 0.
    Geo16::from_bits(libm::roundf(v * 65536.0) as i32)
}

/// Direction (components in Q30, i.e. unit = 2^30) and length of a Q16.16 vector.
/// Uses 64-bit arithmetic (a per-light, not a per-channel cost).
#[inline]
pub(crate) fn geo16_direction(v: Vec3<Geo16>, newton: u8) -> (Vec3<i32>, Geo16) {
    let (x, y, z) = (
        v.x.to_bits() as i64,
        v.y.to_bits() as i64,
        v.z.to_bits() as i64,
    );
    // |v|² in Q32 units: each square ≤ 2^62, sum < 2^64.
    let s = (x * x) as u64 + (y * y) as u64 + (z * z) as u64;
    if s == 0 {
        return (Vec3::new(0, 0, 0), Geo16::ZERO);
    }
    let (t, k) = super::rsqrt::split_u64(s);
    let r = super::rsqrt::rsqrt_q30_mantissa(t, newton) as i64; // Q30
                                                                // |v|² (raw) = s′·2^(64−k): 1/|v|raw = r·2^(−30)·2^((k−64)/2)
                                                                // unit component (Q30) = c·r·2^((k−64)/2) = c·r ≫ (32 − k/2)
    let sh = 32 - k / 2;
    let unit = |c: i64| round_shr(c * r, sh).max(-(1 << 30)).min(1 << 30) as i32;
    // |v| (raw Q16) = √s′·2^(32−k/2); √s′ = s′·r (Q30)
    let sqrt_sp = ((t as u64 * r as u64) >> 32) as i64; // Q30
    let len_raw = if k / 2 >= 2 {
        round_shr(sqrt_sp, k / 2 - 2)
    } else {
        sqrt_sp << (2 - k / 2)
    };
    (
        Vec3::new(unit(x), unit(y), unit(z)),
        Geo16::from_bits(len_raw.min(i32::MAX as i64) as i32),
    )
}
