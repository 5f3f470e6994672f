//! Any embedded-graphics `DrawTarget` as a span framebuffer.

use core::fmt;
use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use super::{span_in, Framebuffer};

/// Pixels shaded per `fill_contiguous` call of a [`DrawTargetAdapter`].
pub const ADAPTER_CHUNK: usize = 64;

/// Drives any [`DrawTarget`] (display drivers, `SimulatorDisplay`, …) as a
/// [`Framebuffer`].
///
/// Each span is shaded into a stack buffer of [`ADAPTER_CHUNK`] pixels (longer
/// spans in several pieces) and sent with `fill_contiguous` on a 1-pixel-high
/// rectangle. A display error stops the span and is returned from
/// [`Framebuffer::fill_span`] (and from the drawing call that made it).
///
/// The accepted area comes from the display's `bounding_box()`: columns
/// `0..right edge`, rows `top..bottom`.
///
/// ```
/// use embedded_graphics::mock_display::MockDisplay;
/// use embedded_graphics_core::pixelcolor::BinaryColor;
/// use fixshade::target::{DrawTargetAdapter, Framebuffer};
///
/// let mut display = MockDisplay::<BinaryColor>::new();
/// let mut fb = DrawTargetAdapter::new(&mut display);
/// assert_eq!((fb.width(), fb.rows()), (64, 0..64));
/// fb.fill_span(2, 1, 3, |_x, piece| piece.fill(BinaryColor::On)).unwrap();
/// assert_eq!(display.get_pixel(embedded_graphics_core::geometry::Point::new(4, 1)), Some(BinaryColor::On));
/// ```
pub struct DrawTargetAdapter<'a, D: DrawTarget> {
    display: &'a mut D,
    buf: [D::Color; ADAPTER_CHUNK],
    width: u32,
    rows: Range<i32>,
}

impl<'a, D: DrawTarget> DrawTargetAdapter<'a, D>
where
    D::Color: Default,
{
    /// Wraps `display`; its bounding box is read once, here.
    pub fn new(display: &'a mut D) -> Self {
        let bb = display.bounding_box();
        let right = i64::from(bb.top_left.x) + i64::from(bb.size.width);
        let width = right.clamp(0, i64::from(i32::MAX)) as u32;
        let top = bb.top_left.y;
        let bottom = (i64::from(top) + i64::from(bb.size.height)).min(i64::from(i32::MAX)) as i32;
        DrawTargetAdapter {
            display,
            buf: [D::Color::default(); ADAPTER_CHUNK],
            width,
            rows: top..bottom,
        }
    }
}

impl<D: DrawTarget> DrawTargetAdapter<'_, D> {
    /// The wrapped display.
    pub fn display(&mut self) -> &mut D {
        self.display
    }
}

impl<D: DrawTarget> fmt::Debug for DrawTargetAdapter<'_, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("DrawTargetAdapter")
            .field("width", &self.width)
            .field("rows", &self.rows)
            .finish_non_exhaustive()
    }
}

impl<D: DrawTarget> Framebuffer for DrawTargetAdapter<'_, D> {
    type Color = D::Color;
    type Error = D::Error;

    fn width(&self) -> u32 {
        self.width
    }

    fn rows(&self) -> Range<i32> {
        self.rows.clone()
    }

    fn fill_span<F: FnMut(u32, &mut [D::Color])>(
        &mut self,
        x: u32,
        y: i32,
        len: u32,
        mut fill: F,
    ) -> Result<(), D::Error> {
        let Some(cols) = span_in(self.width, &self.rows, x, y, len) else {
            return Ok(());
        };
        let mut px = cols.start;
        while px < cols.end {
            let n = (cols.end - px).min(ADAPTER_CHUNK);
            let piece = &mut self.buf[..n];
            fill(px as u32, piece);
            let area = Rectangle::new(Point::new(px as i32, y), Size::new(n as u32, 1));
            self.display.fill_contiguous(&area, piece.iter().copied())?;
            px += n;
        }
        Ok(())
    }
}
