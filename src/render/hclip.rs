//! Clipping in clip space for perspective meshes: a triangle is cut to the
//! near plane and to the guard band before the division by `w`, so that every
//! point it projects lies in front of the eye and within `i32` sub-pixels.
//!
//! As in the window clipper ([`crate::raster::clip`]), every cut point is
//! computed from its edge's endpoints in a fixed order (the smaller clip
//! coordinates first), so two triangles sharing an edge cut it at
//! bit-identical points: the mesh stays watertight across the near plane.

use crate::camera::{Clip, GUARD};
use crate::num::wide::lerp_i32;

/// At most 3 + 5 vertices: each plane adds at most one.
pub(crate) const MAX: usize = 8;

/// A vertex the clip-space clipper can cut edges at.
pub(crate) trait HPoint: Copy {
    /// The clip coordinates.
    fn clip(&self) -> Clip;
    /// The point `num/den` of the way from `self` to `other` (`num ≤ den`),
    /// with clip coordinates `c`.
    fn hcut(&self, other: &Self, num: u32, den: u32, c: Clip) -> Self;
}

/// The planes, as signed distances (inside: ≥ 0).
#[derive(Clone, Copy)]
enum Plane {
    /// `w ≥ near`.
    Near(i32),
    /// `x ≥ −G·w`.
    XMin,
    /// `x ≤ G·w`.
    XMax,
    /// `y ≥ −G·w`.
    YMin,
    /// `y ≤ G·w`.
    YMax,
}

impl Plane {
    #[inline]
    fn distance(self, c: &Clip) -> i64 {
        let gw = i64::from(GUARD) * i64::from(c.w);
        match self {
            Plane::Near(n) => i64::from(c.w) - i64::from(n),
            Plane::XMin => i64::from(c.x) + gw,
            Plane::XMax => gw - i64::from(c.x),
            Plane::YMin => i64::from(c.y) + gw,
            Plane::YMax => gw - i64::from(c.y),
        }
    }
}

/// A convex polygon in clip space.
pub(crate) struct HPolygon<V: HPoint> {
    v: [V; MAX],
    n: usize,
}

impl<V: HPoint> HPolygon<V> {
    /// Triangle `t` clipped to the near plane `w ≥ near` and the guard band.
    pub(crate) fn clipped(t: &[V; 3], near: i32) -> Self {
        let mut v = [t[0]; MAX];
        v[..3].copy_from_slice(t);
        let mut p = HPolygon { v, n: 3 };
        for plane in [
            Plane::Near(near),
            Plane::XMin,
            Plane::XMax,
            Plane::YMin,
            Plane::YMax,
        ] {
            if p.n < 3 {
                p.n = 0;
                break;
            }
            p.clip(plane);
        }
        if p.n < 3 {
            p.n = 0;
        }
        p
    }

    /// The vertices.
    pub(crate) fn vertices(&self) -> &[V] {
        &self.v[..self.n]
    }

    fn clip(&mut self, plane: Plane) {
        let d: [i64; MAX] = core::array::from_fn(|i| {
            if i < self.n {
                plane.distance(&self.v[i].clip())
            } else {
                0
            }
        });
        if d[..self.n].iter().all(|&x| x >= 0) {
            return;
        }
        let mut out = [self.v[0]; MAX];
        let mut m = 0;
        for i in 0..self.n {
            let j = (i + 1) % self.n;
            let (pin, qin) = (d[i] >= 0, d[j] >= 0);
            if pin && m < MAX {
                out[m] = self.v[i];
                m += 1;
            }
            if pin != qin && m < MAX {
                out[m] = cut(&self.v[i], d[i], &self.v[j], d[j]);
                m += 1;
            }
        }
        self.v = out;
        self.n = m;
    }
}

/// The point of segment `p`–`q` on the plane (distances `dp`, `dq` of opposite
/// signs), from the endpoints in canonical order.
fn cut<V: HPoint>(p: &V, dp: i64, q: &V, dq: i64) -> V {
    let ((a, da), (b, db)) = if p.clip() <= q.clip() {
        ((p, dp), (q, dq))
    } else {
        ((q, dq), (p, dp))
    };
    // t = da / (da − db) ∈ [0, 1], both below 2^60: scaled to 32 bits
    let mut num = da.unsigned_abs();
    let mut den = (da - db).unsigned_abs();
    while den >> 32 != 0 {
        num >>= 1;
        den >>= 1;
    }
    let (num, den) = (num as u32, (den as u32).max(1));
    let (ca, cb) = (a.clip(), b.clip());
    let l = |x: i32, y: i32| lerp_i32(x, y, num.min(den), den);
    let c = Clip {
        x: l(ca.x, cb.x),
        y: l(ca.y, cb.y),
        z: l(ca.z, cb.z),
        w: l(ca.w, cb.w),
    };
    a.hcut(b, num.min(den), den, c)
}

/// The facing of a clip-space triangle, valid for any signs of `w`: `Some(true)`
/// for a front face (counter-clockwise on the screen), `None` for zero area
/// (`sign det[x y w]`, exactly, in 128 bits: the rare path only).
pub(crate) fn facing(c: [Clip; 3]) -> Option<bool> {
    let m = |a: i32, b: i32| i128::from(a) * i128::from(b);
    let det = i128::from(c[0].x) * (m(c[1].y, c[2].w) - m(c[2].y, c[1].w))
        - i128::from(c[0].y) * (m(c[1].x, c[2].w) - m(c[2].x, c[1].w))
        + i128::from(c[0].w) * (m(c[1].x, c[2].y) - m(c[2].x, c[1].y));
    // positive: clockwise on the screen (y points down), a back face
    match det.cmp(&0) {
        core::cmp::Ordering::Greater => Some(false),
        core::cmp::Ordering::Less => Some(true),
        core::cmp::Ordering::Equal => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    #[derive(Clone, Copy, Debug, PartialEq)]
    struct P(Clip);
    impl HPoint for P {
        fn clip(&self) -> Clip {
            self.0
        }
        fn hcut(&self, _: &Self, _: u32, _: u32, c: Clip) -> Self {
            P(c)
        }
    }
    fn c(x: i32, y: i32, w: i32) -> P {
        P(Clip { x, y, z: 0, w })
    }

    #[test]
    fn near_plane_cuts_are_canonical_and_on_the_plane() {
        let (a, b) = (c(-500, 300, -7000), c(900, -100, 40000));
        let t1 = HPolygon::clipped(&[a, b, c(0, 5000, 30000)], 1000);
        let t2 = HPolygon::clipped(&[b, a, c(7, -5000, 25000)], 1000);
        let on = |p: &HPolygon<P>| -> Vec<Clip> {
            p.vertices()
                .iter()
                .map(|v| v.0)
                .filter(|v| (v.w - 1000).abs() <= 1)
                .collect()
        };
        let (c1, c2) = (on(&t1), on(&t2));
        // the cut of the shared edge a–b appears in both, bit for bit
        assert!(c1.iter().any(|p| c2.contains(p)), "{c1:?} {c2:?}");
        for v in t1.vertices().iter().chain(t2.vertices()) {
            assert!(v.0.w >= 999, "{v:?}");
        }
    }

    #[test]
    fn behind_the_eye_is_empty_and_guard_band_holds() {
        assert!(
            HPolygon::clipped(&[c(0, 0, -5), c(10, 0, -5), c(0, 10, -1)], 1)
                .vertices()
                .is_empty()
        );
        let far = HPolygon::clipped(&[c(i32::MAX, 0, 1), c(0, i32::MAX, 1), c(0, 0, 1000)], 1);
        for v in far.vertices() {
            // within the guard band up to the rounding of w (½ unit)
            let g = i64::from(GUARD) * (i64::from(v.0.w) + 1);
            assert!(
                i64::from(v.0.x).abs() <= g && i64::from(v.0.y).abs() <= g,
                "{v:?}"
            );
        }
        assert!(!far.vertices().is_empty());
    }

    #[test]
    fn facing_matches_the_screen_orientation() {
        // counter-clockwise on a y-down screen: (0,0) → (0,10) → (10,0)
        let t = [c(0, 0, 1), c(0, 10, 1), c(10, 0, 1)].map(|p| p.0);
        assert_eq!(facing(t), Some(true));
        assert_eq!(facing([t[0], t[2], t[1]]), Some(false));
        // scaling a vertex by a positive w does not change it
        let s = [c(0, 0, 1), c(0, 70, 7), c(30, 0, 3)].map(|p| p.0);
        assert_eq!(facing(s), Some(true));
    }
}
