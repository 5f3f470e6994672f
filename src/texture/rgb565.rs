//! The 5-6-5 fast path of a textured Gouraud span (see
//! [`Textured`](crate::shade::Textured)): `Rgb565` texels, nearest, repeated,
//! fetched at packed 16-bit coordinates and modulated by the Gouraud colour
//! channels as the Gouraud kernel steps them, and the pieces in which a run's
//! texture coordinates are re-anchored.

use crate::color::OutputColor;

/// Pixels per piece of an affine run: the packed 16-bit coordinates of the
/// fast path are re-anchored this often (their rounded steps drift by at most
/// `2^−17` of a texture per pixel).
pub(crate) const AFFINE_CHUNK: usize = 32;

/// The texture coordinates of a run, piece by piece: [`Pieces::next`] gives
/// `(len, u, du, v, dv)` (Q24) for the next `len` pixels (at most
/// [`AFFINE_CHUNK`]), pixel `j` of the piece at `u + j·du`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pieces {
    n: usize,
    k0: usize,
    u: i32,
    du: i32,
    v: i32,
    dv: i32,
}

impl Pieces {
    /// `n` pixels from `(u, v)` stepping by `(du, dv)` (Q24).
    #[inline(always)]
    pub(crate) fn new(n: usize, u: i32, du: i32, v: i32, dv: i32) -> Self {
        Pieces {
            n,
            k0: 0,
            u,
            du,
            v,
            dv,
        }
    }

    /// The next piece: `(len, u, du, v, dv)`.
    #[inline(always)]
    pub(crate) fn next(&mut self) -> Option<(usize, i32, i32, i32, i32)> {
        let k0 = self.k0;
        if k0 >= self.n {
            return None;
        }
        let len = (self.n - k0).min(AFFINE_CHUNK);
        let r = (len, self.u, self.du, self.v, self.dv);
        // the values at the next piece's start, as if stepped
        self.u = self.u.wrapping_add(self.du.wrapping_mul(len as i32));
        self.v = self.v.wrapping_add(self.dv.wrapping_mul(len as i32));
        self.k0 = k0 + len;
        Some(r)
    }
}

/// The 5-6-5 fast path over a run: texels `words` of a `2^lw × 2^lh`
/// texture (`lw`, `lh` ≥ 1), coordinates from `coords`, the Gouraud channels
/// `c = [rb, drb, g, dg]` packed as in the Gouraud kernel (see
/// [`fill_tex565`]).
#[inline(always)]
pub(crate) fn modulate_run<C: OutputColor>(
    words: &[u16],
    (lw, lh): (u8, u8),
    coords: Pieces,
    c: [u32; 4],
    color: &mut [C],
) {
    match (lw, lh) {
        (4, 4) => fast_run::<C, 4, 4, 256>(words, coords, c, color),
        (5, 5) => fast_run::<C, 5, 5, 1024>(words, coords, c, color),
        (6, 6) => fast_run::<C, 6, 6, 4096>(words, coords, c, color),
        (7, 7) => fast_run::<C, 7, 7, 16384>(words, coords, c, color),
        (8, 8) => fast_run::<C, 8, 8, 65536>(words, coords, c, color),
        _ => fast_run_any(words, (u32::from(lw), u32::from(lh)), coords, c, color),
    }
}

/// Q24 coordinates and steps packed for the fast path: `v` in the top 15
/// bits (2^15 per texture), a guard bit, `u` in the low 16 bits (2^16 per
/// texture). The guard bit takes `u`'s carry (or borrow, for a negative
/// step: then it starts set) when `u` wraps once within a piece, so that `v`
/// is not disturbed.
#[inline(always)]
fn pack(u: i32, du: i32, v: i32, dv: i32) -> (u32, u32) {
    let u16 = ((u >> 8) as u32) & 0xFFFF;
    let v15 = ((v >> 9) as u32) << 17;
    let guard = if du < 0 { 1 << 16 } else { 0 };
    // steps rounded to nearest
    let du16 = (du.wrapping_add(128) >> 8) as u32;
    let dv15 = ((dv.wrapping_add(256) >> 9) as u32) << 17;
    (v15 | guard | u16, dv15.wrapping_add(du16))
}

/// The 5-6-5 fast path for a `2^LW × 2^LH` texture of `N` texels (see
/// [`fill_tex565`]).
#[inline(never)]
fn fast_run<C: OutputColor, const LW: u32, const LH: u32, const N: usize>(
    words: &[u16],
    mut gen: Pieces,
    mut c: [u32; 4],
    color: &mut [C],
) {
    let Ok(words) = <&[u16; N]>::try_from(words) else {
        return;
    };
    let mut rest = color;
    while let Some((len, u, du, v, dv)) = gen.next() {
        let uv = pack(u, du, v, dv);
        let (part, tail) = rest.split_at_mut(len.min(rest.len()));
        tex565_const::<C, LW, LH, N>(words, uv, &mut c, part);
        rest = tail;
    }
}

/// [`fill_tex565`] for constant sizes: the index is provably in the array.
#[inline(never)]
fn tex565_const<C: OutputColor, const LW: u32, const LH: u32, const N: usize>(
    words: &[u16; N],
    uv: (u32, u32),
    c: &mut [u32; 4],
    out: &mut [C],
) {
    let [rb, drb, g, dg] = *c;
    let (rb, g) = fill_tex565::<C>(
        words.as_slice(),
        (LW, LH),
        [uv.0, uv.1],
        [rb, drb],
        [g, dg],
        out,
    );
    c[0] = rb;
    c[2] = g;
}

/// [`fast_run`] for any texture size (run-time shifts).
#[inline(never)]
fn fast_run_any<C: OutputColor>(
    words: &[u16],
    size: (u32, u32),
    mut gen: Pieces,
    c: [u32; 4],
    color: &mut [C],
) {
    let [mut rb, drb, mut g, dg] = c;
    let (lw, lh) = (size.0.clamp(1, 15), size.1.clamp(1, 15));
    let mut rest = color;
    while let Some((len, u, du, v, dv)) = gen.next() {
        let (uv, duv) = pack(u, du, v, dv);
        let (part, tail) = rest.split_at_mut(len.min(rest.len()));
        (rb, g) = fill_tex565(words, (lw, lh), [uv, duv], [rb, drb], [g, dg], part);
        rest = tail;
    }
}

/// The fast path's loop (see the [`Textured`](crate::shade::Textured) docs): `Rgb565` texels at the
/// packed coordinates `uv` (see [`pack`]; the wrapping addition is
/// [`Wrap::Repeat`](super::Wrap::Repeat)), the Gouraud channels packed as in the Gouraud kernel
/// (red and blue in `rb`, 16 bits each with 11 fraction bits; green in `g`
/// with 23), modulated as `⌊(t + 1)·A / 2^k⌋`; `lw`, `lh` (1 to 15): the
/// texture's `log2` sides. Returns `rb`, `g` after the last pixel.
#[inline(always)]
fn fill_tex565<C: OutputColor>(
    words: &[u16],
    (lw, lh): (u32, u32),
    [mut uv, duv]: [u32; 2],
    [mut rb, drb]: [u32; 2],
    [mut g, dg]: [u32; 2],
    out: &mut [C],
) -> (u32, u32) {
    for c in out.iter_mut() {
        let col = (uv << 16) >> (32 - lw);
        let row = uv >> (32 - lh);
        let t = u32::from(
            words
                .get(((row << lw) | col) as usize)
                .copied()
                .unwrap_or(0),
        );
        // (t + 1)·A < 2^16 for every channel: the product's top bits are the
        // channel (shift pairs instead of masks: no constants to hold)
        let r = ((((t >> 11) + 1) * (rb >> 21)) >> 11) << 11;
        let gr = (((((t << 21) >> 26) + 1) * (g >> 19)) >> 10) << 5;
        let b = ((((t << 27) >> 27) + 1) * ((rb << 16) >> 21)) >> 11;
        *c = C::from_rgb565_raw((r | gr | b) as u16);
        // the values after the last pixel are not used: wrapping is harmless
        uv = uv.wrapping_add(duv);
        rb = rb.wrapping_add(drb);
        g = g.wrapping_add(dg);
        crate::num::no_unroll();
    }
    (rb, g)
}
