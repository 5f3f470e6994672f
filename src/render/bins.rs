//! Binning: back faces culled, the visible triangles sorted by the band they
//! start in, so that a band touches only its triangles.
//!
//! The caller's `u16` slice holds, in order: the start offset of every band's
//! bin (`bands + 1` values), the number of triangles crossing each band
//! boundary (`bands + 1` values, to size the resume records), and the
//! triangle indices, band by band, each band's in mesh order (a stable
//! counting sort).

use super::{Layout, RenderError};

/// The sorted bins of one mesh (views into the caller's slice).
#[derive(Debug, Default)]
pub(crate) struct Bins<'a> {
    heads: &'a [u16],
    indices: &'a [u16],
    /// The most triangles crossing one band boundary.
    pub crossing: usize,
}

impl<'a> Bins<'a> {
    /// The triangle indices starting in band `b`.
    #[inline]
    pub(crate) fn band(&self, b: u32) -> &'a [u16] {
        let b = b as usize;
        let (Some(&s), Some(&e)) = (self.heads.get(b), self.heads.get(b + 1)) else {
            return &[];
        };
        self.indices.get(s as usize..e as usize).unwrap_or(&[])
    }
}

/// Sorts the triangles `0..n` into bins over `buf`. `classify(t)` gives the
/// first and last frame row of triangle `t` (rows already clamped to the
/// frame) or `None` when it is not drawn; it is called twice per triangle.
///
/// # Errors
///
/// [`RenderError::BufferTooSmall`] when `buf` cannot hold the heads, the
/// crossings and one index per visible triangle; [`RenderError::TooManyVertices`]
/// for more than 65535 triangles (a mesh and its refinement).
pub(crate) fn sort<'a>(
    layout: &Layout,
    n: usize,
    classify: impl Fn(usize) -> Option<(u32, u32)>,
    buf: &'a mut [u16],
) -> Result<Bins<'a>, RenderError> {
    if n > u16::MAX as usize {
        return Err(RenderError::TooManyVertices { needed: n });
    }
    let bands = layout.bands() as usize;
    let head_len = bands + 1;
    if buf.len() < 2 * head_len {
        return Err(RenderError::BufferTooSmall {
            which: "bins",
            needed: 2 * head_len,
            got: buf.len(),
        });
    }
    let too_small = RenderError::BufferTooSmall {
        which: "bins",
        needed: 2 * head_len,
        got: buf.len(),
    };
    // (checked above: the `else` arms only drop the panic paths)
    let Some((heads, rest)) = buf.split_at_mut_checked(head_len) else {
        return Err(too_small);
    };
    let Some((cross, indices)) = rest.split_at_mut_checked(head_len) else {
        return Err(too_small);
    };
    heads.fill(0);
    cross.fill(0);
    // pass 1: count per start band; crossings as a difference array (+1 at
    // the start band, −1 at the end band, wrapping u16 arithmetic)
    let mut visible = 0usize;
    for t in 0..n {
        if let Some((r0, r1)) = classify(t) {
            let (b0, b1) = (layout.band_of(r0) as usize, layout.band_of(r1) as usize);
            if let Some(h) = heads.get_mut(b0) {
                *h += 1;
            }
            if b1 > b0 {
                if let Some(c) = cross.get_mut(b0) {
                    *c = c.wrapping_add(1);
                }
                if let Some(c) = cross.get_mut(b1) {
                    *c = c.wrapping_sub(1);
                }
            }
            visible += 1;
        }
    }
    if indices.len() < visible {
        return Err(RenderError::BufferTooSmall {
            which: "bins",
            needed: 2 * head_len + visible,
            got: 2 * head_len + indices.len(),
        });
    }
    // the largest number of triangles carried over one boundary
    let mut open = 0i32;
    let mut crossing = 0i32;
    for c in cross.iter() {
        open += i32::from(*c as i16);
        crossing = crossing.max(open);
    }
    // offsets: heads[b] = first index of band b (exclusive prefix sums)
    let mut sum = 0u16;
    for h in heads.iter_mut() {
        let c = *h;
        *h = sum;
        sum = sum.wrapping_add(c);
    }
    // pass 2: place, stable (mesh order within each band); `cross` is reused
    // as the write cursor of every band
    // (both `head_len` long; a zip rather than `copy_from_slice`, whose length
    // check is left in at opt-level z: no panic path)
    for (c, h) in cross.iter_mut().zip(heads.iter()) {
        *c = *h;
    }
    for t in 0..n {
        if let Some((r0, _)) = classify(t) {
            let b0 = layout.band_of(r0) as usize;
            if let Some(c) = cross.get_mut(b0) {
                if let Some(slot) = indices.get_mut(*c as usize) {
                    *slot = t as u16;
                }
                *c += 1;
            }
        }
    }
    Ok(Bins {
        heads,
        indices,
        crossing: crossing.max(0) as usize,
    })
}
