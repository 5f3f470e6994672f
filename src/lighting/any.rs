//! Lights described at run time: [`LightDesc`] (the kind and colours as `f32`
//! parameters) and [`AnyLight`], which holds any kind and chooses per light.

use super::light::{Incident, LightColors, LightSource, PointLight, SpotLight};
use super::{Attenuation, ColorTerms, DirectionalLight, Material};
use crate::color::Rgb;
use crate::error::ParamError;
use crate::num::{Mat4, Point3, Scalar, Vec3};

/// Any light kind, chosen at run time (costs a branch per light and point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnyLight<S: Scalar> {
    /// A [`DirectionalLight`].
    Directional(DirectionalLight<S>),
    /// A [`PointLight`].
    Point(PointLight<S>),
    /// A [`SpotLight`].
    Spot(SpotLight<S>),
}

/// `$e` with `$l` bound to the light `$any` (an [`AnyLight`]) holds.
macro_rules! each_kind {
    ($any:expr, $l:ident => $e:expr) => {
        match $any {
            AnyLight::Directional($l) => $e,
            AnyLight::Point($l) => $e,
            AnyLight::Spot($l) => $e,
        }
    };
}

impl<S: Scalar> LightSource<S> for AnyLight<S> {
    const NEEDS_POSITION: bool = true;
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
        each_kind!(self, l => LightSource::prepare(l, material, view))
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        each_kind!(self, l => LightSource::constant_ambient(l))
    }
    #[inline(always)]
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S> {
        match self {
            Self::Directional(l) => l.incident(p),
            Self::Point(l) => l.incident(p),
            Self::Spot(l) => l.incident(p),
        }
    }
    fn color_terms(&self, material: &Material<S>) -> Option<ColorTerms> {
        each_kind!(self, l => LightSource::color_terms(l, material))
    }
    fn transform(&mut self, m: &Mat4) -> Result<(), ParamError> {
        each_kind!(self, l => LightSource::transform(l, m))
    }
}

/// A plain `f32` description of a light, shared by the tiers, the OpenGL parameter
/// set and the `f64` reference model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightDesc {
    /// Where the light is and how it spreads.
    pub kind: LightKind,
    /// Ambient colour.
    pub ambient: [f32; 3],
    /// Diffuse colour.
    pub diffuse: [f32; 3],
    /// Specular colour.
    pub specular: [f32; 3],
}

/// The geometry of a [`LightDesc`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Parallel light from `towards_light`.
    Directional {
        /// Direction from the surface towards the light.
        towards_light: [f32; 3],
    },
    /// A point light with attenuation `[a, b, c]`.
    Point {
        /// Position.
        position: [f32; 3],
        /// Attenuation `[constant, linear, quadratic]`.
        attenuation: [f32; 3],
    },
    /// A spot light.
    Spot {
        /// Position.
        position: [f32; 3],
        /// Direction the spot points to.
        axis: [f32; 3],
        /// Spot exponent `e` of `cos^e φ` (a real number in 0..=65535).
        exponent: f32,
        /// Cone half-angle in degrees, 0..=90.
        cutoff_deg: f32,
        /// Attenuation `[constant, linear, quadratic]`.
        attenuation: [f32; 3],
    },
}

impl<S: Scalar> AnyLight<S> {
    /// Builds and validates a light from its description (non-negative colours).
    pub fn new(d: &LightDesc) -> Result<Self, ParamError> {
        Self::with_colors(d, LightColors::new(d.ambient, d.diffuse, d.specular)?)
    }

    /// [`AnyLight::new`] with colours of any sign ([`LightColors::signed`]).
    pub fn signed(d: &LightDesc) -> Result<Self, ParamError> {
        Self::with_colors(d, LightColors::signed(d.ambient, d.diffuse, d.specular)?)
    }

    /// The light of `d`'s kind with the validated `colors`.
    pub fn with_colors(d: &LightDesc, colors: LightColors<S>) -> Result<Self, ParamError> {
        Ok(match d.kind {
            LightKind::Directional { towards_light } => {
                Self::Directional(DirectionalLight::new(towards_light, colors)?)
            }
            LightKind::Point {
                position,
                attenuation: [a, b, c],
            } => Self::Point(PointLight::new(
                position,
                Attenuation::new::<S>(a, b, c)?,
                colors,
            )?),
            LightKind::Spot {
                position,
                axis,
                exponent,
                cutoff_deg,
                attenuation: [a, b, c],
            } => Self::Spot(SpotLight::new(
                position,
                axis,
                exponent,
                cutoff_deg,
                Attenuation::new::<S>(a, b, c)?,
                colors,
            )?),
        })
    }
}
