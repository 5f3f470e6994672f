//! Inputs the fuzz targets of `fuzz/` found crashing, kept as regression tests
//! (overflow checks are on in this profile, as in the fuzz build).

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::raster::{
    draw_triangle, draw_triangle_perspective, RasterOptions, RasterVertex, SpanShader,
    SUBPIXEL_BITS,
};
use fixshade::target::{DepthBuffer, SliceFramebuffer};

struct White;
impl SpanShader<0> for White {
    type Color = Gray8;
    fn shade_span(&mut self, _x: i32, _y: i32, _s: &[i32; 0], _d: &[i32; 0], out: &mut [Gray8]) {
        out.fill(Gray8::WHITE);
    }
}

/// fuzz target `raster`, crash-f27790be: a vertex at depth `u16::MAX` (the far
/// plane) overflowed the upper depth bound `(65535 << 15) + 2^15 − 1` in
/// `raster::exact` ("attempt to add with overflow"; in release it wrapped twice
/// back to the right value). Every pixel must be drawn and pass `z < 65535`
/// where its interpolated depth is below the far plane.
#[test]
fn a_vertex_at_the_far_plane() {
    let v = |x: i32, y: i32, z: u16| RasterVertex {
        x: x << SUBPIXEL_BITS,
        y: y << SUBPIXEL_BITS,
        z,
        inv_w: 1 << 16,
        attrs: [],
    };
    for z in [
        [u16::MAX; 3],
        [0, u16::MAX, u16::MAX],
        [u16::MAX, 1, 30_000],
    ] {
        let tri = [v(0, 0, z[0]), v(16, 0, z[1]), v(0, 16, z[2])];
        let mut px = [Gray8::BLACK; 16 * 16];
        let mut depth = [u16::MAX; 16 * 16];
        let mut fb = SliceFramebuffer::new(&mut px, 16, 16).unwrap();
        let mut db = DepthBuffer::new(&mut depth, 16).unwrap();
        let s = draw_triangle(
            &mut fb,
            Some(&mut db),
            &tri,
            &RasterOptions::default(),
            &mut White,
        )
        .unwrap();
        let mut px2 = [Gray8::BLACK; 16 * 16];
        let mut depth2 = [u16::MAX; 16 * 16];
        let mut fb2 = SliceFramebuffer::new(&mut px2, 16, 16).unwrap();
        let mut db2 = DepthBuffer::new(&mut depth2, 16).unwrap();
        let p = draw_triangle_perspective(
            &mut fb2,
            Some(&mut db2),
            &tri,
            &RasterOptions::default(),
            &mut White,
        )
        .unwrap();
        assert_eq!(s, p, "{z:?}");
        if z == [u16::MAX; 3] {
            assert_eq!(s.pixels, 0, "nothing passes z < 65535 at the far plane");
        } else {
            assert!(s.pixels > 0, "{z:?}");
        }
        // every drawn pixel stored a depth that passed the test, and only those
        for (p, d) in px.iter().zip(depth) {
            assert_eq!(*p == Gray8::WHITE, d < u16::MAX, "{z:?}");
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
    use fixshade::camera::Camera;
    use fixshade::mesh::{Mat4, Viewport};
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

/// The fuzz targets' decoding and checks (`fuzz/src/`), so that a kept input
/// replays here exactly as in the fuzzer.
#[path = "../fuzz/src/lib.rs"]
mod fuzz;

/// fuzz target `surface`, crash-4a9262f7: a 1 × 1 normal map of
/// `normalize_texels([i16::MIN; 3])` = `[−9459; 3]` (a unit normal facing
/// into the surface) on the seamed 6 × 8 sphere turned by `f32::MAX` radians,
/// a 12-pixel frame, through `FastNormalMapShader` (`Q14<1>`, Blinn-Phong):
/// "attempt to multiply with overflow" in the fast path's `n·L` (normalmap.rs
/// line 852).
#[test]
fn surface_fast_normal_map_on_a_turned_sphere() {
    fuzz::surface::run(include_bytes!(
        "../fuzz/regressions/surface/crash-4a9262f7c490278123e3aac51c48d2d7e0b7fc34"
    ));
}

/// fuzz target `mesh`, crash-335eed3a: a small mesh of extreme positions and
/// normals through `IncrementalPhongShading`: "attempt to multiply with
/// overflow" squaring an interpolated normal component (incremental.rs line
/// 194).
#[test]
fn mesh_incremental_phong_extreme_normals() {
    fuzz::mesh::run(include_bytes!(
        "../fuzz/regressions/mesh/crash-335eed3a497e6dd397f3ee982617850211fe40e6"
    ));
}

/// fuzz target `surface`, crash-569c613a: a 1 × 1 map of
/// `normalize_texels([0, i16::MIN, i16::MIN])` on the sphere turned by
/// `−f32::MAX` radians, `FastNormalMapShader` (`Q14<1>`): the Newton update
/// of `1/|H|` after a span's last pixel, from `|H|²` stepped beyond the span
/// (wrapped, never used), overflowed ("attempt to multiply with overflow",
/// normalmap.rs line 891); it wraps now, like the other accumulators there.
#[test]
fn surface_fast_normal_map_newton_after_the_last_pixel() {
    fuzz::surface::run(include_bytes!(
        "../fuzz/regressions/surface/crash-569c613ab464faaebbc74a3599ffa85ce416b263"
    ));
}
