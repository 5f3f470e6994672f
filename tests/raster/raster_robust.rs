//! Any corner values through the per-triangle front (`render::draw_triangle`,
//! screen space or a perspective clip space, any culling, with or without a
//! depth buffer, whole frame or bands): no panic, no overflow (debug
//! build), no run outside the band, every pixel written at most once, and
//! the values a kernel is handed inside the range it declares safe
//! (`Kernel::safe`, here the corners' range: the pipeline must clamp runs
//! whose error bound could leave it) — for a perspective clip space, inside
//! the corners' range always (every value is a convex combination).

use std::cell::Cell;

use fixshade_testkit::seeded;

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};
use fixshade::camera::{Clip, ClipSpace};
use fixshade::framebuffer::{BandView, DrawBand};
use fixshade::num::ATTR_FRAC;
use fixshade::raster::interp::VARYING_LIMIT;
use fixshade::raster::Cull;
use fixshade::render::{draw_triangle, Corner};
use fixshade::shade::{Kernel, VertexIn};
use fixshade_testkit::support::{banded, full, lumas};
use proptest::prelude::*;

const W: u32 = 40;
const H: u32 = 30;

/// Checks every run against the band and the declared range, counts pixels.
#[derive(Debug)]
struct Check {
    /// The corners' range of each value, with `ATTR_FRAC` bits.
    lo: [i64; 2],
    hi: [i64; 2],
    /// The frame width.
    w: u32,
    rows: Cell<(i32, i32)>,
    pixels: Cell<u32>,
}

impl Kernel for &Check {
    type Color = Gray8;
    type Vertex = [i32; 2];
    type Varyings = [i32; 2];
    type Triangle = ();
    const NEEDS_POSITION: bool = false;

    fn vertex(&self, v: &VertexIn) -> [i32; 2] {
        [v.normal[0], v.normal[1]]
    }

    fn triangle(&self, v: [&[i32; 2]; 3], _: &[[i32; 3]; 3]) -> ((), [[i32; 2]; 3]) {
        ((), [*v[0], *v[1], *v[2]])
    }

    fn safe(&self, i: usize) -> (i32, i32) {
        (self.lo[i] as i32, self.hi[i] as i32)
    }

    fn span(&self, _: &(), start: &[i32; 2], step: &[i32; 2], x: i32, y: i32, out: &mut [Gray8]) {
        assert!(!out.is_empty());
        assert!(
            x >= 0 && x as u32 + out.len() as u32 <= self.w,
            "x {x} len {}",
            out.len()
        );
        let rows = self.rows.get();
        assert!((rows.0..rows.1).contains(&y), "row {y} outside {rows:?}");
        for i in 0..2 {
            for k in [0, out.len() as i64 - 1] {
                let a = i64::from(start[i]) + k * i64::from(step[i]);
                assert!(
                    a >= self.lo[i] && a <= self.hi[i],
                    "value {i} = {a} outside {}..={} (pixel {k} of {} at ({x}, {y}))",
                    self.lo[i],
                    self.hi[i],
                    out.len()
                );
            }
        }
        self.pixels.set(self.pixels.get() + out.len() as u32);
        for p in out.iter_mut() {
            *p = Gray8::new(p.luma().wrapping_add(1));
        }
    }
}

fn checker(t: &[Corner; 3]) -> Check {
    let r = |i: usize| {
        // values are clamped to ±VARYING_LIMIT before set-up
        let lim = i64::from(VARYING_LIMIT);
        let a = t.map(|c| i64::from(c.vertex.normal[i]).clamp(-lim, lim) << ATTR_FRAC);
        (a[0].min(a[1]).min(a[2]), a[0].max(a[1]).max(a[2]))
    };
    Check {
        lo: [r(0).0, r(1).0],
        hi: [r(0).1, r(1).1],
        w: W,
        rows: Cell::new((0, 0)),
        pixels: Cell::new(0),
    }
}

/// One triangle, the checker told each band's rows.
struct One<'a> {
    check: &'a Check,
    tri: [Corner; 3],
    space: ClipSpace,
    cull: Cull,
}

impl DrawBand<Gray8> for One<'_> {
    fn draw_band(&mut self, band: &mut BandView<'_, Gray8>) {
        let r = band.rows();
        self.check.rows.set((r.start, r.end));
        draw_triangle(band, &self.space, &self.check, &self.tri, self.cull);
    }
}

fn coord() -> impl Strategy<Value = i32> {
    prop_oneof![
        any::<i32>(),
        -2000i32..2000,
        -100_000i32..100_000,
        Just(i32::MIN),
        Just(i32::MAX)
    ]
}

fn value() -> impl Strategy<Value = i32> {
    prop_oneof![
        any::<i32>(),
        -VARYING_LIMIT..=VARYING_LIMIT,
        Just(VARYING_LIMIT),
        Just(-VARYING_LIMIT)
    ]
}

fn corner() -> impl Strategy<Value = Corner> {
    let w = prop_oneof![any::<i32>(), 1i32..100_000, Just(1), Just(0), Just(-1)];
    (coord(), coord(), any::<i32>(), w, value(), value()).prop_map(|(x, y, z, w, a, b)| Corner {
        clip: Clip { x, y, z, w },
        vertex: VertexIn::new([a, b, 0], [0; 3]),
    })
}

/// A corner near the frame (sub-pixels; in perspective spaces with `w` up
/// to 4 still near the centre): most of such triangles cover part of it.
fn near_corner() -> impl Strategy<Value = Corner> {
    let w = prop_oneof![1i32..4, Just(1), any::<i32>()];
    (
        -400i32..1100,
        -400i32..900,
        any::<i32>(),
        w,
        value(),
        value(),
    )
        .prop_map(|(x, y, z, w, a, b)| Corner {
            clip: Clip { x, y, z, w },
            vertex: VertexIn::new([a, b, 0], [0; 3]),
        })
}

fn triangle() -> impl Strategy<Value = [Corner; 3]> {
    prop_oneof![
        [corner(), corner(), corner()],
        [near_corner(), near_corner(), near_corner()],
        (near_corner(), near_corner(), corner()).prop_map(|(a, b, c)| [a, b, c]),
    ]
}

/// Screen space, or a perspective clip space with any centre and near plane.
fn space() -> impl Strategy<Value = ClipSpace> {
    prop_oneof![
        Just(ClipSpace::SCREEN),
        (coord(), coord(), any::<i32>()).prop_map(|(x, y, n)| ClipSpace::perspective([x, y], n)),
        (0i32..(W as i32) << 4, 0i32..(H as i32) << 4, 1i32..5000)
            .prop_map(|(x, y, n)| ClipSpace::perspective([x, y], n)),
    ]
}

fn cull() -> impl Strategy<Value = Cull> {
    prop_oneof![Just(Cull::None), Just(Cull::Back), Just(Cull::Front)]
}

proptest! {
    #![proptest_config(seeded::config("raster_robust", 3000))]

    #[test]
    fn any_triangle_is_safe(tri in triangle(), space in space(), cull in cull(), use_depth in any::<bool>()) {
        let check = checker(&tri);
        let mut item = One { check: &check, tri, space, cull };
        let px = lumas(&full(W, H, Gray8::new(0), use_depth, &mut [&mut item]));
        prop_assert!(px.iter().all(|&p| p <= 1), "pixel written twice by one triangle");
        prop_assert_eq!(px.iter().filter(|&&p| p == 1).count() as u32, check.pixels.get());
    }

    #[test]
    fn any_triangle_in_bands_is_safe(tri in triangle(), space in space(), cull in cull(), band_rows in 1u32..9) {
        let check = checker(&tri);
        let mut item = One { check: &check, tri, space, cull };
        let px = lumas(&banded(W, H, band_rows, Gray8::new(0), true, &mut [&mut item]));
        prop_assert!(px.iter().all(|&p| p <= 1), "pixel written twice by one triangle");
        prop_assert_eq!(px.iter().filter(|&&p| p == 1).count() as u32, check.pixels.get());
        // the same pixels as the whole frame
        let check2 = checker(&tri);
        let mut item = One { check: &check2, tri, space, cull };
        let whole = lumas(&full(W, H, Gray8::new(0), true, &mut [&mut item]));
        prop_assert_eq!(px, whole);
    }
}

/// The sliver of `raster_precision` (a plane whose change per pixel
/// saturates, beyond `Setup::err`): its values still stay in the range the
/// kernel declares safe (clamped runs).
#[test]
fn sliver_with_a_saturating_gradient_stays_in_the_safe_range() {
    let tri = [(609, 2392, 32767), (2951, 827, -168), (532, 2438, -6211)].map(|(x, y, a)| Corner {
        clip: Clip { x, y, z: 0, w: 1 },
        vertex: VertexIn::new([a, 0, 0], [0; 3]),
    });
    let check = Check {
        w: 200,
        ..checker(&tri)
    };
    let mut item = One {
        check: &check,
        tri,
        space: ClipSpace::SCREEN,
        cull: Cull::None,
    };
    full(200, 200, Gray8::new(0), false, &mut [&mut item]);
    assert!(check.pixels.get() > 0, "{}", check.pixels.get());
}

/// Found by the `raster` fuzz target (fuzz/regressions/raster/crash-f684d5c9…):
/// a sliver with one corner on the near plane, one just beyond it and one
/// behind the eye, in a perspective clip space. Clipped to the near plane
/// and the window and cut into a fan, it must still cover every pixel at
/// most once.
#[test]
fn near_clipped_sliver_writes_each_pixel_once() {
    let space = ClipSpace::perspective([280, 280], 71);
    let c = |x: i32, y: i32, z: i32, w: i32| Corner {
        clip: Clip { x, y, z, w },
        vertex: VertexIn::new([0; 3], [0; 3]),
    };
    let tri = [
        c(562, 562, -57252, 71),
        c(7, 0, i32::MIN, 256),
        c(i32::MIN, i32::MIN, i32::MIN, 1),
    ];
    let check = Check {
        w: 18,
        ..checker(&tri)
    };
    let mut item = One {
        check: &check,
        tri,
        space,
        cull: Cull::None,
    };
    let px = lumas(&full(18, 33, Gray8::new(0), false, &mut [&mut item]));
    let twice: Vec<(usize, usize)> = (0..px.len())
        .filter(|&i| px[i] > 1)
        .map(|i| (i % 18, i / 18))
        .collect();
    assert!(px.iter().any(|&n| n > 0));
    assert!(twice.is_empty(), "written twice: {twice:?}");
}
