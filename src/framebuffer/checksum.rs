//! A display that only checksums the pixels it receives.

use core::convert::Infallible;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::raw::RawData;
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// A [`DrawTarget`] that keeps only a checksum of the raw pixel values in
/// arrival order, and their number, for firmware tests without a display:
/// Fletcher's sums `s1 += raw`, `s2 += s1` modulo 2^32 (two additions per
/// pixel), equal for two frames sent alike exactly when their pixels are (up
/// to collisions).
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// use embedded_graphics_core::prelude::*;
/// use embedded_graphics_core::primitives::Rectangle;
/// use fixshade::framebuffer::Checksum;
/// let mut a = Checksum::<Rgb565>::new(Size::new(4, 1));
/// let mut b = Checksum::<Rgb565>::new(Size::new(4, 1));
/// let area = Rectangle::new(Point::zero(), Size::new(4, 1));
/// a.fill_contiguous(&area, [Rgb565::RED, Rgb565::BLUE, Rgb565::RED, Rgb565::RED]).unwrap();
/// b.fill_contiguous(&area, [Rgb565::BLUE, Rgb565::RED, Rgb565::RED, Rgb565::RED]).unwrap();
/// assert_ne!(a.value(), b.value());
/// assert_eq!(a.pixels(), 4);
/// // fill_solid and clear hand over an endless stream: the area's pixels count
/// a.fill_solid(&area, Rgb565::RED).unwrap();
/// a.clear(Rgb565::RED).unwrap();
/// assert_eq!(a.pixels(), 12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Checksum<C> {
    size: Size,
    sum1: u32,
    sum2: u32,
    pixels: u32,
    color: core::marker::PhantomData<C>,
}

impl<C> Checksum<C> {
    /// A checksumming display of `size`.
    pub fn new(size: Size) -> Self {
        Checksum {
            size,
            sum1: 0,
            sum2: 0,
            pixels: 0,
            color: core::marker::PhantomData,
        }
    }

    /// The checksum of the raw values so far: `s2 ^ rotate_left(s1, 16)`.
    pub fn value(&self) -> u32 {
        self.sum2 ^ self.sum1.rotate_left(16)
    }

    /// Pixels received.
    pub fn pixels(&self) -> u32 {
        self.pixels
    }

    /// Starts over.
    pub fn reset(&mut self) {
        *self = Checksum::new(self.size);
    }
}

impl<C> OriginDimensions for Checksum<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor + Into<C::Raw>> DrawTarget for Checksum<C>
where
    <C::Raw as RawData>::Storage: Into<u32>,
{
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        self.fill_contiguous_raw(pixels.into_iter().map(|Pixel(_, c)| c));
        Ok(())
    }

    /// Every colour of `colors` (the renderer hands exactly the area's; a
    /// longer iterator is counted to its end).
    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        _area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        self.fill_contiguous_raw(colors);
        Ok(())
    }

    /// The area's pixels of `color` (the default hands `fill_contiguous` an
    /// endless iterator).
    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        let n = area.size.width as usize * area.size.height as usize;
        self.fill_contiguous_raw(core::iter::repeat_n(color, n));
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        self.fill_solid(&Rectangle::new(Point::zero(), self.size), color)
    }
}

impl<C: PixelColor + Into<C::Raw>> Checksum<C>
where
    <C::Raw as RawData>::Storage: Into<u32>,
{
    #[inline]
    fn fill_contiguous_raw<I: IntoIterator<Item = C>>(&mut self, colors: I) {
        let (mut s1, mut s2) = (self.sum1, self.sum2);
        let mut k = 0u32;
        for c in colors {
            let raw: u32 = Into::<C::Raw>::into(c).into_inner().into();
            s1 = s1.wrapping_add(raw);
            s2 = s2.wrapping_add(s1);
            k = k.wrapping_add(1);
        }
        self.sum1 = s1;
        self.sum2 = s2;
        self.pixels = self.pixels.wrapping_add(k);
    }
}
