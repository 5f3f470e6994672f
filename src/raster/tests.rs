//! Unit tests: fill rule, coverage, attribute exactness.

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};

use super::*;
use crate::target::SliceFramebuffer;

const S: i32 = 1 << SUBPIXEL_BITS;

/// Adds 1 to every pixel it shades.
struct Count;
impl<const N: usize> SpanShader<N> for Count {
    type Color = Gray8;
    fn shade_span(&mut self, _x: i32, _y: i32, _s: &[i32; N], _d: &[i32; N], out: &mut [Gray8]) {
        for p in out.iter_mut() {
            *p = Gray8::new(p.luma() + 1);
        }
    }
}

/// Records attribute 0 of every pixel (start + k·step) into a 16×16 grid.
struct Record([[Option<i64>; 16]; 16]);
impl SpanShader<1> for Record {
    type Color = Gray8;
    fn shade_span(&mut self, x: i32, y: i32, s: &[i32; 1], d: &[i32; 1], out: &mut [Gray8]) {
        for (k, p) in out.iter_mut().enumerate() {
            let v = i64::from(s[0]) + k as i64 * i64::from(d[0]);
            self.0[y as usize][x as usize + k] = Some(v);
            *p = Gray8::new(1);
        }
    }
}

fn vtx(x: i32, y: i32) -> RasterVertex<0> {
    RasterVertex {
        x,
        y,
        z: 0,
        inv_w: 1,
        attrs: [],
    }
}

fn coverage(tris: &[[RasterVertex<0>; 3]], opts: &RasterOptions) -> [[u8; 16]; 16] {
    let mut px = [Gray8::new(0); 256];
    let mut fb = SliceFramebuffer::new(&mut px, 16, 16).unwrap();
    for t in tris {
        draw_triangle(&mut fb, None, t, opts, &mut Count).unwrap();
    }
    let mut out = [[0u8; 16]; 16];
    for (i, p) in px.iter().enumerate() {
        out[i / 16][i % 16] = p.luma();
    }
    out
}

#[test]
fn shared_diagonal_covers_square_once() {
    let (a, b, c, d) = (vtx(S, S), vtx(9 * S, S), vtx(9 * S, 9 * S), vtx(S, 9 * S));
    let cov = coverage(&[[a, b, c], [a, c, d]], &RasterOptions::default());
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
        vtx(2 * S + h, 3 * S + h),
        vtx(6 * S + h, 3 * S + h),
        vtx(6 * S + h, 7 * S + h),
        vtx(2 * S + h, 7 * S + h),
    );
    for tris in [[[a, b, c], [a, c, d]], [[a, b, d], [b, c, d]]] {
        let cov = coverage(&tris, &RasterOptions::default());
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
    let cov = coverage(
        &[[vtx(cx - 2, cy - 2), vtx(cx + 3, cy - 1), vtx(cx, cy + 3)]],
        &RasterOptions::default(),
    );
    let total: u32 = cov.iter().flatten().map(|&n| u32::from(n)).sum();
    assert_eq!(total, 1);
    assert_eq!(cov[7][5], 1);
    // A triangle between centres covers nothing.
    let cov = coverage(
        &[[
            vtx(5 * S + 9, 5 * S + 9),
            vtx(5 * S + 15, 5 * S + 9),
            vtx(5 * S + 9, 5 * S + 15),
        ]],
        &RasterOptions::default(),
    );
    assert!(cov.iter().flatten().all(|&n| n == 0));
}

#[test]
fn winding_and_culling() {
    // (0,0) → (0,10) → (10,0) runs counter-clockwise on screen: front-facing.
    let ccw = [vtx(0, 0), vtx(0, 10 * S), vtx(10 * S, 0)];
    let cw = [ccw[0], ccw[2], ccw[1]];
    let opts = |cull| RasterOptions {
        cull,
        ..RasterOptions::default()
    };
    let count = |t: &[RasterVertex<0>; 3], o: &RasterOptions| {
        coverage(&[*t], o)
            .iter()
            .flatten()
            .map(|&n| u32::from(n))
            .sum::<u32>()
    };
    // Centres with x + y <= 8; those with x + y = 9 lie on the right edge: excluded.
    assert_eq!(count(&ccw, &opts(Cull::None)), 45);
    assert_eq!(count(&cw, &opts(Cull::None)), 45);
    assert_eq!(count(&ccw, &opts(Cull::Back)), 45);
    assert_eq!(count(&cw, &opts(Cull::Back)), 0);
    assert_eq!(count(&ccw, &opts(Cull::Front)), 0);
    assert_eq!(count(&cw, &opts(Cull::Front)), 45);
}

#[test]
fn degenerate_triangles_draw_nothing() {
    let line = [vtx(0, 0), vtx(5 * S, 5 * S), vtx(10 * S, 10 * S)];
    let point = [vtx(3 * S, 3 * S); 3];
    let cov = coverage(&[line, point], &RasterOptions::default());
    assert!(cov.iter().flatten().all(|&n| n == 0));
}

/// Exact plane value of attribute `a` at `(px, py)` (sub-pixel units), as f64.
fn plane_value(v: &[RasterVertex<1>; 3], px: f64, py: f64) -> f64 {
    let f = |i: usize| {
        (
            f64::from(v[i].x),
            f64::from(v[i].y),
            f64::from(v[i].attrs[0]),
        )
    };
    let ((x0, y0, a0), (x1, y1, a1), (x2, y2, a2)) = (f(0), f(1), f(2));
    let det = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
    let b1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) / det;
    let b2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) / det;
    a0 + b1 * (a1 - a0) + b2 * (a2 - a0)
}

#[test]
fn attributes_exact_at_vertices_and_on_the_plane() {
    let c = |p: i32| p * S + S / 2;
    for attrs in [
        [0, 1 << 16, -(1 << 16)],
        [-ATTR_LIMIT, ATTR_LIMIT, 12345],
        [1000, 1000, 1000],
        [7, -3, 100_000_000],
    ] {
        let v = [
            RasterVertex {
                x: c(1),
                y: c(1),
                z: 0,
                inv_w: 1,
                attrs: [attrs[0]],
            },
            RasterVertex {
                x: c(14),
                y: c(3),
                z: 0,
                inv_w: 1,
                attrs: [attrs[1]],
            },
            RasterVertex {
                x: c(4),
                y: c(14),
                z: 0,
                inv_w: 1,
                attrs: [attrs[2]],
            },
        ];
        for perspective in [false, true] {
            let mut px = [Gray8::new(0); 256];
            let mut fb = SliceFramebuffer::new(&mut px, 16, 16).unwrap();
            let mut rec = Record([[None; 16]; 16]);
            let opts = RasterOptions::default();
            if perspective {
                draw_triangle_perspective(&mut fb, None, &v, &opts, &mut rec).unwrap();
            } else {
                draw_triangle(&mut fb, None, &v, &opts, &mut rec).unwrap();
            }
            let range =
                f64::from(*attrs.iter().max().unwrap()) - f64::from(*attrs.iter().min().unwrap());
            for (y, row) in rec.0.iter().enumerate() {
                for (x, got) in row.iter().enumerate() {
                    let Some(got) = *got else { continue };
                    let exact = plane_value(&v, f64::from(c(x as i32)), f64::from(c(y as i32)));
                    // ½ + k·½ units from step rounding (k ≤ 15), plus the gradient
                    // rounding; the perspective path is exact to ±1 with equal 1/w.
                    let tol = 1.0 + 8.0 + range * 1e-9;
                    assert!(
                        (got as f64 - exact).abs() <= tol,
                        "({x},{y}) got {got} exact {exact} attrs {attrs:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn attribute_exact_at_a_drawn_vertex_whatever_its_index() {
    let c = |p: i32| p * S + S / 2;
    let vert = |x, y, a| RasterVertex {
        x: c(x),
        y: c(y),
        z: 0,
        inv_w: 1,
        attrs: [a],
    };
    // Only the top-left vertex P lies on a top and a left edge: its pixel is drawn.
    let (p, q, r) = (
        vert(1, 1, -123_456_789),
        vert(14, 1, ATTR_LIMIT),
        vert(1, 14, -ATTR_LIMIT),
    );
    for tri in [[p, q, r], [q, r, p], [r, p, q]] {
        for perspective in [false, true] {
            let mut px = [Gray8::new(0); 256];
            let mut fb = SliceFramebuffer::new(&mut px, 16, 16).unwrap();
            let mut rec = Record([[None; 16]; 16]);
            let opts = RasterOptions::default();
            if perspective {
                draw_triangle_perspective(&mut fb, None, &tri, &opts, &mut rec).unwrap();
            } else {
                draw_triangle(&mut fb, None, &tri, &opts, &mut rec).unwrap();
            }
            assert_eq!(rec.0[1][1], Some(-123_456_789), "perspective {perspective}");
        }
    }
}

#[test]
fn huge_and_offscreen_triangles_do_not_panic() {
    let big = [vtx(i32::MIN, i32::MIN), vtx(i32::MAX, 0), vtx(0, i32::MAX)];
    let cov = coverage(&[big], &RasterOptions::default());
    // The clipped triangle covers the whole 16×16 frame exactly once.
    assert!(cov.iter().flatten().all(|&n| n == 1));
    let off = [
        vtx(-100 * S, -100 * S),
        vtx(-50 * S, -100 * S),
        vtx(-50 * S, -20 * S),
    ];
    let cov = coverage(&[off], &RasterOptions::default());
    assert!(cov.iter().flatten().all(|&n| n == 0));
}
