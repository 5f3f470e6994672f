//! Errors for parameters that cannot describe a valid scene.

use core::fmt;

/// Why a lighting, material, colour or gamma parameter was rejected.
///
/// Constructors that take `f32` validate their input and return this error instead
/// of panicking. Each variant names the offending parameter.
///
/// ```
/// use fixshade::light::DirectionalLight;
/// use fixshade::error::ParamError;
/// let err = DirectionalLight::<f32>::white([0.0, 0.0, 0.0]).unwrap_err();
/// assert_eq!(err, ParamError::ZeroDirection("direction"));
/// assert_eq!(err.to_string(), "direction: zero-length direction");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ParamError {
    /// The named parameter is NaN or infinite.
    NotFinite(&'static str),
    /// The named coefficient or intensity is negative.
    Negative(&'static str),
    /// The named direction has zero (or denormal) length.
    ZeroDirection(&'static str),
    /// The spot cutoff is outside [0°, 90°] (or exactly 180° for "no cone").
    CutoffOutOfRange,
    /// All three attenuation coefficients are zero.
    AttenuationAllZero,
    /// The named exponent is outside its documented range.
    ExponentOutOfRange(&'static str),
    /// The relative index of refraction is not positive.
    RefractiveIndex,
    /// The gamma exponent is outside [1, 4].
    GammaOutOfRange,
    /// The fog end distance is not beyond its start.
    FogRange,
    /// A value the scene needs lies beyond the range of the number tier: the named
    /// term (a light colour times a material colour, with the attenuation's `1/a`
    /// folded in, or a bound of the per-channel sum) must stay below `limit` in
    /// magnitude in tier `tier` ([`Scalar::NAME`](crate::num::Scalar::NAME)). Use a
    /// wider tier (`f32`) for such scenes.
    TierRange {
        /// The term.
        param: &'static str,
        /// The tier's name.
        tier: &'static str,
        /// The largest magnitude the tier holds, rounded up (2 for the fixed tiers).
        limit: u32,
    },
    /// An OpenGL light of another kind than the light type asked for (e.g. a
    /// positional `GL_POSITION` for a [`DirectionalLight`](crate::light::DirectionalLight)).
    LightKind(&'static str),
    /// More lights than the light set holds.
    LightCount {
        /// Lights given.
        lights: usize,
        /// Lights the set holds (its exact length for arrays).
        capacity: usize,
    },
    /// The viewer type does not match `GL_LIGHT_MODEL_LOCAL_VIEWER`.
    Viewer(&'static str),
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(p) => write!(f, "{p}: NaN or infinite"),
            Self::Negative(p) => write!(f, "{p}: negative"),
            Self::ZeroDirection(p) => write!(f, "{p}: zero-length direction"),
            Self::CutoffOutOfRange => f.write_str("spot cutoff: outside 0..=90 degrees (or 180)"),
            Self::AttenuationAllZero => f.write_str("attenuation: all coefficients are zero"),
            Self::ExponentOutOfRange(p) => write!(f, "{p}: exponent out of range"),
            Self::RefractiveIndex => f.write_str("relative refractive index: not positive"),
            Self::GammaOutOfRange => f.write_str("gamma: outside 1..=4"),
            Self::FogRange => f.write_str("fog: end is not beyond start"),
            Self::TierRange { param, tier, limit } => {
                write!(
                    f,
                    "{param}: beyond the range of tier {tier} (magnitude below {limit})"
                )
            }
            Self::LightKind(p) => write!(f, "light kind: {p}"),
            Self::LightCount { lights, capacity } => {
                write!(f, "{lights} lights for a light set of {capacity}")
            }
            Self::Viewer(p) => write!(f, "viewer: {p}"),
        }
    }
}

impl core::error::Error for ParamError {}

/// Checks that `v` is finite.
pub(crate) fn finite(name: &'static str, v: f32) -> Result<f32, ParamError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ParamError::NotFinite(name))
    }
}

/// Checks that `v` is finite and not negative.
pub(crate) fn non_negative(name: &'static str, v: f32) -> Result<f32, ParamError> {
    let v = finite(name, v)?;
    if v < 0.0 {
        Err(ParamError::Negative(name))
    } else {
        Ok(v)
    }
}

/// Checks every component with [`non_negative`].
pub(crate) fn non_negative3(name: &'static str, v: [f32; 3]) -> Result<[f32; 3], ParamError> {
    Ok([
        non_negative(name, v[0])?,
        non_negative(name, v[1])?,
        non_negative(name, v[2])?,
    ])
}

/// Checks that a direction is finite and has a usable length; returns it normalised
/// in `f32` (relative error ≈ 10⁻⁷, below every tier's resolution but Q30's 2⁻³⁰,
/// where it stays under 1 LSB of 8-bit output). `f32`, not `f64`: a firmware that
/// builds a light would otherwise link soft double-precision arithmetic.
pub(crate) fn direction(name: &'static str, v: [f32; 3]) -> Result<[f32; 3], ParamError> {
    for c in v {
        finite(name, c)?;
    }
    // scale by the largest component first so that squaring neither overflows nor
    // underflows for any finite input
    let m = v[0].abs().max(v[1].abs()).max(v[2].abs());
    if !(m > 1.0e-30) {
        return Err(ParamError::ZeroDirection(name));
    }
    let [x, y, z] = v.map(|c| c / m);
    let len = libm::sqrtf(x * x + y * y + z * z);
    Ok([x / len, y / len, z / len])
}
