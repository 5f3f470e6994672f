//! The float tiers: `f32` (exact functions from `libm`) and [`F32Fast`] (micromath's
//! approximate inverse square root).

use super::Scalar;
use crate::vector::Vec3;

/// The range of the float tiers: conversions from `f32` clamp to ±`F32_LIMIT`, so
/// that the products of the lighting equation (at most four factors) stay finite.
pub const F32_LIMIT: f32 = 1.0e9;

/// The float tier with a fast inverse square root for normalisation and light
/// directions: micromath's bit-trick seed (a few percent off on its own) refined by
/// one Newton step, about 1.8·10⁻³ relative error. Everything else is plain `f32`.
/// It avoids `libm::sqrtf` and a division, which are software on a Cortex-M4F.
///
/// ```
/// use fixshade::num::{F32Fast, Scalar};
/// let x = F32Fast::from_f32(0.5);
/// assert_eq!(x.mul(x).to_f32(), 0.25);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct F32Fast(pub f32);

#[inline(always)]
fn clamp_f32(v: f32) -> f32 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(-F32_LIMIT, F32_LIMIT)
    }
}

#[inline(always)]
fn rsqrt_exact(x: f32) -> f32 {
    1.0 / libm::sqrtf(x)
}

/// micromath's bit-trick seed (about 3.4 % error on its own) refined by one Newton
/// step `y ← y·(1.5 − ½·x·y²)` (about 1.8·10⁻³).
#[inline(always)]
fn rsqrt_micromath(x: f32) -> f32 {
    let y = micromath::F32Ext::invsqrt(x);
    y * (1.5 - 0.5 * x * y * y)
}

macro_rules! float_tier {
    ($ty:ty, $name:expr, $wrap:expr, $get:expr, $rsqrt:path) => {
        impl Scalar for $ty {
            type Geo = f32;
            const ZERO: Self = $wrap(0.0);
            const ONE: Self = $wrap(1.0);
            const MAX: Self = $wrap(F32_LIMIT);
            const NAME: &'static str = $name;

            #[inline(always)]
            fn from_f32(v: f32) -> Self {
                $wrap(clamp_f32(v))
            }
            #[inline(always)]
            fn to_f32(self) -> f32 {
                $get(self)
            }
            #[inline(always)]
            fn add(self, rhs: Self) -> Self {
                $wrap($get(self) + $get(rhs))
            }
            #[inline(always)]
            fn sub(self, rhs: Self) -> Self {
                $wrap($get(self) - $get(rhs))
            }
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                $wrap($get(self) * $get(rhs))
            }
            #[inline]
            fn div(self, rhs: Self) -> Self {
                let (a, b) = ($get(self), $get(rhs));
                if b > 0.0 {
                    $wrap(clamp_f32(a / b))
                } else if a > 0.0 {
                    <Self as Scalar>::MAX
                } else {
                    <Self as Scalar>::ZERO
                }
            }
            #[inline]
            fn sqrt(self) -> Self {
                let x = $get(self);
                if x > 0.0 {
                    $wrap(x * $rsqrt(x))
                } else {
                    <Self as Scalar>::ZERO
                }
            }
            #[inline]
            fn to_unorm(self, bits: u32) -> u32 {
                let max = ((1u32 << bits.clamp(1, 16)) - 1) as f32;
                // `as` maps NaN to 0; the clamp keeps the result within `bits`.
                ($get(self).clamp(0.0, 1.0) * max + 0.5) as u32
            }
            #[inline]
            fn normalize(v: Vec3<Self>) -> Vec3<Self> {
                let (x, y, z) = ($get(v.x), $get(v.y), $get(v.z));
                let s = x * x + y * y + z * z;
                if !(s > f32::MIN_POSITIVE) || s.is_infinite() {
                    return Vec3::new(<Self as Scalar>::ZERO, <Self as Scalar>::ZERO, <Self as Scalar>::ZERO);
                }
                let r = $rsqrt(s);
                Vec3::new($wrap(x * r), $wrap(y * r), $wrap(z * r))
            }

            #[inline(always)]
            fn geo_from_f32(v: f32) -> f32 {
                clamp_f32(v)
            }
            #[inline(always)]
            fn geo_to_f32(g: f32) -> f32 {
                g
            }
            #[inline(always)]
            fn geo_add(a: f32, b: f32) -> f32 {
                a + b
            }
            #[inline(always)]
            fn geo_sub(a: f32, b: f32) -> f32 {
                a - b
            }
            #[inline(always)]
            fn geo_mul(a: f32, b: f32) -> f32 {
                a * b
            }
            #[inline(always)]
            fn geo_to_unit(g: f32) -> Self {
                $wrap(if g > 0.0 { g.min(1.0) } else { 0.0 })
            }
            #[inline]
            fn geo_recip(g: f32) -> Self {
                if g > 1.0 / F32_LIMIT {
                    $wrap(1.0 / g)
                } else {
                    <Self as Scalar>::MAX
                }
            }
            #[inline]
            fn geo_direction(v: Vec3<f32>) -> (Vec3<Self>, f32) {
                let s = v.x * v.x + v.y * v.y + v.z * v.z;
                if !(s > f32::MIN_POSITIVE) || s.is_infinite() {
                    return (Vec3::new(<Self as Scalar>::ZERO, <Self as Scalar>::ZERO, <Self as Scalar>::ZERO), 0.0);
                }
                let r = $rsqrt(s);
                (
                    Vec3::new($wrap(v.x * r), $wrap(v.y * r), $wrap(v.z * r)),
                    s * r,
                )
            }
        }
    };
}

#[inline(always)]
const fn wrap_f32(v: f32) -> f32 {
    v
}
#[inline(always)]
fn get_f32(v: f32) -> f32 {
    v
}
#[inline(always)]
const fn wrap_fast(v: f32) -> F32Fast {
    F32Fast(v)
}
#[inline(always)]
fn get_fast(v: F32Fast) -> f32 {
    v.0
}

float_tier!(f32, "f32", wrap_f32, get_f32, rsqrt_exact);
float_tier!(F32Fast, "f32 (micromath invsqrt)", wrap_fast, get_fast, rsqrt_micromath);
