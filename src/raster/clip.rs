//! The one clipper: a triangle cut in clip space ([`Clip`]), before the
//! division by `w`, to the near plane (perspective only) and the set-up
//! window. Each cut point is computed from its edge's endpoints in canonical
//! order (the smaller clip coordinates first): bit-identical for both
//! triangles of an edge. Attributes are interpolated linearly in clip space,
//! the perspective-correct value at a cut. 64-bit values from 32-bit
//! operations ([`crate::num::wide`]); 128-bit products for the facing across
//! the near plane (the rare path).

use super::{WINDOW_MAX, WINDOW_MIN};
use crate::camera::{Clip, ClipSpace};
use crate::num::wide::{lerp_i32, mul_i32, mul_u32};
use core::cmp::Ordering;

/// At most 3 + 5 vertices: each plane adds at most one.
pub(crate) const MAX: usize = 8;

/// A point on the screen after clipping: sub-pixel position inside the
/// window, depth, and the clip `w` (1 for an orthographic projection).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Screen {
    pub x: i32,
    pub y: i32,
    pub z: u16,
    pub w: i32,
}

/// The screen position of clip coordinates `c` after clipping (inside the
/// window up to the rounding of a cut: clamped to it); `PERSP`: a perspective
/// clip space.
#[inline]
pub(crate) fn screen<const PERSP: bool>(s: &ClipSpace, c: Clip) -> Screen {
    let p = s.screen::<PERSP>(c);
    Screen {
        x: p.x.clamp(WINDOW_MIN, WINDOW_MAX),
        y: p.y.clamp(WINDOW_MIN, WINDOW_MAX),
        z: p.z,
        w: if PERSP { c.w.max(1) } else { 1 },
    }
}

/// The planes, as signed distances (inside: ≥ 0).
#[derive(Clone, Copy)]
enum ClipPlane {
    /// `w ≥ near`.
    Near,
    /// `cx + x/w ≥ WINDOW_MIN`.
    XMin,
    /// `cx + x/w ≤ WINDOW_MAX`.
    XMax,
    /// `cy + y/w ≥ WINDOW_MIN`.
    YMin,
    /// `cy + y/w ≤ WINDOW_MAX`.
    YMax,
}

impl ClipPlane {
    /// The signed distance of `c` (exact: every product below 2^48, from
    /// 32-bit multiplications; `PERSP`: a perspective clip space, else
    /// `w = 1` and the centre is 0).
    #[inline]
    fn distance<const PERSP: bool>(self, c: &Clip, s: &ClipSpace) -> i64 {
        let w = i64::from(c.w);
        // |k| < 2^17
        let times_w = |k: i64| if PERSP { mul_i32(k as i32, c.w) } else { k };
        let lo = |centre: i32| times_w(i64::from(WINDOW_MIN) - i64::from(centre));
        let hi = |centre: i32| times_w(i64::from(WINDOW_MAX) - i64::from(centre));
        let centre = s.centre();
        match self {
            ClipPlane::Near => w - i64::from(s.near()),
            ClipPlane::XMin => i64::from(c.x) - lo(centre[0]),
            ClipPlane::XMax => hi(centre[0]) - i64::from(c.x),
            ClipPlane::YMin => i64::from(c.y) - lo(centre[1]),
            ClipPlane::YMax => hi(centre[1]) - i64::from(c.y),
        }
    }
}

/// How a corner of a polygon cut by a plane is made from the polygon before
/// the cut: its corner `a` (`den == 0`), or the point `num/den` of the way
/// from corner `a` to corner `b` (`a` the smaller clip coordinates: the cut
/// of an edge is the same from both triangles sharing it).
#[derive(Clone, Copy, Default)]
struct Step {
    a: u8,
    b: u8,
    num: u32,
    den: u32,
}

/// A convex polygon in clip space: its corners' clip coordinates. Not
/// generic: the values a kernel interpolates follow the cuts in
/// [`clipped`], so one copy of the clipper serves every kernel.
pub(crate) struct Polygon {
    c: [Clip; MAX],
    n: usize,
}

/// Triangle `t` (clip coordinates, values `v`) clipped to the near plane
/// (`PERSP`: a perspective clip space) and the window: the polygon and its
/// corners' values, each cut made by `lerp(a, b, num, den)` (the point
/// `num/den` of the way from `a` to `b`), which is the perspective-correct
/// value there.
#[inline]
pub(crate) fn clipped<V: Copy, const PERSP: bool>(
    t: [Clip; 3],
    v: &[V; 3],
    lerp: impl Fn(&V, &V, u32, u32) -> V,
    s: &ClipSpace,
) -> (Polygon, [V; MAX]) {
    let mut c = [t[0]; MAX];
    let mut vs = [v[0]; MAX];
    for ((c, v), (t, tv)) in c.iter_mut().zip(vs.iter_mut()).zip(t.iter().zip(v)) {
        (*c, *v) = (*t, *tv);
    }
    let mut p = Polygon { c, n: 3 };
    let planes = [
        ClipPlane::Near,
        ClipPlane::XMin,
        ClipPlane::XMax,
        ClipPlane::YMin,
        ClipPlane::YMax,
    ];
    for plane in planes.iter().skip(usize::from(!PERSP)) {
        if p.n < 3 {
            break;
        }
        if let Some(steps) = p.clip::<PERSP>(*plane, s) {
            let old = vs;
            for (out, st) in vs.iter_mut().zip(&steps).take(p.n) {
                let at = |i: u8| old[usize::from(i) & (MAX - 1)];
                *out = if st.den == 0 {
                    at(st.a)
                } else {
                    lerp(&at(st.a), &at(st.b), st.num, st.den)
                };
            }
        }
    }
    if p.n < 3 {
        p.n = 0;
    }
    (p, vs)
}

impl Polygon {
    /// The corners' clip coordinates.
    pub(crate) fn vertices(&self) -> &[Clip] {
        self.c.get(..self.n).unwrap_or(&[])
    }

    /// All corners' clip coordinates, the first [`Polygon::vertices`] of
    /// them valid.
    pub(crate) fn corners(&self) -> &[Clip; MAX] {
        &self.c
    }

    /// Cuts the polygon by `plane`: how each new corner is made, `None`
    /// when every corner is inside (nothing changes).
    #[inline(never)]
    fn clip<const PERSP: bool>(&mut self, plane: ClipPlane, s: &ClipSpace) -> Option<[Step; MAX]> {
        let n = self.n.min(MAX);
        let d: [i64; MAX] = core::array::from_fn(|i| {
            if i < n {
                plane.distance::<PERSP>(&self.c[i], s)
            } else {
                0
            }
        });
        if d[..n].iter().all(|&x| x >= 0) {
            return None;
        }
        let mut out = [self.c[0]; MAX];
        let mut steps = [Step::default(); MAX];
        let mut m = 0;
        for i in 0..n {
            // (i + 1) mod n without a division; indices below MAX (no panic path)
            let j = if i + 1 < n { i + 1 } else { 0 };
            let (pin, qin) = (d[i] >= 0, d[j] >= 0);
            if pin && m < MAX {
                out[m] = self.c[i];
                steps[m].a = i as u8;
                m += 1;
            }
            if pin != qin && m < MAX {
                (out[m], steps[m]) = cut((i, &self.c[i], d[i]), (j, &self.c[j], d[j]));
                m += 1;
            }
        }
        self.c = out;
        self.n = m;
        Some(steps)
    }
}

/// The point of segment `p`–`q` (corner index, clip coordinates, distance;
/// distances of opposite signs) on the plane, and how it is made, from the
/// endpoints in canonical order.
fn cut(p: (usize, &Clip, i64), q: (usize, &Clip, i64)) -> (Clip, Step) {
    let ((ia, ca, da), (ib, cb, db)) = if p.1 <= q.1 { (p, q) } else { (q, p) };
    // t = da / (da − db) ∈ [0, 1], both below 2^50: scaled to 32 bits
    let mut num = da.unsigned_abs();
    let mut den = (da - db).unsigned_abs();
    while den >> 32 != 0 {
        num >>= 1;
        den >>= 1;
    }
    let (num, den) = (num as u32, (den as u32).max(1));
    let num = num.min(den);
    let l = |x: i32, y: i32| lerp_i32(x, y, num, den);
    let c = Clip {
        x: l(ca.x, cb.x),
        y: l(ca.y, cb.y),
        z: l(ca.z, cb.z),
        w: l(ca.w, cb.w),
    };
    let step = Step {
        a: ia as u8,
        b: ib as u8,
        num,
        den,
    };
    (c, step)
}

/// `sign(a·b − c·d)` for differences of `i32` values (magnitudes below 2^32),
/// from 32-bit multiplications.
pub(crate) fn cmp_products(a: i64, b: i64, c: i64, d: i64) -> Ordering {
    let prod = |x: i64, y: i64| {
        let m = mul_u32(x.unsigned_abs() as u32, y.unsigned_abs() as u32);
        ((x < 0) != (y < 0) && m != 0, m)
    };
    let (n1, m1) = prod(a, b);
    let (n2, m2) = prod(c, d);
    match (n1, n2) {
        (false, true) => Ordering::Greater,
        (true, false) => Ordering::Less,
        (false, false) => m1.cmp(&m2),
        (true, true) => m2.cmp(&m1),
    }
}

/// The facing of a clip-space triangle: `Some(true)` for a front face
/// (counter-clockwise on the screen), `None` for zero area. `PERSP`: valid
/// for any signs of `w` (`sign det[x y w]`, exactly, in 128 bits: the rare
/// path only); else `w = 1` and it is the sign of the screen area (64-bit
/// values from 32-bit multiplications).
pub(crate) fn facing<const PERSP: bool>(c: [Clip; 3]) -> Option<bool> {
    if !PERSP {
        let d = |i: usize| {
            (
                i64::from(c[i].x) - i64::from(c[0].x),
                i64::from(c[i].y) - i64::from(c[0].y),
            )
        };
        let (d1, d2) = (d(1), d(2));
        // A = d1.x·d2.y − d1.y·d2.x: positive is clockwise (a back face)
        return match cmp_products(d1.0, d2.1, d1.1, d2.0) {
            Ordering::Greater => Some(false),
            Ordering::Less => Some(true),
            Ordering::Equal => None,
        };
    }
    let m = |a: i32, b: i32| i128::from(a) * i128::from(b);
    let det = i128::from(c[0].x) * (m(c[1].y, c[2].w) - m(c[2].y, c[1].w))
        - i128::from(c[0].y) * (m(c[1].x, c[2].w) - m(c[2].x, c[1].w))
        + i128::from(c[0].w) * (m(c[1].x, c[2].y) - m(c[2].x, c[1].y));
    // positive: clockwise on the screen (y points down), a back face
    match det.cmp(&0) {
        Ordering::Greater => Some(false),
        Ordering::Less => Some(true),
        Ordering::Equal => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    #[derive(Clone, Copy, Debug, PartialEq)]
    struct P(Clip);
    fn c(x: i32, y: i32, w: i32) -> P {
        P(Clip { x, y, z: 0, w })
    }
    /// The clip coordinates of triangle `t` clipped, each corner also
    /// carried as a value (the values must follow the cuts).
    fn poly<const PERSP: bool>(t: &[P; 3], s: &ClipSpace) -> Vec<P> {
        let lerp = |a: &Clip, b: &Clip, num: u32, den: u32| {
            let l = |x: i32, y: i32| lerp_i32(x, y, num, den);
            Clip {
                x: l(a.x, b.x),
                y: l(a.y, b.y),
                z: l(a.z, b.z),
                w: l(a.w, b.w),
            }
        };
        let (p, v) = clipped::<Clip, PERSP>(t.map(|p| p.0), &t.map(|p| p.0), lerp, s);
        assert_eq!(p.vertices(), &v[..p.vertices().len()]);
        p.vertices().iter().map(|&c| P(c)).collect()
    }
    const PERSP: ClipSpace = ClipSpace::perspective([1920, 1920], 1000);

    #[test]
    fn near_plane_cuts_are_canonical_and_on_the_plane() {
        let (a, b) = (c(-500, 300, -7000), c(900, -100, 40000));
        let t1 = poly::<true>(&[a, b, c(0, 5000, 30000)], &PERSP);
        let t2 = poly::<true>(&[b, a, c(7, -5000, 25000)], &PERSP);
        let on = |p: &Vec<P>| -> Vec<Clip> {
            p.iter()
                .map(|v| v.0)
                .filter(|v| (v.w - 1000).abs() <= 1)
                .collect()
        };
        let (c1, c2) = (on(&t1), on(&t2));
        // the cut of the shared edge a–b appears in both, bit for bit
        assert!(c1.iter().any(|p| c2.contains(p)), "{c1:?} {c2:?}");
        for v in t1.iter().chain(&t2) {
            assert!(v.0.w >= 999, "{v:?}");
        }
    }

    #[test]
    fn behind_the_eye_is_empty_and_the_window_holds() {
        assert!(poly::<true>(&[c(0, 0, -5), c(10, 0, -5), c(0, 10, -1)], &PERSP).is_empty());
        let far = poly::<true>(
            &[c(i32::MAX, 0, 1000), c(0, i32::MAX, 1000), c(0, 0, 1000)],
            &PERSP,
        );
        assert!(!far.is_empty());
        for v in &far {
            // on or inside the window up to the rounding of the cut
            let x = PERSP.screen::<true>(v.0).x;
            assert!(x <= WINDOW_MAX + 1, "{v:?} {x}");
        }
    }

    #[test]
    fn orthographic_clips_to_the_window_only() {
        let p = poly::<false>(
            &[c(-100_000, 0, 1), c(100, 0, 1), c(100, 200, 1)],
            &ClipSpace::SCREEN,
        );
        assert!(p.len() >= 3);
        for v in &p {
            assert!(v.0.x >= WINDOW_MIN - 1, "{v:?}");
        }
    }

    #[test]
    fn facing_matches_the_screen_orientation() {
        // counter-clockwise on a y-down screen: (0,0) → (0,10) → (10,0)
        let t = [c(0, 0, 1), c(0, 10, 1), c(10, 0, 1)].map(|p| p.0);
        assert_eq!(facing::<true>(t), Some(true));
        assert_eq!(facing::<false>(t), Some(true));
        assert_eq!(facing::<true>([t[0], t[2], t[1]]), Some(false));
        assert_eq!(facing::<false>([t[0], t[2], t[1]]), Some(false));
        // scaling a vertex by a positive w does not change it
        let s = [c(0, 0, 1), c(0, 70, 7), c(30, 0, 3)].map(|p| p.0);
        assert_eq!(facing::<true>(s), Some(true));
    }
}
