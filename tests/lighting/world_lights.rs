//! Lights placed in world coordinates, seen through a moving camera
//! (`Lighting::viewed`, issue 20 item 2): a camera circles a fixed lamp
//! (directional, point and spot light together), and every visible point of a
//! sphere at the world's origin is lit as the `f64` reference lights it in
//! world coordinates (the viewer at infinity behind the camera), within the
//! tier's stated bound (1 LSB for Q14 and f32 below n = 64, README
//! "Accuracy"). Without `viewed`, the lamp moves with the camera: the same
//! check fails, which the last test asserts. And `Lighting::new` has
//! OpenGL's global ambient light (issue 20 item 3).

use fixshade::lighting::Illuminate;
use fixshade::lighting::{
    AmbientSource, AnyLight, BlinnPhong, DirectionalLight, LightDesc, LightKind, Lighting,
    Material, MaterialDesc,
};
use fixshade::num::{point_from_f32, Mat4, Vec3, Q14};
use fixshade_testkit::reference::{ModelDesc, Reference, ViewerDesc};

type V3 = [f64; 3];

fn lamp() -> [LightDesc; 3] {
    let colors = |a: f32, d: f32, s: f32| ([a; 3], [d; 3], [s; 3]);
    let (ambient, diffuse, specular) = colors(0.05, 0.5, 0.4);
    let light = |kind| LightDesc {
        kind,
        ambient,
        diffuse,
        specular,
    };
    [
        light(LightKind::Directional {
            towards_light: [1.0, 2.0, 3.0],
        }),
        light(LightKind::Point {
            position: [0.0, 3.0, 2.0],
            attenuation: [1.0, 0.05, 0.01],
        }),
        light(LightKind::Spot {
            position: [2.0, 2.5, 2.0],
            axis: [-1.0, -1.2, -1.0],
            exponent: 4.0,
            cutoff_deg: 45.0,
            attenuation: [1.0, 0.0, 0.02],
        }),
    ]
}

fn material() -> MaterialDesc {
    MaterialDesc::classic([0.9, 0.6, 0.3], AmbientSource::Object, 0.2, 0.8, 0.5, 32.0)
}

/// Cameras on a circle of radius 5 around the origin, at three heights.
fn cameras() -> Vec<([f32; 3], Mat4)> {
    let mut out = Vec::new();
    for k in 0..12 {
        for h in [-2.0f32, 0.5, 3.0] {
            let a = k as f32 * core::f32::consts::TAU / 12.0;
            let eye = [5.0 * a.cos(), h, 5.0 * a.sin()];
            out.push((eye, Mat4::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0]).unwrap()));
        }
    }
    out
}

/// Unit directions over the sphere (a latitude–longitude grid).
fn directions() -> Vec<[f32; 3]> {
    let mut out = Vec::new();
    for i in 1..24 {
        for j in 0..48 {
            let (t, p) = (
                i as f32 * core::f32::consts::PI / 24.0,
                j as f32 * core::f32::consts::TAU / 48.0,
            );
            out.push([t.sin() * p.cos(), t.cos(), t.sin() * p.sin()]);
        }
    }
    out
}

fn to_u8(c: V3) -> [u8; 3] {
    c.map(fixshade_testkit::reference::to_u8)
}

/// The largest channel difference, in 8-bit steps, of the tier's colour at
/// every visible point of the unit sphere from every camera, against the
/// reference in world coordinates; `view_lights`: see the lamp through the
/// camera (else it is taken as given, in eye coordinates).
fn worst(view_lights: bool) -> (u32, String) {
    let descs = lamp();
    let mat = material();
    let lights: [AnyLight<Q14>; 3] = descs.map(|d| AnyLight::new(&d).unwrap());
    let world = Lighting::<Q14, _, BlinnPhong>::new(lights, Material::new(&mat).unwrap())
        .with_global_ambient_f32([0.0; 3]);
    let mut worst = (0, String::new());
    for (eye, view) in cameras() {
        let lit = if view_lights {
            world.viewed(&view).unwrap()
        } else {
            world.eye_space()
        };
        // the viewer at infinity behind the camera, in world coordinates
        let back = [view.m[2][0], view.m[2][1], view.m[2][2]];
        let reference = Reference {
            lights: &descs,
            material: mat,
            global_ambient: [0.0; 3],
            viewer: ViewerDesc::Infinite(back),
            fog: None,
            model: ModelDesc::of::<BlinnPhong>(),
        };
        for n in directions() {
            let p = n; // on the unit sphere at the origin
            let pe = view.transform_point(p);
            let ne = view.transform_vector(n);
            // the visible side, within 75° of the viewer (the accuracy domain)
            if ne[2] < 0.26 {
                continue;
            }
            let got = lit
                .shade(
                    &point_from_f32::<Q14>([pe[0], pe[1], pe[2]]),
                    Vec3::from_f32(ne),
                )
                .to_rgb888();
            let got = [got.r(), got.g(), got.b()];
            let want = to_u8(reference.shade(p.map(f64::from), n.map(f64::from)));
            let e = (0..3)
                .map(|c| u32::from(got[c].abs_diff(want[c])))
                .max()
                .unwrap_or(0);
            if e > worst.0 {
                worst = (
                    e,
                    format!("camera at {eye:?}, point {p:?}: got {got:?}, reference {want:?}"),
                );
            }
        }
    }
    worst
}

use embedded_graphics_core::pixelcolor::RgbColor;

#[test]
fn a_fixed_lamp_seen_by_a_circling_camera_matches_the_world_reference() {
    let (e, at) = worst(true);
    assert!(e <= 1, "{e} LSB at {at}");
}

#[test]
fn without_viewing_the_lamp_moves_with_the_camera() {
    let (e, at) = worst(false);
    assert!(
        e > 40,
        "only {e} LSB ({at}): the check would not see eye-space lights"
    );
}

#[test]
fn a_singular_view_is_refused() {
    let world = Lighting::<Q14, _, BlinnPhong>::new(
        AnyLight::<Q14>::new(&lamp()[0]).unwrap(),
        Material::new(&material()).unwrap(),
    )
    .with_global_ambient_f32([0.0; 3]);
    let flat = Mat4 {
        m: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
    };
    // the direction [1, 2, 3] keeps its x and y: allowed
    assert!(world.viewed(&flat).is_ok());
    let zero = Mat4 { m: [[0.0; 4]; 4] };
    assert!(world.viewed(&zero).is_err());
}

/// `Lighting::new` follows OpenGL's `GL_LIGHT_MODEL_AMBIENT` default (0.2):
/// a surface facing away from the only light shows 0.2 × the material's
/// ambient colour, in every tier, and `with_global_ambient_f32([0.0; 3])`
/// makes it black (the README example's `ka = 0.1` is visible).
#[test]
fn lighting_new_has_opengls_global_ambient() {
    fn check<S: fixshade::num::Scalar>(name: &str) {
        // LightColors::white(): no ambient of its own (OpenGL's light 0)
        let light = DirectionalLight::<S>::white([0.0, 0.0, 1.0]).unwrap();
        let mat =
            MaterialDesc::classic([1.0, 0.5, 0.25], AmbientSource::Object, 0.8, 0.7, 0.6, 32.0);
        let lit = Lighting::<S, _, BlinnPhong>::new(light, Material::new(&mat).unwrap());
        let (p, away) = (
            point_from_f32::<S>([0.0; 3]),
            Vec3::from_f32([0.0, 0.0, -1.0]),
        );
        let got = lit.shade(&p, away).to_unorm(8);
        let want = [1.0f64, 0.5, 0.25].map(|c| (0.2 * 0.8 * c * 255.0).round() as i32);
        for k in 0..3 {
            assert!(
                (got[k] as i32 - want[k]).abs() <= 1,
                "{name}: {got:?} vs {want:?}"
            );
        }
        assert!(got[0] >= 40, "{name}: the ambient is visible: {got:?}");
        let none = lit
            .with_global_ambient_f32([0.0; 3])
            .shade(&p, away)
            .to_unorm(8);
        assert_eq!(none, [0; 3], "{name}");
    }
    check::<Q14>("Q14");
    check::<f32>("f32");
    check::<fixshade::num::Q30>("Q30");
}

/// World coordinates are the default, and only a lighting seen from the eye
/// reaches a shader (drawing `Lighting::new` as it is does not compile: the
/// `compile_fail` example of `Lighting::new`): after `viewed` (a camera
/// circling the sphere) the lit side follows the world's lamp; after
/// `eye_space` the lamp moves with the camera.
#[test]
fn viewed_lights_follow_the_world_and_eye_space_ones_the_camera() {
    use fixshade::prelude::*;
    const N: (usize, usize) = uv_sphere_counts(16, 24);
    static SPHERE: MeshData<{ N.0 }, { N.1 }> = MeshData::uv_sphere(16, 24, 14);
    // the lamp on the world's +x side
    let lamp = DirectionalLight::<Q14>::white([1.0, 0.0, 0.0]).unwrap();
    let mat = MaterialDesc::classic([1.0; 3], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0);
    let world = Lighting::<Q14, _, Lambert>::new(lamp, Material::new(&mat).unwrap());
    let vp = Viewport::new(0, 0, 64, 64).unwrap();
    // one frame seen from `eye` with `lit`: the number of lit pixels and
    // their mean column
    let frame = |eye: [f32; 3], lit: &Viewed<Lighting<Q14, DirectionalLight<Q14>, Lambert>>| {
        let camera = Camera::orthographic(-1.2, 1.2, -1.2, 1.2, 1.0, 10.0, vp)
            .unwrap()
            .with_view(Mat4::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0]).unwrap());
        let t = camera.mesh_transform(&Mat4::IDENTITY, SPHERE.frac).unwrap();
        let layout = Layout::full(64, 64).unwrap();
        let mut buffers: MeshBuffers<_, { N.0 }, { bins_len(N.1, 1) }, 1> = MeshBuffers::new();
        let shader = Shader::new(GouraudShading, lit, Linear);
        let mut sphere = MeshDraw::new(
            layout,
            SPHERE.mesh(),
            &t,
            shader,
            buffers.memory(),
            DrawOptions::default(),
        )
        .unwrap();
        let (mut color, mut depth) = ([Rgb565::BLACK; 64 * 64], [0u16; 64 * 64]);
        let mut fb = FullFrame::new(64, 64, &mut color, Some(&mut depth)).unwrap();
        fb.render(Rgb565::BLACK, &mut [&mut sphere]).unwrap();
        let lit: Vec<usize> = (0..64 * 64).filter(|&i| fb.pixels()[i].g() > 20).collect();
        let mean = lit.iter().map(|i| (i % 64) as f32).sum::<f32>() / lit.len().max(1) as f32;
        (lit.len(), mean)
    };
    let front = [0.0, 0.0, 5.0]; // the lamp on the camera's right
    let right = [5.0, 0.0, 0.0]; // the lamp behind the camera: the front lit
    let left = [-5.0, 0.0, 0.0]; // the lamp behind the sphere: unlit from here
    let view = |eye: [f32; 3]| Mat4::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    let (n, x) = frame(front, &world.viewed(&view(front)).unwrap());
    assert!(
        n > 500 && x > 40.0,
        "the lamp on the right: {n} lit, mean column {x}"
    );
    let (n, x) = frame(right, &world.viewed(&view(right)).unwrap());
    assert!(
        n > 1500 && (x - 31.5).abs() < 2.0,
        "the lamp behind the camera: {n} lit, mean column {x}"
    );
    let (n, _) = frame(left, &world.viewed(&view(left)).unwrap());
    assert_eq!(n, 0, "the lamp behind the sphere");
    // eye coordinates by choice: the lamp moves with the camera (on its right)
    let eye = world.eye_space();
    let (n, x) = frame(right, &eye);
    assert!(
        n > 500 && x > 40.0,
        "eye-space lamp on the right: {n} lit, mean column {x}"
    );
}
