//! The float tiers: `f32` (exact functions from `libm`) and [`F32Fast`] (micromath's
//! approximate inverse square root).

use super::rsqrt::{rsqrt_exact, rsqrt_micromath};
use super::Scalar;
use crate::num::Vec3;

/// The linear fog ramp of the float tiers (see [`Scalar::ramp`]):
/// `clamp((end − d)·scale·inv, 0, 1)` with `end` as given and
/// `scale·inv = 1/(end − start)` formed without overflow: a range beyond `f32::MAX`
/// is halved first, and a range below 2⁻¹⁰⁰ (whose inverse may exceed `f32::MAX`)
/// is scaled by `scale = 2¹⁰⁰` (otherwise 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RampF32 {
    end: f32,
    scale: f32,
    inv: f32,
}

impl RampF32 {
    fn new(start: f32, end: f32) -> Self {
        const TINY: f32 = 7.888_609e-31; // 2^-100
        const HUGE: f32 = 1.267_650_6e30; // 2^100
        let r = end - start;
        let (scale, inv) = if !r.is_finite() {
            (1.0, 0.5 / (end * 0.5 - start * 0.5))
        } else if r < TINY {
            (HUGE, 1.0 / (r * HUGE))
        } else {
            (1.0, 1.0 / r)
        };
        Self { end, scale, inv }
    }

    #[inline(always)]
    fn at(&self, d: f32) -> f32 {
        // (end − d) is finite for |d| ≤ F32_LIMIT and `scale` may take it to ±∞, which
        // clamps; an infinite or NaN distance (a position given directly as `Vec3`)
        // gives 1 or 0, never NaN
        let x = (self.end - d) * self.scale * self.inv;
        unit(x)
    }
}

/// `1/(a + b·d + c·d²)` in `f32`: the distance is made finite and non-negative first
/// (NaN to 0, ∞ to `f32::MAX`), so that no product is `0·∞`; an infinite sum gives 0.
#[inline(always)]
fn inv_quadratic(k: &[f32; 3], d: f32) -> Option<f32> {
    // comparisons, not `f32::min`/`max` (library calls on a Cortex-M4F)
    let d = if d > f32::MAX {
        f32::MAX
    } else if d > 0.0 {
        d
    } else {
        0.0
    };
    let [a, b, c] = *k;
    let q = a + d * (b + c * d);
    if q > 1.0 / F32_LIMIT {
        Some(1.0 / q)
    } else {
        None
    }
}

/// The range of the float tiers: conversions from `f32` clamp to ±`F32_LIMIT`, so
/// that the products of the lighting equation (at most four factors) stay finite.
pub(crate) const F32_LIMIT: f32 = 1.0e9;

/// The float tier with a fast inverse square root (no `libm::sqrtf` or
/// division, software on a Cortex-M4F): micromath's seed (3.4 % off) and
/// `NEWTON` steps `y ← y·(1.5 − ½·x·y²)`, about 1.8·10⁻³ relative error with
/// one, 4.7·10⁻⁶ with two. Everything else is plain `f32`.
///
/// ```
/// use fixshade::num::{F32Fast, Scalar};
/// let x = F32Fast::<2>::from_f32(0.5);
/// assert_eq!(x.mul(x).to_f32(), 0.25);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct F32Fast<const NEWTON: u8 = 2>(pub f32);

#[inline(always)]
fn clamp_f32(v: f32) -> f32 {
    // explicit comparisons rather than `f32::clamp`, whose `min <= max` assertion
    // can survive in a size-optimised build
    if v > F32_LIMIT {
        F32_LIMIT
    } else if v < -F32_LIMIT {
        -F32_LIMIT
    } else if v.is_nan() {
        0.0
    } else {
        v
    }
}

/// `x` limited to [0, 1], NaN to 0 (comparisons: `f32::clamp` has a panicking
/// assertion and `f32::min` is a library call on a Cortex-M4F).
#[inline(always)]
fn unit(x: f32) -> f32 {
    // two independent conditional moves (as `f32::clamp` compiles), not a chain of
    // branches
    let mut x = x;
    if !(x > 0.0) {
        x = 0.0;
    }
    if x > 1.0 {
        x = 1.0;
    }
    x
}

/// `(v/|v|, |v|², 1/|v|)` with the inverse square root `rsqrt`; `None` when `|v|²`
/// is below `f32::MIN_POSITIVE`, infinite or NaN.
#[inline(always)]
fn unit_vector(v: [f32; 3], rsqrt: impl Fn(f32) -> f32) -> Option<([f32; 3], f32, f32)> {
    let s = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if !(s > f32::MIN_POSITIVE) || s.is_infinite() {
        return None;
    }
    let r = rsqrt(s);
    Some((v.map(|c| c * r), s, r))
}

/// The components of `v` in a float tier (`wrap`).
#[inline(always)]
fn vec3<T>(v: [f32; 3], wrap: impl Fn(f32) -> T) -> Vec3<T> {
    let [x, y, z] = v;
    Vec3::new(wrap(x), wrap(y), wrap(z))
}

macro_rules! float_tier {
    ([$($gen:tt)*] $ty:ty, $name:expr, $wrap:expr, $get:expr, $rsqrt:expr, $refine:expr) => {
        impl<$($gen)*> Scalar for $ty {
            type Geo = f32;
            type Ramp = RampF32;
            const ZERO: Self = $wrap(0.0);
            const ONE: Self = $wrap(1.0);
            const MAX: Self = $wrap(F32_LIMIT);
            const FLOAT: bool = true;
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
            #[inline(always)]
            fn twice_mul_sub(self, b: Self, c: Self) -> Self {
                $wrap(2.0 * $get(self) * $get(b) - $get(c))
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
                let max = ((1u32 << bits.max(1).min(16)) - 1) as f32;
                // NaN fails `> 0` and becomes 0; the result stays within `bits`.
                (unit($get(self)) * max + 0.5) as u32
            }
            #[inline]
            fn normalize(v: Vec3<Self>) -> Vec3<Self> {
                let v = [$get(v.x), $get(v.y), $get(v.z)];
                vec3(unit_vector(v, $rsqrt).map_or([0.0; 3], |(u, ..)| u), $wrap)
            }

            const ATTR_FRAC: u32 = 26;
            #[inline(always)]
            fn to_attr(self) -> i32 {
                // `as` saturates (and maps NaN to 0)
                ($get(self) * (1u32 << 26) as f32) as i32
            }
            #[inline(always)]
            fn from_attr(a: i32) -> Self {
                $wrap(a as f32 * (1.0 / (1u32 << 26) as f32))
            }
            #[inline(always)]
            fn geo_to_attr(g: f32) -> i32 {
                (g * 65536.0) as i32
            }
            #[inline(always)]
            fn geo_from_attr(a: i32) -> f32 {
                a as f32 * (1.0 / 65536.0)
            }

            #[inline]
            fn normalize_precise(v: Vec3<Self>) -> Vec3<Self> {
                let v = [$get(v.x), $get(v.y), $get(v.z)];
                vec3(unit_vector(v, rsqrt_exact).map_or([0.0; 3], |(u, ..)| u), $wrap)
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
                $wrap(unit(g))
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
            fn geo_inv_quadratic(k: &[f32; 3], d: f32) -> Self {
                match inv_quadratic(k, d) {
                    Some(f) => $wrap(f),
                    None => <Self as Scalar>::MAX,
                }
            }
            fn ramp(start: f32, end: f32) -> RampF32 {
                RampF32::new(start, end)
            }
            #[inline]
            fn ramp_at(r: &RampF32, d: f32) -> Self {
                $wrap(r.at(d))
            }
            #[inline]
            fn geo_direction(v: Vec3<f32>) -> (Vec3<Self>, f32) {
                let Some((u, s, r)) = unit_vector([v.x, v.y, v.z], $rsqrt) else {
                    return (vec3([0.0; 3], $wrap), 0.0);
                };
                let d = s * r;
                // The fog ramp scales a distance error by 1/(end − start): with an
                // approximate r (relative error e), one step d·(3 − d·r)/2 takes the
                // length's error to e² (2·10⁻¹¹ with two Newton steps), for four
                // operations per light or local viewer.
                let d = if $refine { d * (1.5 - 0.5 * d * r) } else { d };
                (vec3(u, $wrap), d)
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

// `f32`'s lengths are exact to 10⁻⁷: no refinement of distances.
float_tier!([] f32, "f32", wrap_f32, get_f32, rsqrt_exact, false);
float_tier!(
    [const N: u8] F32Fast<N>,
    match N {
        0 => "f32 (micromath invsqrt)",
        1 => "f32 (micromath + 1 Newton)",
        2 => "f32 (micromath + 2 Newton)",
        _ => "f32 (micromath + 3+ Newton)",
    },
    F32Fast::<N>,
    |v: F32Fast<N>| v.0,
    rsqrt_micromath::<N>,
    true
);
