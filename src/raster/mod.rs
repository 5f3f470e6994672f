//! Triangle rasterization in 32-bit integer arithmetic: exact edge walking with
//! a top-left fill rule, clipping to a guard window, optional depth test and
//! screen-linear or perspective-correct attribute interpolation.
//!
//! [`draw_triangle`] turns three [`RasterVertex`]es into horizontal runs of
//! pixels and hands each run to a [`SpanShader`], which writes the colours
//! into a [`Framebuffer`] span. The mesh renderer ([`crate::render`]) uses the
//! same set-up and walker with its own depth-fused span kernels.
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
//! - **Window**: set-up works on vertices inside a window of 2^15 sub-pixels
//!   per axis, [`WINDOW_MIN`]`..=`[`WINDOW_MAX`] (−512 to 1536 pixels), so
//!   that every product of the set-up fits 32 bits. A triangle reaching beyond
//!   it is clipped to the window first (Sutherland–Hodgman; every cut point is
//!   computed from its edge's endpoints in a fixed order, so neighbours that
//!   share the edge get the same point and stay watertight). Frames up to
//!   1024 × 1024 pixels lie inside the window with a guard band of at least
//!   512 pixels; columns and rows beyond 1536 are never drawn.
//! - **Depth**: `z` is interpolated linearly in screen space; smaller is
//!   nearer; a pixel passes when `z < stored` (see [`DepthBuffer`]).
//!
//! # Arithmetic
//!
//! The set-up of a triangle takes one 32-bit division (the reciprocal of its
//! area) and a few dozen 32 × 32 → 32-bit multiplications; edges are walked
//! column by column without division (exact: the same integers as evaluating
//! the edge functions at every pixel). Clipping to the window, which only
//! triangles larger than the window need, uses 64-bit values built from
//! 32-bit operations (no 64-bit multiply or divide routine is linked).
//!
//! # Attribute precision
//!
//! [`draw_triangle`] evaluates the plane through the three vertex values
//! exactly at the first and the last pixel of every run (barycentric
//! numerators are exact edge-function values; products and the division in 64
//! bits, rounded once), so the value handed to a shader for the first pixel of
//! a run is the exact value rounded to a unit (at most ½ unit off). The step is
//! the difference of the two end values divided by the run length, rounded,
//! and shrunk towards zero where `start + k·step` would leave the range of the
//! three vertex values: pixel `k` of a run is at most `½ + k` units off the
//! exact plane (rounding alone gives `½ + k·(½ + 1/len)`; the shrink truncates).
//! The worst case found by a search (thin triangles, attribute differences up
//! to the 2^29 limit, runs of up to 200 pixels) is `½ + k` exactly:
//! `tests/raster_precision.rs`. A shader that needs every pixel within a unit
//! steps at most a few pixels or uses short runs. Values are always clamped:
//! `start + k·step` stays within the range of the three vertex values for every
//! `k < len` of a run, so shaders may use plain `i32` arithmetic. Framebuffers
//! that hand out a run in several pieces get `start + k·step` continued across
//! the pieces: the image does not depend on how a framebuffer splits spans
//! (`tests/framebuffer_pieces.rs`).
//!
//! The mesh renderer ([`crate::render`]) interpolates from per-triangle planes
//! whose barycentric coefficients carry 14 significant bits instead (one
//! reciprocal per triangle, no 64-bit arithmetic per run).
//!
//! With [`draw_triangle_perspective`], attribute values are computed
//! perspective-correctly at the ends of sub-spans of [`PERSPECTIVE_SPAN`]
//! pixels and interpolated linearly in between. The weights `qᵢ·nᵢ` (`q` the
//! [`RasterVertex::inv_w`], any positive `i32`: no truncation of `1/w`) are
//! truncated to 30 significant bits, so a sub-span end is the exact value
//! rounded, plus at most `5·2^−29·max|Δa|` units (a bound from the arithmetic:
//! each of the three truncated weights is off by less than one part in 2^29 of
//! their sum; 10 units at the ±2^29 attribute limit, under ½ unit for vertex
//! differences below 2^25). Between the ends the extra error is about
//! `¼·|Δa|·|Δq/q|` (`Δa`, `Δq/q`: the change of the attribute and the relative
//! change of `1/w` across the sub-span).

use crate::target::{DepthBuffer, Framebuffer};

pub(crate) mod clip;
mod edge;
mod exact;
pub(crate) mod setup;

pub(crate) use edge::Walker;
pub(crate) use setup::ClampTo;
pub use setup::ATTR_FRAC;
#[doc(hidden)]
pub use setup::{Plane, Setup};

/// Fractional bits of [`RasterVertex::x`] and [`RasterVertex::y`]: 4, i.e.
/// positions are in 1/16 pixel.
pub const SUBPIXEL_BITS: u32 = 4;

/// The smallest sub-pixel coordinate set-up works on: −512 pixels.
pub const WINDOW_MIN: i32 = -(1 << 13);
/// The largest sub-pixel coordinate set-up works on: just below 1536 pixels
/// (`WINDOW_MAX − WINDOW_MIN = 2^15 − 1`).
pub const WINDOW_MAX: i32 = (3 << 13) - 1;

/// Length of the sub-spans whose ends are computed exactly by
/// [`draw_triangle_perspective`] (8).
pub const PERSPECTIVE_SPAN: usize = 1 << PERSPECTIVE_SHIFT;
const PERSPECTIVE_SHIFT: u32 = 3;

/// Attribute values of [`RasterVertex::attrs`] are clamped to ±`ATTR_LIMIT`
/// (2^29) before set-up.
pub const ATTR_LIMIT: i32 = 1 << 29;

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
    /// three vertices (only ratios matter; any ratio of positive `i32`s is
    /// used as given, see the module docs for the precision).
    /// Used only by [`draw_triangle_perspective`]; values `<= 0` count as the
    /// smallest positive value.
    pub inv_w: i32,
    /// Attributes in caller-chosen fixed-point units, within ±[`ATTR_LIMIT`]
    /// (larger values are clamped).
    pub attrs: [i32; N],
}

/// Which triangles are skipped.
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
    /// Test `z < stored` against the depth buffer, if one is given.
    pub depth_test: bool,
    /// Store `z` of drawn pixels in the depth buffer, if one is given.
    pub depth_write: bool,
}

impl Default for RasterOptions {
    /// No culling, depth test and write on.
    fn default() -> Self {
        RasterOptions {
            cull: Cull::None,
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

impl DrawStats {
    /// The sum of two statistics (saturating).
    pub fn add(self, o: DrawStats) -> DrawStats {
        DrawStats {
            pixels: self.pixels.saturating_add(o.pixels),
            spans: self.spans.saturating_add(o.spans),
        }
    }
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
    /// `start + k·step`, which stays within the vertex range for `k <
    /// out.len()` (no `i32` overflow; `start + out.len()·step` may overflow,
    /// so do not compute it). See the [module docs](self) for the error bounds.
    fn shade_span(
        &mut self,
        x: i32,
        y: i32,
        start: &[i32; N],
        step: &[i32; N],
        out: &mut [Self::Color],
    );
}

/// Rasterizes one triangle into `fb`, shading every covered pixel with
/// `shader`, attributes interpolated linearly in screen space.
///
/// Pixels are covered by the top-left rule, clipped to `fb.width()` ×
/// `fb.rows()` (and to the depth buffer when it is used). If `depth` is given
/// and `opts.depth_test` is set, only pixels with `z < stored` are drawn; if
/// `opts.depth_write` is set, drawn pixels store their `z`. The shader is
/// called once per maximal run of drawn pixels (per framebuffer piece).
///
/// Never panics, for any vertex values. Returns the first error of the
/// framebuffer (drawing stops there).
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
///         for (k, p) in out.iter_mut().enumerate() {
///             // luma = (start + k·step) / 256
///             *p = Gray8::new(((start[0] + k as i32 * step[0]) >> 8) as u8);
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
/// let stats = draw_triangle(&mut fb, None, &tri, &RasterOptions::default(), &mut Ramp).unwrap();
/// assert_eq!(stats.pixels, 120); // 15 + 14 + … + 1: centres on the hypotenuse (a right edge) are out
/// assert_eq!(fb.get(5, 0), Some(Gray8::new(55))); // centre x = 5.5: 160 · 5.5/16
/// ```
pub fn draw_triangle<F, S, const N: usize>(
    fb: &mut F,
    depth: Option<&mut DepthBuffer<'_>>,
    v: &[RasterVertex<N>; 3],
    opts: &RasterOptions,
    shader: &mut S,
) -> Result<DrawStats, F::Error>
where
    F: Framebuffer,
    S: SpanShader<N, Color = F::Color>,
{
    draw_clipped::<F, S, N, false>(fb, depth, v, opts, shader)
}

/// [`draw_triangle`] with perspective-correct attributes: with `qᵢ` the
/// [`RasterVertex::inv_w`] of the vertices and `βᵢ` the screen-space
/// barycentric weights, a pixel gets `Σ βᵢ·qᵢ·aᵢ / Σ βᵢ·qᵢ`, computed at the
/// ends of sub-spans of [`PERSPECTIVE_SPAN`] pixels (one division per sub-span
/// end and attribute) and interpolated linearly in between. Depth stays
/// screen-linear.
///
/// The extra error inside a sub-span is about `¼·|Δa|·|Δq/q|`, `Δa` and
/// `Δq/q` being the change of the attribute and the relative change of `1/w`
/// across it.
pub fn draw_triangle_perspective<F, S, const N: usize>(
    fb: &mut F,
    depth: Option<&mut DepthBuffer<'_>>,
    v: &[RasterVertex<N>; 3],
    opts: &RasterOptions,
    shader: &mut S,
) -> Result<DrawStats, F::Error>
where
    F: Framebuffer,
    S: SpanShader<N, Color = F::Color>,
{
    draw_clipped::<F, S, N, true>(fb, depth, v, opts, shader)
}

/// Whether a sub-pixel position lies inside the window.
#[inline(always)]
pub(crate) fn in_window(x: i32, y: i32) -> bool {
    (WINDOW_MIN..=WINDOW_MAX).contains(&x) && (WINDOW_MIN..=WINDOW_MAX).contains(&y)
}

fn draw_clipped<F, S, const N: usize, const PERSP: bool>(
    fb: &mut F,
    mut depth: Option<&mut DepthBuffer<'_>>,
    v: &[RasterVertex<N>; 3],
    opts: &RasterOptions,
    shader: &mut S,
) -> Result<DrawStats, F::Error>
where
    F: Framebuffer,
    S: SpanShader<N, Color = F::Color>,
{
    let mut v = *v;
    for p in v.iter_mut() {
        for a in p.attrs.iter_mut() {
            *a = (*a).clamp_to(-ATTR_LIMIT, ATTR_LIMIT);
        }
        p.inv_w = p.inv_w.max(1);
    }
    if v.iter().all(|p| in_window(p.x, p.y)) {
        return draw_inside::<F, S, N, PERSP>(fb, depth, &v, opts, shader);
    }
    // cull on the unclipped triangle (clipping keeps the winding)
    let mut poly = clip::Polygon::new(&v.map(clip::Cut::<N, PERSP>));
    let Some(front) = poly.facing() else {
        return Ok(DrawStats::default());
    };
    let culled = match opts.cull {
        Cull::None => false,
        Cull::Back => !front,
        Cull::Front => front,
    };
    if culled {
        return Ok(DrawStats::default());
    }
    poly.clip_to_window();
    let mut stats = DrawStats::default();
    let mut tri = [clip::Cut(v[0]); 3];
    let mut k = 0;
    while poly.fan(k, &mut tri) {
        let t = tri.map(|c| c.0);
        let s = draw_inside::<F, S, N, PERSP>(fb, depth.as_deref_mut(), &t, opts, shader)?;
        stats = stats.add(s);
        k += 1;
    }
    Ok(stats)
}

/// Draws a triangle whose vertices are inside the window.
fn draw_inside<F, S, const N: usize, const PERSP: bool>(
    fb: &mut F,
    depth: Option<&mut DepthBuffer<'_>>,
    v: &[RasterVertex<N>; 3],
    opts: &RasterOptions,
    shader: &mut S,
) -> Result<DrawStats, F::Error>
where
    F: Framebuffer,
    S: SpanShader<N, Color = F::Color>,
{
    let mut stats = DrawStats::default();
    let Some(s) = Setup::new(
        [(v[0].x, v[0].y), (v[1].x, v[1].y), (v[2].x, v[2].y)],
        opts.cull,
    ) else {
        return Ok(stats);
    };
    let mut depth = if opts.depth_test || opts.depth_write {
        depth
    } else {
        None
    };
    // scissor: columns 0..x_end, rows y_start..y_end
    let fb_rows = fb.rows();
    let mut x_end = fb.width().min((WINDOW_MAX >> SUBPIXEL_BITS) as u32) as i32;
    let mut y_start = fb_rows.start.max(s.rows.0);
    let mut y_end = fb_rows.end.min(s.rows.1.saturating_add(1));
    if let Some(d) = depth.as_deref() {
        x_end = x_end.min(d.width().min(i32::MAX as u32) as i32);
        y_start = y_start.max(d.rows().start);
        y_end = y_end.min(d.rows().end);
    }
    if y_start >= y_end || x_end <= 0 {
        return Ok(stats);
    }
    let mut walker = s.walker(y_start);
    let exact = exact::Exact::<N, PERSP>::new(&s, v);
    let mut run = Runner {
        exact: &exact,
        shader,
    };
    while walker.more() && walker.y < y_end {
        let y = walker.y;
        let (lo, hi) = walker.next();
        let (lo, hi) = (lo.max(0), hi.min(x_end - 1));
        if lo > hi {
            continue;
        }
        match depth.as_deref_mut() {
            None => run.emit(fb, y, lo, hi, &mut stats)?,
            Some(d) => {
                let Some(stored) = d.row_mut(y, lo as u32..(hi + 1) as u32) else {
                    continue;
                };
                // z at each pixel centre: exact at both ends, stepped between
                let (z0, dz) = exact.depth_run(lo, hi, y);
                let mut z = z0;
                let mut start: Option<i32> = None;
                for (x, old) in (lo..).zip(stored.iter_mut()) {
                    let zi = (z >> exact::Z_FRAC) as u16;
                    if !opts.depth_test || zi < *old {
                        if opts.depth_write {
                            *old = zi;
                        }
                        start.get_or_insert(x);
                    } else if let Some(r) = start.take() {
                        run.emit(fb, y, r, x - 1, &mut stats)?;
                    }
                    // the value after the last pixel is not used: wrapping is harmless
                    z = z.wrapping_add(dz);
                }
                if let Some(r) = start {
                    run.emit(fb, y, r, hi, &mut stats)?;
                }
            }
        }
    }
    Ok(stats)
}

/// Hands runs to the framebuffer and the shader, with exact attribute values.
struct Runner<'a, S, const N: usize, const PERSP: bool> {
    exact: &'a exact::Exact<N, PERSP>,
    shader: &'a mut S,
}

impl<S: SpanShader<N>, const N: usize, const PERSP: bool> Runner<'_, S, N, PERSP> {
    /// Hands pixels `lo..=hi` of row `y` to the framebuffer and shader.
    fn emit<F: Framebuffer<Color = S::Color>>(
        &mut self,
        fb: &mut F,
        y: i32,
        lo: i32,
        hi: i32,
        stats: &mut DrawStats,
    ) -> Result<(), F::Error> {
        let len = (hi - lo + 1) as u32;
        stats.pixels = stats.pixels.saturating_add(len);
        stats.spans = stats.spans.saturating_add(1);
        let exact = self.exact;
        let shader = &mut *self.shader;
        // segments: the whole run (screen-linear) or PERSPECTIVE_SPAN pixels from
        // its first pixel (perspective), whatever pieces the framebuffer hands out
        let seg = if PERSP {
            PERSPECTIVE_SPAN as i32
        } else {
            i32::MAX
        };
        let mut cur: Option<(i32, [i32; N], [i32; N])> = None;
        fb.fill_span(lo as u32, y, len, |px, piece| {
            let mut x = px as i32;
            let mut rest = piece;
            while !rest.is_empty() {
                let k0 = if PERSP {
                    lo + (((x - lo) >> PERSPECTIVE_SHIFT) << PERSPECTIVE_SHIFT)
                } else {
                    lo
                };
                let k1 = k0.saturating_add(seg).min(hi + 1) - 1;
                let (s0, d) = match cur {
                    Some((k, s0, d)) if k == k0 => (s0, d),
                    _ => {
                        let (s0, d) = exact.segment(k0, k1, y);
                        cur = Some((k0, s0, d));
                        (s0, d)
                    }
                };
                let n = ((k1 + 1 - x) as usize).min(rest.len());
                let (part, tail) = rest.split_at_mut(n);
                // pixel k of the segment is s0 + k·d; this part starts at k = x − k0
                let start = core::array::from_fn(|i| s0[i].wrapping_add(d[i].wrapping_mul(x - k0)));
                shader.shade_span(x, y, &start, &d, part);
                x += n as i32;
                rest = tail;
            }
        })
    }
}

/// `step` shrunk toward zero if needed so that `start + k·step` stays in
/// `lo..=hi` for every `k < n` (`start` already in range).
#[inline]
pub(crate) fn fit(start: i32, step: i32, n: i32, lo: i32, hi: i32) -> (i32, i32) {
    if n <= 1 {
        return (start, 0);
    }
    let k = n - 1;
    let up = hi.wrapping_sub(start) as u32; // hi ≥ start
    let dn = start.wrapping_sub(lo) as u32; // start ≥ lo
    let d = if step > 0 && step.unsigned_abs() > up / k as u32 {
        (up / k as u32) as i32
    } else if step < 0 && step.unsigned_abs() > dn / k as u32 {
        -((dn / k as u32) as i32)
    } else {
        step
    };
    (start, d)
}

#[cfg(test)]
mod tests;
