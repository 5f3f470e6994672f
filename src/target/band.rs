//! A full frame rendered strip by strip through a small buffer.

use core::convert::Infallible;
use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;

use super::{span_in, DepthBuffer, Framebuffer, TargetError};

/// Renders a `frame_width` × `frame_height` frame in horizontal bands of
/// `N = buf.len() / frame_width` rows, each flushed to a [`DrawTarget`].
///
/// Band `i` covers frame rows `i·N .. min((i+1)·N, frame_height)`; as a
/// [`Framebuffer`] the band buffer accepts only those rows, and the rasterizer
/// clips every triangle to them. The scene is drawn once per band.
///
/// RAM: a 240×240 `Rgb565` frame needs 112.5 KiB as a whole; with 8-row bands
/// the colour strip is 240 · 8 · 2 B = 3.75 KiB (plus 3.75 KiB for an 8-row
/// [`DepthBuffer`] if depth testing is used), for 30 passes over the scene.
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// use embedded_graphics_core::geometry::{Point, Size};
/// use embedded_graphics_simulator::SimulatorDisplay;
/// use fixshade::raster::{draw_triangle, RasterOptions, RasterVertex, SpanShader, SUBPIXEL_BITS};
/// use fixshade::target::BandBuffer;
/// # struct Solid(Rgb565);
/// # impl SpanShader<0> for Solid {
/// #     type Color = Rgb565;
/// #     fn shade_span(&mut self, _x: i32, _y: i32, _s: &[i32; 0], _d: &[i32; 0], out: &mut [Rgb565]) {
/// #         out.fill(self.0);
/// #     }
/// # }
///
/// let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(240, 240));
/// // 8 rows of 240 pixels: 3.75 KiB instead of 112.5 KiB.
/// let mut strip = [Rgb565::BLACK; 240 * 8];
/// let mut band = BandBuffer::new(&mut strip, 240, 240).unwrap();
/// assert_eq!(band.bands(), 30);
///
/// let px = |x: i32, y: i32| RasterVertex { x: x << SUBPIXEL_BITS, y: y << SUBPIXEL_BITS, z: 0, inv_w: 1, attrs: [] };
/// let tri = [px(10, 10), px(230, 40), px(60, 230)];
/// band.render(&mut display, Rgb565::BLACK, |fb| {
///     draw_triangle(fb, None, &tri, &RasterOptions::default(), &mut Solid(Rgb565::RED));
/// })
/// .unwrap();
/// assert_eq!(display.get_pixel(Point::new(100, 100)), Rgb565::RED);
/// assert_eq!(display.get_pixel(Point::new(230, 230)), Rgb565::BLACK);
/// ```
#[derive(Debug)]
pub struct BandBuffer<'a, C> {
    buf: &'a mut [C],
    width: u32,
    height: u32,
    band_rows: u32,
    band: u32,
}

impl<'a, C: PixelColor> BandBuffer<'a, C> {
    /// A band buffer for a `frame_width` × `frame_height` frame over `buf`,
    /// which holds `buf.len() / frame_width` rows (at least one). Band 0 is selected.
    pub fn new(buf: &'a mut [C], frame_width: u32, frame_height: u32) -> Result<Self, TargetError> {
        if frame_width == 0 || frame_height == 0 {
            return Err(TargetError::ZeroSize);
        }
        if frame_width > i32::MAX as u32 || frame_height > i32::MAX as u32 {
            return Err(TargetError::TooLarge);
        }
        let rows = buf.len() / frame_width as usize;
        if rows == 0 {
            return Err(TargetError::BufferTooSmall {
                needed: frame_width as usize,
                got: buf.len(),
            });
        }
        let band_rows = rows.min(frame_height as usize) as u32;
        Ok(BandBuffer {
            buf,
            width: frame_width,
            height: frame_height,
            band_rows,
            band: 0,
        })
    }

    /// Rows per band (the last band may have fewer).
    pub fn band_rows(&self) -> u32 {
        self.band_rows
    }

    /// Number of bands in the frame.
    pub fn bands(&self) -> u32 {
        self.height.div_ceil(self.band_rows)
    }

    /// The selected band.
    pub fn band(&self) -> u32 {
        self.band
    }

    /// Selects band `i`; returns `false` (and changes nothing) if `i >= bands()`.
    pub fn set_band(&mut self, i: u32) -> bool {
        if i >= self.bands() {
            return false;
        }
        self.band = i;
        true
    }

    /// Frame height in pixels.
    pub fn frame_height(&self) -> u32 {
        self.height
    }

    /// Sets every pixel of the selected band.
    pub fn clear(&mut self, color: C) {
        let n = self.band_len();
        let n = n.min(self.buf.len());
        self.buf[..n].fill(color);
    }

    /// Sends the selected band to `display` with one `fill_contiguous`.
    pub fn flush<D: DrawTarget<Color = C>>(&self, display: &mut D) -> Result<(), D::Error> {
        let rows = self.rows();
        let area = Rectangle::new(
            Point::new(0, rows.start),
            Size::new(self.width, (rows.end - rows.start) as u32),
        );
        let px = self.buf.get(..self.band_len()).unwrap_or(&[]);
        display.fill_contiguous(&area, px.iter().copied())
    }

    /// Draws a whole frame: for every band, clears it to `clear_color`, calls
    /// `draw` (which draws the whole scene; the rasterizer keeps only the
    /// band's rows) and flushes it. Stops at the first display error.
    pub fn render<D, F>(
        &mut self,
        display: &mut D,
        clear_color: C,
        mut draw: F,
    ) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
        F: FnMut(&mut Self),
    {
        for i in 0..self.bands() {
            self.set_band(i);
            self.clear(clear_color);
            draw(self);
            self.flush(display)?;
        }
        Ok(())
    }

    /// Like [`render`](BandBuffer::render) with a depth buffer that follows the
    /// band: before each band, `depth` is moved to the band's first row and
    /// cleared to `far`. Give `depth` at least [`band_rows`](BandBuffer::band_rows)
    /// rows of `frame_width` values (rows it lacks are not drawn when depth is used).
    pub fn render_with_depth<D, F>(
        &mut self,
        display: &mut D,
        clear_color: C,
        depth: &mut DepthBuffer<'_>,
        far: u16,
        mut draw: F,
    ) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
        F: FnMut(&mut Self, &mut DepthBuffer<'_>),
    {
        for i in 0..self.bands() {
            self.set_band(i);
            self.clear(clear_color);
            depth.set_first_row(self.rows().start);
            depth.clear(far);
            draw(self, depth);
            self.flush(display)?;
        }
        Ok(())
    }

    /// Pixels in the selected band.
    fn band_len(&self) -> usize {
        let rows = self.rows();
        (rows.end - rows.start) as usize * self.width as usize
    }
}

impl<C: PixelColor> Framebuffer for BandBuffer<'_, C> {
    type Color = C;
    type Error = Infallible;

    fn width(&self) -> u32 {
        self.width
    }

    fn rows(&self) -> Range<i32> {
        let first = self.band * self.band_rows;
        let end = (first + self.band_rows).min(self.height);
        first as i32..end as i32
    }

    fn fill_span<F: FnMut(u32, &mut [C])>(
        &mut self,
        x: u32,
        y: i32,
        len: u32,
        mut fill: F,
    ) -> Result<(), Infallible> {
        let rows = self.rows();
        let Some(cols) = span_in(self.width, &rows, x, y, len) else {
            return Ok(());
        };
        let row = (y - rows.start) as usize * self.width as usize;
        if let Some(piece) = self.buf.get_mut(row + cols.start..row + cols.end) {
            fill(x, piece);
        }
        Ok(())
    }
}
