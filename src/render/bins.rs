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
#[derive(Clone, Copy, Debug, Default)]
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
/// first and last frame row (clamped) of triangle `t`, or `None` when it is
/// not drawn; it is called once per triangle when the index area holds the
/// [`Kept`] record too (the usual case with [`bins_len`](super::bins_len), and fewer than 255
/// bands), else twice.
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
    // the start band, −1 at the end band, wrapping u16 arithmetic); the start
    // bands kept while there is room (`Kept`)
    let mut keep = Kept::new(indices.len(), n, bands);
    if keep.room {
        keep.clear(indices);
    }
    let mut visible = 0usize;
    for t in 0..n {
        if let Some((r0, r1)) = classify(t) {
            let (b0, b1) = (layout.band_of(r0) as usize, layout.band_of(r1) as usize);
            keep.push(indices, t, visible, b0);
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
    // the largest number of triangles carried over one boundary: the running
    // sum of the differences is a count in 0..=n ≤ 65535, so the wrapping u16
    // sum is exact (an entry alone can exceed i16, a sum never exceeds u16)
    let mut open = 0u16;
    let mut crossing = 0u16;
    for c in cross.iter() {
        open = open.wrapping_add(*c);
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
    let mut place = |indices: &mut [u16], t: usize, b0: usize| {
        if let Some(c) = cross.get_mut(b0) {
            if let Some(slot) = indices.get_mut(*c as usize) {
                *slot = t as u16;
            }
            *c += 1;
        }
    };
    if keep.room {
        // the kept start bands, read below the slots written (every slot is
        // below `visible`, every kept entry at or above it)
        let mut v = 0;
        for t in 0..n {
            if keep.visible(indices, t) {
                let b0 = keep.band(indices, v);
                v += 1;
                place(indices, t, b0);
            }
        }
    } else {
        for t in 0..n {
            if let Some((r0, _)) = classify(t) {
                place(indices, t, layout.band_of(r0) as usize);
            }
        }
    }
    Ok(Bins {
        heads,
        indices,
        crossing: usize::from(crossing),
    })
}

/// Where pass 1 of [`sort`] keeps what pass 2 needs, at the end of the index
/// area of `len` entries: a bitmap of the `n` triangles (`⌈n/16⌉` entries,
/// last), below it the start band of each visible triangle in order, one
/// byte each, growing down. `room` stays true while all of it fits above
/// the slots of the visible triangles.
struct Kept {
    len: usize,
    /// The first entry of the bitmap.
    bitmap: usize,
    room: bool,
}

impl Kept {
    #[inline(always)]
    fn new(len: usize, n: usize, bands: usize) -> Kept {
        let words = n.div_ceil(16);
        Kept {
            len,
            bitmap: len.saturating_sub(words),
            room: words <= len && bands < 256,
        }
    }

    /// The entry holding visible triangle `v`'s start band (two per entry).
    #[inline(always)]
    fn band_entry(&self, v: usize) -> usize {
        // (bitmap ≥ 1 + v/2 while `room`)
        self.bitmap.wrapping_sub(1 + v / 2)
    }

    /// Clears the bitmap.
    #[inline(always)]
    fn clear(&self, indices: &mut [u16]) {
        if let Some(b) = indices.get_mut(self.bitmap..self.len) {
            b.fill(0);
        }
    }

    /// Records triangle `t`, the `v`-th visible one, starting in band `b0`
    /// (gives up when the entries would reach the slots of the first
    /// `v + 1` visible triangles).
    #[inline(always)]
    fn push(&mut self, indices: &mut [u16], t: usize, v: usize, b0: usize) {
        if !self.room {
            return;
        }
        if self.bitmap < v + 1 + (v / 2 + 1) {
            self.room = false;
            return;
        }
        if let Some(w) = indices.get_mut(self.bitmap + t / 16) {
            *w |= 1 << (t % 16);
        }
        if let Some(e) = indices.get_mut(self.band_entry(v)) {
            let sh = 8 * (v % 2);
            *e = (*e & !(0xFF << sh)) | ((b0 as u16) << sh);
        }
    }

    /// Whether triangle `t` was recorded visible.
    #[inline(always)]
    fn visible(&self, indices: &[u16], t: usize) -> bool {
        indices
            .get(self.bitmap + t / 16)
            .is_some_and(|w| w & (1 << (t % 16)) != 0)
    }

    /// The start band of the `v`-th visible triangle.
    #[inline(always)]
    fn band(&self, indices: &[u16], v: usize) -> usize {
        let e = indices.get(self.band_entry(v)).copied().unwrap_or(0);
        usize::from((e >> (8 * (v % 2))) & 0xFF)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use std::vec::Vec;

    /// The bins of the single-classify path (room kept at the end of the
    /// index area) equal those of the double-classify path (a buffer with no
    /// room) and a plain stable sort by start band; the roomy path classifies
    /// each triangle once, the tight one twice. Meshes of 1 to 700 triangles,
    /// 1 to 240 bands, 0 to 100 % visible.
    #[test]
    fn kept_bands_give_the_bins_of_a_second_classification() {
        let mut rng = Rng(0x2545_F491_4F6C_DD1D);
        for case in 0..300 {
            let n = 1 + (rng.next() % 700) as usize;
            let rows = [1, 2, 8, 240][case % 4];
            let layout = Layout::banded(240, 240, rows).unwrap();
            let share = rng.next() % 101;
            let tris: Vec<Option<(u32, u32)>> = (0..n)
                .map(|_| {
                    (rng.next() % 100 < share).then(|| {
                        let r0 = (rng.next() % 240) as u32;
                        (r0, (r0 + (rng.next() % 40) as u32).min(239))
                    })
                })
                .collect();
            let visible = tris.iter().flatten().count();
            let bands = layout.bands() as usize;
            let mut want: Vec<u16> = (0..n as u16)
                .filter(|&t| tris[t as usize].is_some())
                .collect();
            want.sort_by_key(|&t| layout.band_of(tris[t as usize].unwrap().0));
            let mut got = Vec::new();
            for len in [2 * (bands + 1) + n, 2 * (bands + 1) + visible] {
                let calls = core::cell::Cell::new(0);
                let classify = |t: usize| {
                    calls.set(calls.get() + 1);
                    tris[t]
                };
                let mut buf = std::vec![0xA5A5u16; len];
                let bins = sort(&layout, n, classify, &mut buf).unwrap();
                let all: Vec<u16> = (0..bands as u32)
                    .flat_map(|b| bins.band(b).iter().copied())
                    .collect();
                assert_eq!(all, want, "case {case} len {len}");
                got.push((calls.get(), bins.crossing));
            }
            // a tight buffer classifies twice; one with room for the kept
            // bands (visible·3/2 + n/16 entries) once
            assert_eq!(got[1].0, 2 * n, "case {case}");
            let room = visible + visible.div_ceil(2) + n.div_ceil(16) < n;
            if room && bands < 256 {
                assert_eq!(got[0].0, n, "case {case}: {visible} of {n} visible");
            }
            assert_eq!(got[0].1, got[1].1);
        }
    }
}
