//! Surface materials: emission, ambient, diffuse (with brilliance), specular,
//! Fresnel angle factor and transmission coefficients.

use crate::error::{finite, finite_all, non_negative, non_negative3, ParamError};
use crate::num::{Exponent, Scalar};

/// A plain `f32` description of a material, shared by the tiers, the OpenGL
/// parameter set and the `f64` reference model. `Default` is OpenGL's default
/// material (ambient 0.2, diffuse 0.8, no specular, no emission).
///
/// ```
/// use fixshade::lighting::{AmbientSource, MaterialDesc};
/// // seed 001: a red object, ka = 0.4 of the object colour, kd = 0.5, ks = 0.5, n = 20
/// let d = MaterialDesc::classic([1.0, 0.0, 0.0], AmbientSource::Object, 0.4, 0.5, 0.5, 20.0);
/// assert_eq!(d.ambient, [0.4, 0.0, 0.0]);
/// assert_eq!(d.specular, [0.5, 0.5, 0.5]); // not tinted by the object colour
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialDesc {
    /// Light the surface emits itself (`GL_EMISSION`).
    pub emission: [f32; 3],
    /// Ambient reflection per channel (`ka·Io` or `ka`).
    pub ambient: [f32; 3],
    /// Diffuse reflection per channel (`kd·Io`: coloured diffuse).
    pub diffuse: [f32; 3],
    /// Specular reflection per channel (`ks`, normally grey: not tinted).
    pub specular: [f32; 3],
    /// Specular exponent `n`, a real number in 0..=65535 (OpenGL: 0..=128).
    pub shininess: f32,
    /// Diffuse brilliance exponent `b` of `(N·L)^b` (1 = Lambert); used by models
    /// with [`Model::BRILLIANCE`](crate::lighting::Model::BRILLIANCE).
    pub brilliance: u8,
    /// Schlick's `F0` for the angle factor `f(β) = F0 + (1 − F0)(1 − cos β)^5`;
    /// used by models with [`Model::FRESNEL`](crate::lighting::Model::FRESNEL).
    pub fresnel_f0: f32,
    /// Transmission coefficient `kst` per channel; used by models with
    /// [`Model::TRANSMISSION`](crate::lighting::Model::TRANSMISSION).
    pub transmission: [f32; 3],
    /// Exponent `n''` of `(T·V)^n''`, a real number in 0..=65535.
    pub transmission_exponent: f32,
    /// Relative index of refraction `n21 = n_inside / n_outside`, in 0.5..=8.
    pub refractive_index: f32,
}

impl Default for MaterialDesc {
    fn default() -> Self {
        Self {
            emission: [0.0; 3],
            ambient: [0.2; 3],
            diffuse: [0.8; 3],
            specular: [0.0; 3],
            shininess: 0.0,
            brilliance: 1,
            fresnel_f0: 1.0,
            transmission: [0.0; 3],
            transmission_exponent: 1.0,
            refractive_index: 1.0,
        }
    }
}

/// What the ambient coefficient multiplies (the two variants of the seeds).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AmbientSource {
    /// `ka·Ia`: the ambient term has the light's colour.
    Light,
    /// `ka·Io`: the ambient term has the object's colour (seed 001, ka ≈ 0.4).
    Object,
}

impl MaterialDesc {
    /// The seeds' classic parameterisation: object colour `Io`, ambient `ka`,
    /// diffuse `kd` (coloured: `kd·Io`), specular `ks` (white), exponent `n`.
    pub fn classic(
        object: [f32; 3],
        ambient: AmbientSource,
        ka: f32,
        kd: f32,
        ks: f32,
        n: f32,
    ) -> Self {
        let ambient = match ambient {
            AmbientSource::Light => [ka; 3],
            AmbientSource::Object => object.map(|c| ka * c),
        };
        Self {
            ambient,
            diffuse: object.map(|c| kd * c),
            specular: [ks; 3],
            shininess: n,
            ..Self::default()
        }
    }
}

/// A validated material in tier `S`.
///
/// The colours stay `f32`: only their products with the lights' colours must
/// fit the tier ([`LightColors`](crate::lighting::LightColors)); a material
/// colour of 3 under a light of 0.5 is exact in every tier.
///
/// ```
/// use fixshade::lighting::{Material, MaterialDesc};
/// use fixshade::num::{Exponent, Q14};
/// let m = Material::<Q14>::new(&MaterialDesc::default()).unwrap();
/// assert_eq!(m.shininess, Exponent::ZERO);
/// let bad = MaterialDesc { shininess: -1.0, ..MaterialDesc::default() };
/// assert!(Material::<Q14>::new(&bad).is_err());
/// // OpenGL allows negative colours; `signed` takes them
/// let neg = MaterialDesc { ambient: [0.4, -0.2, 0.3], ..MaterialDesc::default() };
/// assert!(Material::<Q14>::new(&neg).is_err());
/// assert!(Material::<Q14>::signed(&neg).is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<S> {
    /// `GL_EMISSION`.
    pub emission: [f32; 3],
    /// Ambient reflection.
    pub ambient: [f32; 3],
    /// Diffuse reflection.
    pub diffuse: [f32; 3],
    /// Specular reflection.
    pub specular: [f32; 3],
    /// Specular exponent (real: `GL_SHININESS` 12.8 is 12.8).
    pub shininess: Exponent,
    /// Diffuse brilliance exponent (≥ 1).
    pub brilliance: u8,
    /// Schlick's `F0`.
    pub fresnel_f0: S,
    /// Transmission coefficient.
    pub transmission: [f32; 3],
    /// Transmission exponent.
    pub transmission_exponent: Exponent,
    /// `η = 1/n21` (ratio of refractive indices, outside over inside).
    pub eta: S,
}

impl<S: Scalar> Material<S> {
    /// Validates a description: colours finite and non-negative, exponents in
    /// 0..=65535 (real numbers), brilliance ≥ 1, `F0` in [0, 1], `n21` in 0.5..=8.
    pub fn new(d: &MaterialDesc) -> Result<Self, ParamError> {
        Self::validate(d, false)
    }

    /// [`Material::new`] accepting negative emission, ambient, diffuse and
    /// specular colours as OpenGL does (they subtract light; the output clamps
    /// to [0, 1]); transmission stays non-negative.
    pub fn signed(d: &MaterialDesc) -> Result<Self, ParamError> {
        Self::validate(d, true)
    }

    fn validate(d: &MaterialDesc, signed: bool) -> Result<Self, ParamError> {
        let f0 = non_negative("fresnel F0", d.fresnel_f0)?;
        if f0 > 1.0 {
            return Err(ParamError::ExponentOutOfRange("fresnel F0"));
        }
        if d.brilliance == 0 {
            return Err(ParamError::ExponentOutOfRange("brilliance"));
        }
        let n21 = finite("refractive index", d.refractive_index)?;
        if !(0.5..=8.0).contains(&n21) {
            return Err(ParamError::RefractiveIndex);
        }
        let colour = |name: &'static str, c: [f32; 3]| {
            if signed {
                finite_all(name, c)
            } else {
                non_negative3(name, c)
            }
        };
        Ok(Self {
            emission: colour("emission", d.emission)?,
            ambient: colour("ambient", d.ambient)?,
            diffuse: colour("diffuse", d.diffuse)?,
            specular: colour("specular", d.specular)?,
            shininess: Exponent::new("shininess", d.shininess)?,
            brilliance: d.brilliance,
            fresnel_f0: S::from_f32(f0),
            transmission: non_negative3("transmission", d.transmission)?,
            transmission_exponent: Exponent::new("transmission exponent", d.transmission_exponent)?,
            eta: S::from_f32(1.0 / n21),
        })
    }
}
