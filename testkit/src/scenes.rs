//! Random lighting samples for comparing the tiers with the f64 reference.
//!
//! Used by the lighting accuracy tests and the `accuracy` harness, so the
//! README's figures and the asserted bounds come from one generator.

#![allow(dead_code)]

use crate::reference::{to_u8, FogDesc, ModelDesc, Reference, ViewerDesc};
use fixshade::color::Rgb;
use fixshade::lighting::{AnyLight, LightDesc, LightKind};
use fixshade::lighting::{InfiniteViewer, Lighting, LinearFog, LocalViewer, Model};
use fixshade::lighting::{Material, MaterialDesc};
use fixshade::num::{point_from_f32, Scalar, Vec3};
use proptest::prelude::*;

/// The lighting term a sample isolates (all others off or zero).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Term {
    Ambient,
    Diffuse,
    Brilliance,
    Phong,
    BlinnPhong,
    Fresnel,
    Transmission,
    PointAttenuation,
    Spot,
    LocalViewer,
    Fog,
    Everything,
}

pub const TERMS: [Term; 12] = [
    Term::Ambient,
    Term::Diffuse,
    Term::Brilliance,
    Term::Phong,
    Term::BlinnPhong,
    Term::Fresnel,
    Term::Transmission,
    Term::PointAttenuation,
    Term::Spot,
    Term::LocalViewer,
    Term::Fog,
    Term::Everything,
];

/// Which model type a term is evaluated with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelKind {
    Lambert,
    Brilliance,
    Phong,
    Blinn,
    Full,
}

impl Term {
    pub fn model(self) -> ModelKind {
        match self {
            Term::Ambient | Term::Diffuse => ModelKind::Lambert,
            Term::Brilliance => ModelKind::Brilliance,
            Term::Phong => ModelKind::Phong,
            Term::Fresnel | Term::Transmission | Term::Everything => ModelKind::Full,
            _ => ModelKind::Blinn,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Term::Ambient => "ambient + emission",
            Term::Diffuse => "Lambert diffuse",
            Term::Brilliance => "diffuse brilliance (N·L)^b",
            Term::Phong => "Phong specular (R·V)^n",
            Term::BlinnPhong => "Blinn-Phong specular (N·H)^n",
            Term::Fresnel => "Fresnel angle factor f(β)",
            Term::Transmission => "transmission (T·V)^n",
            Term::PointAttenuation => "point light, 1/(a+bd+cd²)",
            Term::Spot => "spot light cos^e φ",
            Term::LocalViewer => "local viewer",
            Term::Fog => "linear fog",
            Term::Everything => "all terms, 1-4 mixed lights",
        }
    }
}

/// One shading problem: a scene and a surface point.
#[derive(Clone, Debug)]
pub struct Sample {
    pub lights: Vec<LightDesc>,
    pub material: MaterialDesc,
    pub global_ambient: [f32; 3],
    pub viewer: ViewerDesc,
    pub fog: Option<FogDesc>,
    pub p: [f32; 3],
    pub n: [f32; 3],
    pub model: ModelKind,
}

fn norm(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}
fn f32s(v: [f64; 3]) -> [f32; 3] {
    [v[0] as f32, v[1] as f32, v[2] as f32]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// A unit vector at angle `theta` from `axis`, azimuth `phi`.
fn around(axis: [f64; 3], theta: f64, phi: f64) -> [f64; 3] {
    let a = norm(axis);
    let helper = if a[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = norm(cross(a, helper));
    let w = cross(a, u);
    let (s, c) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    norm([
        a[0] * c + (u[0] * cp + w[0] * sp) * s,
        a[1] * c + (u[1] * cp + w[1] * sp) * s,
        a[2] * c + (u[2] * cp + w[2] * sp) * s,
    ])
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

prop_compose! {
    fn colour(max: f32)(r in 0.0..=max, g in 0.0..=max, b in 0.0..=max) -> [f32; 3] { [r, g, b] }
}

/// A range of specular exponents (the error of a power grows with the exponent).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Band {
    /// n in 1..=64
    Low,
    /// n in 65..=256
    Mid,
    /// n in 257..=1024
    High,
}

pub const BANDS: [Band; 3] = [Band::Low, Band::Mid, Band::High];

impl Band {
    pub fn range(self) -> (u32, u32) {
        match self {
            Band::Low => (1, 64),
            Band::Mid => (65, 256),
            Band::High => (257, 1024),
        }
    }
}

/// Specular exponents in a band.
pub fn shininess(band: Band) -> impl Strategy<Value = f32> {
    let (lo, hi) = band.range();
    (lo..=hi).prop_map(|n| n as f32)
}

/// A random sample isolating `term`. Light colours are scaled by 0.9/lights so the
/// light-dependent sum stays below 2 (the fixed tiers' range) before fog.
pub fn sample(term: Term, band: Band) -> impl Strategy<Value = Sample> {
    let lights_n = if term == Term::Everything {
        1usize..=4
    } else {
        1usize..=1
    };
    (
        lights_n,
        proptest::collection::vec(
            (
                0.0f64..1.0,
                0.0f64..1.0,
                0.0f64..1.0,
                0.0f64..1.0,
                (0.0f64..1.0, 0.0f64..1.0),
                colour(1.0),
            ),
            4,
        ),
        colour(1.0),
        colour(1.0),
        colour(1.0),
        shininess(band),
        // the normal: direction, and length (1, or below 1 as interpolated normals are)
        (
            0.0f64..1.3,
            0.0f64..6.3,
            prop_oneof![Just(1.0f64), 0.6f64..1.0],
        ),
        (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0),
        (0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0),
        (0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0),
    )
        .prop_map(
            move |(k, lights_raw, ka, kd, ks, n_exp, (nt, np, len), p, extra, wide)| {
                build(
                    term,
                    k,
                    &lights_raw,
                    ka,
                    kd,
                    ks,
                    n_exp,
                    (nt, np, len),
                    [p.0, p.1, p.2],
                    extra,
                    wide,
                )
            },
        )
}

/// The random numbers of one light: kind, direction (2), distance, attenuation (2),
/// colour.
type LightRaw = (f64, f64, f64, f64, (f64, f64), [f32; 3]);

#[allow(clippy::too_many_arguments)]
fn build(
    term: Term,
    k: usize,
    lights_raw: &[LightRaw],
    ka: [f32; 3],
    kd: [f32; 3],
    ks: [f32; 3],
    n_exp: f32,
    (nt, np, len): (f64, f64, f64),
    p: [f32; 3],
    extra: (f64, f64, f64),
    w: (f64, f64, f64),
) -> Sample {
    // Half of the samples with distances, attenuation or fog span the whole legal
    // range: positions up to ±12 288 units, lights up to 13 300 units away,
    // attenuation coefficients from 0 to whatever makes each term reach 3 at that
    // distance (c down to 10⁻⁸), fog ranges from a few units to 10³⁸ and to
    // ±f32::MAX, placed around the point's viewing distance.
    let ranged = matches!(
        term,
        Term::PointAttenuation | Term::Spot | Term::Fog | Term::LocalViewer | Term::Everything
    );
    let wide = ranged && w.0 < 0.5;
    let p = if wide {
        p.map(|c| c * (w.1 * 12.0).exp2() as f32)
    } else {
        p
    };
    let local = matches!(term, Term::LocalViewer | Term::Everything) && extra.0 < 0.7;
    let eye = [0.5f32, -0.3, 8.0];
    let viewer = if local {
        ViewerDesc::Local(eye)
    } else {
        ViewerDesc::Infinite([0.0, 0.0, 1.0])
    };
    let pd = [p[0] as f64, p[1] as f64, p[2] as f64];
    let v = match viewer {
        ViewerDesc::Local(e) => norm([
            e[0] as f64 - pd[0],
            e[1] as f64 - pd[1],
            e[2] as f64 - pd[2],
        ]),
        ViewerDesc::Infinite(d) => norm([d[0] as f64, d[1] as f64, d[2] as f64]),
    };
    // the normal: within ~75° of the viewer
    let n = around(v, nt, np);
    let specular_term = matches!(
        term,
        Term::Phong | Term::BlinnPhong | Term::Fresnel | Term::Everything
    );
    let scale = 0.9 / k as f32;
    let mut lights = Vec::new();
    for (i, &(a, b, c, d, (e, f), col)) in lights_raw.iter().take(k).enumerate() {
        let col = col.map(|x| x * scale);
        // direction to the light: near the specular direction half of the time, else anywhere
        // in the hemisphere around N (or behind it for transmission)
        let l = if specular_term && a < 0.5 {
            let spread = 2.0 / (n_exp as f64).sqrt();
            if term == Term::Phong {
                // R near V: L = reflect(V') about N, V' = V tilted
                let vt = around(v, b * spread, c * std::f64::consts::TAU);
                let nv = dot(n, vt);
                norm([
                    2.0 * nv * n[0] - vt[0],
                    2.0 * nv * n[1] - vt[1],
                    2.0 * nv * n[2] - vt[2],
                ])
            } else {
                // H near N: L = reflect(V) about H
                let h = around(n, b * spread, c * std::f64::consts::TAU);
                let hv = dot(h, v);
                norm([
                    2.0 * hv * h[0] - v[0],
                    2.0 * hv * h[1] - v[1],
                    2.0 * hv * h[2] - v[2],
                ])
            }
        } else if term == Term::Transmission {
            around([-n[0], -n[1], -n[2]], b * 1.5, c * std::f64::consts::TAU)
        } else {
            around(n, b * 1.6, c * std::f64::consts::TAU)
        };
        let dist = if wide {
            (-1.0 + 14.7 * d).exp2()
        } else {
            0.5 + d * 15.0
        };
        let pos = f32s([
            pd[0] + l[0] * dist,
            pd[1] + l[1] * dist,
            pd[2] + l[2] * dist,
        ]);
        let att = if wide {
            // a = 0 (pure 1/(b·d + c·d²)) a quarter of the time, b·d and c·d² up to 3
            // each (either may be 0); a + b·d + c·d² ≥ 0.6 keeps the factor within the
            // fixed tiers' range (below 2)
            let a = if e < 0.25 { 0.0 } else { 0.5 + e };
            let tb = if f < 0.2 { 0.0 } else { 3.0 * f };
            let tc = if (e * 13.0).fract() < 0.2 {
                0.0
            } else {
                3.0 * (e * 7.0).fract()
            };
            let tc = if a + tb + tc < 0.6 { tc + 0.6 } else { tc };
            [a as f32, (tb / dist) as f32, (tc / (dist * dist)) as f32]
        } else {
            [1.0, (b * 0.3) as f32, (c * 0.05) as f32]
        };
        let kind_pick = if term == Term::Everything {
            (i as f64 * 0.37 + a) % 1.0
        } else {
            0.0
        };
        let kind = match term {
            Term::PointAttenuation => LightKind::Point {
                position: pos,
                attenuation: att,
            },
            Term::Spot => spot(pos, l, extra, att),
            Term::Everything if kind_pick > 0.66 => spot(pos, l, extra, att),
            Term::Everything if kind_pick > 0.33 => LightKind::Point {
                position: pos,
                attenuation: att,
            },
            _ => LightKind::Directional {
                towards_light: f32s(l),
            },
        };
        lights.push(LightDesc {
            kind,
            ambient: if matches!(term, Term::Ambient | Term::Everything) {
                col.map(|x| x * 0.5)
            } else {
                [0.0; 3]
            },
            diffuse: col,
            specular: col,
        });
    }
    let none = [0.0f32; 3];
    let mut m = MaterialDesc {
        emission: none,
        ambient: none,
        diffuse: kd,
        specular: none,
        shininess: n_exp,
        brilliance: 1,
        fresnel_f0: 1.0,
        transmission: none,
        transmission_exponent: 1.0,
        refractive_index: 1.0,
    };
    let mut global_ambient = none;
    match term {
        Term::Ambient => {
            m.ambient = ka;
            m.emission = ks.map(|x| x * 0.3);
            m.diffuse = none;
            global_ambient = [0.3, 0.3, 0.3];
        }
        Term::Brilliance => m.brilliance = [1u8, 2, 4, 8][(extra.1 * 3.99) as usize],
        Term::Phong | Term::BlinnPhong => {
            m.diffuse = none;
            m.specular = ks;
        }
        Term::Fresnel => {
            m.diffuse = none;
            m.specular = ks;
            m.fresnel_f0 = extra.1 as f32;
        }
        Term::Transmission => {
            m.diffuse = none;
            m.transmission = ks;
            m.transmission_exponent = (1.0 + extra.1 * 30.0).round() as f32;
            m.refractive_index = (0.6 + extra.2 * 1.5) as f32;
        }
        Term::Everything => {
            m.ambient = ka.map(|x| x * 0.5);
            m.emission = [0.05, 0.02, 0.0];
            m.specular = ks.map(|x| x * 0.5);
            m.brilliance = [1u8, 2, 4, 8][(extra.1 * 3.99) as usize];
            m.fresnel_f0 = extra.2 as f32;
            m.transmission = ks.map(|x| x * 0.3);
            m.transmission_exponent = 4.0;
            m.refractive_index = 1.33;
            global_ambient = [0.1, 0.1, 0.1];
        }
        _ => {}
    }
    let fog = matches!(term, Term::Fog | Term::Everything).then(|| {
        if wide {
            // the viewing distance of the point, as the reference computes it
            let d = match viewer {
                ViewerDesc::Infinite(_) => -dot(pd, v),
                ViewerDesc::Local(e) => {
                    let t = [0, 1, 2].map(|i| e[i] as f64 - pd[i]);
                    dot(t, t).sqrt()
                }
            };
            if w.2 > 0.95 {
                FogDesc {
                    start: -f32::MAX,
                    end: f32::MAX,
                    color: [0.5, 0.55, 0.6],
                }
            } else {
                // range R from where the distance's own rounding (2^-16 units in the
                // fixed tiers, 2^-24 relative in f32) stays below 2^-10 of it, to 10^38;
                // d at fraction f0 ∈ [−0.3, 1.3] of the ramp
                let r_min = 0.05 + d.abs() * 2f64.powi(-11);
                let r = r_min * ((126.0 - r_min.log2()) * w.2 / 0.95).exp2();
                let f0 = -0.3 + 1.6 * extra.1;
                let end = d + f0 * r;
                FogDesc {
                    start: (end - r) as f32,
                    end: end as f32,
                    color: [0.5, 0.55, 0.6],
                }
            }
        } else {
            FogDesc {
                start: 2.0 + extra.2 as f32,
                end: 9.0 + extra.1 as f32 * 4.0,
                color: [0.5, 0.55, 0.6],
            }
        }
    });
    Sample {
        lights,
        material: m,
        global_ambient,
        viewer,
        fog,
        p,
        // an interpolated normal (length below 1) is what per-pixel shading
        // renormalises; the reference normalises it in f64
        n: f32s(n.map(|c| c * len)),
        model: term.model(),
    }
}

fn spot(pos: [f32; 3], l: [f64; 3], extra: (f64, f64, f64), att: [f32; 3]) -> LightKind {
    // the axis points from the light back towards the point, tilted by up to 40°
    let axis = around(
        [-l[0], -l[1], -l[2]],
        extra.2 * 0.7,
        extra.1 * std::f64::consts::TAU,
    );
    LightKind::Spot {
        position: pos,
        axis: f32s(axis),
        exponent: (extra.0 * 40.0).round() as f32,
        cutoff_deg: 20.0 + extra.1 as f32 * 60.0,
        attenuation: att,
    }
}

/// Whether the accuracy bounds exclude the sample: near a discontinuity, or outside
/// the fixed tiers' range.
pub fn excluded(s: &Sample) -> bool {
    near_discontinuity(s) || beyond_range(s)
}

/// Whether an attenuation factor of the sample exceeds 2 (`a + b·d + c·d² < ½`):
/// beyond the fixed tiers' range, where they carry the factor as `m·2^e` and the
/// error of every cosine is multiplied by it (the reference's sensitivity too;
/// `tests/lighting/attenuation_unbounded.rs` covers that domain with a bound that grows
/// with the factor); the generator keeps the sum above 0.6, but a search may
/// move a light closer.
pub fn beyond_range(s: &Sample) -> bool {
    let pd = s.p.map(|c| c as f64);
    s.lights.iter().any(|l| {
        let (pos, k) = match l.kind {
            LightKind::Directional { .. } => return false,
            LightKind::Point {
                position,
                attenuation,
            } => (position, attenuation),
            LightKind::Spot {
                position,
                attenuation,
                ..
            } => (position, attenuation),
        };
        let t = [0, 1, 2].map(|i| pos[i] as f64 - pd[i]);
        let d = dot(t, t).sqrt();
        (k[0] as f64 + k[1] as f64 * d + k[2] as f64 * d * d) < 0.5
    })
}

/// Whether the sample sits within 10⁻³ of a discontinuity of the equation, where
/// any rounding may switch a whole term on or off: `N·L = 0` (the specular term
/// exists only for `N·L > 0`), a spot cone's edge, or the edge of total internal
/// reflection (transmission: `cos² θt = 1 − η²·sin² θi` near 0, where the refracted
/// light jumps from grazing to none). The accuracy bounds exclude these samples;
/// `tests/lighting/lighting_extremes.rs` covers them for panics and range.
pub fn near_discontinuity(s: &Sample) -> bool {
    let pd = [s.p[0] as f64, s.p[1] as f64, s.p[2] as f64];
    let n = norm([s.n[0] as f64, s.n[1] as f64, s.n[2] as f64]);
    let transmits = s.model == ModelKind::Full && s.material.transmission != [0.0; 3];
    let eta = 1.0 / s.material.refractive_index as f64;
    s.lights.iter().any(|l| {
        let (dir, cone) = match l.kind {
            LightKind::Directional { towards_light } => {
                (norm(towards_light.map(|x| x as f64)), None)
            }
            LightKind::Point { position, .. } => {
                (norm([0, 1, 2].map(|i| position[i] as f64 - pd[i])), None)
            }
            LightKind::Spot {
                position,
                axis,
                cutoff_deg,
                ..
            } => {
                let d = norm([0, 1, 2].map(|i| position[i] as f64 - pd[i]));
                let a = norm(axis.map(|x| x as f64));
                let cos_phi = -dot(a, d);
                (
                    d,
                    Some((cos_phi - (cutoff_deg as f64).to_radians().cos()).abs()),
                )
            }
        };
        let nl = dot(n, dir);
        let tir_edge = transmits && nl < 0.0 && {
            let k = 1.0 - eta * eta * (1.0 - nl * nl);
            k.abs() < 1.0e-3
        };
        nl.abs() < 1.0e-3 || cone.is_some_and(|c| c < 1.0e-3) || tir_edge
    })
}

/// The reference colour of a sample, 8 bits per channel.
pub fn reference_u8(s: &Sample) -> [u8; 3] {
    reference_rgb(s).map(to_u8)
}

type M0 = fixshade::lighting::Lambert;
type MB = fixshade::lighting::Terms<0, true, false, false>;
type MP = fixshade::lighting::Phong;
type Mbp = fixshade::lighting::BlinnPhong;
type MF = fixshade::lighting::Full;

fn model_desc(m: ModelKind) -> ModelDesc {
    match m {
        ModelKind::Lambert => ModelDesc::of::<M0>(),
        ModelKind::Brilliance => ModelDesc::of::<MB>(),
        ModelKind::Phong => ModelDesc::of::<MP>(),
        ModelKind::Blinn => ModelDesc::of::<Mbp>(),
        ModelKind::Full => ModelDesc::of::<MF>(),
    }
}

/// The tier's colour of a sample, 8 bits per channel.
pub fn tier_u8<S: Scalar>(s: &Sample) -> [u8; 3] {
    let [r, g, b] = tier_rgb::<S>(s).to_unorm(8);
    [r as u8, g as u8, b as u8]
}

/// The tier's linear colour of a sample.
pub fn tier_rgb<S: Scalar>(s: &Sample) -> Rgb<S> {
    match s.model {
        ModelKind::Lambert => eval::<S, M0>(s),
        ModelKind::Brilliance => eval::<S, MB>(s),
        ModelKind::Phong => eval::<S, MP>(s),
        ModelKind::Blinn => eval::<S, Mbp>(s),
        ModelKind::Full => eval::<S, MF>(s),
    }
}

/// The reference's linear colour of a sample.
pub fn reference_rgb(s: &Sample) -> [f64; 3] {
    let r = Reference {
        lights: &s.lights,
        material: s.material,
        global_ambient: s.global_ambient,
        viewer: s.viewer,
        fog: s.fog,
        model: model_desc(s.model),
    };
    let p = [s.p[0] as f64, s.p[1] as f64, s.p[2] as f64];
    let n = [s.n[0] as f64, s.n[1] as f64, s.n[2] as f64];
    r.shade(p, n)
}

fn eval<S: Scalar, M: Model>(s: &Sample) -> Rgb<S> {
    let lights: heapless::Vec<AnyLight<S>, 4> =
        s.lights.iter().map(|d| AnyLight::new(d).unwrap()).collect();
    let mat = Material::<S>::new(&s.material).unwrap();
    let lit = Lighting::<S, _, M>::new(lights, mat)
        .with_global_ambient(fixshade::color::Rgb::from_f32(s.global_ambient));
    let p = point_from_f32::<S>(s.p);
    let n = Vec3::<S>::from_f32(s.n);
    match (s.viewer, s.fog) {
        (ViewerDesc::Infinite(d), None) => lit
            .with_viewer(InfiniteViewer::new(d).unwrap())
            .shade_normalizing(&p, n),
        (ViewerDesc::Infinite(d), Some(f)) => lit
            .with_viewer(InfiniteViewer::new(d).unwrap())
            .with_fog(LinearFog::new(f.start, f.end, f.color).unwrap())
            .shade_normalizing(&p, n),
        (ViewerDesc::Local(e), None) => lit
            .with_viewer(LocalViewer::new(e).unwrap())
            .shade_normalizing(&p, n),
        (ViewerDesc::Local(e), Some(f)) => lit
            .with_viewer(LocalViewer::new(e).unwrap())
            .with_fog(LinearFog::new(f.start, f.end, f.color).unwrap())
            .shade_normalizing(&p, n),
    }
}

/// Largest channel difference in 8-bit LSBs.
pub fn lsb_error(a: [u8; 3], b: [u8; 3]) -> u32 {
    (0..3)
        .map(|i| (a[i] as i32 - b[i] as i32).unsigned_abs())
        .max()
        .unwrap_or(0)
}

/// Max and mean error of tier `S` over `cases` samples of `term` (deterministic).
pub fn measure<S: Scalar>(term: Term, band: Band, cases: u32, seed: u64) -> (u32, f64, Sample) {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes),
    );
    let strat = sample(term, band);
    let (mut max, mut sum) = (0u32, 0u64);
    let mut worst = None;
    let mut done = 0;
    while done < cases {
        let s = strat.new_tree(&mut runner).unwrap().current();
        if excluded(&s) {
            continue;
        }
        done += 1;
        let e = lsb_error(tier_u8::<S>(&s), reference_u8(&s));
        sum += e as u64;
        if e >= max {
            max = e;
            worst = Some(s);
        }
    }
    (max, sum as f64 / cases as f64, worst.unwrap())
}

/// A small deterministic generator for the worst-case search (xorshift64*).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// Uniform in [0, 1).
    pub fn f(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The error of a sample before 8-bit quantisation: the largest channel difference
/// of the clamped linear colours, in 8-bit LSBs. The hill climb follows it (the
/// quantised error is flat almost everywhere).
pub fn linear_error<S: Scalar>(s: &Sample) -> f64 {
    let t = tier_rgb::<S>(s).to_f32();
    let r = reference_rgb(s);
    (0..3)
        .map(|i| ((t[i] as f64).clamp(0.0, 1.0) - r[i].clamp(0.0, 1.0)).abs() * 255.0)
        .fold(0.0, f64::max)
}

/// `s` moved a little: the normal's direction (and, for an interpolated normal, its
/// length), every light's direction from the surface point and its distance, the
/// exponent within `band`. `amount` is the rotation in radians.
pub fn perturb(s: &Sample, band: Band, amount: f64, rng: &mut Rng) -> Sample {
    let mut out = s.clone();
    let n = [s.n[0] as f64, s.n[1] as f64, s.n[2] as f64];
    let len = dot(n, n).sqrt();
    let dir = around(norm(n), amount * rng.f(), rng.f() * std::f64::consts::TAU);
    let len = if len > 0.9999 && rng.f() < 0.5 {
        len
    } else {
        (len * (1.0 + amount * (rng.f() - 0.5))).clamp(0.6, 1.0)
    };
    out.n = f32s(dir.map(|c| c * len));
    let pd = s.p.map(|c| c as f64);
    for l in &mut out.lights {
        let rotate = |v: [f64; 3], rng: &mut Rng| {
            let d = dot(v, v).sqrt();
            let u = around(norm(v), amount * rng.f(), rng.f() * std::f64::consts::TAU);
            let d = d * (1.0 + amount * (rng.f() - 0.5));
            u.map(|c| c * d)
        };
        match &mut l.kind {
            LightKind::Directional { towards_light } => {
                *towards_light = f32s(rotate(towards_light.map(|c| c as f64), rng));
            }
            LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
                let rel = [0, 1, 2].map(|i| position[i] as f64 - pd[i]);
                let rel = rotate(rel, rng);
                *position = f32s([0, 1, 2].map(|i| pd[i] + rel[i]));
            }
        }
    }
    let (lo, hi) = band.range();
    if rng.f() < 0.2 {
        let n = s.material.shininess + if rng.f() < 0.5 { -1.0 } else { 1.0 };
        out.material.shininess = n.clamp(lo as f32, hi as f32);
    }
    out
}

/// A search for the largest error of tier `S` on `term` and `band`: `cases` random
/// samples (the generator above, which puts half of the lights near the highlight),
/// then `climbs` hill climbs of `steps` steps from the worst of them. A step moves
/// the sample by a random amount between 10⁻⁴ and 10⁻¹ radians (see [`perturb`]) and
/// keeps it when the unquantised error does not decrease. Deterministic for a seed.
/// Returns the largest quantised error met and its sample.
pub fn search<S: Scalar>(
    term: Term,
    band: Band,
    cases: u32,
    climbs: usize,
    steps: u32,
    seed: u64,
) -> (u32, Sample) {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes),
    );
    let strat = sample(term, band);
    let mut pool: Vec<(f64, Sample)> = Vec::new();
    let mut best: Option<(u32, Sample)> = None;
    fn note<S: Scalar>(s: &Sample, best: &mut Option<(u32, Sample)>) {
        let e = lsb_error(tier_u8::<S>(s), reference_u8(s));
        if best.as_ref().is_none_or(|b| e > b.0) {
            *best = Some((e, s.clone()));
        }
    }
    let mut done = 0;
    while done < cases {
        let s = strat.new_tree(&mut runner).unwrap().current();
        if excluded(&s) {
            continue;
        }
        done += 1;
        note::<S>(&s, &mut best);
        pool.push((linear_error::<S>(&s), s));
    }
    pool.sort_by(|a, b| b.0.total_cmp(&a.0));
    pool.truncate(climbs);
    let mut rng = Rng::new(seed);
    for (mut err, mut s) in pool {
        for _ in 0..steps {
            let amount = 10f64.powf(-1.0 - 3.0 * rng.f());
            let t = perturb(&s, band, amount, &mut rng);
            if excluded(&t) {
                continue;
            }
            let e = linear_error::<S>(&t);
            if e >= err {
                note::<S>(&t, &mut best);
                (err, s) = (e, t);
            }
        }
    }
    best.unwrap()
}

// ---- targeted worst-case search (issue 21, item 6) ------------------------------------

/// The unit direction towards the viewer at the sample's point.
fn view_dir(s: &Sample) -> [f64; 3] {
    match s.viewer {
        ViewerDesc::Infinite(d) => norm(d.map(|c| c as f64)),
        ViewerDesc::Local(e) => norm([0, 1, 2].map(|i| e[i] as f64 - s.p[i] as f64)),
    }
}

/// Puts light `l` in the unit direction `dir` from the sample's point (at its
/// distance; a spot light's axis aimed back at the point).
fn aim(l: &mut LightDesc, p: [f32; 3], dir: [f64; 3]) {
    let pd = p.map(|c| c as f64);
    match &mut l.kind {
        LightKind::Directional { towards_light } => *towards_light = f32s(dir),
        LightKind::Point { position, .. } => {
            let dist = [0, 1, 2]
                .map(|i| position[i] as f64 - pd[i])
                .iter()
                .map(|c| c * c)
                .sum::<f64>()
                .sqrt()
                .max(1.0e-3);
            *position = f32s([0, 1, 2].map(|i| pd[i] + dir[i] * dist));
        }
        LightKind::Spot { position, axis, .. } => {
            let dist = [0, 1, 2]
                .map(|i| position[i] as f64 - pd[i])
                .iter()
                .map(|c| c * c)
                .sum::<f64>()
                .sqrt()
                .max(1.0e-3);
            *position = f32s([0, 1, 2].map(|i| pd[i] + dir[i] * dist));
            *axis = f32s(dir.map(|c| -c));
        }
    }
}

/// Moves a point or spot light along its direction to where `a + b·d + c·d²`
/// equals `t` (if it can).
fn place_for_attenuation(l: &mut LightDesc, p: [f32; 3], t: f64) {
    let pd = p.map(|c| c as f64);
    let (position, [a, b, c]) = match &mut l.kind {
        LightKind::Point {
            position,
            attenuation,
        }
        | LightKind::Spot {
            position,
            attenuation,
            ..
        } => (position, attenuation.map(|x| x as f64)),
        LightKind::Directional { .. } => return,
    };
    let d = if c > 0.0 {
        (-b + (b * b + 4.0 * c * (t - a)).max(0.0).sqrt()) / (2.0 * c)
    } else if b > 0.0 {
        (t - a) / b
    } else {
        return;
    };
    if !(d > 1.0e-3 && d < 2.0e4) {
        return;
    }
    let dir = norm([0, 1, 2].map(|i| position[i] as f64 - pd[i]));
    *position = f32s([0, 1, 2].map(|i| pd[i] + dir[i] * d));
}

/// Targeted starts for the worst-case search of `term` and `band`: `count`
/// samples of the generator, each moved to a place where a tier's rounding is
/// amplified most (in turn):
/// - the mirror direction: the light placed so that `R = V` (and `H = N`),
///   then turned away by up to `2/√n` radians, at the band's highest exponent;
/// - a grazing light: `N·L` from `1.2·10⁻³` (just outside the excluded band)
///   to `2·10⁻²`;
/// - near saturation: the light colours scaled so that the brightest channel
///   of the reference is at 0.97–1.0;
/// - attenuation extremes: point and spot lights where `a + b·d + c·d²` is
///   0.5–0.53 (a factor just below the fixed tiers' 2) or 10⁴;
/// - the mirror direction at a random exponent of the band.
pub fn targeted_starts(term: Term, band: Band, count: usize, seed: u64) -> Vec<Sample> {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes),
    );
    let strat = sample(term, band);
    let mut rng = Rng::new(seed ^ 0x5EED);
    let (_, n_max) = band.range();
    let mut out = Vec::new();
    let mut k = 0usize;
    while out.len() < count && k < 50 * count {
        let mut s = strat.new_tree(&mut runner).unwrap().current();
        let family = k % 5;
        k += 1;
        let n = norm(s.n.map(|c| c as f64));
        let v = view_dir(&s);
        let p = s.p;
        match family {
            0 | 4 => {
                if family == 0 {
                    s.material.shininess = n_max as f32;
                }
                let spread = 2.0 / (s.material.shininess.max(1.0) as f64).sqrt();
                let l0 = if term == Term::Transmission {
                    around(
                        n.map(|c| -c),
                        rng.f() * 0.5,
                        rng.f() * std::f64::consts::TAU,
                    )
                } else {
                    let m = [0, 1, 2].map(|i| 2.0 * dot(n, v) * n[i] - v[i]);
                    norm(m)
                };
                let th = spread * rng.f() * rng.f();
                for l in &mut s.lights {
                    let dir = around(l0, th, rng.f() * std::f64::consts::TAU);
                    aim(l, p, dir);
                }
            }
            1 => {
                for l in &mut s.lights {
                    let g = 1.2e-3 + rng.f() * 0.019;
                    let dir = around(
                        n,
                        std::f64::consts::FRAC_PI_2 - g,
                        rng.f() * std::f64::consts::TAU,
                    );
                    aim(l, p, dir);
                }
            }
            2 => {
                let r = reference_rgb(&s);
                let top = r.iter().cloned().fold(0.0f64, f64::max);
                let brightest = s
                    .lights
                    .iter()
                    .flat_map(|l| l.diffuse.iter().chain(l.specular.iter()))
                    .cloned()
                    .fold(0.0f32, f32::max);
                if top > 1.0e-3 && brightest > 0.0 {
                    let k = ((0.97 + 0.03 * rng.f()) / top).min(1.8 / brightest as f64) as f32;
                    for l in &mut s.lights {
                        l.diffuse = l.diffuse.map(|c| c * k);
                        l.specular = l.specular.map(|c| c * k);
                        l.ambient = l.ambient.map(|c| c * k);
                    }
                }
            }
            _ => {
                let t = if rng.f() < 0.7 {
                    0.5 + 0.03 * rng.f()
                } else {
                    1.0e4
                };
                for l in &mut s.lights {
                    place_for_attenuation(l, p, t);
                }
            }
        }
        if !excluded(&s) {
            out.push(s);
        }
    }
    out
}

/// The worst-case search from [`targeted_starts`]: `count` starts, hill climbs of
/// `steps` moves ([`perturb`], following [`linear_error`]), samples the bounds
/// exclude skipped. Returns the largest quantised error met and its sample.
pub fn targeted_search<S: Scalar>(
    term: Term,
    band: Band,
    count: usize,
    steps: u32,
    seed: u64,
) -> (u32, Option<Sample>) {
    let starts = targeted_starts(term, band, count, seed);
    let mut rng = Rng::new(seed ^ 0xC11B);
    let w = super::worst_case::climb(
        &starts,
        steps,
        seed,
        |s, amount, _| perturb(s, band, amount, &mut rng),
        |s| {
            if excluded(s) {
                None
            } else {
                Some((
                    linear_error::<S>(s),
                    lsb_error(tier_u8::<S>(s), reference_u8(s)),
                ))
            }
        },
    );
    (w.error, w.at)
}
