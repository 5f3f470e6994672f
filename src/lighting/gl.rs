//! OpenGL 1.x fixed-function lighting (`glLightfv`, `glMaterialfv`,
//! `glLightModelfv`, `glColorMaterial`) with its defaults, converted to
//! fixshade's: the same colours (checked against Mesa by `conformance/`).
//!
//! [`GlScene::lighting`] builds a tier's lighting from the GL state in one call;
//! the caller chooses the light set (a [`DirectionalLight`] array for the fast
//! kernels, `AnyLight` for anything), model and viewer types, checked against it:
//!
//! ```
//! use fixshade::lighting::gl::{GlLight, GlLightModel, GlMaterial, GlScene};
//! use fixshade::prelude::*;
//! // glEnable(GL_LIGHT0) with every parameter at its default
//! let lights = [GlLight::light0()];
//! let scene = GlScene::new(&lights, GlMaterial::default(), GlLightModel::default());
//! let lit: Viewed<Lighting<Q14, [DirectionalLight<Q14>; 1]>> = scene.lighting()?;
//! // 0.2·0.2 (global ambient) + 0.8 (diffuse, N = L) = 0.84
//! let c = lit.shade(&Lighting::<Q14, [DirectionalLight<Q14>; 1]>::origin(), Vec3::from_f32([0.0, 0.0, 1.0]));
//! assert_eq!(c.to_rgb888().r(), 214);
//! # Ok::<(), ParamError>(())
//! ```
//!
//! # What maps to what
//!
//! | OpenGL | fixshade |
//! |---|---|
//! | `glLightfv(GL_LIGHTi, …)`, position and spot direction through the modelview | [`GlLight`], [`GlLight::transformed`] |
//! | `GL_POSITION` w = 0 / w ≠ 0, `GL_SPOT_CUTOFF` 180 / 0..=90 | [`DirectionalLight`] / [`PointLight`] / [`SpotLight`] ([`GlLight::to_light`]) |
//! | `GL_CONSTANT/LINEAR/QUADRATIC_ATTENUATION` | [`Attenuation`](crate::lighting::Attenuation) (`1/a` folded into the colours) |
//! | `GL_SPOT_EXPONENT`, `GL_SHININESS` (real, 0..=128) | [`Exponent`](crate::num::Exponent) |
//! | `glMaterialfv(GL_FRONT / GL_BACK, …)` | [`GlMaterial`] → [`Material::signed`] |
//! | `GL_LIGHT_MODEL_AMBIENT` (any sign) | [`GlLightModel::ambient`] |
//! | `GL_LIGHT_MODEL_LOCAL_VIEWER` | [`LocalViewer`] at the eye ([`GlViewer`]) |
//! | `GL_LIGHT_MODEL_TWO_SIDE` | [`GlScene::back_lighting`] ([`BackFaces`]) for the back faces |
//! | `GL_LIGHT_MODEL_COLOR_CONTROL` = `GL_SEPARATE_SPECULAR_COLOR` | [`LitColor`](crate::lighting::LitColor), [`SeparateSpecular`](crate::lighting::SeparateSpecular) |
//! | `glColorMaterial` + `GL_COLOR_MATERIAL` | [`GlColorMaterial`] → [`ColorMaterial`] |
//! | `GL_NORMALIZE`, `GL_RESCALE_NORMAL` | [`GlNormals`], [`GlNormals::eye_normal`] |
//! | lit alpha (the material's diffuse alpha) | [`GlMaterial::alpha`] (the pixel formats have no alpha) |
//!
//! Coordinates are eye space (the eye at the origin looking down −z), as OpenGL
//! stores light positions after `glLightfv`.

use crate::color::Rgb;
use crate::error::{finite, finite_all, ParamError};
use crate::lighting::{
    AnyLight, DirectionalLight, LightColors, LightDesc, LightKind, LightSet, PointLight, SpotLight,
};
use crate::lighting::{
    BackFaces, ColorMaterial, InfiniteViewer, Lighting, LocalViewer, Model, NoFog, Viewer,
};
use crate::lighting::{Material, MaterialDesc, Viewed};
use crate::num::{cof3, dot3, Mat4, Scalar};

fn rgb(c: [f32; 4]) -> [f32; 3] {
    [c[0], c[1], c[2]]
}

/// [`ParamError::LightCount`] for `lights` in a set of `capacity`.
fn count_error(lights: &[GlLight], capacity: usize) -> ParamError {
    ParamError::LightCount {
        lights: lights.len(),
        capacity,
    }
}

/// One OpenGL light's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlLight {
    /// `GL_AMBIENT` (default 0, 0, 0, 1).
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE` (default 1, 1, 1, 1 for light 0, else 0, 0, 0, 1).
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR` (default as diffuse).
    pub specular: [f32; 4],
    /// `GL_POSITION` in eye coordinates (default 0, 0, 1, 0): `w = 0` is a
    /// directional light from `xyz`, otherwise a positional light at `xyz/w`.
    pub position: [f32; 4],
    /// `GL_SPOT_DIRECTION` in eye coordinates (default 0, 0, −1).
    pub spot_direction: [f32; 3],
    /// `GL_SPOT_EXPONENT` (default 0; a real number in 0..=128).
    pub spot_exponent: f32,
    /// `GL_SPOT_CUTOFF` in degrees: 0..=90, or 180 for no cone (default 180).
    pub spot_cutoff: f32,
    /// `GL_CONSTANT_ATTENUATION` (default 1).
    pub constant_attenuation: f32,
    /// `GL_LINEAR_ATTENUATION` (default 0).
    pub linear_attenuation: f32,
    /// `GL_QUADRATIC_ATTENUATION` (default 0).
    pub quadratic_attenuation: f32,
}

impl GlLight {
    /// `GL_LIGHT0`'s defaults: white diffuse and specular, directional from +z.
    pub fn light0() -> Self {
        Self {
            diffuse: [1.0; 4],
            specular: [1.0; 4],
            ..Self::light_n()
        }
    }

    /// The defaults of `GL_LIGHT1` and later: black diffuse and specular.
    pub fn light_n() -> Self {
        Self {
            ambient: [0.0, 0.0, 0.0, 1.0],
            diffuse: [0.0, 0.0, 0.0, 1.0],
            specular: [0.0, 0.0, 0.0, 1.0],
            position: [0.0, 0.0, 1.0, 0.0],
            spot_direction: [0.0, 0.0, -1.0],
            spot_exponent: 0.0,
            spot_cutoff: 180.0,
            constant_attenuation: 1.0,
            linear_attenuation: 0.0,
            quadratic_attenuation: 0.0,
        }
    }

    /// The light as `glLightfv` stores it when `modelview` is the current matrix
    /// (`GL_POSITION` by the whole matrix, `GL_SPOT_DIRECTION` by its upper-left
    /// 3×3): world lights and the view matrix give eye coordinates.
    ///
    /// ```
    /// use fixshade::lighting::gl::GlLight;
    /// use fixshade::num::Mat4;
    /// let world = GlLight { position: [1.0, 2.0, 3.0, 1.0], ..GlLight::light0() };
    /// let eye = world.transformed(&Mat4::translate([0.0, 0.0, -5.0]));
    /// assert_eq!(eye.position, [1.0, 2.0, -2.0, 1.0]);
    /// ```
    pub fn transformed(&self, modelview: &Mat4) -> Self {
        let m = &modelview.m;
        // in f64: the products of a view matrix with far positions keep f32 precision
        let row = |r: usize, v: [f32; 4], n: usize| {
            (0..n)
                .map(|c| f64::from(m[r][c]) * f64::from(v[c]))
                .sum::<f64>() as f32
        };
        let d = self.spot_direction;
        Self {
            position: core::array::from_fn(|r| row(r, self.position, 4)),
            spot_direction: core::array::from_fn(|r| row(r, [d[0], d[1], d[2], 0.0], 3)),
            ..*self
        }
    }

    /// The equivalent light description. Errors as OpenGL's `GL_INVALID_VALUE`:
    /// a cutoff outside 0..=90 and not 180, a spot exponent outside 0..=128, a
    /// negative attenuation (when the light is built); also non-finite values.
    /// Colours are taken as given (any sign).
    pub fn to_desc(&self) -> Result<LightDesc, ParamError> {
        let [x, y, z, w] = finite_all("GL_POSITION", self.position)?;
        let attenuation = [
            self.constant_attenuation,
            self.linear_attenuation,
            self.quadratic_attenuation,
        ];
        let kind = if w == 0.0 {
            LightKind::Directional {
                towards_light: [x, y, z],
            }
        } else {
            let position = [x / w, y / w, z / w];
            let cutoff = finite("GL_SPOT_CUTOFF", self.spot_cutoff)?;
            if cutoff == 180.0 {
                LightKind::Point {
                    position,
                    attenuation,
                }
            } else if (0.0..=90.0).contains(&cutoff) {
                let e = finite("GL_SPOT_EXPONENT", self.spot_exponent)?;
                if !(0.0..=128.0).contains(&e) {
                    return Err(ParamError::ExponentOutOfRange("GL_SPOT_EXPONENT"));
                }
                LightKind::Spot {
                    position,
                    axis: self.spot_direction,
                    exponent: e,
                    cutoff_deg: cutoff,
                    attenuation,
                }
            } else {
                return Err(ParamError::CutoffOutOfRange);
            }
        };
        Ok(LightDesc {
            kind,
            ambient: rgb(self.ambient),
            diffuse: rgb(self.diffuse),
            specular: rgb(self.specular),
        })
    }

    /// The light's colours in tier `S` (any sign, as OpenGL takes them; kept
    /// `f32` until a lighting multiplies them with a material).
    pub fn colors<S: Scalar>(&self) -> Result<LightColors<S>, ParamError> {
        LightColors::signed(rgb(self.ambient), rgb(self.diffuse), rgb(self.specular))
    }

    /// The light as the fixshade light type of its kind: `L` is
    /// [`DirectionalLight`] (`w = 0`), [`PointLight`] (`w ≠ 0`, cutoff 180),
    /// [`SpotLight`] (`w ≠ 0`, cutoff 0..=90) or [`AnyLight`] (any); a light of
    /// another kind is a [`ParamError::LightKind`].
    ///
    /// ```
    /// use fixshade::lighting::gl::GlLight;
    /// use fixshade::lighting::{AnyLight, DirectionalLight, PointLight};
    /// use fixshade::num::Q14;
    /// let sun = GlLight::light0();
    /// let d: DirectionalLight<Q14> = sun.to_light().unwrap();
    /// assert!(sun.to_light::<PointLight<Q14>>().is_err());
    /// let bulb = GlLight { position: [0.0, 2.0, 1.0, 1.0], ..GlLight::light0() };
    /// let p: AnyLight<Q14> = bulb.to_light().unwrap();
    /// assert!(matches!(p, AnyLight::Point(_)));
    /// ```
    pub fn to_light<L: FromGlLight>(&self) -> Result<L, ParamError> {
        L::from_gl_light(self)
    }
}

/// The light types an OpenGL light converts to ([`GlLight::to_light`]) and the
/// light sets [`GlScene::lighting`] builds: sealed, not re-exported.
mod from_gl {
    use super::{GlLight, LightSet, ParamError, Scalar};

    /// A light type that an OpenGL light converts to (`GlLight::to_light`).
    pub trait FromGlLight: Sized {
        /// The light of `light`'s parameters.
        fn from_gl_light(light: &GlLight) -> Result<Self, ParamError>;
    }

    /// A light set built from the enabled OpenGL lights (`GlScene::lighting`).
    pub trait GlLightSet<S: Scalar>: LightSet<S> + Sized {
        /// The set of `lights`; `ParamError::LightCount` when their number does
        /// not fit, `ParamError::LightKind` when a light is of another kind.
        fn from_gl_lights(lights: &[GlLight]) -> Result<Self, ParamError>;
    }
}
use from_gl::{FromGlLight, GlLightSet};

impl<S: Scalar> FromGlLight for AnyLight<S> {
    fn from_gl_light(light: &GlLight) -> Result<Self, ParamError> {
        AnyLight::with_colors(&light.to_desc()?, light.colors()?)
    }
}

macro_rules! from_gl_kind {
    ($($ty:ident, $variant:ident, $msg:expr;)*) => {$(
        impl<S: Scalar> FromGlLight for $ty<S> {
            fn from_gl_light(light: &GlLight) -> Result<Self, ParamError> {
                match AnyLight::<S>::from_gl_light(light)? {
                    AnyLight::$variant(l) => Ok(l),
                    _ => Err(ParamError::LightKind($msg)),
                }
            }
        }
    )*};
}
from_gl_kind! {
    DirectionalLight, Directional, "a DirectionalLight needs GL_POSITION w = 0";
    PointLight, Point, "a PointLight needs GL_POSITION w ≠ 0 and GL_SPOT_CUTOFF 180";
    SpotLight, Spot, "a SpotLight needs GL_POSITION w ≠ 0 and GL_SPOT_CUTOFF in 0..=90";
}

macro_rules! gl_light_set_single {
    ($($ty:ident),*) => {$(
        impl<S: Scalar> GlLightSet<S> for $ty<S> {
            fn from_gl_lights(lights: &[GlLight]) -> Result<Self, ParamError> {
                match lights {
                    [l] => l.to_light(),
                    _ => Err(count_error(lights, 1)),
                }
            }
        }
    )*};
}
gl_light_set_single!(DirectionalLight, PointLight, SpotLight, AnyLight);

impl<S: Scalar, L: FromGlLight + LightSet<S>, const K: usize> GlLightSet<S> for [L; K] {
    fn from_gl_lights(lights: &[GlLight]) -> Result<Self, ParamError> {
        if lights.len() != K {
            return Err(count_error(lights, K));
        }
        let v: heapless::Vec<L, K> = GlLightSet::<S>::from_gl_lights(lights)?;
        v.into_array().map_err(|_| count_error(lights, K))
    }
}

impl<S: Scalar, L: FromGlLight + LightSet<S>, const K: usize> GlLightSet<S>
    for heapless::Vec<L, K>
{
    fn from_gl_lights(lights: &[GlLight]) -> Result<Self, ParamError> {
        let mut v = heapless::Vec::new();
        for l in lights {
            v.push(l.to_light()?).map_err(|_| count_error(lights, K))?;
        }
        Ok(v)
    }
}

/// A viewer type that `GL_LIGHT_MODEL_LOCAL_VIEWER` selects: [`InfiniteViewer`]
/// on +z (false, OpenGL's default) or [`LocalViewer`] at the eye (true). The
/// other type is a [`ParamError::Viewer`].
pub trait GlViewer<S: Scalar>: Viewer<S> + Sized {
    /// The viewer of `model`.
    fn from_light_model(model: &GlLightModel) -> Result<Self, ParamError>;
}

impl<S: Scalar> GlViewer<S> for InfiniteViewer<S> {
    fn from_light_model(model: &GlLightModel) -> Result<Self, ParamError> {
        if model.local_viewer {
            return Err(ParamError::Viewer(
                "GL_LIGHT_MODEL_LOCAL_VIEWER is set: use LocalViewer",
            ));
        }
        Ok(Self::default())
    }
}

impl<S: Scalar> GlViewer<S> for LocalViewer<S> {
    fn from_light_model(model: &GlLightModel) -> Result<Self, ParamError> {
        if !model.local_viewer {
            return Err(ParamError::Viewer(
                "GL_LIGHT_MODEL_LOCAL_VIEWER is not set: use InfiniteViewer",
            ));
        }
        LocalViewer::new([0.0; 3])
    }
}

/// OpenGL material parameters (one face).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlMaterial {
    /// `GL_AMBIENT` (default 0.2, 0.2, 0.2, 1).
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE` (default 0.8, 0.8, 0.8, 1).
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR` (default 0, 0, 0, 1).
    pub specular: [f32; 4],
    /// `GL_EMISSION` (default 0, 0, 0, 1).
    pub emission: [f32; 4],
    /// `GL_SHININESS` (default 0; a real number in 0..=128).
    pub shininess: f32,
}

impl Default for GlMaterial {
    fn default() -> Self {
        Self {
            ambient: [0.2, 0.2, 0.2, 1.0],
            diffuse: [0.8, 0.8, 0.8, 1.0],
            specular: [0.0, 0.0, 0.0, 1.0],
            emission: [0.0, 0.0, 0.0, 1.0],
            shininess: 0.0,
        }
    }
}

impl GlMaterial {
    /// `GL_AMBIENT_AND_DIFFUSE`: both colours at once.
    pub fn with_ambient_and_diffuse(self, c: [f32; 4]) -> Self {
        Self {
            ambient: c,
            diffuse: c,
            ..self
        }
    }

    /// The equivalent material description (validated later by
    /// [`Material::signed`]). Errors as OpenGL's `GL_INVALID_VALUE`: a
    /// `GL_SHININESS` outside 0..=128.
    pub fn to_desc(&self) -> Result<MaterialDesc, ParamError> {
        let n = finite("GL_SHININESS", self.shininess)?;
        if !(0.0..=128.0).contains(&n) {
            return Err(ParamError::ExponentOutOfRange("GL_SHININESS"));
        }
        Ok(MaterialDesc {
            emission: rgb(self.emission),
            ambient: rgb(self.ambient),
            diffuse: rgb(self.diffuse),
            specular: rgb(self.specular),
            shininess: n,
            ..MaterialDesc::default()
        })
    }

    /// The material in tier `S` (colours of any sign, as OpenGL takes them).
    pub fn to_material<S: Scalar>(&self) -> Result<Material<S>, ParamError> {
        Material::signed(&self.to_desc()?)
    }

    /// The alpha OpenGL's lighting gives this face (the diffuse colour's), for a
    /// program that blends: fixshade's pixel formats have no alpha channel.
    pub fn alpha(&self) -> f32 {
        self.diffuse[3]
    }
}

/// `glLightModel` parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlLightModel {
    /// `GL_LIGHT_MODEL_AMBIENT` (default 0.2, 0.2, 0.2, 1; any sign).
    pub ambient: [f32; 4],
    /// `GL_LIGHT_MODEL_LOCAL_VIEWER` (default false: viewer at infinity on +z; true:
    /// [`LocalViewer`] at the origin).
    pub local_viewer: bool,
    /// `GL_LIGHT_MODEL_TWO_SIDE` (default false): back faces lit with the back
    /// material and the negated normal ([`GlScene::back_lighting`]).
    pub two_side: bool,
    /// `GL_LIGHT_MODEL_COLOR_CONTROL` = `GL_SEPARATE_SPECULAR_COLOR` (default false,
    /// `GL_SINGLE_COLOR`): the specular colour clamped and added apart
    /// ([`LitColor::separate`](crate::lighting::LitColor::separate)).
    pub separate_specular: bool,
}

impl Default for GlLightModel {
    fn default() -> Self {
        Self {
            ambient: [0.2, 0.2, 0.2, 1.0],
            local_viewer: false,
            two_side: false,
            separate_specular: false,
        }
    }
}

impl GlLightModel {
    /// The global ambient light in tier `S`, validated (finite; any sign).
    pub fn ambient_rgb<S: Scalar>(&self) -> Result<Rgb<S>, ParamError> {
        Rgb::try_from_f32_signed("GL_LIGHT_MODEL_AMBIENT", rgb(self.ambient))
    }
}

/// Which faces `glColorMaterial` applies to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum GlFace {
    /// `GL_FRONT`.
    Front,
    /// `GL_BACK`.
    Back,
    /// `GL_FRONT_AND_BACK` (OpenGL's default).
    #[default]
    FrontAndBack,
}

/// `glEnable(GL_COLOR_MATERIAL)` with `glColorMaterial(face, mode)`: the vertex
/// colour replaces the material colour `mode` names on `face`.
///
/// The default is OpenGL's: both faces, `GL_AMBIENT_AND_DIFFUSE`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GlColorMaterial {
    /// The faces.
    pub face: GlFace,
    /// The material colour replaced (OpenGL's default:
    /// [`ColorMaterial::AmbientAndDiffuse`]; [`ColorMaterial::Off`] replaces none).
    pub mode: ColorMaterial,
}

impl Default for GlColorMaterial {
    fn default() -> Self {
        Self {
            face: GlFace::default(),
            mode: ColorMaterial::AmbientAndDiffuse,
        }
    }
}

/// The OpenGL lighting state of one draw: the enabled lights (eye coordinates, see
/// [`GlLight::transformed`]), the front and back materials, the light model and
/// `GL_COLOR_MATERIAL`. [`GlScene::lighting`] turns it into a [`Lighting`] of any
/// tier in one call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlScene<'a> {
    /// The enabled lights, in order (up to 8 in OpenGL; as many as the light set
    /// holds here).
    pub lights: &'a [GlLight],
    /// `GL_FRONT` material.
    pub front: GlMaterial,
    /// `GL_BACK` material (used with [`GlLightModel::two_side`]).
    pub back: GlMaterial,
    /// `glLightModel` state.
    pub model: GlLightModel,
    /// `GL_COLOR_MATERIAL` (`None`: disabled, OpenGL's default).
    pub color_material: Option<GlColorMaterial>,
}

impl<'a> GlScene<'a> {
    /// `lights` with `material` on both faces, no colour material.
    pub fn new(lights: &'a [GlLight], material: GlMaterial, model: GlLightModel) -> Self {
        Self {
            lights,
            front: material,
            back: material,
            model,
            color_material: None,
        }
    }

    /// The lighting of the front faces in tier `S`, built from the GL state and
    /// [checked](Lighting::checked): model `M` (OpenGL's is
    /// [`BlinnPhong`](crate::lighting::BlinnPhong)) and viewer `V` of the
    /// caller's choosing; `L` is one light type ([`GlLight::to_light`]) for
    /// exactly one enabled light, `[L; K]` for exactly `K`,
    /// `heapless::Vec<L, K>` for up to `K` (OpenGL guarantees 8).
    ///
    /// Errors: invalid GL parameters (as `GL_INVALID_VALUE`), lights `L` cannot
    /// hold ([`ParamError::LightCount`], [`ParamError::LightKind`]), a viewer
    /// not matching `GL_LIGHT_MODEL_LOCAL_VIEWER` ([`GlViewer`]), terms beyond
    /// the tier's range ([`ParamError::TierRange`]).
    ///
    /// ```
    /// use fixshade::heapless;
    /// use fixshade::lighting::gl::{GlLight, GlLightModel, GlMaterial, GlScene};
    /// use fixshade::prelude::*;
    /// let lights = [
    ///     GlLight { diffuse: [2.5, 2.5, 2.5, 1.0], ..GlLight::light0() },
    ///     GlLight { position: [0.0, 1.0, 2.0, 1.0], constant_attenuation: 0.25, ..GlLight::light0() },
    /// ];
    /// let mat = GlMaterial { diffuse: [0.2, 0.2, 0.2, 1.0], ..GlMaterial::default() };
    /// let model = GlLightModel { local_viewer: true, ..GlLightModel::default() };
    /// let scene = GlScene::new(&lights, mat, model);
    /// // up to 8 lights of any kind, OpenGL's model, GL_LIGHT_MODEL_LOCAL_VIEWER
    /// let lit: Viewed<Lighting<Q14, heapless::Vec<AnyLight<Q14>, 8>, BlinnPhong, LocalViewer<Q14>>> =
    ///     scene.lighting()?;
    /// // the wrong viewer type is an error, not another picture
    /// assert!(scene.lighting::<Q14, [AnyLight<Q14>; 2], BlinnPhong, InfiniteViewer<Q14>>().is_err());
    /// # Ok::<(), ParamError>(())
    /// ```
    #[allow(clippy::type_complexity)]
    pub fn lighting<S, L, M, V>(&self) -> Result<Viewed<Lighting<S, L, M, V, NoFog>>, ParamError>
    where
        S: Scalar,
        L: GlLightSet<S>,
        M: Model,
        V: GlViewer<S>,
    {
        self.face_lighting(&self.front, GlFace::Front)
    }

    /// The lighting of the back faces with `GL_LIGHT_MODEL_TWO_SIDE`: the back
    /// material, the normal negated ([`BackFaces`]). Draw the back faces with it
    /// (`Cull::Front`), the front faces with [`GlScene::lighting`] (`Cull::Back`);
    /// without two-sided lighting, every face with [`GlScene::lighting`].
    #[allow(clippy::type_complexity)]
    pub fn back_lighting<S, L, M, V>(
        &self,
    ) -> Result<BackFaces<Viewed<Lighting<S, L, M, V, NoFog>>>, ParamError>
    where
        S: Scalar,
        L: GlLightSet<S>,
        M: Model,
        V: GlViewer<S>,
    {
        self.face_lighting(&self.back, GlFace::Back).map(BackFaces)
    }

    /// The `GL_COLOR_MATERIAL` mode on `face`.
    pub fn color_material_on(&self, face: GlFace) -> ColorMaterial {
        match self.color_material {
            Some(cm) if cm.face == face || cm.face == GlFace::FrontAndBack => cm.mode,
            _ => ColorMaterial::Off,
        }
    }

    #[allow(clippy::type_complexity)]
    fn face_lighting<S, L, M, V>(
        &self,
        material: &GlMaterial,
        face: GlFace,
    ) -> Result<Viewed<Lighting<S, L, M, V, NoFog>>, ParamError>
    where
        S: Scalar,
        L: GlLightSet<S>,
        M: Model,
        V: GlViewer<S>,
    {
        let lights = L::from_gl_lights(self.lights)?;
        let material = material.to_material::<S>()?;
        let ambient = finite_all("GL_LIGHT_MODEL_AMBIENT", rgb(self.model.ambient))?;
        Lighting::build(
            lights,
            material,
            ambient,
            V::from_light_model(&self.model)?,
            NoFog,
            self.color_material_on(face),
        )
        .checked()
        .map(Lighting::eye_space)
    }
}

/// What OpenGL does to normals after the modelview transform.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum GlNormals {
    /// Neither `GL_NORMALIZE` nor `GL_RESCALE_NORMAL` (OpenGL's default): the
    /// transformed normal is lit with its length, which dims or brightens the
    /// diffuse and specular terms.
    #[default]
    AsGiven,
    /// `GL_NORMALIZE`: unit length.
    Normalize,
    /// `GL_RESCALE_NORMAL`: scaled by the factor that makes unit normals unit again
    /// under a uniformly scaling modelview (`1/|row 3 of M⁻¹|`).
    Rescale,
}

impl GlNormals {
    /// The eye-space normal OpenGL lights for object-space normal `n` under
    /// `modelview`: `M⁻ᵀ·n` (upper-left 3×3), then normalised or rescaled as `self`
    /// says; a singular matrix gives zero; a fixed tier saturates a component
    /// beyond ±2. The renderer always lights as `GL_NORMALIZE` does (every mode
    /// normalises [`VertexIn::normal`](crate::shade::VertexIn::normal)).
    ///
    /// ```
    /// use fixshade::lighting::gl::GlNormals;
    /// use fixshade::num::Mat4;
    /// let m = Mat4::scale([2.0, 2.0, 2.0]);
    /// let n = [0.0, 0.0, 1.0];
    /// assert_eq!(GlNormals::AsGiven.eye_normal(&m, n), [0.0, 0.0, 0.5]);
    /// assert_eq!(GlNormals::Rescale.eye_normal(&m, n), [0.0, 0.0, 1.0]);
    /// assert_eq!(GlNormals::Normalize.eye_normal(&m, n), [0.0, 0.0, 1.0]);
    /// ```
    pub fn eye_normal(self, modelview: &Mat4, n: [f32; 3]) -> [f32; 3] {
        let m: [[f64; 3]; 3] =
            core::array::from_fn(|r| core::array::from_fn(|c| f64::from(modelview.m[r][c])));
        let cof = cof3(m);
        let det = dot3(m[0], cof[0]);
        if det == 0.0 || !det.is_finite() {
            return [0.0; 3];
        }
        // M⁻ᵀ = cof(M)/det; M⁻¹ = cof(M)ᵀ/det
        let nd = n.map(f64::from);
        let t: [f64; 3] =
            core::array::from_fn(|r| (0..3).map(|c| cof[r][c] * nd[c]).sum::<f64>() / det);
        let len = |v: [f64; 3]| libm::sqrt(dot3(v, v));
        let k = match self {
            GlNormals::AsGiven => 1.0,
            GlNormals::Normalize => {
                let l = len(t);
                if l > 0.0 {
                    1.0 / l
                } else {
                    0.0
                }
            }
            GlNormals::Rescale => {
                // row 3 of M⁻¹ is column 3 of cof(M), divided by det
                let row3 = [cof[0][2], cof[1][2], cof[2][2]].map(|v| v / det);
                1.0 / len(row3)
            }
        };
        t.map(|v| (v * k) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Q14, Q30};

    #[test]
    fn light_kinds() {
        let sun = GlLight::light0();
        assert!(DirectionalLight::<Q14>::from_gl_light(&sun).is_ok());
        assert_eq!(
            PointLight::<Q14>::from_gl_light(&sun).unwrap_err(),
            ParamError::LightKind("a PointLight needs GL_POSITION w ≠ 0 and GL_SPOT_CUTOFF 180")
        );
        let spot = GlLight {
            position: [0.0, 0.0, 3.0, 1.0],
            spot_cutoff: 30.0,
            spot_exponent: 2.5,
            ..GlLight::light0()
        };
        assert!(SpotLight::<Q30>::from_gl_light(&spot).is_ok());
        let bad = GlLight {
            spot_exponent: 129.0,
            ..spot
        };
        assert_eq!(
            AnyLight::<Q30>::from_gl_light(&bad).unwrap_err(),
            ParamError::ExponentOutOfRange("GL_SPOT_EXPONENT")
        );
        let lights = [sun, spot];
        assert!(<[AnyLight<Q14>; 2]>::from_gl_lights(&lights).is_ok());
        assert_eq!(
            <[AnyLight<Q14>; 3]>::from_gl_lights(&lights).unwrap_err(),
            ParamError::LightCount {
                lights: 2,
                capacity: 3
            }
        );
        assert!(<heapless::Vec<AnyLight<Q14>, 8>>::from_gl_lights(&lights).is_ok());
        assert!(<heapless::Vec<DirectionalLight<Q14>, 8>>::from_gl_lights(&lights).is_err());
    }

    #[test]
    fn rescale_is_normalize_for_uniform_scales() {
        let m = Mat4::scale([3.0, 3.0, 3.0]).mul(&Mat4::rotate_y(0.7));
        for n in [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, -1.0, 0.0]] {
            let a = GlNormals::Rescale.eye_normal(&m, n);
            let b = GlNormals::Normalize.eye_normal(&m, n);
            for i in 0..3 {
                assert!((a[i] - b[i]).abs() < 1e-6, "{a:?} {b:?}");
            }
        }
    }
}
