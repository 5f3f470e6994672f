//! 2D over 3D: [`BandView`] as an embedded-graphics `DrawTarget`, every
//! `Drawable` a [`DrawBand`] (see [`BandView`]).

use core::convert::Infallible;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, Point, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::{Drawable, Pixel};

use super::{BandView, DrawBand};

impl<C: PixelColor> Dimensions for BandView<'_, C> {
    /// The band's rows of the frame, in screen coordinates: `(0, first row)`,
    /// `width × rows`.
    fn bounding_box(&self) -> Rectangle {
        let rows = (self.rows.end - self.rows.start).max(0) as u32;
        Rectangle::new(Point::new(0, self.rows.start), Size::new(self.width, rows))
    }
}

impl<C: PixelColor> DrawTarget for BandView<'_, C> {
    type Color = C;
    type Error = Infallible;

    /// Writes the pixels inside the band; the others are dropped.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, c) in pixels {
            if let Some(i) = self.index(p) {
                if let Some(px) = self.color.get_mut(i) {
                    *px = c;
                }
            }
        }
        Ok(())
    }

    /// Fills the part of `area` inside the band, row by row.
    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        let area = area.intersection(&self.bounding_box());
        let Some(last) = area.bottom_right() else {
            return Ok(());
        };
        let w = area.size.width as usize;
        for y in area.top_left.y..=last.y {
            if let Some(i) = self.index(Point::new(area.top_left.x, y)) {
                if let Some(row) = self.color.get_mut(i..i + w) {
                    row.fill(color);
                }
            }
        }
        Ok(())
    }
}

impl<C> BandView<'_, C> {
    /// The strip index of screen pixel `p`, if the band holds it.
    fn index(&self, p: Point) -> Option<usize> {
        let inside = (0..self.width as i32).contains(&p.x) && self.rows.contains(&p.y);
        inside.then(|| (p.y - self.rows.start) as usize * self.width as usize + p.x as usize)
    }
}

/// Every embedded-graphics [`Drawable`] draws into the bands: its pixels in
/// screen coordinates, clipped to each band (see [`BandView`]).
impl<C: PixelColor, D: Drawable<Color = C>> DrawBand<C> for D {
    fn draw_band(&mut self, band: &mut BandView<'_, C>) {
        // a band view never fails (Infallible)
        let _ = self.draw(band);
    }
}
