//! The lighting evaluation of every tier never yields a NaN (or infinite) channel,
//! never panics and never wraps (overflow checks are on in this profile), for any `f32` the
//! constructors accept and for any point and normal handed to `Lighting::shade`
//! directly: huge, infinite and NaN coordinates included (the float tiers' `Vec3`
//! holds any `f32`; the fixed tiers' any raw value).

use fixshade_testkit::seeded;

use fixshade::color::Rgb;
use fixshade::lighting::{AnyLight, LightDesc, LightKind, LightSet};
use fixshade::lighting::{
    BlinnPhong, FogModel, Full, InfiniteViewer, Lighting, LinearFog, LocalViewer, Model, Phong,
    Viewer,
};
use fixshade::lighting::{Material, MaterialDesc};
use fixshade::num::{F32Fast, Geo16, Scalar, Q14, Q30};
use fixshade::num::{Point3, Vec3};
use proptest::prelude::*;

/// How a test builds raw points and normals of a tier, bypassing the saturating
/// conversions.
trait Raw: Scalar {
    fn normal(v: [f32; 3], bits: [u32; 3]) -> Vec3<Self>;
    fn point(v: [f32; 3], bits: [u32; 3]) -> Point3<Self>;
}

impl<const N: u8> Raw for Q14<N> {
    fn normal(v: [f32; 3], bits: [u32; 3]) -> Vec3<Self> {
        if bits[0] & 1 == 0 {
            Vec3::from_f32(v)
        } else {
            let q = |b: u32| Q14::from_raw(b as i16 as i32);
            Vec3::new(q(bits[0]), q(bits[1]), q(bits[2]))
        }
    }
    fn point(v: [f32; 3], bits: [u32; 3]) -> Point3<Self> {
        if bits[1] & 1 == 0 {
            fixshade::num::point_from_f32::<Self>(v)
        } else {
            let g = |b: u32| Geo16::from_bits(b as i32);
            Vec3::new(g(bits[0]), g(bits[1]), g(bits[2]))
        }
    }
}

impl<const N: u8> Raw for Q30<N> {
    fn normal(v: [f32; 3], bits: [u32; 3]) -> Vec3<Self> {
        if bits[0] & 1 == 0 {
            Vec3::from_f32(v)
        } else {
            let q = |b: u32| Q30::from_raw(b as i32);
            Vec3::new(q(bits[0]), q(bits[1]), q(bits[2]))
        }
    }
    fn point(v: [f32; 3], bits: [u32; 3]) -> Point3<Self> {
        <Q14 as Raw>::point(v, bits)
    }
}

impl Raw for f32 {
    fn normal(v: [f32; 3], _: [u32; 3]) -> Vec3<f32> {
        Vec3::new(v[0], v[1], v[2])
    }
    fn point(v: [f32; 3], _: [u32; 3]) -> Point3<f32> {
        Vec3::new(v[0], v[1], v[2])
    }
}

impl<const N: u8> Raw for F32Fast<N> {
    fn normal(v: [f32; 3], _: [u32; 3]) -> Vec3<Self> {
        Vec3::new(F32Fast(v[0]), F32Fast(v[1]), F32Fast(v[2]))
    }
    fn point(v: [f32; 3], _: [u32; 3]) -> Point3<Self> {
        Vec3::new(v[0], v[1], v[2])
    }
}

fn check<S: Scalar>(c: Rgb<S>, what: &str) {
    for x in c.to_f32() {
        assert!(
            x.is_finite(),
            "{}: non-finite channel {c:?} ({what})",
            S::NAME
        );
    }
    for u in c.to_unorm(8) {
        assert!(u <= 255);
    }
}

fn shade_all<S: Raw, L: LightSet<S> + Copy, V: Viewer<S>, F: FogModel<S>>(
    lights: L,
    m: Material<S>,
    viewer: V,
    fog: F,
    p: &Point3<S>,
    n: Vec3<S>,
) {
    fn one<S: Scalar, L: LightSet<S>, M: Model, V: Viewer<S>, F: FogModel<S>>(
        lights: L,
        m: Material<S>,
        viewer: V,
        fog: F,
        p: &Point3<S>,
        n: Vec3<S>,
    ) {
        let lit = Lighting::<S, L, M>::new(lights, m)
            .with_global_ambient(Rgb::splat(S::from_f32(0.2)))
            .with_viewer(viewer)
            .with_fog(fog);
        check(lit.shade(p, n), "shade");
        check(lit.shade_normalizing(p, n), "shade_normalizing");
    }
    one::<S, L, Full, V, F>(lights, m, viewer, fog, p, n);
    one::<S, L, Phong, V, F>(lights, m, viewer, fog, p, n);
    one::<S, L, BlinnPhong, V, F>(lights, m, viewer, fog, p, n);
}

/// Any f32, with the special values made likely.
fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => -4.0f32..4.0,
        2 => proptest::num::f32::ANY,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(f32::MAX),
        1 => Just(-3.0e38f32),
        1 => Just(1.0e30f32),
        1 => Just(1.0e-40f32),
        1 => Just(0.0f32),
    ]
}

fn any3() -> impl Strategy<Value = [f32; 3]> {
    [any_f32(), any_f32(), any_f32()]
}

#[allow(clippy::too_many_arguments)]
fn tier<S: Raw>(
    pos: [f32; 3],
    dir: [f32; 3],
    col: [f32; 3],
    att: [f32; 3],
    scal: [f32; 4],
    mat: [f32; 3],
    p: [f32; 3],
    nrm: [f32; 3],
    eye: [f32; 3],
    bits: [u32; 3],
) {
    let [e, cutoff, n, fog_end] = scal;
    let desc = MaterialDesc {
        emission: mat,
        diffuse: mat,
        specular: mat,
        shininess: n,
        transmission: mat,
        transmission_exponent: n,
        refractive_index: 1.0 + (e.abs() % 7.0),
        fresnel_f0: 0.3,
        ..MaterialDesc::default()
    };
    let Ok(m) = Material::<S>::new(&desc) else {
        return;
    };
    let kinds = [
        LightKind::Directional { towards_light: dir },
        LightKind::Point {
            position: pos,
            attenuation: att,
        },
        LightKind::Spot {
            position: pos,
            axis: dir,
            exponent: e,
            cutoff_deg: cutoff,
            attenuation: att,
        },
    ];
    let point = S::point(p, bits);
    let normal = S::normal(nrm, bits);
    let fog = LinearFog::<S>::new(cutoff, fog_end, col)
        .or_else(|_| LinearFog::<S>::new(-f32::MAX, f32::MAX, [0.5; 3]));
    for kind in kinds {
        let Ok(light) = AnyLight::<S>::new(&LightDesc {
            kind,
            ambient: col,
            diffuse: col,
            specular: col,
        }) else {
            continue;
        };
        let lights = [light, light];
        let viewer = InfiniteViewer::<S>::new(eye).unwrap_or_default();
        if let Ok(fog) = fog {
            shade_all(lights, m, viewer, fog, &point, normal);
        }
        shade_all(lights, m, viewer, fixshade::lighting::NoFog, &point, normal);
        if let Ok(local) = LocalViewer::<S>::new(eye) {
            shade_all(lights, m, local, fixshade::lighting::NoFog, &point, normal);
            if let Ok(fog) = fog {
                shade_all(lights, m, local, fog, &point, normal);
            }
        }
    }
}

proptest! {
    #![proptest_config(seeded::config("stability_nan", 3000))]

    #[test]
    fn no_nan_and_no_wrap_for_any_input(
        pos in any3(), dir in any3(), col in any3(), att in any3(),
        scal in [any_f32(), any_f32(), any_f32(), any_f32()], mat in any3(),
        p in any3(), nrm in any3(), eye in any3(), bits in any::<[u32; 3]>(),
    ) {
        tier::<Q14<0>>(pos, dir, col, att, scal, mat, p, nrm, eye, bits);
        tier::<Q14<2>>(pos, dir, col, att, scal, mat, p, nrm, eye, bits);
        tier::<Q30<3>>(pos, dir, col, att, scal, mat, p, nrm, eye, bits);
        tier::<f32>(pos, dir, col, att, scal, mat, p, nrm, eye, bits);
        tier::<F32Fast<1>>(pos, dir, col, att, scal, mat, p, nrm, eye, bits);
        tier::<F32Fast<2>>(pos, dir, col, att, scal, mat, p, nrm, eye, bits);
    }
}

/// The special positions and normals one by one, with a plain scene.
#[test]
fn special_points_and_normals() {
    fn t<S: Raw>() {
        let specials = [
            0.0f32,
            1.0,
            -1.0,
            1.0e30,
            -1.0e30,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for &a in &specials {
            for &b in &specials {
                let bits = [a.to_bits(), b.to_bits(), 3];
                tier::<S>(
                    [1.0, 2.0, 3.0],
                    [0.2, 0.3, 1.0],
                    [0.9, 0.5, 0.1],
                    [1.0, 0.1, 0.01],
                    [2.0, 45.0, 20.0, 30.0],
                    [0.5, 0.5, 0.5],
                    [a, b, 1.0],
                    [b, 0.5, a],
                    [0.0, a, 9.0],
                    bits,
                );
            }
        }
    }
    t::<Q14<2>>();
    t::<Q30<3>>();
    t::<f32>();
    t::<F32Fast<2>>();
}
