//! The `f64` reference model: the same equations as [`fixshade::lighting`], written
//! plainly for reading, from the same `f32` descriptions. Tests, benchmarks and
//! the host harnesses compare every tier against it; firmware never uses it.

use fixshade::lighting::MaterialDesc;
use fixshade::lighting::{ColorMaterial, Specular};
use fixshade::lighting::{LightDesc, LightKind};

/// A 3-vector of `f64`.
pub type V3 = [f64; 3];

fn v(a: [f32; 3]) -> V3 {
    [a[0] as f64, a[1] as f64, a[2] as f64]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn mul(a: V3, b: V3) -> V3 {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}
fn length(a: V3) -> f64 {
    libm::sqrt(dot(a, a))
}
/// `a/|a|`, or zero for a zero vector.
pub fn normalize(a: V3) -> V3 {
    let l = length(a);
    if l > 0.0 {
        scale(a, 1.0 / l)
    } else {
        [0.0; 3]
    }
}
/// `x^n` for a real exponent (`x^0 = 1`, also for `x = 0`).
fn powf(x: f64, n: f32) -> f64 {
    libm::pow(x, n as f64)
}

/// Where the eye is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewerDesc {
    /// At infinity, in this direction from the scene.
    Infinite([f32; 3]),
    /// At this point.
    Local([f32; 3]),
}

/// Linear fog parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FogDesc {
    /// Distance where fading starts.
    pub start: f32,
    /// Distance where only the fog colour remains.
    pub end: f32,
    /// Fog colour.
    pub color: [f32; 3],
}

/// The terms to evaluate (the reference's counterpart of [`fixshade::lighting::Model`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelDesc {
    /// Specular model.
    pub specular: Specular,
    /// `(N·L)^b`.
    pub brilliance: bool,
    /// Schlick's `f(β)`.
    pub fresnel: bool,
    /// Transmission.
    pub transmission: bool,
}

impl ModelDesc {
    /// The description of a [`fixshade::lighting::Model`] type.
    pub fn of<M: fixshade::lighting::Model>() -> Self {
        Self {
            specular: M::SPECULAR,
            brilliance: M::BRILLIANCE,
            fresnel: M::FRESNEL,
            transmission: M::TRANSMISSION,
        }
    }
}

/// A scene for the reference model.
#[derive(Clone, Copy, Debug)]
pub struct Reference<'a> {
    /// The lights.
    pub lights: &'a [LightDesc],
    /// The material.
    pub material: MaterialDesc,
    /// Global ambient light.
    pub global_ambient: [f32; 3],
    /// The viewer.
    pub viewer: ViewerDesc,
    /// Fog, if any.
    pub fog: Option<FogDesc>,
    /// The terms.
    pub model: ModelDesc,
}

/// How [`Reference::shade_parts`] treats a vertex (OpenGL state beyond the light
/// and material parameters).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOptions {
    /// `GL_NORMALIZE`: normalise the normal (else it is used as given).
    pub normalize: bool,
    /// `GL_COLOR_MATERIAL`'s mode.
    pub color_material: ColorMaterial,
    /// The vertex colour (`glColor`), used when `color_material` is not `Off`.
    pub color: [f32; 3],
}

impl Default for VertexOptions {
    fn default() -> Self {
        Self {
            normalize: true,
            color_material: ColorMaterial::Off,
            color: [1.0; 3],
        }
    }
}

impl Reference<'_> {
    /// Linear RGB at point `p` with normal `n` (normalised here), unclamped.
    pub fn shade(&self, p: V3, n: V3) -> V3 {
        let (primary, secondary) = self.shade_parts(p, n, &VertexOptions::default());
        add(primary, secondary)
    }

    /// OpenGL's primary (emission, ambient, diffuse) and secondary (specular,
    /// transmission) colours at `p` with normal `n`, unclamped: the material colour
    /// `o.color_material` names is `o.color`, and the normal is normalised only with
    /// `o.normalize`. Fog fades the diffuse part towards its colour and the
    /// secondary colour towards zero.
    pub fn shade_parts(&self, p: V3, n: V3, o: &VertexOptions) -> (V3, V3) {
        let n = if o.normalize { normalize(n) } else { n };
        let mut m = self.material;
        match o.color_material {
            ColorMaterial::Off => {}
            ColorMaterial::Emission => m.emission = o.color,
            ColorMaterial::Ambient => m.ambient = o.color,
            ColorMaterial::Diffuse => m.diffuse = o.color,
            ColorMaterial::Specular => m.specular = o.color,
            ColorMaterial::AmbientAndDiffuse => {
                m.ambient = o.color;
                m.diffuse = o.color;
            }
        }
        let m = &m;

        let (view, view_dist) = match self.viewer {
            ViewerDesc::Infinite(d) => {
                let d = normalize(v(d));
                (d, -dot(p, d))
            }
            ViewerDesc::Local(e) => {
                let to_eye = sub(v(e), p);
                (normalize(to_eye), length(to_eye))
            }
        };
        // emission + global ambient
        let mut ambient = add(v(m.emission), mul(v(self.global_ambient), v(m.ambient)));
        let mut direct = [0.0; 3];
        let mut specular = [0.0; 3];
        for light in self.lights {
            let (l, factor) = match light.kind {
                LightKind::Directional { towards_light } => (normalize(v(towards_light)), 1.0),
                LightKind::Point {
                    position,
                    attenuation,
                } => {
                    let to_light = sub(v(position), p);
                    let d = length(to_light);
                    (normalize(to_light), attenuation_factor(attenuation, d))
                }
                LightKind::Spot {
                    position,
                    axis,
                    exponent,
                    cutoff_deg,
                    attenuation,
                } => {
                    let to_light = sub(v(position), p);
                    let d = length(to_light);
                    let l = normalize(to_light);
                    let cos_phi = -dot(normalize(v(axis)), l);
                    let cos_cut = libm::cos(cutoff_deg as f64 * core::f64::consts::PI / 180.0);
                    let spot = if cos_phi >= cos_cut && cos_phi > 0.0 {
                        powf(cos_phi.min(1.0), exponent)
                    } else {
                        0.0
                    };
                    (l, spot * attenuation_factor(attenuation, d))
                }
            };
            // ambient of this light: ka·Ia
            ambient = add(ambient, scale(mul(v(light.ambient), v(m.ambient)), factor));
            let nl = dot(n, l);
            let mut c = [0.0; 3];
            let mut sp = [0.0; 3];
            if nl > 0.0 {
                // diffuse: kd·Id·(N·L)^b
                let d = if self.model.brilliance {
                    libm::pow(nl.min(1.0), m.brilliance as f64)
                } else {
                    nl
                };
                c = scale(mul(v(light.diffuse), v(m.diffuse)), d);
                // specular: ks·Is·f(β)·x^n
                let x = match self.model.specular {
                    Specular::None => 0.0,
                    Specular::Phong => dot(sub(scale(n, 2.0 * nl), l), view),
                    Specular::BlinnPhong => dot(n, normalize(add(l, view))),
                };
                if self.model.specular != Specular::None && x > 0.0 {
                    let mut s = powf(x.min(1.0), m.shininess);
                    if self.model.fresnel {
                        let f0 = m.fresnel_f0 as f64;
                        s *= f0 + (1.0 - f0) * libm::pow(1.0 - nl.min(1.0), 5.0);
                    }
                    sp = scale(mul(v(light.specular), v(m.specular)), s);
                }
            } else if self.model.transmission && nl < 0.0 {
                // Snell: T = −η·L + (c2 − η·c1)·N, c1 = −N·L, c2 = √(1 − η²(1 − c1²))
                let eta = 1.0 / m.refractive_index as f64;
                let c1 = -nl;
                let k = 1.0 - eta * eta * (1.0 - c1 * c1);
                if k > 0.0 {
                    let t = sub(scale(n, libm::sqrt(k) - eta * c1), scale(l, eta));
                    let tv = dot(t, view).clamp(0.0, 1.0);
                    sp = scale(
                        mul(v(light.specular), v(m.transmission)),
                        powf(tv, m.transmission_exponent),
                    );
                }
            }
            direct = add(direct, scale(c, factor));
            specular = add(specular, scale(sp, factor));
        }
        if let Some(f) = self.fog {
            let k = ((f.end as f64 - view_dist) / (f.end as f64 - f.start as f64)).clamp(0.0, 1.0);
            direct = add(scale(direct, k), scale(v(f.color), 1.0 - k));
            specular = scale(specular, k);
        }
        (add(ambient, direct), specular)
    }
}

fn attenuation_factor(k: [f32; 3], d: f64) -> f64 {
    let denom = k[0] as f64 + k[1] as f64 * d + k[2] as f64 * d * d;
    if denom > 0.0 {
        1.0 / denom
    } else {
        f64::INFINITY
    }
}

/// A linear value quantised to 8 bits as the tiers do: clamp to [0, 1], round.
pub fn to_u8(x: f64) -> u8 {
    libm::round(x.clamp(0.0, 1.0) * 255.0) as u8
}
