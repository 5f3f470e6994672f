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
//! Types decide which terms exist (the [`Model`], the light set, the [`Viewer`],
//! the [`FogModel`]): a term a type leaves out generates no code.
//!
//! # Extremes
//! - `N·L ≤ 0`: no diffuse and no specular from that light (nothing leaks behind the
//!   surface); transmission only there.
//! - Grazing angles, `R·V` or `N·H` slightly above 1 from rounding: the base of every
//!   power is clamped to [0, 1] first, so powers never exceed 1.
//! - The sum may exceed 1 (bright lights, several lights): it saturates at the tier's
//!   maximum while summed and is clamped to [0, 1] when converted to an output colour.
//! - Normals are expected unit length; [`Lighting::shade_normalizing`] normalises
//!   first (a zero normal gives ambient and emission only). A fixed tier's rounded
//!   unit vector is up to 5·10⁻⁵ off unit length, which a power `n` amplifies
//!   n-fold: every cosine a power raises ([`Scalar::cos_normal`],
//!   [`Scalar::reflect_dot`]) corrects the lengths to first order in `Q14`, and
//!   Phong's `R = 2(N·L)N − L` is exact at the mirror direction (where `2(N·L)`
//!   is 2, beyond the fixed tiers' range).
//! - No channel is ever NaN or infinite: see [`Lighting::shade`].

mod any;
mod channels;
pub mod gl;
mod illuminate;
mod light;
mod material;
mod model;
mod viewer;

pub use any::{AnyLight, LightDesc, LightKind};
pub(crate) use channels::ChannelTerms;
pub use illuminate::{BackFaces, Illuminate, SeparateSpecular};
pub(crate) use illuminate::{Directional, DirectionalTerms};
pub use light::{Attenuation, DirectionalLight, LightColors, LightSet, PointLight, SpotLight};
// The machinery of `LightSet` (each light's incident terms, its colours
// prepared for a material, the visitor that sums them): public in their
// module, not nameable outside the crate (the crate's lights, arrays,
// `heapless::Vec` and tuples implement `LightSet`).
pub(crate) use light::{ColorTerms, Incident, IncidentVisitor};
pub use material::{AmbientSource, Material, MaterialDesc};
pub use model::{BlinnPhong, Full, Lambert, Model, Phong, Specular, Terms};
pub use viewer::{FogModel, InfiniteViewer, LinearFog, LocalViewer, NoFog, Viewer};

use crate::color::Rgb;
use crate::error::ParamError;
use crate::num::Scalar;
use crate::num::{point_from_f32, Point3, Vec3};
use core::marker::PhantomData;

/// `GL_COLOR_MATERIAL`: which material colour a per-vertex colour replaces
/// (`glColorMaterial`'s mode), for [`Lighting::shade_parts`] with a colour.
///
/// The replaced colour counts as white in the prepared terms, and the sums it
/// multiplies are multiplied by the vertex colour per point (one product per
/// channel, no per-light work). [`Lighting::shade`] is the lighting under a white
/// vertex colour, OpenGL's default current colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColorMaterial {
    /// `glDisable(GL_COLOR_MATERIAL)`: vertex colours are ignored.
    #[default]
    Off,
    /// `GL_EMISSION`.
    Emission,
    /// `GL_AMBIENT`.
    Ambient,
    /// `GL_DIFFUSE`.
    Diffuse,
    /// `GL_SPECULAR`.
    Specular,
    /// `GL_AMBIENT_AND_DIFFUSE` (OpenGL's default mode).
    AmbientAndDiffuse,
}

impl ColorMaterial {
    /// The material the lights are prepared with: the replaced colours white.
    fn effective<S: Scalar>(self, m: &Material<S>) -> Material<S> {
        let mut e = *m;
        match self {
            Self::Off => {}
            Self::Emission => e.emission = [1.0; 3],
            Self::Ambient => e.ambient = [1.0; 3],
            Self::Diffuse => e.diffuse = [1.0; 3],
            Self::Specular => e.specular = [1.0; 3],
            Self::AmbientAndDiffuse => {
                e.ambient = [1.0; 3];
                e.diffuse = [1.0; 3];
            }
        }
        e
    }
}

/// The colour of a surface point in the two parts OpenGL keeps apart: the primary
/// colour (emission, ambient and diffuse) and the secondary colour (specular, and
/// transmission), both linear and unclamped. `GL_SINGLE_COLOR` is their
/// [`sum`](LitColor::sum); `GL_SEPARATE_SPECULAR_COLOR` clamps each to [0, 1]
/// first ([`separate`](LitColor::separate)), so that a texture can modulate the
/// primary colour before the secondary one is added.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LitColor<S> {
    /// Emission + ambient + diffuse.
    pub primary: Rgb<S>,
    /// Specular (+ transmission).
    pub secondary: Rgb<S>,
}

impl<S: Scalar> LitColor<S> {
    /// `primary + secondary` (OpenGL's `GL_SINGLE_COLOR`).
    #[inline(always)]
    pub fn sum(self) -> Rgb<S> {
        self.primary.add(self.secondary)
    }

    /// `clamp(primary) + clamp(secondary)`, each clamped to [0, 1] (OpenGL's
    /// `GL_SEPARATE_SPECULAR_COLOR` without a texture; in [0, 2], clamped again by
    /// the output).
    #[inline(always)]
    pub fn separate(self) -> Rgb<S> {
        self.primary.clamp01().add(self.secondary.clamp01())
    }
}

/// A lighting configuration: lights, material, viewer, fog and the global ambient
/// light, with everything that is constant precomputed.
///
/// # Building
///
/// The lights' colours are multiplied with the material's (and the attenuation's
/// `1/a`) in `f32` when built, each product rounded to the tier once. [`Lighting::new`]
/// and the `with_*` builders are infallible: a product beyond the tier's range (±2
/// for `Q14`/`Q30`) saturates. [`Lighting::checked`] rejects such a lighting
/// instead; one that passes gives the `f64` reference's colours up to the tier's
/// bound (`GL_DIFFUSE` 2.5, `GL_CONSTANT_ATTENUATION` 0.25 and negative colours
/// included).
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
    global_ambient: [f32; 3],
    color_material: ColorMaterial,
    /// `emission + ambient_base`.
    base: Rgb<S>,
    /// The emission (white under `ColorMaterial::Emission`).
    emission: Rgb<S>,
    /// `global ∘ ka + Σ` the ambient of lights without attenuation.
    ambient_base: Rgb<S>,
    viewer: V,
    fog: F,
    model: PhantomData<M>,
}

/// A lighting whose lights are in eye coordinates (the eye at the origin,
/// looking down −z), where the renderer hands points and normals: the only form
/// of a [`Lighting`] a shader takes, so that no kernel draws world lights. Made
/// by [`Lighting::viewed`] (world lights seen through the camera) or
/// [`Lighting::eye_space`] (lights given in eye coordinates).
///
/// ```
/// use fixshade::prelude::*;
/// let light = DirectionalLight::<Q14>::white([0.0, 1.0, 0.0])?;
/// let world = Lighting::<Q14, _, Lambert>::new(light, Material::new(&MaterialDesc::default())?);
/// let camera = fixshade::standard::camera()?;
/// let lit = world.viewed(camera.view())?; // once per frame for a moving camera
/// let shader = Shader::<_, _, _, Rgb565>::new(GouraudShading, &lit, Linear);
/// # let _ = shader;
/// # Ok::<(), fixshade::error::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Viewed<L>(L);

impl<L> Viewed<L> {
    /// The lighting, its lights in eye coordinates.
    pub fn lighting(&self) -> &L {
        &self.0
    }
}

/// OpenGL's default `GL_LIGHT_MODEL_AMBIENT` (without alpha).
const GL_GLOBAL_AMBIENT: [f32; 3] = [0.2; 3];

impl<S: Scalar, L: LightSet<S>, M: Model> Lighting<S, L, M> {
    /// Lights and a material with OpenGL's defaults for the rest: the viewer
    /// at infinity on +z (`GL_LIGHT_MODEL_LOCAL_VIEWER` false), no fog, and a
    /// global ambient light of 0.2 (`GL_LIGHT_MODEL_AMBIENT`) times the
    /// material's ambient ([`Lighting::with_global_ambient_f32`] changes it).
    ///
    /// The lights are in **world coordinates**: a shader takes a [`Viewed`]
    /// lighting ([`Lighting::viewed`] or [`Lighting::eye_space`], as
    /// [`GlScene::lighting`] does); drawing with world lights does not compile.
    ///
    /// ```compile_fail,E0277
    /// use fixshade::prelude::*;
    /// let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
    /// let world = Lighting::<Q14, _, Lambert>::new(light, Material::new(&MaterialDesc::default()).unwrap());
    /// // error: the lights of `Lighting<…>` are in world coordinates
    /// let shader = Shader::<_, _, _, Rgb565>::new(FlatShading, &world, Linear);
    /// ```
    ///
    /// [`GlScene::lighting`]: crate::lighting::gl::GlScene::lighting
    pub fn new(lights: L, material: Material<S>) -> Self {
        Self::build(
            lights,
            material,
            GL_GLOBAL_AMBIENT,
            InfiniteViewer::default(),
            NoFog,
            ColorMaterial::Off,
        )
    }
}

impl<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>> Lighting<S, L, M, V, F> {
    /// Every part at once (world lights, as [`Lighting::new`]).
    pub fn with_parts(
        lights: L,
        material: Material<S>,
        global_ambient: Rgb<S>,
        viewer: V,
        fog: F,
    ) -> Self {
        Self::build(
            lights,
            material,
            global_ambient.to_f32(),
            viewer,
            fog,
            ColorMaterial::Off,
        )
    }

    /// Every part, the global ambient light in `f32` (multiplied with the material's
    /// ambient colour before it is converted to the tier).
    pub(crate) fn build(
        mut lights: L,
        material: Material<S>,
        global_ambient: [f32; 3],
        viewer: V,
        fog: F,
        color_material: ColorMaterial,
    ) -> Self {
        let eff = color_material.effective(&material);
        lights.prepare(&eff, viewer.constant_dir());
        let ga: [f32; 3] = core::array::from_fn(|i| global_ambient[i] * eff.ambient[i]);
        let emission = Rgb::from_f32(eff.emission);
        let ambient_base = Rgb::from_f32(ga).add(lights.constant_ambient());
        let base = Rgb::from_f32(core::array::from_fn(|i| eff.emission[i] + ga[i]))
            .add(lights.constant_ambient());
        Self {
            lights,
            material,
            global_ambient,
            color_material,
            base,
            emission,
            ambient_base,
            viewer,
            fog,
            model: PhantomData,
        }
    }

    /// `self`'s lights, material, global ambient light and colour material,
    /// prepared again with `viewer`, `fog` and model `M2`; the lights stay in
    /// the coordinates they are in (the `with_*` builders).
    fn remade<M2: Model, V2: Viewer<S>, F2: FogModel<S>>(
        self,
        viewer: V2,
        fog: F2,
    ) -> Lighting<S, L, M2, V2, F2> {
        Lighting::build(
            self.lights,
            self.material,
            self.global_ambient,
            viewer,
            fog,
            self.color_material,
        )
    }

    /// The lighting of `self`'s parts, prepared again (after a part changed).
    fn rebuilt(self) -> Self {
        self.with_model()
    }

    /// The same lighting with its lights taken as given, in eye coordinates
    /// ([`Viewed`]): OpenGL's `GL_POSITION` set after the camera's matrix, or a
    /// lamp that moves with the camera.
    pub fn eye_space(self) -> Viewed<Self> {
        Viewed(self)
    }

    /// The same configuration with a global ambient light `Ia` (OpenGL's
    /// `GL_LIGHT_MODEL_AMBIENT`, default 0.2).
    pub fn with_global_ambient(self, ambient: Rgb<S>) -> Self {
        self.with_global_ambient_f32(ambient.to_f32())
    }

    /// [`Lighting::with_global_ambient`] from `f32` channels (any sign), multiplied
    /// with the material's ambient colour before it is converted to the tier.
    pub fn with_global_ambient_f32(mut self, ambient: [f32; 3]) -> Self {
        self.global_ambient = ambient;
        self.rebuilt()
    }

    /// The same configuration with its world lights seen through `view` (the
    /// camera's view matrix, [`Camera::view`](crate::camera::Camera::view)): a
    /// moving camera calls this once per frame. Positions move by the whole
    /// matrix, directions (a directional light's, a spot's axis) by its upper-left
    /// 3×3, normalised again, as OpenGL does to `GL_POSITION` and
    /// `GL_SPOT_DIRECTION` set after the camera's matrix
    /// (`gl::GlLight::transformed` for parameter sets). In the tier's precision (a
    /// Q14 direction within one unit of the `f64` result); a few hundred `f32`
    /// operations per light (soft float without an FPU), then the lights are
    /// prepared again.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// // a lamp up and to the right of the world's origin, a camera at +x looking at it
    /// let lamp = DirectionalLight::<Q14>::white([1.0, 1.0, 0.0])?;
    /// let mat = Material::new(&MaterialDesc::classic([1.0; 3], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0))?;
    /// let world = Lighting::<Q14, _, Lambert>::new(lamp, mat);
    /// let view = Mat4::look_at([5.0, 0.0, 0.0], [0.0; 3], [0.0, 1.0, 0.0])?;
    /// let eye = world.viewed(&view)?;
    /// // the world's +x (towards the camera) is the eye's +z
    /// let o = Lighting::<Q14, DirectionalLight<Q14>>::origin();
    /// let lit = |l: &Lighting<Q14, _, Lambert>, n: [f32; 3]| l.shade(&o, Vec3::from_f32(n)).to_rgb888();
    /// assert_eq!(lit(eye.lighting(), [0.0, 0.0, 1.0]), lit(&world, [1.0, 0.0, 0.0]));
    /// assert_eq!(lit(eye.lighting(), [0.0, 1.0, 0.0]), lit(&world, [0.0, 1.0, 0.0]));
    /// # Ok::<(), fixshade::error::ParamError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`ParamError::ZeroDirection`] when `view` maps a light's direction to
    /// zero (a singular matrix), [`ParamError::NotFinite`] for a non-finite
    /// position.
    pub fn viewed(&self, view: &crate::num::Mat4) -> Result<Viewed<Self>, ParamError>
    where
        L: Clone,
    {
        let mut l = self.clone();
        l.lights.transform(view)?;
        Ok(Viewed(l.rebuilt()))
    }

    /// The same configuration with another viewer.
    pub fn with_viewer<V2: Viewer<S>>(self, viewer: V2) -> Lighting<S, L, M, V2, F> {
        let fog = self.fog;
        self.remade(viewer, fog)
    }

    /// The same configuration with fog.
    pub fn with_fog<F2: FogModel<S>>(self, fog: F2) -> Lighting<S, L, M, V, F2> {
        let viewer = self.viewer;
        self.remade(viewer, fog)
    }

    /// The same configuration with another material model.
    pub fn with_model<M2: Model>(self) -> Lighting<S, L, M2, V, F> {
        let (viewer, fog) = (self.viewer, self.fog);
        self.remade(viewer, fog)
    }

    /// The same lights and viewer with another material.
    pub fn with_material(mut self, material: Material<S>) -> Self {
        self.material = material;
        self.rebuilt()
    }

    /// The same configuration with `GL_COLOR_MATERIAL` in mode `mode`: the vertex
    /// colour given to [`Lighting::shade_parts`] replaces that material colour.
    pub fn with_color_material(mut self, mode: ColorMaterial) -> Self {
        self.color_material = mode;
        self.rebuilt()
    }

    /// The lighting if the tier holds every term of its equation, else the term
    /// that does not fit: [`ParamError::TierRange`] with the tier's limit.
    ///
    /// Tested per channel on the `f32` products (light colour × material colour ×
    /// `1/a`), each of which must be below the tier's maximum in magnitude; with a
    /// negative colour anywhere, or fog, so must the sum of all positive terms
    /// (emission and global ambient included) and that of all negative ones. A
    /// light whose attenuation has no constant term
    /// ([`Attenuation::is_unbounded`]: it saturates near the light) allows no
    /// negative term on that light, no fog, and negative terms summing to more
    /// than `1 − max` per channel, so that the saturated output stays 1 as the
    /// reference's.
    ///
    /// Where it passes, an intermediate value saturates only where the output
    /// clamps to 1 either way. The float tiers (maximum 10⁹) pass every finite
    /// scene but those three unbounded-attenuation cases.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// use fixshade::error::ParamError;
    /// // GL_DIFFUSE 2.5 on a material of 0.3: the product 0.75 fits Q14
    /// let light = DirectionalLight::<Q14>::new([0.0, 0.0, 1.0],
    ///     LightColors::new([0.0; 3], [2.5; 3], [0.0; 3]).unwrap()).unwrap();
    /// let mat = Material::new(&MaterialDesc { diffuse: [0.3; 3], ..MaterialDesc::default() }).unwrap();
    /// let lit = Lighting::<Q14, _, BlinnPhong>::new(light, mat).checked().unwrap();
    /// let c = lit.shade(&Lighting::<Q14, DirectionalLight<Q14>>::origin(), Vec3::from_f32([0.0, 0.0, 1.0]));
    /// // 0.75, plus OpenGL's global ambient 0.2 × the default material ambient 0.2
    /// assert_eq!(c.to_rgb888().r(), 201); // 0.79
    /// // on a material of 1.0 the product 2.5 does not
    /// let mat = Material::new(&MaterialDesc { diffuse: [1.0; 3], ..MaterialDesc::default() }).unwrap();
    /// let err = Lighting::<Q14, _, BlinnPhong>::new(light, mat).checked().unwrap_err();
    /// assert!(matches!(err, ParamError::TierRange { limit: 2, .. }));
    /// ```
    pub fn checked(self) -> Result<Self, ParamError> {
        let max = S::MAX.to_f32();
        let err = |param| ParamError::TierRange {
            param,
            tier: S::NAME,
            limit: libm::ceilf(max) as u32,
        };
        let eff = self.color_material.effective(&self.material);
        // 0·∞ (a colour 0 under a folded 1/a of ∞) is no light
        let no_nan = |v: f32| if v.is_nan() { 0.0 } else { v };
        let constant: [f32; 3] = core::array::from_fn(|i| {
            no_nan(eff.emission[i] + self.global_ambient[i] * eff.ambient[i])
        });
        let mut pos = constant.map(|v| v.max(0.0));
        let mut neg = constant.map(|v| v.min(0.0));
        let mut negative = neg.iter().any(|&v| v < 0.0);
        let mut unbounded = false;
        let mut result = Ok(());
        const NAMES: [&str; 4] = [
            "light ambient × material ambient",
            "light diffuse × material diffuse",
            "light specular × material specular",
            "light specular × material transmission",
        ];
        self.lights.for_each_color_terms(&eff, &mut |t| {
            for c in 0..3 {
                let terms =
                    [t.ambient[c], t.diffuse[c], t.specular[c], t.transmission[c]].map(no_nan);
                for (v, name) in terms.iter().zip(NAMES) {
                    if !(v.abs() < max) {
                        result = Err(err(name));
                    }
                }
                let [a, d, s, tr] = terms;
                // diffuse + specular and transmission exclude each other
                pos[c] += a.max(0.0) + (d.max(0.0) + s.max(0.0)).max(tr.max(0.0));
                neg[c] += a.min(0.0) + (d.min(0.0) + s.min(0.0)).min(tr.min(0.0));
                negative |= terms.iter().any(|&v| v < 0.0);
                if t.unbounded && terms.iter().any(|&v| v < 0.0) {
                    result = Err(err(
                        "negative colour under an attenuation without a constant term (a = 0)",
                    ));
                }
            }
            unbounded |= t.unbounded;
        });
        result?;
        if unbounded {
            // a saturated contribution (max) must stay at or above 1 whatever
            // is added to it
            if F::NEEDS_DISTANCE {
                return Err(err(
                    "fog with an attenuation without a constant term (a = 0)",
                ));
            }
            if neg.iter().any(|&v| !(v > 1.0 - max)) {
                return Err(err(
                    "negative terms with an attenuation without a constant term (a = 0)",
                ));
            }
        }
        let sums_fit = (0..3).all(|c| pos[c] < max && neg[c] > -max);
        if (negative || F::NEEDS_DISTANCE) && !sums_fit {
            return Err(err(
                "sum of the lighting terms (with negative colours or fog)",
            ));
        }
        Ok(self)
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

    /// The `GL_COLOR_MATERIAL` mode.
    pub fn color_material(&self) -> ColorMaterial {
        self.color_material
    }

    /// The part of the colour that is the same at every point: emission, global
    /// ambient and the ambient of lights without attenuation.
    pub fn base(&self) -> Rgb<S> {
        self.base
    }

    /// The colour of surface point `p` with unit normal `n`, linear RGB.
    ///
    /// Never NaN or infinite, whatever a float tier's `Vec3` holds: a normal with
    /// an infinite or NaN component lights nothing (ambient and emission remain);
    /// infinite or NaN positions give zero light directions and distances (full
    /// fog for a NaN viewing distance).
    #[inline(always)]
    pub fn shade(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        let (sum, dist) = self.sum_lights::<false>(p, n, self.base);
        sum.ambient.add(self.fog.apply(sum.direct, dist))
    }

    /// [`Lighting::shade`] for a normal of any length (normalised first).
    #[inline(always)]
    pub fn shade_normalizing(&self, p: &Point3<S>, n: Vec3<S>) -> Rgb<S> {
        self.shade(p, n.normalize())
    }

    /// The colour of `p` with normal `n` in OpenGL's two parts ([`LitColor`]):
    /// `color` (a vertex colour; `None` is white) replaces the material colour of
    /// the [`ColorMaterial`] mode. `shade_parts(p, n, None).sum()` is
    /// [`Lighting::shade`] up to rounding. Fog fades the diffuse part towards the
    /// fog colour and the secondary colour towards zero.
    #[inline(always)]
    pub fn shade_parts(&self, p: &Point3<S>, n: Vec3<S>, color: Option<Rgb<S>>) -> LitColor<S> {
        let (sum, dist) = self.sum_lights::<true>(p, n, self.ambient_base);
        let (mut emission, mut ambient) = (self.emission, sum.ambient);
        let (mut diffuse, mut specular) = (sum.direct, sum.specular);
        if let Some(c) = color {
            match self.color_material {
                ColorMaterial::Off => {}
                ColorMaterial::Emission => emission = c,
                ColorMaterial::Ambient => ambient = ambient.mul(c),
                ColorMaterial::Diffuse => diffuse = diffuse.mul(c),
                ColorMaterial::Specular => specular = specular.mul(c),
                ColorMaterial::AmbientAndDiffuse => {
                    ambient = ambient.mul(c);
                    diffuse = diffuse.mul(c);
                }
            }
        }
        LitColor {
            primary: emission.add(ambient).add(self.fog.apply(diffuse, dist)),
            secondary: self.fog.fade(specular, dist),
        }
    }

    /// The lights' sum at `p` with normal `n`, starting from `ambient`, and the
    /// viewing distance.
    #[inline(always)]
    fn sum_lights<const SPLIT: bool>(
        &self,
        p: &Point3<S>,
        n: Vec3<S>,
        ambient: Rgb<S>,
    ) -> (LightSum<'_, S, L, M, V, F, SPLIT>, S::Geo) {
        let (v, dist) = self.viewer.view(p);
        let mut sum = LightSum {
            lighting: self,
            n,
            v,
            ambient,
            direct: Rgb::BLACK,
            specular: Rgb::BLACK,
        };
        self.lights.for_each(p, &mut sum);
        (sum, dist)
    }

    /// One light's (per-point ambient, diffuse, specular): with `SPLIT` the
    /// specular (and transmission) part apart, else added to the diffuse part
    /// (and the specular part zero).
    #[inline(always)]
    fn light_terms<const SPLIT: bool>(
        &self,
        inc: &Incident<'_, S>,
        n: Vec3<S>,
        v: Vec3<S>,
    ) -> (Option<Rgb<S>>, Rgb<S>, Rgb<S>) {
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
        // the per-point factor (attenuation, spot cone) scales each scalar
        // before the colours: the sum diffuse + specular is formed scaled, so it
        // saturates only where the light's true contribution does
        let k = inc.scale;
        let sc = |x: S| match k {
            Some(k) => x.mul(k),
            None => x,
        };
        let mut direct = Rgb::BLACK;
        let mut specular = Rgb::BLACK;
        // an infinite or NaN N·L (a float tier's directly built `Vec3`) lights
        // nothing; free for the fixed tiers, which never exceed MAX
        if nl > S::ZERO && nl <= S::MAX {
            // diffuse: kd·Id·(N·L)^b
            let d = if M::BRILLIANCE {
                nl.min1().powi(m.brilliance as u16)
            } else {
                nl
            };
            direct = c.diffuse.scale(sc(d));
            // specular: ks·Is·f(β)·x^n, x = R·V or N·H
            let x = match M::SPECULAR {
                Specular::None => S::ZERO,
                Specular::Phong => S::reflect_dot(n, inc.l, v),
                Specular::BlinnPhong => {
                    S::cos_normal(n, c.half.unwrap_or_else(|| inc.l.add(v).normalize()))
                }
            };
            if M::SPECULAR != Specular::None && x > S::ZERO {
                let mut s = x.min1().pow(m.shininess);
                if M::FRESNEL {
                    // Schlick: F0 + (1 − F0)(1 − cos β)^5, cos β = N·L
                    let f = m
                        .fresnel_f0
                        .add(S::ONE.sub(m.fresnel_f0).mul(S::ONE.sub(nl.min1()).powi(5)));
                    s = s.mul(f);
                }
                let s = sc(s);
                if SPLIT {
                    specular = c.specular.scale(s);
                } else {
                    direct = direct.add_scaled(c.specular, s);
                }
            }
        } else if M::TRANSMISSION && nl < S::ZERO && nl >= S::ZERO.sub(S::MAX) {
            let t = c.transmission.scale(sc(
                transmission(n, inc.l, v, m.eta, nl).pow(m.transmission_exponent)
            ));
            if SPLIT {
                specular = t;
            } else {
                direct = t;
            }
        }
        let mut ambient = inc.ambient_per_point.then_some(c.ambient).map(|a| match k {
            Some(k) => a.scale(k),
            None => a,
        });
        // a factor beyond the tier's range (an attenuation without a constant
        // term, near the light): the rest of it, 2^e, multiplies the terms
        // formed, so that they saturate only where the true contribution does
        let e = inc.scale_exp;
        if e != 0 {
            let up = |c: Rgb<S>| Rgb::new(c.r.mul_pow2(e), c.g.mul_pow2(e), c.b.mul_pow2(e));
            ambient = ambient.map(up);
            direct = up(direct);
            specular = up(specular);
        }
        (ambient, direct, specular)
    }
}

/// Σ over the lights: the per-point ambient and the light-dependent part (with
/// `SPLIT`, its specular part apart).
struct LightSum<
    'a,
    S: Scalar,
    L: LightSet<S>,
    M: Model,
    V: Viewer<S>,
    F: FogModel<S>,
    const SPLIT: bool,
> {
    lighting: &'a Lighting<S, L, M, V, F>,
    n: Vec3<S>,
    v: Vec3<S>,
    ambient: Rgb<S>,
    direct: Rgb<S>,
    specular: Rgb<S>,
}

impl<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>, const SPLIT: bool>
    IncidentVisitor<S> for LightSum<'_, S, L, M, V, F, SPLIT>
{
    #[inline(always)]
    fn visit(&mut self, inc: Incident<'_, S>) {
        let (a, d, s) = self.lighting.light_terms::<SPLIT>(&inc, self.n, self.v);
        if let Some(a) = a {
            self.ambient = self.ambient.add(a);
        }
        self.direct = self.direct.add(d);
        if SPLIT {
            self.specular = self.specular.add(s);
        }
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
