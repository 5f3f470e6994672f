//! Normal maps and bump maps: per-texel tangent-space normals for
//! [`NormalMapped`](crate::shade::NormalMapped) (see [`NormalMap`]).

use super::{TexCoord, Wrap};
use crate::error::TextureError;

/// The flat normal `(0, 0, 1)`.
const FLAT_NORMAL: [i16; 3] = NormalMap::FLAT;

/// The largest `|x² + y² + z² − 2^28|` of a texel [`NormalMap::new`] accepts
/// (`2^15`: a length within `1 ± 6.1·10⁻⁵`). Rounding each component of a
/// unit vector to the nearest Q14 step moves the squared length by at most
/// `2^14·√3 + ¾ < 28 379`, so every texel of [`NormalMap::unit_texel`] is accepted.
const UNIT_TOLERANCE: u32 = 1 << 15;

/// Whether `t` is a unit normal within [`UNIT_TOLERANCE`] (exact, in 64-bit
/// integers).
pub(crate) const fn is_unit_texel(t: [i16; 3]) -> bool {
    let (x, y, z) = (t[0] as i64, t[1] as i64, t[2] as i64);
    let d = x * x + y * y + z * z - (1 << 28);
    d.unsigned_abs() <= UNIT_TOLERANCE as u64
}

/// A tangent-space normal map over borrowed texels, for
/// [`NormalMapped`](crate::shade::NormalMapped): a power-of-two size, 1 … 4096
/// texels a side, each texel a unit normal in Q14 (`[x, y, z]`, `16384` = 1.0;
/// `x` along the tangent (increasing `u`), `y` along the bitangent, `z` along
/// the surface normal: flat is [`NormalMap::FLAT`]).
///
/// **Quantisation.** Six bytes a texel (64 × 64: 24 KiB of flash).
/// [`NormalMap::unit_texel`] rounds each component to the nearest Q14 step:
/// the length stays within `1 ± 2^-15·√3` (< 6·10⁻⁵), the angle within 0.006°,
/// so the fast path uses a texel as a unit normal without renormalising (an
/// 8-bit format would be 0.7 % off in length, 25 % of a highlight of exponent
/// 32).
///
/// **Validation.** [`NormalMap::new`] checks every texel once (a texel such
/// as `[i16::MAX; 3]` would overflow the fast path's 32-bit dot products and
/// light 3.5 times too brightly); [`NormalMap::normalize_texels`] repairs
/// texels from another source (an 8-bit map scaled up, a truncating tool).
///
/// **Sampling.** The nearest texel ([`NormalMap::sample`], as
/// [`crate::texture`]). **Bump maps:** [`NormalMap::from_bump`].
///
/// ```
/// use fixshade::texture::{NormalMap, Wrap};
/// use fixshade::texture::TexCoord;
/// // a 4 × 4 height ramp rising along u, converted into a normal map
/// let heights: [u8; 16] = core::array::from_fn(|i| (i % 4) as u8 * 10);
/// let mut texels = [[0i16; 3]; 16];
/// NormalMap::from_bump(&heights, 2, 2, Wrap::Clamp, 0.1, &mut texels)?;
/// let map = NormalMap::new(&texels, 2, 2, Wrap::Clamp)?;
/// // ∂h/∂u = 10 per texel, scale 0.1: n = normalize(−1, 0, 1)
/// let n = map.sample(TexCoord::from_f32(0.4, 0.6));
/// assert_eq!(n, [-11585, 0, 11585]);
/// # Ok::<(), fixshade::error::TextureError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NormalMap<'a> {
    texels: &'a [[i16; 3]],
    w_log2: u8,
    h_log2: u8,
    wrap: Wrap,
}

/// The number of texels of a `2^w_log2 × 2^h_log2` map, checked.
fn texel_count(w_log2: u8, h_log2: u8) -> Result<usize, TextureError> {
    for log2 in [w_log2, h_log2] {
        if log2 > NormalMap::MAX_LOG2_SIZE {
            return Err(TextureError::TooLarge { log2 });
        }
    }
    Ok(1usize << (u32::from(w_log2) + u32::from(h_log2)))
}

impl<'a> NormalMap<'a> {
    /// The largest `log2` of a map side (4096 texels): the mesh's Q12
    /// texture coordinates address a texel of a map up to that size.
    pub const MAX_LOG2_SIZE: u8 = 12;

    /// The flat normal texel `(0, 0, 1)` in Q14: a map of it shades like no map
    /// at all.
    pub const FLAT: [i16; 3] = [0, 0, 1 << 14];

    /// A map of `2^w_log2 × 2^h_log2` texels, row by row from the top-left
    /// (`v = 0`) texel; checking them costs one pass (three 32-bit squares
    /// each). Every texel of [`NormalMap::unit_texel`] and
    /// [`NormalMap::from_bump`] passes. Errors: a side above
    /// [`NormalMap::MAX_LOG2_SIZE`], fewer texels than the size (extra ones are
    /// ignored), a texel that is not a unit normal (`x² + y² + z²` within
    /// `2^28 ± 2^15`, a length within `1 ± 6.1·10⁻⁵`: [`TextureError::NotUnit`],
    /// the first one).
    ///
    /// ```
    /// use fixshade::error::TextureError;
    /// use fixshade::texture::{NormalMap, Wrap};
    /// static FLAT: [[i16; 3]; 1] = [NormalMap::FLAT];
    /// let map = NormalMap::new(&FLAT, 0, 0, Wrap::Repeat).unwrap();
    /// assert_eq!((map.width(), map.height()), (1, 1));
    /// // not unit length: a typed error, not an overflow in the kernel
    /// let long = [NormalMap::FLAT, [i16::MAX; 3]];
    /// assert_eq!(
    ///     NormalMap::new(&long, 1, 0, Wrap::Repeat),
    ///     Err(TextureError::NotUnit { index: 1, texel: [i16::MAX; 3] })
    /// );
    /// ```
    pub fn new(
        texels: &'a [[i16; 3]],
        w_log2: u8,
        h_log2: u8,
        wrap: Wrap,
    ) -> Result<Self, TextureError> {
        let needed = texel_count(w_log2, h_log2)?;
        TextureError::check_len("texels", needed, texels.len())?;
        let texels = texels.get(..needed).unwrap_or(texels);
        if let Some(index) = texels.iter().position(|&t| !is_unit_texel(t)) {
            return Err(TextureError::NotUnit {
                index,
                texel: texels[index],
            });
        }
        Ok(Self {
            texels,
            w_log2,
            h_log2,
            wrap,
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        1 << self.w_log2
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        1 << self.h_log2
    }

    /// `log2` of the width and the height.
    pub fn size_log2(&self) -> (u8, u8) {
        (self.w_log2, self.h_log2)
    }

    /// The wrap mode.
    pub fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// The texels (exactly `width · height`).
    pub fn texels(&self) -> &'a [[i16; 3]] {
        self.texels
    }

    /// Texel `(x, y)` (any integers: wrapped or clamped by the map's mode).
    #[inline(always)]
    pub fn texel(&self, x: i32, y: i32) -> [i16; 3] {
        self.sample_fixed(x, y, 0)
    }

    /// The texel containing the point `c` (nearest sampling).
    #[inline]
    pub fn sample(&self, c: TexCoord) -> [i16; 3] {
        self.sample_fixed(c.u, c.v, crate::texture::TEX_FRAC)
    }

    /// The texel containing the point `(u, v)` given with `frac` fraction bits
    /// (`frac ≥` [`NormalMap::MAX_LOG2_SIZE`]; 12 for the mesh's Q12 texture coordinates).
    #[inline(always)]
    pub fn sample_fixed(&self, u: i32, v: i32, frac: u32) -> [i16; 3] {
        let s = self.nearest(frac);
        match self.wrap {
            Wrap::Repeat => s.get::<true>(u, v),
            Wrap::Clamp => s.get::<false>(u, v),
        }
    }

    /// Nearest sampling at coordinates with `frac` fraction bits, its shifts
    /// and masks worked out once (for a span's loop).
    #[inline(always)]
    pub(crate) fn nearest(&self, frac: u32) -> Nearest<'a> {
        let (wl, hl) = (u32::from(self.w_log2), u32::from(self.h_log2));
        Nearest {
            texels: self.texels,
            su: frac.saturating_sub(wl).min(31),
            sv: frac.saturating_sub(hl).min(31),
            wm: (1 << wl) - 1,
            hm: (1 << hl) - 1,
            wl,
        }
    }
}

/// Nearest sampling of a [`NormalMap`] at fixed-point coordinates (see
/// [`NormalMap::nearest`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nearest<'a> {
    texels: &'a [[i16; 3]],
    su: u32,
    sv: u32,
    wm: i32,
    hm: i32,
    wl: u32,
}

impl Nearest<'_> {
    /// The texel containing `(u, v)`: wrapped (`REPEAT`) or clamped.
    #[inline(always)]
    pub(crate) fn get<const REPEAT: bool>(&self, u: i32, v: i32) -> [i16; 3] {
        let (x, y) = (u >> self.su, v >> self.sv);
        let (x, y) = if REPEAT {
            (x & self.wm, y & self.hm)
        } else {
            (x.clamp(0, self.wm), y.clamp(0, self.hm))
        };
        self.texels
            .get(((y << self.wl) | x) as usize)
            .copied()
            .unwrap_or(FLAT_NORMAL)
    }
}

impl NormalMap<'_> {
    /// The Q14 texel of the unit vector along `n` (normalised here, each component
    /// rounded to nearest). Errors: a non-finite component, a zero vector.
    ///
    /// ```
    /// use fixshade::texture::NormalMap;
    /// assert_eq!(NormalMap::unit_texel([0.0, 0.0, 2.0]), Ok([0, 0, 16384]));
    /// assert_eq!(NormalMap::unit_texel([1.0, 0.0, 1.0]), Ok([11585, 0, 11585]));
    /// ```
    pub fn unit_texel(n: [f32; 3]) -> Result<[i16; 3], TextureError> {
        if n.iter().any(|v| !v.is_finite()) {
            return Err(TextureError::NotFinite("normal"));
        }
        let d = n.map(f64::from);
        let len = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if !(len > 0.0) || !len.is_finite() {
            return Err(TextureError::Degenerate("normal"));
        }
        Ok(d.map(|c| libm::round(c / len * 16384.0).clamp(-16384.0, 16384.0) as i16))
    }

    /// Makes every texel of `texels` a unit normal in place: each is replaced by
    /// [`NormalMap::unit_texel`] of its direction (so the result passes
    /// [`NormalMap::new`]); unit texels are kept as they are. For maps from
    /// another source, e.g. an 8-bit map scaled to Q14 (`(c − 128)·16384/127`),
    /// once at load time, in `f64`.
    ///
    /// Errors: a zero texel ([`TextureError::Degenerate`]`("texel")`, which has
    /// no direction); nothing is written then.
    ///
    /// ```
    /// use fixshade::texture::{NormalMap, Wrap};
    /// // an 8-bit normal map's texels scaled up: 0.7 % too short
    /// let mut texels = [[0i16, 0, 16256], [11494, 0, 11494]];
    /// assert!(NormalMap::new(&texels, 1, 0, Wrap::Repeat).is_err());
    /// NormalMap::normalize_texels(&mut texels)?;
    /// assert_eq!(texels, [[0, 0, 16384], [11585, 0, 11585]]);
    /// assert!(NormalMap::new(&texels, 1, 0, Wrap::Repeat).is_ok());
    /// # Ok::<(), fixshade::error::TextureError>(())
    /// ```
    pub fn normalize_texels(texels: &mut [[i16; 3]]) -> Result<(), TextureError> {
        if texels.contains(&[0; 3]) {
            return Err(TextureError::Degenerate("texel"));
        }
        for t in texels.iter_mut().filter(|t| !is_unit_texel(**t)) {
            *t = NormalMap::unit_texel(t.map(f32::from))?;
        }
        Ok(())
    }

    /// Converts a height map into a normal map (bump mapping, once at load time).
    ///
    /// `heights` holds `2^w_log2 × 2^h_log2` heights row by row (`v` down);
    /// `scale` is the height change, in texels, of one height step (so `∂h/∂u`
    /// is measured in texel widths). Texel `(x, y)` of `out` gets
    /// `normalize(−scale·∂h/∂u, −scale·∂h/∂v, 1)` with central differences
    /// `(h[x+1] − h[x−1]) / 2`; at the edges of a [`Wrap::Clamp`] map one-sided
    /// differences `h[x+1] − h[x]`, `h[x] − h[x−1]` are used (so a linear ramp
    /// gives its exact slope everywhere), a [`Wrap::Repeat`] map wraps around.
    /// A constant map gives the flat normal `[0, 0, 16384]` exactly.
    ///
    /// Errors: a side above [`NormalMap::MAX_LOG2_SIZE`], `heights` or `out` too short, a
    /// non-finite `scale`. Nothing is written on error.
    ///
    /// ```
    /// use fixshade::texture::{NormalMap, Wrap};
    /// let heights = [77u8; 64];
    /// let mut out = [[0i16; 3]; 64];
    /// NormalMap::from_bump(&heights, 3, 3, Wrap::Repeat, 4.0, &mut out)?;
    /// assert!(out.iter().all(|&t| t == NormalMap::FLAT));
    /// # Ok::<(), fixshade::error::TextureError>(())
    /// ```
    pub fn from_bump(
        heights: &[u8],
        w_log2: u8,
        h_log2: u8,
        wrap: Wrap,
        scale: f32,
        out: &mut [[i16; 3]],
    ) -> Result<(), TextureError> {
        let needed = texel_count(w_log2, h_log2)?;
        for got in [heights.len(), out.len()] {
            TextureError::check_len("heights or out", needed, got)?;
        }
        if !scale.is_finite() {
            return Err(TextureError::NotFinite("scale"));
        }
        let (w, h) = (1i32 << w_log2, 1i32 << h_log2);
        let height = |x: i32, y: i32| -> f64 {
            let i = ((y & (h - 1)) * w + (x & (w - 1))) as usize;
            heights.get(i).copied().map_or(0.0, f64::from)
        };
        // the difference quotient along one axis: neighbours `a`, `b` of texel `c`
        // (`len` texels along the axis)
        let slope = |c: i32, len: i32, at: &dyn Fn(i32) -> f64| -> f64 {
            if len == 1 {
                return 0.0;
            }
            match wrap {
                Wrap::Repeat => (at(c + 1) - at(c - 1)) / 2.0,
                Wrap::Clamp => {
                    let (lo, hi) = ((c - 1).max(0), (c + 1).min(len - 1));
                    (at(hi) - at(lo)) / f64::from(hi - lo)
                }
            }
        };
        let s = f64::from(scale);
        for (i, t) in out.iter_mut().take(needed).enumerate() {
            let (x, y) = (i as i32 & (w - 1), i as i32 >> w_log2);
            let du = slope(x, w, &|xx| height(xx, y));
            let dv = slope(y, h, &|yy| height(x, yy));
            let n = [-s * du, -s * dv, 1.0];
            let len = libm::sqrt(n[0] * n[0] + n[1] * n[1] + 1.0);
            *t = n.map(|c| libm::round(c / len * 16384.0).clamp(-16384.0, 16384.0) as i16);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_errors() {
        let t = [FLAT_NORMAL; 16];
        assert!(NormalMap::new(&t, 2, 2, Wrap::Repeat).is_ok());
        assert_eq!(
            NormalMap::new(&t, 13, 0, Wrap::Repeat),
            Err(TextureError::TooLarge { log2: 13 })
        );
        assert_eq!(
            NormalMap::new(&t, 3, 2, Wrap::Repeat),
            Err(TextureError::BufferTooSmall {
                which: "texels",
                needed: 32,
                got: 16
            })
        );
        let mut out = [[0i16; 3]; 4];
        assert_eq!(
            NormalMap::from_bump(&[0; 4], 1, 1, Wrap::Repeat, f32::NAN, &mut out),
            Err(TextureError::NotFinite("scale"))
        );
        assert_eq!(
            NormalMap::from_bump(&[0; 3], 1, 1, Wrap::Repeat, 1.0, &mut out),
            Err(TextureError::BufferTooSmall {
                which: "heights or out",
                needed: 4,
                got: 3
            })
        );
        assert_eq!(
            NormalMap::unit_texel([0.0; 3]),
            Err(TextureError::Degenerate("normal"))
        );
        assert_eq!(
            NormalMap::unit_texel([f32::INFINITY, 0.0, 1.0]),
            Err(TextureError::NotFinite("normal"))
        );
    }

    #[test]
    fn wrap_and_clamp_at_the_edges() {
        // texel i holds [i, 0, 16384] (unit within the tolerance)
        let t: [[i16; 3]; 8] = core::array::from_fn(|i| [i as i16, 0, 16384]);
        let r = NormalMap::new(&t, 2, 1, Wrap::Repeat).unwrap();
        let c = NormalMap::new(&t, 2, 1, Wrap::Clamp).unwrap();
        assert_eq!(r.texel(-1, 0)[0], 3);
        assert_eq!(r.texel(4, 1)[0], 4);
        assert_eq!(r.texel(-5, -1)[0], 7);
        assert_eq!(c.texel(-1, 0)[0], 0);
        assert_eq!(c.texel(9, 5)[0], 7);
        // Q16: u = 1 − 2^-16 is the last column, u = 1 wraps to the first
        assert_eq!(r.sample(TexCoord { u: 65535, v: 0 })[0], 3);
        assert_eq!(r.sample(TexCoord { u: 65536, v: 0 })[0], 0);
        assert_eq!(c.sample(TexCoord { u: 65536, v: 0 })[0], 3);
        // v = ½ is the second row; just below it the first
        assert_eq!(r.sample(TexCoord { u: 0, v: 32768 })[0], 4);
        assert_eq!(r.sample(TexCoord { u: 0, v: 32767 })[0], 0);
        // Q12 coordinates of the mesh
        assert_eq!(r.sample_fixed(3 * 1024, 2048, 12)[0], 7);
    }

    /// The texel's exact unit vector (f64).
    fn unit(t: [i16; 3]) -> [f64; 3] {
        t.map(|c| f64::from(c) / 16384.0)
    }

    #[test]
    fn quantised_normals_are_unit_within_the_stated_bound() {
        // worst case search over a grid of directions, including near the
        // tangent plane (z → 0)
        let mut worst: f64 = 0.0;
        for a in 0..200 {
            for b in 0..50 {
                let phi = a as f32 * 0.0314159;
                let z = b as f32 / 49.0;
                let r = libm::sqrtf(1.0 - z * z);
                let t =
                    NormalMap::unit_texel([r * libm::cosf(phi), r * libm::sinf(phi), z]).unwrap();
                let u = unit(t);
                let len = libm::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
                worst = worst.max((len - 1.0).abs());
            }
        }
        assert!(worst < 6e-5, "length error {worst}");
    }

    #[test]
    fn texels_must_be_unit_normals() {
        for (t, ok) in [
            (FLAT_NORMAL, true),
            ([-16384, 0, 0], true),
            ([0, 0, -16384], true),
            ([16384, 1, 1], true),
            ([16385, 0, 0], false),   // 2^28 + 32769
            ([16383, 0, 0], true),    // 2^28 − 32767
            ([16382, 0, 0], false),   // 2^28 − 65532
            ([16384, 181, 0], true),  // 2^28 + 32761
            ([16384, 182, 0], false), // 2^28 + 33124
            ([i16::MAX; 3], false),
            ([i16::MIN; 3], false),
            ([i16::MIN, 0, 0], false),
            ([0; 3], false),
        ] {
            assert_eq!(is_unit_texel(t), ok, "{t:?}");
        }
        let t = [FLAT_NORMAL, FLAT_NORMAL, [1, 2, 3], FLAT_NORMAL];
        assert_eq!(
            NormalMap::new(&t, 1, 1, Wrap::Clamp),
            Err(TextureError::NotUnit {
                index: 2,
                texel: [1, 2, 3]
            })
        );
        // texels beyond the size are not read, nor checked
        assert!(NormalMap::new(&t, 1, 0, Wrap::Clamp).is_ok());
        // every i16 texel but zero can be made unit
        let mut t = [[i16::MAX; 3], [i16::MIN, 5, -7], [1, 0, 0], [0, -3, 0]];
        NormalMap::normalize_texels(&mut t).unwrap();
        assert!(t.iter().all(|&t| is_unit_texel(t)), "{t:?}");
        assert_eq!(t[2..], [[16384, 0, 0], [0, -16384, 0]]);
        let mut z = [FLAT_NORMAL, [0; 3], [9, 9, 9]];
        assert_eq!(
            NormalMap::normalize_texels(&mut z),
            Err(TextureError::Degenerate("texel"))
        );
        assert_eq!(z[2], [9, 9, 9], "nothing written on error");
    }

    #[test]
    fn linear_ramps_give_the_analytic_tilt() {
        // h = 3x + 5y (u8, 8 × 8), clamp: one-sided at the edges, exact everywhere
        let heights: [u8; 64] = core::array::from_fn(|i| (3 * (i % 8) + 5 * (i / 8)) as u8);
        let mut out = [[0i16; 3]; 64];
        let s = 0.25f64;
        NormalMap::from_bump(&heights, 3, 3, Wrap::Clamp, s as f32, &mut out).unwrap();
        let n = [-s * 3.0, -s * 5.0, 1.0];
        let l = libm::sqrt(n[0] * n[0] + n[1] * n[1] + 1.0);
        for t in out {
            for (c, e) in unit(t).iter().zip(n) {
                assert!((c - e / l).abs() <= 0.5 / 16384.0 + 1e-12, "{t:?}");
            }
        }
        // a repeating ramp along v only (wrap seam excluded): tilt in y only
        let heights: [u8; 16] = core::array::from_fn(|i| (10 * (i / 4)) as u8);
        let mut out = [[0i16; 3]; 16];
        NormalMap::from_bump(&heights, 2, 2, Wrap::Repeat, 0.1, &mut out).unwrap();
        for (i, t) in out.iter().enumerate() {
            let y = i / 4;
            if y == 1 || y == 2 {
                assert_eq!(*t, [0, -11585, 11585]);
            } else {
                // across the seam: (h[y+1] − h[y−1])/2 = ∓10 (one side jumps by 30)
                assert_eq!(t[0], 0);
                assert!(t[1] > 0, "{t:?}");
            }
        }
    }

    #[test]
    fn constant_heights_give_the_flat_normal() {
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let mut out = [[1i16; 3]; 32];
            NormalMap::from_bump(&[200; 32], 3, 2, wrap, 100.0, &mut out).unwrap();
            assert!(out.iter().all(|&t| t == FLAT_NORMAL));
            // 1-texel sides have no slope
            let mut one = [[1i16; 3]; 1];
            NormalMap::from_bump(&[9], 0, 0, wrap, 1.0, &mut one).unwrap();
            assert_eq!(one[0], FLAT_NORMAL);
        }
    }
}
