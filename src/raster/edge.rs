//! Exact per-row span bounds of a triangle, walked without division.
//!
//! With the edge function `E(X, Y) = dx·(Y − ya) − dy·(X − xa)` of an edge
//! `a → b` (sub-pixel units, pixel centres `X = 16x + 8`, `Y = 16y + 8`), a
//! pixel is inside the edge iff `E − bias ≥ 0`, bias 0 on top and left edges
//! and 1 elsewhere (the top-left fill rule). Along a row `E` changes by
//! `−16·dy` per column, down a column by `16·dx` per row. An [`Edge`] keeps the
//! bound column of the current row and `e = E − bias` there with
//! `0 ≤ e < 16·|dy|`; moving to the next row adds `16·dx` and walks the bound
//! column by column back into that interval. The walk is exact (the same
//! integers as evaluating `E` at every pixel) and costs one step per column the
//! edge moves, so the whole walk of an edge costs its horizontal extent.

use super::setup::{at3, next3, Setup};
use super::SUBPIXEL_BITS;

/// One non-horizontal edge of a triangle, positioned at a row.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Edge {
    /// The bound column: the first inside column of a left edge, the last of a
    /// right edge.
    pub x: i32,
    /// `E − bias` at the bound column and current row, in `0..pp`.
    e: i32,
    /// `16·|dy|`: the change of `E` per column (inwards).
    pp: i32,
    /// `16·dx`: the change of `E` per row down.
    q: i32,
    /// `+1` for a left edge, `−1` for a right edge.
    d: i32,
}

impl Default for Edge {
    /// An edge that never moves (stands for a horizontal one, whose fill rule
    /// is applied separately): stepping it cannot loop.
    fn default() -> Self {
        Edge {
            x: 0,
            e: 0,
            pp: 1,
            q: 0,
            d: 1,
        }
    }
}

impl Edge {
    /// The edge `a → b` of a positively oriented triangle (`dy ≠ 0`), positioned
    /// at pixel row `row`, searching from column `guess`.
    #[inline]
    pub(crate) fn new(a: (i32, i32), b: (i32, i32), row: i32, guess: i32) -> Edge {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        let bias = i32::from(!top_left);
        let half = 1 << (SUBPIXEL_BITS - 1);
        let y = (row << SUBPIXEL_BITS) + half - a.1;
        let x = (guess << SUBPIXEL_BITS) + half - a.0;
        // both products < 2^30 inside the window
        let e = dx * y - dy * x - bias;
        let mut edge = Edge {
            x: guess,
            e,
            // never 0: horizontal edges are not walked (the guard keeps `settle` finite)
            pp: (dy << SUBPIXEL_BITS).abs().max(1),
            q: dx << SUBPIXEL_BITS,
            d: if dy < 0 { 1 } else { -1 },
        };
        edge.settle();
        edge
    }

    /// A column near the edge at pixel row `row`: `xa + (Y − ya)·dx/dy` in
    /// pixels (one division), for positioning far from the start vertex.
    #[inline]
    pub(crate) fn guess(a: (i32, i32), b: (i32, i32), row: i32) -> i32 {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let half = 1 << (SUBPIXEL_BITS - 1);
        let y = (row << SUBPIXEL_BITS) + half - a.1;
        // |y·dx| < 2^30
        // (dy ≠ 0 for an edge that walks: `checked_div` only drops the panic path)
        (a.0 + (y * dx).checked_div(dy).unwrap_or(0)) >> SUBPIXEL_BITS
    }

    /// Walks the bound column until `0 ≤ e < pp`.
    #[inline(always)]
    fn settle(&mut self) {
        while self.e < 0 {
            self.x += self.d;
            self.e += self.pp;
        }
        while self.e >= self.pp {
            self.x -= self.d;
            self.e -= self.pp;
        }
    }

    /// Moves to the next row: `e += q`, then the bound walks back into
    /// `0..pp`; for an edge known to be a left edge (`LEFT`) or a right edge,
    /// so that the direction of the walk is a constant.
    #[inline(always)]
    fn step_side<const LEFT: bool>(&mut self) {
        let d = if LEFT { 1 } else { -1 };
        self.e += self.q;
        if self.e < 0 {
            loop {
                self.x += d;
                self.e += self.pp;
                if self.e >= 0 {
                    break;
                }
            }
        } else if self.e >= self.pp {
            loop {
                self.x -= d;
                self.e -= self.pp;
                if self.e < self.pp {
                    break;
                }
            }
        }
    }
}

/// The bounding edges of a triangle walked down its rows.
///
/// Rows above the middle vertex are bounded by the long edge and the upper
/// short edge, rows below by the long edge and the lower one; a row level with
/// the middle vertex applies both short edges (or a horizontal one's fill
/// rule), so every row gets exactly the pixels passing all three edge
/// functions. That row is the only special one (a cold path): an ordinary row
/// costs two edge steps and one comparison.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walker {
    left: Edge,
    right: Edge,
    /// The next row to emit.
    pub y: i32,
    /// Last row of the triangle.
    pub last: i32,
    /// The row where the short edge changes (the row level with the middle
    /// vertex, or the first row below it); `i32::MAX` once changed.
    switch: i32,
    /// Whether `switch` is the row level with the middle vertex.
    level: bool,
    /// The long edge is the left one.
    long_left: bool,
    /// The upper/lower short edge is horizontal: `Some(true)` when its row
    /// is excluded by the fill rule (a horizontal edge excludes its row
    /// unless it runs to the right: a top edge).
    upper_flat: Option<bool>,
    lower_flat: Option<bool>,
    /// Vertex indices (top, middle, bottom) and positions.
    tmb: [usize; 3],
    xy: [(i32, i32); 3],
}

impl Walker {
    /// The walker positioned at `row` (at least the triangle's first row).
    pub(crate) fn new(s: &Setup, row: i32) -> Walker {
        Walker::build(s, row.max(s.rows.0), None)
    }

    /// The walker at row `y` with the long edge and the short edge in use
    /// there: searched from the edges' upper vertices (`cols` `None`), or
    /// from the bound columns `cols` of [`Walker::snapshot`]; built in place
    /// (no copy of a finished walker).
    fn build(s: &Setup, y: i32, cols: Option<(i32, i32)>) -> Walker {
        let edge = |xy: &[(i32, i32); 3], i, j, long: bool| match cols {
            None => edge_near(xy, i, j, y),
            Some(c) => edge_from(xy, i, j, y, if long { c.0 } else { c.1 }),
        };
        let [t, m, b] = s.tmb;
        let xy = s.xy;
        let half = 1 << (SUBPIXEL_BITS - 1);
        let ym = at3(&xy, m).1;
        let below = ((ym - half) >> SUBPIXEL_BITS) + 1;
        let level = (ym - half) & ((1 << SUBPIXEL_BITS) - 1) == 0;
        // a horizontal edge a → b is a top edge (row included) iff dx > 0
        let flat = |i: usize, j: usize| {
            let (a, bb) = if next3(i) == j { (i, j) } else { (j, i) };
            let (pa, pb) = (at3(&xy, a), at3(&xy, bb));
            (pa.1 == pb.1).then_some(pb.0 <= pa.0)
        };
        // the long edge as oriented: going down (t → b) it is a right edge
        let long_left = next3(t) != b;
        let switch = if level { below - 1 } else { below };
        let long = edge(&xy, t, b, true);
        // before the switch row, or at it (which replaces the upper edge
        // itself): the upper short edge; after it, the lower one
        let (short, switch) = if y <= switch {
            (edge(&xy, t, m, false), switch)
        } else {
            (edge(&xy, m, b, false), i32::MAX)
        };
        let (left, right) = if long_left {
            (long, short)
        } else {
            (short, long)
        };
        Walker {
            left,
            right,
            y,
            last: s.rows.1,
            switch,
            level,
            long_left,
            upper_flat: flat(t, m),
            lower_flat: flat(m, b),
            tmb: s.tmb,
            xy,
        }
    }

    /// Whether rows remain.
    #[inline(always)]
    pub(crate) fn more(&self) -> bool {
        self.y <= self.last
    }

    /// The inside columns `(lo, hi)` of the current row (empty when `lo > hi`),
    /// then moves to the next row.
    #[inline(always)]
    pub(crate) fn next(&mut self) -> (i32, i32) {
        if self.y == self.switch {
            return self.switch_row();
        }
        let r = (self.left.x, self.right.x);
        self.left.step_side::<true>();
        self.right.step_side::<false>();
        self.y += 1;
        r
    }

    /// The row where the short edge changes from the upper to the lower one.
    #[cold]
    #[inline(never)]
    fn switch_row(&mut self) -> (i32, i32) {
        let [_, m, b] = self.tmb;
        let y = self.y;
        self.switch = i32::MAX;
        let (mut lo, mut hi) = (self.left.x, self.right.x);
        let lower = edge_near(&self.xy, m, b, y);
        if self.level {
            // level with the middle vertex: the upper short edge (or its fill
            // rule), the lower one (or its), and the long edge all apply
            let ex = |f: Option<bool>| f == Some(true);
            if ex(self.upper_flat) || ex(self.lower_flat) {
                hi = lo - 1;
            }
            if self.lower_flat.is_none() {
                if self.long_left {
                    hi = hi.min(lower.x);
                } else {
                    lo = lo.max(lower.x);
                }
            }
            if self.upper_flat.is_some() {
                // the upper short edge never walked: the long edge alone
                // bounded its side
                if self.long_left {
                    hi = if ex(self.upper_flat) || ex(self.lower_flat) {
                        lo - 1
                    } else {
                        lower.x
                    };
                } else {
                    lo = lower.x;
                    if ex(self.upper_flat) || ex(self.lower_flat) {
                        hi = lo - 1;
                    }
                }
            }
        } else if self.long_left {
            hi = lower.x;
        } else {
            lo = lower.x;
        }
        if self.long_left {
            self.right = lower;
            self.left.step_side::<true>();
            self.right.step_side::<false>();
        } else {
            self.left = lower;
            self.left.step_side::<true>();
            self.right.step_side::<false>();
        }
        self.y += 1;
        (lo, hi)
    }

    /// What [`Walker::resume`] needs to continue at the current row: the bound
    /// columns of the long edge and of the short edge in use at this row.
    #[inline]
    pub(crate) fn snapshot(&self) -> (i32, i32) {
        if self.long_left {
            (self.left.x, self.right.x)
        } else {
            (self.right.x, self.left.x)
        }
    }

    /// The walker at `row` given the bound columns from [`Walker::snapshot`]
    /// taken at that row: positioning costs no division and no walk.
    pub(crate) fn resume(s: &Setup, row: i32, cols: (i32, i32)) -> Walker {
        Walker::build(s, row, Some(cols))
    }
}

/// The edge between vertices `i` and `j` of `xy` (as oriented in the
/// triangle) at row `row`, searching from the upper vertex's column when the
/// bound is within 4 columns of it, else from a division estimate.
fn edge_near(xy: &[(i32, i32); 3], i: usize, j: usize, row: i32) -> Edge {
    let (a, b) = if next3(i) == j { (i, j) } else { (j, i) };
    let (pa, pb) = (at3(xy, a), at3(xy, b));
    if pa.1 == pb.1 {
        // a horizontal edge bounds no column (its fill rule is applied
        // separately); an edge that never walks
        return Edge::default();
    }
    let upper = if pa.1 <= pb.1 { pa } else { pb };
    let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
    let down = (row << SUBPIXEL_BITS) + (1 << (SUBPIXEL_BITS - 1)) - upper.1;
    // |dx|·down ≤ 4·16·|dy|: the bound is within ~4 columns of the vertex
    let guess = if down.unsigned_abs() * dx.unsigned_abs() <= (dy.unsigned_abs() << 6) {
        upper.0 >> SUBPIXEL_BITS
    } else {
        Edge::guess(pa, pb, row)
    };
    Edge::new(pa, pb, row, guess)
}

/// The edge between `i` and `j` of `xy` at `row`, searching from column
/// `guess`.
fn edge_from(xy: &[(i32, i32); 3], i: usize, j: usize, row: i32, guess: i32) -> Edge {
    let (a, b) = if next3(i) == j { (i, j) } else { (j, i) };
    let (pa, pb) = (at3(xy, a), at3(xy, b));
    if pa.1 == pb.1 {
        return Edge::default();
    }
    Edge::new(pa, pb, row, guess)
}
