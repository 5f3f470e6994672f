//! Where a frame's pixels go: a band strip flushed to any embedded-graphics
//! `DrawTarget` ([`Bands`]), or a whole frame in memory ([`FullFrame`]), both
//! in caller-owned memory; [`Checksum`], a display that only checksums what
//! it receives (firmware tests).
//!
//! A frame is drawn band by band: [`Bands::render`] (or [`FullFrame::render`],
//! one band) clears the band's strip and depth strip, hands a [`BandView`] to
//! every item ([`DrawBand`], implemented by the meshes of
//! [`crate::render`]) and sends the band to the display with one
//! `fill_contiguous` (what display drivers accelerate).

mod checksum;

pub use checksum::Checksum;

use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;

use crate::error::RenderError;

/// The largest frame width and height the renderer accepts: 1024.
pub(crate) const MAX_SIZE: u32 = 1024;

/// The band layout of a frame: `width` × `height` pixels drawn `band_rows`
/// rows at a time (the whole height for a full frame).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Layout {
    width: u32,
    height: u32,
    band_rows: u32,
}

impl Layout {
    /// A frame drawn in bands of `band_rows` rows.
    ///
    /// # Errors
    ///
    /// [`RenderError::Size`] unless `1 ≤ width, height ≤ 1024` and
    /// `band_rows ≥ 1`.
    ///
    /// A `const fn`: a layout known at compile time sizes the buffers of a
    /// firmware's statics (a bad layout is then a compile-time error):
    ///
    /// ```
    /// use fixshade::render::{bins_len, Layout};
    /// const LAYOUT: Layout = match Layout::banded(240, 240, 8) {
    ///     Ok(layout) => layout,
    ///     Err(_) => panic!("not a layout"),
    /// };
    /// const STRIP: usize = (LAYOUT.width() * LAYOUT.band_rows()) as usize;
    /// const BINS: usize = bins_len(720, LAYOUT.bands() as usize);
    /// assert_eq!((STRIP, LAYOUT.bands(), BINS), (1920, 30, 782));
    /// ```
    pub const fn banded(width: u32, height: u32, band_rows: u32) -> Result<Layout, RenderError> {
        if width == 0 || width > MAX_SIZE || height == 0 || height > MAX_SIZE || band_rows == 0 {
            return Err(RenderError::Size);
        }
        Ok(Layout {
            width,
            height,
            band_rows: if band_rows < height {
                band_rows
            } else {
                height
            },
        })
    }

    /// A frame drawn whole (one band).
    ///
    /// # Errors
    ///
    /// As [`Layout::banded`].
    pub const fn full(width: u32, height: u32) -> Result<Layout, RenderError> {
        Layout::banded(width, height, height)
    }

    /// Frame width.
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Frame height.
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// Rows per band (the last band may have fewer).
    pub const fn band_rows(&self) -> u32 {
        self.band_rows
    }

    /// Number of bands.
    pub const fn bands(&self) -> u32 {
        // band_rows ≥ 1 (the constructors): the test only drops the panic path
        let rows = if self.band_rows == 0 {
            1
        } else {
            self.band_rows
        };
        self.height.div_ceil(rows)
    }

    /// The rows of band `b`.
    pub fn rows(&self, b: u32) -> Range<i32> {
        // b·band_rows cannot overflow for b ≤ bands: both are at most MAX_SIZE
        let start = b
            .min(MAX_SIZE)
            .wrapping_mul(self.band_rows)
            .min(self.height);
        let end = (start + self.band_rows).min(self.height);
        start as i32..end as i32
    }

    /// The band containing row `y` (`0 ≤ y < height`).
    #[inline]
    pub(crate) fn band_of(&self, y: u32) -> u32 {
        if self.band_rows.is_power_of_two() {
            y >> self.band_rows.trailing_zeros()
        } else {
            y / self.band_rows.max(1)
        }
    }
}

/// The pixels of one band while it is drawn: colour and (optional) depth rows
/// in memory.
#[derive(Debug)]
pub struct BandView<'a, C> {
    pub(crate) color: &'a mut [C],
    pub(crate) depth: Option<&'a mut [u16]>,
    pub(crate) width: u32,
    pub(crate) rows: Range<i32>,
}

impl<'a, C> BandView<'a, C> {
    /// The frame rows this band holds.
    pub fn rows(&self) -> Range<i32> {
        self.rows.clone()
    }

    /// The frame width.
    pub const fn width(&self) -> u32 {
        self.width
    }
}

/// Something drawn band by band: a prepared mesh
/// ([`MeshDraw`](crate::render::MeshDraw)), or anything else with the same
/// interface (object-safe, so meshes with different shaders share one call).
pub trait DrawBand<C> {
    /// Draws what falls into `band`. Bands come in order, from the top, once
    /// per frame.
    fn draw_band(&mut self, band: &mut BandView<'_, C>);

    /// The layout the item was prepared for, if it depends on one (a mesh's
    /// bins do): [`Bands::render`] and [`FullFrame::render`] refuse to draw
    /// an item prepared for another layout. `None` (the default): any.
    fn layout(&self) -> Option<Layout> {
        None
    }
}

/// [`RenderError::LayoutMismatch`] unless every item fits `layout`.
fn check_layouts<C>(layout: Layout, items: &[&mut dyn DrawBand<C>]) -> Result<(), RenderError> {
    if items
        .iter()
        .any(|i| i.layout().is_some_and(|l| l != layout))
    {
        Err(RenderError::LayoutMismatch)
    } else {
        Ok(())
    }
}

/// The memory of [`Bands`] and [`FullFrame`]: colours and (optional) depth values
/// for `layout`, at least `width · band_rows` of each.
#[derive(Debug)]
struct Buffers<'a, C> {
    layout: Layout,
    color: &'a mut [C],
    depth: Option<&'a mut [u16]>,
}

impl<'a, C: Copy> Buffers<'a, C> {
    /// [`RenderError::BufferTooSmall`] naming `names[0]` (colour) or `names[1]`
    /// (depth) for a buffer shorter than `width · band_rows`.
    fn new(
        layout: Layout,
        names: [&'static str; 2],
        color: &'a mut [C],
        depth: Option<&'a mut [u16]>,
    ) -> Result<Self, RenderError> {
        let needed = layout.width as usize * layout.band_rows as usize;
        let lens = [Some(color.len()), depth.as_deref().map(<[u16]>::len)];
        for (which, got) in names.into_iter().zip(lens) {
            if let Some(got) = got.filter(|&got| got < needed) {
                return Err(RenderError::BufferTooSmall { which, needed, got });
            }
        }
        Ok(Buffers {
            layout,
            color,
            depth,
        })
    }

    /// Draws the band of `rows`: clears its colours to `clear` and its depth
    /// values to `u16::MAX`, lets every item draw, and returns the view (`None`
    /// for buffers too short, which [`Buffers::new`] excludes).
    fn draw(
        &mut self,
        rows: Range<i32>,
        clear: C,
        items: &mut [&mut dyn DrawBand<C>],
    ) -> Option<BandView<'_, C>> {
        let n = (rows.end - rows.start) as usize * self.layout.width as usize;
        let color = self.color.get_mut(..n)?;
        fill(color, clear);
        let mut depth = self.depth.as_deref_mut().and_then(|d| d.get_mut(..n));
        if let Some(d) = depth.as_deref_mut() {
            fill(d, u16::MAX);
        }
        let mut view = BandView {
            color,
            depth,
            width: self.layout.width,
            rows,
        };
        for item in items.iter_mut() {
            item.draw_band(&mut view);
        }
        Some(view)
    }
}

/// A frame drawn in horizontal bands through a caller-owned strip, each band
/// flushed to a [`DrawTarget`] (a display driver, the simulator).
///
/// RAM: `width · band_rows` colours and (with depth testing) as many `u16`s:
/// 7.5 KiB for a 240 × 240 `Rgb565` frame in 8-row bands.
#[derive(Debug)]
pub struct Bands<'a, C>(Buffers<'a, C>);

impl<'a, C: PixelColor> Bands<'a, C> {
    /// A band renderer for `layout` over `strip` (at least `width · band_rows`
    /// colours) and `depth` (as many values, or `None` for no depth test).
    ///
    /// # Errors
    ///
    /// [`RenderError::BufferTooSmall`] for a short strip or depth strip.
    pub fn new(
        layout: Layout,
        strip: &'a mut [C],
        depth: Option<&'a mut [u16]>,
    ) -> Result<Self, RenderError> {
        Buffers::new(layout, ["colour strip", "depth strip"], strip, depth).map(Bands)
    }

    /// The layout.
    pub fn layout(&self) -> Layout {
        self.0.layout
    }

    /// Renders a frame: for every band, clears the strip to `clear` and the
    /// depth strip to `u16::MAX`, lets every item draw, and sends the band to
    /// `display` with one `fill_contiguous`.
    ///
    /// # Errors
    ///
    /// [`RenderError::LayoutMismatch`] (nothing drawn) when an item was
    /// prepared for another layout; [`RenderError::Display`] with the
    /// display's first error (drawing stops there).
    pub fn render<D: DrawTarget<Color = C>>(
        &mut self,
        display: &mut D,
        clear: C,
        items: &mut [&mut dyn DrawBand<C>],
    ) -> Result<(), RenderError<D::Error>> {
        let layout = self.0.layout;
        check_layouts(layout, items).map_err(RenderError::widen)?;
        for b in 0..layout.bands() {
            let rows = layout.rows(b);
            let Some(view) = self.0.draw(rows.clone(), clear, items) else {
                return Ok(());
            };
            let area = Rectangle::new(
                Point::new(0, rows.start),
                Size::new(layout.width, (rows.end - rows.start) as u32),
            );
            display
                .fill_contiguous(&area, view.color.iter().copied())
                .map_err(RenderError::Display)?;
        }
        Ok(())
    }
}

/// A whole frame in caller-owned memory (row-major, `width` per row), with an
/// optional depth buffer of the same size.
#[derive(Debug)]
pub struct FullFrame<'a, C>(Buffers<'a, C>);

impl<'a, C: PixelColor> FullFrame<'a, C> {
    /// A frame over `color` (and `depth`), `width · height` elements each.
    ///
    /// # Errors
    ///
    /// [`RenderError::Size`] for a size out of range;
    /// [`RenderError::BufferTooSmall`] for short buffers.
    pub fn new(
        width: u32,
        height: u32,
        color: &'a mut [C],
        depth: Option<&'a mut [u16]>,
    ) -> Result<Self, RenderError> {
        let layout = Layout::full(width, height)?;
        Buffers::new(layout, ["frame", "depth buffer"], color, depth).map(FullFrame)
    }

    /// The layout (one band).
    pub fn layout(&self) -> Layout {
        self.0.layout
    }

    /// Clears the frame to `clear` and the depth buffer to `u16::MAX`, then
    /// lets every item draw.
    ///
    /// # Errors
    ///
    /// [`RenderError::LayoutMismatch`] (nothing drawn) when an item was
    /// prepared for another layout.
    pub fn render(
        &mut self,
        clear: C,
        items: &mut [&mut dyn DrawBand<C>],
    ) -> Result<(), RenderError> {
        check_layouts(self.0.layout, items)?;
        self.0.draw(0..self.0.layout.height as i32, clear, items);
        Ok(())
    }

    /// The pixels.
    pub fn pixels(&self) -> &[C] {
        self.0.color
    }

    /// Sends the frame to `display` with one `fill_contiguous`.
    pub fn flush<D: DrawTarget<Color = C>>(&self, display: &mut D) -> Result<(), D::Error> {
        let layout = self.0.layout;
        let n = layout.width as usize * layout.height as usize;
        let area = Rectangle::new(Point::zero(), Size::new(layout.width, layout.height));
        let px = self.0.color.get(..n).unwrap_or(&[]);
        display.fill_contiguous(&area, px.iter().copied())
    }
}

/// Sets every element (`slice::fill`: a `memset` where the value's bytes are
/// all equal, e.g. black and the far depth).
#[inline]
fn fill<T: Copy>(buf: &mut [T], v: T) {
    buf.fill(v);
}

#[cfg(test)]
mod tests {
    use super::MAX_SIZE;
    use crate::error::RenderError;
    use std::string::ToString;

    /// The size error's message states this module's limit.
    #[test]
    fn size_message_states_the_limit() {
        let m = RenderError::<core::convert::Infallible>::Size.to_string();
        assert!(m.contains(&std::format!("1 to {MAX_SIZE} pixels")), "{m}");
    }
}
