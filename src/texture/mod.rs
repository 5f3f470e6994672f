//! Textures in flash and their sampling in fixed point (the sampler of
//! [`Textured`](crate::shade::Textured)).
//!
//! A [`Texture`] borrows texel data (`Rgb565` words, 8-bit grey levels, or
//! 8-bit indices into an `Rgb565` palette) of a power-of-two size, 1 … 32 768
//! texels a side. [`TexCoord`]s are Q16 (`1 << 16` is one whole texture), so
//! `u = (i + ½)/w` is the centre of texel column `i`, as in OpenGL; so are
//! the [`Wrap`] modes (`Repeat` for any `i32` coordinate) and [`Filter`]s.
//! 32-bit integers only (no division, float or table); a sample never panics
//! and never reads outside the data.
//!
//! ```
//! use fixshade::texture::{Filter, TexCoord, Texture, Texels, Wrap};
//! // a 2 × 2 grey checkerboard in flash
//! static CHECKER: [u8; 4] = [0, 255, 255, 0];
//! let tex = Texture::new(Texels::Gray8(&CHECKER), 1, 1, Wrap::Repeat).unwrap();
//! // the centre of texel (1, 0) is at u = 3/4, v = 1/4
//! let c = tex.sample(TexCoord::from_f32(0.75, 0.25), Filter::Nearest);
//! assert_eq!(c, [255, 255, 255]);
//! // halfway between two texel centres, bilinear filtering averages them
//! let m = tex.sample(TexCoord::from_f32(0.5, 0.25), Filter::Bilinear);
//! assert_eq!(m, [128, 128, 128]);
//! ```

mod normal_map;
mod rgb565;

pub(crate) use normal_map::Nearest;
pub use normal_map::NormalMap;
pub(crate) use rgb565::{modulate_run, Pieces};

use crate::error::TextureError;

/// Fraction bits of a [`TexCoord`] component.
pub(crate) const TEX_FRAC: u32 = 16;

/// Texel data of a [`Texture`], row by row from the top-left texel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Texels<'a> {
    /// `Rgb565` colours as raw 16-bit words (red in the top five bits), the
    /// format of `embedded_graphics`' `Rgb565::into_storage`.
    Rgb565(&'a [u16]),
    /// Grey levels, 0 = black, 255 = white.
    Gray8(&'a [u8]),
    /// Indices into a palette of raw `Rgb565` words (an index beyond the palette
    /// is black).
    Palette8 {
        /// One index per texel.
        indices: &'a [u8],
        /// The colours, at most 256.
        palette: &'a [u16],
    },
}

impl Texels<'_> {
    const fn len(&self) -> usize {
        match self {
            Texels::Rgb565(d) => d.len(),
            Texels::Gray8(d) => d.len(),
            Texels::Palette8 { indices, .. } => indices.len(),
        }
    }

    /// Texel `i` as 8-bit RGB (5- and 6-bit channels expanded by bit replication,
    /// so 0 and the maximum map to 0 and 255 exactly). `i` is in range.
    #[inline(always)]
    fn rgb(&self, i: usize) -> [u32; 3] {
        let from565 = |w: u16| {
            let w = u32::from(w);
            let (r, g, b) = (w >> 11, (w >> 5) & 63, w & 31);
            [
                (r << 3) | (r >> 2),
                (g << 2) | (g >> 4),
                (b << 3) | (b >> 2),
            ]
        };
        match self {
            Texels::Rgb565(d) => from565(d.get(i).copied().unwrap_or(0)),
            Texels::Gray8(d) => {
                let g = u32::from(d.get(i).copied().unwrap_or(0));
                [g, g, g]
            }
            Texels::Palette8 { indices, palette } => {
                let k = usize::from(indices.get(i).copied().unwrap_or(0));
                from565(palette.get(k).copied().unwrap_or(0))
            }
        }
    }
}

/// What happens outside `[0, 1)` of a texture coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// The texture repeats (`GL_REPEAT`).
    Repeat,
    /// The edge texels extend forever (`GL_CLAMP_TO_EDGE`).
    Clamp,
}

/// How a sample is read from the texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The texel containing the point (`GL_NEAREST`).
    Nearest,
    /// The four nearest texel centres blended with 8-bit weights (`GL_LINEAR`).
    Bilinear,
}

/// A texture coordinate: `u` (across) and `v` (down) in Q16, `1 << 16` being one
/// whole texture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TexCoord {
    /// Across, Q16.
    pub u: i32,
    /// Down, Q16.
    pub v: i32,
}

impl TexCoord {
    /// From `f32` (rounded to Q16, saturating; NaN is 0).
    pub fn from_f32(u: f32, v: f32) -> Self {
        let q = |x: f32| {
            let s = x * (1u32 << TEX_FRAC) as f32;
            if s.is_nan() {
                0
            } else {
                // `as` saturates; adding ½ and flooring rounds to nearest
                libm::floorf(s + 0.5) as i32
            }
        };
        Self { u: q(u), v: q(v) }
    }
}

/// A texture of `2^log2_w × 2^log2_h` texels borrowed from caller-owned (usually
/// flash) data.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Texture<'a> {
    texels: Texels<'a>,
    log2_w: u8,
    log2_h: u8,
    wrap: Wrap,
}

impl Texture<'static> {
    /// A 1 × 1 white texture (what modulation leaves unchanged).
    pub const WHITE: Texture<'static> = Texture {
        texels: Texels::Rgb565(&[0xFFFF]),
        log2_w: 0,
        log2_h: 0,
        wrap: Wrap::Repeat,
    };
}

impl<'a> Texture<'a> {
    /// The largest `log2` of a texture side (32 768 texels).
    pub const MAX_LOG2_SIZE: u8 = 15;

    /// A texture of `2^log2_w` columns and `2^log2_h` rows. Errors: a side above
    /// 2^15 texels, data of another length than `w·h`, a palette of more than 256
    /// colours.
    pub const fn new(
        texels: Texels<'a>,
        log2_w: u8,
        log2_h: u8,
        wrap: Wrap,
    ) -> Result<Self, TextureError> {
        if log2_w > Self::MAX_LOG2_SIZE || log2_h > Self::MAX_LOG2_SIZE {
            return Err(TextureError::TooLarge {
                log2: if log2_w > log2_h { log2_w } else { log2_h },
            });
        }
        if let Texels::Palette8 { palette, .. } = texels {
            if palette.len() > 256 {
                return Err(TextureError::PaletteTooLong);
            }
        }
        if let Err(e) = TextureError::check_len("texels", 1 << (log2_w + log2_h), texels.len()) {
            return Err(e);
        }
        Ok(Self {
            texels,
            log2_w,
            log2_h,
            wrap,
        })
    }

    /// Width in texels.
    pub const fn width(&self) -> u32 {
        1 << self.log2_w
    }

    /// Height in texels.
    pub const fn height(&self) -> u32 {
        1 << self.log2_h
    }

    /// The wrap mode.
    pub const fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// `log2` of the width and of the height.
    pub const fn log2_size(&self) -> (u8, u8) {
        (self.log2_w, self.log2_h)
    }

    /// The texel data.
    pub const fn texels(&self) -> Texels<'a> {
        self.texels
    }

    /// Texel `(x, y)` after wrapping or clamping, 8-bit RGB.
    #[inline(always)]
    pub fn texel(&self, x: i32, y: i32) -> [u8; 3] {
        let [r, g, b] = self.fetch(x, y);
        [r as u8, g as u8, b as u8]
    }

    #[inline(always)]
    fn index(&self, x: i32, log2: u8) -> usize {
        let n = 1i32 << log2;
        match self.wrap {
            Wrap::Repeat => (x & (n - 1)) as usize,
            Wrap::Clamp => x.clamp(0, n - 1) as usize,
        }
    }

    #[inline(always)]
    fn fetch(&self, x: i32, y: i32) -> [u32; 3] {
        let i = (self.index(y, self.log2_h) << self.log2_w) | self.index(x, self.log2_w);
        debug_assert!(i < self.texels.len());
        self.texels.rgb(i)
    }

    /// The texel coordinate of `c` along one axis in 24.8: `c·size − ½` (texel
    /// centres at integers), computed without overflow for every `i32`.
    #[inline(always)]
    fn axis(c: i32, log2: u8) -> i64 {
        // c·2^log2 in Q16 → Q8; minus ½ texel (128 in Q8)
        ((i64::from(c) << log2) >> (TEX_FRAC - 8)) - 128
    }

    /// The colour at `c`, 8-bit RGB.
    pub fn sample(&self, c: TexCoord, filter: Filter) -> [u8; 3] {
        match filter {
            Filter::Nearest => {
                // the texel containing the point: floor(c·size), exact as a shift
                // (sides are at most 2^15 < 2^TEX_FRAC)
                let x = c.u >> (TEX_FRAC - u32::from(self.log2_w));
                let y = c.v >> (TEX_FRAC - u32::from(self.log2_h));
                self.texel(x, y)
            }
            Filter::Bilinear => {
                let sx = Self::axis(c.u, self.log2_w);
                let sy = Self::axis(c.v, self.log2_h);
                let (x0, fx) = (wrap_i64(sx >> 8), (sx & 255) as u32);
                let (y0, fy) = (wrap_i64(sy >> 8), (sy & 255) as u32);
                // neighbours: x0 + 1 wraps (Repeat) or clamps (Clamp) in `index`
                let x1 = x0.wrapping_add(1);
                let y1 = y0.wrapping_add(1);
                let (a, b) = (self.fetch(x0, y0), self.fetch(x1, y0));
                let (d, e) = (self.fetch(x0, y1), self.fetch(x1, y1));
                let mut out = [0u8; 3];
                for (k, o) in out.iter_mut().enumerate() {
                    // rows in 8.8, then columns in 8.16; round once at the end
                    let top = a[k] * (256 - fx) + b[k] * fx;
                    let bottom = d[k] * (256 - fx) + e[k] * fx;
                    let v = top * (256 - fy) + bottom * fy;
                    *o = ((v + (1 << 15)) >> 16) as u8;
                }
                out
            }
        }
    }
}

/// An `i64` texel index to `i32` keeping its value modulo 2^16 (enough for
/// [`Wrap::Repeat`] of sides up to 2^15) and its sign region for [`Wrap::Clamp`].
#[inline(always)]
fn wrap_i64(x: i64) -> i32 {
    if x > i64::from(i32::MAX >> 1) {
        // beyond any side: keep the low bits (Repeat) and stay far positive (Clamp)
        ((x & 0xFFFF) as i32) | (1 << 30)
    } else if x < -i64::from(i32::MAX >> 1) {
        ((x & 0xFFFF) as i32) - (1 << 30)
    } else {
        x as i32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn lcg(seed: &mut u64) -> u32 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 33) as u32
    }

    fn rgb565(r: u16, g: u16, b: u16) -> u16 {
        (r << 11) | (g << 5) | b
    }

    /// The centre of texel (i, j) in Q16.
    fn centre(i: i64, j: i64, lw: u8, lh: u8) -> TexCoord {
        TexCoord {
            u: (((2 * i + 1) << TEX_FRAC) >> (lw + 1)) as i32,
            v: (((2 * j + 1) << TEX_FRAC) >> (lh + 1)) as i32,
        }
    }

    #[test]
    fn texel_centres_are_exact_in_every_format_filter_and_wrap() {
        let mut seed = 7;
        for (lw, lh) in [(0u8, 0u8), (1, 3), (4, 2), (6, 6), (8, 1)] {
            let n = 1usize << (lw + lh);
            let words: Vec<u16> = (0..n).map(|_| lcg(&mut seed) as u16).collect();
            let grey: Vec<u8> = (0..n).map(|_| lcg(&mut seed) as u8).collect();
            let palette: Vec<u16> = (0..256).map(|_| lcg(&mut seed) as u16).collect();
            for texels in [
                Texels::Rgb565(&words),
                Texels::Gray8(&grey),
                Texels::Palette8 {
                    indices: &grey,
                    palette: &palette,
                },
            ] {
                for wrap in [Wrap::Repeat, Wrap::Clamp] {
                    let t = Texture::new(texels, lw, lh, wrap).unwrap();
                    for j in 0..(1i64 << lh) {
                        for i in 0..(1i64 << lw) {
                            let want = t.texel(i as i32, j as i32);
                            let c = centre(i, j, lw, lh);
                            assert_eq!(t.sample(c, Filter::Nearest), want);
                            assert_eq!(t.sample(c, Filter::Bilinear), want, "{lw}x{lh} ({i},{j})");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn rgb565_expands_to_the_full_range() {
        let d = [rgb565(31, 63, 31), rgb565(0, 0, 0), rgb565(16, 32, 16), 0];
        let t = Texture::new(Texels::Rgb565(&d), 1, 1, Wrap::Clamp).unwrap();
        assert_eq!(t.texel(0, 0), [255, 255, 255]);
        assert_eq!(t.texel(1, 0), [0, 0, 0]);
        assert_eq!(t.texel(0, 1), [132, 130, 132]);
    }

    #[test]
    fn repeat_is_periodic_and_clamp_holds_the_edge() {
        let mut seed = 3;
        let grey: Vec<u8> = (0..64).map(|_| lcg(&mut seed) as u8).collect();
        let rep = Texture::new(Texels::Gray8(&grey), 3, 3, Wrap::Repeat).unwrap();
        let cl = Texture::new(Texels::Gray8(&grey), 3, 3, Wrap::Clamp).unwrap();
        for _ in 0..2000 {
            let c = TexCoord {
                u: (lcg(&mut seed) as i32) >> 8,
                v: (lcg(&mut seed) as i32) >> 8,
            };
            let k = (lcg(&mut seed) % 64) as i32 - 32;
            let shifted = TexCoord {
                u: c.u.wrapping_add(k << TEX_FRAC),
                v: c.v.wrapping_sub(k << TEX_FRAC),
            };
            for f in [Filter::Nearest, Filter::Bilinear] {
                assert_eq!(rep.sample(c, f), rep.sample(shifted, f));
            }
            // clamp: anything left of / above the texture reads column / row 0
            let far = TexCoord {
                u: -(1 << 20) - (lcg(&mut seed) as i32 & 0xFFFF),
                v: (1 << 20) + (lcg(&mut seed) as i32 & 0xFFFF),
            };
            for f in [Filter::Nearest, Filter::Bilinear] {
                assert_eq!(cl.sample(far, f), cl.texel(0, 7));
            }
        }
    }

    #[test]
    fn bilinear_matches_an_exact_blend_within_half_a_step() {
        let mut seed = 11;
        let words: Vec<u16> = (0..256).map(|_| lcg(&mut seed) as u16).collect();
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let t = Texture::new(Texels::Rgb565(&words), 4, 4, wrap).unwrap();
            for _ in 0..5000 {
                let c = TexCoord {
                    u: (lcg(&mut seed) % (3 << 16)) as i32 - (1 << 16),
                    v: (lcg(&mut seed) % (3 << 16)) as i32 - (1 << 16),
                };
                // exact: the texel-space point, its neighbours and weights in f64,
                // with the weights quantised to 8 bits as documented
                let sx = (f64::from(c.u) / 65536.0) * 16.0 - 0.5;
                let sy = (f64::from(c.v) / 65536.0) * 16.0 - 0.5;
                let (x0, y0) = (sx.floor(), sy.floor());
                let fx = ((sx - x0) * 256.0).floor() / 256.0;
                let fy = ((sy - y0) * 256.0).floor() / 256.0;
                let at = |x: f64, y: f64| t.texel(x as i32, y as i32).map(f64::from);
                let (a, b) = (at(x0, y0), at(x0 + 1.0, y0));
                let (d, e) = (at(x0, y0 + 1.0), at(x0 + 1.0, y0 + 1.0));
                let got = t.sample(c, Filter::Bilinear);
                for k in 0..3 {
                    let want = (a[k] * (1.0 - fx) + b[k] * fx) * (1.0 - fy)
                        + (d[k] * (1.0 - fx) + e[k] * fx) * fy;
                    assert!(
                        (f64::from(got[k]) - want).abs() <= 0.5 + 1e-9,
                        "{c:?}: {got:?} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn extreme_coordinates_never_panic_and_stay_in_the_data() {
        let grey = [1u8, 2, 3, 4, 5, 6, 7, 8];
        for wrap in [Wrap::Repeat, Wrap::Clamp] {
            let t = Texture::new(Texels::Gray8(&grey), 3, 0, wrap).unwrap();
            for u in [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX] {
                for v in [i32::MIN, 0, i32::MAX] {
                    for f in [Filter::Nearest, Filter::Bilinear] {
                        let s = t.sample(TexCoord { u, v }, f);
                        assert!(s[0] >= 1 && s[0] <= 8, "{u} {v} {f:?}: {s:?}");
                    }
                }
            }
        }
        // the largest side
        let big = std::vec![0u8; 1 << 15];
        let t = Texture::new(Texels::Gray8(&big), 15, 0, Wrap::Repeat).unwrap();
        assert_eq!(
            t.sample(
                TexCoord {
                    u: i32::MAX,
                    v: i32::MIN
                },
                Filter::Bilinear
            ),
            [0; 3]
        );
    }

    #[test]
    fn bad_parameters_are_typed_errors() {
        let d = [0u8; 8];
        assert_eq!(
            Texture::new(Texels::Gray8(&d), 16, 0, Wrap::Repeat),
            Err(TextureError::TooLarge { log2: 16 })
        );
        assert_eq!(
            Texture::new(Texels::Gray8(&d), 2, 2, Wrap::Repeat),
            Err(TextureError::BufferTooSmall {
                which: "texels",
                needed: 16,
                got: 8
            })
        );
        let pal = [0u16; 257];
        assert_eq!(
            Texture::new(
                Texels::Palette8 {
                    indices: &d,
                    palette: &pal
                },
                3,
                0,
                Wrap::Clamp
            ),
            Err(TextureError::PaletteTooLong)
        );
    }
}
