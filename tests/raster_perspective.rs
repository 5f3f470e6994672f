//! Perspective-correct interpolation against the exact value of an attribute
//! that is linear in 3D, on a tilted quad.

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::raster::{
    draw_triangle, draw_triangle_perspective, RasterOptions, RasterVertex, SpanShader,
    SUBPIXEL_BITS,
};
use fixshade::target::SliceFramebuffer;

const W: usize = 128;
const H: usize = 128;
const F: f64 = 100.0; // focal length in pixels
const UNIT: f64 = 65536.0; // attribute scale

/// Records start + k·step of both attributes per pixel.
struct Record(Vec<Option<[f64; 2]>>);
impl SpanShader<2> for Record {
    type Color = Gray8;
    fn shade_span(&mut self, x: i32, y: i32, s: &[i32; 2], d: &[i32; 2], out: &mut [Gray8]) {
        for (k, p) in out.iter_mut().enumerate() {
            let a = |i: usize| f64::from(s[i]) + k as f64 * f64::from(d[i]);
            self.0[y as usize * W + x as usize + k] = Some([a(0), a(1)]);
            *p = Gray8::new(255);
        }
    }
}

/// World point of the floor quad at parameters (u, v) in [0, 1]²: a plane
/// receding from z = 1.5 to z = 9.
fn world(u: f64, v: f64) -> [f64; 3] {
    [-2.0 + 4.0 * u, 1.0 - 0.5 * v, 1.5 + 7.5 * v]
}

fn project(p: [f64; 3]) -> (f64, f64) {
    (
        W as f64 / 2.0 + F * p[0] / p[2],
        H as f64 / 2.0 - F * p[1] / p[2],
    )
}

fn vertex(u: f64, v: f64) -> RasterVertex<2> {
    let p = world(u, v);
    let (sx, sy) = project(p);
    let sub = f64::from(1 << SUBPIXEL_BITS);
    RasterVertex {
        x: (sx * sub).round() as i32,
        y: (sy * sub).round() as i32,
        z: 0,
        inv_w: (f64::from(1 << 24) / p[2]).round() as i32,
        attrs: [(u * UNIT).round() as i32, (v * UNIT).round() as i32],
    }
}

/// Exact (u, v) seen through the centre of pixel (x, y), by intersecting the
/// view ray with the quad's plane; uses the sub-pixel-rounded vertices'
/// positions only through the projection, so it is exact up to that rounding.
fn exact(x: usize, y: usize) -> [f64; 2] {
    let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
    let dir = [(px - W as f64 / 2.0) / F, -(py - H as f64 / 2.0) / F, 1.0];
    // Plane through world(u, v): y_w = 1 − 0.5 v, z = 1.5 + 7.5 v → y_w = 1 − (z − 1.5)/15.
    // Ray t·dir: t·dir1 = 1 − (t − 1.5)/15 → t = (1 + 0.1) / (dir1 + 1/15).
    let t = 1.1 / (dir[1] + 1.0 / 15.0);
    let (xw, zw) = (t * dir[0], t);
    [((xw + 2.0) / 4.0) * UNIT, ((zw - 1.5) / 7.5) * UNIT]
}

fn render(perspective: bool) -> f64 {
    let q = [
        vertex(0.0, 0.0),
        vertex(1.0, 0.0),
        vertex(1.0, 1.0),
        vertex(0.0, 1.0),
    ];
    let mut px = vec![Gray8::new(0); W * H];
    let mut fb = SliceFramebuffer::new(&mut px, W as u32, H as u32).unwrap();
    let mut rec = Record(vec![None; W * H]);
    let opts = RasterOptions::default();
    for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
        if perspective {
            draw_triangle_perspective(&mut fb, None, &t, &opts, &mut rec).unwrap();
        } else {
            draw_triangle(&mut fb, None, &t, &opts, &mut rec).unwrap();
        }
    }
    let mut worst = 0.0f64;
    let mut n = 0;
    for y in 0..H {
        for x in 0..W {
            if let Some(got) = rec.0[y * W + x] {
                let want = exact(x, y);
                for i in 0..2 {
                    worst = worst.max((got[i] - want[i]).abs());
                }
                n += 1;
            }
        }
    }
    assert!(n > 2000, "quad covers {n} pixels");
    worst
}

#[test]
fn perspective_matches_exact_values() {
    let persp = render(true);
    let affine = render(false);
    eprintln!("max error: perspective {persp:.1}, affine {affine:.1} units (1.0 = {UNIT})");
    // Vertex positions are rounded to 1/16 pixel, which moves the exact value by
    // up to ~0.1 % of the range near the far edge; the interpolation adds little.
    assert!(
        persp < 0.001 * UNIT,
        "perspective error {persp} units of {UNIT}"
    );
    assert!(
        affine > 20.0 * persp,
        "affine error {affine} should dwarf perspective {persp}"
    );
}
