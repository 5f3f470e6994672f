//! Real exponents: `x^e` for `x` in [0, 1] and any `e` in 0..=65535, with the
//! fraction of `e` evaluated only where there is one.
//!
//! `x^e = x^⌊e⌋ · x^f`: the integer part by repeated squaring ([`Scalar::powi`],
//! exact up to the rounding of each product), the fraction `f` (kept in 2⁻¹⁶
//! units) as `2^(f·log₂ x)` from two interpolated tables. An integer exponent
//! costs one comparison more than [`Scalar::powi`] and never evaluates a
//! logarithm.
//!
//! Quantising `f` to 2⁻¹⁶ moves `x^e` by at most `2⁻¹⁶·x^e·|ln x|`, which is below
//! `2⁻¹⁶/(e·e_)` (`e_` = 2.718…) for `e ≥ 1`: 8·10⁻⁷ at `e = 12.8`, 1.4·10⁻⁵ below
//! `e = 1` (0.004 of an 8-bit step).

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

/// `x^n` over `[x0, 1]` for a material's (real) shininess `n`, `x0 = 4096^(−1/n)`
/// (below `x0` the power is under 1/4096 and read as 0), at `POW_SEGMENTS + 1`
/// evenly spaced points, linearly interpolated: the per-pixel specular power of
/// the shading kernels (one multiplication where [`Scalar::pow`] takes a chain of
/// products or logarithms). `x0` (rounded down), `x` and `x^n` are `Q`-bit fixed
/// point (`Q` = 14 or 15).
///
/// The table coordinate `u` of `x` is `(x − x0)/(1 − x0)·POW_END`; [`PowTable::get`]
/// computes it, a kernel that interpolates the coordinate itself reads
/// [`PowTable::at`]. Error: the chord of `x^n` over a segment, at most
/// `n(n − 1)·x^(n−2)·(1 − x0)²/(8·64²)`, plus the rounding of the entries and of
/// the interpolation (2^−Q each).
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

    /// The table of `x^n` (`n ≥ 0`; `n = 0` gives 1 everywhere).
    pub(crate) fn new(n: f32) -> Self {
        // f32 (libm's powf is exact to an ulp) so that the fast path links no f64
        let x0 = if n == 0.0 {
            0.0
        } else {
            libm::powf(4096.0, -1.0 / n)
        };
        let one = Self::ONE as f32;
        let x0q = libm::floorf(x0 * one) as i32;
        let width = (Self::ONE - x0q).max(1);
        let mut t = [0u16; POW_SEGMENTS + 2];
        for (i, v) in t.iter_mut().enumerate() {
            let x = (x0q as f32 + width as f32 * i.min(POW_SEGMENTS) as f32 / POW_SEGMENTS as f32)
                / one;
            let p = if n == 0.0 { 1.0 } else { libm::powf(x, n) };
            *v = libm::roundf(p * one).clamp(0.0, one) as u16;
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
            let t = PowTable::<15>::new(n);
            let x0 = t.x0() as f32 / 32768.0;
            for i in (0..=POW_END).step_by(61) {
                let x = x0 + (1.0 - x0) * i as f32 / POW_END as f32;
                let want = libm::powf(x, n);
                let got = t.at(i) as f32 / 32768.0;
                assert!((got - want).abs() < 2.5e-3, "n {n} i {i}: {got} {want}");
            }
            assert_eq!(t.at(POW_END + 3 * POW_SEG + 77), 32768);
            assert_eq!(t.at_clamped(-5), 0);
            let t14 = PowTable::<14>::new(n);
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
}
