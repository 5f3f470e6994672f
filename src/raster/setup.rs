//! Triangle set-up in 32-bit arithmetic: orientation, culling, the barycentric
//! coefficients (one reciprocal of the area per triangle) and attribute planes.
//!
//! Every product is a 32 × 32 → 32-bit `MULS` that cannot overflow: within
//! the [window](super::WINDOW_MIN) coordinate differences are below 2^15 and
//! edge-function products below 2^30. The only division is the area's
//! reciprocal.

pub(crate) use crate::num::at3;

use super::{Cull, SUBPIXEL_BITS};

pub use crate::num::ATTR_FRAC;

/// Number of significant bits of `|x|` (0 for 0): `32 − leading_zeros`, without
/// a library call on cores lacking a count-leading-zeros instruction.
#[inline]
pub(crate) fn bit_length(x: u32) -> u32 {
    let mut x = x;
    let mut n = 0;
    if x >= 1 << 16 {
        x >>= 16;
        n += 16;
    }
    if x >= 1 << 8 {
        x >>= 8;
        n += 8;
    }
    if x >= 1 << 4 {
        x >>= 4;
        n += 4;
    }
    if x >= 1 << 2 {
        x >>= 2;
        n += 2;
    }
    if x >= 1 << 1 {
        x >>= 1;
        n += 1;
    }
    n + x
}

/// The vertex after `i` in the triangle's order: `(i + 1) mod 3` without a
/// division (a library call on a Cortex-M0).
#[inline(always)]
pub(crate) fn next3(i: usize) -> usize {
    if i >= 2 {
        0
    } else {
        i + 1
    }
}

/// `v · 2^s` for a signed shift `s`: a right shift rounds to nearest, a left
/// shift saturates at ±2^30 (gradients of triangles smaller than a pixel).
#[inline]
pub(crate) fn scale(v: i32, s: i32) -> i32 {
    if s <= 0 {
        let r = (-s) as u32;
        if r == 0 {
            v
        } else if r >= 31 {
            0
        } else {
            // (v + half) >> r without overflow: halve first (callers pass
            // |v| < 2^31 − 1: a sum of two products below 2^30 each)
            ((v >> (r - 1)) + 1) >> 1
        }
    } else if s >= 30 {
        if v > 0 {
            1 << 30
        } else if v < 0 {
            -(1 << 30)
        } else {
            0
        }
    } else {
        let lim = (1i32 << 30) >> s;
        if v >= lim {
            1 << 30
        } else if v <= -lim {
            -(1 << 30)
        } else {
            v << s
        }
    }
}

/// A triangle whose vertices lie in the window, oriented so that its doubled
/// area is positive, with the barycentric coefficients of its plane (opaque:
/// made by the rasterizer, read by the shading kernels).
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    /// Sub-pixel positions, oriented (`A > 0`: clockwise on a y-down screen).
    pub(crate) xy: [(i32, i32); 3],
    /// Which input vertex each oriented vertex is.
    pub(crate) order: [usize; 3],
    /// Index (into `xy`) of the top, middle and bottom vertex (by `y`).
    pub(crate) tmb: [usize; 3],
    /// First and last pixel row whose centre lies in `[y_top, y_bottom]`.
    pub(crate) rows: (i32, i32),
    /// Barycentric coefficients relative to the top vertex.
    pub(crate) bary: Bary,
}

/// `∂β/∂X` and `∂β/∂Y` (per sub-pixel) of the barycentric weights of the two
/// vertices other than the top one, as `C · 2^−k` with `|C| < 2^14`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Bary {
    /// The two vertices (indices into `Setup::xy`) whose weights these are.
    pub(crate) other: [usize; 2],
    c1x: i32,
    c2x: i32,
    c1y: i32,
    c2y: i32,
    /// `ATTR_FRAC + SUBPIXEL_BITS − k`: a gradient `G` is `G·2^s` per pixel.
    s: i32,
    /// The reference pixel centre `(c0, rows.0)` relative to the top vertex:
    /// `dxs` sub-pixels (in −8..8) across, `rows` whole rows and `rem`
    /// sub-pixels (in 0..16) down.
    c0: i32,
    dxs: i32,
    rows: i32,
    rem: i32,
    /// Bounding-box width and height in pixels, plus slack (for error bounds).
    w: u32,
    h: u32,
}

impl Bary {
    /// The barycentric coefficients of the oriented triangle `xy` relative to
    /// its top vertex `t`, whose pixel rows are `rows` (one reciprocal, no
    /// division).
    #[inline(always)]
    fn new(xy: &[(i32, i32); 3], t: usize, rows: (i32, i32)) -> Bary {
        let (i1, i2) = (next3(t), next3(next3(t)));
        let (o, p1, p2) = (at3(xy, t), at3(xy, i1), at3(xy, i2));
        let d1 = (p1.0 - o.0, p1.1 - o.1);
        let d2 = (p2.0 - o.0, p2.1 - o.1);
        // A' = d1 × d2 = the doubled area (the orientation is kept by rotation)
        let a = d1.0 * d2.1 - d1.1 * d2.0;
        // 1/A' ≈ R·2^−(31 + sh) with a_n = A' / 2^sh in [2^15, 2^16)
        let bits = bit_length(a as u32) as i32;
        let sh = bits - 16;
        let an = if sh >= 0 { a >> sh } else { a << -sh };
        // R in (2^15, 2^16]: relative error ≤ 2^−15 each for a_n and R
        // (`an` ≥ 2^15 for a triangle with an area: `max(1)` only drops the panic path)
        // (exactly the quotient, without a library division)
        let r = crate::num::recip::div_2p31(an as u32) as i32;
        // ∂β1/∂X = d2.y/A', ∂β2/∂X = −d1.y/A', ∂β1/∂Y = −d2.x/A', ∂β2/∂Y = d1.x/A'
        // |d|·R < 2^15·2^16 = 2^31
        let raw = [d2.1 * r, -(d1.1 * r), -(d2.0 * r), d1.0 * r];
        let m = raw.iter().fold(0u32, |m, &c| m.max(c.unsigned_abs()));
        // |C| < 2^14
        let shift = (bit_length(m) as i32 - 14).max(0);
        let c = raw.map(|v| scale(v, -shift));
        let k = 31 + sh - shift;
        let half = 1 << (SUBPIXEL_BITS - 1);
        let c0 = o.0 >> SUBPIXEL_BITS;
        let dys = (rows.0 << SUBPIXEL_BITS) + half - o.1;
        Bary {
            other: [i1, i2],
            c1x: c[0],
            c2x: c[1],
            c1y: c[2],
            c2y: c[3],
            s: ATTR_FRAC as i32 + SUBPIXEL_BITS as i32 - k,
            c0,
            dxs: (c0 << SUBPIXEL_BITS) + half - o.0,
            rows: dys >> SUBPIXEL_BITS,
            rem: dys & ((1 << SUBPIXEL_BITS) - 1),
            w: {
                let (x0, x1) = (o.0.min(p1.0).min(p2.0), o.0.max(p1.0).max(p2.0));
                ((x1 - x0) >> SUBPIXEL_BITS) as u32 + 2
            },
            h: (rows.1 - rows.0).max(0) as u32 + 3,
        }
    }
}

impl Setup {
    /// Orients and culls three sub-pixel positions already inside the window.
    /// `None` for zero-area or culled triangles; else with its barycentric
    /// coefficients (one reciprocal, no division).
    #[inline(always)]
    pub(crate) fn new(p: [(i32, i32); 3], cull: Cull) -> Option<Setup> {
        // A = (x1 − x0)(y2 − y0) − (y1 − y0)(x2 − x0): each product < 2^30
        let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
        let front = area < 0;
        let culled = match cull {
            Cull::None => false,
            Cull::Back => !front,
            Cull::Front => front,
        };
        if area == 0 || culled {
            return None;
        }
        let (xy, order) = if area < 0 {
            ([p[0], p[2], p[1]], [0, 2, 1])
        } else {
            (p, [0, 1, 2])
        };
        // sort by y: t ≤ m ≤ b
        let (mut t, mut m, mut b) = (0usize, 1usize, 2usize);
        if xy[m].1 < xy[t].1 {
            core::mem::swap(&mut t, &mut m);
        }
        if xy[b].1 < xy[m].1 {
            core::mem::swap(&mut m, &mut b);
        }
        if xy[m].1 < xy[t].1 {
            core::mem::swap(&mut t, &mut m);
        }
        let half = 1 << (SUBPIXEL_BITS - 1);
        // rows whose centre Y = 16y + 8 lies in [y_t, y_b]
        let first = (xy[t].1 - half + (1 << SUBPIXEL_BITS) - 1) >> SUBPIXEL_BITS;
        let last = (xy[b].1 - half) >> SUBPIXEL_BITS;
        let rows = (first, last);
        Some(Setup {
            xy,
            order,
            tmb: [t, m, b],
            rows,
            // built in place (a default first was a memclr per triangle)
            bary: Bary::new(&xy, t, rows),
        })
    }

    /// An upper bound of `|computed − exact|` (in the plane's units) of every
    /// value a [`Plane`] of this triangle yields at a pixel inside the
    /// triangle, reached by stepping rows and columns from its reference pixel
    /// without clamping.
    ///
    /// Each coefficient `C` is within 1.5 of its exact value (the normalised
    /// area and its reciprocal carry 2^−15 relative error each, `C` is
    /// rounded), so the per-pixel gradients are off by at most
    /// `ε = ½ + 1.5·2^s·spread` (`spread = |Δa₁| + |Δa₂|` of the plane); over
    /// the bounding box (`w` columns, `h` rows from the reference pixel) and
    /// with the reference value's own rounding (< 24 units) the error is below
    /// `ε·(w + h) + 24`. Computed generously, saturating.
    ///
    /// A plane whose gradient saturated at ±2^30 ([`scale`]: a sliver across
    /// which the attribute changes by over four units of its range per pixel)
    /// has no bound, `u32::MAX`, so its values are clamped to the vertex range
    /// (fuzz target `surface`).
    #[inline]
    pub(crate) fn err(&self, p: &Plane) -> u32 {
        if p.dx.unsigned_abs() >= 1 << 30 || p.dy.unsigned_abs() >= 1 << 30 {
            return u32::MAX;
        }
        let b = &self.bary;
        let spread3 = mul_bound(3, p.spread);
        // 1.5·2^s·spread = 3·spread·2^(s − 1), rounded up
        let s = b.s - 1;
        let g = if s >= 0 {
            if s >= 31 || spread3 > (u32::MAX >> s) {
                u32::MAX
            } else {
                spread3 << s
            }
        } else {
            let r = (-s) as u32;
            if r >= 32 {
                1
            } else {
                (spread3 >> r) + 1
            }
        };
        mul_bound(g.saturating_add(1), b.w + b.h).saturating_add(24)
    }

    /// The plane of an attribute with values `a` at the oriented vertices
    /// (`a[i]` belongs to `xy[i]`), relative to the top vertex's value, in
    /// `2^ATTR_FRAC` units of `a >> sa`, where `sa` is chosen so that the
    /// differences fit 16 bits (0 for differences below 2^16). The row value
    /// is positioned at the triangle's first row, column 0 (computed at the
    /// top vertex's column `c0` and carried to column 0, wrapping).
    #[inline]
    pub(crate) fn plane(&self, a: [i32; 3]) -> Plane {
        let b = &self.bary;
        let t = self.tmb[0];
        // differences may need 32 bits (attributes in ±2^30)
        let at = at3(&a, t);
        let d1 = at3(&a, b.other[0]).wrapping_sub(at);
        let d2 = at3(&a, b.other[1]).wrapping_sub(at);
        let fits = |d: i32| (d as u32).wrapping_add(1 << 16) < (1 << 17);
        let sa = if fits(d1) && fits(d2) {
            0
        } else {
            let big = d1.unsigned_abs().max(d2.unsigned_abs());
            (bit_length(big) as i32 - 16).max(0)
        };
        let (d1, d2) = (d1 >> sa, d2 >> sa);
        // |d|·|C| < 2^16·2^14: each product < 2^30, the sum < 2^31
        let gx = d1 * b.c1x + d2 * b.c2x;
        let gy = d1 * b.c1y + d2 * b.c2y;
        // per pixel: G·2^s
        let dx = scale(gx, b.s);
        let dy = scale(gy, b.s);
        // value at (c0, rows.0) relative to the top vertex: per sub-pixel
        // gradients times the offsets, whole rows by the row step
        let v = ((dx >> SUBPIXEL_BITS) * b.dxs)
            .wrapping_add((dy >> SUBPIXEL_BITS) * b.rem)
            .wrapping_add(dy.wrapping_mul(b.rows));
        let lo = 0.min(d1).min(d2);
        let hi = 0.max(d1).max(d2);
        Plane {
            row: v.wrapping_sub(dx.wrapping_mul(b.c0)),
            dx,
            dy,
            lo: lo << ATTR_FRAC,
            hi: hi << ATTR_FRAC,
            spread: d1.unsigned_abs() + d2.unsigned_abs(),
        }
    }
}

impl Setup {
    /// The reciprocal of the doubled area for [`Setup::plane_exact`]:
    /// `(R, b)` with `R = ⌊(2^(31 + b) − 1) / A'⌋` (in `[2^31, 2^32)`), `b`
    /// the bit length of `A'`. One bit-serial division.
    #[inline(never)]
    pub(crate) fn exact_recip(&self) -> (u32, u32) {
        let t = self.tmb[0];
        let (o, p1, p2) = (
            at3(&self.xy, t),
            at3(&self.xy, self.bary.other[0]),
            at3(&self.xy, self.bary.other[1]),
        );
        // A' = D1 × D2 > 0 (oriented), each product below 2^30
        let a = ((p1.0 - o.0) * (p2.1 - o.1) - (p1.1 - o.1) * (p2.0 - o.0)).max(1) as u32;
        let b = bit_length(a);
        let (r, _) = crate::num::wide::div_u64_u32((1u64 << (31 + b)) - 1, a);
        (r, b)
    }

    /// [`Setup::plane`] with gradients exact to rounding (one unit of
    /// `2^−ATTR_FRAC` per pixel stepped), from the 32-bit reciprocal `recip`
    /// ([`Setup::exact_recip`]) and 64-bit products of 32-bit ones instead of
    /// 14-bit coefficients: for texture coordinates. Values within ±(2^15 − 1).
    #[inline]
    pub(crate) fn plane_exact(&self, a: [i32; 3], recip: (u32, u32)) -> Plane {
        let b = &self.bary;
        let t = self.tmb[0];
        let (o, p1, p2) = (
            at3(&self.xy, t),
            at3(&self.xy, b.other[0]),
            at3(&self.xy, b.other[1]),
        );
        let at = at3(&a, t);
        // |d| ≤ 2^16 − 2, |D| < 2^15: each product below 2^31
        let d1 = at3(&a, b.other[0]) - at;
        let d2 = at3(&a, b.other[1]) - at;
        let (e1, e2) = ((p1.0 - o.0, p1.1 - o.1), (p2.0 - o.0, p2.1 - o.1));
        // ∂a/∂X = (d1·D2y − d2·D1y)/A', ∂a/∂Y = (d2·D1x − d1·D2x)/A' (per
        // sub-pixel); per pixel with ATTR_FRAC bits: N·2^(SUBPIXEL_BITS +
        // ATTR_FRAC)/A' = N·R / 2^(31 + b − 18), rounded, saturated at ±2^30
        let nx = i64::from(d1 * e2.1) - i64::from(d2 * e1.1);
        let ny = i64::from(d2 * e1.0) - i64::from(d1 * e2.0);
        let (r, bits) = recip;
        let sh = 31 + bits - (SUBPIXEL_BITS + ATTR_FRAC);
        let grad = |n: i64| {
            let m = crate::num::wide::mul_u32(n.unsigned_abs() as u32, r);
            let g = ((m >> (sh - 1)) + 1) >> 1;
            let g = g.min(1 << 30) as i32;
            if n < 0 {
                -g
            } else {
                g
            }
        };
        let (dx, dy) = (grad(nx), grad(ny));
        let v = ((dx >> SUBPIXEL_BITS) * b.dxs)
            .wrapping_add((dy >> SUBPIXEL_BITS) * b.rem)
            .wrapping_add(dy.wrapping_mul(b.rows));
        Plane {
            row: v.wrapping_sub(dx.wrapping_mul(b.c0)),
            dx,
            dy,
            lo: 0.min(d1).min(d2) << ATTR_FRAC,
            hi: 0.max(d1).max(d2) << ATTR_FRAC,
            // the error bound of `Setup::err` with no coefficient error: one
            // unit per step
            spread: 0,
        }
    }
}

/// One attribute over a triangle: the value at column 0 of the current row
/// (the plane extended there) and its changes per pixel and per row, in `2^ATTR_FRAC` units of
/// `attribute >> sa`, relative to the top vertex's value. Values are computed
/// with wrapping arithmetic: only values inside the triangle are read, and
/// those are clamped to the vertex range.
#[derive(Clone, Copy, Debug, Default)]
pub struct Plane {
    /// Value at the centre of pixel `(0, current row)`: a pixel of the
    /// triangle is one multiply and one add away (wrapping, as every value).
    pub(crate) row: i32,
    /// Change per pixel to the right.
    pub(crate) dx: i32,
    /// Change per row down.
    pub(crate) dy: i32,
    /// The vertex range (relative values).
    pub(crate) lo: i32,
    pub(crate) hi: i32,
    /// `|Δa₁| + |Δa₂|` after the shift (for [`Setup::err`]).
    pub(crate) spread: u32,
}

impl Plane {
    /// The plane with `base` added to its values and its vertex range (a
    /// plane of [`Setup::plane`] is relative to the top vertex; `base` is the
    /// top vertex's value with [`ATTR_FRAC`] bits, so that the result holds
    /// absolute values). For planes whose differences needed no shift
    /// (`sa = 0`).
    #[inline(always)]
    pub(crate) fn absolute(mut self, base: i32) -> Plane {
        self.row = self.row.wrapping_add(base);
        self.lo = self.lo.wrapping_add(base);
        self.hi = self.hi.wrapping_add(base);
        self
    }

    /// Value at the centre of pixel `x` of the current row.
    #[inline(always)]
    pub(crate) fn at(&self, x: i32) -> i32 {
        self.row.wrapping_add(self.dx.wrapping_mul(x))
    }

    /// Moves to the next row.
    #[inline(always)]
    pub(crate) fn next_row(&mut self) {
        self.row = self.row.wrapping_add(self.dy);
    }

    /// Moves `n` rows down.
    #[inline(always)]
    pub(crate) fn skip_rows(&mut self, n: i32) {
        self.row = self.row.wrapping_add(self.dy.wrapping_mul(n));
    }

    /// `(start, step)` of a run of `n ≥ 1` pixels from column `x`, clamped so
    /// that `start + k·step` stays within the vertex range for `k < n` (the step
    /// shrinks toward zero when the end would leave it: one division, rare).
    #[inline(always)]
    pub(crate) fn clamped(&self, x: i32, n: i32) -> (i32, i32) {
        // the run's last value is the plane's at its last pixel, exactly
        // `start + (n − 1)·step` (wrapping arithmetic, and both pixels are inside
        // the triangle, so no value is off by 2^32): the common case needs no
        // division
        let s = self.at(x);
        let e = s.wrapping_add(self.dx.wrapping_mul(n - 1));
        if s >= self.lo && s <= self.hi && e >= self.lo && e <= self.hi {
            return (s, self.dx);
        }
        self.clamped_slow(s, n)
    }

    /// [`Plane::clamped`] when an end leaves the vertex range (one division).
    #[cold]
    #[inline(never)]
    fn clamped_slow(&self, s: i32, n: i32) -> (i32, i32) {
        let s = s.clamp_to(self.lo, self.hi);
        let mut d = self.dx;
        if n > 1 {
            let k = n - 1;
            // |d·k| may exceed i32 for extreme gradients: compare without overflow
            let room_up = self.hi - s;
            let room_dn = self.lo - s; // ≤ 0
            if d > 0 && d > room_up / k {
                d = room_up / k;
            } else if d < 0 && d < room_dn / k {
                d = room_dn / k;
            }
        } else {
            d = 0;
        }
        (s, d)
    }
}

/// `clamp` without `Ord::clamp`'s `min ≤ max` assertion (and its panic path).
pub(crate) trait ClampTo {
    fn clamp_to(self, lo: Self, hi: Self) -> Self;
}

impl ClampTo for i32 {
    #[inline(always)]
    fn clamp_to(self, lo: i32, hi: i32) -> i32 {
        if self < lo {
            lo
        } else if self > hi {
            hi
        } else {
            self
        }
    }
}

/// `a·b`, or `u32::MAX` when the product may not fit (decided from the bit
/// lengths, without the 32×32→64 multiply that `saturating_mul` needs on
/// thumbv6m, nor a count-leading-zeros call): an upper bound of the
/// saturated product.
#[inline]
fn mul_bound(a: u32, b: u32) -> u32 {
    if (a | b) <= 0xFFFF || bit_length(a) + bit_length(b) <= 32 {
        a * b
    } else {
        u32::MAX
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_length_matches_leading_zeros() {
        for x in (0..=20u32)
            .chain((0..32).map(|s| 1u32 << s))
            .chain((1..32).map(|s| (1u32 << s) - 1))
            .chain([u32::MAX, 12345, 0x8000_0001])
        {
            assert_eq!(bit_length(x), 32 - x.leading_zeros(), "{x}");
        }
    }

    #[test]
    fn scale_rounds_and_saturates() {
        assert_eq!(scale(5, -1), 3); // 2.5 → 3
        assert_eq!(scale(-5, -1), -2); // −2.5 → −2 (ties up)
        assert_eq!(scale(7, 2), 28);
        assert_eq!(scale(1 << 29, 2), 1 << 30);
        assert_eq!(scale(-(1 << 29), 3), -(1 << 30));
        assert_eq!(scale(i32::MAX, -31), 0);
        assert_eq!(scale(i32::MIN, -1), -(1 << 30));
    }
}
