//! The lighting equation at the extremes, for every tier: bad parameters give typed
//! errors, evaluation never panics (these tests run with overflow checks on) and
//! behaves as documented.

use fixshade::error::ParamError;
use fixshade::lighting::{
    AnyLight, Attenuation, DirectionalLight, LightColors, LightDesc, LightKind, PointLight,
    SpotLight,
};
use fixshade::lighting::{BlinnPhong, Full, Lighting, LocalViewer, Phong};
use fixshade::lighting::{Material, MaterialDesc};
use fixshade::num::{point_from_f32, Vec3};
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade_testkit::reference::ViewerDesc;
use fixshade_testkit::scenes::{lsb_error, reference_u8, sample, tier_u8, Band, Sample, Term};
use proptest::prelude::*;

macro_rules! for_each_tier {
    ($f:ident $(, $arg:expr)*) => {{
        $f::<Q14<1>>($($arg),*);
        $f::<Q14<2>>($($arg),*);
        $f::<Q30<3>>($($arg),*);
        $f::<f32>($($arg),*);
        $f::<F32Fast<2>>($($arg),*);
    }};
}

fn shiny(n: f32) -> MaterialDesc {
    MaterialDesc {
        ambient: [0.1; 3],
        diffuse: [0.6, 0.3, 0.1],
        specular: [0.8; 3],
        shininess: n,
        ..MaterialDesc::default()
    }
}

#[test]
fn bad_parameters_are_typed_errors() {
    fn tier<S: Scalar>() {
        assert_eq!(
            DirectionalLight::<S>::white([0.0, 0.0, 0.0]).unwrap_err(),
            ParamError::ZeroDirection("direction")
        );
        assert_eq!(
            DirectionalLight::<S>::white([f32::NAN, 0.0, 1.0]).unwrap_err(),
            ParamError::NotFinite("direction")
        );
        assert!(DirectionalLight::<S>::white([f32::INFINITY, 0.0, 1.0]).is_err());
        assert_eq!(
            LightColors::<S>::rgb([1.0, -0.1, 0.0]).unwrap_err(),
            ParamError::Negative("light diffuse")
        );
        assert_eq!(
            Attenuation::new::<S>(0.0, 0.0, 0.0).unwrap_err(),
            ParamError::AttenuationAllZero
        );
        assert!(Attenuation::new::<S>(1.0, -1.0, 0.0).is_err());
        let att = Attenuation::none::<S>();
        let w = LightColors::white();
        assert_eq!(
            SpotLight::<S>::new([0.0; 3], [0.0, 0.0, -1.0], 1.0, 91.0, att, w).unwrap_err(),
            ParamError::CutoffOutOfRange
        );
        assert!(SpotLight::<S>::new([0.0; 3], [0.0, 0.0, -1.0], 1.0, f32::NAN, att, w).is_err());
        assert!(SpotLight::<S>::new([0.0; 3], [0.0, 0.0, -1.0], -2.0, 30.0, att, w).is_err());
        assert!(SpotLight::<S>::new([0.0; 3], [0.0, 0.0, 0.0], 2.0, 30.0, att, w).is_err());
        assert!(PointLight::<S>::new([f32::NAN, 0.0, 0.0], att, w).is_err());
        for bad in [
            MaterialDesc {
                shininess: -1.0,
                ..shiny(1.0)
            },
            MaterialDesc {
                shininess: 70000.0,
                ..shiny(1.0)
            },
            MaterialDesc {
                diffuse: [0.0, f32::NAN, 0.0],
                ..shiny(1.0)
            },
            MaterialDesc {
                brilliance: 0,
                ..shiny(1.0)
            },
            MaterialDesc {
                fresnel_f0: 1.5,
                ..shiny(1.0)
            },
            MaterialDesc {
                refractive_index: 0.0,
                ..shiny(1.0)
            },
        ] {
            assert!(Material::<S>::new(&bad).is_err(), "{bad:?}");
        }
        assert!(LocalViewer::<S>::new([0.0, f32::NAN, 0.0]).is_err());
        assert!(fixshade::lighting::LinearFog::<S>::new(5.0, 5.0, [0.0; 3]).is_err());
    }
    for_each_tier!(tier);
    // every error has a message
    assert_eq!(
        ParamError::CutoffOutOfRange.to_string(),
        "spot cutoff: outside 0..=90 degrees (180, no cone, is a point light: PointLight)"
    );
}

/// No specular leaks behind the surface: with every light behind (N·L ≤ 0) the
/// colour is exactly the ambient part, for Phong and Blinn-Phong, at any exponent.
#[test]
fn nothing_leaks_behind_the_surface() {
    fn tier<S: Scalar>() {
        for n in [0.0f32, 1.0, 5.0, 1024.0, 65535.0] {
            let mat = Material::<S>::new(&shiny(n)).unwrap();
            let ambient = Material::<S>::new(&MaterialDesc {
                diffuse: [0.0; 3],
                specular: [0.0; 3],
                ..shiny(n)
            })
            .unwrap();
            for l in [
                [0.0f32, 0.0, -1.0],
                [1.0, 0.0, -1.0e-6],
                [0.0, 1.0, 0.0],
                [0.3, -0.9, -0.2],
            ] {
                let light = DirectionalLight::<S>::white(l).unwrap();
                let pt = point_from_f32::<S>([0.0; 3]);
                let nrm = Vec3::<S>::from_f32([0.0, 0.0, 1.0]);
                let base = Lighting::<S, _, Phong>::new(light, ambient)
                    .with_global_ambient_f32([0.0; 3])
                    .shade(&pt, nrm);
                let phong = Lighting::<S, _, Phong>::new(light, mat)
                    .with_global_ambient_f32([0.0; 3])
                    .shade(&pt, nrm);
                let blinn = Lighting::<S, _, BlinnPhong>::new(light, mat)
                    .with_global_ambient_f32([0.0; 3])
                    .shade(&pt, nrm);
                assert_eq!(phong, base, "{} n={n} l={l:?}", S::NAME);
                assert_eq!(blinn, base, "{} n={n} l={l:?}", S::NAME);
            }
        }
    }
    for_each_tier!(tier);
}

/// Shininess 0, 1, 256, 1024, 4096 and u16::MAX: a full highlight where N = H
/// (Blinn-Phong) and where R = V (Phong); `x^0 = 1`.
#[test]
fn extreme_shininess() {
    fn tier<S: Scalar>() {
        for n in [0.0f32, 1.0, 256.0, 1024.0, 4096.0, 65535.0] {
            let m = MaterialDesc {
                ambient: [0.0; 3],
                diffuse: [0.0; 3],
                specular: [1.0; 3],
                shininess: n,
                ..Default::default()
            };
            let lit = Lighting::<S, _, BlinnPhong>::new(
                DirectionalLight::<S>::white([0.0, 0.0, 1.0]).unwrap(),
                Material::new(&m).unwrap(),
            )
            .with_global_ambient_f32([0.0; 3]);
            let pt = point_from_f32::<S>([0.0; 3]);
            let at_peak = lit.shade(&pt, Vec3::from_f32([0.0, 0.0, 1.0])).to_unorm(8);
            assert_eq!(at_peak, [255; 3], "{} n={n}", S::NAME);
            // Phong's mirror peak: 2(N·L) = 2 inside R = 2(N·L)N − L, which the fixed
            // tiers cannot hold (issue 11, item 7: Q14 gave e^(−n/16384), 5 at 65535)
            let phong = lit.with_model::<Phong>();
            let at_peak = phong.shade(&pt, Vec3::from_f32([0.0, 0.0, 1.0]));
            assert_eq!(at_peak.to_unorm(8), [255; 3], "{} Phong n={n}", S::NAME);
            let n3 = Vec3::<S>::from_f32([0.0, 0.0, 1.0]);
            let r = n3.reflect(n3);
            assert_eq!(r, n3, "{} reflect at the peak", S::NAME);
            // off the peak: N·H = cos 30° = 0.866; 0.866^n
            let off = lit
                .shade(&pt, Vec3::from_f32([0.5, 0.0, 0.8660254]))
                .to_unorm(8)[0];
            let want = (0.8660254f64.powf(n as f64) * 255.0).round() as u32;
            assert!(
                off.abs_diff(want) <= 1,
                "{} n={n}: {off} vs {want}",
                S::NAME
            );
        }
    }
    for_each_tier!(tier);
}

/// Intensities summing above 1 clamp to full output; several lights saturate the
/// fixed tiers at ≈ 2 internally without wrapping.
#[test]
fn bright_sums_clamp() {
    fn tier<S: Scalar>() {
        let big = LightColors::<S>::rgb([1.9, 1.9, 1.9]).unwrap();
        let lights = [DirectionalLight::<S>::new([0.0, 0.0, 1.0], big).unwrap(); 4];
        let m = Material::<S>::new(&MaterialDesc {
            specular: [1.9; 3],
            shininess: 1.0,
            diffuse: [1.9; 3],
            emission: [1.9; 3],
            ..Default::default()
        })
        .unwrap();
        let c = Lighting::<S, _, BlinnPhong>::new(lights, m)
            .with_global_ambient_f32([0.0; 3])
            .shade(
                &point_from_f32::<S>([0.0; 3]),
                Vec3::from_f32([0.0, 0.0, 1.0]),
            );
        assert_eq!(c.to_unorm(8), [255; 3], "{}", S::NAME);
        assert_eq!(
            c.to_rgb565(),
            embedded_graphics_core::pixelcolor::Rgb565::new(31, 63, 31)
        );
    }
    for_each_tier!(tier);
}

/// A point light exactly at the surface point (d = 0: L is the zero vector), a
/// light at the far end of the geometry range and beyond it, a = 0 at d = 0.
#[test]
fn light_at_the_surface_and_far_away() {
    fn tier<S: Scalar>() {
        let m = Material::<S>::new(&shiny(20.0)).unwrap();
        let pt = point_from_f32::<S>([1.0, 2.0, 3.0]);
        let nrm = Vec3::<S>::from_f32([0.0, 0.0, 1.0]);
        for (pos, att) in [
            ([1.0f32, 2.0, 3.0], [1.0f32, 0.0, 0.0]),
            ([1.0, 2.0, 3.0], [0.0, 0.0, 1.0]),
            ([1.0, 2.0, 3.0], [0.0, 1.0, 0.0]),
            ([1.0, 2.0, 30000.0], [1.0, 0.0, 0.0]),
            ([1.0, 2.0, 30000.0], [0.0, 0.0, 1.0]),
            ([1.0e30, -1.0e30, 1.0e30], [1.0, 0.1, 0.01]),
        ] {
            let light = PointLight::<S>::new(
                pos,
                Attenuation::new::<S>(att[0], att[1], att[2]).unwrap(),
                LightColors::white(),
            )
            .unwrap();
            let c = Lighting::<S, _, Full>::new(light, m)
                .with_global_ambient_f32([0.0; 3])
                .shade(&pt, nrm)
                .to_unorm(8);
            assert!(c.iter().all(|&x| x <= 255), "{}", S::NAME);
            if pos[2] == 3.0 {
                // L = 0: no diffuse or specular, only ka·La·att (La = 0 here) → ambient 0
                assert_eq!(c, [0; 3], "{} att {att:?}", S::NAME);
            }
            if pos[2] == 30000.0 && att[0] == 1.0 {
                // unattenuated light straight above: diffuse 0.6/0.3/0.1 + full highlight 0.8
                assert_eq!(&c[..2], &[255, 255], "{}", S::NAME);
                assert!(c[2].abs_diff(230) <= 1, "{} {c:?}", S::NAME);
            }
        }
    }
    for_each_tier!(tier);
}

/// Unnormalised and tiny normals: `shade_normalizing` matches the reference
/// evaluated at the tier's own (quantised) normal within the tier's diffuse bound;
/// a zero normal gives the ambient and emission terms only.
#[test]
fn unnormalised_and_tiny_normals() {
    fn tier<S: Scalar>() {
        let desc = MaterialDesc {
            emission: [0.05; 3],
            ..shiny(8.0)
        };
        let light_desc = LightDesc {
            kind: LightKind::Directional {
                towards_light: [0.2, 0.4, 1.0],
            },
            ambient: [0.2; 3],
            diffuse: [0.9; 3],
            specular: [0.9; 3],
        };
        let lit = Lighting::<S, _, BlinnPhong>::new(
            AnyLight::<S>::new(&light_desc).unwrap(),
            Material::new(&desc).unwrap(),
        )
        .with_global_ambient_f32([0.0; 3]);
        let pt = point_from_f32::<S>([0.0; 3]);
        for scale in [1.9f32, 1.0, 0.3, 0.01, 1.0e-3] {
            let n = Vec3::<S>::from_f32([0.3 * scale, -0.2 * scale, 0.9 * scale]);
            if n == Vec3::from_f32([0.0; 3]) {
                continue;
            }
            let got = lit.shade_normalizing(&pt, n).to_unorm(8).map(|x| x as u8);
            let s = Sample {
                lights: vec![light_desc],
                material: desc,
                global_ambient: [0.0; 3],
                viewer: ViewerDesc::Infinite([0.0, 0.0, 1.0]),
                fog: None,
                p: [0.0; 3],
                n: n.to_f32(),
                model: fixshade_testkit::scenes::ModelKind::Blinn,
            };
            let want = reference_u8(&s);
            assert!(
                lsb_error(got, want) <= 2,
                "{} scale {scale}: {got:?} vs {want:?}",
                S::NAME
            );
        }
        let zero = lit
            .shade_normalizing(&pt, Vec3::from_f32([0.0; 3]))
            .to_unorm(8);
        // emission 0.05 + La·ka = 0.2·0.1 = 0.07 → 18
        assert_eq!(zero, [18; 3], "{}", S::NAME);
        let nan = lit
            .shade_normalizing(&pt, Vec3::from_f32([f32::NAN; 3]))
            .to_unorm(8);
        assert_eq!(nan, [18; 3], "{}", S::NAME);
    }
    for_each_tier!(tier);
}

/// Grazing angles: N·L just above and below 0, and samples right on the
/// discontinuities the accuracy suite excludes, never panic and stay in range.
#[test]
fn grazing_angles_and_cone_edges() {
    fn tier<S: Scalar>() {
        let m = Material::<S>::new(&shiny(64.0)).unwrap();
        let pt = point_from_f32::<S>([0.0; 3]);
        let nrm = Vec3::<S>::from_f32([0.0, 0.0, 1.0]);
        for z in [-1.0e-3f32, -1.0e-7, 0.0, 1.0e-7, 1.0e-3] {
            if let Ok(l) = DirectionalLight::<S>::white([1.0, 0.0, z]) {
                let c = Lighting::<S, _, Full>::new(l, m)
                    .with_global_ambient_f32([0.0; 3])
                    .shade(&pt, nrm);
                assert!(c.to_unorm(8).iter().all(|&x| x <= 255));
            }
        }
        // exactly on the cone edge, cutoff 0 and 90
        for cutoff in [0.0f32, 45.0, 90.0] {
            let s = SpotLight::<S>::new(
                [0.0, 0.0, 5.0],
                [1.0, 0.0, -1.0],
                3.0,
                cutoff,
                Attenuation::none::<S>(),
                LightColors::white(),
            )
            .unwrap();
            let c = Lighting::<S, _, Full>::new(s, m)
                .with_global_ambient_f32([0.0; 3])
                .shade(&pt, nrm);
            assert!(c.to_unorm(8).iter().all(|&x| x <= 255));
        }
    }
    for_each_tier!(tier);
}

fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -4.0f32..4.0,
        1 => proptest::num::f32::ANY,
        1 => Just(0.0f32),
        1 => Just(1.0e30f32),
        1 => Just(-1.0e-30f32),
    ]
}

fn any3() -> impl Strategy<Value = [f32; 3]> {
    [any_f32(), any_f32(), any_f32()]
}

proptest! {
    #![proptest_config(fixshade_testkit::seeded::config("lighting_extremes", 2000))]

    /// Arbitrary `f32` parameters (NaN, infinities, huge, negative): every
    /// constructor returns `Ok` or a typed error, and shading whatever was accepted
    /// at arbitrary points and normals never panics.
    #[test]
    fn arbitrary_parameters_never_panic(
        pos in any3(), dir in any3(), col in any3(), att in any3(),
        e in any_f32(), cutoff in any_f32(), n in any_f32(), mat in any3(),
        p in any3(), nrm in any3(), eye in any3(),
    ) {
        #[allow(clippy::too_many_arguments)]
        fn tier<S: Scalar>(pos: [f32; 3], dir: [f32; 3], col: [f32; 3], att: [f32; 3], e: f32, cutoff: f32, n: f32, mat: [f32; 3], p: [f32; 3], nrm: [f32; 3], eye: [f32; 3]) {
            let kinds = [
                LightKind::Directional { towards_light: dir },
                LightKind::Point { position: pos, attenuation: att },
                LightKind::Spot { position: pos, axis: dir, exponent: e, cutoff_deg: cutoff, attenuation: att },
            ];
            let desc = MaterialDesc { diffuse: mat, specular: mat, shininess: n, transmission: mat, ..MaterialDesc::default() };
            let Ok(m) = Material::<S>::new(&desc) else { return };
            for kind in kinds {
                let Ok(light) = AnyLight::<S>::new(&LightDesc { kind, ambient: col, diffuse: col, specular: col }) else { continue };
                let lit = Lighting::<S, _, Full>::new([light, light], m).with_global_ambient_f32([0.0; 3]);
                let c = lit.shade_normalizing(&point_from_f32::<S>(p), Vec3::from_f32(nrm));
                let _ = c.to_rgb565();
                if let Ok(v) = LocalViewer::<S>::new(eye) {
                    let _ = lit.with_viewer(v).shade_normalizing(&point_from_f32::<S>(p), Vec3::from_f32(nrm)).to_rgb888();
                }
            }
        }
        tier::<Q14<0>>(pos, dir, col, att, e, cutoff, n, mat, p, nrm, eye);
        tier::<Q14<1>>(pos, dir, col, att, e, cutoff, n, mat, p, nrm, eye);
        tier::<Q30<0>>(pos, dir, col, att, e, cutoff, n, mat, p, nrm, eye);
        tier::<Q30<3>>(pos, dir, col, att, e, cutoff, n, mat, p, nrm, eye);
        tier::<f32>(pos, dir, col, att, e, cutoff, n, mat, p, nrm, eye);
        tier::<F32Fast<1>>(pos, dir, col, att, e, cutoff, n, mat, p, nrm, eye);
    }

    /// Random scenes with every term: the same sample gives the same colour in
    /// every fixed tier within their bounds of each other (a cheap consistency
    /// check beside the reference comparison), and never panics.
    #[test]
    fn tiers_agree_on_random_scenes(s in sample(Term::Everything, Band::Low)) {
        let a = tier_u8::<Q30<3>>(&s);
        let b = tier_u8::<f32>(&s);
        prop_assert!(lsb_error(a, b) <= 2);
    }
}
