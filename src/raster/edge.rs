//! Exact per-row span bounds of one triangle edge, without per-row division.

/// Which side of the span an edge bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    /// Inside columns are `x >= -floor(t / p)`.
    Left,
    /// Inside columns are `x <= floor(t / p)`.
    Right,
    /// Horizontal edge: a row is wholly inside iff `t >= 0`.
    Flat,
}

/// One edge `a → b` of a positively oriented triangle, walked row by row.
///
/// With the edge function `E(X, Y) = dx·(Y − ya) − dy·(X − xa)` in sub-pixel
/// units and pixel centres `X = 16x + 8`, `Y = 16y + 8` (for 4 sub-pixel
/// bits), a pixel is inside the edge iff `E >= bias` (bias 0 on top and left
/// edges, 1 elsewhere: the top-left fill rule). Writing `E − bias = P·x + T(y)`
/// with `P = −16·dy` and `T(y) = T(0) + Q·y`, `Q = 16·dx`, the bound is
/// `x >= ceil(−T/P)` for `P > 0` and `x <= floor(T/−P)` for `P < 0`.
/// The walker keeps `T = p·m + s` with `0 <= s < p` (`p = |P|`) and adds `Q`
/// per row as an exact Bresenham-style quotient/remainder step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgeWalker {
    side: Side,
    /// `floor(T / p)` (or `T` itself for a flat edge).
    m: i64,
    /// `T − p·m`, in `0..p`.
    s: i64,
    p: i64,
    /// `floor(Q / p)` and `Q mod p`.
    dq: i64,
    dr: i64,
}

impl EdgeWalker {
    /// The walker for edge `a → b` (sub-pixel coordinates, within the guard
    /// band), positioned at pixel row `y`.
    pub(crate) fn new(a: (i64, i64), b: (i64, i64), y: i64, sub_bits: u32) -> Self {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let half = 1i64 << (sub_bits - 1);
        // Top-left rule for a positively oriented (clockwise on screen) triangle:
        // top edges run to the right, left edges run upwards.
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        let bias = i64::from(!top_left);
        let q = dx << sub_bits;
        // T(y) = E(x = 0, y) − bias
        let t = dx * ((y << sub_bits) + half - a.1) - dy * (half - a.0) - bias;
        if dy == 0 {
            return EdgeWalker {
                side: Side::Flat,
                m: t,
                s: 0,
                p: 1,
                dq: q,
                dr: 0,
            };
        }
        let p = (dy << sub_bits).abs();
        EdgeWalker {
            side: if dy < 0 { Side::Left } else { Side::Right },
            m: t.div_euclid(p),
            s: t.rem_euclid(p),
            p,
            dq: q.div_euclid(p),
            dr: q.rem_euclid(p),
        }
    }

    /// Narrows the inclusive column range `lo..=hi` to this edge's inside on the current row.
    #[inline]
    pub(crate) fn clip(&self, lo: &mut i64, hi: &mut i64) {
        match self.side {
            Side::Left => *lo = (*lo).max(-self.m),
            Side::Right => *hi = (*hi).min(self.m),
            Side::Flat => {
                if self.m < 0 {
                    *hi = *lo - 1;
                }
            }
        }
    }

    /// Moves to the next row: `T += Q`, i.e. `m += floor(Q/p)`, `s += Q mod p`, carry.
    #[inline]
    pub(crate) fn step(&mut self) {
        self.m += self.dq;
        self.s += self.dr;
        if self.s >= self.p {
            self.s -= self.p;
            self.m += 1;
        }
    }
}
