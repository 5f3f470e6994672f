//! The attribute precision the `raster` module documents (issue 11, item 10),
//! measured by a search for the worst case rather than a uniform sample:
//! triangles are drawn at random and then mutated towards larger errors (thin
//! slivers, attribute differences up to the 2^29 limit, long runs), and the
//! largest error found is checked against the documented bound.
//!
//! Documented (module docs of `fixshade::raster`): with `draw_triangle`, the
//! value of the first pixel of every run is the exact plane value rounded to a
//! unit (≤ ½ unit off); pixel `k` of the run gets `start + k·step`, the step
//! rounded from the exact (rounded) end values and, where that would leave the
//! vertex range, shrunk towards zero, so pixel `k` is at most `½ + k` units off
//! (`k/2 + ½ + k/span` from the rounding alone; the shrink truncates, up to one
//! more unit per pixel). A bound of `½ + k/2`, which rounding alone would
//! suggest, is exceeded by tens of units on long runs of steep attributes.

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::raster::{draw_triangle, RasterOptions, RasterVertex, SpanShader, SUBPIXEL_BITS};
use fixshade::target::SliceFramebuffer;

const W: u32 = 200;
/// The documented growth per pixel of a run (units).
const SLOPE: f64 = 1.0;

/// Records the worst error of every run against the exact plane.
struct Probe {
    v: [(f64, f64, f64); 3],
    /// Worst error of a run's first pixel, worst of `err − k/2` over all pixels.
    first: f64,
    excess: f64,
    pixels: u64,
}

impl Probe {
    fn exact(&self, x: i32, y: i32) -> f64 {
        let s = f64::from(1 << SUBPIXEL_BITS);
        let (px, py) = ((f64::from(x) + 0.5) * s, (f64::from(y) + 0.5) * s);
        let [(x0, y0, a0), (x1, y1, a1), (x2, y2, a2)] = self.v;
        let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        let b1 = ((px - x0) * (y2 - y0) - (x2 - x0) * (py - y0)) / area;
        let b2 = ((x1 - x0) * (py - y0) - (px - x0) * (y1 - y0)) / area;
        a0 + b1 * (a1 - a0) + b2 * (a2 - a0)
    }
}

impl SpanShader<1> for Probe {
    type Color = Gray8;
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; 1], step: &[i32; 1], out: &mut [Gray8]) {
        for k in 0..out.len() {
            let got = f64::from(start[0]) + k as f64 * f64::from(step[0]);
            let err = (got - self.exact(x + k as i32, y)).abs();
            if k == 0 {
                self.first = self.first.max(err);
            }
            self.excess = self.excess.max(err - k as f64 * SLOPE);
            self.pixels += 1;
        }
    }
}

/// A small deterministic generator (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo + 1) as u64) as i32
    }
}

type Tri = [(i32, i32, i32); 3];

fn measure(t: &Tri) -> (f64, f64, u64) {
    let mut px = vec![Gray8::new(0); (W * W) as usize];
    let mut fb = SliceFramebuffer::new(&mut px, W, W).unwrap();
    let v = t.map(|(x, y, a)| RasterVertex {
        x,
        y,
        z: 0,
        inv_w: 1,
        attrs: [a],
    });
    let mut p = Probe {
        v: t.map(|(x, y, a)| (f64::from(x), f64::from(y), f64::from(a))),
        first: 0.0,
        excess: f64::NEG_INFINITY,
        pixels: 0,
    };
    let _ = draw_triangle(&mut fb, None, &v, &RasterOptions::default(), &mut p);
    (p.first, p.excess, p.pixels)
}

fn random(r: &mut Rng) -> Tri {
    let big = 1 << 29;
    let a = |r: &mut Rng| match r.next() % 3 {
        0 => r.range(-big, big),
        1 => r.range(-1000, 1000),
        _ => r.range(-(1 << 20), 1 << 20),
    };
    let c = (W as i32) << SUBPIXEL_BITS;
    core::array::from_fn(|_| (r.range(0, c), r.range(0, c), a(r)))
}

fn mutate(r: &mut Rng, t: &Tri) -> Tri {
    let mut t = *t;
    let i = (r.next() % 3) as usize;
    let s = 1 << r.range(0, 8);
    let c = (W as i32) << SUBPIXEL_BITS;
    match r.next() % 3 {
        0 => t[i].0 = (t[i].0 + r.range(-s, s)).clamp(0, c),
        1 => t[i].1 = (t[i].1 + r.range(-s, s)).clamp(0, c),
        _ => t[i].2 = (t[i].2 + r.range(-s << 12, s << 12)).clamp(-(1 << 29), 1 << 29),
    }
    t
}

#[test]
fn screen_linear_values_within_the_documented_bound_at_the_worst_case_found() {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut worst_first, mut worst_excess) = (0.0f64, f64::NEG_INFINITY);
    for _ in 0..60 {
        // hill-climb on the error beyond k/2 from a random start
        let mut t = random(&mut r);
        let (f, mut e, _) = measure(&t);
        worst_first = worst_first.max(f);
        for _ in 0..60 {
            let u = mutate(&mut r, &t);
            let (f, eu, n) = measure(&u);
            worst_first = worst_first.max(f);
            if n > 0 && eu >= e {
                (t, e) = (u, eu);
            }
        }
        worst_excess = worst_excess.max(e);
    }
    println!("worst first-pixel error {worst_first:.3} units, worst err − k {worst_excess:.3}");
    assert!(
        worst_first <= 0.5 + 1e-6,
        "first pixel of a run {worst_first} units off"
    );
    assert!(
        worst_excess <= 1.5 + 1e-9,
        "pixel k of a run {worst_excess} + k units off"
    );
}
