//! Fill rule, coverage, winding and culling, degenerate and huge triangles,
//! and the precision of interpolated values, through the per-triangle front
//! of the pipeline (`render::draw_triangle`) with kernels of the test's own
//! (ported from the unit tests of the removed per-triangle rasterizer).

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::num::ATTR_FRAC;
use fixshade::raster::interp::VARYING_LIMIT;
use fixshade::raster::Cull;
use fixshade::render::Corner;
use fixshade_testkit::support::{
    clip_corner, corner, counts, exact_plane, full, lumas, plane_bound, Count, Record,
};
use fixshade_testkit::support::{Tris, PERSPECTIVE_SPAN, S};

const N: u32 = 16;

/// A screen-space corner at sub-pixel `(x, y)`.
fn v(x: i32, y: i32) -> Corner {
    corner(x, y, 0, 0)
}

/// Write counts of a 16 × 16 frame as rows.
fn coverage(tris: &[[Corner; 3]]) -> Vec<Vec<u8>> {
    counts(N, N, tris)
        .chunks(N as usize)
        .map(|r| r.to_vec())
        .collect()
}

/// Pixels written by one triangle drawn with `cull`.
fn count_culled(t: [Corner; 3], cull: Cull) -> u32 {
    let mut item = Tris {
        cull,
        ..Tris::screen(Count, vec![t])
    };
    let px = full(N, N, Gray8::new(0), false, &mut [&mut item]);
    lumas(&px).iter().map(|&n| u32::from(n)).sum()
}

#[test]
fn shared_diagonal_covers_square_once() {
    let (a, b, c, d) = (v(S, S), v(9 * S, S), v(9 * S, 9 * S), v(S, 9 * S));
    let cov = coverage(&[[a, b, c], [a, c, d]]);
    for (y, row) in cov.iter().enumerate() {
        for (x, &n) in row.iter().enumerate() {
            let inside = (1..9).contains(&x) && (1..9).contains(&y);
            assert_eq!(n, u8::from(inside), "pixel ({x}, {y})");
        }
    }
}

#[test]
fn edges_through_pixel_centres_follow_top_left_rule() {
    // Square with all four edges through pixel centres: x = 2.5 .. 6.5, y = 3.5 .. 7.5.
    let h = S / 2;
    let (a, b, c, d) = (
        v(2 * S + h, 3 * S + h),
        v(6 * S + h, 3 * S + h),
        v(6 * S + h, 7 * S + h),
        v(2 * S + h, 7 * S + h),
    );
    for tris in [[[a, b, c], [a, c, d]], [[a, b, d], [b, c, d]]] {
        let cov = coverage(&tris);
        for (y, row) in cov.iter().enumerate() {
            for (x, &n) in row.iter().enumerate() {
                // Top edge (row 3) and left edge (column 2) included; bottom and right excluded.
                let inside = (2..6).contains(&x) && (3..7).contains(&y);
                assert_eq!(n, u8::from(inside), "pixel ({x}, {y})");
            }
        }
    }
}

#[test]
fn tiny_triangle_around_a_centre_covers_one_pixel() {
    let (cx, cy) = (5 * S + S / 2, 7 * S + S / 2);
    let cov = coverage(&[[v(cx - 2, cy - 2), v(cx + 3, cy - 1), v(cx, cy + 3)]]);
    let total: u32 = cov.iter().flatten().map(|&n| u32::from(n)).sum();
    assert_eq!(total, 1);
    assert_eq!(cov[7][5], 1);
    // A triangle between centres covers nothing.
    let cov = coverage(&[[
        v(5 * S + 9, 5 * S + 9),
        v(5 * S + 15, 5 * S + 9),
        v(5 * S + 9, 5 * S + 15),
    ]]);
    assert!(cov.iter().flatten().all(|&n| n == 0));
}

#[test]
fn winding_and_culling() {
    // (0,0) → (0,10) → (10,0) runs counter-clockwise on screen: front-facing.
    let ccw = [v(0, 0), v(0, 10 * S), v(10 * S, 0)];
    let cw = [ccw[0], ccw[2], ccw[1]];
    // Centres with x + y <= 8; those with x + y = 9 lie on the right edge: excluded.
    assert_eq!(count_culled(ccw, Cull::None), 45);
    assert_eq!(count_culled(cw, Cull::None), 45);
    assert_eq!(count_culled(ccw, Cull::Back), 45);
    assert_eq!(count_culled(cw, Cull::Back), 0);
    assert_eq!(count_culled(ccw, Cull::Front), 0);
    assert_eq!(count_culled(cw, Cull::Front), 45);
}

#[test]
fn degenerate_triangles_draw_nothing() {
    let line = [v(0, 0), v(5 * S, 5 * S), v(10 * S, 10 * S)];
    let point = [v(3 * S, 3 * S); 3];
    let cov = coverage(&[line, point]);
    assert!(cov.iter().flatten().all(|&n| n == 0));
}

/// The centre of pixel `p` in sub-pixels.
fn c(p: i32) -> i32 {
    p * S + S / 2
}

/// Draws the screen-space triangle `xy` with values `a` through the
/// recording kernel; returns every pixel's value.
fn record(xy: [(i32, i32); 3], a: [i32; 3]) -> Vec<(i32, i32, i64)> {
    let rec = Record::default();
    let tri = [0, 1, 2].map(|i| corner(xy[i].0, xy[i].1, 0, a[i]));
    let mut item = Tris::screen(&rec, vec![tri]);
    full(N, N, Gray8::new(0), false, &mut [&mut item]);
    rec.pixels()
}

#[test]
fn attributes_within_the_plane_error_bound() {
    // Orthographic (screen-linear) values come from 32-bit planes with 14-bit
    // barycentric coefficients: no longer exact per run, but within the
    // planes' error bound (`support::plane_bound`, `Setup::err` restated),
    // at every pixel and in particular at the vertices' pixel centres.
    let xy = [(c(1), c(1)), (c(14), c(3)), (c(4), c(14))];
    let lim = VARYING_LIMIT;
    for a in [
        [0, 1 << 14, -(1 << 14)],
        [-lim, lim, 12345],
        [1000, 1000, 1000],
        [7, -3, lim],
        [lim, -lim, lim],
    ] {
        let bound = plane_bound(xy, a);
        let px = record(xy, a);
        assert!(px.len() > 60, "{a:?}: {} pixels", px.len());
        let mut worst = 0.0f64;
        for &(x, y, got) in &px {
            let exact = exact_plane(xy, a, x, y);
            let err = (got as f64 - exact).abs();
            worst = worst.max(err);
            assert!(
                err <= bound,
                "({x},{y}) got {got} exact {exact:.1} (error {err:.1} > bound {bound:.1}) values {a:?}"
            );
        }
        // at the vertices' pixel centres, where drawn (the fill rule decides),
        // the vertex's value up to the bound
        for (i, &(vx, vy)) in xy.iter().enumerate() {
            if let Some(p) = px.iter().find(|p| (c(p.0), c(p.1)) == (vx, vy)) {
                let want = f64::from(a[i]) * f64::from(1u32 << ATTR_FRAC);
                assert!(
                    (p.2 as f64 - want).abs() <= bound,
                    "{a:?}: vertex {i}: {p:?}"
                );
            }
        }
        println!(
            "values {a:?}: worst error {worst:.1} of bound {bound:.1} (units of 2^-{ATTR_FRAC})"
        );
    }
}

#[test]
fn attribute_at_a_drawn_vertex_whatever_its_index() {
    // Only the top-left vertex P lies on a top and a left edge: its pixel is
    // drawn, and gets P's value within the plane bound whichever corner P is.
    let lim = VARYING_LIMIT;
    let (p, q, r) = (
        (c(1), c(1), -20_000),
        (c(14), c(1), lim),
        (c(1), c(14), -lim),
    );
    for tri in [[p, q, r], [q, r, p], [r, p, q]] {
        let xy = tri.map(|t| (t.0, t.1));
        let a = tri.map(|t| t.2);
        let bound = plane_bound(xy, a);
        let px = record(xy, a);
        let got = px
            .iter()
            .find(|p| (p.0, p.1) == (1, 1))
            .expect("P's pixel")
            .2;
        let want = -20_000.0 * f64::from(1u32 << ATTR_FRAC);
        assert!(
            (got as f64 - want).abs() <= bound,
            "{tri:?}: {got} vs {want} (bound {bound:.1})"
        );
    }
}

#[test]
fn perspective_path_with_equal_w_matches_the_screen_plane() {
    // The perspective-correct path with the same w at every corner (and
    // positions that project exactly): the exact value is the screen
    // plane's. The pipeline evaluates it at the start of every sub-span of
    // PERSPECTIVE_SPAN pixels (the runs a kernel is handed) as
    // a0 + w1·(a1 − a0) + w2·(a2 − a0), the weights wj in Q14 from the
    // barycentric planes: each wj is off by at most the β plane's error
    // (`plane_bound` of the plane 0..2^14, in units of 2^-28: `beta` Q14
    // units), + 1 for the truncation to Q14, + ½ for the reciprocal of the
    // weights' sum (relative error 2^-15 of a weight ≤ 2^14), + 1 for the
    // truncation of the weight, + ½ for the normalising shifts: so a start
    // value is off by at most (beta + 3)·spread units of 2^-14, spread =
    // |a1 − a0| + |a2 − a0|.
    let space = ClipSpace::perspective([0, 0], 1);
    let w = 1000;
    let xy = [(c(1), c(1)), (c(14), c(3)), (c(4), c(14))];
    let lim = VARYING_LIMIT;
    for a in [[0, 1 << 14, -(1 << 14)], [-lim, lim, 12345], [7, -3, lim]] {
        let rec = Record::default();
        let tri = [0, 1, 2].map(|i| {
            let clip = Clip {
                x: xy[i].0 * w,
                y: xy[i].1 * w,
                z: 0,
                w,
            };
            clip_corner(clip, a[i])
        });
        let mut item = Tris {
            space,
            ..Tris::screen(&rec, vec![tri])
        };
        full(N, N, Gray8::new(0), false, &mut [&mut item]);
        let beta = plane_bound(xy, [0, 1 << 14, 0]) / f64::from(1u32 << ATTR_FRAC);
        let spread = [1, 2]
            .iter()
            .map(|&i| (f64::from(a[i]) - f64::from(a[0])).abs())
            .sum::<f64>();
        let bound = (beta + 3.0) * spread;
        let runs = rec.runs.borrow();
        assert!(runs.len() > 14, "{} runs", runs.len());
        for r in runs.iter() {
            assert!(r.len <= PERSPECTIVE_SPAN, "{r:?}");
            let exact = exact_plane(xy, a, r.x, r.y);
            let err = (f64::from(r.start) - exact).abs();
            assert!(
                err <= bound,
                "{a:?} {r:?}: exact {exact:.1}, error {err:.1} > {bound:.1}"
            );
        }
    }
}

#[test]
fn huge_and_offscreen_triangles_do_not_panic() {
    let big = [v(i32::MIN, i32::MIN), v(i32::MAX, 0), v(0, i32::MAX)];
    let cov = coverage(&[big]);
    // The clipped triangle covers the whole 16×16 frame exactly once.
    assert!(cov.iter().flatten().all(|&n| n == 1), "{cov:?}");
    let off = [
        v(-100 * S, -100 * S),
        v(-50 * S, -100 * S),
        v(-50 * S, -20 * S),
    ];
    let cov = coverage(&[off]);
    assert!(cov.iter().flatten().all(|&n| n == 0));
}

/// The per-triangle front draws a triangle whatever its first row (on
/// `one-renderer` 3c38dd9…3b82c69 it passed `height = u32::MAX` to the
/// classification, which read it as −1 and dropped every triangle starting
/// at row −1 or below: nothing was drawn; its own doc example failed).
#[test]
fn a_triangle_below_the_top_row_is_drawn() {
    let t = [v(2 * S, 20 * S), v(2 * S, 30 * S), v(12 * S, 20 * S)];
    let px = counts(32, 32, &[t]);
    assert_eq!(px.iter().filter(|&&n| n == 1).count(), 45);
}
