//! Triangle rasterization: exact fixed-point edge walking with a top-left
//! fill rule, scissor clipping, optional depth test and perspective-correct
//! attribute interpolation.
//!
//! [`draw_triangle`] turns three [`RasterVertex`]es into horizontal runs of
//! pixels and hands each run to a [`SpanShader`], which writes the colours
//! into a [`Framebuffer`] span.
//!
//! # Conventions
//!
//! - **Coordinates**: `x`, `y` in screen pixels with [`SUBPIXEL_BITS`]
//!   fractional bits, `y` pointing down. Pixel `(x, y)` is sampled at its
//!   centre `(x + ½, y + ½)`.
//! - **Fill rule**: top-left. A pixel centre exactly on an edge belongs to the
//!   triangle only if the edge is a top edge (horizontal, triangle below) or a
//!   left edge. Triangles that share an edge (same two vertices) therefore
//!   cover every pixel along it exactly once: a mesh is watertight.
//! - **Winding**: a triangle is *front-facing* when its vertices run
//!   counter-clockwise as seen on the screen (y down), e.g. `(0,0) → (0,10) →
//!   (10,0)`. [`Cull::Back`] drops the others; with [`Cull::None`] both draw.
//! - **Guard band**: coordinates are clamped to ±[`GUARD_BAND`] pixels before
//!   setup, so no input can overflow. Geometry beyond the guard band is
//!   distorted: clip it before rasterizing (near-plane clipping belongs to the
//!   transform stage).
//! - **Depth**: `z` is interpolated linearly in screen space; smaller is
//!   nearer; a pixel passes when `z < stored` (see [`DepthBuffer`]).
//!
//! # Attribute precision
//!
//! Attributes are interpolated in i64 from the exact plane through the three
//! vertices (gradients carry 16 fractional bits per sub-pixel). For every run
//! of pixels the rasterizer recomputes `start` from the plane, so:
//!
//! - `start` is the plane value at the first pixel centre to within
//!   `½ + d·2⁻¹²` units, `d` being the distance in pixels from vertex 0
//!   (exact at vertex positions);
//! - `step` is the per-pixel gradient rounded to the nearest unit, so pixel
//!   `k` of the run is within `½ + d·2⁻¹² + k·½` units of the plane;
//! - `start + k·step` never leaves the range of the three vertex values for
//!   any `k < out.len()`, so shaders may use plain `i32` arithmetic;
//! - triangles whose attributes change by more than 2^29 units per pixel
//!   (only thinner than a pixel with huge attribute ranges) get clamped
//!   gradients: values stay within the vertex range but may be off.
//!
//! With [`RasterOptions::perspective`], values are exact (±1 unit) at the
//! ends of sub-spans of [`PERSPECTIVE_SPAN`] pixels and linear in between; the
//! extra error inside a sub-span is about `¼·|Δa|·|Δq/q|`, `Δa` and `Δq/q`
//! being the change of the attribute and the relative change of `1/w`
//! across that sub-span.

use crate::target::{DepthBuffer, Framebuffer};

mod edge;
mod perspective;
mod plane;
mod setup;

use edge::EdgeWalker;
use perspective::Perspective;
use plane::{fit, Plane, FRAC};
use setup::Setup;

/// Fractional bits of [`RasterVertex::x`] and [`RasterVertex::y`]: 4, i.e.
/// positions are in 1/16 pixel.
pub const SUBPIXEL_BITS: u32 = 4;

/// Vertex coordinates are clamped to `-GUARD_BAND..=GUARD_BAND` pixels
/// (2^15) before setup; the framebuffer is clipped to `0..GUARD_BAND` columns
/// and `-GUARD_BAND..GUARD_BAND` rows.
pub const GUARD_BAND: i32 = 1 << 15;

/// Length of the sub-spans whose ends are computed exactly in perspective mode (16).
pub const PERSPECTIVE_SPAN: usize = 1 << PERSPECTIVE_SHIFT;
const PERSPECTIVE_SHIFT: u32 = 4;

/// One corner of a triangle in screen space.
///
/// ```
/// use fixshade::raster::{RasterVertex, SUBPIXEL_BITS};
///
/// // The centre of pixel (10, 20), carrying one attribute: red = 0.5 in Q16.
/// let v = RasterVertex {
///     x: (10 << SUBPIXEL_BITS) + 8,
///     y: (20 << SUBPIXEL_BITS) + 8,
///     z: 1000,
///     inv_w: 1 << 16,
///     attrs: [1 << 15],
/// };
/// # let _ = v;
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RasterVertex<const N: usize> {
    /// Column in pixels with [`SUBPIXEL_BITS`] fractional bits.
    pub x: i32,
    /// Row in pixels with [`SUBPIXEL_BITS`] fractional bits (down is positive).
    pub y: i32,
    /// Depth for the depth test: smaller is nearer.
    pub z: u16,
    /// `1/w` of the vertex in any positive fixed-point scale shared by the
    /// three vertices (only ratios matter; ratios beyond 2^15 lose precision).
    /// Used only with [`RasterOptions::perspective`]; values `<= 0` count as
    /// the smallest positive value.
    pub inv_w: i32,
    /// Attributes in caller-chosen fixed-point units (any `i32`).
    pub attrs: [i32; N],
}

/// Which triangles [`draw_triangle`] skips.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Cull {
    /// Draw both windings.
    #[default]
    None,
    /// Skip back faces: vertices clockwise as seen on the screen.
    Back,
    /// Skip front faces: vertices counter-clockwise as seen on the screen.
    Front,
}

/// How [`draw_triangle`] rasterizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RasterOptions {
    /// Face culling.
    pub cull: Cull,
    /// Perspective-correct attributes (from [`RasterVertex::inv_w`]).
    pub perspective: bool,
    /// Test `z < stored` against the depth buffer, if one is given.
    pub depth_test: bool,
    /// Store `z` of drawn pixels in the depth buffer, if one is given.
    pub depth_write: bool,
}

impl Default for RasterOptions {
    /// No culling, screen-linear attributes, depth test and write on.
    fn default() -> Self {
        RasterOptions {
            cull: Cull::None,
            perspective: false,
            depth_test: true,
            depth_write: true,
        }
    }
}

/// What one [`draw_triangle`] call did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DrawStats {
    /// Pixels handed to the shader (saturating).
    pub pixels: u32,
    /// Runs of pixels handed to the framebuffer (saturating).
    pub spans: u32,
}

/// Writes the colours of runs of pixels; implemented by the shading stage.
///
/// The shader owns the per-pixel loop, so it can be specialised per scene.
pub trait SpanShader<const N: usize> {
    /// The colour written.
    type Color: Copy;

    /// Shades `out.len()` consecutive pixels of row `y`, the first at column `x`.
    ///
    /// `start` holds the attribute values at the centre of the first pixel,
    /// `step` their change per pixel to the right: pixel `k` gets
    /// `start + k·step`, which stays within the vertex range (no `i32`
    /// overflow). See the [module docs](self) for the error bounds.
    fn shade_span(
        &mut self,
        x: i32,
        y: i32,
        start: &[i32; N],
        step: &[i32; N],
        out: &mut [Self::Color],
    );
}

/// Rasterizes one triangle into `fb`, shading every covered pixel with `shader`.
///
/// Pixels are covered by the top-left rule, clipped to `fb.width()` ×
/// `fb.rows()` (and to the depth buffer when it is used). If `depth` is given
/// and `opts.depth_test` is set, only pixels with `z < stored` are drawn; if
/// `opts.depth_write` is set, drawn pixels store their `z`. The shader is
/// called once per maximal run of drawn pixels (per framebuffer piece, and per
/// [`PERSPECTIVE_SPAN`] pixels in perspective mode).
///
/// Never panics, for any vertex values.
///
/// ```
/// use embedded_graphics_core::pixelcolor::Gray8;
/// use fixshade::raster::{draw_triangle, RasterOptions, RasterVertex, SpanShader, SUBPIXEL_BITS};
/// use fixshade::target::SliceFramebuffer;
///
/// /// Grey level = attribute 0 (in Q8).
/// struct Ramp;
/// impl SpanShader<1> for Ramp {
///     type Color = Gray8;
///     fn shade_span(&mut self, _x: i32, _y: i32, start: &[i32; 1], step: &[i32; 1], out: &mut [Gray8]) {
///         let mut a = start[0];
///         for p in out.iter_mut() {
///             // luma = a / 256
///             *p = Gray8::new((a >> 8) as u8);
///             a += step[0];
///         }
///     }
/// }
///
/// let mut pixels = [Gray8::new(0); 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// let v = |x: i32, y: i32, grey: i32| RasterVertex {
///     x: x << SUBPIXEL_BITS, y: y << SUBPIXEL_BITS, z: 0, inv_w: 1, attrs: [grey << 8],
/// };
/// let tri = [v(0, 0, 0), v(16, 0, 160), v(0, 16, 0)];
/// let stats = draw_triangle(&mut fb, None, &tri, &RasterOptions::default(), &mut Ramp);
/// assert_eq!(stats.pixels, 120); // 15 + 14 + … + 1: centres on the hypotenuse (a right edge) are out
/// assert_eq!(fb.get(5, 0), Some(Gray8::new(55))); // centre x = 5.5: 160 · 5.5/16
/// ```
pub fn draw_triangle<F, S, const N: usize>(
    fb: &mut F,
    depth: Option<&mut DepthBuffer<'_>>,
    v: &[RasterVertex<N>; 3],
    opts: &RasterOptions,
    shader: &mut S,
) -> DrawStats
where
    F: Framebuffer,
    S: SpanShader<N, Color = F::Color>,
{
    let mut stats = DrawStats::default();
    let Some(s) = Setup::new(v, opts.cull) else {
        return stats;
    };
    let depth = if opts.depth_test || opts.depth_write {
        depth
    } else {
        None
    };

    // Scissor: columns 0..x_end, rows y_start..y_end.
    let guard = i64::from(GUARD_BAND);
    let fb_rows = fb.rows();
    let mut x_end = i64::from(fb.width()).min(guard);
    let mut y_start = i64::from(fb_rows.start).max(-guard).max(s.rows.0);
    let mut y_end = i64::from(fb_rows.end).min(guard).min(s.rows.1 + 1);
    if let Some(d) = depth.as_deref() {
        x_end = x_end.min(i64::from(d.width()));
        y_start = y_start.max(i64::from(d.rows().start));
        y_end = y_end.min(i64::from(d.rows().end));
    }
    if y_start >= y_end || x_end <= 0 {
        return stats;
    }

    let mut edges = [
        EdgeWalker::new(s.xy[0], s.xy[1], y_start, SUBPIXEL_BITS),
        EdgeWalker::new(s.xy[1], s.xy[2], y_start, SUBPIXEL_BITS),
        EdgeWalker::new(s.xy[2], s.xy[0], y_start, SUBPIXEL_BITS),
    ];
    let mut interp = SpanInterpolator {
        planes: core::array::from_fn(|i| {
            Plane::new(&s.xy, s.area, s.v.map(|v| i64::from(v.attrs[i])))
        }),
        values: core::array::from_fn(|i| s.v.map(|v| i64::from(v.attrs[i]))),
        perspective: opts.perspective.then(|| Perspective::new(&s)),
        row: [0; N],
        y: 0,
        last: 0,
        shader,
    };
    let zplane = Plane::new(&s.xy, s.area, s.v.map(|v| i64::from(v.z)));
    let mut depth = depth;
    // plane values at column 0 step by a constant per row: one i64 addition per
    // attribute and row instead of two 64-bit multiplications (library calls on a
    // Cortex-M0); exact, since every term is an integer
    interp.first_row(y_start);
    let mut zrow_next = zplane.row(y_start);

    for y in y_start..y_end {
        let zrow = zrow_next;
        zrow_next += zplane.row_step();
        interp.next_row(y);
        // Inside columns of this row: the intersection of the three edge half-planes.
        let (mut lo, mut hi) = (0i64, x_end - 1);
        for e in edges.iter() {
            e.clip(&mut lo, &mut hi);
        }
        for e in edges.iter_mut() {
            e.step();
        }
        if lo > hi {
            continue;
        }
        match depth.as_deref_mut() {
            None => emit(fb, &mut interp, lo, hi, &mut stats),
            Some(d) => {
                let Some(stored) = d.row_mut(y as i32, lo as u32..(hi + 1) as u32) else {
                    continue;
                };
                // z(x) = plane value at each pixel centre; runs of passing pixels are shaded.
                let mut z = zplane.at(zrow, lo);
                let dz = zplane.step();
                let mut run: Option<i64> = None;
                for (x, old) in (lo..).zip(stored.iter_mut()) {
                    let zi = zplane.round(z) as u16;
                    if !opts.depth_test || zi < *old {
                        if opts.depth_write {
                            *old = zi;
                        }
                        run.get_or_insert(x);
                    } else if let Some(r) = run.take() {
                        emit(fb, &mut interp, r, x - 1, &mut stats);
                    }
                    z += dz;
                }
                if let Some(r) = run {
                    emit(fb, &mut interp, r, hi, &mut stats);
                }
            }
        }
    }
    stats
}

/// Hands pixels `lo..=hi` of the interp's row to the framebuffer and shader.
fn emit<F, S, const N: usize>(
    fb: &mut F,
    p: &mut SpanInterpolator<'_, S, N>,
    lo: i64,
    hi: i64,
    stats: &mut DrawStats,
) where
    F: Framebuffer,
    S: SpanShader<N, Color = F::Color>,
{
    let len = (hi - lo + 1) as u32;
    stats.pixels = stats.pixels.saturating_add(len);
    stats.spans = stats.spans.saturating_add(1);
    p.last = hi;
    let y = p.y;
    fb.fill_span(lo as u32, y as i32, len, |x, piece| {
        p.paint(i64::from(x), piece)
    });
}

/// Computes `start`/`step` for runs of one row and calls the shader.
struct SpanInterpolator<'s, S, const N: usize> {
    planes: [Plane; N],
    /// Vertex values per attribute, for perspective evaluation.
    values: [[i64; 3]; N],
    perspective: Option<Perspective>,
    /// Plane values at column 0 of the current row ([`FRAC`] bits).
    row: [i64; N],
    y: i64,
    /// Last column of the current run.
    last: i64,
    shader: &'s mut S,
}

impl<S: SpanShader<N>, const N: usize> SpanInterpolator<'_, S, N> {
    /// Sets the plane values for row `y`; then [`next_row`](Self::next_row) is called
    /// for every row from `y` on, in order.
    fn first_row(&mut self, y: i64) {
        if self.perspective.is_none() {
            for (r, p) in self.row.iter_mut().zip(self.planes.iter()) {
                *r = p.row(y) - p.row_step();
            }
        }
        self.y = y - 1;
    }

    /// Moves to row `y = previous + 1`: `row += gy·16` per attribute.
    fn next_row(&mut self, y: i64) {
        self.y = y;
        if self.perspective.is_none() {
            for (r, p) in self.row.iter_mut().zip(self.planes.iter()) {
                *r += p.row_step();
            }
        }
    }

    /// Shades `piece`, whose first pixel is column `x` of the current row.
    fn paint(&mut self, x: i64, piece: &mut [S::Color]) {
        let mut start = [0i32; N];
        let mut step = [0i32; N];
        let Some(persp) = self.perspective else {
            // start = round(plane(x + ½, y + ½)), step = round(∂a/∂x)
            for i in 0..N {
                let p = &self.planes[i];
                let a = p.round(p.at(self.row[i], x));
                let d = (p.step() + (1 << (FRAC - 1))) >> FRAC;
                (start[i], step[i]) = fit(a, d, piece.len(), p.lo, p.hi);
            }
            self.shader
                .shade_span(x as i32, self.y as i32, &start, &step, piece);
            return;
        };
        // Sub-spans of PERSPECTIVE_SPAN pixels: exact values at both ends,
        // step = (a(end) − a(start)) / (end − start).
        let y = self.y;
        let eval = |x: i64| {
            let beta = persp.weights(x, y);
            let mut a = [0i64; N];
            for (a, v) in a.iter_mut().zip(self.values.iter()) {
                *a = Perspective::value(&beta, v);
            }
            a
        };
        let mut cached: Option<(i64, [i64; N])> = None;
        let mut sx = x;
        for seg in piece.chunks_mut(PERSPECTIVE_SPAN) {
            let a0 = match cached {
                Some((cx, a)) if cx == sx => a,
                _ => eval(sx),
            };
            let ex = (sx + PERSPECTIVE_SPAN as i64).min(self.last).max(sx);
            let a1 = if ex > sx { eval(ex) } else { a0 };
            let span = ex - sx;
            for i in 0..N {
                let delta = a1[i] - a0[i];
                let d = match span {
                    0 => 0,
                    n if n == PERSPECTIVE_SPAN as i64 => (delta + n / 2) >> PERSPECTIVE_SHIFT,
                    n => (2 * delta + n).div_euclid(2 * n),
                };
                let p = &self.planes[i];
                (start[i], step[i]) = fit(a0[i], d, seg.len(), p.lo, p.hi);
            }
            self.shader
                .shade_span(sx as i32, y as i32, &start, &step, seg);
            cached = Some((ex, a1));
            sx += seg.len() as i64;
        }
    }
}

#[cfg(test)]
mod tests;
