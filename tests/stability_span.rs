//! Drawing never panics or wraps at the geometry range (issue 11, item 1):
//! `Phong` and `Gouraud` step their attributes along a run, and with the
//! eye-space position as an attribute (point light, local viewer, fog) a
//! vertex at or beyond ±32 768 units — or an infinite or huge `f32` position
//! through `ShadeVertex::new` — made `start + len·step` leave `i32` after the
//! last pixel ("attempt to add with overflow" inside `Shading::draw`). Overflow
//! checks are on in this profile (opt-level 2 with debug assertions), so any
//! wrap fails these tests. Every tier, Flat/Gouraud/Phong, `draw` and
//! `draw_perspective`, wide triangles (long runs, large steps).

#[path = "common/seeded.rs"]
mod seeded;

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::color::Rgb;
use fixshade::light::{AnyLight, LightDesc, LightKind};
use fixshade::lighting::{BlinnPhong, Lighting, LinearFog, LocalViewer};
use fixshade::material::{Material, MaterialDesc};
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade::raster::{RasterOptions, SUBPIXEL_BITS};
use fixshade::shade::{
    FlatShading, GouraudShading, Linear, PhongShading, ShadeVertex, Shader, Shading,
};
use fixshade::target::SliceFramebuffer;
use proptest::prelude::*;

const W: u32 = 64;

/// Draws one wide triangle with the given eye-space positions in every mode,
/// screen-linear and perspective; returns the Phong frame.
fn draw_all<S: Scalar>(pos: [[f32; 3]; 3], light: [f32; 3]) -> Vec<Rgb565> {
    let desc = LightDesc {
        kind: LightKind::Point {
            position: light,
            attenuation: [1.0, 0.0, 0.0],
        },
        ambient: [0.1; 3],
        diffuse: [0.8; 3],
        specular: [0.5; 3],
    };
    // a light position the constructor rejects (∞, NaN: a typed error) falls back to the origin
    let light = AnyLight::<S>::new(&desc).unwrap_or_else(|_| {
        let mut d = desc;
        d.kind = LightKind::Point {
            position: [0.0; 3],
            attenuation: [1.0, 0.0, 0.0],
        };
        AnyLight::new(&d).unwrap()
    });
    let lights = [light];
    let m = Material::<S>::new(&MaterialDesc {
        diffuse: [0.8, 0.6, 0.4],
        specular: [0.5; 3],
        shininess: 16.0,
        ..MaterialDesc::default()
    })
    .unwrap();
    let fog = LinearFog::<S>::new(1.0, 50_000.0, [0.2, 0.3, 0.4]).unwrap();
    let lit = Lighting::<S, _, BlinnPhong>::new(lights, m)
        .with_global_ambient(Rgb::splat(S::from_f32(0.1)))
        .with_viewer(LocalViewer::<S>::new([0.0; 3]).unwrap())
        .with_fog(fog);
    // a triangle covering most of the 64 × 64 frame: runs of up to 60 pixels
    let scr = [[2, 2], [62, 5], [10, 62]]
        .map(|[x, y]: [i32; 2]| [x << SUBPIXEL_BITS, y << SUBPIXEL_BITS]);
    let inv_w = [1 << 16, 1 << 12, 1 << 15];
    let normals = [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, -0.6, 0.8]];
    let tri: [ShadeVertex<S>; 3] =
        core::array::from_fn(|i| ShadeVertex::new(scr[i], 100, inv_w[i], pos[i], normals[i]));
    let o = RasterOptions::default();
    let mut px = vec![Rgb565::BLACK; (W * W) as usize];
    let mut phong = Vec::new();
    for persp in [false, true] {
        macro_rules! run {
            ($mode:expr) => {{
                px.fill(Rgb565::BLACK);
                let mut fb = SliceFramebuffer::new(&mut px, W, W).unwrap();
                let mut s = Shader::new($mode, &lit, Linear);
                let r = if persp {
                    s.draw_perspective(&mut fb, None, &tri, &o)
                } else {
                    s.draw(&mut fb, None, &tri, &o)
                };
                let stats = r.unwrap();
                assert!(stats.pixels > 1000, "{}: the triangle is drawn", S::NAME);
            }};
        }
        run!(FlatShading);
        run!(GouraudShading);
        run!(PhongShading);
        if !persp {
            phong = px.clone();
        }
    }
    phong
}

fn every_tier(pos: [[f32; 3]; 3], light: [f32; 3]) {
    draw_all::<f32>(pos, light);
    draw_all::<F32Fast<1>>(pos, light);
    draw_all::<Q30<3>>(pos, light);
    draw_all::<Q14<0>>(pos, light);
    draw_all::<Q14<2>>(pos, light);
}

#[test]
fn positions_at_and_beyond_the_geometry_range() {
    let edges = [
        32_767.0f32,
        32_768.0,
        -32_768.0,
        -32_769.0,
        40_000.0,
        -40_000.0,
        1.0e9,
        -1.0e9,
        1.0e30,
        f32::MAX,
        -f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];
    for &e in &edges {
        // one vertex far away, the others near: the largest steps
        every_tier(
            [[0.0, 0.0, -5.0], [e, 0.0, -5.0], [0.0, 1.0, -5.0]],
            [0.0, 10.0, 0.0],
        );
        every_tier(
            [[0.0, 0.0, -5.0], [1.0, 0.0, -5.0], [0.0, -e, e]],
            [0.0, 10.0, 0.0],
        );
        // opposite extremes on two vertices
        every_tier([[-e, -e, -e], [e, e, e], [0.0, 0.0, -5.0]], [e, 0.0, 0.0]);
        every_tier(
            [[e, 0.0, -5.0], [-e, 0.0, -5.0], [0.0, e, -e]],
            [0.0, 0.0, 0.0],
        );
    }
}

/// Item 6's case through the whole pipeline: a surface at z = −40 000 lit by a
/// point light 10 units above it is lit under Phong as under Gouraud (the
/// float tiers no longer clamp the position attribute to ±32 768).
#[test]
fn phong_lights_a_surface_beyond_32768_units() {
    let z = -40_000.0f32;
    let pos = [[-1.0, -1.0, z], [1.0, -1.0, z], [-1.0, 1.0, z]];
    let frame = draw_all::<f32>(pos, [0.0, 0.0, z + 10.0]);
    let lit = frame.iter().filter(|p| p.r() > 4).count();
    assert!(lit > 1000, "Phong at z = −40 000: {lit} lit pixels");
}

fn wild() -> impl Strategy<Value = f32> {
    prop_oneof![
        2 => -100.0f32..100.0,
        2 => -70_000.0f32..70_000.0,
        1 => proptest::num::f32::ANY,
        1 => Just(32_768.0f32),
        1 => Just(-32_768.0f32),
        1 => Just(f32::INFINITY),
        1 => Just(f32::MAX),
    ]
}

proptest! {
    #![proptest_config(seeded::config("stability_span", 300))]

    #[test]
    fn wild_positions_never_wrap(
        p in proptest::array::uniform3(proptest::array::uniform3(wild())),
        light in proptest::array::uniform3(wild()),
    ) {
        every_tier(p, light);
    }
}
