//! Perspective-correct interpolation on a tilted quad drawn through the
//! per-triangle front in a perspective clip space: the values at the
//! sub-span ends against the exact perspective interpolation of the corners
//! as drawn (within a bound derived below), the pixels between them linear,
//! and all of it far closer to the exact value of the 3D attribute than
//! screen-linear interpolation.

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::camera::{Clip, ClipSpace};
use fixshade::num::ATTR_FRAC;
use fixshade::render::Corner;
use fixshade_testkit::support::{
    clip_corner, full, plane_bound, Record, Run, Tris, PERSPECTIVE_SPAN,
};

const W: usize = 128;
const H: usize = 128;
const F: f64 = 100.0; // focal length in pixels
/// Attribute scale: values at the vertices stay within ±(2^15 − 1).
const UNIT: f64 = 16384.0;
/// Clip coordinates per eye-space unit (so that `w` is an integer).
const K: f64 = 1000.0;
/// One unit of a value handed to a kernel.
const ONE: f64 = (1u32 << ATTR_FRAC) as f64;

/// World point of the floor quad at parameters (u, v) in [0, 1]²: a plane
/// receding from z = 1.5 to z = 9.
fn world(u: f64, v: f64) -> [f64; 3] {
    [-2.0 + 4.0 * u, 1.0 - 0.5 * v, 1.5 + 7.5 * v]
}

fn space(persp: bool) -> ClipSpace {
    if persp {
        ClipSpace::perspective([(W as i32 / 2) << 4, (H as i32 / 2) << 4], 1)
    } else {
        ClipSpace::SCREEN
    }
}

/// The corner at (u, v) carrying the attribute `u` or `v` (`which`), in the
/// perspective clip space (`persp`) or in screen space (position rounded to
/// a sub-pixel, `w = 1`).
fn vertex(u: f64, v: f64, which: usize, persp: bool) -> Corner {
    let p = world(u, v);
    let a = ([u, v][which] * UNIT).round() as i32;
    let sub = f64::from(1 << SUBPIXEL_BITS);
    let clip = if persp {
        // screen = centre + x/w sub-pixels
        Clip {
            x: (sub * F * p[0] * K).round() as i32,
            y: (-sub * F * p[1] * K).round() as i32,
            z: 0,
            w: (p[2] * K).round() as i32,
        }
    } else {
        Clip {
            x: ((W as f64 / 2.0 + F * p[0] / p[2]) * sub).round() as i32,
            y: ((H as f64 / 2.0 - F * p[1] / p[2]) * sub).round() as i32,
            z: 0,
            w: 1,
        }
    };
    clip_corner(clip, a)
}

/// The two triangles of the quad for attribute `which`.
fn quad(which: usize, persp: bool) -> [[Corner; 3]; 2] {
    let q =
        [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(u, v)| vertex(u, v, which, persp));
    [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
}

/// Exact (u, v) seen through the centre of pixel (x, y), by intersecting the
/// view ray with the quad's plane (in `UNIT`s).
fn analytic(x: i32, y: i32) -> [f64; 2] {
    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let dir = [(px - W as f64 / 2.0) / F, -(py - H as f64 / 2.0) / F, 1.0];
    // Plane through world(u, v): y_w = 1 − 0.5 v, z = 1.5 + 7.5 v → y_w = 1 − (z − 1.5)/15.
    // Ray t·dir: t·dir1 = 1 − (t − 1.5)/15 → t = (1 + 0.1) / (dir1 + 1/15).
    let t = 1.1 / (dir[1] + 1.0 / 15.0);
    let (xw, zw) = (t * dir[0], t);
    [((xw + 2.0) / 4.0) * UNIT, ((zw - 1.5) / 7.5) * UNIT]
}

/// A triangle as drawn: screen positions (sub-pixels), clip `w`, values.
struct Drawn {
    xy: [(i32, i32); 3],
    w: [f64; 3],
    a: [f64; 3],
    /// Q14 error of each barycentric weight, see [`Drawn::bound`].
    e: f64,
}

impl Drawn {
    fn new(t: &[Corner; 3], s: &ClipSpace) -> Drawn {
        let xy = t.map(|c| {
            let p = s.project(c.clip).expect("in front of the near plane");
            (p.x, p.y)
        });
        let e1 = plane_bound(xy, [0, 1 << 14, 0]) / ONE + 1.0;
        let e2 = plane_bound(xy, [0, 0, 1 << 14]) / ONE + 1.0;
        Drawn {
            xy,
            w: t.map(|c| f64::from(c.clip.w)),
            a: t.map(|c| f64::from(c.vertex.normal[0])),
            e: e1 + e2,
        }
    }

    /// Screen barycentric weights of the centre of pixel `(x, y)`.
    fn beta(&self, x: i32, y: i32) -> [f64; 3] {
        let s = f64::from(1 << SUBPIXEL_BITS);
        let (px, py) = ((f64::from(x) + 0.5) * s, (f64::from(y) + 0.5) * s);
        let f = |i: usize| (f64::from(self.xy[i].0), f64::from(self.xy[i].1));
        let ((x0, y0), (x1, y1), (x2, y2)) = (f(0), f(1), f(2));
        let det = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
        let b1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) / det;
        let b2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) / det;
        [1.0 - b1 - b2, b1, b2]
    }

    fn inside(&self, x: i32, y: i32) -> bool {
        self.beta(x, y).iter().all(|&b| b >= 0.0)
    }

    /// The exact perspective-correct value at pixel `(x, y)`, attribute units.
    fn exact(&self, x: i32, y: i32) -> f64 {
        let b = self.beta(x, y);
        let t: Vec<f64> = (0..3).map(|i| b[i] / self.w[i]).collect();
        (0..3).map(|i| t[i] * self.a[i]).sum::<f64>() / t.iter().sum::<f64>()
    }

    /// The error bound (attribute units) of a value the pipeline evaluates
    /// at pixel `(x, y)` (a sub-span end, inside the triangle).
    ///
    /// The pipeline (`raster::interp::Persp`) computes `V = Σ Wᵢ·aᵢ`,
    /// `Wᵢ = bᵢ·qᵢ / Σ bⱼ·qⱼ`, from Q14 screen weights `bᵢ` (two 32-bit
    /// planes, truncated to Q14; the third `b₀ = 2^14 − b₁ − b₂`) and
    /// `qᵢ ∝ 1/wᵢ`. First-order perturbation, with `T = Σ βⱼ·qⱼ` at the
    /// exact weights `βᵢ`:
    /// - `∂V/∂βₖ = qₖ·(aₖ − V)/T`; each `bₖ` is off by at most `e` Q14
    ///   units, `e` = the two planes' `Setup::err` bounds
    ///   (`support::plane_bound` of the planes 0..2^14) + 1 each for the
    ///   truncation (`b₀` carries both);
    /// - `∂V/∂qₖ = βₖ·(aₖ − V)/T`; `qₖ` (products of the other two `w`,
    ///   shifted so that the largest is below 2^16) is off by less than one
    ///   unit of 2^−15 of the largest: relative `2^−15·q_max/qₖ`, counted
    ///   twice (numerator and sum);
    /// - the normalisation (one reciprocal, relative error ≈ 2^−15, and the
    ///   shifts and truncation of the weights, ≤ 2^−14 + 2^−15 each) adds at
    ///   most `1.1·2^−15 + 2^−15 + 2^−14` per weight, times `|a₁ − a₀| +
    ///   |a₂ − a₀|`;
    ///
    /// plus 1 % for the second-order terms.
    fn bound(&self, x: i32, y: i32) -> f64 {
        let b = self.beta(x, y);
        let q = self.w.map(|w| 1.0 / w);
        let qmax = q.iter().cloned().fold(0.0, f64::max);
        let t: f64 = (0..3).map(|i| b[i].abs() * q[i]).sum();
        let v = self.exact(x, y);
        let mut err = 0.0;
        for k in 0..3 {
            let d = (self.a[k] - v).abs();
            err += q[k] * d / t * self.e / ONE;
            err += b[k].abs() * qmax / t * d * 2.0 / 32768.0;
        }
        let spread = (self.a[1] - self.a[0]).abs() + (self.a[2] - self.a[0]).abs();
        err += spread * (2.1 / 32768.0 + 1.0 / ONE);
        err * 1.01
    }
}

/// Draws triangle `t` (in the space `s`) alone; the runs handed to the kernel.
fn runs(t: &[Corner; 3], s: ClipSpace) -> Vec<Run> {
    let rec = Record::default();
    let mut item = Tris {
        space: s,
        ..Tris::screen(&rec, vec![*t])
    };
    full(W as u32, H as u32, Gray8::new(0), false, &mut [&mut item]);
    rec.runs.into_inner()
}

/// Checks every sub-span of both triangles of the quad, for `u` and `v`:
/// its start (evaluated exactly) within [`Drawn::bound`] of the exact value;
/// its pixels linear between its ends, i.e. within the larger of the ends'
/// bounds plus the exact curve's distance from its chord plus the step's
/// truncation. With `ends_outside`, also the sub-spans whose end (8 pixels
/// on) lies beyond the triangle. Returns the worst error against the
/// analytic value of the 3D attribute (`UNIT`s), and the number of pixels.
fn check(ends_outside: bool) -> (f64, usize) {
    let s = space(true);
    let (mut worst, mut n, mut ratio) = (0.0f64, 0, 0.0f64);
    for which in 0..2 {
        for t in quad(which, true) {
            let d = Drawn::new(&t, &s);
            for r in runs(&t, s) {
                assert!(r.len <= PERSPECTIVE_SPAN, "{r:?}");
                let start = f64::from(r.start) / ONE;
                let e = (start - d.exact(r.x, r.y)).abs();
                assert!(
                    e <= d.bound(r.x, r.y),
                    "{which} {r:?}: start {start:.2}, exact {:.2}, error {e:.2} > bound {:.2}",
                    d.exact(r.x, r.y),
                    d.bound(r.x, r.y)
                );
                ratio = ratio.max(e / d.bound(r.x, r.y));
                let end = r.x + PERSPECTIVE_SPAN as i32;
                if !ends_outside && !d.inside(end, r.y) {
                    continue;
                }
                let (e0, e8) = (d.exact(r.x, r.y), d.exact(end, r.y));
                let ends = d.bound(r.x, r.y).max(d.bound(end, r.y));
                for k in 0..r.len {
                    let x = r.x + k as i32;
                    let got = (f64::from(r.start) + k as f64 * f64::from(r.step)) / ONE;
                    let exact = d.exact(x, r.y);
                    let chord = e0 + (e8 - e0) * k as f64 / 8.0;
                    let tol = ends + (exact - chord).abs() + 8.0 / ONE;
                    assert!(
                        (got - exact).abs() <= tol,
                        "{which} {r:?} pixel {k}: {got:.2}, exact {exact:.2}, allowed {tol:.2}"
                    );
                    worst = worst.max((got - analytic(x, r.y)[which]).abs());
                    n += 1;
                }
            }
        }
    }
    eprintln!("sub-span starts: worst error / bound = {ratio:.2}");
    (worst, n)
}

#[test]
fn perspective_values_within_their_bound_and_far_better_than_affine() {
    let (persp, n) = check(false);
    assert!(n > 4000, "{n} pixels checked");
    // the same quad interpolated screen-linearly
    let mut affine = 0.0f64;
    for which in 0..2 {
        for t in quad(which, false) {
            for r in runs(&t, space(false)) {
                for k in 0..r.len {
                    let got = (f64::from(r.start) + k as f64 * f64::from(r.step)) / ONE;
                    let want = analytic(r.x + k as i32, r.y)[which];
                    affine = affine.max((got - want).abs());
                }
            }
        }
    }
    eprintln!("max error against the 3D attribute: perspective {persp:.1}, affine {affine:.1} units (1.0 = {UNIT})");
    assert!(
        affine > 20.0 * persp,
        "affine error {affine} should dwarf perspective {persp}"
    );
}

#[test]
fn every_pixel_linear_between_exact_ends() {
    check(true);
}
