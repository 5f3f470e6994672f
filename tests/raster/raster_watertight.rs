//! Watertightness: meshes of triangles sharing edges cover every pixel of
//! their hull exactly once, whatever the sub-pixel jitter and winding,
//! through the per-triangle front (`render::draw_triangle`): in screen space,
//! reaching far beyond the set-up window (the clipper), lifted into a
//! perspective clip space with a different `w` per vertex, and in bands.

use fixshade_testkit::seeded;
use fixshade_testkit::support;

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::render::Corner;
use fixshade_testkit::support::{banded, counts, full, lumas, Count, Tris, S};
use proptest::prelude::*;

const W: u32 = 64;
const H: u32 = 48;

type Tri = [Corner; 3];

fn v(x: i32, y: i32) -> Corner {
    support::corner(x, y, 0, 0)
}

/// A grid of `nx × ny` quads of `cell` sub-pixels starting at `origin`,
/// interior vertices moved by `jitter`, each quad split along a chosen
/// diagonal, each triangle in a chosen winding.
fn grid(
    origin: (i32, i32),
    cell: i32,
    nx: usize,
    ny: usize,
    jitter: &[(i32, i32)],
    split: &[bool],
    flip: &[bool],
) -> Vec<Tri> {
    let at = |i: usize, j: usize| {
        let interior = i > 0 && j > 0 && i < nx && j < ny;
        let (jx, jy) = if interior {
            jitter[(j * (nx + 1) + i) % jitter.len()]
        } else {
            (0, 0)
        };
        v(
            origin.0 + i as i32 * cell + jx,
            origin.1 + j as i32 * cell + jy,
        )
    };
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            let k = j * nx + i;
            let pair = if split[k % split.len()] {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            for (n, mut t) in pair.into_iter().enumerate() {
                if flip[(2 * k + n) % flip.len()] {
                    t.swap(1, 2);
                }
                tris.push(t);
            }
        }
    }
    tris
}

/// 1 for pixels whose centre is inside the half-open rectangle [x0, x1) × [y0, y1) (sub-pixels).
fn rect_coverage(x0: i32, y0: i32, x1: i32, y1: i32) -> Vec<u8> {
    let mut out = vec![0; (W * H) as usize];
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let (cx, cy) = (x * S + S / 2, y * S + S / 2);
            out[(y * W as i32 + x) as usize] = u8::from(cx >= x0 && cx < x1 && cy >= y0 && cy < y1);
        }
    }
    out
}

proptest! {
    #![proptest_config(seeded::config("raster_watertight", 200))]

    #[test]
    fn jittered_grid_covers_its_rectangle_once(
        ox in -40i32..40, oy in -40i32..40,
        cell in 24i32..200,
        jitter in prop::collection::vec((-1000i32..1000, -1000i32..1000), 1..64),
        split in prop::collection::vec(any::<bool>(), 1..16),
        flip in prop::collection::vec(any::<bool>(), 1..16),
    ) {
        let (nx, ny) = (6, 5);
        // Jitter below a quarter of a cell keeps every quad convex.
        let lim = cell / 4 - 1;
        let jitter: Vec<_> = jitter.iter().map(|&(x, y)| (x % lim.max(1), y % lim.max(1))).collect();
        let origin = (ox * 3, oy * 3);
        let tris = grid(origin, cell, nx, ny, &jitter, &split, &flip);
        let got = counts(W, H, &tris);
        let want = rect_coverage(origin.0, origin.1, origin.0 + nx as i32 * cell, origin.1 + ny as i32 * cell);
        prop_assert_eq!(got, want);
    }

    #[test]
    fn fan_and_strip_of_a_convex_polygon_agree(
        cx in 200i32..800, cy in 200i32..560,
        n in 3usize..24,
        radii in prop::collection::vec(150i32..400, 24),
        phase in 0.0f64..1.0,
        flip in prop::collection::vec(any::<bool>(), 1..8),
    ) {
        // A convex polygon (points on an ellipse-ish curve, equal radius) and a centre vertex.
        let r = radii[0];
        let pts: Vec<_> = (0..n)
            .map(|k| {
                let a = (k as f64 + phase) * core::f64::consts::TAU / n as f64;
                v(cx + (f64::from(r) * a.cos()) as i32, cy + (f64::from(r) * 0.8 * a.sin()) as i32)
            })
            .collect();
        let centre = v(cx + radii[1] % 30, cy + radii[2] % 30);
        let mut fan: Vec<Tri> = (0..n).map(|k| [centre, pts[k], pts[(k + 1) % n]]).collect();
        for (k, t) in fan.iter_mut().enumerate() {
            if flip[k % flip.len()] {
                t.swap(0, 1);
            }
        }
        let other: Vec<Tri> = (1..n - 1).map(|k| [pts[0], pts[k], pts[k + 1]]).collect();
        let a = counts(W, H, &fan);
        let b = counts(W, H, &other);
        prop_assert!(a.iter().all(|&c| c <= 1), "double write in fan");
        prop_assert!(b.iter().all(|&c| c <= 1), "double write in polygon fan");
        prop_assert_eq!(a, b);
    }

    #[test]
    fn bands_match_full_frame(
        band_rows in 1u32..20,
        jitter in prop::collection::vec((-5i32..5, -5i32..5), 1..16),
        split in prop::collection::vec(any::<bool>(), 1..8),
    ) {
        let tris = grid((37, 21), 150, 6, 5, &jitter, &split, &[false]);
        let want = counts(W, H, &tris);
        let mut item = Tris::screen(Count, tris);
        let got = lumas(&banded(W, H, band_rows, Gray8::new(0), false, &mut [&mut item]));
        prop_assert_eq!(got, want);
    }

    #[test]
    fn grid_beyond_the_window_covers_the_frame_once(
        ox in -40_000i32..0, oy in -40_000i32..0,
        cell in 2_000i32..40_000,
        jitter in prop::collection::vec((-100_000i32..100_000, -100_000i32..100_000), 1..64),
        split in prop::collection::vec(any::<bool>(), 1..16),
        flip in prop::collection::vec(any::<bool>(), 1..16),
    ) {
        // cells of up to 2 500 pixels from up to 2 500 pixels left of and
        // above the frame: most triangles reach beyond the set-up window
        // (−512..1536 pixels) and are clipped in clip space
        let (nx, ny) = (6, 5);
        let lim = cell / 4 - 1;
        let jitter: Vec<_> = jitter.iter().map(|&(x, y)| (x % lim, y % lim)).collect();
        let tris = grid((ox, oy), cell, nx, ny, &jitter, &split, &flip);
        let got = counts(W, H, &tris);
        let want = rect_coverage(ox, oy, ox + nx as i32 * cell, oy + ny as i32 * cell);
        prop_assert_eq!(got, want);
    }

    #[test]
    fn grid_in_a_perspective_clip_space_covers_its_rectangle_once(
        ox in -40i32..40, oy in -40i32..40,
        cell in 24i32..200,
        jitter in prop::collection::vec((-1000i32..1000, -1000i32..1000), 1..64),
        w in prop::collection::vec(1i32..3000, 1..64),
        split in prop::collection::vec(any::<bool>(), 1..16),
        flip in prop::collection::vec(any::<bool>(), 1..16),
        band_rows in 1u32..13,
    ) {
        // the jittered grid, each vertex lifted to clip space with its own w
        // (x = (screen − centre)·w: the same screen positions, exactly)
        let (nx, ny) = (6, 5);
        let lim = cell / 4 - 1;
        let jitter: Vec<_> = jitter.iter().map(|&(x, y)| (x % lim.max(1), y % lim.max(1))).collect();
        let origin = (ox * 3, oy * 3);
        let centre = [(W as i32 / 2) * S, (H as i32 / 2) * S];
        let tris: Vec<Tri> = grid(origin, cell, nx, ny, &jitter, &split, &flip)
            .into_iter()
            .map(|t| {
                t.map(|c| {
                    // the same w for the same vertex in every triangle
                    let key = (c.clip.x * 7919 + c.clip.y).unsigned_abs() as usize;
                    let wv = w[key % w.len()];
                    Corner {
                        clip: Clip {
                            x: (c.clip.x - centre[0]) * wv,
                            y: (c.clip.y - centre[1]) * wv,
                            z: 0,
                            w: wv,
                        },
                        ..c
                    }
                })
            })
            .collect();
        let want = rect_coverage(origin.0, origin.1, origin.0 + nx as i32 * cell, origin.1 + ny as i32 * cell);
        let mut item = Tris { space: ClipSpace::perspective(centre, 1), ..Tris::screen(Count, tris) };
        let got = lumas(&full(W, H, Gray8::new(0), false, &mut [&mut item]));
        prop_assert_eq!(&got, &want);
        let got = lumas(&banded(W, H, band_rows, Gray8::new(0), false, &mut [&mut item]));
        prop_assert_eq!(got, want);
    }
}
