//! Materials: an MTL material's or a glTF material's values as fixshade's
//! [`MaterialDesc`] (OpenGL's Blinn-Phong parameters) and an opacity,
//! validated.
//!
//! **MTL**: `Kd` → diffuse, `Ka` → ambient, `Ks` → specular, `Ke` →
//! emission, `Ns` → shininess, `d` → opacity (or `1 − Tr` without `d`).
//! An absent statement keeps OpenGL's default ([`MaterialDesc::default`]:
//! ambient 0.2, diffuse 0.8, specular 0, emission 0, shininess 0; opacity 1).
//!
//! **glTF** (metallic-roughness; the reasons are in the crate's README):
//!
//! - diffuse = base colour · (1 − metallic);
//! - ambient = base colour;
//! - specular = 0.04 · (1 − metallic) + base colour · metallic (Schlick's
//!   `F0`: 4 % for dielectrics, the base colour for metals);
//! - shininess `n = 2/α² − 2` with `α = roughness²`, clamped to OpenGL's
//!   0..=128 ([`gltf_shininess`]);
//! - emission = emissive factor;
//! - opacity = the base colour's alpha, 1 when `alphaMode` is `OPAQUE`.
//!
//! **Validation** (what OpenGL and `fixshade::lighting::Material::new`
//! accept): colours finite and non-negative, shininess in 0..=128 (OpenGL's
//! `GL_SHININESS` range; MTL's `Ns` goes to 1000), opacity and the glTF
//! factors in 0..=1. A value outside is clamped with a warning, or is an
//! [`Error::Material`] with `--strict`; a NaN or infinite value takes the
//! default's.

use fixshade::lighting::MaterialDesc;

use crate::error::Error;
use crate::source::{MaterialValues, SourceMaterial};

/// OpenGL's largest `GL_SHININESS`.
pub const MAX_SHININESS: f64 = 128.0;

/// Schlick's `F0` of a dielectric (4 %, glTF's value for `metallic = 0`).
pub const DIELECTRIC_F0: f64 = 0.04;

/// A part's material as emitted: the library's description and the opacity
/// (the library draws opaque surfaces; the opacity is emitted for the
/// firmware to use or ignore).
#[derive(Clone, Debug, PartialEq)]
pub struct PartMaterial {
    /// The material's name (`None`: OpenGL's default material, for faces
    /// without one).
    pub name: Option<String>,
    /// What `fixshade::lighting::Material::new` takes.
    pub desc: MaterialDesc,
    /// 1 opaque, 0 invisible (MTL `d`, `1 − Tr`; glTF base colour alpha).
    pub opacity: f32,
}

impl Default for PartMaterial {
    /// OpenGL's default material, opaque, without a name.
    fn default() -> Self {
        PartMaterial {
            name: None,
            desc: MaterialDesc::default(),
            opacity: 1.0,
        }
    }
}

/// Blinn-Phong shininess for a glTF roughness: `α = roughness²` (glTF's
/// GGX `α`), `n = 2/α² − 2` (the exponent whose Blinn-Phong lobe matches a
/// Beckmann lobe of `α`, Walter et al. 2007), clamped to OpenGL's 0..=128.
///
/// ```
/// use fixshade_import::material::gltf_shininess;
/// assert_eq!(gltf_shininess(1.0), 0.0);
/// assert_eq!(gltf_shininess(0.5), 30.0); // α = 0.25: 2/0.0625 − 2
/// assert_eq!(gltf_shininess(0.3), 128.0); // 244.9, clamped
/// assert_eq!(gltf_shininess(0.0), 128.0);
/// ```
pub fn gltf_shininess(roughness: f64) -> f64 {
    let a = roughness * roughness;
    if a <= 0.0 {
        return MAX_SHININESS;
    }
    (2.0 / (a * a) - 2.0).clamp(0.0, MAX_SHININESS)
}

/// Checks values against their legal ranges: clamps with a warning, or the
/// error with `strict`.
struct Checker<'a> {
    material: &'a str,
    strict: bool,
    warnings: &'a mut Vec<String>,
}

impl Checker<'_> {
    /// `value` of `what` within `lo..=hi` (`hi` infinite: no upper bound);
    /// a NaN or infinite value is `default`.
    fn scalar(
        &mut self,
        what: &str,
        value: f64,
        lo: f64,
        hi: f64,
        default: f64,
    ) -> Result<f64, Error> {
        let (fixed, why) = if !value.is_finite() {
            (default, format!("is not a finite number: {default} used"))
        } else if value < lo || value > hi {
            let c = value.clamp(lo, hi);
            let range = if hi.is_finite() {
                format!("{lo}..={hi}")
            } else {
                format!("≥ {lo}")
            };
            (c, format!("is outside {range}: clamped to {c}"))
        } else {
            return Ok(value);
        };
        let message = format!("{what} {value} {why}");
        if self.strict {
            return Err(Error::Material {
                material: self.material.to_string(),
                message,
            });
        }
        self.warnings
            .push(format!("material `{}`: {message}", self.material));
        Ok(fixed)
    }

    /// A colour: every channel finite and non-negative.
    fn colour(&mut self, what: &str, c: [f64; 3], default: [f32; 3]) -> Result<[f32; 3], Error> {
        let mut out = [0.0f32; 3];
        for k in 0..3 {
            let what = format!("{what}[{k}]");
            out[k] = self.scalar(&what, c[k], 0.0, f64::INFINITY, f64::from(default[k]))? as f32;
        }
        Ok(out)
    }
}

/// The material of `m` (see the module documentation).
///
/// # Errors
///
/// With `strict`, [`Error::Material`] for the first value out of range;
/// otherwise it is clamped and a warning added to `warnings`.
pub fn convert(
    m: &SourceMaterial,
    strict: bool,
    warnings: &mut Vec<String>,
) -> Result<PartMaterial, Error> {
    let mut check = Checker {
        material: &m.name,
        strict,
        warnings,
    };
    let (desc, opacity) = match &m.values {
        MaterialValues::Mtl {
            ambient,
            diffuse,
            specular,
            emission,
            shininess,
            dissolve,
            transparency,
        } => from_mtl(
            &mut check,
            [*ambient, *diffuse, *specular, *emission],
            *shininess,
            *dissolve,
            *transparency,
        )?,
        MaterialValues::Gltf {
            base_colour,
            metallic,
            roughness,
            emissive,
            opaque,
        } => from_gltf(
            &mut check,
            *base_colour,
            *metallic,
            *roughness,
            *emissive,
            *opaque,
        )?,
    };
    // what the library will be asked to accept
    debug_assert!(fixshade::lighting::Material::<fixshade::num::Q14>::new(&desc).is_ok());
    Ok(PartMaterial {
        name: Some(m.name.clone()),
        desc,
        opacity,
    })
}

/// `[Ka, Kd, Ks, Ke]`, `Ns`, `d`, `Tr`.
fn from_mtl(
    check: &mut Checker<'_>,
    colours: [Option<[f64; 3]>; 4],
    shininess: Option<f64>,
    dissolve: Option<f64>,
    transparency: Option<f64>,
) -> Result<(MaterialDesc, f32), Error> {
    let d = MaterialDesc::default();
    let [ka, kd, ks, ke] = colours;
    let mut colour = |what: &str, c: Option<[f64; 3]>, default: [f32; 3]| match c {
        Some(c) => check.colour(what, c, default),
        None => Ok(default),
    };
    let ambient = colour("Ka", ka, d.ambient)?;
    let diffuse = colour("Kd", kd, d.diffuse)?;
    let specular = colour("Ks", ks, d.specular)?;
    let emission = colour("Ke", ke, d.emission)?;
    let shininess = match shininess {
        Some(n) => check.scalar("Ns", n, 0.0, MAX_SHININESS, f64::from(d.shininess))? as f32,
        None => d.shininess,
    };
    let opacity = match (dissolve, transparency) {
        (Some(o), _) => check.scalar("d", o, 0.0, 1.0, 1.0)?,
        (None, Some(t)) => 1.0 - check.scalar("Tr", t, 0.0, 1.0, 0.0)?,
        (None, None) => 1.0,
    };
    Ok((
        MaterialDesc {
            emission,
            ambient,
            diffuse,
            specular,
            shininess,
            ..d
        },
        opacity as f32,
    ))
}

/// A glTF metallic-roughness material as Blinn-Phong.
///
/// Why this mapping: it is the simplest that keeps what glTF's two factors
/// mean. A metal reflects only specularly, tinted by its base colour (its
/// Schlick `F0`), a dielectric diffusely in its base colour plus a white 4 %
/// specular — so diffuse = base · (1 − metallic) and specular =
/// mix(0.04, base, metallic). Ambient light arrives from every direction, and
/// a surface returns about its base colour of it whether it is a metal or
/// not: ambient = base colour (which also keeps a metal from going black
/// under ambient light alone). Roughness widens the highlight: Blinn-Phong's
/// exponent for a microfacet lobe of width `α` is `2/α² − 2` ([`gltf_shininess`]).
/// Not representable: the Fresnel rise at grazing angles, energy
/// conservation; a rough metal (metallic 1, roughness near 1) gets shininess
/// near 0 and no diffuse, and looks flat.
fn from_gltf(
    check: &mut Checker<'_>,
    base: [f64; 4],
    metallic: f64,
    roughness: f64,
    emissive: [f64; 3],
    opaque: bool,
) -> Result<(MaterialDesc, f32), Error> {
    let d = MaterialDesc::default();
    let mut unit = |what: &str, v: f64, default: f64| check.scalar(what, v, 0.0, 1.0, default);
    let mut b = [0.0f64; 4];
    for k in 0..4 {
        b[k] = unit(&format!("baseColorFactor[{k}]"), base[k], 1.0)?;
    }
    let m = unit("metallicFactor", metallic, 1.0)?;
    let r = unit("roughnessFactor", roughness, 1.0)?;
    let mut e = [0.0f64; 3];
    for k in 0..3 {
        e[k] = unit(&format!("emissiveFactor[{k}]"), emissive[k], 0.0)?;
    }
    let rgb = |f: &dyn Fn(usize) -> f64| -> [f32; 3] { core::array::from_fn(|k| f(k) as f32) };
    Ok((
        MaterialDesc {
            emission: rgb(&|k| e[k]),
            ambient: rgb(&|k| b[k]),
            diffuse: rgb(&|k| b[k] * (1.0 - m)),
            specular: rgb(&|k| DIELECTRIC_F0 * (1.0 - m) + b[k] * m),
            shininess: gltf_shininess(r) as f32,
            ..d
        },
        if opaque { 1.0 } else { b[3] as f32 },
    ))
}
