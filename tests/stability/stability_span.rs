//! Drawing never panics or wraps at the geometry range (issue 11, item 1):
//! the kernels interpolate values along a run, and with the eye-space
//! position as a value (point light, local viewer, fog) a vertex at the edge
//! of the range once made `start + len·step` leave `i32` after the last
//! pixel ("attempt to add with overflow"). Overflow checks are on in this
//! profile (opt-level 2 with debug assertions), so any wrap fails these
//! tests. Every tier, Flat/Gouraud/Phong (both kernels), through the
//! per-triangle front (`render::draw_triangle`) in screen space and in a
//! perspective clip space (varying `w`), wide triangles (long runs, large
//! steps).
//!
//! The eye position reaches a kernel as Q16.16 (`VertexIn::eye`): the
//! geometry range is ±32 768 units, and `f32` positions at and beyond it
//! (huge, infinite, NaN) are what a transform saturates them to (`as`
//! saturates, NaN → 0; `MeshTransform::eye` saturates the same way).

use fixshade_testkit::seeded;

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::color::Linear;
use fixshade::color::Rgb;
use fixshade::lighting::{AnyLight, LightDesc, LightKind};
use fixshade::lighting::{BlinnPhong, Lighting, LinearFog, LocalViewer};
use fixshade::lighting::{Material, MaterialDesc};
use fixshade::num::{F32Fast, Scalar, Q14, Q30};
use fixshade::raster::Cull;
use fixshade::render::Corner;
use fixshade::shade::{FlatShading, GouraudShading, PhongShading, Shader, VertexIn};
use fixshade_testkit::support::{full, Tris};
use proptest::prelude::*;

const W: u32 = 64;

/// Draws one wide triangle with the given eye-space positions in every mode
/// (`flat`: Flat shading too), screen-linear and perspective; returns the
/// Phong frame.
fn draw_all<S: Scalar>(pos: [[f32; 3]; 3], light: [f32; 3], flat: bool) -> Vec<Rgb565> {
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
        .with_fog(fog)
        .eye_space();
    // a triangle covering most of the 64 × 64 frame: runs of up to 60 pixels
    let scr = [[2, 2], [62, 5], [10, 62]]
        .map(|[x, y]: [i32; 2]| [x << SUBPIXEL_BITS, y << SUBPIXEL_BITS]);
    let w = [4096, 256, 2048];
    let normals = [[0, 0, 16384], [9830, 0, 13107], [0, -9830, 13107]];
    let q16 = |v: f32| (v * 65536.0) as i32;
    let centre = [32 << SUBPIXEL_BITS; 2];
    let tri = |persp: bool| -> [Corner; 3] {
        core::array::from_fn(|i| {
            let clip = if persp {
                Clip {
                    x: (scr[i][0] - centre[0]) * w[i],
                    y: (scr[i][1] - centre[1]) * w[i],
                    z: 0,
                    w: w[i],
                }
            } else {
                Clip {
                    x: scr[i][0],
                    y: scr[i][1],
                    z: 100,
                    w: 1,
                }
            };
            Corner {
                clip,
                vertex: VertexIn::new(normals[i], pos[i].map(q16)),
            }
        })
    };
    let mut phong = Vec::new();
    for persp in [false, true] {
        let space = if persp {
            ClipSpace::perspective(centre, 1)
        } else {
            ClipSpace::SCREEN
        };
        macro_rules! run {
            ($mode:expr) => {{
                let s = Shader::new($mode, &lit, Linear);
                let mut item = Tris {
                    space,
                    cull: Cull::None,
                    ..Tris::screen(s, vec![tri(persp)])
                };
                let px = full(W, W, Rgb565::BLACK, true, &mut [&mut item]);
                // (a black pixel may be lit black: count the frame's drawn
                // pixels by drawing once more over white)
                let mut item = Tris {
                    space,
                    cull: Cull::None,
                    ..Tris::screen(s, vec![tri(persp)])
                };
                let over = full(W, W, Rgb565::WHITE, true, &mut [&mut item]);
                let drawn = px.iter().zip(&over).filter(|(a, b)| a == b).count();
                assert!(drawn > 1000, "{}: the triangle is drawn ({drawn})", S::NAME);
                px
            }};
        }
        if flat {
            run!(FlatShading);
        }
        run!(GouraudShading);
        // (`PhongShading` picks this kernel for a point light; generic
        // code over the tier names it)
        let p = run!(PhongShading);
        if !persp {
            phong = p;
        }
    }
    phong
}

fn every_tier(pos: [[f32; 3]; 3], light: [f32; 3]) {
    every_tier_of(pos, light, true)
}

fn every_tier_of(pos: [[f32; 3]; 3], light: [f32; 3], flat: bool) {
    draw_all::<f32>(pos, light, flat);
    draw_all::<F32Fast<1>>(pos, light, flat);
    draw_all::<Q30<3>>(pos, light, flat);
    draw_all::<Q14<0>>(pos, light, flat);
    draw_all::<Q14<2>>(pos, light, flat);
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

/// Item 6's case through the whole pipeline, at the edge of the Q16.16 range
/// that eye positions now have (it was z = −40 000 with `f32` vertex
/// positions, which the new vertex input cannot carry): a surface at
/// z = −32 000 lit by a point light 10 units above it is lit under Phong.
#[test]
fn phong_lights_a_surface_near_the_edge_of_the_range() {
    let z = -32_000.0f32;
    let pos = [[-1.0, -1.0, z], [1.0, -1.0, z], [-1.0, 1.0, z]];
    let frame = draw_all::<f32>(pos, [0.0, 0.0, z + 10.0], true);
    let lit = frame.iter().filter(|p| p.r() > 4).count();
    assert!(lit > 1000, "Phong at z = −32 000: {lit} lit pixels");
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
        every_tier_of(p, light, false);
    }

    #[test]
    fn wild_positions_never_wrap_flat(
        p in proptest::array::uniform3(proptest::array::uniform3(wild())),
        light in proptest::array::uniform3(wild()),
    ) {
        every_tier(p, light);
    }
}

/// The case the property test found: two vertices 32 768 units (Q16.16
/// `i32::MAX`) from the first along z.
#[test]
fn flat_centroid_of_far_apart_positions() {
    every_tier(
        [[0.0, 0.0, 0.0], [0.0, 0.0, 32768.0], [0.0, 0.0, 32768.0]],
        [0.0; 3],
    );
}
