//! The number layer: the scalar a lighting pipeline computes in.
//!
//! A *tier* is a type implementing [`Scalar`]. The lighting equation is written
//! once, generic over the tier, so choosing a tier is choosing a point on the
//! speed/accuracy trade:
//!
//! | tier | storage | per-pixel products | range | approximations |
//! |---|---|---|---|---|
//! | [`Q14<NEWTON>`](Q14) | `i32` holding Q2.14 | 16×16→32 bit (one `MULS` on a Cortex-M0) | [−2, 2) | inverse square root: 48-entry seed + `NEWTON` steps |
//! | [`Q30<NEWTON>`](Q30) | `i32` holding Q2.30 | 32×32→64 bit | [−2, 2) | inverse square root: 48-entry seed + `NEWTON` steps |
//! | `f32` | IEEE single | FPU (or soft float) | ±10⁹ | exact (`libm`) |
//! | [`F32Fast`] | IEEE single | FPU | ±10⁹ | micromath inverse square root |
//!
//! Geometry (positions, distances) needs range rather than precision: each tier
//! names a [`Scalar::Geo`] type, [`Geo16`] (Q16.16, ±32768 scene units) for the
//! fixed tiers, `f32` for the float tiers. Attenuation coefficients and fog
//! ranges keep their `f32` relative precision over the whole legal range
//! ([`Scalar::geo_inv_quadratic`], [`Scalar::ramp`]).
//!
//! # Overflow behaviour
//!
//! Every operation of every tier **saturates**: it never wraps and never panics,
//! overflow checks included. Conversions from `f32` map NaN to zero and clamp to
//! the tier's range. Powers: see [`Scalar::powi`] and [`Scalar::pow_frac`].

// `max(lo).min(hi)` rather than `clamp(lo, hi)` on the per-pixel path: `clamp`'s
// `min <= max` assertion (a panic path) can survive in a size-optimised build.
#![allow(clippy::manual_clamp)]

mod float;
mod geo;
mod matrix;
pub(crate) mod pow;
mod q14;
mod q30;
pub(crate) mod recip;
pub(crate) use recip::div_small;
pub(crate) mod rsqrt;
mod trig;
mod vector;
pub(crate) mod wide;

pub use float::F32Fast;
pub(crate) use geo::GeoScalar;
pub use matrix::Mat4;
pub(crate) use matrix::{cof3, cross3, dot3, sub3};
pub use pow::Exponent;
pub use q14::Q14;
pub use q30::Q30;
pub(crate) use trig::sin_cos;
pub(crate) use vector::point_sub;
pub use vector::{point_from_f32, Point3, Vec3};

use core::fmt::Debug;

/// Fraction bits of interpolated values: a value `v` is `v · 2^ATTR_FRAC`
/// (what the rasterizer hands the shading kernels, and the encoders read).
pub const ATTR_FRAC: u32 = 14;

/// `a[i]` for a vertex index `i < 3`, the index limited to 2 so that no bounds
/// check (no panic path) is left in the image.
#[inline(always)]
pub(crate) fn at3<T: Copy>(a: &[T; 3], i: usize) -> T {
    a[i.min(2)]
}

/// `v · 2^-shift` rounded to nearest (ties up), for `shift` in 0..=62: an
/// arithmetic shift, so it cannot overflow for any `v` whose magnitude is below
/// 2^62.
#[inline(always)]
pub(crate) fn round_shr(v: i64, shift: u32) -> i64 {
    if shift == 0 {
        v
    } else {
        (v + (1i64 << (shift - 1))) >> shift
    }
}

/// Geometry scalar of the fixed-point tiers: Q16.16 in an `i32`
/// ([`fixed::types::I16F16`]), range ±32768 scene units, resolution 1.5·10⁻⁵.
pub type Geo16 = fixed::types::I16F16;

/// A number tier: the scalar type the lighting equation is evaluated in.
///
/// Values of a tier are *unit-range* quantities (colour channels, unit-vector
/// components, dot products, attenuation and spot factors); positions and
/// distances use [`Scalar::Geo`]. All operations saturate and never panic.
pub trait Scalar: Copy + Debug + PartialEq + PartialOrd + Default + Send + Sync + 'static {
    /// The scalar for positions and distances (more range, less precision).
    type Geo: GeoScalar;
    /// The linear fog ramp `clamp((end − d)/(end − start), 0, 1)` in the form this
    /// tier evaluates (see [`Scalar::ramp`]).
    type Ramp: Copy + Debug + PartialEq + Send + Sync + 'static;

    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// The largest representable value; results above it saturate to it.
    const MAX: Self;
    /// A short human-readable name of the tier, for reports.
    const NAME: &'static str;
    /// Whether the tier is a floating-point type (`f32`, [`F32Fast`]): the
    /// quadratic per-pixel kernel evaluates its anchors in `f32` for these, in
    /// 32-bit integers for the fixed tiers.
    const FLOAT: bool;

    /// Converts from `f32`, rounding to nearest; NaN becomes zero, values beyond
    /// the range saturate.
    fn from_f32(v: f32) -> Self;
    /// Converts to `f32` (exact for the fixed tiers).
    fn to_f32(self) -> f32;

    /// `self + rhs`, saturating.
    fn add(self, rhs: Self) -> Self;
    /// `self − rhs`, saturating.
    fn sub(self, rhs: Self) -> Self;
    /// `self · rhs`, rounded, saturating.
    fn mul(self, rhs: Self) -> Self;
    /// `self / rhs`, saturating; a zero or negative divisor gives [`Scalar::MAX`]
    /// for a positive dividend and zero otherwise.
    fn div(self, rhs: Self) -> Self;
    /// `√self`; zero for `self ≤ 0`.
    fn sqrt(self) -> Self;

    /// `a·b = ax·bx + ay·by + az·bz`, saturating ([`Vec3::dot`]). The default rounds
    /// each product; `Q14` sums the three exact products and rounds once (more
    /// accurate, and fewer instructions).
    #[inline(always)]
    fn dot3(a: Vec3<Self>, b: Vec3<Self>) -> Self {
        a.x.mul(b.x).add(a.y.mul(b.y)).add(a.z.mul(b.z))
    }

    /// `2·self·b − c`, rounded once and saturated only at the end: a component of
    /// the reflection `2(N·L)N − L`, whose partial product `2(N·L)·N` reaches 2 for
    /// unit vectors (the fixed tiers' range ends just below 2) while the result stays
    /// within [−1, 1].
    #[inline(always)]
    fn twice_mul_sub(self, b: Self, c: Self) -> Self {
        let t = self.mul(b);
        t.sub(c).add(t)
    }

    /// `N·U/(|N||U|)` for `n`, `u` unit up to rounding. Powers amplify a length's
    /// deviation from 1 (`d(xⁿ) = n·xⁿ⁻¹·dx`); a `Q14` unit vector is up to
    /// 5·10⁻⁵ off (4·10⁻⁴ after one Newton step). The default is `n·u`. `Q14`
    /// sums the products unrounded and, when a squared length is within 2⁻⁵ of 1,
    /// corrects it to first order (`N·U·(1 − (|N|² − 1)/2 − (|U|² − 1)/2)`:
    /// residual below 10⁻⁸ for normalised vectors, 4·10⁻⁴ at the window's edge).
    /// The others use the default: a normalised vector is within 10⁻⁸ (`Q30`),
    /// 10⁻⁷ (`f32`) or 4.7·10⁻⁶ (`F32Fast<2>`, which limits its highlights at
    /// high exponents).
    #[inline(always)]
    fn cos_normal(n: Vec3<Self>, u: Vec3<Self>) -> Self {
        n.dot(u)
    }

    /// `R·V`, the Phong specular base, `R` the reflection of `l` about `n` (all
    /// unit up to rounding); `R·V = 2(N·L)(N·V) − L·V` is twice as sensitive to
    /// `|N|` as a plain cosine. The default is `n.reflect(l).dot(v)`. `Q14`
    /// evaluates `(2(N·L)(N·V)/|N|² − L·V)/(|L||V|)`, dot products unrounded and
    /// lengths corrected as in [`Scalar::cos_normal`], falling back to the
    /// default when a dot product exceeds 1.125.
    #[inline(always)]
    fn reflect_dot(n: Vec3<Self>, l: Vec3<Self>, v: Vec3<Self>) -> Self {
        n.reflect(l).dot(v)
    }

    /// `max(self, 0)`.
    #[inline(always)]
    fn max0(self) -> Self {
        if self > Self::ZERO {
            self
        } else {
            Self::ZERO
        }
    }

    /// `min(self, 1)`.
    #[inline(always)]
    fn min1(self) -> Self {
        if self < Self::ONE {
            self
        } else {
            Self::ONE
        }
    }

    /// `self^n` by repeated squaring (exact for the integer exponent up to the
    /// rounding of each product). `x^0 = 1` (also for `x = 0`). The base is expected
    /// in [0, 1]; use [`Scalar::max0`] and [`Scalar::min1`] first.
    #[inline]
    fn powi(self, n: u16) -> Self {
        let mut base = self;
        let mut n = n;
        let mut acc = Self::ONE;
        // acc · base^n is invariant; each step consumes one bit of n.
        while n > 0 {
            if n & 1 == 1 {
                acc = acc.mul(base);
            }
            n >>= 1;
            if n > 0 {
                base = base.mul(base);
            }
        }
        acc
    }

    /// `self^(f/2^16)`, the fractional part of a real power, for `self` in [0, 1]
    /// (below 0 it is 0, above 1 it is 1; `f = 0` gives 1). The float tiers use
    /// `libm::powf`; `Q14` and `Q30` evaluate `2^(f·log₂ x)` from interpolated
    /// tables (relative error below 1.2·10⁻⁴ in `Q14`, with 32-bit products only,
    /// and 5·10⁻⁶ in `Q30`).
    #[inline]
    fn pow_frac(self, f: u16) -> Self {
        Self::from_f32(pow::pow_frac_f32(self.to_f32(), f))
    }

    /// `self^e` for a real exponent ([`Exponent`]): [`Scalar::powi`] of the integer
    /// part times [`Scalar::pow_frac`] of the fraction, which an integer exponent
    /// skips. The base is expected in [0, 1]; `x^0 = 1` (also for `x = 0`).
    #[inline(always)]
    fn pow(self, e: Exponent) -> Self {
        pow::pow(self, e)
    }

    /// `round(clamp(self, 0, 1) · (2^bits − 1))` for `bits` in 1..=16 (the quantised
    /// output channel). NaN maps to 0.
    fn to_unorm(self, bits: u32) -> u32;

    /// `v / |v|`. A zero vector (or one whose length underflows the tier) gives the
    /// zero vector; a tiny vector keeps only the direction resolution its
    /// components carry. Never panics.
    fn normalize(v: Vec3<Self>) -> Vec3<Self>;

    /// [`Scalar::normalize`] with the tier's most accurate inverse square root,
    /// for vectors normalised once (precomputed halfway vectors), not per pixel.
    #[inline]
    fn normalize_precise(v: Vec3<Self>) -> Vec3<Self> {
        Self::normalize(v)
    }

    /// The unit vector along `v` for a precomputed direction kernels take as
    /// unit uncorrected (the halfway vector, whose `x^n` amplifies a length
    /// error `n` times): of the tier's vectors within one step of the direction,
    /// the one nearest to unit length. Default [`Scalar::normalize_precise`];
    /// `Q14` (rounding leaves `5·10⁻⁵`, 5 % of a highlight of exponent 1024)
    /// picks per component floor or ceiling, about ten times closer.
    #[inline]
    fn normalize_nearest_unit(v: Vec3<Self>) -> Vec3<Self> {
        Self::normalize_precise(v)
    }

    /// A renormalisation for interpolated normals, whose length stays near 1
    /// (between about 0.7 and 1 for reasonably tessellated meshes): the same
    /// result as [`Scalar::normalize`] for every input, possibly cheaper.
    #[inline(always)]
    fn normalize_interpolated(v: Vec3<Self>) -> Vec3<Self> {
        Self::normalize(v)
    }

    /// Fraction bits of a unit-range value as a rasterizer attribute: 26 for
    /// every tier (a normal turning 180° within one pixel stays far below the
    /// gradient limit of 2^29 units per pixel). [`Scalar::to_attr`] is
    /// `round(x · 2^ATTR_FRAC)` saturated to `i32`.
    const ATTR_FRAC: u32;
    /// The value as a rasterizer attribute (see [`Scalar::ATTR_FRAC`]).
    fn to_attr(self) -> i32;
    /// The value of a rasterizer attribute (inverse of [`Scalar::to_attr`]).
    fn from_attr(a: i32) -> Self;
    /// A position coordinate as a rasterizer attribute: Q16.16, saturated.
    fn geo_to_attr(g: Self::Geo) -> i32;
    /// The position coordinate of a rasterizer attribute.
    fn geo_from_attr(a: i32) -> Self::Geo;

    /// Converts a geometric value from `f32`: NaN becomes zero, values beyond the
    /// geometry range saturate.
    fn geo_from_f32(v: f32) -> Self::Geo;
    /// Converts a geometric value to `f32`.
    fn geo_to_f32(g: Self::Geo) -> f32;
    /// `a + b`, saturating.
    fn geo_add(a: Self::Geo, b: Self::Geo) -> Self::Geo;
    /// `a − b`, saturating.
    fn geo_sub(a: Self::Geo, b: Self::Geo) -> Self::Geo;
    /// `a · b`, saturating.
    fn geo_mul(a: Self::Geo, b: Self::Geo) -> Self::Geo;
    /// `clamp(g, 0, 1)` converted to the tier.
    fn geo_to_unit(g: Self::Geo) -> Self;
    /// `1 / g` converted to the tier, saturating at [`Scalar::MAX`]; `g ≤ 0` gives
    /// [`Scalar::MAX`].
    fn geo_recip(g: Self::Geo) -> Self;
    /// The unit vector along `v` and the length of `v`. A zero vector gives the zero
    /// vector and length zero. Lengths beyond the geometry range saturate.
    fn geo_direction(v: Vec3<Self::Geo>) -> (Vec3<Self>, Self::Geo);

    /// The attenuation `1/(a + b·d + c·d²)` of the coefficients `k` (as an
    /// [`Attenuation`](crate::lighting::Attenuation) stores them) at distance
    /// `d`; a negative (or NaN) distance counts as 0. Saturates at [`Scalar::MAX`] where `a + b·d + c·d²` is below
    /// `1/MAX` (0.5 for the fixed tiers, 10⁻⁹ for the float tiers); the lights use
    /// [`Scalar::geo_inv_quadratic_exp`], which goes on beyond.
    ///
    /// Accuracy, for every finite non-negative `a, b, c` and every distance of the
    /// geometry range: `Q14` within 2⁻¹³ relative (16-bit mantissas) plus its final
    /// rounding (2⁻¹⁵), `Q30` and the float tiers within 10⁻⁶ relative
    /// (`tests/stability_distance.rs` sweeps every binade of both).
    fn geo_inv_quadratic(k: &<Self::Geo as GeoScalar>::InvQuadratic, d: Self::Geo) -> Self;

    /// [`Scalar::geo_inv_quadratic`] beyond the tier's range, as `m·2^e`: `e = 0`
    /// below [`Scalar::MAX`]; above it (only with `a < ½`, near the light) the
    /// fixed tiers return `m` in `[1, 2)` (same relative accuracy) and `e ≥ 1`,
    /// `(1, u32::MAX)` for an infinite factor, so a product saturates only once
    /// formed ([`Scalar::mul_pow2`]). The float tiers keep `e = 0` (their 10⁹
    /// saturates every product of the factor above 10⁻⁹).
    #[inline]
    fn geo_inv_quadratic_exp(
        k: &<Self::Geo as GeoScalar>::InvQuadratic,
        d: Self::Geo,
    ) -> (Self, u32) {
        (Self::geo_inv_quadratic(k, d), 0)
    }

    /// `self · 2^e`, saturated at `±MAX` (`e = 0` returns `self`; any `e` is
    /// allowed, `u32::MAX` saturates every non-zero value). The default doubles
    /// with [`Scalar::add`] (saturating in the fixed tiers) until the value stops
    /// changing; the fixed tiers shift.
    #[inline]
    fn mul_pow2(self, e: u32) -> Self {
        let mut v = self;
        for _ in 0..e.min(160) {
            let w = v.add(v);
            if w == v {
                break;
            }
            v = w;
        }
        v
    }

    /// The ramp `clamp((end − d)/(end − start), 0, 1)` for finite `start < end`
    /// (validated by the caller). Either end may lie beyond the geometry range, and
    /// the range may be anything from the smallest `f32` step to `2·f32::MAX`.
    fn ramp(start: f32, end: f32) -> Self::Ramp;

    /// The value of ramp `r` at distance `d`, within 2⁻¹³ (`Q14`) or 10⁻⁶ (the
    /// others) of the exact ramp at that distance (a NaN distance gives 0).
    fn ramp_at(r: &Self::Ramp, d: Self::Geo) -> Self;
}

/// Keeps LLVM from unrolling the calling loop (an empty barrier the unroller
/// counts as a call): on a Cortex-M0 the unrolled body overflows the eight low
/// registers, and short runs spend their time in the remainder loop.
#[inline(always)]
pub(crate) fn no_unroll() {
    core::hint::black_box(());
}

/// A type with an all-zero value known at compile time, so that `const fn`
/// buffers ([`MeshBuffers::new`](crate::render::MeshBuffers::new)) can hold it;
/// a kernel of one's own implements it for its
/// [`Kernel::Vertex`](crate::shade::Kernel::Vertex) (or uses slices through
/// [`MeshMemory`](crate::render::MeshMemory)).
pub trait Zeroed: Copy {
    /// The zero value.
    const ZERO: Self;
}

macro_rules! zeroed_ints {
    ($($t:ty),*) => {$(
        impl Zeroed for $t {
            const ZERO: Self = 0;
        }
    )*};
}
zeroed_ints!(u8, i8, u16, i16, u32, i32);

impl Zeroed for () {
    const ZERO: Self = ();
}

impl<T: Zeroed, const N: usize> Zeroed for [T; N] {
    const ZERO: Self = [T::ZERO; N];
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_tier<S: Scalar>(tol: f32, fixed: bool) {
        let xs = [0.0f32, 0.1, 0.25, 0.5, 0.7, 0.9, 1.0, 1.3];
        for &a in &xs {
            for &b in &xs {
                let p = S::from_f32(a).mul(S::from_f32(b)).to_f32();
                assert!((p - a * b).abs() < tol, "{} {a}*{b}={p}", S::NAME);
            }
            let s = S::from_f32(a).sqrt().to_f32();
            assert!(
                (s - libm::sqrtf(a)).abs() < tol * 4.0,
                "{} sqrt({a})={s}",
                S::NAME
            );
        }
        // saturation instead of wrapping
        let big = S::from_f32(1.0e30);
        assert_eq!(big, S::MAX);
        if fixed {
            assert!(big.add(big) == S::MAX);
            assert!(big.mul(big) == S::MAX);
            assert!(S::from_f32(-1.9).mul(big) == S::from_f32(-2.0));
        }
        assert_eq!(S::from_f32(f32::NAN), S::ZERO);
        assert_eq!(S::ONE.div(S::ZERO), S::MAX);
        assert_eq!(S::ZERO.div(S::ZERO), S::ZERO);
        // unorm rounding
        assert_eq!(S::ONE.to_unorm(8), 255);
        assert_eq!(S::ZERO.to_unorm(8), 0);
        assert_eq!(S::from_f32(-3.0).to_unorm(8), 0);
        assert_eq!(S::from_f32(1.9).to_unorm(5), 31);
        assert_eq!(S::from_f32(0.5).to_unorm(8), 128);
        // powers
        let p = S::from_f32(0.9).powi(16).to_f32();
        assert!(
            (p - libm::powf(0.9, 16.0)).abs() < tol * 16.0,
            "{} {p}",
            S::NAME
        );
        assert_eq!(S::from_f32(0.3).powi(0), S::ONE);
        assert_eq!(S::ZERO.powi(0), S::ONE);
        assert_eq!(S::ZERO.powi(u16::MAX), S::ZERO);
        assert!(S::ONE.powi(u16::MAX).to_f32() > 0.99);
    }

    fn check_normalize<S: Scalar>(tol: f32) {
        let cases = [
            [1.0f32, 0.0, 0.0],
            [0.3, -0.4, 1.2],
            [1.9, 1.9, -1.9],
            [1.0e-3, 2.0e-3, -2.0e-3],
            [0.0, 0.0, 1.0e-4],
        ];
        for c in cases {
            let v = Vec3::new(S::from_f32(c[0]), S::from_f32(c[1]), S::from_f32(c[2]));
            let n = S::normalize(v);
            let (fx, fy, fz) = (v.x.to_f32(), v.y.to_f32(), v.z.to_f32());
            let len = libm::sqrtf(fx * fx + fy * fy + fz * fz);
            for (got, want) in [(n.x, fx / len), (n.y, fy / len), (n.z, fz / len)] {
                assert!((got.to_f32() - want).abs() < tol, "{} {c:?}", S::NAME);
            }
        }
        let z = S::normalize(Vec3::new(S::ZERO, S::ZERO, S::ZERO));
        assert_eq!(z, Vec3::new(S::ZERO, S::ZERO, S::ZERO));
    }

    fn check_geo<S: Scalar>(tol: f32) {
        let cases = [
            [3.0f32, 4.0, 0.0],
            [-100.0, 20.0, 7.5],
            [0.01, 0.0, -0.02],
            [30000.0, 30000.0, 30000.0],
        ];
        for c in cases {
            let v = Vec3::new(
                S::geo_from_f32(c[0]),
                S::geo_from_f32(c[1]),
                S::geo_from_f32(c[2]),
            );
            let (u, d) = S::geo_direction(v);
            // compare with the direction of the quantised input
            let c = [S::geo_to_f32(v.x), S::geo_to_f32(v.y), S::geo_to_f32(v.z)];
            let len = libm::sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            let want_d = len.min(S::geo_to_f32(S::geo_from_f32(1.0e30)));
            assert!(
                (S::geo_to_f32(d) - want_d).abs() <= want_d * 2.0e-4 + 1.0e-4,
                "{} {c:?} d={}",
                S::NAME,
                S::geo_to_f32(d)
            );
            assert!((u.x.to_f32() - c[0] / len).abs() < tol, "{} {c:?}", S::NAME);
            assert!((u.z.to_f32() - c[2] / len).abs() < tol, "{} {c:?}", S::NAME);
        }
        let zero = S::geo_from_f32(0.0);
        let (u, d) = S::geo_direction(Vec3::new(zero, zero, zero));
        assert_eq!(u, Vec3::new(S::ZERO, S::ZERO, S::ZERO));
        assert_eq!(d, zero);
        assert_eq!(S::geo_recip(zero), S::MAX);
    }

    #[test]
    fn q14_basics() {
        check_tier::<Q14<2>>(2.0e-4, true);
        check_normalize::<Q14<2>>(2.0e-3);
        check_geo::<Q14<2>>(4.0e-4);
    }

    #[test]
    fn q30_basics() {
        check_tier::<Q30<3>>(1.0e-6, true);
        check_normalize::<Q30<3>>(1.0e-5);
        check_geo::<Q30<3>>(1.0e-5);
    }

    #[test]
    fn f32_basics() {
        check_tier::<f32>(1.0e-6, false);
        check_normalize::<f32>(1.0e-6);
        check_geo::<f32>(1.0e-6);
        check_tier::<F32Fast>(1.0e-3, false);
        check_normalize::<F32Fast>(3.0e-3);
    }
}
