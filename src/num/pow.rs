//! Real exponents: `x^e` for `x` in [0, 1] and any `e` in 0..=65535, with the
//! fraction of `e` evaluated only where there is one.
//!
//! `x^e = x^⌊e⌋ · x^f`: the integer part by [`Scalar::powi`], the fraction `f`
//! (in 2⁻¹⁶ units) as `2^(f·log₂ x)` from two interpolated tables; an integer
//! exponent costs one comparison more than [`Scalar::powi`].
//!
//! Quantising `f` to 2⁻¹⁶ moves `x^e` by at most `2⁻¹⁶·x^e·|ln x|`, which is below
//! `2⁻¹⁶/(e·e_)` (`e_` = 2.718…) for `e ≥ 1`: 8·10⁻⁷ at `e = 12.8`, 1.4·10⁻⁵ below
//! `e = 1` (0.004 of an 8-bit step).

use super::wide::{div_u64_u32, mul_u32};
use super::Scalar;
use crate::error::{finite, ParamError};

/// A real exponent `e` in 0..=65535 (OpenGL's `GL_SHININESS` and
/// `GL_SPOT_EXPONENT` are 0..=128): an integer part and a fraction in 2⁻¹⁶ units.
///
/// ```
/// use fixshade::num::{Exponent, Scalar, Q14};
/// let e = Exponent::new("shininess", 12.8).unwrap();
/// assert_eq!(e.integer_part(), 12);
/// assert!(!e.is_integer());
/// assert!((e.to_f32() - 12.8).abs() < 1.0e-5);
/// let x = Q14::<2>::from_f32(0.9);
/// assert!((x.pow(e).to_f32() - 0.9f32.powf(12.8)).abs() < 2.0e-4);
/// assert!(Exponent::new("shininess", -1.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Exponent {
    int: u16,
    /// `f·2^16`, `f` in [0, 1).
    frac: u16,
}

impl Exponent {
    /// The exponent 0 (`x^0 = 1`).
    pub const ZERO: Self = Self { int: 0, frac: 0 };

    /// An integer exponent.
    pub const fn integer(n: u16) -> Self {
        Self { int: n, frac: 0 }
    }

    /// Validates an exponent given as `f32` (`name` is reported in the error): finite
    /// and in 0..=65535; the fraction is rounded to 2⁻¹⁶.
    pub fn new(name: &'static str, e: f32) -> Result<Self, ParamError> {
        let e = finite(name, e)?;
        if !(0.0..=65535.0).contains(&e) {
            return Err(ParamError::ExponentOutOfRange(name));
        }
        // e < 2^16 and f32 has 24 bits: e·2^16 is exact as f64 and fits u32
        let units = libm::round(f64::from(e) * 65536.0) as u32;
        let units = units.min(65535 << 16);
        Ok(Self {
            int: (units >> 16) as u16,
            frac: (units & 0xFFFF) as u16,
        })
    }

    /// `⌊e⌋`.
    pub const fn integer_part(self) -> u16 {
        self.int
    }

    /// The fraction `e − ⌊e⌋` in 2⁻¹⁶ units.
    pub const fn fraction(self) -> u16 {
        self.frac
    }

    /// `e·2^16`.
    const fn units(self) -> u32 {
        ((self.int as u32) << 16) | self.frac as u32
    }

    /// Whether `e` is an integer (then `x^e` is [`Scalar::powi`]).
    pub const fn is_integer(self) -> bool {
        self.frac == 0
    }

    /// The exponent as `f32` (exact but for values above 256 with a fraction).
    pub fn to_f32(self) -> f32 {
        (f64::from(self.int) + f64::from(self.frac) / 65536.0) as f32
    }
}

// ------------------------------------------------------------------ tables

/// `ln(1 + t)` by the series of `2·atanh(t/(2 + t))` (`|z| ≤ 1/3`: 40 terms are far
/// beyond f64's precision), for the tables below, evaluated at compile time.
const fn ln1p(t: f64) -> f64 {
    let z = t / (2.0 + t);
    let z2 = z * z;
    let mut s = 0.0;
    let mut p = z;
    let mut k = 0;
    while k < 40 {
        s += p / (2 * k + 1) as f64;
        p *= z2;
        k += 1;
    }
    2.0 * s
}

/// `e^x` by its Taylor series for `|x| ≤ 1` (30 terms).
const fn exp(x: f64) -> f64 {
    let mut s = 1.0;
    let mut term = 1.0;
    let mut k = 1;
    while k < 30 {
        term *= x / k as f64;
        s += term;
        k += 1;
    }
    s
}

/// The function a table samples.
enum Sampled {
    /// `log₂(1 + x)`.
    Log2,
    /// `2^(−x)`.
    Exp2,
}

/// `round(f(i/N)·2^SCALE)` for `i` in 0..=N.
const fn table<const M: usize>(f: Sampled, scale: u32) -> [u32; M] {
    let n = (M - 1) as f64;
    let mut t = [0u32; M];
    let mut i = 0;
    while i < M {
        let x = i as f64 / n;
        let v = match f {
            Sampled::Log2 => ln1p(x) / core::f64::consts::LN_2,
            Sampled::Exp2 => exp(-x * core::f64::consts::LN_2),
        };
        t[i] = (v * (1u64 << scale) as f64 + 0.5) as u32;
        i += 1;
    }
    t
}

/// `Q14`: `log₂(1 + i/64)` in Q16.
static LOG2_64: [u32; 65] = table::<65>(Sampled::Log2, 16);
/// `Q14`: `2^(−i/64)` in Q15.
static EXP2_64: [u32; 65] = table::<65>(Sampled::Exp2, 15);
/// `Q30`: `log₂(1 + i/256)` in Q30.
static LOG2_256: [u32; 257] = table::<257>(Sampled::Log2, 30);
/// `Q30`: `2^(−i/256)` in Q31.
static EXP2_256: [u32; 257] = table::<257>(Sampled::Exp2, 31);

/// `x^(f/2^16)` in Q14 for a raw Q14 `x` (32-bit arithmetic only: no 64-bit
/// multiply on a Cortex-M0). Relative error below 1.2·10⁻⁴ (linear interpolation
/// of 64-segment tables of `log₂` and `2^−t`).
pub(crate) fn pow_frac_q14(x: i32, f: u16) -> i32 {
    if x <= 0 {
        return if f == 0 { 1 << 14 } else { 0 };
    }
    if x >= 1 << 14 || f == 0 {
        return 1 << 14;
    }
    // x = r·2^−(13 + k) with r in [2^13, 2^14): a binary search (no CLZ on a Cortex-M0)
    let (r, k) = normalize_step(x as u32, 0, 6, 8);
    let (r, k) = normalize_step(r, k, 10, 4);
    let (r, k) = normalize_step(r, k, 12, 2);
    let (r, k) = normalize_step(r, k, 13, 1);
    // −log₂ x = (k + 1) − log₂(r/2^13); log₂ of t = r − 2^13 in 64 segments of 2^7
    let t = r - (1 << 13);
    // (t < 2^13: i ≤ 63; the min lets opt-level "z" drop the bounds check)
    let (i, w) = (((t >> 7) as usize).min(63), t & 127);
    let (a, b) = (LOG2_64[i], LOG2_64[i + 1]);
    let l = a + (((b - a) * w + 64) >> 7); // Q16, < 2^16
                                           // y = −f·log₂ x in Q16: f·(k + 1) < 2^20, f·l < 2^32
    let f = u32::from(f);
    let y = f * (k + 1) - ((f * l + (1 << 15)) >> 16);
    // 2^−y = 2^−q · 2^−(s/2^16), s in 64 segments of 2^10
    let (q, s) = (y >> 16, y & 0xFFFF);
    if q >= 15 {
        return 0;
    }
    let (j, w) = ((s >> 10) as usize, s & 1023);
    let (a, b) = (EXP2_64[j], EXP2_64[j + 1]);
    let e = a - (((a - b) * w + 512) >> 10); // Q15, in (2^14, 2^15]
    ((e + (1 << q)) >> (q + 1)) as i32
}

/// One step of a binary search for the leading bit: `(r·2^s, k + s)` when
/// `r < 2^b`, else `(r, k)`.
#[inline(always)]
fn normalize_step(r: u32, k: u32, b: u32, s: u32) -> (u32, u32) {
    if r < 1 << b {
        (r << s, k + s)
    } else {
        (r, k)
    }
}

/// `x^(f/2^16)` in Q30 for a raw Q30 `x` (64-bit products). Relative error below
/// 5·10⁻⁶ (256-segment tables).
pub(crate) fn pow_frac_q30(x: i32, f: u16) -> i32 {
    if x <= 0 {
        return if f == 0 { 1 << 30 } else { 0 };
    }
    if x >= 1 << 30 || f == 0 {
        return 1 << 30;
    }
    // x = r·2^−(29 + k), r in [2^29, 2^30)
    let k = x.leading_zeros() - 2;
    let r = (x as u32) << k;
    let t = r - (1 << 29);
    // 256 segments of 2^21
    let (i, w) = (((t >> 21) as usize).min(255), u64::from(t & 0x1F_FFFF));
    let (a, b) = (u64::from(LOG2_256[i]), u64::from(LOG2_256[i + 1]));
    let l = a + (((b - a) * w + (1 << 20)) >> 21); // Q30, < 2^30
                                                   // y = −f·log₂ x in Q30 (as u64): f·(k + 1)·2^30 < 2^51
    let f = u64::from(f);
    let y = ((f * u64::from(k + 1)) << 14) - ((f * l + (1 << 15)) >> 16);
    let (q, s) = (y >> 30, y & ((1 << 30) - 1));
    if q >= 31 {
        return 0;
    }
    // 256 segments of 2^22
    let (j, w) = ((s >> 22) as usize, s & 0x3F_FFFF);
    let (a, b) = (u64::from(EXP2_256[j]), u64::from(EXP2_256[j + 1]));
    let e = a - (((a - b) * w + (1 << 21)) >> 22); // Q31, in (2^30, 2^31]
    ((e + (1 << q)) >> (q + 1)) as i32
}

/// `x^(f/2^16)` in `f32` (`libm::powf`, exact to an ulp).
#[inline]
pub(crate) fn pow_frac_f32(x: f32, f: u16) -> f32 {
    if f == 0 {
        return 1.0;
    }
    if !(x > 0.0) {
        return 0.0;
    }
    libm::powf(x, f32::from(f) / 65536.0)
}

/// `x^e` from [`Scalar::powi`] and the tier's fractional power.
#[inline(always)]
pub(crate) fn pow<S: Scalar>(x: S, e: Exponent) -> S {
    let p = x.powi(e.int);
    if e.frac == 0 {
        p
    } else {
        p.mul(pow_frac_out_of_line(x, e.frac))
    }
}

/// The fractional part's factor, kept out of the integer-exponent path (a
/// scene with integer exponents pays one compare per power).
#[inline(never)]
fn pow_frac_out_of_line<S: Scalar>(x: S, f: u16) -> S {
    x.pow_frac(f)
}

// ------------------------------------------------------------------ power table

/// Segments of a [`PowTable`].
pub(crate) const POW_SEGMENTS: usize = 64;
/// Table coordinate units per segment of a [`PowTable`] (fine: a coordinate that
/// is interpolated keeps a fraction in its second differences).
pub(crate) const POW_SEG: i32 = 1 << 16;
/// The table coordinate of `x = 1`.
pub(crate) const POW_END: i32 = POW_SEGMENTS as i32 * POW_SEG;

/// The kernels' per-pixel specular power (one multiplication): `x^n` for a
/// real shininess `n` over `[x0, 1]`, `x0 = 4096^(−1/n)` (below, under 1/4096,
/// read as 0), at `POW_SEGMENTS + 1` even points, linearly interpolated; `x0`
/// (rounded down), `x` and `x^n` in `Q`-bit fixed point (`Q` = 14 or 15). The
/// coordinate of `x` is `u = (x − x0)/(1 − x0)·POW_END` ([`PowTable::get`];
/// [`PowTable::at`] for a kernel interpolating `u`). Error: the chord,
/// `n(n − 1)·x^(n−2)·(1 − x0)²/(8·64²)`, plus 2^−Q each for the entries' and
/// the interpolation's rounding.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PowTable<const Q: u32> {
    /// `x0`, `Q`-bit.
    x0: i32,
    /// `(x − x0)·mul` is the coordinate of `x` (`Q`-bit) in `2^24` per segment:
    /// `⌊2^30/(2^Q − x0)⌋`.
    mul: i32,
    /// `x^n` at the segment ends (`≤ 2^Q`), the last repeated: the entry after
    /// an index is always there.
    t: [u16; POW_SEGMENTS + 2],
}

impl<const Q: u32> PowTable<Q> {
    /// One in `Q`-bit fixed point.
    const ONE: i32 = 1 << Q;

    /// The table of `x^n` (`n = 0`: all 1) in 32-bit integers, no float or
    /// 64-bit routine ([`pow_entry`]). Each entry is within `2^−Q·(½ + 2⁻¹²)`
    /// of `x^n`: `round(x^n·2^Q)`, or one off within 2⁻¹² of a half (test
    /// `pow_table_entries_match_f64`); `x0` is
    /// `⌊4096^(−1/n)·2^Q⌋`, or one less within 2⁻¹⁰ above an integer.
    pub(crate) fn new(n: Exponent) -> Self {
        const { assert!(Q <= 15) };
        let nu = n.units();
        let x0q = if nu == 0 { 0 } else { pow_x0(nu, Q) };
        let width = (Self::ONE - x0q).max(1);
        let mut t = [0u16; POW_SEGMENTS + 2];
        for (i, v) in t.iter_mut().enumerate() {
            // x = (x0 + width·i/64)/2^Q = m/2^21 (exact: m ≤ 2^21)
            let m = ((64 * x0q + width * i.min(POW_SEGMENTS) as i32) as u32) << (15 - Q);
            *v = if nu == 0 || m >= 1 << 21 {
                Self::ONE as u16
            } else {
                pow_entry(nu, m, Q) as u16
            };
        }
        Self {
            x0: x0q,
            // POW_SEGMENTS·2^24 = 2^30
            mul: ((1u32 << 30) / width as u32) as i32,
            t,
        }
    }

    /// `x0`, `Q`-bit.
    #[inline(always)]
    pub(crate) fn x0(&self) -> i32 {
        self.x0
    }

    /// `x^n` (`Q`-bit) for `x` (`Q`-bit; above 1 read as 1).
    #[inline(always)]
    pub(crate) fn get(&self, x: i32) -> i32 {
        if x <= self.x0 {
            return 0;
        }
        // (x − x0)·mul ≤ (2^Q − x0)·⌊2^30/(2^Q − x0)⌋ ≤ 2^30
        self.at(((x.min(Self::ONE) - self.x0) * self.mul) >> 8)
    }

    /// `x^n` (`Q`-bit) at table coordinate `u ≥ 0` (beyond [`POW_END`]: 1).
    #[inline(always)]
    pub(crate) fn at(&self, u: i32) -> i32 {
        let i = ((u >> 16) as usize).min(POW_SEGMENTS);
        let (a, b) = (i32::from(self.t[i]), i32::from(self.t[i + 1]));
        a + (((b - a) * ((u >> 8) & 255)) >> 8)
    }

    /// [`PowTable::at`] for any `u`: 0 at and below 0.
    #[inline(always)]
    pub(crate) fn at_clamped(&self, u: i32) -> i32 {
        if u <= 0 {
            0
        } else {
            self.at(u)
        }
    }
}

// ---------------------------------------------------- the power table in integers
//
// `x^n = 2^−(n·(−log₂ x))` for `x = m/2^21` (exact: the table's points), `n` in
// 2⁻¹⁶ units: `−log₂ x` from a 32-entry table of `2^(−j/32)` and a series (near
// `x = 1` a series in `1 − x`, relative: no cancellation for a large `n`), the
// product with `n` in 32 significant bits, `2^−y` from the same table and a
// series; products from `mul_u32` (16-bit halves: no `__aeabi_lmul` on a
// Cortex-M0). The power's error is below 2⁻²⁵ (2⁻¹⁰ of an LSB at `Q` = 15,
// far below the entries' rounding).

/// `2^(−j/32)` in Q31 for `j` in 0..=32: the table of [`exp2_neg`] and the
/// reduction of [`neg_log2`].
static EXP2_32: [u32; 33] = table::<33>(Sampled::Exp2, 31);
/// `ln 2` in Q32.
const LN2_Q32: u32 = 2_977_044_472;
/// `log₂ e` in Q31.
const LOG2E_Q31: u32 = 3_098_164_009;
/// `1/k` in Q31 for `k` in 1..=6 (index `k − 1`).
const INV_Q31: [u32; 6] = [
    2_147_483_648,
    1_073_741_824,
    715_827_883,
    536_870_912,
    429_496_730,
    357_913_941,
];
/// `1/k!` in Q31 for `k` in 0..=4.
const INV_FACT_Q31: [u32; 5] = [
    2_147_483_648,
    2_147_483_648,
    1_073_741_824,
    357_913_941,
    89_478_485,
];

/// `(a·b) >> s`, truncated (`s` such that the result fits).
#[inline(always)]
fn mulq(a: u32, b: u32, s: u32) -> u32 {
    (mul_u32(a, b) >> s) as u32
}

/// An unsigned number `m·2^e`, `m` normalised (`2^31 ≤ m < 2^32`): 32
/// significant bits (a product is truncated: relative error below 2⁻³¹).
#[derive(Clone, Copy)]
struct Scaled {
    m: u32,
    e: i32,
}

impl Scaled {
    /// `v·2^e` (`v > 0`).
    fn new(v: u32, e: i32) -> Self {
        let z = v.leading_zeros();
        Self {
            m: v << z,
            e: e - z as i32,
        }
    }

    /// `v·2^e` (`v > 0`), truncated to 32 significant bits.
    fn from_u64(v: u64, e: i32) -> Self {
        let hi = (v >> 32) as u32;
        if hi == 0 {
            Self::new(v as u32, e)
        } else {
            let z = hi.leading_zeros();
            Self {
                m: ((v << z) >> 32) as u32,
                e: e + 32 - z as i32,
            }
        }
    }

    fn mul(self, o: Self) -> Self {
        let p = mul_u32(self.m, o.m); // in [2^62, 2^64)
        if p >> 63 != 0 {
            Self {
                m: (p >> 32) as u32,
                e: self.e + o.e + 32,
            }
        } else {
            Self {
                m: (p >> 31) as u32,
                e: self.e + o.e + 31,
            }
        }
    }

    /// The value in Q32 (truncated); `None` at or above 32.
    fn to_q32(self) -> Option<u64> {
        let s = self.e + 32;
        if s >= 1 {
            // the value is at least 2^(31 + e) = 2^(s − 1)
            if s >= 6 {
                None
            } else {
                Some(u64::from(self.m) << s)
            }
        } else if s > -64 {
            Some(u64::from(self.m) >> -s)
        } else {
            Some(0)
        }
    }
}

/// `−log₂(m/2^21)` for `m` in 1..2^21: relative error below 2⁻²⁸ for
/// `x > 31/32`, absolute below 2⁻³⁰ elsewhere.
fn neg_log2(m: u32) -> Scaled {
    let d = (1 << 21) - m; // 1 − x in 2^−21
    if d < 1 << 16 {
        // x > 31/32: −ln(1 − d) = d·(1 + d/2 + d²/3 + … + d⁵/6), relative error
        // below d⁶/7 < 2^−32 (no cancellation: a relative error near x = 1)
        let dq = d << 16; // Q37, < 2^32
        let mut s = INV_Q31[5];
        for &c in INV_Q31[..5].iter().rev() {
            s = c + mulq(dq, s, 37); // < 1.02·2^31
        }
        Scaled::new(d, -21)
            .mul(Scaled { m: s, e: -31 })
            .mul(Scaled {
                m: LOG2E_Q31,
                e: -31,
            })
    } else {
        // x = r·2^(k − 21), r in [1, 2): −log₂ x = 21 − k − log₂ r
        let z = m.leading_zeros(); // ≥ 11
        let k = 31 - z;
        let r = m << z; // Q31
                        // j: the largest in 0..32 with r ≥ 2^(j/32), i.e. r/2 ≥ 2^(−(32 − j)/32)
                        // (`j + step ≤ 31` and `j ≤ 31`: the `get`s only drop the panic paths)
        let exp2 = |i: usize| EXP2_32.get(i).copied().unwrap_or(0);
        let mut j = 0;
        for step in [16, 8, 4, 2, 1] {
            if r >> 1 >= exp2(32usize.wrapping_sub(j + step)) {
                j += step;
            }
        }
        // r·2^(−j/32) = 1 + t, t in [0, 2^−5.5) (the table's rounding: 2^−32)
        let t = (mul_u32(r, exp2(j)).saturating_sub(1 << 62) >> 25) as u32; // Q37
                                                                            // ln(1 + t) = t·(1 − t/2 + t²/3 − t³/4 + t⁴/5): error below t⁶/6 < 2^−35
        let mut s = INV_Q31[4];
        for &c in INV_Q31[..4].iter().rev() {
            s = c - mulq(t, s, 37);
        }
        let lg = mulq(mulq(t, s, 31), LOG2E_Q31, 31); // log₂(1 + t), Q37
                                                      // L = 21 − k − j/32 − log₂(1 + t) in Q37: above 0.045 (x < 31/32), absolute
                                                      // error ≈ 2^−31 (the table)
        let l = (u64::from(21 - k) << 37) - ((j as u64) << 32) - u64::from(lg);
        Scaled::from_u64(l, -37)
    }
}

/// `2^−y` for `y` in Q32 below 2^37 as `(r, q)`: `r·2^−(31 + q)`, `r` in
/// (2^30, 2^31], relative error below 2⁻²⁹.
fn exp2_neg(y: u64) -> (u32, u32) {
    let (q, s) = ((y >> 32) as u32, y as u32);
    let j = (s >> 27) as usize;
    // u = (s − j/32)·ln 2 < 2^−5.5, Q37
    let u = mulq((s & ((1 << 27) - 1)) << 5, LN2_Q32, 32);
    // e^−u = 1 − u·(1 − u·(1/2 − u·(1/6 − u/24))): error below u⁵/120 < 2^−34
    let mut p = INV_FACT_Q31[4];
    for &c in INV_FACT_Q31[..4].iter().rev() {
        p = c - mulq(u, p, 37);
    }
    (mulq(EXP2_32[j], p, 31), q)
}

/// `(m/2^21)^n` (`n = nu/2^16 > 0`, `m` in 1..2^21) as `(r, k)`: `r·2^−(31 + k)`,
/// `None` below `2^−(q + 2)` (`q ≤ 15`). Absolute error below 2⁻²⁵, relative below 2⁻²³ (the
/// test `pow_error_is_far_below_an_lsb`).
fn pow_parts(nu: u32, m: u32, q: u32) -> Option<(u32, u32)> {
    let y = Scaled::new(nu, -16).mul(neg_log2(m)).to_q32()?;
    if y >> 32 > u64::from(q + 1) {
        return None;
    }
    Some(exp2_neg(y))
}

/// `round((m/2^21)^n·2^q)` (`n = nu/2^16 > 0`, `m` in 0..2^21, `q ≤ 15`).
fn pow_entry(nu: u32, m: u32, q: u32) -> u32 {
    if m == 0 {
        return 0;
    }
    let Some((r, k)) = pow_parts(nu, m, q) else {
        return 0; // below 2^−(q + 2)
    };
    // r·2^(q − 31 − k), the shift ≤ 32
    let sh = 31 - q + k;
    ((u64::from(r) + (1 << (sh - 1))) >> sh) as u32
}

/// `⌊4096^(−1/n)·2^q⌋` (`n = nu/2^16 > 0`, `q ≤ 15`) from `2^−(12/n)`: never above,
/// one below where the product lies within 2⁻²⁶ (relative) above an integer.
fn pow_x0(nu: u32, q: u32) -> i32 {
    // 12/n = 12·2^16/nu in Q32 (truncated)
    let num = 12 << 16;
    let (whole, rem) = (num / nu, num % nu);
    if whole > q {
        return 0; // 2^−(12/n)·2^q < 1
    }
    let frac = div_u64_u32(u64::from(rem) << 32, nu).0;
    let (r, k) = exp2_neg((u64::from(whole) << 32) | u64::from(frac));
    // the margin (2^−26 relative) exceeds the error of 12/n and of exp2_neg
    let r = r - (r >> 26) - 1;
    (r >> (31 - q + k)) as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{F32Fast, Q14, Q30};

    fn worst<S: Scalar>(samples: u32) -> (f64, f64) {
        let (mut abs, mut rel) = (0.0f64, 0.0f64);
        for fi in (0..=65535u32).step_by(251).chain([1, 32768, 65535]) {
            let f = fi as u16;
            for k in 0..=samples {
                let x = S::from_f32(k as f32 / samples as f32);
                let xf = f64::from(x.to_f32());
                let want = if f == 0 {
                    1.0
                } else if xf <= 0.0 {
                    0.0
                } else {
                    xf.powf(f64::from(f) / 65536.0)
                };
                let got = f64::from(x.pow_frac(f).to_f32());
                abs = abs.max((got - want).abs());
                // relative, beyond the result's own rounding (2^-15 in Q14)
                if want > 0.05 {
                    rel = rel.max(((got - want).abs() - 3.1e-5).max(0.0) / want);
                }
            }
        }
        (abs, rel)
    }

    /// Every tier's fractional power against f64 over the whole fraction range and
    /// x in [0, 1].
    #[test]
    fn fractional_powers() {
        let (a, r) = worst::<Q14<2>>(4096);
        assert!(a < 1.2e-4 && r < 1.2e-4, "Q14: {a:e} {r:e}");
        let (a, r) = worst::<Q30<3>>(4096);
        assert!(a < 5e-6 && r < 5e-6, "Q30: {a:e} {r:e}");
        let (a, r) = worst::<f32>(1024);
        assert!(a < 2e-7, "f32: {a:e} {r:e}");
        let (a, _) = worst::<F32Fast<2>>(1024);
        assert!(a < 2e-7, "F32Fast: {a:e}");
    }

    /// Tiny inputs (every Q14 value below 2^-6 and the smallest Q30 values).
    #[test]
    fn fractional_powers_of_tiny_values() {
        for raw in 1..64 {
            let want = (raw as f64 / 16384.0).powf(0.5);
            let got = pow_frac_q14(raw, 32768) as f64 / 16384.0;
            assert!((got - want).abs() < 1.0e-4, "{raw}: {got} {want}");
        }
        for raw in [1i32, 2, 3, 1000, 1 << 20] {
            let want = (raw as f64 / 1073741824.0).powf(0.25);
            let got = pow_frac_q30(raw, 16384) as f64 / 1073741824.0;
            assert!(
                (got - want).abs() < 1.0e-6 * want.max(1e-3),
                "{raw}: {got} {want}"
            );
        }
    }

    #[test]
    fn exponents() {
        let e = Exponent::new("e", 2.5).unwrap();
        assert_eq!((e.integer_part(), e.fraction()), (2, 32768));
        assert_eq!(
            Exponent::new("e", 65535.0).unwrap(),
            Exponent::integer(65535)
        );
        assert_eq!(
            Exponent::new("e", 65535.5).unwrap_err(),
            ParamError::ExponentOutOfRange("e")
        );
        assert!(Exponent::new("e", f32::NAN).is_err());
        // a fraction that rounds up carries into the integer part
        assert_eq!(Exponent::new("e", 2.9999999).unwrap(), Exponent::integer(3));
        for (x, e) in [(0.9f32, 12.8f32), (0.5, 1.5), (0.99, 27.8974), (0.3, 0.25)] {
            let ex = Exponent::new("e", e).unwrap();
            let want = f64::from(x).powf(f64::from(e));
            assert!((f64::from(Q14::<2>::from_f32(x).pow(ex).to_f32()) - want).abs() < 2.5e-4);
            assert!((f64::from(Q30::<3>::from_f32(x).pow(ex).to_f32()) - want).abs() < 2e-6);
            assert!((f64::from(x.pow(ex)) - want).abs() < 1e-6);
        }
        // x^0 = 1, 0^e = 0 for e > 0
        assert_eq!(Q14::<2>::ZERO.pow(Exponent::ZERO), Q14::ONE);
        assert_eq!(
            Q30::<3>::ZERO.pow(Exponent::new("e", 0.5).unwrap()),
            Q30::ZERO
        );
        assert_eq!(0.0f32.pow(Exponent::new("e", 0.5).unwrap()), 0.0);
    }
    /// The table against `powf` at points across the whole coordinate range, and
    /// `get` against `at` for both precisions.
    #[test]
    fn pow_table_matches_powf() {
        for n in [0.0f32, 1.0, 1.5, 8.0, 12.8, 32.0, 256.0, 1024.0] {
            let e = Exponent::new("n", n).unwrap();
            let t = PowTable::<15>::new(e);
            let x0 = t.x0() as f32 / 32768.0;
            for i in (0..=POW_END).step_by(61) {
                let x = x0 + (1.0 - x0) * i as f32 / POW_END as f32;
                let want = libm::powf(x, n);
                let got = t.at(i) as f32 / 32768.0;
                assert!((got - want).abs() < 2.5e-3, "n {n} i {i}: {got} {want}");
            }
            assert_eq!(t.at(POW_END + 3 * POW_SEG + 77), 32768);
            assert_eq!(t.at_clamped(-5), 0);
            let t14 = PowTable::<14>::new(e);
            for x in (0..=20000).step_by(7) {
                let want = if x <= t14.x0() {
                    0.0
                } else {
                    libm::powf(x.min(16384) as f32 / 16384.0, n)
                };
                let got = t14.get(x) as f32 / 16384.0;
                assert!(
                    (got - want).abs() < 2.5e-3 + 1.0 / 4096.0,
                    "n {n} x {x}: {got} {want}"
                );
            }
        }
    }

    /// Every entry and `x0` of the integer table against `f64` for both
    /// precisions, at the table's own points and exponent (`n` in 2⁻¹⁶ units): 0,
    /// every integer to 1024 (the tests' shininess: 1..=1024, 614), every multiple
    /// of 1/16 to 128 (12.8's neighbours, 0.0625…), fractional and large values
    /// and 4000 pseudo-random exponents in (0, 65535]. An entry is within
    /// `½ + 2⁻¹²` LSB of the exact `x^n·2^Q`: `round` of it, or one off where
    /// `x^n·2^Q` lies within 2⁻¹² of a half. `x0` is `⌊4096^(−1/n)·2^Q⌋`, or one
    /// less where that product is within 2⁻¹⁰ above an integer.
    #[test]
    fn pow_table_entries_match_f64() {
        let mut state = 0x2545_F491u32;
        let random = core::iter::repeat_with(move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            // exponents spread over the octaves: n = 2^(s/256 − 8), up to 65535
            let s = (state >> 8) % (24 * 256);
            let n = libm::exp2(f64::from(s) / 256.0 - 8.0).min(65535.0);
            n as f32
        })
        .take(4000);
        let ns = [
            0.0f32, 0.01, 0.1, 0.25, 0.3, 0.5, 0.75, 1.5, 2.5, 12.8, 27.8974,
        ]
        .into_iter()
        .chain((1..=1024).map(|i| i as f32))
        .chain((1..=2048).map(|i| i as f32 / 16.0))
        .chain([
            100.5, 1000.3, 1500.0, 2048.0, 2100.0, 4096.0, 10000.0, 30000.0, 65535.0,
        ])
        .chain(random);
        let (mut worst, mut worst_at, mut off, mut entries) = (0.0f64, (0.0, 0, 0), 0u32, 0u32);
        let (mut x0_low, mut x0_worst) = (0u32, 0.0f64);
        for n in ns {
            let n = Exponent::new("n", n).unwrap();
            let nu = n.units();
            let ne = f64::from(nu) / 65536.0;
            for q in [14u32, 15] {
                let (x0, t) = if q == 14 {
                    let t = PowTable::<14>::new(n);
                    (t.x0, t.t)
                } else {
                    let t = PowTable::<15>::new(n);
                    (t.x0, t.t)
                };
                let one = f64::from(1u32 << q);
                if nu == 0 {
                    assert_eq!(x0, 0);
                    assert!(t.iter().all(|&v| f64::from(v) == one), "n {n:?}");
                    continue;
                }
                let v = libm::pow(4096.0, -1.0 / ne) * one;
                let fl = libm::floor(v);
                if f64::from(x0) != fl {
                    assert!(
                        f64::from(x0) == fl - 1.0 && v - fl < 1.0 / 1024.0,
                        "n {ne} Q{q}: x0 {x0}, 4096^(-1/n)·2^Q = {v}"
                    );
                    x0_low += 1;
                    x0_worst = x0_worst.max(v - fl);
                }
                let width = (1i32 << q) - x0;
                for (i, &got) in t.iter().enumerate() {
                    let m = 64 * x0 + width * i.min(POW_SEGMENTS) as i32;
                    let x = f64::from(m) / f64::from(1u32 << (q + 6));
                    let want = libm::pow(x, ne) * one;
                    let err = (f64::from(got) - want).abs();
                    entries += 1;
                    off += u32::from(f64::from(got) != libm::round(want));
                    if err > worst {
                        (worst, worst_at) = (err, (ne, q, i));
                    }
                    assert!(
                        err <= 0.5 + 1.0 / 4096.0,
                        "n {ne} Q{q} entry {i}: {got}, x^n·2^Q = {want}"
                    );
                }
            }
        }
        std::println!(
            "entries {entries}: worst |entry − x^n·2^Q| {worst:.6} LSB at (n, Q, i) {worst_at:?}, \
             {off} not round(x^n·2^Q); x0 one below the floor {x0_low} times (fraction ≤ {x0_worst:e})"
        );
    }

    /// The unrounded power against `f64` at every point `x = m/2^21` of the
    /// tables' grid, for exponents across the range (an exhaustive search of
    /// the worst case in `x`): absolute error below 2⁻²⁵ (2⁻¹⁰ LSB of a `Q` = 15
    /// entry before its rounding), relative error below 2⁻²³.
    #[test]
    fn pow_error_is_far_below_an_lsb() {
        let (mut abs, mut rel) = ((0.0f64, 0.0, 0), (0.0f64, 0.0, 0));
        for n in [
            0.01f32, 0.5, 1.0, 2.0, 5.0, 10.0, 12.8, 32.0, 100.0, 128.0, 1024.0, 65535.0,
        ] {
            let nu = Exponent::new("n", n).unwrap().units();
            let ne = f64::from(nu) / 65536.0;
            for m in 1..1u32 << 21 {
                let want = libm::pow(f64::from(m) / 2097152.0, ne);
                match pow_parts(nu, m, 15) {
                    Some((r, k)) => {
                        let got = f64::from(r) * libm::exp2(-31.0 - f64::from(k));
                        let e = (got - want).abs();
                        if e > abs.0 {
                            abs = (e, ne, m);
                        }
                        if e / want > rel.0 {
                            rel = (e / want, ne, m);
                        }
                    }
                    // below 2^−17: an entry rounds to 0
                    None => assert!(want < 1.0 / 131072.0 * (1.0 + 1e-6), "n {ne} m {m}: {want}"),
                }
            }
        }
        std::println!(
            "worst absolute error 2^{:.2} at (n, m) {:?}, relative 2^{:.2} at {:?}",
            libm::log2(abs.0),
            (abs.1, abs.2),
            libm::log2(rel.0),
            (rel.1, rel.2)
        );
        assert!(abs.0 < libm::exp2(-25.0) && rel.0 < libm::exp2(-23.0));
    }
}
