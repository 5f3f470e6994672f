//! A whole frame in a caller-owned slice.

use core::convert::Infallible;
use core::ops::Range;

use embedded_graphics_core::pixelcolor::PixelColor;

use super::{span_in, Framebuffer, TargetError};

/// A framebuffer over a caller-owned slice, row-major, `stride` elements per row.
///
/// Spans are sub-slices of the caller's memory, written in place. Pixel
/// `(x, y)` lives at index `y * stride + x`.
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// use fixshade::target::SliceFramebuffer;
///
/// let mut pixels = [Rgb565::BLACK; 32 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 32, 16).unwrap();
/// fb.clear(Rgb565::BLUE);
/// assert_eq!(fb.get(31, 15), Some(Rgb565::BLUE));
/// assert_eq!(fb.get(32, 0), None);
/// ```
#[derive(Debug)]
pub struct SliceFramebuffer<'a, C> {
    buf: &'a mut [C],
    width: u32,
    height: u32,
    stride: usize,
}

impl<'a, C: PixelColor> SliceFramebuffer<'a, C> {
    /// A tightly packed frame (`stride == width`).
    pub fn new(buf: &'a mut [C], width: u32, height: u32) -> Result<Self, TargetError> {
        Self::with_stride(buf, width, height, width as usize)
    }

    /// A frame whose rows start `stride` elements apart (`stride >= width`).
    ///
    /// Fails if a size is zero, `stride < width`, the height exceeds
    /// `i32::MAX`, or `buf` is shorter than `stride * (height - 1) + width`.
    pub fn with_stride(
        buf: &'a mut [C],
        width: u32,
        height: u32,
        stride: usize,
    ) -> Result<Self, TargetError> {
        if width == 0 || height == 0 {
            return Err(TargetError::ZeroSize);
        }
        if stride < width as usize {
            return Err(TargetError::StrideTooSmall);
        }
        if height > i32::MAX as u32 {
            return Err(TargetError::TooLarge);
        }
        let needed = stride
            .checked_mul(height as usize - 1)
            .and_then(|n| n.checked_add(width as usize))
            .ok_or(TargetError::TooLarge)?;
        if buf.len() < needed {
            return Err(TargetError::BufferTooSmall {
                needed,
                got: buf.len(),
            });
        }
        Ok(SliceFramebuffer {
            buf,
            width,
            height,
            stride,
        })
    }

    /// Frame height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Elements between the starts of two rows.
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The colour of pixel `(x, y)`, or `None` outside the frame.
    pub fn get(&self, x: u32, y: u32) -> Option<C> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.buf.get(y as usize * self.stride + x as usize).copied()
    }

    /// Sets every pixel of the frame (padding between rows is left alone).
    pub fn clear(&mut self, color: C) {
        let w = self.width as usize;
        for row in self.buf.chunks_mut(self.stride).take(self.height as usize) {
            for p in row.iter_mut().take(w) {
                *p = color;
            }
        }
    }

    /// The underlying slice.
    pub fn as_slice(&self) -> &[C] {
        self.buf
    }

    /// The underlying slice, mutably.
    pub fn as_mut_slice(&mut self) -> &mut [C] {
        self.buf
    }
}

impl<C: PixelColor> Framebuffer for SliceFramebuffer<'_, C> {
    type Color = C;
    type Error = Infallible;

    fn width(&self) -> u32 {
        self.width
    }

    fn rows(&self) -> Range<i32> {
        0..self.height as i32
    }

    fn fill_span<F: FnMut(u32, &mut [C])>(
        &mut self,
        x: u32,
        y: i32,
        len: u32,
        mut fill: F,
    ) -> Result<(), Infallible> {
        let Some(cols) = span_in(self.width, &self.rows(), x, y, len) else {
            return Ok(());
        };
        let row = y as usize * self.stride;
        if let Some(piece) = self.buf.get_mut(row + cols.start..row + cols.end) {
            fill(x, piece);
        }
        Ok(())
    }
}
