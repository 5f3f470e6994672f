//! The precision of screen-linear values (issue 11, item 10), measured by a
//! search for the worst case rather than a uniform sample: triangles are
//! drawn at random through the per-triangle front (`render::draw_triangle`,
//! screen space) and then mutated towards larger errors (thin slivers, value
//! differences up to the ±(2^15 − 1) limit, long runs), and the largest
//! error found is checked against the bound the pipeline states.
//!
//! The pipeline's statement (`raster::interp`, `Setup::err`): values come
//! from 32-bit planes with 14-bit barycentric coefficients, no longer exact
//! per run (the 64-bit per-run planes that made the first pixel of a run
//! exact to ½ unit are gone); every value is within the plane's error bound
//! of the exact plane. `support::plane_bound` restates that bound from the
//! triangle's geometry (see its comment for the derivation); the search
//! maximises the ratio of the error to it.

mod support;

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::raster::interp::VARYING_LIMIT;
use fixshade::raster::SUBPIXEL_BITS;
use support::{corner, exact_plane, full, plane_bound, Record, Rng, Tris};

const W: u32 = 200;

type Tri = [(i32, i32, i32); 3];

/// The largest per-pixel change (units of 2^-14) of the exact plane.
fn gradient(t: &Tri) -> f64 {
    let xy = t.map(|(x, y, _)| (x, y));
    let a = t.map(|(_, _, a)| a);
    // the plane's value at three pixel centres
    let (x, y) = (xy[0].0 >> SUBPIXEL_BITS, xy[0].1 >> SUBPIXEL_BITS);
    let v = exact_plane(xy, a, x, y);
    let dx = exact_plane(xy, a, x + 1, y) - v;
    let dy = exact_plane(xy, a, x, y + 1) - v;
    dx.abs().max(dy.abs())
}

/// The largest `error / bound` over the triangle's pixels, the largest
/// error (units of 2^-14) and the pixels drawn; with `saturating` false,
/// nothing for a triangle whose plane changes by 2^30 or more per pixel
/// (see the ignored test).
fn measure(t: &Tri, saturating: bool) -> (f64, f64, usize) {
    if !saturating && gradient(t) >= f64::from(1 << 30) * 0.999 {
        return (0.0, 0.0, 0);
    }
    let rec = Record::default();
    let tri = t.map(|(x, y, a)| corner(x, y, 0, a));
    let mut item = Tris::screen(&rec, vec![tri]);
    full(W, W, Gray8::new(0), false, &mut [&mut item]);
    let xy = t.map(|(x, y, _)| (x, y));
    let a = t.map(|(_, _, a)| a);
    let bound = plane_bound(xy, a);
    let px = rec.pixels();
    let (mut ratio, mut worst) = (0.0f64, 0.0f64);
    for &(x, y, got) in &px {
        let err = (got as f64 - exact_plane(xy, a, x, y)).abs();
        worst = worst.max(err);
        ratio = ratio.max(err / bound);
    }
    (ratio, worst, px.len())
}

fn random(r: &mut Rng) -> Tri {
    let lim = VARYING_LIMIT;
    let a = |r: &mut Rng| match r.next() % 3 {
        0 => r.range(-lim, lim),
        1 => r.range(-1000, 1000),
        _ => [-lim, lim][(r.next() % 2) as usize],
    };
    let c = (W as i32) << SUBPIXEL_BITS;
    core::array::from_fn(|_| (r.range(0, c), r.range(0, c), a(r)))
}

fn mutate(r: &mut Rng, t: &Tri) -> Tri {
    let mut t = *t;
    let i = (r.next() % 3) as usize;
    let s = 1 << r.range(0, 8);
    let c = (W as i32) << SUBPIXEL_BITS;
    let lim = VARYING_LIMIT;
    match r.next() % 3 {
        0 => t[i].0 = (t[i].0 + r.range(-s, s)).clamp(0, c),
        1 => t[i].1 = (t[i].1 + r.range(-s, s)).clamp(0, c),
        _ => t[i].2 = (t[i].2 + r.range(-s << 7, s << 7)).clamp(-lim, lim),
    }
    t
}

/// The hill-climb: the worst `error / bound` found, the worst error and
/// the pixels measured.
fn search(saturating: bool) -> (f64, f64, usize) {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut worst_ratio, mut worst_err, mut pixels) = (0.0f64, 0.0f64, 0usize);
    for _ in 0..60 {
        // hill-climb on error / bound from a random start
        let mut t = random(&mut r);
        let (mut e, w, n) = measure(&t, saturating);
        worst_err = worst_err.max(w);
        pixels += n;
        for _ in 0..60 {
            let u = mutate(&mut r, &t);
            let (eu, w, n) = measure(&u, saturating);
            worst_err = worst_err.max(w);
            pixels += n;
            if n > 0 && eu >= e {
                (t, e) = (u, eu);
            }
        }
        worst_ratio = worst_ratio.max(e);
    }
    (worst_ratio, worst_err, pixels)
}

#[test]
fn screen_linear_values_within_the_stated_bound_at_the_worst_case_found() {
    let (worst_ratio, worst_err, pixels) = search(false);
    println!(
        "worst error / bound {worst_ratio:.3}, worst error {worst_err:.1} units of 2^-14 ({pixels} pixels)"
    );
    assert!(pixels > 1_000_000, "{pixels} pixels");
    assert!(
        worst_ratio <= 1.0,
        "a value {worst_ratio} times the stated bound off"
    );
}

#[test]
#[ignore = "library bug: a plane whose exact change per pixel reaches 2^30 units saturates \
            (raster::setup::scale) and its values leave Setup::err's bound (which the pipeline \
            uses to decide clamping), e.g. the sliver (609, 2392, 32767), (2951, 827, -168), \
            (532, 2438, -6211): pixel (63, 132) gets -8360.0, exact 26827.0"]
fn slivers_with_saturating_gradients_within_the_stated_bound() {
    let sliver = [(609, 2392, 32767), (2951, 827, -168), (532, 2438, -6211)];
    let (ratio, err, _) = measure(&sliver, true);
    assert!(
        ratio <= 1.0,
        "the sliver: {ratio} times the bound off ({err:.0} units)"
    );
    let (worst_ratio, worst_err, _) = search(true);
    assert!(
        worst_ratio <= 1.0,
        "a value {worst_ratio} times the stated bound off ({worst_err:.0} units of 2^-14)"
    );
}
