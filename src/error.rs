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
