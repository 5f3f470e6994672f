//! Framebuffers: where the rasterizer writes its spans.
//!
//! The rasterizer never writes single pixels: it asks a [`Framebuffer`] for a
//! whole horizontal run of pixels and lets the shader fill it. Four rooms:
//!
//! - [`SliceFramebuffer`] — a full frame in a caller-owned slice, written in place;
//! - [`DrawTargetAdapter`] — any embedded-graphics `DrawTarget` (every display
//!   driver, the simulator), fed through a small stack buffer;
//! - [`BandBuffer`] — a full frame rendered in horizontal strips through a few
//!   KiB of RAM, each strip flushed to a `DrawTarget`;
//! - [`DepthBuffer`] — caller-owned `u16` depth values (smaller is nearer).

use core::fmt;
use core::ops::Range;

use embedded_graphics_core::pixelcolor::PixelColor;

mod band;
mod checksum;
mod depth;
mod draw_target;
mod slice;

pub use band::BandBuffer;
pub use checksum::Checksum;
pub use depth::DepthBuffer;
pub use draw_target::{DrawTargetAdapter, ADAPTER_CHUNK};
pub use slice::SliceFramebuffer;

/// A surface that accepts horizontal spans of pixels.
///
/// The accepted pixels are `x` in `0..width()` and `y` in `rows()` (a band
/// buffer covers only some rows of the frame). The rasterizer clips every span
/// to that rectangle before calling [`fill_span`](Framebuffer::fill_span);
/// implementations ignore requests that are not inside it (they never panic).
///
/// ```
/// use embedded_graphics_core::pixelcolor::Gray8;
/// use fixshade::target::{Framebuffer, SliceFramebuffer};
///
/// let mut pixels = [Gray8::new(0); 4 * 2];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 4, 2).unwrap();
/// // Pixels 1..4 of row 1 become 1, 2, 3.
/// fb.fill_span(1, 1, 3, |x, piece| {
///     for (i, p) in piece.iter_mut().enumerate() {
///         *p = Gray8::new((x as usize + i) as u8);
///     }
/// })?;
/// assert_eq!(fb.get(3, 1), Some(Gray8::new(3)));
/// # Ok::<(), core::convert::Infallible>(())
/// ```
pub trait Framebuffer {
    /// The colour stored per pixel.
    type Color: PixelColor;
    /// What can go wrong when pixels are written: [`Infallible`](core::convert::Infallible) for buffers in
    /// memory, the display's error for a [`DrawTargetAdapter`].
    type Error;

    /// Number of pixel columns: spans live in `x` in `0..width()`.
    fn width(&self) -> u32;

    /// The rows this buffer currently accepts (all rows of a frame buffer,
    /// the rows of the current band for a [`BandBuffer`]).
    fn rows(&self) -> Range<i32>;

    /// Hands out pixels `x..x + len` of row `y` for writing.
    ///
    /// `fill(px, piece)` is called one or more times with consecutive pieces,
    /// in order from left to right, that together cover the span; `px` is the
    /// column of the first pixel of `piece`. `fill` must write every pixel of
    /// every piece. Spans outside `0..width()` × `rows()` are ignored. An error
    /// of the underlying surface stops the span and is returned.
    fn fill_span<F: FnMut(u32, &mut [Self::Color])>(
        &mut self,
        x: u32,
        y: i32,
        len: u32,
        fill: F,
    ) -> Result<(), Self::Error>;
}

/// Why a framebuffer could not be built over a caller's slice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum TargetError {
    /// Width or height is zero.
    ZeroSize,
    /// The row stride is smaller than the width.
    StrideTooSmall,
    /// The slice holds fewer elements than the frame (or one row) needs.
    BufferTooSmall {
        /// Elements needed.
        needed: usize,
        /// Elements given.
        got: usize,
    },
    /// A dimension does not fit the index arithmetic of this platform.
    TooLarge,
}

impl fmt::Display for TargetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TargetError::ZeroSize => f.write_str("framebuffer width or height is zero"),
            TargetError::StrideTooSmall => {
                f.write_str("framebuffer stride is smaller than its width")
            }
            TargetError::BufferTooSmall { needed, got } => {
                write!(
                    f,
                    "framebuffer slice too small: needs {needed} elements, got {got}"
                )
            }
            TargetError::TooLarge => f.write_str("framebuffer dimensions overflow usize"),
        }
    }
}

/// Checks that a span lies inside `0..width` × `rows` and returns the index
/// range of its pixels relative to the start of row `y`, or `None`.
pub(crate) fn span_in(
    width: u32,
    rows: &Range<i32>,
    x: u32,
    y: i32,
    len: u32,
) -> Option<Range<usize>> {
    let end = x.checked_add(len)?;
    if len == 0 || end > width || !rows.contains(&y) {
        return None;
    }
    Some(x as usize..end as usize)
}

impl core::error::Error for TargetError {}
