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

/// A jittered sheet of `6 × 5` quads in eye space crossing the near plane:
/// corners `centre + f·(x, y)/d` on the screen (`d` the depth), `w = d·K`,
/// each quad split along a random diagonal, each triangle in a random
/// winding; `None` when a coordinate leaves `i32`.
fn near_sheet(rng: &mut fixshade_testkit::worst_case::Rng) -> Option<Vec<Tri>> {
    const K: f64 = 1000.0;
    const F: f64 = 40.0 * S as f64;
    let (nx, ny) = (6usize, 5usize);
    // the sheet: origin, two spanning vectors; depth d = −z
    let o = [
        rng.range(-1.5, 1.5),
        rng.range(-1.5, 1.5),
        rng.range(-2.0, 0.5),
    ];
    let a = [
        rng.range(-1.0, 1.0),
        rng.range(-0.3, 0.3),
        rng.range(-1.0, 1.0),
    ]
    .map(|c| c / nx as f64 * 3.0);
    let b = [
        rng.range(-0.3, 0.3),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    ]
    .map(|c| c / ny as f64 * 3.0);
    // the whole sheet scaled about the eye: from far beyond the near plane to
    // mostly behind it
    let g = 10f64.powf(rng.range(-1.5, 1.0));
    let (mut o, mut a, mut b) = (o.map(|c| c * g), a.map(|c| c * g), b.map(|c| c * g));
    // half of them nearly parallel to the near plane, through it: edges cut
    // at grazing angles
    if rng.f() < 0.5 {
        let t = 10f64.powf(rng.range(-3.0, -1.0));
        (a[2], b[2]) = (a[2] * t, b[2] * t);
        o[2] = -0.1 - (a[2] * 3.0 + b[2] * 2.5)
            + rng.range(-1.0, 1.0) * (a[2].abs() * 3.0 + b[2].abs() * 2.5);
    }
    // seen at least 15° off edge-on from every corner: a sheet seen edge-on
    // folds over itself when its corners are rounded to sub-pixels (slivers
    // turn round), which no rasterizer can draw once
    let ab = fixshade_testkit::worst_case::cross(a, b);
    let len = |v: [f64; 3]| fixshade_testkit::worst_case::dot(v, v).sqrt();
    // and cells that are not slivers: spanning vectors at least 30° apart
    if len(ab) < 0.5 * len(a) * len(b) {
        return None;
    }
    let nrm = fixshade_testkit::worst_case::norm(ab);
    let mut pts = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (u, v) = (
                i as f64 + rng.range(-0.2, 0.2),
                j as f64 + rng.range(-0.2, 0.2),
            );
            let p: [f64; 3] = core::array::from_fn(|k| o[k] + u * a[k] + v * b[k]);
            let ray = fixshade_testkit::worst_case::norm(p);
            if fixshade_testkit::worst_case::dot(ray, nrm).abs() < 0.26 {
                return None;
            }
            let d = -p[2];
            let c = [F * p[0] * K, -F * p[1] * K, 0.0, d * K];
            if c.iter().any(|x| x.abs() > 2.0e9) {
                return None;
            }
            let clip = Clip {
                x: c[0] as i32,
                y: c[1] as i32,
                z: 0,
                w: c[3] as i32,
            };
            pts.push(fixshade_testkit::support::clip_corner(clip, 0));
        }
    }
    let at = |i: usize, j: usize| pts[j * (nx + 1) + i];
    // and every cell in front of the near plane at least 2 pixels wide on the
    // screen: sub-pixel cells fold when rounded too
    let screen = |c: Clip| {
        (
            f64::from(c.x) / f64::from(c.w),
            f64::from(c.y) / f64::from(c.w),
        )
    };
    for j in 0..=ny {
        for i in 0..=nx {
            for (di, dj) in [(1, 0), (0, 1), (1, 1)] {
                if i + di > nx || j + dj > ny {
                    continue;
                }
                let (p, q) = (at(i, j).clip, at(i + di, j + dj).clip);
                if p.w > 100 && q.w > 100 {
                    let (a, b) = (screen(p), screen(q));
                    if (a.0 - b.0).hypot(a.1 - b.1) < 2.0 * S as f64 {
                        return None;
                    }
                }
            }
        }
    }
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (p, q, r, s) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            let pair = if rng.f() < 0.5 {
                [[p, q, r], [p, r, s]]
            } else {
                [[p, q, s], [q, r, s]]
            };
            for mut t in pair {
                if rng.f() < 0.5 {
                    t.swap(1, 2);
                }
                tris.push(t);
            }
        }
    }
    Some(tris)
}

/// Issue 35, item 5: sheets crossing the near plane (each triangle clipped
/// on its own, the cut of a shared edge bit-identical from both sides) draw
/// every pixel at most once, with no culling: the convex pieces of a clipped
/// triangle whose rounded corners bend keep its outline, so no sliver along a
/// shared edge is drawn twice.
#[test]
fn sheets_through_the_near_plane_draw_every_pixel_at_most_once() {
    let mut rng = fixshade_testkit::worst_case::Rng::new(35);
    let centre = [(W as i32 / 2) * S, (H as i32 / 2) * S];
    let space = ClipSpace::perspective(centre, 100);
    let (mut sheets, mut bad, mut first) = (0, 0, None);
    while sheets < 20_000 {
        let Some(tris) = near_sheet(&mut rng) else {
            continue;
        };
        sheets += 1;
        let mut item = Tris {
            space,
            ..Tris::screen(Count, tris)
        };
        let got = lumas(&full(W, H, Gray8::new(0), false, &mut [&mut item]));
        if let Some(i) = got.iter().position(|&c| c > 1) {
            bad += 1;
            first.get_or_insert((sheets, i as u32 % W, i as u32 / W));
        }
    }
    assert_eq!(
        bad, 0,
        "{bad} of {sheets} sheets draw a pixel twice; the first: sheet, x, y = {first:?}"
    );
}

/// Issue 35, item 5: pairs of triangles sharing an edge, each with a corner
/// behind the near plane and one in front, in the same facing (a sheet, not
/// folded), fat and not seen edge-on, draw every pixel at most once: the
/// pieces of a clipped triangle keep its rounded outline (ear clipping), where
/// the convex fan drawn before overlapped its neighbour by a sliver on 3 of
/// these million pairs (the first the 738 658th).
#[test]
fn pairs_across_the_near_plane_draw_every_pixel_at_most_once() {
    use fixshade_testkit::worst_case::{cross, dot, norm};
    let mut rng = fixshade_testkit::worst_case::Rng::new(7);
    let centre = [(W as i32 / 2) * S, (H as i32 / 2) * S];
    let near = 1000;
    let space = ClipSpace::perspective(centre, near);
    const K: f64 = 10000.0;
    const F: f64 = 40.0 * S as f64;
    let (mut n, mut bad, mut first) = (0u32, 0u32, None);
    while n < 1_000_000 {
        let g = 10f64.powf(rng.range(-1.0, 1.0));
        let pt = |rng: &mut fixshade_testkit::worst_case::Rng| {
            [
                rng.range(-1.0, 1.0) * g,
                rng.range(-1.0, 1.0) * g,
                -0.1 + rng.range(-1.0, 1.0) * g,
            ]
        };
        let (p, q, r, s) = (pt(&mut rng), pt(&mut rng), pt(&mut rng), pt(&mut rng));
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let n1 = cross(sub(q, p), sub(r, p));
        let n2 = cross(sub(p, q), sub(s, q));
        let len = |v: [f64; 3]| dot(v, v).sqrt();
        // both triangles fat, on opposite sides of p–q (a sheet, not folded): normals agree
        if len(n1) < 0.3 * len(sub(q, p)) * len(sub(r, p))
            || len(n2) < 0.3 * len(sub(p, q)) * len(sub(s, q))
        {
            continue;
        }
        if dot(norm(n1), norm(n2)) < 0.5 {
            continue;
        }
        // not seen edge-on from any corner
        if [p, q, r, s]
            .iter()
            .any(|v| dot(norm(*v), norm(n1)).abs() < 0.26 || dot(norm(*v), norm(n2)).abs() < 0.26)
        {
            continue;
        }
        let clip = |v: [f64; 3]| {
            let c = [F * v[0] * K, -F * v[1] * K, -v[2] * K];
            (c.iter().all(|x| x.abs() < 2.0e9)).then(|| Clip {
                x: c[0] as i32,
                y: c[1] as i32,
                z: 0,
                w: c[2] as i32,
            })
        };
        let (Some(cp), Some(cq), Some(cr), Some(cs)) = (clip(p), clip(q), clip(r), clip(s)) else {
            continue;
        };
        // at least one corner behind the near plane and one in front
        let ws = [cp.w, cq.w, cr.w, cs.w];
        if !(ws.iter().any(|&w| w < near) && ws.iter().any(|&w| w > near)) {
            continue;
        }
        let det = |a: Clip, b: Clip, c: Clip| {
            let m = |a: i32, b: i32| i128::from(a) * i128::from(b);
            i128::from(a.x) * (m(b.y, c.w) - m(c.y, b.w))
                - i128::from(a.y) * (m(b.x, c.w) - m(c.x, b.w))
                + i128::from(a.w) * (m(b.x, c.y) - m(c.x, b.y))
        };
        if det(cp, cq, cr).signum() != det(cq, cp, cs).signum() {
            continue;
        }
        n += 1;
        let c = |k: Clip| fixshade_testkit::support::clip_corner(k, 0);
        let tris = vec![[c(cp), c(cq), c(cr)], [c(cq), c(cp), c(cs)]];
        let mut item = Tris {
            space,
            ..Tris::screen(Count, tris.clone())
        };
        let got = lumas(&full(W, H, Gray8::new(0), false, &mut [&mut item]));
        if let Some(i) = got.iter().position(|&c| c > 1) {
            bad += 1;
            first.get_or_insert((
                n,
                i as u32 % W,
                i as u32 / W,
                tris.iter().map(|t| t.map(|c| c.clip)).collect::<Vec<_>>(),
            ));
        }
    }
    assert_eq!(
        bad, 0,
        "{bad} of {n} pairs draw a pixel twice; the first (pair, x, y, triangles): {first:?}"
    );
}
