//! Screen-linear attribute planes in fixed point.

use super::SUBPIXEL_BITS;

/// Fractional bits of plane values and gradients.
pub(crate) const FRAC: u32 = 16;
/// Gradients are clamped to ±2^41 (2^-16 units per sub-pixel), i.e. 2^29
/// units per pixel, so that `gradient × distance` stays far inside i64.
const GRAD_CAP: i64 = 1 << 41;
/// Steps handed to shaders are clamped to ±2^30 units per pixel.
const STEP_CAP: i64 = 1 << 30;

/// `a(X, Y) = a0 + gx·(X − x0) + gy·(Y − y0)` over sub-pixel positions,
/// with `gx`, `gy` in units per sub-pixel with [`FRAC`] fractional bits.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plane {
    a0: i64,
    gx: i64,
    gy: i64,
    origin: (i64, i64),
    /// The smallest and largest vertex value: every exact value inside the
    /// triangle lies between them, so computed values are clamped to them.
    pub(crate) lo: i64,
    pub(crate) hi: i64,
}

impl Plane {
    /// The plane through `(xy[i], a[i])`; `area` is the doubled signed area, `> 0`.
    pub(crate) fn new(xy: &[(i64, i64); 3], area: i64, a: [i64; 3]) -> Self {
        let (dx1, dy1) = (xy[1].0 - xy[0].0, xy[1].1 - xy[0].1);
        let (dx2, dy2) = (xy[2].0 - xy[0].0, xy[2].1 - xy[0].1);
        let (da1, da2) = (a[1] - a[0], a[2] - a[0]);
        // Cramer: gx = (Δa1·Δy2 − Δa2·Δy1) / A, gy = (Δa2·Δx1 − Δa1·Δx2) / A.
        Plane {
            a0: a[0],
            gx: gradient(da1 * dy2 - da2 * dy1, area),
            gy: gradient(da2 * dx1 - da1 * dx2, area),
            origin: xy[0],
            lo: a[0].min(a[1]).min(a[2]),
            hi: a[0].max(a[1]).max(a[2]),
        }
    }

    /// Value at the centre of pixel `(0, y)` (with [`FRAC`] bits); add
    /// [`at`](Plane::at) for other columns.
    #[inline]
    pub(crate) fn row(&self, y: i64) -> i64 {
        let half = 1i64 << (SUBPIXEL_BITS - 1);
        (self.a0 << FRAC)
            + self.gy * ((y << SUBPIXEL_BITS) + half - self.origin.1)
            + self.gx * (half - self.origin.0)
    }

    /// `row(y + 1) − row(y)`: `gy·16`.
    #[inline]
    pub(crate) fn row_step(&self) -> i64 {
        self.gy << SUBPIXEL_BITS
    }

    /// Value at the centre of pixel `(x, y)` given `row = self.row(y)`: `row + gx·16x`.
    #[inline]
    pub(crate) fn at(&self, row: i64, x: i64) -> i64 {
        row + self.gx * (x << SUBPIXEL_BITS)
    }

    /// Change per pixel to the right, with [`FRAC`] bits.
    #[inline]
    pub(crate) fn step(&self) -> i64 {
        self.gx << SUBPIXEL_BITS
    }

    /// A [`FRAC`]-bit value rounded to units and clamped to the vertex range.
    #[inline]
    pub(crate) fn round(&self, v: i64) -> i64 {
        ((v + (1 << (FRAC - 1))) >> FRAC).clamp(self.lo, self.hi)
    }
}

/// `floor(num · 2^FRAC / den)` for `den > 0`, without overflowing, clamped to ±[`GRAD_CAP`].
fn gradient(num: i64, den: i64) -> i64 {
    let q = num.div_euclid(den);
    let r = num.rem_euclid(den);
    q.saturating_mul(1 << FRAC)
        .saturating_add((r << FRAC) / den)
        .clamp(-GRAD_CAP, GRAD_CAP)
}

/// The `(start, step)` handed to a shader for `n` pixels: `start` clamped to
/// `lo..=hi`, `step` clamped to ±2^30 and shrunk (toward zero) if needed so
/// that `start + k·step` stays in `lo..=hi` for every `k < n`.
#[inline]
pub(crate) fn fit(start: i64, step: i64, n: usize, lo: i64, hi: i64) -> (i32, i32) {
    let start = start.clamp(lo, hi);
    let mut step = step.clamp(-STEP_CAP, STEP_CAP);
    if n > 1 {
        let k = n as i64 - 1;
        let end = start + step * k;
        if end > hi {
            step = (hi - start) / k;
        } else if end < lo {
            step = (lo - start) / k;
        }
    } else {
        step = 0;
    }
    (start as i32, step as i32)
}
