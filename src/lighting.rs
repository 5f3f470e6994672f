//! The lighting equation — the only place it is written.
//!
//! ```text
//! I = Ke + ka∘Ia_global
//!   + Σ_lights scale_i · ( ka∘Ia_i
//!                        + kd∘Id_i · max(0, N·L)^b
//!                        + ks∘Is_i · f(β) · max(0, R·V)^n     (Phong; only where N·L > 0)
//!                        | ks∘Is_i · f(β) · max(0, N·H)^n     (Blinn-Phong)
//!                        + kst∘Is_i · max(0, T·V)^n''         (transmission; light behind)
//!                        )
//! scale_i = att(d) · spot(φ)      att = 1/(a + b·d + c·d²),  spot = cos^e φ in the cone
//! fog:  the Σ part becomes  f·Σ + (1 − f)·fog_colour,  f = clamp((end − d)/(end − start))
//! ```
//!
//! Which terms exist is decided by types: the [`Model`] (specular kind, brilliance,
//! Fresnel, transmission), the light set (directional lights have no attenuation or
//! cone), the [`Viewer`] (at infinity: V constant) and the [`FogModel`]. A term that
//! a type leaves out is not evaluated and its code is not generated.
//!
//! # Extremes
//! - `N·L ≤ 0`: no diffuse and no specular from that light (nothing leaks behind the
//!   surface); transmission only there.
//! - Grazing angles, `R·V` or `N·H` slightly above 1 from rounding: the base of every
//!   power is clamped to [0, 1] first, so powers never exceed 1.
//! - The sum may exceed 1 (bright lights, several lights): it saturates at the tier's
//!   maximum while summed and is clamped to [0, 1] when converted to an output colour.
//! - Normals are expected unit length; [`Lighting::shade`] takes them as they are,
//!   [`Lighting::shade_normalizing`] normalises first (a zero normal gives the ambient
//!   and emission terms only). A unit vector rounded to a fixed tier is up to
//!   5·10⁻⁵ too long or short, which the powers amplify (n·5·10⁻⁵ at the top of a
//!   highlight): every cosine that a power raises ([`Scalar::cos_normal`],
//!   [`Scalar::reflect_dot`]) corrects the lengths of `N`, `L`, `V` and `H` to
//!   first order in `Q14` when they are within 2⁻⁵ of unit length, and Phong's
//!   `R = 2(N·L)N − L` is exact at the mirror direction (where `2(N·L)` is 2,
//!   beyond the fixed tiers' range).
//! - A float tier's normal with an infinite or NaN component (only a `Vec3` built
//!   directly holds one) lights nothing; infinite or NaN positions give zero light
//!   directions and distances: no channel is ever NaN or infinite.

use crate::color::Rgb;
use crate::error::{finite, ParamError};
use crate::light::{Incident, IncidentVisitor, LightSet};
use crate::material::Material;
use crate::num::Scalar;
use crate::vector::{point_from_f32, point_sub, Point3, Vec3};
use core::marker::PhantomData;

/// Which specular reflection model a [`Model`] evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Specular {
    /// No specular term.
    None,
    /// Phong: `(R·V)^n`, `R = 2(N·L)N − L`.
    Phong,
    /// Blinn-Phong: `(N·H)^n`, `H = (L + V)/|L + V|` (constant for a directional
    /// light and a viewer at infinity).
    BlinnPhong,
}

/// The material terms a lighting configuration evaluates, as compile-time constants.
pub trait Model: Copy + Default + core::fmt::Debug {
    /// The specular model.
    const SPECULAR: Specular;
    /// Diffuse `(N·L)^b` with the material's brilliance `b` instead of `N·L`.
    const BRILLIANCE: bool;
    /// The angle factor `f(β)` (Schlick's Fresnel) on the specular term.
    const FRESNEL: bool;
    /// The transmission term `kst·(T·V)^n''`.
    const TRANSMISSION: bool;
}

/// A model from four constants: `SPEC` is 0 (none), 1 (Phong) or 2 (Blinn-Phong).
#[derive(Clone, Copy, Debug, Default)]
pub struct Terms<
    const SPEC: u8,
    const BRILLIANCE: bool,
    const FRESNEL: bool,
    const TRANSMISSION: bool,
>;

impl<const SPEC: u8, const BRILLIANCE: bool, const FRESNEL: bool, const TRANSMISSION: bool> Model
    for Terms<SPEC, BRILLIANCE, FRESNEL, TRANSMISSION>
{
    const SPECULAR: Specular = match SPEC {
        0 => Specular::None,
        1 => Specular::Phong,
        _ => Specular::BlinnPhong,
    };
    const BRILLIANCE: bool = BRILLIANCE;
    const FRESNEL: bool = FRESNEL;
    const TRANSMISSION: bool = TRANSMISSION;
}

/// Ambient + Lambert diffuse only.
pub type Lambert = Terms<0, false, false, false>;
/// Ambient + diffuse + Phong specular `(R·V)^n`.
pub type Phong = Terms<1, false, false, false>;
/// Ambient + diffuse + Blinn-Phong specular `(N·H)^n` (OpenGL's model).
pub type BlinnPhong = Terms<2, false, false, false>;
/// Every term: brilliance, Blinn-Phong with the Fresnel angle factor, transmission.
pub type Full = Terms<2, true, true, true>;

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
        for c in eye {
            finite("eye", c)?;
        }
        Ok(Self {
            eye: point_from_f32::<S>(eye),
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
}

/// Linear depth cueing (seed 004's atmospheric attenuation): the diffuse and
/// specular light fades towards `colour` between `start` and `end`:
/// `f = clamp((end − d)/(end − start), 0, 1)`.
///
/// # Representation and extremes
///
/// The ramp is stored per tier ([`Scalar::ramp`]) so that any finite `start < end`
/// works: ranges of `f32::MAX` and more (`start = −f32::MAX, end = f32::MAX` is
/// half fog near 0), ends far beyond the geometry range (`0…200 000` fades over the
/// whole range of the fixed tiers' distances), ranges down to one `f32` step (a step
/// at `end`). The fixed tiers hold the slope `1/(end − start)` as a mantissa and an
/// exponent rather than in Q16.16, and evaluate it from the point of the geometry
/// range nearest to `end`; `f` is within 2⁻¹³ (`Q14`) or 10⁻⁶ (the others) of the
/// exact ramp at the tier's distance `d`. What remains is the distance's own
/// rounding (2⁻¹⁶ units for the fixed tiers, 2⁻²⁴ relative for `f32`), which the
/// ramp scales by `1/(end − start)`. A NaN distance (only from non-finite positions
/// given directly as `Vec3`) is full fog.
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
}

/// A lighting configuration: lights, material, viewer, fog and the global ambient
/// light, with everything that is constant precomputed.
///
/// ```
/// use fixshade::prelude::*;
/// let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// let mat = Material::new(&MaterialDesc::classic([1.0, 0.0, 0.0], AmbientSource::Object, 0.0, 0.5, 0.5, 20.0)).unwrap();
/// let lit = Lighting::<Q14, _, BlinnPhong>::new(light, mat);
/// let c = lit.shade(&Lighting::<Q14, DirectionalLight<Q14>>::origin(), Vec3::from_f32([0.0, 0.0, 1.0]));
/// assert_eq!(c.to_rgb888(), embedded_graphics_core::pixelcolor::Rgb888::new(255, 128, 128));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Lighting<S, L, M = BlinnPhong, V = InfiniteViewer<S>, F = NoFog>
where
    S: Scalar,
    L: LightSet<S>,
    M: Model,
    V: Viewer<S>,
    F: FogModel<S>,
{
    lights: L,
    material: Material<S>,
    global_ambient: Rgb<S>,
    base: Rgb<S>,
    viewer: V,
    fog: F,
    model: PhantomData<M>,
}

impl<S: Scalar, L: LightSet<S>, M: Model> Lighting<S, L, M> {
    /// Lights and a material, the viewer at infinity on +z, no fog and no global
    /// ambient light.
    pub fn new(lights: L, material: Material<S>) -> Self {
        Self::with_parts(
            lights,
            material,
            Rgb::BLACK,
            InfiniteViewer::default(),
            NoFog,
        )
    }
}

impl<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>> Lighting<S, L, M, V, F> {
    /// Every part at once.
    pub fn with_parts(
        mut lights: L,
        material: Material<S>,
        global_ambient: Rgb<S>,
        viewer: V,
        fog: F,
    ) -> Self {
        lights.prepare(&material, viewer.constant_dir());
        let base = material
            .emission
            .add(global_ambient.mul(material.ambient))
            .add(lights.constant_ambient());
        Self {
            lights,
            material,
            global_ambient,
            base,
            viewer,
            fog,
            model: PhantomData,
        }
    }

    /// The same configuration with a global ambient light `Ia` (OpenGL's
    /// `GL_LIGHT_MODEL_AMBIENT`, default 0.2).
    pub fn with_global_ambient(self, ambient: Rgb<S>) -> Self {
        Self::with_parts(self.lights, self.material, ambient, self.viewer, self.fog)
    }

    /// The same configuration with another viewer.
    pub fn with_viewer<V2: Viewer<S>>(self, viewer: V2) -> Lighting<S, L, M, V2, F> {
        Lighting::with_parts(
            self.lights,
            self.material,
            self.global_ambient,
            viewer,
            self.fog,
        )
    }

    /// The same configuration with fog.
    pub fn with_fog<F2: FogModel<S>>(self, fog: F2) -> Lighting<S, L, M, V, F2> {
        Lighting::with_parts(
            self.lights,
            self.material,
            self.global_ambient,
            self.viewer,
            fog,
        )
    }

    /// The same configuration with another material model.
    pub fn with_model<M2: Model>(self) -> Lighting<S, L, M2, V, F> {
        Lighting::with_parts(
            self.lights,
            self.material,
            self.global_ambient,
            self.viewer,
            self.fog,
        )
    }

    /// The same lights and viewer with another material.
    pub fn with_material(self, material: Material<S>) -> Self {
        Self::with_parts(
            self.lights,
            material,
            self.global_ambient,
            self.viewer,
            self.fog,
        )
    }

    /// Whether [`Lighting::shade`] reads the surface position (point or spot lights,
    /// a local viewer, fog). When `false`, any position may be passed.
    pub const NEEDS_POSITION: bool = L::NEEDS_POSITION || V::NEEDS_POSITION || F::NEEDS_DISTANCE;

    /// The origin, for configurations that do not need a position.
    pub fn origin() -> Point3<S> {
        point_from_f32::<S>([0.0; 3])
    }

    /// The material.
    pub fn material(&self) -> &Material<S> {
        &self.material
    }

    /// The lights (prepared for this material and viewer).
    pub fn lights(&self) -> &L {
        &self.lights
    }

    /// The part of the colour that is the same at every point: emission, global
    /// ambient and the ambient of lights without attenuation.
    pub fn base(&self) -> Rgb<S> {
        self.base
    }

    /// The colour of surface point `p` with unit normal `n`, linear RGB.
    ///
    /// Never NaN or infinite, whatever a float tier's `Vec3` holds: a normal with an
    /// infinite or NaN component lights nothing (only the ambient and emission terms
    /// remain), infinite or NaN positions give zero light directions and distances
    /// (and full fog for a NaN viewing distance).
    #[inline(always)]
    pub fn shade(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        let (v, dist) = self.viewer.view(p);
        let mut sum = LightSum {
            lighting: self,
            n,
            v,
            ambient: self.base,
            direct: Rgb::BLACK,
        };
        self.lights.for_each(p, &mut sum);
        sum.ambient.add(self.fog.apply(sum.direct, dist))
    }

    /// [`Lighting::shade`] for a normal of any length (normalised first).
    #[inline(always)]
    pub fn shade_normalizing(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        self.shade(p, n.normalize())
    }

    /// One light's (per-point ambient, diffuse + specular + transmission).
    #[inline(always)]
    fn light_terms(
        &self,
        inc: &Incident<'_, S>,
        n: Vec3<S>,
        v: Vec3<S>,
    ) -> (Option<Rgb<S>>, Rgb<S>) {
        let c = inc.colors;
        let m = &self.material;
        // N·L: with the lengths corrected where a power (brilliance) or the refraction
        // amplifies their rounding (see `Scalar::cos_normal`); the plain dot product
        // elsewhere (the diffuse term is linear in it: 5·10⁻⁵ is 0.013 LSB)
        let nl = if M::BRILLIANCE || M::TRANSMISSION {
            S::cos_normal(n, inc.l)
        } else {
            n.dot(inc.l)
        };
        let mut direct = Rgb::BLACK;
        // A float tier's normal with an infinite component (only a `Vec3` built directly
        // holds one) makes N·L infinite or NaN: outside (0, MAX] and [−MAX, 0) it
        // lights nothing, so no channel becomes infinite or NaN. (Free for the fixed
        // tiers, whose values never exceed MAX.)
        if nl > S::ZERO && nl <= S::MAX {
            // diffuse: kd·Id·(N·L)^b
            let d = if M::BRILLIANCE {
                nl.min1().powi(m.brilliance as u16)
            } else {
                nl
            };
            direct = c.diffuse.scale(d);
            // specular: ks·Is·f(β)·x^n, x = R·V or N·H
            let x = match M::SPECULAR {
                Specular::None => S::ZERO,
                Specular::Phong => S::reflect_dot(n, inc.l, v),
                Specular::BlinnPhong => {
                    S::cos_normal(n, c.half.unwrap_or_else(|| inc.l.add(v).normalize()))
                }
            };
            if M::SPECULAR != Specular::None && x > S::ZERO {
                let mut s = x.min1().powi(m.shininess);
                if M::FRESNEL {
                    // Schlick: F0 + (1 − F0)(1 − cos β)^5, cos β = N·L
                    let f = m
                        .fresnel_f0
                        .add(S::ONE.sub(m.fresnel_f0).mul(S::ONE.sub(nl.min1()).powi(5)));
                    s = s.mul(f);
                }
                direct = direct.add_scaled(c.specular, s);
            }
        } else if M::TRANSMISSION && nl < S::ZERO && nl >= S::ZERO.sub(S::MAX) {
            direct = c
                .transmission
                .scale(transmission(n, inc.l, v, m.eta, nl).powi(m.transmission_exponent));
        }
        let ambient = inc.ambient_per_point.then_some(c.ambient);
        match inc.scale {
            Some(k) => (ambient.map(|a| a.scale(k)), direct.scale(k)),
            None => (ambient, direct),
        }
    }
}

/// What the shading stage lights with: anything that gives the colour of a surface
/// point. Implemented by every [`Lighting`] configuration; the shading modes take
/// one type parameter for it instead of the five of [`Lighting`].
pub trait Illuminate {
    /// The number tier.
    type Scalar: Scalar;
    /// Whether [`Illuminate::shade`] reads the position (see [`Lighting::NEEDS_POSITION`]).
    const NEEDS_POSITION: bool;
    /// The colour of surface point `p` with unit normal `n`, linear RGB.
    fn shade(&self, p: &Point3<Self::Scalar>, n: Vec3<Self::Scalar>) -> Rgb<Self::Scalar>;
}

impl<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>> Illuminate
    for Lighting<S, L, M, V, F>
{
    type Scalar = S;
    const NEEDS_POSITION: bool = Self::NEEDS_POSITION;
    #[inline(always)]
    fn shade(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        Lighting::shade(self, p, n)
    }
}

/// Σ over the lights: the per-point ambient and the light-dependent part.
struct LightSum<'a, S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>> {
    lighting: &'a Lighting<S, L, M, V, F>,
    n: Vec3<S>,
    v: Vec3<S>,
    ambient: Rgb<S>,
    direct: Rgb<S>,
}

impl<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>> IncidentVisitor<S>
    for LightSum<'_, S, L, M, V, F>
{
    #[inline(always)]
    fn visit(&mut self, inc: Incident<'_, S>) {
        let (a, d) = self.lighting.light_terms(&inc, self.n, self.v);
        if let Some(a) = a {
            self.ambient = self.ambient.add(a);
        }
        self.direct = self.direct.add(d);
    }
}

/// `max(0, T·V)` for light arriving from behind the surface (`N·L < 0`): `T` is the
/// refracted direction of the incoming ray `−L` by Snell's law with `η = n1/n2`;
/// zero under total internal reflection.
#[inline(always)]
fn transmission<S: Scalar>(n: Vec3<S>, l: Vec3<S>, v: Vec3<S>, eta: S, nl: S) -> S {
    // incident d = −L, normal on the incoming side −N, c1 = −N·L = cos θi > 0
    let c1 = S::ZERO.sub(nl);
    // cos² θt = 1 − η·a with a = η·sin² θi. a ≥ 1 implies η ≥ 1 and η·a ≥ 1: total
    // internal reflection. Testing it first keeps η·a below 2 (the fixed tiers' range).
    let a = eta.mul(S::ONE.sub(c1.mul(c1)));
    if a >= S::ONE {
        return S::ZERO;
    }
    let k = S::ONE.sub(eta.mul(a));
    if k <= S::ZERO {
        return S::ZERO;
    }
    let c2 = k.sqrt();
    // T = η·d + (η·c1 − c2)·(−N) = −η·L + (c2 − η·c1)·N, so
    // T·V = (c2 − η·c1)·(N·V) − η·(L·V), with cosines that correct the lengths
    let tv = c2
        .sub(eta.mul(c1))
        .mul(S::cos_normal(n, v))
        .sub(eta.mul(S::cos_normal(l, v)));
    tv.max0().min1()
}
