//! PNG textures to fixshade's texel formats: `Rgb565`, `Gray8`, or
//! `Palette8` (at most 256 `Rgb565` colours).
//!
//! - **Sizes**: fixshade samples with masks, so both sides must be powers of
//!   two (1 … 32 768). Other sizes are an [`Error::TextureSize`] unless
//!   resizing is asked for: each side then goes to the nearest power of two
//!   (`round(log2(side))`), shrinking by area averaging and growing by
//!   bilinear interpolation, per axis.
//! - **Alpha** is dropped (fixshade textures are opaque); a texture that uses
//!   it gets a warning.
//! - **Rgb565**: every channel is rounded to the 5- or 6-bit code whose
//!   expansion by the renderer (bit replication) is nearest.
//! - **Gray8**: Rec. 601 luma, `(299 R + 587 G + 114 B) / 1000`, rounded.
//! - **Palette8**: the texture's own colours if at most 256 `Rgb565` colours
//!   occur; otherwise a median cut (boxes split at the pixel-weighted median
//!   of their widest channel until there are 256) refined by three rounds of
//!   k-means, every texel mapped to its nearest palette colour.
//!
//! The error of every conversion is measured against what the renderer will
//! sample (the library's [`Texture::texel`]): the largest per-channel
//! difference and the RMS, in 8-bit LSBs, against the RGB image (against its
//! luma for `Gray8`).

use std::collections::{BTreeMap, HashMap};
use std::io::Cursor;
use std::path::Path;

use fixshade::texture::{Texels, Texture, Wrap};

use crate::error::Error;

/// The texel format of the emitted texture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TextureFormat {
    /// 16-bit colours, 2 bytes a texel.
    #[default]
    Rgb565,
    /// 8-bit grey levels, 1 byte a texel.
    Gray8,
    /// 8-bit indices into at most 256 `Rgb565` colours: 1 byte a texel plus
    /// 2 a colour.
    Palette8,
}

impl TextureFormat {
    /// The name used on the command line and in messages.
    pub fn name(self) -> &'static str {
        match self {
            TextureFormat::Rgb565 => "rgb565",
            TextureFormat::Gray8 => "gray8",
            TextureFormat::Palette8 => "palette8",
        }
    }
}

/// An 8-bit RGB image (alpha dropped), row by row from the top left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height` pixels.
    pub pixels: Vec<[u8; 3]>,
    /// Whether the PNG had an alpha channel with values below 255.
    pub had_alpha: bool,
}

/// Texel data in the library's formats, owned.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TexelData {
    /// Raw `Rgb565` words.
    Rgb565(Vec<u16>),
    /// Grey levels.
    Gray8(Vec<u8>),
    /// Palette indices and the palette (raw `Rgb565` words).
    Palette8 {
        /// One index per texel.
        indices: Vec<u8>,
        /// At most 256 colours.
        palette: Vec<u16>,
    },
}

/// What a conversion did and what it cost.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureReport {
    /// The image's size as read.
    pub source_size: (u32, u32),
    /// Whether it was resampled to power-of-two sides.
    pub resized: bool,
    /// The format.
    pub format: TextureFormat,
    /// Distinct colours of the (resized) image.
    pub source_colours: usize,
    /// Whether the palette had to be quantised (more than 256 colours).
    pub quantised: bool,
    /// The largest per-channel difference between the image and what the
    /// renderer samples, in 8-bit LSBs.
    pub max_error: u8,
    /// The RMS of that difference over all channels.
    pub rms_error: f64,
    /// Bytes in flash (texels and palette).
    pub bytes: usize,
    /// Things to tell the user.
    pub warnings: Vec<String>,
}

/// A texture converted for flash.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvertedTexture {
    /// `log2` of the width.
    pub log2_width: u8,
    /// `log2` of the height.
    pub log2_height: u8,
    /// The texels.
    pub texels: TexelData,
    /// Repeat or clamp outside `[0, 1)`.
    pub wrap: Wrap,
    /// What the conversion did.
    pub report: TextureReport,
}

impl ConvertedTexture {
    /// The library's view of this texture.
    ///
    /// # Errors
    ///
    /// Those of [`Texture::new`]; never for a texture made by [`convert`].
    pub fn texture(&self) -> Result<Texture<'_>, fixshade::error::TextureError> {
        let texels = match &self.texels {
            TexelData::Rgb565(d) => Texels::Rgb565(d),
            TexelData::Gray8(d) => Texels::Gray8(d),
            TexelData::Palette8 { indices, palette } => Texels::Palette8 { indices, palette },
        };
        Texture::new(texels, self.log2_width, self.log2_height, self.wrap)
    }
}

/// Decodes a PNG (any colour type and depth) to 8-bit RGB.
///
/// # Errors
///
/// [`Error::Texture`] naming `path` when the bytes are not a valid PNG.
pub fn decode_png(bytes: &[u8], path: &Path) -> Result<Image, Error> {
    let fail = |message: String| Error::Texture {
        path: path.to_path_buf(),
        message,
    };
    let mut decoder = png::Decoder::new(Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| fail("image too large".into()))?;
    let mut buf = vec![0u8; size];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| fail(e.to_string()))?;
    let channels = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err(fail("palette not expanded".into())),
    };
    let (w, h) = (info.width as usize, info.height as usize);
    let mut pixels = Vec::with_capacity(w * h);
    let mut had_alpha = false;
    for row in buf.chunks(info.line_size).take(h) {
        for px in row.chunks_exact(channels).take(w) {
            let rgb = match channels {
                1 | 2 => [px[0]; 3],
                _ => [px[0], px[1], px[2]],
            };
            had_alpha |= channels % 2 == 0 && px[channels - 1] < 255;
            pixels.push(rgb);
        }
    }
    if pixels.len() != w * h {
        return Err(fail("truncated image data".into()));
    }
    Ok(Image {
        width: info.width,
        height: info.height,
        pixels,
        had_alpha,
    })
}

/// `log2(n)` when `n` is a power of two fixshade accepts (1 … 2^15).
fn log2_exact(n: u32) -> Option<u8> {
    (n.is_power_of_two() && n.trailing_zeros() <= u32::from(Texture::MAX_LOG2_SIZE))
        .then(|| n.trailing_zeros() as u8)
}

/// The power of two nearest to `n` in the logarithm (`round(log2 n)`),
/// within 1 … 2^15.
pub fn nearest_power_of_two(n: u32) -> u32 {
    let l = f64::from(n.max(1)).log2().round() as u32;
    1 << l.min(u32::from(Texture::MAX_LOG2_SIZE))
}

/// Converts `image` (named `path` in messages) to `format`.
///
/// # Errors
///
/// [`Error::TextureSize`] for a side that is not a power of two up to 2^15
/// when `resize` is false; [`Error::Texture`] when `image.pixels` does not
/// hold `width · height` pixels.
pub fn convert(
    image: &Image,
    path: &Path,
    format: TextureFormat,
    wrap: Wrap,
    resize: bool,
) -> Result<ConvertedTexture, Error> {
    if image.pixels.len() as u64 != u64::from(image.width) * u64::from(image.height) {
        return Err(Error::Texture {
            path: path.to_path_buf(),
            message: format!(
                "{} pixels for {} × {}",
                image.pixels.len(),
                image.width,
                image.height
            ),
        });
    }
    let (lw, lh) = (log2_exact(image.width), log2_exact(image.height));
    let mut warnings = Vec::new();
    if image.had_alpha {
        warnings.push("the alpha channel is dropped (fixshade textures are opaque)".to_string());
    }
    let (img, lw, lh, resized) = match (lw, lh) {
        (Some(lw), Some(lh)) => (image.clone(), lw, lh, false),
        _ if resize && image.width > 0 && image.height > 0 => {
            let (w, h) = (
                nearest_power_of_two(image.width),
                nearest_power_of_two(image.height),
            );
            let r = resample(image, w, h);
            (r, w.trailing_zeros() as u8, h.trailing_zeros() as u8, true)
        }
        _ => {
            return Err(Error::TextureSize {
                path: path.to_path_buf(),
                width: image.width,
                height: image.height,
            })
        }
    };
    let mut distinct: BTreeMap<[u8; 3], usize> = BTreeMap::new();
    for p in &img.pixels {
        *distinct.entry(*p).or_default() += 1;
    }
    let mut quantised = false;
    let texels = match format {
        TextureFormat::Rgb565 => TexelData::Rgb565(img.pixels.iter().map(|&p| rgb565(p)).collect()),
        TextureFormat::Gray8 => TexelData::Gray8(img.pixels.iter().map(|&p| luma(p)).collect()),
        TextureFormat::Palette8 => {
            let (indices, palette, q) = palettise(&img.pixels, &distinct);
            quantised = q;
            TexelData::Palette8 { indices, palette }
        }
    };
    let bytes = match &texels {
        TexelData::Rgb565(d) => 2 * d.len(),
        TexelData::Gray8(d) => d.len(),
        TexelData::Palette8 { indices, palette } => indices.len() + 2 * palette.len(),
    };
    let mut out = ConvertedTexture {
        log2_width: lw,
        log2_height: lh,
        texels,
        wrap,
        report: TextureReport {
            source_size: (image.width, image.height),
            resized,
            format,
            source_colours: distinct.len(),
            quantised,
            max_error: 0,
            rms_error: 0.0,
            bytes,
            warnings,
        },
    };
    // the error against what the renderer samples
    let (max, rms) = {
        let tex = out.texture().map_err(|e| Error::Texture {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let w = 1usize << lw;
        let (mut max, mut sum) = (0u8, 0.0f64);
        for (i, &p) in img.pixels.iter().enumerate() {
            let got = tex.texel((i % w) as i32, (i / w) as i32);
            let want = if format == TextureFormat::Gray8 {
                [luma(p); 3]
            } else {
                p
            };
            for k in 0..3 {
                let d = got[k].abs_diff(want[k]);
                max = max.max(d);
                sum += f64::from(d) * f64::from(d);
            }
        }
        (max, (sum / (3 * img.pixels.len()).max(1) as f64).sqrt())
    };
    out.report.max_error = max;
    out.report.rms_error = rms;
    Ok(out)
}

/// The renderer's expansion of a 5- or 6-bit channel to 8 bits (bit
/// replication, as `fixshade::texture` does).
fn expand(code: u8, bits: u32) -> u8 {
    let c = u32::from(code);
    ((c << (8 - bits)) | (c >> (2 * bits - 8))) as u8
}

/// The `bits`-bit code whose expansion is nearest to `v` (the lower on a tie).
fn nearest_code(v: u8, bits: u32) -> u8 {
    let max = (1u32 << bits) - 1;
    // round(v · max / 255), then the neighbours: replication is not linear
    let guess = (u32::from(v) * max + 127) / 255;
    (guess.saturating_sub(1)..=(guess + 1).min(max))
        .map(|c| c as u8)
        .min_by_key(|&c| expand(c, bits).abs_diff(v))
        .unwrap_or(0)
}

/// The `Rgb565` word nearest to `p` as the renderer expands it.
pub fn rgb565(p: [u8; 3]) -> u16 {
    let (r, g, b) = (
        nearest_code(p[0], 5),
        nearest_code(p[1], 6),
        nearest_code(p[2], 5),
    );
    (u16::from(r) << 11) | (u16::from(g) << 5) | u16::from(b)
}

/// The renderer's 8-bit RGB of an `Rgb565` word.
pub fn rgb888(w: u16) -> [u8; 3] {
    [
        expand((w >> 11) as u8, 5),
        expand(((w >> 5) & 63) as u8, 6),
        expand((w & 31) as u8, 5),
    ]
}

/// Rec. 601 luma, rounded.
pub fn luma(p: [u8; 3]) -> u8 {
    ((299 * u32::from(p[0]) + 587 * u32::from(p[1]) + 114 * u32::from(p[2]) + 500) / 1000) as u8
}

fn distance2(a: [u8; 3], b: [u8; 3]) -> u32 {
    (0..3)
        .map(|k| {
            let d = i32::from(a[k]) - i32::from(b[k]);
            (d * d) as u32
        })
        .sum()
}

/// Indices, palette, and whether colours had to be merged.
fn palettise(pixels: &[[u8; 3]], distinct: &BTreeMap<[u8; 3], usize>) -> (Vec<u8>, Vec<u16>, bool) {
    // the exact case: at most 256 Rgb565 colours, in order of first use
    let mut exact: Vec<u16> = Vec::new();
    let mut index: HashMap<u16, u8> = HashMap::new();
    let mut fits = true;
    for &p in pixels {
        let w = rgb565(p);
        if let std::collections::hash_map::Entry::Vacant(e) = index.entry(w) {
            if exact.len() == 256 {
                fits = false;
                break;
            }
            e.insert(exact.len() as u8);
            exact.push(w);
        }
    }
    if fits {
        let indices = pixels.iter().map(|&p| index[&rgb565(p)]).collect();
        return (indices, exact, false);
    }
    // median cut over the distinct colours, weighted by their pixel counts
    let colours: Vec<([u8; 3], usize)> = distinct.iter().map(|(c, n)| (*c, *n)).collect();
    let mut boxes: Vec<Vec<([u8; 3], usize)>> = vec![colours];
    while boxes.len() < 256 {
        // the box with the widest channel range (the first on a tie)
        let widest = boxes
            .iter()
            .enumerate()
            .filter(|(_, b)| b.len() > 1)
            .map(|(i, b)| {
                let (ch, range) = widest_channel(b);
                (range, std::cmp::Reverse(i), ch)
            })
            .max();
        let Some((_, std::cmp::Reverse(i), ch)) = widest else {
            break;
        };
        let mut b = std::mem::take(&mut boxes[i]);
        b.sort_by_key(|(c, _)| (c[ch], *c));
        let total: usize = b.iter().map(|(_, n)| n).sum();
        let mut acc = 0;
        let mut cut = 1;
        for (k, (_, n)) in b.iter().enumerate() {
            acc += n;
            if 2 * acc >= total {
                cut = (k + 1).clamp(1, b.len() - 1);
                break;
            }
        }
        let hi = b.split_off(cut);
        boxes[i] = b;
        boxes.push(hi);
    }
    let mut palette: Vec<u16> = boxes.iter().map(|b| rgb565(mean(b))).collect();
    // k-means refinement: assign, recentre
    let colours: Vec<([u8; 3], usize)> = distinct.iter().map(|(c, n)| (*c, *n)).collect();
    let mut assign = nearest_all(&colours, &palette);
    for _ in 0..3 {
        let mut sums = vec![([0u64; 3], 0u64); palette.len()];
        for ((c, n), &k) in colours.iter().zip(&assign) {
            let s = &mut sums[usize::from(k)];
            for (acc, &ch) in s.0.iter_mut().zip(c) {
                *acc += u64::from(ch) * *n as u64;
            }
            s.1 += *n as u64;
        }
        for (p, (s, n)) in palette.iter_mut().zip(&sums) {
            if *n > 0 {
                *p = rgb565(s.map(|x| ((x + n / 2) / n) as u8));
            }
        }
        assign = nearest_all(&colours, &palette);
    }
    let lookup: HashMap<[u8; 3], u8> = colours.iter().map(|(c, _)| *c).zip(assign).collect();
    let indices = pixels
        .iter()
        .map(|p| lookup.get(p).copied().unwrap_or(0))
        .collect();
    (indices, palette, true)
}

/// The nearest palette entry (as the renderer expands it) of every colour.
fn nearest_all(colours: &[([u8; 3], usize)], palette: &[u16]) -> Vec<u8> {
    let expanded: Vec<[u8; 3]> = palette.iter().map(|&w| rgb888(w)).collect();
    colours
        .iter()
        .map(|(c, _)| {
            expanded
                .iter()
                .enumerate()
                .min_by_key(|(_, e)| distance2(*c, **e))
                .map_or(0, |(i, _)| i as u8)
        })
        .collect()
}

fn widest_channel(b: &[([u8; 3], usize)]) -> (usize, u8) {
    (0..3)
        .map(|ch| {
            let lo = b.iter().map(|(c, _)| c[ch]).min().unwrap_or(0);
            let hi = b.iter().map(|(c, _)| c[ch]).max().unwrap_or(0);
            (ch, hi - lo)
        })
        .max_by_key(|&(ch, r)| (r, std::cmp::Reverse(ch)))
        .unwrap_or((0, 0))
}

fn mean(b: &[([u8; 3], usize)]) -> [u8; 3] {
    let n: u64 = b.iter().map(|(_, n)| *n as u64).sum::<u64>().max(1);
    let mut s = [0u64; 3];
    for (c, k) in b {
        for ch in 0..3 {
            s[ch] += u64::from(c[ch]) * *k as u64;
        }
    }
    s.map(|x| ((x + n / 2) / n) as u8)
}

/// Per-axis resampling weights from `n_in` to `n_out` samples: area
/// coverage when shrinking, linear interpolation between pixel centres when
/// growing (edges clamped).
fn weights(n_in: u32, n_out: u32) -> Vec<Vec<(usize, f64)>> {
    let scale = f64::from(n_in) / f64::from(n_out);
    (0..n_out)
        .map(|o| {
            if scale >= 1.0 {
                let (a, b) = (f64::from(o) * scale, f64::from(o + 1) * scale);
                let mut w = Vec::new();
                let mut i = a.floor() as u32;
                while f64::from(i) < b && i < n_in {
                    let cover = b.min(f64::from(i + 1)) - a.max(f64::from(i));
                    if cover > 0.0 {
                        w.push((i as usize, cover / scale));
                    }
                    i += 1;
                }
                w
            } else {
                let x = ((f64::from(o) + 0.5) * scale - 0.5).clamp(0.0, f64::from(n_in - 1));
                let i = x.floor() as usize;
                let f = x - i as f64;
                let j = (i + 1).min(n_in as usize - 1);
                vec![(i, 1.0 - f), (j, f)]
            }
        })
        .collect()
}

/// `image` resampled to `w × h`: per axis, area averaging when shrinking,
/// linear interpolation between pixel centres when growing (edges clamped).
pub fn resample(image: &Image, w: u32, h: u32) -> Image {
    let (wx, wy) = (weights(image.width, w), weights(image.height, h));
    let sw = image.width as usize;
    let mut pixels = Vec::with_capacity((w * h) as usize);
    for ry in &wy {
        for rx in &wx {
            let mut acc = [0.0f64; 3];
            for &(y, a) in ry {
                for &(x, b) in rx {
                    let p = image.pixels.get(y * sw + x).copied().unwrap_or([0; 3]);
                    for k in 0..3 {
                        acc[k] += a * b * f64::from(p[k]);
                    }
                }
            }
            pixels.push(acc.map(|v| v.round().clamp(0.0, 255.0) as u8));
        }
    }
    Image {
        width: w,
        height: h,
        pixels,
        had_alpha: image.had_alpha,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgb565_rounds_to_the_rendered_value() {
        assert_eq!(rgb565([0, 0, 0]), 0);
        assert_eq!(rgb565([255, 255, 255]), 0xFFFF);
        assert_eq!(rgb565([255, 0, 0]), 0xF800);
        for v in 0..=255u8 {
            let back = rgb888(rgb565([v, v, v]));
            assert!(back[0].abs_diff(v) <= 4 && back[1].abs_diff(v) <= 2, "{v}");
        }
    }

    #[test]
    fn resampling_keeps_a_flat_image_flat() {
        let img = Image {
            width: 3,
            height: 5,
            pixels: vec![[10, 20, 30]; 15],
            had_alpha: false,
        };
        for (w, h) in [(4, 4), (2, 8), (1, 1)] {
            let r = resample(&img, w, h);
            assert!(r.pixels.iter().all(|&p| p == [10, 20, 30]), "{w}×{h}");
        }
        assert_eq!(nearest_power_of_two(3), 4);
        assert_eq!(nearest_power_of_two(5), 4);
        assert_eq!(nearest_power_of_two(100), 128);
        assert_eq!(nearest_power_of_two(90), 64);
    }
}
