//! Where a frame's pixels go: a band strip flushed to any embedded-graphics
//! `DrawTarget` ([`Bands`]), or a whole frame in memory ([`FullFrame`]), both
//! in caller-owned memory; [`Checksum`], a display that only checksums what
//! it receives (firmware tests).
//!
//! Per band, [`Bands::render`] (or [`FullFrame::render`], one band) clears the
//! strip and depth strip, lets every item ([`DrawBand`]: the meshes of
//! [`crate::render`], and every embedded-graphics `Drawable` — text, shapes,
//! images over or under the 3D, see [`BandView`]'s `DrawTarget`) draw into a
//! [`BandView`], and hands the band to a
//! [`BandSink`] (see there). Several renderers (one per core) can share a
//! frame's bands ([`Bands::render_bands`]).

mod checksum;
mod overlay;

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
    /// A `const fn`: a compile-time layout sizes a firmware's static buffers
    /// (a bad one is then a compile error):
    ///
    /// ```
    /// use fixshade::render::bins_len;
    /// use fixshade::framebuffer::Layout;
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
///
/// **2D over 3D**: a band is an embedded-graphics `DrawTarget` in screen
/// coordinates, and every embedded-graphics `Drawable` (text, primitives,
/// images) is a [`DrawBand`] item. A band's view is clipped to the band: a pixel outside its rows or the
/// frame's width is dropped, so a drawable drawn into every band of a frame
/// (by [`Bands::render`]) gives, bit for bit, the frame
/// the same drawable would give drawn once over the whole picture. Items draw
/// in the order of the slice: a drawable after the meshes is drawn over them
/// (a label, a HUD), one before them is a background the meshes cover. 2D
/// items write colours only: they neither test nor write depth.
///
/// ```
/// use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use embedded_graphics::prelude::*;
/// use embedded_graphics::text::Text;
/// use fixshade::framebuffer::FullFrame;
///
/// let mut color = [Rgb565::BLACK; 64 * 16];
/// let mut frame = FullFrame::new(64, 16, &mut color, None)?;
/// let mut label = Text::new("fixshade", Point::new(2, 10), MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE));
/// // with meshes: &mut [&mut sphere, &mut label], the label drawn over the sphere
/// frame.render(Rgb565::BLACK, &mut [&mut label])?;
/// assert!(frame.pixels().contains(&Rgb565::WHITE));
/// # Ok::<(), fixshade::error::RenderError>(())
/// ```
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
    /// Draws what falls into `band`: once per band of a frame, in the order
    /// the renderer draws them ([`Bands::render`]: from the top;
    /// [`Bands::render_bands`]: the order it is given).
    fn draw_band(&mut self, band: &mut BandView<'_, C>);

    /// Whether the item can be drawn in frames of `layout`, checked before
    /// anything is drawn; the default: any layout.
    ///
    /// # Errors
    ///
    /// Why not: a mesh binned for another layout
    /// ([`RenderError::LayoutMismatch`]) or short of resume records
    /// ([`RenderError::BufferTooSmall`]).
    fn check(&self, layout: Layout) -> Result<(), RenderError> {
        let _ = layout;
        Ok(())
    }
}

/// The first item's error from [`DrawBand::check`].
fn check_items<C>(layout: Layout, items: &[&mut dyn DrawBand<C>]) -> Result<(), RenderError> {
    items.iter().try_for_each(|i| i.check(layout))
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
        let lens = [color.len(), depth.as_deref().map_or(needed, <[u16]>::len)];
        for (which, got) in names.into_iter().zip(lens) {
            RenderError::check_len(which, needed, got)?;
        }
        Ok(Buffers {
            layout,
            color,
            depth,
        })
    }

    /// Colours (and depth values) a band needs: `width · band_rows`.
    fn needed(&self) -> usize {
        self.layout.width as usize * self.layout.band_rows as usize
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

/// Where finished bands go: a display sending each band as it comes (every
/// embedded-graphics [`DrawTarget`], through one `fill_contiguous`), or one
/// that starts a transfer (DMA) while the next band is drawn
/// ([`Bands::with_second_strip`]). Such a sink owns the strip until
/// [`finish`](BandSink::finish) gives it back: with `'a = 'static` (e.g.
/// `static_cell::ConstStaticCell`) DMA can read it without `unsafe`. One
/// transfer at a time: [`Bands`] calls `finish` before the next `start`.
///
/// ```
/// use core::convert::Infallible;
/// use embedded_graphics_core::{pixelcolor::Rgb565, primitives::Rectangle};
/// use fixshade::framebuffer::BandSink;
///
/// /// A sink that keeps the strip until asked, as a DMA transfer would.
/// struct Later<'a> {
///     held: Option<&'a mut [Rgb565]>,
///     sent: usize,
/// }
///
/// impl<'a> BandSink<'a, Rgb565> for Later<'a> {
///     type Error = Infallible;
///     fn start(&mut self, area: &Rectangle, strip: &'a mut [Rgb565])
///         -> Result<Option<&'a mut [Rgb565]>, Infallible> {
///         // a DMA sink starts the transfer of the first `area` pixels here
///         self.sent += (area.size.width * area.size.height) as usize;
///         self.held = Some(strip);
///         Ok(None)
///     }
///     fn finish(&mut self) -> Result<&'a mut [Rgb565], Infallible> {
///         // ... and waits for it here
///         Ok(self.held.take().unwrap_or(&mut []))
///     }
/// }
/// ```
pub trait BandSink<'a, C> {
    /// The sink's error ([`RenderError::Display`] carries it).
    type Error;

    /// Starts sending the band `area`: the first `width · height` colours of
    /// `strip`, row-major. Returns the strip when it is sent (a blocking
    /// sink), or `None` when a transfer still reads it, which
    /// [`finish`](BandSink::finish) waits for.
    fn start(
        &mut self,
        area: &Rectangle,
        strip: &'a mut [C],
    ) -> Result<Option<&'a mut [C]>, Self::Error>;

    /// Waits until the transfer [`start`](BandSink::start) left running has
    /// ended and gives its strip back (the same slice: a shorter one is
    /// [`RenderError::BufferTooSmall`] at the next band).
    fn finish(&mut self) -> Result<&'a mut [C], Self::Error>;
}

/// The blocking sink: each band sent with one `fill_contiguous` (what
/// display drivers accelerate) before the next is drawn.
impl<'a, C: PixelColor, D: DrawTarget<Color = C>> BandSink<'a, C> for D {
    type Error = D::Error;

    fn start(
        &mut self,
        area: &Rectangle,
        strip: &'a mut [C],
    ) -> Result<Option<&'a mut [C]>, D::Error> {
        let n = area.size.width as usize * area.size.height as usize;
        let px = strip.get(..n).unwrap_or(&[]);
        self.fill_contiguous(area, px.iter().copied())?;
        Ok(Some(strip))
    }

    /// Never called: [`start`](BandSink::start) gives every strip back.
    fn finish(&mut self) -> Result<&'a mut [C], D::Error> {
        Ok(&mut [])
    }
}

/// A frame drawn in horizontal bands through a caller-owned strip, each band
/// sent to a [`BandSink`].
///
/// RAM: `width · band_rows` colours (twice with a second strip) and (with
/// depth testing) as many `u16`s: 7.5 KiB for a 240 × 240 `Rgb565` frame in
/// 8-row bands, 11.25 KiB with a second strip.
#[derive(Debug)]
pub struct Bands<'a, C> {
    buf: Buffers<'a, C>,
    /// The second strip (empty without).
    spare: &'a mut [C],
}

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
        let buf = Buffers::new(layout, ["colour strip", "depth strip"], strip, depth)?;
        Ok(Bands {
            buf,
            spare: &mut [],
        })
    }

    /// This renderer with a second colour strip (as long as the first), drawn
    /// into while a non-blocking sink ([`BandSink::start`] returning `None`,
    /// e.g. DMA) sends the other.
    ///
    /// # Errors
    ///
    /// [`RenderError::BufferTooSmall`] for a short strip.
    pub fn with_second_strip(mut self, strip: &'a mut [C]) -> Result<Self, RenderError> {
        RenderError::check_len("second colour strip", self.buf.needed(), strip.len())?;
        self.spare = strip;
        Ok(self)
    }

    /// The layout.
    pub fn layout(&self) -> Layout {
        self.buf.layout
    }

    /// Renders a frame: [`Bands::render_bands`] of every band, from the top.
    ///
    /// # Errors
    ///
    /// As [`Bands::render_bands`].
    #[inline(always)]
    pub fn render<S: BandSink<'a, C>>(
        &mut self,
        sink: &mut S,
        clear: C,
        items: &mut [&mut dyn DrawBand<C>],
    ) -> Result<(), RenderError<S::Error>> {
        let bands = self.buf.layout.bands();
        self.render_bands(sink, clear, items, 0..bands)
    }

    /// Renders the bands `bands` (in any order; consecutive increasing bands are
    /// cheapest, see [`MeshDraw::share`](crate::render::MeshDraw::share); those
    /// beyond the layout skipped): for each, clears the strip to `clear` and the depth strip to
    /// `u16::MAX`, lets every item draw, and hands the band to `sink` (with a
    /// second strip and a non-blocking sink, the next band is drawn meanwhile;
    /// the last transfer has ended on return). The other bands are other
    /// renderers', e.g. on other cores with each item
    /// [`MeshDraw::share`](crate::render::MeshDraw::share)d: together bit for
    /// bit the frame of [`Bands::render`].
    ///
    /// # Errors
    ///
    /// An item's error from [`DrawBand::check`] (nothing drawn: a mesh
    /// prepared for another layout, or without resume records);
    /// [`RenderError::Display`] with the sink's first error (drawing stops; a
    /// strip the sink kept is not given back); [`RenderError::BufferTooSmall`]
    /// when a sink gave back a shorter strip than it took.
    pub fn render_bands<S: BandSink<'a, C>>(
        &mut self,
        sink: &mut S,
        clear: C,
        items: &mut [&mut dyn DrawBand<C>],
        bands: impl IntoIterator<Item = u32>,
    ) -> Result<(), RenderError<S::Error>> {
        let layout = self.buf.layout;
        check_items(layout, items).map_err(RenderError::widen)?;
        // whether a transfer is running (holding one strip)
        let mut running = false;
        for b in bands {
            if b >= layout.bands() {
                continue;
            }
            let rows = layout.rows(b);
            if self.buf.draw(rows.clone(), clear, items).is_none() {
                return Err(RenderError::BufferTooSmall {
                    which: "colour strip",
                    needed: self.buf.needed(),
                    got: self.buf.color.len(),
                });
            }
            let area = Rectangle::new(
                Point::new(0, rows.start),
                Size::new(layout.width, (rows.end - rows.start) as u32),
            );
            // one transfer at a time: the one before ends first
            if running {
                self.spare = sink.finish().map_err(RenderError::Display)?;
                running = false;
            }
            let strip = core::mem::take(&mut self.buf.color);
            self.buf.color = match sink.start(&area, strip).map_err(RenderError::Display)? {
                Some(strip) => strip,
                None if self.spare.is_empty() => sink.finish().map_err(RenderError::Display)?,
                None => {
                    running = true;
                    core::mem::take(&mut self.spare)
                }
            };
        }
        if running {
            self.spare = sink.finish().map_err(RenderError::Display)?;
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
    /// An item's error from [`DrawBand::check`] (nothing drawn).
    pub fn render(
        &mut self,
        clear: C,
        items: &mut [&mut dyn DrawBand<C>],
    ) -> Result<(), RenderError> {
        check_items(self.0.layout, items)?;
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
