//! The one clipper: a triangle cut in clip space to the near plane (under a
//! perspective projection) and to the set-up window, before the division by
//! `w`, so that every point it projects lies in front of the eye and inside
//! the window where set-up works in 32-bit arithmetic.
//!
//! Clip coordinates ([`Clip`]) put a point on the screen at
//! `centre + (x/w, y/w)` sub-pixels. An orthographic transform has `w = 1`
//! and a zero centre: its clip coordinates are the screen position and depth
//! themselves, and the same planes cut it (the near plane never does).
//!
//! Every cut point is computed from its edge's endpoints in a canonical order
//! (the smaller clip coordinates first), so two triangles sharing an edge cut
//! it at bit-identical points: meshes stay watertight across the near plane
//! and the window's edges. Attributes are interpolated linearly in clip space
//! at a cut, which is the perspective-correct value there. The arithmetic uses
//! 64-bit values built from 32-bit operations ([`crate::num::wide`]) and, for
//! the facing of a triangle crossing the near plane, 128-bit products: the
//! rare path only.

use super::{WINDOW_MAX, WINDOW_MIN};
use crate::camera::Clip;
use crate::num::wide::lerp_i32;

/// At most 3 + 5 vertices: each plane adds at most one.
pub(crate) const MAX: usize = 8;

/// Where clip coordinates land on the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ClipSpace {
    /// The screen position of `x = y = 0`, in sub-pixels.
    pub centre: [i32; 2],
    /// The near plane in `w` units (at least 1).
    pub near: i32,
    /// Whether `w` varies (a perspective projection: `z/w` is the depth
    /// in `[−1, 1]`); else `w = 1` and `z` is the depth in `0..=65535`.
    pub perspective: bool,
}

/// A point on the screen after clipping: sub-pixel position inside the
/// window, depth, and the clip `w` (1 for an orthographic projection).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Screen {
    pub x: i32,
    pub y: i32,
    pub z: u16,
    pub w: i32,
}

impl ClipSpace {
    /// The screen position of clip coordinates `c` (with `w ≥ 1` under a
    /// perspective projection), clamped to the window.
    pub(crate) fn screen(&self, c: Clip) -> Screen {
        let clamp = |v: i64| v.clamp(i64::from(WINDOW_MIN), i64::from(WINDOW_MAX)) as i32;
        if self.perspective {
            let w = i64::from(c.w.max(1));
            let z = div_round((i64::from(c.z) + w) * 65535, 2 * w);
            Screen {
                x: clamp(i64::from(self.centre[0]) + div_round(i64::from(c.x), w)),
                y: clamp(i64::from(self.centre[1]) + div_round(i64::from(c.y), w)),
                z: z.clamp(0, 65535) as u16,
                w: c.w.max(1),
            }
        } else {
            Screen {
                x: clamp(i64::from(c.x)),
                y: clamp(i64::from(c.y)),
                z: c.z.clamp(0, 65535) as u16,
                w: 1,
            }
        }
    }
}

/// `round(n / d)` (halves away from zero) for `d > 0`.
#[inline]
pub(crate) fn div_round(n: i64, d: i64) -> i64 {
    let q = (2 * n.unsigned_abs() + d as u64) / (2 * d as u64);
    if n < 0 {
        -(q as i64)
    } else {
        q as i64
    }
}

/// A vertex the clipper can cut edges at.
pub(crate) trait ClipPoint: Copy {
    /// The clip coordinates.
    fn clip(&self) -> Clip;
    /// The point `num/den` of the way from `self` to `other` (`num ≤ den`),
    /// with clip coordinates `c`.
    fn cut(&self, other: &Self, num: u32, den: u32, c: Clip) -> Self;
}

/// The planes, as signed distances (inside: ≥ 0).
#[derive(Clone, Copy)]
enum Plane {
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

impl Plane {
    /// The signed distance of `c` (exact: every product below 2^48).
    #[inline]
    fn distance(self, c: &Clip, s: &ClipSpace) -> i64 {
        let w = i64::from(c.w);
        let lo = |centre: i32| (i64::from(WINDOW_MIN) - i64::from(centre)) * w;
        let hi = |centre: i32| (i64::from(WINDOW_MAX) - i64::from(centre)) * w;
        match self {
            Plane::Near => w - i64::from(s.near),
            Plane::XMin => i64::from(c.x) - lo(s.centre[0]),
            Plane::XMax => hi(s.centre[0]) - i64::from(c.x),
            Plane::YMin => i64::from(c.y) - lo(s.centre[1]),
            Plane::YMax => hi(s.centre[1]) - i64::from(c.y),
        }
    }
}

/// A convex polygon in clip space.
pub(crate) struct Polygon<V: ClipPoint> {
    v: [V; MAX],
    n: usize,
}

impl<V: ClipPoint> Polygon<V> {
    /// Triangle `t` clipped to the near plane (perspective) and the window.
    pub(crate) fn clipped(t: &[V; 3], s: &ClipSpace) -> Self {
        let mut v = [t[0]; MAX];
        v[..3].copy_from_slice(t);
        let mut p = Polygon { v, n: 3 };
        let planes = [
            Plane::Near,
            Plane::XMin,
            Plane::XMax,
            Plane::YMin,
            Plane::YMax,
        ];
        for plane in planes.iter().skip(usize::from(!s.perspective)) {
            if p.n < 3 {
                break;
            }
            p.clip(*plane, s);
        }
        if p.n < 3 {
            p.n = 0;
        }
        p
    }

    /// The vertices.
    pub(crate) fn vertices(&self) -> &[V] {
        self.v.get(..self.n).unwrap_or(&[])
    }

    fn clip(&mut self, plane: Plane, s: &ClipSpace) {
        let n = self.n.min(MAX);
        let d: [i64; MAX] = core::array::from_fn(|i| {
            if i < n {
                plane.distance(&self.v[i].clip(), s)
            } else {
                0
            }
        });
        if d[..n].iter().all(|&x| x >= 0) {
            return;
        }
        let mut out = [self.v[0]; MAX];
        let mut m = 0;
        for i in 0..n {
            // (i + 1) mod n without a division; indices below MAX (no panic path)
            let j = if i + 1 < n { i + 1 } else { 0 };
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
fn cut<V: ClipPoint>(p: &V, dp: i64, q: &V, dq: i64) -> V {
    let ((a, da), (b, db)) = if p.clip() <= q.clip() {
        ((p, dp), (q, dq))
    } else {
        ((q, dq), (p, dp))
    };
    // t = da / (da − db) ∈ [0, 1], both below 2^50: scaled to 32 bits
    let mut num = da.unsigned_abs();
    let mut den = (da - db).unsigned_abs();
    while den >> 32 != 0 {
        num >>= 1;
        den >>= 1;
    }
    let (num, den) = (num as u32, (den as u32).max(1));
    let num = num.min(den);
    let (ca, cb) = (a.clip(), b.clip());
    let l = |x: i32, y: i32| lerp_i32(x, y, num, den);
    let c = Clip {
        x: l(ca.x, cb.x),
        y: l(ca.y, cb.y),
        z: l(ca.z, cb.z),
        w: l(ca.w, cb.w),
    };
    a.cut(b, num, den, c)
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
    impl ClipPoint for P {
        fn clip(&self) -> Clip {
            self.0
        }
        fn cut(&self, _: &Self, _: u32, _: u32, c: Clip) -> Self {
            P(c)
        }
    }
    fn c(x: i32, y: i32, w: i32) -> P {
        P(Clip { x, y, z: 0, w })
    }
    const PERSP: ClipSpace = ClipSpace {
        centre: [1920, 1920],
        near: 1000,
        perspective: true,
    };

    #[test]
    fn near_plane_cuts_are_canonical_and_on_the_plane() {
        let (a, b) = (c(-500, 300, -7000), c(900, -100, 40000));
        let t1 = Polygon::clipped(&[a, b, c(0, 5000, 30000)], &PERSP);
        let t2 = Polygon::clipped(&[b, a, c(7, -5000, 25000)], &PERSP);
        let on = |p: &Polygon<P>| -> Vec<Clip> {
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
    fn behind_the_eye_is_empty_and_the_window_holds() {
        assert!(
            Polygon::clipped(&[c(0, 0, -5), c(10, 0, -5), c(0, 10, -1)], &PERSP)
                .vertices()
                .is_empty()
        );
        let far = Polygon::clipped(
            &[c(i32::MAX, 0, 1000), c(0, i32::MAX, 1000), c(0, 0, 1000)],
            &PERSP,
        );
        assert!(!far.vertices().is_empty());
        for v in far.vertices() {
            let s = PERSP.screen(v.0);
            assert!((WINDOW_MIN..=WINDOW_MAX).contains(&s.x), "{v:?}");
            // on or inside the window up to the rounding of the cut (1 unit of w)
            let x = PERSP.centre[0] as i64 + div_round(v.0.x as i64, v.0.w as i64);
            assert!(x <= WINDOW_MAX as i64 + 1, "{v:?} {x}");
        }
    }

    #[test]
    fn orthographic_clips_to_the_window_only() {
        let ortho = ClipSpace {
            centre: [0, 0],
            near: 1,
            perspective: false,
        };
        let p = Polygon::clipped(&[c(-100_000, 0, 1), c(100, 0, 1), c(100, 200, 1)], &ortho);
        assert!(p.vertices().len() >= 3);
        for v in p.vertices() {
            assert!(v.0.x >= WINDOW_MIN - 1, "{v:?}");
        }
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
