//! Clipping a triangle to the set-up window (Sutherland–Hodgman against the
//! four window lines), for triangles reaching beyond it.
//!
//! Every cut point is computed from its edge's two endpoints taken in a fixed
//! order (the lexicographically smaller `(x, y)` first), so two triangles that
//! share an edge get bit-identical cut points on it and stay watertight. The
//! arithmetic is exact to rounding for any `i32` coordinates and uses 64-bit
//! values built from 32-bit operations ([`crate::num::wide`]).

use super::{RasterVertex, WINDOW_MAX, WINDOW_MIN};
use crate::num::wide::{lerp_i32, mul_u32};
use core::cmp::Ordering;

/// At most 3 + 4 vertices: each window line adds at most one.
const MAX: usize = 7;

/// A vertex the clipper can cut edges at.
pub(crate) trait ClipPoint: Copy {
    /// The sub-pixel position.
    fn xy(&self) -> (i32, i32);
    /// The point `num/den` of the way from `self` to `other` (`num ≤ den`),
    /// with its position set to `xy`.
    fn cut(&self, other: &Self, num: u32, den: u32, xy: (i32, i32)) -> Self;
}

/// A rasterizer vertex, attributes screen-linear (`PERSP = false`) or
/// perspective-correct.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cut<const N: usize, const PERSP: bool>(pub(crate) RasterVertex<N>);

impl<const N: usize, const PERSP: bool> ClipPoint for Cut<N, PERSP> {
    #[inline]
    fn xy(&self) -> (i32, i32) {
        (self.0.x, self.0.y)
    }

    fn cut(&self, other: &Self, num: u32, den: u32, xy: (i32, i32)) -> Self {
        let (a, b) = (&self.0, &other.0);
        let mut c = *a;
        let lerp = |x: i32, y: i32| lerp_i32(x, y, num, den);
        (c.x, c.y) = xy;
        c.z = lerp(i32::from(a.z), i32::from(b.z)) as u16;
        c.inv_w = lerp(a.inv_w, b.inv_w).max(1);
        if PERSP {
            // the attribute parameter s = t·q_b / (t·q_b + (1 − t)·q_a)
            let qa = a.inv_w.max(1) as u32;
            let qb = b.inv_w.max(1) as u32;
            let mut sn = mul_u32(num, qb);
            let mut sd = sn + mul_u32(den - num, qa);
            while sd >> 32 != 0 {
                sn >>= 1;
                sd >>= 1;
            }
            let (sn, sd) = (sn as u32, (sd as u32).max(1));
            for (o, (&x, &y)) in c.attrs.iter_mut().zip(a.attrs.iter().zip(b.attrs.iter())) {
                *o = lerp_i32(x, y, sn, sd);
            }
        } else {
            for (o, (&x, &y)) in c.attrs.iter_mut().zip(a.attrs.iter().zip(b.attrs.iter())) {
                *o = lerp(x, y);
            }
        }
        Cut(c)
    }
}

/// A convex polygon in screen space.
pub(crate) struct Polygon<V: ClipPoint> {
    v: [V; MAX],
    n: usize,
}

/// `sign(a·b − c·d)` for differences of `i32` values (magnitudes below 2^32).
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

/// Which side of a window line.
#[derive(Clone, Copy)]
enum Line {
    XMin,
    XMax,
    YMin,
    YMax,
}

impl Line {
    #[inline]
    fn inside(self, (x, y): (i32, i32)) -> bool {
        match self {
            Line::XMin => x >= WINDOW_MIN,
            Line::XMax => x <= WINDOW_MAX,
            Line::YMin => y >= WINDOW_MIN,
            Line::YMax => y <= WINDOW_MAX,
        }
    }

    /// The coordinate this line constrains, and the line's value.
    #[inline]
    fn coord(self, (x, y): (i32, i32)) -> (i32, i32) {
        match self {
            Line::XMin => (x, WINDOW_MIN),
            Line::XMax => (x, WINDOW_MAX),
            Line::YMin => (y, WINDOW_MIN),
            Line::YMax => (y, WINDOW_MAX),
        }
    }
}

impl<V: ClipPoint> Polygon<V> {
    pub(crate) fn new(t: &[V; 3]) -> Self {
        let mut v = [t[0]; MAX];
        v[..3].copy_from_slice(t);
        Polygon { v, n: 3 }
    }

    /// `Some(true)` for a front face (counter-clockwise on the screen),
    /// `Some(false)` for a back face, `None` for zero area.
    pub(crate) fn facing(&self) -> Option<bool> {
        let d = |i: usize, j: usize| {
            let (a, b) = (self.v[i].xy(), self.v[j].xy());
            (
                i64::from(b.0) - i64::from(a.0),
                i64::from(b.1) - i64::from(a.1),
            )
        };
        let (d1, d2) = (d(0, 1), d(0, 2));
        // A = d1.x·d2.y − d1.y·d2.x: positive is clockwise (a back face)
        match cmp_products(d1.0, d2.1, d1.1, d2.0) {
            Ordering::Greater => Some(false),
            Ordering::Less => Some(true),
            Ordering::Equal => None,
        }
    }

    /// Clips to the window.
    pub(crate) fn clip_to_window(&mut self) {
        for line in [Line::XMin, Line::XMax, Line::YMin, Line::YMax] {
            if self.n < 3 {
                return;
            }
            self.clip(line);
        }
    }

    fn clip(&mut self, line: Line) {
        let mut out = [self.v[0]; MAX];
        let mut m = 0;
        let n = self.n.min(MAX);
        for i in 0..n {
            // (i + 1) mod n without a division; indices below MAX (no panic path)
            let (p, q) = (self.v[i], self.v[if i + 1 < n { i + 1 } else { 0 }]);
            let (pin, qin) = (line.inside(p.xy()), line.inside(q.xy()));
            if pin && m < MAX {
                out[m] = p;
                m += 1;
            }
            if pin != qin && m < MAX {
                out[m] = Self::cut(&p, &q, line);
                m += 1;
            }
        }
        self.v = out;
        self.n = m;
    }

    /// The point of segment `p`–`q` on `line` (the endpoints are on opposite
    /// sides), from the endpoints in canonical order.
    fn cut(p: &V, q: &V, line: Line) -> V {
        let (a, b) = if p.xy() <= q.xy() { (p, q) } else { (q, p) };
        let (pa, pb) = (a.xy(), b.xy());
        let (ca, at) = line.coord(pa);
        let (cb, _) = line.coord(pb);
        // t = (at − ca) / (cb − ca) ∈ [0, 1]
        let num = (i64::from(at) - i64::from(ca)).unsigned_abs() as u32;
        let den = (i64::from(cb) - i64::from(ca)).unsigned_abs() as u32;
        let lerp = |x: i32, y: i32| lerp_i32(x, y, num, den);
        let xy = match line {
            Line::XMin | Line::XMax => (at, lerp(pa.1, pb.1)),
            Line::YMin | Line::YMax => (lerp(pa.0, pb.0), at),
        };
        a.cut(b, num, den, xy)
    }

    /// Triangle `k` of the fan from vertex 0; `false` when there is none.
    pub(crate) fn fan(&self, k: usize, tri: &mut [V; 3]) -> bool {
        match (self.v.get(k + 1), self.v.get(k + 2)) {
            (Some(&b), Some(&c)) if k + 2 < self.n => {
                *tri = [self.v[0], b, c];
                true
            }
            _ => false,
        }
    }
}
