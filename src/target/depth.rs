//! Caller-owned depth values.

use core::ops::Range;

use super::TargetError;

/// A depth buffer over caller-owned `u16` values, `width` per row.
///
/// Convention: **smaller is nearer**. A pixel passes the depth test when its
/// depth is strictly less than the stored one (`z < stored`, like `GL_LESS`);
/// a passing pixel stores its depth when depth writes are enabled. Clear to
/// `u16::MAX` for "nothing drawn yet".
///
/// The buffer covers `rows` rows starting at frame row `first_row()`. For a
/// whole frame that is row 0; with a [`BandBuffer`](super::BandBuffer) give it
/// as many rows as a band and move it with
/// [`set_first_row`](DepthBuffer::set_first_row) (or let
/// [`BandBuffer::render_with_depth`](super::BandBuffer::render_with_depth) do it).
///
/// ```
/// use fixshade::target::DepthBuffer;
///
/// let mut z = [0u16; 64 * 8];
/// let mut depth = DepthBuffer::new(&mut z, 64).unwrap();
/// depth.clear(u16::MAX);
/// assert_eq!(depth.rows(), 0..8);
/// assert_eq!(depth.get(3, 7), Some(u16::MAX));
/// ```
#[derive(Debug)]
pub struct DepthBuffer<'a> {
    buf: &'a mut [u16],
    width: u32,
    rows: u32,
    first_row: i32,
}

impl<'a> DepthBuffer<'a> {
    /// A depth buffer of `buf.len() / width` rows of `width` values, starting at row 0.
    ///
    /// Fails if `width` is zero or `buf` holds less than one row.
    pub fn new(buf: &'a mut [u16], width: u32) -> Result<Self, TargetError> {
        if width == 0 {
            return Err(TargetError::ZeroSize);
        }
        let rows = buf.len() / width as usize;
        if rows == 0 {
            return Err(TargetError::BufferTooSmall {
                needed: width as usize,
                got: buf.len(),
            });
        }
        let rows = rows.min(i32::MAX as usize) as u32;
        Ok(DepthBuffer {
            buf,
            width,
            rows,
            first_row: 0,
        })
    }

    /// Values per row.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The frame rows covered: `first_row()..first_row() + number of rows`.
    pub fn rows(&self) -> Range<i32> {
        self.first_row..self.first_row.saturating_add(self.rows as i32)
    }

    /// The frame row stored first.
    pub fn first_row(&self) -> i32 {
        self.first_row
    }

    /// Makes the buffer cover frame rows from `row` on (for band rendering).
    pub fn set_first_row(&mut self, row: i32) {
        self.first_row = row;
    }

    /// Sets every value to `far`.
    pub fn clear(&mut self, far: u16) {
        for z in self.buf.iter_mut() {
            *z = far;
        }
    }

    /// The depth stored for frame pixel `(x, y)`, or `None` outside the buffer.
    pub fn get(&self, x: u32, y: i32) -> Option<u16> {
        let i = self.index(x, y)?;
        self.buf.get(i).copied()
    }

    /// The stored depths of frame row `y`, columns `cols`, or `None` if they
    /// are not all covered.
    pub fn row_mut(&mut self, y: i32, cols: Range<u32>) -> Option<&mut [u16]> {
        if cols.start > cols.end || cols.end > self.width {
            return None;
        }
        let i = self.index(cols.start, y)?;
        self.buf.get_mut(i..i + (cols.end - cols.start) as usize)
    }

    fn index(&self, x: u32, y: i32) -> Option<usize> {
        if x >= self.width || !self.rows().contains(&y) {
            return None;
        }
        let row = (y - self.first_row) as usize;
        Some(row * self.width as usize + x as usize)
    }
}
