//! Perspective-correct barycentric weights.

use super::setup::Setup;
use super::SUBPIXEL_BITS;

/// Fixed-point one of the barycentric weights: 2^30.
const ONE: i64 = 1 << 30;

/// Evaluates perspective-correct attribute values at single pixels:
/// `a = Σ wᵢ·qᵢ·aᵢ / Σ wᵢ·qᵢ`, with `wᵢ` the exact screen-space edge functions
/// (barycentric weights × doubled area) and `qᵢ = 1/wᵢ` of the vertices.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Perspective {
    /// `1/w` per vertex, rescaled to `1..=2^15` (only ratios matter).
    q: [i64; 3],
    xy: [(i64, i64); 3],
    area: i64,
}

impl Perspective {
    pub(crate) fn new<const N: usize>(s: &Setup<N>) -> Self {
        let raw = [0, 1, 2].map(|i| i64::from(s.v[i].inv_w).max(1));
        let max = raw[0].max(raw[1]).max(raw[2]);
        let q = raw.map(|r| ((r << 15) / max).max(1));
        Perspective {
            q,
            xy: s.xy,
            area: s.area,
        }
    }

    /// Perspective barycentric weights `(β0, β1, β2)` in Q30, summing to 2^30,
    /// at the centre of pixel `(x, y)`, which must lie inside the triangle.
    pub(crate) fn weights(&self, x: i64, y: i64) -> [i64; 3] {
        let half = 1i64 << (SUBPIXEL_BITS - 1);
        let p = ((x << SUBPIXEL_BITS) + half, (y << SUBPIXEL_BITS) + half);
        // E_ab(p) = (xb − xa)(py − ya) − (yb − ya)(px − xa), in 0..=A inside.
        let edge =
            |a: (i64, i64), b: (i64, i64)| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        let w1 = edge(self.xy[2], self.xy[0]).clamp(0, self.area);
        let w2 = edge(self.xy[0], self.xy[1]).clamp(0, self.area);
        let w0 = (self.area - w1 - w2).max(0);
        // pᵢ = wᵢ·qᵢ < 2^56; scale so that their sum fits 31 bits.
        let mut pw = [w0 * self.q[0], w1 * self.q[1], w2 * self.q[2]];
        let sum = pw[0] + pw[1] + pw[2];
        let shift = (64 - sum.leading_zeros()).saturating_sub(31);
        for v in pw.iter_mut() {
            *v >>= shift;
        }
        let sum = (pw[0] + pw[1] + pw[2]).max(1);
        let b1 = (pw[1] << 30) / sum;
        let b2 = (pw[2] << 30) / sum;
        [ONE - b1 - b2, b1, b2]
    }

    /// `Σ βᵢ·aᵢ / 2^30`, rounded: a convex combination, so within the vertex range.
    #[inline]
    pub(crate) fn value(beta: &[i64; 3], a: &[i64; 3]) -> i64 {
        (beta[0] * a[0] + beta[1] * a[1] + beta[2] * a[2] + (ONE >> 1)) >> 30
    }
}
