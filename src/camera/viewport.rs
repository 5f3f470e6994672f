//! The screen rectangle a camera draws into.

use super::SUBPIXEL_BITS;
use crate::error::ParamError;

/// The largest viewport side and offset: 32768 pixels.
const LIMIT: i32 = 1 << 15;

/// The screen rectangle clip space maps to: `x0..x0 + width` left to right,
/// `y0..y0 + height` top to bottom (y down), depth `−1..1` to `0..=65535`.
///
/// ```
/// use fixshade::camera::Viewport;
/// let vp = Viewport::new(0, 0, 240, 135)?;
/// assert_eq!((vp.width(), vp.height()), (240, 135));
/// assert!(Viewport::new(0, 0, 0, 10).is_err());
/// # Ok::<(), fixshade::error::ParamError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Viewport {
    x0: i32,
    y0: i32,
    width: i32,
    height: i32,
}

impl Viewport {
    /// A viewport with its top-left corner at pixel `(x0, y0)`: a corner is an
    /// `i32` like embedded-graphics' `Point`, a side a `u32` like its `Size`
    /// and [`Layout`](crate::framebuffer::Layout), so one set of `u32` screen
    /// constants serves all three.
    ///
    /// # Errors
    ///
    /// [`ParamError::OutOfRange`] unless `1 ≤ width, height ≤ 32768` and
    /// `|x0|, |y0| ≤ 32768`.
    pub const fn new(x0: i32, y0: i32, width: u32, height: u32) -> Result<Self, ParamError> {
        if width < 1 || width > LIMIT as u32 {
            return Err(ParamError::OutOfRange("width"));
        }
        if height < 1 || height > LIMIT as u32 {
            return Err(ParamError::OutOfRange("height"));
        }
        if x0 < -LIMIT || x0 > LIMIT {
            return Err(ParamError::OutOfRange("x0"));
        }
        if y0 < -LIMIT || y0 > LIMIT {
            return Err(ParamError::OutOfRange("y0"));
        }
        Ok(Self {
            x0,
            y0,
            width: width as i32,
            height: height as i32,
        })
    }

    /// Left column.
    pub const fn x0(&self) -> i32 {
        self.x0
    }
    /// Top row.
    pub const fn y0(&self) -> i32 {
        self.y0
    }
    /// Width in pixels.
    pub const fn width(&self) -> u32 {
        self.width as u32
    }
    /// Height in pixels.
    pub const fn height(&self) -> u32 {
        self.height as u32
    }

    /// In `f32`: the sub-pixels per unit of normalised device coordinates
    /// (`8·width`, `8·height`: half the viewport's side) and the viewport's
    /// centre in sub-pixels.
    pub(crate) fn scale_centre(&self) -> ([f32; 2], [f32; 2]) {
        let sub = (1 << SUBPIXEL_BITS) as f32;
        let (w8, h8) = (self.width as f32 * 8.0, self.height as f32 * 8.0);
        (
            [w8, h8],
            [self.x0 as f32 * sub + w8, self.y0 as f32 * sub + h8],
        )
    }
}
