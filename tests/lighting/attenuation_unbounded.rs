//! Attenuations without a constant term (issue 21, item 3): `1/(b·d + c·d²)`
//! grows without limit near the light. The fixed tiers saturated the factor
//! itself at 2, so OpenGL's constant attenuation 0 with linear attenuation
//! 10⁻³⁰ gave 97 in `Q30` (and `Q14`) where `f32` and the reference give 255,
//! and `GlScene::lighting` raised no range error. Now the factor is carried
//! beyond the range (`Scalar::geo_inv_quadratic_exp`) and the light's
//! contribution saturates only once formed; what a tier cannot sum right is a
//! `ParamError::TierRange`. Swept here: every tiny coefficient from 10⁻⁴⁵ to
//! 10⁻³ as the constant, linear or quadratic term (the others 0), model ambient
//! positive, zero and negative, a negative light, fog, distances from 10⁻³ to
//! 2·10⁴ and normals from facing the light to grazing it and behind: every
//! tier is either within its bound of the f64 reference or a typed error,
//! never a silently wrong colour.

use fixshade::error::ParamError;
use fixshade::lighting::gl::{GlLight, GlLightModel, GlMaterial, GlScene};
use fixshade::lighting::LinearFog;
use fixshade::lighting::Viewed;
use fixshade::lighting::{AnyLight, LightDesc};
use fixshade::num::{point_from_f32, Vec3};
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade::prelude::*;
use fixshade_testkit::reference::{FogDesc, ModelDesc, Reference, ViewerDesc};

/// What `GlScene::lighting` builds here: up to 8 lights of any kind, OpenGL's
/// Blinn-Phong model, a viewer at infinity.
type SceneLighting<S> = Viewed<Lighting<S, fixshade::heapless::Vec<AnyLight<S>, 8>>>;

/// Tiny coefficients: every decade from 10⁻⁴⁵ (a subnormal) to 10⁻³, and the
/// smallest normal `f32`.
fn tiny() -> Vec<f32> {
    let mut v: Vec<f32> = (3..=45).map(|k| 10f32.powi(-k)).collect();
    v.extend([f32::MIN_POSITIVE, 1.0e-45, 3.0e-3, 0.3]);
    v.retain(|&x| x > 0.0);
    v
}

/// Surface points at distance `d` from the light at `(0, 0, 2)` and normals at
/// angle `θ` from the direction to the light (facing it, 60°, 84° and 89.4°:
/// `N·L` from 1 to 0.01; and 100°: behind).
fn points() -> Vec<([f32; 3], [f32; 3])> {
    let mut out = Vec::new();
    for d in [1.0e-3f32, 0.05, 0.5, 1.0, 7.0, 100.0, 1000.0, 20000.0] {
        let p = [0.0, 0.0, 2.0 - d];
        for theta in [0.0f32, 60.0, 84.0, 89.4, 100.0] {
            let t = theta.to_radians();
            out.push((p, [t.sin(), 0.0, t.cos()]));
        }
    }
    out
}

/// The tier's bound in 8-bit LSBs (no highlight: `tests/lighting/lighting_accuracy.rs`).
const BOUND: u32 = 1;

/// The error of the tier's cosine `N·L` (relative to 1): near the light the
/// factor `f` multiplies it, like the reference's own sensitivity to `N·L`.
fn cosine_error<S: Scalar>() -> f64 {
    match S::NAME.as_bytes()[0] {
        b'Q' if S::NAME.starts_with("Q14") => 1.0 / 8192.0,
        b'Q' => 1.0e-8,
        _ => 1.0e-6,
    }
}

/// One scene through `GlScene::lighting` in tier `S` against the reference.
/// Returns whether the tier accepted it.
fn gl_scene<S: Scalar>(att: [f32; 3], model_ambient: f32, light_diffuse: f32) -> bool {
    let light = GlLight {
        position: [0.0, 0.0, 2.0, 1.0],
        diffuse: [light_diffuse, light_diffuse * 0.5, 1.0, 1.0],
        specular: [0.0, 0.0, 0.0, 1.0],
        constant_attenuation: att[0],
        linear_attenuation: att[1],
        quadratic_attenuation: att[2],
        ..GlLight::light0()
    };
    let lights = [light];
    let material = GlMaterial::default();
    let model = GlLightModel {
        ambient: [model_ambient, model_ambient, model_ambient, 1.0],
        ..GlLightModel::default()
    };
    let scene = GlScene::new(&lights, material, model);
    let lit: SceneLighting<S> = match scene.lighting() {
        Ok(l) => l,
        Err(ParamError::TierRange { .. }) => return false,
        Err(e) => panic!("{}: {att:?}: {e}", S::NAME),
    };
    let descs = [light.to_desc().unwrap()];
    let reference = Reference {
        lights: &descs,
        material: material.to_desc().unwrap(),
        global_ambient: [model_ambient; 3],
        viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
        fog: None,
        model: ModelDesc::of::<BlinnPhong>(),
    };
    let kd = [light_diffuse, light_diffuse * 0.5, 1.0].map(|c| f64::from(c).abs() * 0.8);
    for (p, n) in points() {
        let exact = reference.shade(p.map(f64::from), n.map(f64::from));
        let got = lit
            .shade(&point_from_f32::<S>(p), Vec3::<S>::from_f32(n))
            .to_unorm(8);
        // the factor at p, and the reference's change for the tier's error of
        // N·L: where even that leaves the channel above 1, it must be 255
        let d = 2.0 - f64::from(p[2]);
        let q = f64::from(att[0]) + f64::from(att[1]) * d + f64::from(att[2]) * d * d;
        let f = if q > 0.0 { 1.0 / q } else { f64::INFINITY };
        for c in 0..3 {
            let want = (exact[c].clamp(0.0, 1.0) * 255.0).round() as u32;
            let spread = f * kd[c] * cosine_error::<S>();
            let tol = if exact[c] - spread > 1.0 {
                BOUND
            } else {
                BOUND + (spread * 255.0).ceil().min(255.0) as u32
            };
            assert!(
                got[c].abs_diff(want) <= tol,
                "{}: attenuation {att:?}, model ambient {model_ambient}, light {light_diffuse}, \
                 p {p:?} n {n:?}: {got:?}, reference {want} in channel {c} (± {tol})",
                S::NAME
            );
        }
    }
    true
}

#[test]
fn tiny_coefficients_are_right_or_typed_errors() {
    fn tier<S: Scalar>() -> (usize, usize) {
        let (mut ok, mut refused) = (0, 0);
        for v in tiny() {
            for which in 0..3 {
                let mut att = [0.0f32; 3];
                att[which] = v;
                for (ambient, light) in [(0.2, 1.0), (0.0, 1.0), (-0.2, 1.0), (0.2, -0.5)] {
                    if gl_scene::<S>(att, ambient, light) {
                        ok += 1;
                    } else {
                        refused += 1;
                    }
                }
            }
        }
        (ok, refused)
    }
    for (name, (ok, refused)) in [
        (Q14::<2>::NAME, tier::<Q14<2>>()),
        (Q30::<3>::NAME, tier::<Q30<3>>()),
        (f32::NAME, tier::<f32>()),
        (F32Fast::<2>::NAME, tier::<F32Fast<2>>()),
    ] {
        println!("{name}: {ok} scenes within the bound of the reference, {refused} refused");
        assert!(ok >= 200 && refused >= 200, "{name}");
    }
}

/// The case of the issue, exactly: `Q30` gave 97 (158 LSB off), 183 with a
/// negative model ambient.
#[test]
fn the_case_of_the_issue() {
    let light = GlLight {
        position: [0.0, 0.0, 2.0, 1.0],
        constant_attenuation: 0.0,
        linear_attenuation: 1.0e-30,
        ..GlLight::light0()
    };
    for ambient in [0.2f32, -0.2] {
        let model = GlLightModel {
            ambient: [ambient, ambient, ambient, 1.0],
            ..GlLightModel::default()
        };
        let lights = [light];
        let scene = GlScene::new(&lights, GlMaterial::default(), model);
        let n = [0.98f32, 0.0, 0.2];
        let q30: SceneLighting<Q30> = scene.lighting().unwrap();
        let f32l: SceneLighting<f32> = scene.lighting().unwrap();
        let q14: SceneLighting<Q14> = scene.lighting().unwrap();
        let p = [0.0f32, 0.0, 1.0];
        let a = q30
            .shade(&point_from_f32::<Q30>(p), Vec3::from_f32(n))
            .to_unorm(8);
        let b = f32l
            .shade(&point_from_f32::<f32>(p), Vec3::from_f32(n))
            .to_unorm(8);
        let c = q14
            .shade(&point_from_f32::<Q14>(p), Vec3::from_f32(n))
            .to_unorm(8);
        assert_eq!(b, [255; 3]);
        assert_eq!(a, b, "Q30, model ambient {ambient}");
        assert_eq!(c, b, "Q14, model ambient {ambient}");
    }
}

/// What a saturated contribution cannot be summed with is a typed error: a
/// negative colour on the light, negative terms summing to `1 − max` or below,
/// fog; with a constant term the same scenes pass.
#[test]
fn unbounded_attenuation_range_errors() {
    fn check<S: Scalar>() {
        let desc = |diffuse: f32, att: [f32; 3]| LightDesc {
            kind: fixshade::lighting::LightKind::Point {
                position: [0.0, 0.0, 2.0],
                attenuation: att,
            },
            ambient: [0.0; 3],
            diffuse: [diffuse; 3],
            specular: [0.0; 3],
        };
        let mat = Material::signed(&MaterialDesc {
            diffuse: [0.8; 3],
            ..MaterialDesc::default()
        })
        .unwrap();
        let lighting = |lights: [LightDesc; 2], ambient: f32| {
            let l = lights.map(|d| AnyLight::<S>::signed(&d).unwrap());
            Lighting::<S, _, Lambert>::new(l, mat)
                .with_global_ambient(fixshade::color::Rgb::from_f32([ambient; 3]))
        };
        let unbounded = [0.0, 1.0, 0.0];
        let bounded = [1.0, 1.0, 0.0];
        let off = desc(0.0, bounded);
        // a negative light with a = 0
        assert!(lighting([desc(-0.5, unbounded), off], 0.0)
            .checked()
            .is_err());
        assert!(lighting([desc(-0.5, bounded), off], 0.0).checked().is_ok());
        // a negative light beside one with a = 0: −0.8 × 1.25 = −1 ≤ 1 − max
        // (the fixed tiers; the float tiers' max is 10⁹)
        let fixed = S::MAX.to_f32() < 3.0;
        let l = [desc(1.0, unbounded), desc(-1.25, bounded)];
        assert_eq!(lighting(l, 0.0).checked().is_err(), fixed, "{}", S::NAME);
        let l = [desc(1.0, unbounded), desc(-0.5, bounded)];
        assert!(lighting(l, 0.0).checked().is_ok());
        assert!(lighting(l, -0.3).checked().is_ok());
        // fog
        let l = lighting([desc(1.0, unbounded), off], 0.0);
        assert!(l
            .with_fog(LinearFog::new(1.0, 9.0, [0.5; 3]).unwrap())
            .checked()
            .is_err());
        let l = lighting([desc(1.0, bounded), off], 0.0);
        assert!(l
            .with_fog(LinearFog::new(1.0, 9.0, [0.5; 3]).unwrap())
            .checked()
            .is_ok());
        let _ = FogDesc {
            start: 1.0,
            end: 9.0,
            color: [0.5; 3],
        };
    }
    check::<Q14<2>>();
    check::<Q30<3>>();
    check::<f32>();
}
