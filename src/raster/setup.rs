//! Per-triangle setup: guard-band clamp, orientation, culling, row range.

use super::{Cull, RasterVertex, GUARD_BAND, SUBPIXEL_BITS};

/// A triangle ready to walk: sub-pixel coordinates clamped to the guard band,
/// vertices ordered so that the doubled signed area is positive.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Setup<const N: usize> {
    /// Sub-pixel positions.
    pub(crate) xy: [(i64, i64); 3],
    /// The (possibly reordered) vertices, for z, 1/w and attributes.
    pub(crate) v: [RasterVertex<N>; 3],
    /// Doubled area in sub-pixel units², `> 0`.
    pub(crate) area: i64,
    /// Pixel rows whose centres lie between the lowest and highest vertex.
    pub(crate) rows: (i64, i64),
}

/// Largest sub-pixel coordinate magnitude kept by the clamp.
pub(crate) const GUARD_SUB: i64 = (GUARD_BAND as i64) << SUBPIXEL_BITS;

impl<const N: usize> Setup<N> {
    /// Clamps, orients and culls; `None` for zero-area or culled triangles.
    pub(crate) fn new(v: &[RasterVertex<N>; 3], cull: Cull) -> Option<Self> {
        let clamp = |c: i32| i64::from(c).clamp(-GUARD_SUB, GUARD_SUB);
        let mut xy = [(0i64, 0i64); 3];
        for (p, vert) in xy.iter_mut().zip(v.iter()) {
            *p = (clamp(vert.x), clamp(vert.y));
        }
        // A = (x1 − x0)(y2 − y0) − (y1 − y0)(x2 − x0): positive when the
        // vertices run clockwise as seen on a y-down screen.
        let area =
            (xy[1].0 - xy[0].0) * (xy[2].1 - xy[0].1) - (xy[1].1 - xy[0].1) * (xy[2].0 - xy[0].0);
        let front = area < 0;
        let culled = match cull {
            Cull::None => false,
            Cull::Back => !front,
            Cull::Front => front,
        };
        if area == 0 || culled {
            return None;
        }
        let mut v = *v;
        let mut area = area;
        if area < 0 {
            xy.swap(1, 2);
            v.swap(1, 2);
            area = -area;
        }
        let half = 1i64 << (SUBPIXEL_BITS - 1);
        let (lo, hi) = xy.iter().fold((i64::MAX, i64::MIN), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
        // Rows whose centre Y = 16y + 8 lies in [lo, hi].
        let first = (lo - half + (1 << SUBPIXEL_BITS) - 1).div_euclid(1 << SUBPIXEL_BITS);
        let last = (hi - half).div_euclid(1 << SUBPIXEL_BITS);
        Some(Setup {
            xy,
            v,
            area,
            rows: (first, last),
        })
    }
}
