//! Inputs the fuzz targets of `fuzz/` found crashing, kept as regression tests
//! (overflow checks are on in this profile, as in the fuzz build).

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::framebuffer::FullFrame;
use fixshade::render::Corner;
use fixshade_testkit::support::{clip_corner, Solid, Tris};

/// One triangle drawn white into a 16 × 16 frame with a depth buffer; the
/// pixels and the depth buffer after the frame.
fn draw(space: ClipSpace, tri: [Corner; 3]) -> (Vec<Gray8>, Vec<u16>) {
    let mut px = vec![Gray8::BLACK; 16 * 16];
    let mut depth = vec![0u16; 16 * 16];
    let mut item = Tris {
        space,
        ..Tris::screen(Solid(Gray8::WHITE), vec![tri])
    };
    FullFrame::new(16, 16, &mut px, Some(&mut depth))
        .unwrap()
        .render(Gray8::BLACK, &mut [&mut item])
        .unwrap();
    (px, depth)
}

/// fuzz target `raster`, crash-f27790be: a vertex at depth `u16::MAX` (the far
/// plane) overflowed the upper depth bound `(65535 << 15) + 2^15 − 1` in
/// the removed `raster::exact` ("attempt to add with overflow"; in release it
/// wrapped twice back to the right value). Every pixel must be drawn and pass
/// `z < 65535` where its interpolated depth is below the far plane — in
/// screen space and in a perspective clip space (depth `z/w` at the far
/// plane: `z = w`), where the same triangle gives the same pixels.
#[test]
fn a_vertex_at_the_far_plane() {
    let v = |x: i32, y: i32, z: u16| {
        clip_corner(
            Clip {
                x: x << SUBPIXEL_BITS,
                y: y << SUBPIXEL_BITS,
                z: i32::from(z),
                w: 1,
            },
            0,
        )
    };
    // the same points in a perspective clip space (w = 1000, centre 0):
    // depth 65535 at z = w, 0 at z = −w
    let p = |c: Corner| {
        let (w, d) = (1000, c.clip.z);
        let z = match d {
            65535 => w,
            0 => -w,
            _ => (i64::from(d) * 2 * i64::from(w) / 65535 - i64::from(w)) as i32,
        };
        clip_corner(
            Clip {
                x: c.clip.x * w,
                y: c.clip.y * w,
                z,
                w,
            },
            0,
        )
    };
    for z in [
        [u16::MAX; 3],
        [0, u16::MAX, u16::MAX],
        [u16::MAX, 1, 30_000],
    ] {
        let tri = [v(0, 0, z[0]), v(16, 0, z[1]), v(0, 16, z[2])];
        let (px, depth) = draw(ClipSpace::SCREEN, tri);
        let (px2, depth2) = draw(ClipSpace::perspective([0, 0], 1), tri.map(p));
        let drawn = px.iter().filter(|&&p| p == Gray8::WHITE).count();
        if z == [u16::MAX; 3] {
            assert_eq!(drawn, 0, "nothing passes z < 65535 at the far plane");
        } else {
            assert!(drawn > 0, "{z:?}");
        }
        // every drawn pixel stored a depth that passed the test, and only those
        for (px, depth) in [(&px, &depth), (&px2, &depth2)] {
            for (p, d) in px.iter().zip(depth) {
                assert_eq!(*p == Gray8::WHITE, *d < u16::MAX, "{z:?}");
            }
        }
        if z[0] == z[1] && z[1] == z[2] {
            assert_eq!(px, px2, "{z:?}: perspective with equal w = screen space");
        }
    }
}

/// fuzz target `constructors`, crash-25198181: an orthographic camera and
/// matrices with `f32::MAX` and 32768 entries give a transform row whose
/// output saturates at `i32::MAX` with one fraction bit; rounding it to whole
/// units added 1 to `i32::MAX` in `Row::apply_round` ("attempt to add with
/// overflow"). The rounding is now `(v >> f) + ((v >> (f − 1)) & 1)`: the same
/// values, no overflow.
#[test]
fn orthographic_transform_rounding_at_i32_max() {
    use fixshade::camera::{Camera, Viewport};
    use fixshade::num::Mat4;
    let vp = Viewport::new(0, 0, 64, 64).unwrap();
    let view = Mat4 {
        m: [
            [1.0, 0.0, 0.0, 0.752_929_7],
            [0.0, 1.0, 0.0, -0.0],
            [0.0, 0.0, 1.0, f32::MAX],
            [0.0, 0.0, 0.0, 1.0],
        ],
    };
    let model = Mat4 {
        m: [
            [0.0, 0.0, 0.0, 32768.0],
            [0.0, 0.0, 0.0, f32::MAX],
            [0.0, 0.0, 32768.0, 32768.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
    };
    let cam = Camera::orthographic(f32::MAX, -0.0, 0.619_873_05, 32768.0, 32768.0, -0.0, vp);
    let Ok(cam) = cam else {
        panic!("the fuzzer's camera is accepted: {cam:?}");
    };
    if let Ok(t) = cam.with_view(view).mesh_transform(&model, 4) {
        for raw in [[6189, 0, 0], [i16::MAX; 3], [i16::MIN; 3], [0; 3]] {
            let _ = t.project(raw);
        }
    }
}

// ---- the mesh renderer and surface detail (issue 21, item 7) ---------------------------

// The fuzz targets' decoding and checks: `fixshade_fuzz` (fuzz/src/, the library
// of the fuzz package), so that a kept input replays here exactly as in the fuzzer.

/// fuzz target `surface`, crash-4a9262f7: a 1 × 1 normal map of
/// `NormalMap::normalize_texels([i16::MIN; 3])` = `[−9459; 3]` (a unit normal facing
/// into the surface) on the seamed 6 × 8 sphere turned by `f32::MAX` radians,
/// a 12-pixel frame, through the fast normal-map kernel (then `FastNormalMapShader`) (`Q14<1>`, Blinn-Phong):
/// "attempt to multiply with overflow" in the fast path's `n·L` (normalmap.rs
/// line 852).
#[test]
fn surface_fast_normal_map_on_a_turned_sphere() {
    fixshade_fuzz::surface::run(include_bytes!(
        "../../fuzz/regressions/surface/crash-4a9262f7c490278123e3aac51c48d2d7e0b7fc34"
    ));
}

/// fuzz target `mesh`, crash-335eed3a: a small mesh of extreme positions and
/// normals through `IncrementalPhongShading`: "attempt to multiply with
/// overflow" squaring an interpolated normal component (incremental.rs line
/// 194).
#[test]
fn mesh_incremental_phong_extreme_normals() {
    fixshade_fuzz::mesh::run(include_bytes!(
        "../../fuzz/regressions/mesh/crash-335eed3a497e6dd397f3ee982617850211fe40e6"
    ));
}

/// fuzz target `surface`, crash-569c613a: a 1 × 1 map of
/// `NormalMap::normalize_texels([0, i16::MIN, i16::MIN])` on the sphere turned by
/// `−f32::MAX` radians, the fast normal-map kernel (`Q14<1>`): the Newton update
/// of `1/|H|` after a span's last pixel, from `|H|²` stepped beyond the span
/// (wrapped, never used), overflowed ("attempt to multiply with overflow",
/// normalmap.rs line 891); it wraps now, like the other accumulators there.
#[test]
fn surface_fast_normal_map_newton_after_the_last_pixel() {
    fixshade_fuzz::surface::run(include_bytes!(
        "../../fuzz/regressions/surface/crash-569c613ab464faaebbc74a3599ffa85ce416b263"
    ));
}

/// fuzz targets `raster`, crash-806ef1a3 and crash-820c4833: slivers
/// crossing the near plane (one corner in front; behind it, corners at
/// `(i32::MIN, i32::MIN)` with `w = 1` or `w = i32::MIN`), clipped to the
/// near plane and the window: after rounding their cut corners to
/// sub-pixels, the polygons were no longer convex (in the first, the fan's
/// two non-empty triangles had opposite windings of equal area, so the
/// rounded polygon's winding, zero, could not tell the folded one; in the
/// second, a corner bent inwards), and one pixel was drawn twice by one
/// triangle. The rounded polygon is now made convex again in the triangle's
/// exact facing before its fan is drawn: every pixel is written at most once,
/// in either winding and under every culling.
#[test]
fn slivers_cut_by_the_near_plane_are_drawn_once() {
    use fixshade::raster::Cull;
    use fixshade_testkit::support::{full, lumas, Count, Tris};
    let c = |x: i32, y: i32, z: i32, w: i32| clip_corner(Clip { x, y, z, w }, 0);
    let m = i32::MIN;
    let cases = [
        (
            ClipSpace::perspective([280, 280], 71),
            (18, 33),
            [c(0, -82, -65025, 256), c(650, 650, m, 1), c(m, m, m, 1)],
        ),
        (
            ClipSpace::perspective([289, 0], 1),
            (20, 38),
            [
                c(-197, -192, -404_233_448, 256),
                c(-835, 32382, 2_122_219_262, 152),
                c(m, m, m, m),
            ],
        ),
    ];
    for (space, (w, h), tri) in cases {
        for cull in [Cull::None, Cull::Back, Cull::Front] {
            for t in [tri, [tri[0], tri[2], tri[1]]] {
                let mut item = Tris {
                    space,
                    cull,
                    ..Tris::screen(Count, vec![t])
                };
                let counts = lumas(&full(w, h, Gray8::new(0), false, &mut [&mut item]));
                assert!(counts.iter().all(|&n| n <= 1), "{cull:?} {counts:?}");
            }
        }
    }
}

/// fuzz target `mesh`, crash-5167a126: a model matrix whose normal matrix has
/// only subnormal elements: scaling its largest element to 16384 multiplied by
/// `16384 / max` = infinity, so the Q14 normal rows became `i16::MAX`, and
/// transforming a normal overflowed ("attempt to add with overflow",
/// camera/mod.rs line 365). Each element is now divided by the largest
/// first (at most 1 in magnitude).
#[test]
fn mesh_normal_matrix_of_subnormal_elements() {
    fixshade_fuzz::mesh::run(include_bytes!(
        "../../fuzz/regressions/mesh/crash-5167a126ce8b9c84b1e115695299a119ee61a2cd"
    ));
}
