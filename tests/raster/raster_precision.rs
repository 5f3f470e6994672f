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

use embedded_graphics_core::pixelcolor::Gray8;
use fixshade::camera::SUBPIXEL_BITS;
use fixshade::raster::interp::VARYING_LIMIT;
use fixshade_testkit::support::{corner, exact_plane, full, plane_bound, Record, Rng, Tris};

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
/// error (units of 2^-14) and the pixels drawn;
/// nothing for a triangle whose plane changes by 2^30 or more per pixel
/// (see `slivers_with_saturating_gradients_stay_in_the_corners_range`).
fn measure(t: &Tri) -> (f64, f64, usize) {
    if gradient(t) >= f64::from(1 << 30) * 0.999 {
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
fn search() -> (f64, f64, usize) {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut worst_ratio, mut worst_err, mut pixels) = (0.0f64, 0.0f64, 0usize);
    for _ in 0..60 {
        // hill-climb on error / bound from a random start
        let mut t = random(&mut r);
        let (mut e, w, n) = measure(&t);
        worst_err = worst_err.max(w);
        pixels += n;
        for _ in 0..60 {
            let u = mutate(&mut r, &t);
            let (eu, w, n) = measure(&u);
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
    let (worst_ratio, worst_err, pixels) = search();
    println!(
        "worst error / bound {worst_ratio:.3}, worst error {worst_err:.1} units of 2^-14 ({pixels} pixels)"
    );
    assert!(pixels > 1_000_000, "{pixels} pixels");
    assert!(
        worst_ratio <= 1.0,
        "a value {worst_ratio} times the stated bound off"
    );
}

/// How far (units of 2^-14) the triangle's recorded values leave the range
/// of its corners' values, and the pixels drawn.
fn range_excess(t: &Tri) -> (f64, usize) {
    let rec = Record::default();
    let tri = t.map(|(x, y, a)| corner(x, y, 0, a));
    let mut item = Tris::screen(&rec, vec![tri]);
    full(W, W, Gray8::new(0), false, &mut [&mut item]);
    let a = t.map(|(_, _, a)| i64::from(a) << 14);
    let (lo, hi) = (a.iter().min().unwrap(), a.iter().max().unwrap());
    let px = rec.pixels();
    let excess = px
        .iter()
        .map(|&(_, _, v)| (lo - v).max(v - hi).max(0) as f64)
        .fold(0.0, f64::max);
    (excess, px.len())
}

/// A plane whose exact change per pixel reaches 2^30 units (a sliver across
/// which the value changes by more than 2^16 per pixel) has no error bound
/// (`Setup::err` says so): the pipeline clamps its values to the corners'
/// range. The sliver found, and a hill-climb towards values outside it.
#[test]
fn slivers_with_saturating_gradients_stay_in_the_corners_range() {
    let sliver = [(609, 2392, 32767), (2951, 827, -168), (532, 2438, -6211)];
    assert!(gradient(&sliver) >= f64::from(1 << 30));
    let (excess, n) = range_excess(&sliver);
    assert!(
        n > 0 && excess == 0.0,
        "the sliver: {excess} units outside, {n} pixels"
    );
    // the climb's score: below 0 towards a saturating gradient, then how far
    // outside the corners' range
    let score = |t: &Tri| {
        let g = gradient(t) / f64::from(1 << 30);
        if g < 0.999 {
            (g - 1.0, 1)
        } else {
            range_excess(t)
        }
    };
    let mut r = Rng(0x0005_EED0_F5A7_u64);
    let mut slivers = 0;
    for _ in 0..200 {
        let mut t = random(&mut r);
        let mut e = score(&t).0;
        for _ in 0..40 {
            let u = mutate(&mut r, &t);
            let (eu, n) = score(&u);
            if n > 0 && eu >= e {
                (t, e) = (u, eu);
            }
        }
        slivers += usize::from(e >= 0.0);
        assert!(
            e <= 0.0,
            "{t:?}: a value {e} units outside the corners' range"
        );
    }
    assert!(slivers >= 20, "{slivers} saturating slivers found");
    println!("{slivers} saturating slivers among the triangles searched");
}

/// Triangles reaching far outside the set-up window (issue 21, item 5: one
/// reaching −13 829 px was 7.1 units off the old "½ + k" statement): the
/// pipeline clips them to the window and sets up the pieces; every value is
/// still within the bound of the whole triangle (`plane_bound` of its
/// unclipped corners), searched like the triangles inside it.
#[test]
fn clipped_triangles_within_the_bound_of_the_whole_triangle() {
    let far = 1 << 18; // 16 384 px in sub-pixels
    let c = (W as i32) << SUBPIXEL_BITS;
    let outside = |r: &mut Rng, t: &mut Tri| {
        let i = (r.next() % 3) as usize;
        t[i].0 = r.range(-far, far);
        t[i].1 = r.range(-far, far);
    };
    let mut r = Rng(0x0C11_F0ED);
    let (mut worst, mut pixels, mut clipped) = (0.0f64, 0usize, 0usize);
    for _ in 0..40 {
        let mut t = random(&mut r);
        outside(&mut r, &mut t);
        let (mut e, _, n) = measure(&t);
        pixels += n;
        for _ in 0..40 {
            let mut u = mutate(&mut r, &t);
            if r.next() % 4 == 0 {
                outside(&mut r, &mut u);
            }
            let (eu, _, n) = measure(&u);
            pixels += n;
            if n > 0 && eu >= e {
                (t, e) = (u, eu);
            }
        }
        clipped += usize::from(
            t.iter()
                .any(|p| p.0.min(p.1) < -(c / 4) || p.0.max(p.1) > 2 * c),
        );
        worst = worst.max(e);
    }
    println!("clipped: worst error / bound {worst:.3} ({pixels} pixels, {clipped} far triangles)");
    assert!(
        pixels > 100_000 && clipped >= 10,
        "{pixels} pixels, {clipped}"
    );
    assert!(worst <= 1.0, "a value {worst} times the bound off");
}
