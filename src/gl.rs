//! The OpenGL 1.x fixed-function lighting parameters (`glLightfv`, `glMaterialfv`,
//! `glLightModelfv`), with OpenGL's defaults, converted to fixshade lights and
//! materials. A scene written for the classic pipeline gives the same colours with
//! the [`BlinnPhong`](crate::lighting::BlinnPhong) model (OpenGL evaluates
//! `(N·H)^s` only where `N·L > 0`, as fixshade does). Alpha components are ignored;
//! coordinates are eye space (the eye at the origin looking down −z).
//!
//! ```
//! use fixshade::gl::{GlLight, GlLightModel, GlMaterial};
//! use fixshade::prelude::*;
//! // glEnable(GL_LIGHT0) with every parameter at its default
//! let light = AnyLight::<Q14>::new(&GlLight::light0().to_desc().unwrap()).unwrap();
//! let mat = Material::new(&GlMaterial::default().to_desc().unwrap()).unwrap();
//! let model = GlLightModel::default();
//! let lit = Lighting::<Q14, _, BlinnPhong>::new([light], mat)
//!     .with_global_ambient(model.ambient_rgb().unwrap());
//! // 0.2·0.2 (global ambient) + 0.8 (diffuse, N = L) = 0.84
//! let c = lit.shade(&Lighting::<Q14, [AnyLight<Q14>; 1]>::origin(), Vec3::from_f32([0.0, 0.0, 1.0]));
//! assert_eq!(c.to_rgb888().r(), 214);
//! ```

use crate::color::Rgb;
use crate::error::{finite, ParamError};
use crate::light::{LightDesc, LightKind};
use crate::material::MaterialDesc;
use crate::num::Scalar;

fn rgb(c: [f32; 4]) -> [f32; 3] {
    [c[0], c[1], c[2]]
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
    /// `GL_POSITION` (default 0, 0, 1, 0): `w = 0` is a directional light from
    /// `xyz`, otherwise a positional light at `xyz/w`.
    pub position: [f32; 4],
    /// `GL_SPOT_DIRECTION` (default 0, 0, −1).
    pub spot_direction: [f32; 3],
    /// `GL_SPOT_EXPONENT` (default 0).
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

    /// The equivalent light description. Errors as OpenGL's `GL_INVALID_VALUE`:
    /// a cutoff outside 0..=90 and not 180, a negative exponent or attenuation;
    /// also non-finite values.
    pub fn to_desc(&self) -> Result<LightDesc, ParamError> {
        for c in self.position {
            finite("GL_POSITION", c)?;
        }
        let [x, y, z, w] = self.position;
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
                LightKind::Spot {
                    position,
                    axis: self.spot_direction,
                    exponent: self.spot_exponent,
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
}

/// OpenGL material parameters (front face).
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
    /// `GL_SHININESS` (default 0; OpenGL allows 0..=128, fixshade up to 65535).
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
    /// The equivalent material description (validated later by
    /// [`Material::new`](crate::material::Material::new)).
    pub fn to_desc(&self) -> Result<MaterialDesc, ParamError> {
        Ok(MaterialDesc {
            emission: rgb(self.emission),
            ambient: rgb(self.ambient),
            diffuse: rgb(self.diffuse),
            specular: rgb(self.specular),
            shininess: self.shininess,
            ..MaterialDesc::default()
        })
    }
}

/// `glLightModel` parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlLightModel {
    /// `GL_LIGHT_MODEL_AMBIENT` (default 0.2, 0.2, 0.2, 1).
    pub ambient: [f32; 4],
    /// `GL_LIGHT_MODEL_LOCAL_VIEWER` (default false: viewer at infinity on +z; true:
    /// [`LocalViewer`](crate::lighting::LocalViewer) at the origin).
    pub local_viewer: bool,
}

impl Default for GlLightModel {
    fn default() -> Self {
        Self {
            ambient: [0.2, 0.2, 0.2, 1.0],
            local_viewer: false,
        }
    }
}

impl GlLightModel {
    /// The global ambient light in tier `S`, validated.
    pub fn ambient_rgb<S: Scalar>(&self) -> Result<Rgb<S>, ParamError> {
        Rgb::try_from_f32("GL_LIGHT_MODEL_AMBIENT", rgb(self.ambient))
    }
}
