//! Where the eye is, and how light fades with viewing distance (fog).

use crate::color::Rgb;
use crate::error::{finite, finite_all, ParamError};
use crate::num::{point_from_f32, point_sub, Point3, Scalar, Vec3};

/// Where the eye is.
pub trait Viewer<S: Scalar>: Copy + core::fmt::Debug {
    /// Whether the view vector depends on the surface position.
    const NEEDS_POSITION: bool;
    /// The constant view direction, for a viewer at infinity.
    fn constant_dir(&self) -> Option<Vec3<S>>;
    /// The unit vector from `p` towards the eye and the viewing distance.
    fn view(&self, p: &Point3<S>) -> (Vec3<S>, S::Geo);
}

/// A viewer at infinity: `V` is constant (cheaper; OpenGL's default). The viewing
/// distance for fog is the depth `−(P·V)` measured from the plane through the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InfiniteViewer<S: Scalar> {
    dir: Vec3<S>,
    dir_geo: Point3<S>,
}

impl<S: Scalar> InfiniteViewer<S> {
    /// A viewer in direction `towards_viewer` from the scene (normalised here).
    pub fn new(towards_viewer: [f32; 3]) -> Result<Self, ParamError> {
        let d = crate::error::direction("view direction", towards_viewer)?;
        Ok(Self {
            dir: Vec3::from_f32(d),
            dir_geo: point_from_f32::<S>(d),
        })
    }
}

impl<S: Scalar> Default for InfiniteViewer<S> {
    /// Looking down −z: `V = (0, 0, 1)`.
    fn default() -> Self {
        Self {
            dir: Vec3::new(S::ZERO, S::ZERO, S::ONE),
            dir_geo: point_from_f32::<S>([0.0, 0.0, 1.0]),
        }
    }
}

impl<S: Scalar> Viewer<S> for InfiniteViewer<S> {
    const NEEDS_POSITION: bool = false;
    #[inline(always)]
    fn constant_dir(&self) -> Option<Vec3<S>> {
        Some(self.dir)
    }
    #[inline(always)]
    fn view(&self, p: &Point3<S>) -> (Vec3<S>, S::Geo) {
        let d = &self.dir_geo;
        let along = S::geo_add(
            S::geo_add(S::geo_mul(p.x, d.x), S::geo_mul(p.y, d.y)),
            S::geo_mul(p.z, d.z),
        );
        (self.dir, S::geo_sub(S::geo_from_f32(0.0), along))
    }
}

/// A viewer at a point (OpenGL's `GL_LIGHT_MODEL_LOCAL_VIEWER`): `V` is computed per
/// surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalViewer<S: Scalar> {
    eye: Point3<S>,
}

impl<S: Scalar> LocalViewer<S> {
    /// The eye at `eye` (scene units). Errors: non-finite position.
    pub fn new(eye: [f32; 3]) -> Result<Self, ParamError> {
        Ok(Self {
            eye: point_from_f32::<S>(finite_all("eye", eye)?),
        })
    }
}

impl<S: Scalar> Viewer<S> for LocalViewer<S> {
    const NEEDS_POSITION: bool = true;
    #[inline(always)]
    fn constant_dir(&self) -> Option<Vec3<S>> {
        None
    }
    #[inline(always)]
    fn view(&self, p: &Point3<S>) -> (Vec3<S>, S::Geo) {
        S::geo_direction(point_sub::<S>(self.eye, *p))
    }
}

/// Depth cueing: how the light-dependent part fades with viewing distance.
pub trait FogModel<S: Scalar>: Copy + core::fmt::Debug {
    /// Whether the fog needs the viewing distance.
    const NEEDS_DISTANCE: bool;
    /// `f·direct + (1 − f)·fog_colour` at viewing distance `d`.
    fn apply(&self, direct: Rgb<S>, d: S::Geo) -> Rgb<S>;
    /// `f·c` alone (for a part of the light that is faded but carries no fog
    /// colour: the secondary colour of [`Lighting::shade_parts`](super::Lighting::shade_parts)). The default is
    /// `apply(c) − apply(0)`.
    #[inline(always)]
    fn fade(&self, c: Rgb<S>, d: S::Geo) -> Rgb<S> {
        self.apply(c, d).sub(self.apply(Rgb::BLACK, d))
    }
}

/// No fog.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoFog;

impl<S: Scalar> FogModel<S> for NoFog {
    const NEEDS_DISTANCE: bool = false;
    #[inline(always)]
    fn apply(&self, direct: Rgb<S>, _d: S::Geo) -> Rgb<S> {
        direct
    }
    #[inline(always)]
    fn fade(&self, c: Rgb<S>, _d: S::Geo) -> Rgb<S> {
        c
    }
}

/// Linear depth cueing (seed 004's atmospheric attenuation): the diffuse and
/// specular light fades towards `colour` between `start` and `end`:
/// `f = clamp((end − d)/(end − start), 0, 1)`.
///
/// # Representation and extremes
///
/// The ramp is stored per tier ([`Scalar::ramp`]), so any finite `start < end`
/// works: ranges of `f32::MAX` and more (`−f32::MAX…f32::MAX` is half fog near
/// 0), ends beyond the geometry range (`0…200 000` fades over the fixed tiers'
/// whole range), ranges down to one `f32` step (a step at `end`). The fixed tiers
/// hold the slope as mantissa and exponent, evaluated from the point of the
/// geometry range nearest to `end`; `f` is within 2⁻¹³ (`Q14`) or 10⁻⁶ (the
/// others) of the exact ramp at the tier's distance, plus the distance's own
/// rounding (2⁻¹⁶ units fixed, 2⁻²⁴ relative `f32`) times `1/(end − start)`. A
/// NaN distance (non-finite positions) is full fog.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearFog<S: Scalar> {
    ramp: S::Ramp,
    color: Rgb<S>,
}

impl<S: Scalar> LinearFog<S> {
    /// Fog from `start` to `end` (scene units). Errors: non-finite values,
    /// `end ≤ start`, a negative colour.
    pub fn new(start: f32, end: f32, color: [f32; 3]) -> Result<Self, ParamError> {
        let (s, e) = (finite("fog start", start)?, finite("fog end", end)?);
        if e <= s {
            return Err(ParamError::FogRange);
        }
        Ok(Self {
            ramp: S::ramp(s, e),
            color: Rgb::try_from_f32("fog colour", color)?,
        })
    }
}

impl<S: Scalar> FogModel<S> for LinearFog<S> {
    const NEEDS_DISTANCE: bool = true;
    #[inline(always)]
    fn apply(&self, direct: Rgb<S>, d: S::Geo) -> Rgb<S> {
        self.color.lerp(direct, S::ramp_at(&self.ramp, d))
    }
    #[inline(always)]
    fn fade(&self, c: Rgb<S>, d: S::Geo) -> Rgb<S> {
        c.scale(S::ramp_at(&self.ramp, d))
    }
}
