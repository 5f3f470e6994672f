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

use super::setup::Setup;
use super::SUBPIXEL_BITS;

/// One non-horizontal edge of a triangle, positioned at a row.
#[derive(Clone, Copy, Debug, Default)]
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
        (a.0 + (y * dx) / dy) >> SUBPIXEL_BITS
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

    /// Moves to the next row.
    #[inline(always)]
    pub(crate) fn step(&mut self) {
        self.e += self.q;
        self.settle();
    }

    /// Whether this is a left edge (its bound is the first inside column).
    #[inline(always)]
    pub(crate) fn is_left(&self) -> bool {
        self.d > 0
    }
}

/// The bounding edges of a triangle walked down its rows.
///
/// Rows whose centre lies above the middle vertex are bounded by the long edge
/// (top → bottom) and the upper short edge (top → middle), rows below it by the
/// long edge and the lower short edge (middle → bottom). A row whose centre is
/// exactly level with the middle vertex applies both short edges (or the fill
/// rule of a horizontal one), so every row gets exactly the pixels whose
/// centres pass all three edge functions.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walker {
    long: Edge,
    upper: Edge,
    lower: Edge,
    /// The next row to emit.
    pub y: i32,
    /// Last row of the triangle.
    pub last: i32,
    /// First row whose centre is below the middle vertex.
    below: i32,
    /// The row whose centre is level with the middle vertex, if any (else `i32::MIN`).
    level: i32,
    /// `lower` is positioned at row `y`.
    lower_ready: bool,
    /// The upper short edge is horizontal: it is a top edge (its row is included)
    /// unless it runs to the left.
    upper_flat_excludes: Option<bool>,
    /// The lower short edge is horizontal (a bottom edge: `Some(true)` excludes its row).
    lower_flat_excludes: Option<bool>,
    /// Vertex indices (top, middle, bottom) and positions.
    tmb: [usize; 3],
    xy: [(i32, i32); 3],
}

impl Walker {
    /// The walker positioned at `row` (at least the triangle's first row).
    pub(crate) fn new(s: &Setup, row: i32) -> Walker {
        let mut w = Walker::unpositioned(s, row.max(s.rows.0));
        let [t, m, b] = w.tmb;
        let y = w.y;
        w.long = w.edge_near(t, b, y);
        if y < w.below && y != w.level {
            w.upper = w.edge_near(t, m, y);
        } else if y == w.level {
            if w.upper_flat_excludes.is_none() {
                w.upper = w.edge_near(t, m, y);
            }
        } else if w.lower_flat_excludes.is_none() {
            w.lower = w.edge_near(m, b, y);
            w.lower_ready = true;
        }
        w
    }

    fn unpositioned(s: &Setup, y: i32) -> Walker {
        let [t, m, b] = s.tmb;
        let xy = s.xy;
        let half = 1 << (SUBPIXEL_BITS - 1);
        let ym = xy[m].1;
        let below = ((ym - half) >> SUBPIXEL_BITS) + 1;
        let level = if (ym - half) & ((1 << SUBPIXEL_BITS) - 1) == 0 {
            below - 1
        } else {
            i32::MIN
        };
        // a horizontal edge a → b is a top edge (row included) iff dx > 0
        let flat = |i: usize, j: usize| {
            let (a, bb) = if (i + 1) % 3 == j { (i, j) } else { (j, i) };
            (xy[a].1 == xy[bb].1).then(|| xy[bb].0 <= xy[a].0)
        };
        Walker {
            long: Edge::default(),
            upper: Edge::default(),
            lower: Edge::default(),
            y,
            last: s.rows.1,
            below,
            level,
            lower_ready: false,
            upper_flat_excludes: flat(t, m),
            lower_flat_excludes: flat(m, b),
            tmb: s.tmb,
            xy,
        }
    }

    /// The edge between vertices `i` and `j` (as oriented in the triangle) at
    /// row `row`, searching from the upper vertex's column when the bound is
    /// within 4 columns of it, else from a division estimate.
    fn edge_near(&self, i: usize, j: usize, row: i32) -> Edge {
        let (a, b) = if (i + 1) % 3 == j { (i, j) } else { (j, i) };
        let (pa, pb) = (self.xy[a], self.xy[b]);
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

    /// The edge between `i` and `j` at `row`, searching from column `guess`.
    fn edge_from(&self, i: usize, j: usize, row: i32, guess: i32) -> Edge {
        let (a, b) = if (i + 1) % 3 == j { (i, j) } else { (j, i) };
        Edge::new(self.xy[a], self.xy[b], row, guess)
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
        let y = self.y;
        let (mut lo, mut hi) = (i32::MIN, i32::MAX);
        Self::bound(&self.long, &mut lo, &mut hi);
        if y < self.below && y != self.level {
            Self::bound(&self.upper, &mut lo, &mut hi);
            self.upper.step();
        } else if y == self.level {
            self.level_row(y, &mut lo, &mut hi);
        } else {
            if !self.lower_ready {
                let [_, m, b] = self.tmb;
                self.lower = self.edge_near(m, b, y);
                self.lower_ready = true;
            }
            Self::bound(&self.lower, &mut lo, &mut hi);
            self.lower.step();
        }
        self.long.step();
        self.y += 1;
        (lo, hi)
    }

    #[inline(always)]
    fn bound(e: &Edge, lo: &mut i32, hi: &mut i32) {
        if e.is_left() {
            *lo = (*lo).max(e.x);
        } else {
            *hi = (*hi).min(e.x);
        }
    }

    /// The row level with the middle vertex: both short edges apply.
    #[cold]
    fn level_row(&mut self, y: i32, lo: &mut i32, hi: &mut i32) {
        let [_, m, b] = self.tmb;
        match self.upper_flat_excludes {
            Some(true) => *hi = lo.saturating_sub(1).min(*hi),
            Some(false) => {}
            None => Self::bound(&self.upper, lo, hi),
        }
        match self.lower_flat_excludes {
            Some(true) => *hi = lo.saturating_sub(1).min(*hi),
            Some(false) => {}
            None => {
                self.lower = self.edge_near(m, b, y);
                Self::bound(&self.lower, lo, hi);
                self.lower.step();
                self.lower_ready = true;
            }
        }
    }

    /// What [`Walker::resume`] needs to continue at the current row: the bound
    /// columns of the long edge and of the short edge in use at this row.
    #[inline]
    pub(crate) fn snapshot(&self) -> (i32, i32) {
        let short = if self.y < self.below || self.y == self.level {
            self.upper.x
        } else {
            self.lower.x
        };
        (self.long.x, short)
    }

    /// The walker at `row` given the bound columns from [`Walker::snapshot`]
    /// taken at that row: positioning costs no division and no walk.
    pub(crate) fn resume(s: &Setup, row: i32, cols: (i32, i32)) -> Walker {
        let mut w = Walker::unpositioned(s, row);
        let [t, m, b] = w.tmb;
        w.long = w.edge_from(t, b, row, cols.0);
        if row < w.below || row == w.level {
            if w.upper_flat_excludes.is_none() {
                w.upper = w.edge_from(t, m, row, cols.1);
            }
        } else if w.lower_flat_excludes.is_none() {
            w.lower = w.edge_from(m, b, row, cols.1);
            w.lower_ready = true;
        }
        w
    }
}
