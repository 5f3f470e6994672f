//! Light sources: directional, point (with distance attenuation) and spot lights,
//! and sets of them.
//!
//! Each light kind is its own type, so a scene whose lights are all directional
//! compiles to code without attenuation or spot-cone evaluation. [`AnyLight`] mixes
//! kinds at run time; arrays, `heapless::Vec`s and tuples of lights are light sets.

use crate::color::Rgb;
use crate::error::{direction, finite, non_negative, ParamError};
use crate::material::Material;
use crate::num::{GeoScalar, Scalar};
use crate::vector::{point_from_f32, point_sub, Point3, Vec3};

/// The colours a light emits into each term (OpenGL's `GL_AMBIENT`, `GL_DIFFUSE`,
/// `GL_SPECULAR` light parameters), linear RGB, non-negative.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightColors<S> {
    /// Added to the ambient term (`Ia`), scaled by the material's ambient colour.
    pub ambient: Rgb<S>,
    /// Scaled by the material's diffuse colour and `N·L` (`Il` of the diffuse term).
    pub diffuse: Rgb<S>,
    /// Scaled by the material's specular colour and the highlight (`Il` of the
    /// specular term; also drives the transmission term).
    pub specular: Rgb<S>,
}

impl<S: Scalar> LightColors<S> {
    /// Validated colours: NaN, infinite or negative channels are rejected.
    pub fn new(
        ambient: [f32; 3],
        diffuse: [f32; 3],
        specular: [f32; 3],
    ) -> Result<Self, ParamError> {
        Ok(Self {
            ambient: Rgb::try_from_f32("light ambient", ambient)?,
            diffuse: Rgb::try_from_f32("light diffuse", diffuse)?,
            specular: Rgb::try_from_f32("light specular", specular)?,
        })
    }

    /// A light of colour `c` in the diffuse and specular terms, no ambient
    /// (the seeds' `Il`).
    pub fn rgb(c: [f32; 3]) -> Result<Self, ParamError> {
        Self::new([0.0; 3], c, c)
    }

    /// A white light of intensity 1 (no ambient), like OpenGL's `GL_LIGHT0`.
    pub fn white() -> Self {
        Self {
            ambient: Rgb::BLACK,
            diffuse: Rgb::WHITE,
            specular: Rgb::WHITE,
        }
    }
}

/// Light colours multiplied by a material's colours once, when a
/// [`Lighting`](crate::lighting::Lighting) is built, so the per-pixel work is one
/// product per channel and term.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Prepared<S> {
    /// `La ∘ ka`.
    pub ambient: Rgb<S>,
    /// `Ld ∘ kd`.
    pub diffuse: Rgb<S>,
    /// `Ls ∘ ks`.
    pub specular: Rgb<S>,
    /// `Ls ∘ kst` (transmission).
    pub transmission: Rgb<S>,
    /// The halfway vector `H = (L + V)/|L + V|` when both L and V are constant
    /// (directional light, viewer at infinity).
    pub half: Option<Vec3<S>>,
}

impl<S: Scalar> Prepared<S> {
    /// For a point or spot light: a constant attenuation `1/a` (b = c = 0) is
    /// folded into the colours here, once, instead of per point.
    fn positional(c: &LightColors<S>, m: &Material<S>, att: &Attenuation<S::Geo>) -> Self {
        let mut p = Self::new(c, m, None, None);
        if att.constant {
            let k = att.factor::<S>(S::geo_from_f32(0.0));
            p.ambient = p.ambient.scale(k);
            p.diffuse = p.diffuse.scale(k);
            p.specular = p.specular.scale(k);
            p.transmission = p.transmission.scale(k);
        }
        p
    }

    fn new(c: &LightColors<S>, m: &Material<S>, l: Option<Vec3<S>>, v: Option<Vec3<S>>) -> Self {
        Self {
            ambient: c.ambient.mul(m.ambient),
            diffuse: c.diffuse.mul(m.diffuse),
            specular: c.specular.mul(m.specular),
            transmission: c.specular.mul(m.transmission),
            half: match (l, v) {
                (Some(l), Some(v)) => Some(S::normalize_precise(l.add(v))),
                _ => None,
            },
        }
    }
}

/// What one light contributes at one surface point.
#[derive(Clone, Copy, Debug)]
pub struct Incident<'a, S> {
    /// Unit vector from the surface point towards the light.
    pub l: Vec3<S>,
    /// `att · spot`, the factor on the whole contribution of this light; `None`
    /// means exactly 1 (no multiplication is done).
    pub scale: Option<S>,
    /// Whether this light's ambient term is added per point. `false` for lights
    /// whose ambient is constant: it is folded into the scene's base colour.
    pub ambient_per_point: bool,
    /// The light's colours times the material's.
    pub colors: &'a Prepared<S>,
}

/// One light source.
pub trait LightSource<S: Scalar> {
    /// Whether the light needs the surface position (point and spot lights).
    const NEEDS_POSITION: bool;
    /// Multiplies colours with the material and precomputes what is constant for a
    /// viewer direction `view` (`None` for a local viewer).
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>);
    /// The ambient contribution that does not depend on the surface point, if any.
    fn constant_ambient(&self) -> Option<Rgb<S>>;
    /// The light arriving at surface point `p`.
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S>;
}

/// What receives each light's [`Incident`] from [`LightSet::for_each`] (a trait
/// rather than a closure so that the per-light work is always inlined into the
/// per-pixel loop; closures are also visitors).
pub trait IncidentVisitor<S: Scalar> {
    /// Called once per light.
    fn visit(&mut self, inc: Incident<'_, S>);
}

impl<S: Scalar, F: FnMut(Incident<'_, S>)> IncidentVisitor<S> for F {
    #[inline(always)]
    fn visit(&mut self, inc: Incident<'_, S>) {
        self(inc)
    }
}

/// A set of lights, summed by the lighting equation.
///
/// Implemented for every light type, for arrays `[L; K]`, for `heapless::Vec<L, K>`
/// (a run-time count up to a compile-time capacity) and for tuples of up to four
/// light sets (mixed kinds without run-time dispatch).
pub trait LightSet<S: Scalar> {
    /// Whether any light needs the surface position.
    const NEEDS_POSITION: bool;
    /// See [`LightSource::prepare`].
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>);
    /// The sum of the lights' point-independent ambient contributions.
    fn constant_ambient(&self) -> Rgb<S>;
    /// Hands each light's [`Incident`] at `p` to `visitor`.
    fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V);
}

macro_rules! light_set_for_source {
    ($($ty:ident),*) => {$(
        impl<S: Scalar> LightSet<S> for $ty<S> {
            const NEEDS_POSITION: bool = <Self as LightSource<S>>::NEEDS_POSITION;
            #[inline]
            fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
                LightSource::prepare(self, material, view)
            }
            #[inline]
            fn constant_ambient(&self) -> Rgb<S> {
                LightSource::constant_ambient(self).unwrap_or(Rgb::BLACK)
            }
            #[inline(always)]
            fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V) {
                visitor.visit(self.incident(p))
            }
        }
    )*};
}
light_set_for_source!(DirectionalLight, PointLight, SpotLight, AnyLight);

/// `LightSet` for a container of light sets that iterates by reference.
macro_rules! light_set_for_container {
    ($($ty:ty),*) => {$(
        impl<S: Scalar, L: LightSet<S>, const K: usize> LightSet<S> for $ty {
            const NEEDS_POSITION: bool = L::NEEDS_POSITION;
            fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
                self.iter_mut().for_each(|l| l.prepare(material, view));
            }
            fn constant_ambient(&self) -> Rgb<S> {
                self.iter().fold(Rgb::BLACK, |a, l| a.add(l.constant_ambient()))
            }
            #[inline(always)]
            fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V) {
                for l in self.iter() {
                    l.for_each(p, visitor);
                }
            }
        }
    )*};
}
light_set_for_container!([L; K], heapless::Vec<L, K>);

macro_rules! light_set_tuple {
    ($($name:ident $idx:tt),*) => {
        impl<S: Scalar, $($name: LightSet<S>),*> LightSet<S> for ($($name,)*) {
            const NEEDS_POSITION: bool = false $(|| $name::NEEDS_POSITION)*;
            fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
                $(self.$idx.prepare(material, view);)*
            }
            fn constant_ambient(&self) -> Rgb<S> {
                Rgb::BLACK $(.add(self.$idx.constant_ambient()))*
            }
            #[inline(always)]
            fn for_each<V: IncidentVisitor<S>>(&self, p: &Point3<S>, visitor: &mut V) {
                $(self.$idx.for_each(p, visitor);)*
            }
        }
    };
}
light_set_tuple!(A 0, B 1);
light_set_tuple!(A 0, B 1, C 2);
light_set_tuple!(A 0, B 1, C 2, D 3);

/// A light at infinity: parallel rays, constant direction, no attenuation
/// (homogeneous `w = 0`).
///
/// ```
/// use fixshade::light::{DirectionalLight, LightColors};
/// use fixshade::num::Q14;
/// let sun = DirectionalLight::<Q14>::new([1.0, 1.0, 1.0], LightColors::white()).unwrap();
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight<S> {
    dir: Vec3<S>,
    colors: LightColors<S>,
    pre: Prepared<S>,
}

impl<S: Scalar> DirectionalLight<S> {
    /// A light shining from `towards_light` (the direction from the surface to the
    /// light; normalised here). Errors: non-finite or zero-length direction.
    pub fn new(towards_light: [f32; 3], colors: LightColors<S>) -> Result<Self, ParamError> {
        let d = direction("direction", towards_light)?;
        Ok(Self {
            dir: Vec3::from_f32(d),
            colors,
            pre: Prepared::default(),
        })
    }

    /// A white light of intensity 1 from `towards_light`.
    pub fn white(towards_light: [f32; 3]) -> Result<Self, ParamError> {
        Self::new(towards_light, LightColors::white())
    }

    /// The unit direction towards the light.
    pub fn direction(&self) -> Vec3<S> {
        self.dir
    }

    /// The light's colours times the material's, and the halfway vector, as set by
    /// the last [`LightSource::prepare`].
    pub fn prepared(&self) -> &Prepared<S> {
        &self.pre
    }
}

impl<S: Scalar> LightSource<S> for DirectionalLight<S> {
    const NEEDS_POSITION: bool = false;
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
        self.pre = Prepared::new(&self.colors, material, Some(self.dir), view);
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        Some(self.pre.ambient)
    }
    #[inline(always)]
    fn incident(&self, _p: &Point3<S>) -> Incident<'_, S> {
        Incident {
            l: self.dir,
            scale: None,
            ambient_per_point: false,
            colors: &self.pre,
        }
    }
}

/// Distance attenuation `1/(a + b·d + c·d²)` (OpenGL's constant, linear and
/// quadratic attenuation). `a = 1, b = c = 0` is no attenuation; pure `1/d²` is
/// the physical case.
///
/// # Representation
///
/// The coefficients keep the relative precision of the `f32` they are given as, in
/// the form the geometry type stores them ([`GeoScalar::inv_quadratic`]): `f32` for
/// the float tiers; for the fixed tiers (Q16.16 distances) the exact 24-bit
/// mantissa and exponent of each (a 16-bit mantissa for `Q14`), multiplied with the
/// normalised distance in 32-bit (`Q14`) or 64-bit (`Q30`) integer arithmetic. So
/// `c = 10⁻⁶` at `d = 300` counts (it was 0 in Q16.16), for every legal coefficient
/// and every distance of the geometry range (see [`Scalar::geo_inv_quadratic`] for
/// the error: far below 1 LSB of 8-bit output).
///
/// # Extremes
///
/// - `d = 0` gives `1/a`; a factor beyond the tier's range saturates: the fixed
///   tiers hold factors below 2 (`a + b·d + c·d² ≥ ½`), the float tiers up to 10⁹.
///   With `a = 0` (pure `1/d²`) the factor therefore saturates close to the light.
/// - Very far lights give factors that round to 0; lengths beyond the geometry range
///   (32768 units for the fixed tiers) saturate there.
/// - Negative distances (only reachable through [`Attenuation::factor`]) count as 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attenuation<G: GeoScalar> {
    k: G::InvQuadratic,
    /// `b = c = 0`: the factor is the constant `1/a`, folded into the colours.
    constant: bool,
}

impl<G: GeoScalar> Attenuation<G> {
    /// Validated coefficients: finite, non-negative, not all zero.
    pub fn new<S: Scalar<Geo = G>>(a: f32, b: f32, c: f32) -> Result<Self, ParamError> {
        let a = non_negative("attenuation constant", a)?;
        let b = non_negative("attenuation linear", b)?;
        let c = non_negative("attenuation quadratic", c)?;
        if a == 0.0 && b == 0.0 && c == 0.0 {
            return Err(ParamError::AttenuationAllZero);
        }
        Ok(Self {
            k: G::inv_quadratic(a, b, c),
            constant: b == 0.0 && c == 0.0,
        })
    }

    /// No attenuation (`a = 1, b = c = 0`).
    pub fn none<S: Scalar<Geo = G>>() -> Self {
        Self {
            k: G::inv_quadratic(1.0, 0.0, 0.0),
            constant: true,
        }
    }

    /// The attenuation factor `1/(a + b·d + c·d²)` at distance `d`
    /// ([`Scalar::geo_inv_quadratic`]).
    #[inline(always)]
    pub fn factor<S: Scalar<Geo = G>>(&self, d: G) -> S {
        S::geo_inv_quadratic(&self.k, d)
    }
}

/// A point light at a position, with distance attenuation.
///
/// ```
/// use fixshade::light::{Attenuation, LightColors, PointLight};
/// use fixshade::num::Q14;
/// let att = Attenuation::new::<Q14>(1.0, 0.0, 0.05).unwrap();
/// let bulb = PointLight::<Q14>::new([0.0, 4.0, 3.0], att, LightColors::white()).unwrap();
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight<S: Scalar> {
    pos: Point3<S>,
    att: Attenuation<S::Geo>,
    colors: LightColors<S>,
    pre: Prepared<S>,
}

impl<S: Scalar> PointLight<S> {
    /// A point light at `position` (scene units; saturates beyond the geometry range).
    /// Errors: a non-finite position.
    pub fn new(
        position: [f32; 3],
        attenuation: Attenuation<S::Geo>,
        colors: LightColors<S>,
    ) -> Result<Self, ParamError> {
        for c in position {
            finite("position", c)?;
        }
        Ok(Self {
            pos: point_from_f32::<S>(position),
            att: attenuation,
            colors,
            pre: Prepared::default(),
        })
    }
}

impl<S: Scalar> LightSource<S> for PointLight<S> {
    const NEEDS_POSITION: bool = true;
    fn prepare(&mut self, material: &Material<S>, _view: Option<Vec3<S>>) {
        self.pre = Prepared::positional(&self.colors, material, &self.att);
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        self.att.constant.then_some(self.pre.ambient)
    }
    #[inline(always)]
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S> {
        // L = (P_light − P)/d
        let (l, d) = S::geo_direction(point_sub::<S>(self.pos, *p));
        let varying = !self.att.constant;
        Incident {
            l,
            scale: varying.then(|| self.att.factor::<S>(d)),
            ambient_per_point: varying,
            colors: &self.pre,
        }
    }
}

/// A spot light: a point light whose intensity is `cos^e φ` inside a cone around
/// its axis and zero outside (φ is the angle between the axis and the ray from
/// the light; `cos φ = s·(−L)`).
///
/// At extremes: a cutoff of 90° is a hemisphere; exponent 0 is a sharp-edged cone
/// of uniform intensity; the point exactly at the light has `L = 0`, so only the
/// ambient term survives there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight<S: Scalar> {
    pos: Point3<S>,
    axis: Vec3<S>,
    cos_cutoff: S,
    exponent: u16,
    att: Attenuation<S::Geo>,
    colors: LightColors<S>,
    pre: Prepared<S>,
}

impl<S: Scalar> SpotLight<S> {
    /// A spot light at `position` pointing along `axis`, with `exponent` (rounded to
    /// an integer in 0..=65535) and `cutoff_deg` in 0..=90 degrees (OpenGL's
    /// `GL_SPOT_CUTOFF`; 180 means no cone: use a [`PointLight`] instead).
    ///
    /// Errors: non-finite position, zero or non-finite axis, exponent negative or
    /// above 65535, cutoff outside 0..=90.
    pub fn new(
        position: [f32; 3],
        axis: [f32; 3],
        exponent: f32,
        cutoff_deg: f32,
        attenuation: Attenuation<S::Geo>,
        colors: LightColors<S>,
    ) -> Result<Self, ParamError> {
        for c in position {
            finite("position", c)?;
        }
        let axis = direction("spot axis", axis)?;
        let exponent = exponent_u16("spot exponent", exponent)?;
        let cutoff = finite("spot cutoff", cutoff_deg).map_err(|_| ParamError::CutoffOutOfRange)?;
        if !(0.0..=90.0).contains(&cutoff) {
            return Err(ParamError::CutoffOutOfRange);
        }
        Ok(Self {
            pos: point_from_f32::<S>(position),
            axis: Vec3::from_f32(axis),
            cos_cutoff: S::from_f32(libm::cosf(cutoff.to_radians())),
            exponent,
            att: attenuation,
            colors,
            pre: Prepared::default(),
        })
    }
}

/// Validates an exponent given as `f32`: finite, in 0..=65535, rounded.
pub(crate) fn exponent_u16(name: &'static str, e: f32) -> Result<u16, ParamError> {
    let e = finite(name, e)?;
    if !(0.0..=65535.0).contains(&e) {
        return Err(ParamError::ExponentOutOfRange(name));
    }
    Ok(libm::roundf(e) as u16)
}

impl<S: Scalar> LightSource<S> for SpotLight<S> {
    const NEEDS_POSITION: bool = true;
    fn prepare(&mut self, material: &Material<S>, _view: Option<Vec3<S>>) {
        self.pre = Prepared::positional(&self.colors, material, &self.att);
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        None
    }
    #[inline(always)]
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S> {
        let (l, d) = S::geo_direction(point_sub::<S>(self.pos, *p));
        // cos φ = s·(−L); spot = cos^e φ inside the cone, 0 outside (a cosine that
        // corrects the lengths of s and L, which cos^e φ amplifies)
        let cos_phi = S::ZERO.sub(S::cos_normal(self.axis, l));
        let spot = if cos_phi >= self.cos_cutoff && cos_phi > S::ZERO {
            cos_phi.min1().powi(self.exponent)
        } else {
            S::ZERO
        };
        let scale = if self.att.constant {
            spot
        } else {
            spot.mul(self.att.factor::<S>(d))
        };
        Incident {
            l,
            scale: Some(scale),
            ambient_per_point: true,
            colors: &self.pre,
        }
    }
}

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

impl<S: Scalar> LightSource<S> for AnyLight<S> {
    const NEEDS_POSITION: bool = true;
    fn prepare(&mut self, material: &Material<S>, view: Option<Vec3<S>>) {
        match self {
            Self::Directional(l) => LightSource::prepare(l, material, view),
            Self::Point(l) => LightSource::prepare(l, material, view),
            Self::Spot(l) => LightSource::prepare(l, material, view),
        }
    }
    fn constant_ambient(&self) -> Option<Rgb<S>> {
        match self {
            Self::Directional(l) => LightSource::constant_ambient(l),
            Self::Point(l) => LightSource::constant_ambient(l),
            Self::Spot(l) => LightSource::constant_ambient(l),
        }
    }
    #[inline(always)]
    fn incident(&self, p: &Point3<S>) -> Incident<'_, S> {
        match self {
            Self::Directional(l) => l.incident(p),
            Self::Point(l) => l.incident(p),
            Self::Spot(l) => l.incident(p),
        }
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
        /// Spot exponent `e` of `cos^e φ`.
        exponent: f32,
        /// Cone half-angle in degrees, 0..=90.
        cutoff_deg: f32,
        /// Attenuation `[constant, linear, quadratic]`.
        attenuation: [f32; 3],
    },
}

impl<S: Scalar> AnyLight<S> {
    /// Builds and validates a light from its description.
    pub fn new(d: &LightDesc) -> Result<Self, ParamError> {
        let colors = LightColors::new(d.ambient, d.diffuse, d.specular)?;
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
