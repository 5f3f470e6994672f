//! How a linear colour becomes a pixel: plain rounding, ordered dithering or a
//! gamma table. Gouraud shading interpolates already-encoded channel values, so
//! each encoder also says what a vertex carries and how a pixel reads it.

use crate::color::{GammaTable, OutputColor, Rgb};
use crate::num::Scalar;
use crate::num::ATTR_FRAC;

/// Vertex values are below `2^VERTEX_BITS` (the rasterizer's attribute range).
pub(crate) const VERTEX_BITS: u32 = 15;

/// Turns linear colours into pixels of colour type `C`.
///
/// Gouraud shading stores [`Encoder::vertex`] values (per channel, below
/// 2^15) at the vertices, interpolates them with [`ATTR_FRAC`] extra fraction
/// bits, and turns them into pixels with [`Encoder::pixel`].
pub trait Encoder<C: OutputColor>: Copy {
    /// Whether [`Encoder::pixel`] depends on the pixel position (dithering).
    const POSITIONAL: bool;
    /// Whether this is [`Linear`] rounding (kernels may then pack channels).
    const LINEAR: bool = false;
    /// The pixel at (`x`, `y`) of linear colour `c` (flat and Phong shading).
    fn encode<S: Scalar>(&self, c: Rgb<S>, x: i32, y: i32) -> C;
    /// What a Gouraud vertex of linear colour `c` carries, per channel (each
    /// value in `0..2^15`).
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3];
    /// The pixel at (`x`, `y`) of interpolated vertex values `a` (with
    /// [`ATTR_FRAC`] fraction bits, within the range of the vertex values).
    fn pixel(&self, a: [i32; 3], x: i32, y: i32) -> C;
    /// The values of channel `i` (with [`ATTR_FRAC`] bits) for which
    /// [`Encoder::pixel`] gives the correctly rounded channel: interpolated
    /// values that may leave the vertex range by a known error need no clamping
    /// while they stay inside it.
    fn safe(i: usize) -> (i32, i32);
}

/// Bits of a channel whose largest value is `max` (0 for an unused channel).
const fn bits(max: u32) -> u32 {
    32 - max.leading_zeros()
}

/// The shift `s` of channel values `v·max·2^s`: the largest with
/// `(max + 1)·2^s ≤ 2^15`.
pub(crate) const fn vertex_shift(max: u32) -> u32 {
    VERTEX_BITS - bits(max)
}

/// `⌊x·2^16/65535⌋` for `x ≤ 65535·255`, as `x + ⌊(x + ⌊x/2^16⌋ + 1)/2^16⌋`: no
/// division (equal for every such `x`: see the test).
#[inline(always)]
fn scale_65535(x: u32) -> u32 {
    x + ((x + (x >> 16) + 1) >> 16)
}

/// `round(v·max·2^s)` per channel of the clamped linear channels `v`.
#[inline]
fn scaled_channels<C: OutputColor, S: Scalar>(c: Rgb<S>) -> [i32; 3] {
    let l = C::linear_channels(c);
    core::array::from_fn(|i| {
        let max = C::CHANNEL_MAX[i];
        let sh = 16 - vertex_shift(max);
        // v·max·2^16 (v in 16-bit steps), then rounded to 2^s units
        let x = scale_65535(l[i].to_unorm(16) * max);
        ((x + ((1 << sh) >> 1)) >> sh) as i32
    })
}

/// `⌊x / 255⌋` for `x < 65535` without a division.
#[inline(always)]
pub(crate) fn div255(x: u32) -> u32 {
    (x + 1 + (x >> 8)) >> 8
}

/// Rounds each channel to nearest; no gamma (the display receives linear values).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Linear;

impl<C: OutputColor> Encoder<C> for Linear {
    const POSITIONAL: bool = false;
    const LINEAR: bool = true;
    #[inline(always)]
    fn encode<S: Scalar>(&self, c: Rgb<S>, _x: i32, _y: i32) -> C {
        C::from_linear(c)
    }
    #[inline]
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3] {
        // + ½ step, so that the per-pixel shift rounds to nearest
        let v = scaled_channels::<C, S>(c);
        core::array::from_fn(|i| v[i] + ((1 << vertex_shift(C::CHANNEL_MAX[i])) >> 1))
    }
    #[inline(always)]
    fn pixel(&self, a: [i32; 3], _x: i32, _y: i32) -> C {
        // channel = ⌊a / 2^(ATTR_FRAC + s)⌋ (a ≥ 0, at most (max + ½)·2^s)
        C::from_channels(core::array::from_fn(|i| {
            (a[i] >> (ATTR_FRAC + vertex_shift(C::CHANNEL_MAX[i]))) as u32
        }))
    }
    #[inline]
    fn safe(i: usize) -> (i32, i32) {
        // ⌊a / 2^(ATTR_FRAC + s)⌋ is a channel value for 0 ≤ a < (max + 1)·2^(s + ATTR_FRAC)
        let max = C::CHANNEL_MAX[i.min(2)];
        (0, ((max + 1) << (vertex_shift(max) + ATTR_FRAC)) as i32 - 1)
    }
}

/// 4×4 ordered (Bayer) dithering: `⌊v·max + t(x, y)⌋` with thresholds `t` spread
/// over (0, 1), turning the banding of smooth gradients on 5-6-5 displays into a
/// fine pattern. No gamma.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dithered;

/// Bayer thresholds `(2k + 1)/32` of a channel step, in 2^−16 units.
pub(crate) const BAYER: [[u32; 4]; 4] = {
    const K: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    let mut t = [[0; 4]; 4];
    let mut i = 0;
    while i < 16 {
        t[i / 4][i % 4] = ((2 * K[i / 4][i % 4] + 1) << 16) / 32;
        i += 1;
    }
    t
};

impl<C: OutputColor> Encoder<C> for Dithered {
    const POSITIONAL: bool = true;
    #[inline(always)]
    fn encode<S: Scalar>(&self, c: Rgb<S>, x: i32, y: i32) -> C {
        let v = scaled_channels::<C, S>(c);
        let a = core::array::from_fn(|i| v[i] << ATTR_FRAC);
        self.pixel(a, x, y)
    }
    #[inline]
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3] {
        scaled_channels::<C, S>(c)
    }
    #[inline(always)]
    fn pixel(&self, a: [i32; 3], x: i32, y: i32) -> C {
        let t = BAYER[(y & 3) as usize][(x & 3) as usize];
        let max = C::CHANNEL_MAX;
        // channel = ⌊(a + t·2^(ATTR_FRAC + s)) / 2^(ATTR_FRAC + s)⌋, at most max
        C::from_channels(core::array::from_fn(|i| {
            let sh = ATTR_FRAC + vertex_shift(max[i]);
            let t = (t << sh) >> 16;
            ((a[i] as u32 + t) >> sh).min(max[i])
        }))
    }
    #[inline]
    fn safe(i: usize) -> (i32, i32) {
        // non-negative values; larger ones clamp to the channel maximum
        let max = C::CHANNEL_MAX[i.min(2)];
        (0, ((max + 1) << (vertex_shift(max) + ATTR_FRAC)) as i32 - 1)
    }
}

/// A gamma table is an encoder by reference (`Shader::new(mode, &lighting,
/// &table)`): the 8-bit encoded output is rounded to the channel's bits;
/// Gouraud shading interpolates linear values and looks up per pixel.
impl<C: OutputColor, const N: usize> Encoder<C> for &GammaTable<N> {
    const POSITIONAL: bool = false;
    #[inline(always)]
    fn encode<S: Scalar>(&self, c: Rgb<S>, _x: i32, _y: i32) -> C {
        C::from_linear_gamma(c, self)
    }
    #[inline]
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3] {
        // linear channel in Q15 (0..=32767)
        C::linear_channels(c).map(|v| (v.to_unorm(16) >> 1) as i32)
    }
    #[inline(always)]
    fn pixel(&self, a: [i32; 3], _x: i32, _y: i32) -> C {
        let max = C::CHANNEL_MAX;
        C::from_channels(core::array::from_fn(|i| {
            // Q15 · 2^ATTR_FRAC → 16-bit linear value
            let v = (a[i].max(0) as u32) >> (ATTR_FRAC - 1);
            let e = self.apply_unorm16(v) as u32;
            div255(e * max[i] + 127)
        }))
    }
    #[inline]
    fn safe(_: usize) -> (i32, i32) {
        // negative values read as 0, large ones clamp to the table's end
        (i32::MIN, i32::MAX)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Q14;
    use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};

    #[test]
    fn scale_65535_is_exact() {
        for max in [31u32, 63, 255] {
            for u in 0..=65535u32 {
                let x = u * max;
                assert_eq!(
                    scale_65535(x) as u64,
                    ((x as u64) << 16) / 65535,
                    "{u} {max}"
                );
            }
        }
    }

    #[test]
    fn div255_is_exact() {
        for x in 0..65535u32 {
            assert_eq!(div255(x), x / 255, "{x}");
        }
    }

    #[test]
    fn vertex_values_fit_and_round_trip() {
        // every Q14 linear value: the vertex value fits 15 bits, and a pixel of
        // exactly that value is the rounded channel, except within 2^−s of a
        // channel step from a rounding tie (the vertex value carries s fraction
        // bits: 10 for 5-bit channels, 9 for 6-bit, 7 for 8-bit, and is within
        // 0.77·2^−s of exact: ¼ from the 16-bit intermediate, ½ + 1/64 from
        // rounding to s bits)
        let near_tie = |v: f64, max: f64, s: u32| {
            let x = v * max;
            (x - x.floor() - 0.5).abs() <= 1.0 / f64::from(1u32 << s)
        };
        for i in 0..=16384 {
            let v = Q14::<2>::from_raw(i);
            let f = f64::from(i) / 16384.0;
            let c = Rgb::new(v, v, v);
            let a: [i32; 3] = Encoder::<Rgb565>::vertex(&Linear, c);
            assert!(a.iter().all(|&x| (0..1 << VERTEX_BITS).contains(&x)));
            let p: Rgb565 = Linear.pixel(a.map(|x| x << ATTR_FRAC), 0, 0);
            let want = c.to_rgb565();
            assert!(p.r() == want.r() || near_tie(f, 31.0, 10), "{i}");
            assert!(p.g() == want.g() || near_tie(f, 63.0, 9), "{i}");
            assert!(
                p.r().abs_diff(want.r()) <= 1 && p.g().abs_diff(want.g()) <= 1,
                "{i}"
            );
            let a: [i32; 3] = Encoder::<Rgb888>::vertex(&Linear, c);
            let p: Rgb888 = Linear.pixel(a.map(|x| x << ATTR_FRAC), 0, 0);
            let want = c.to_rgb888();
            assert!(p.r() == want.r() || near_tie(f, 255.0, 7), "{i}");
            assert!(p.r().abs_diff(want.r()) <= 1, "{i}");
            // dithering never exceeds the channel maximum
            let a: [i32; 3] = Encoder::<Rgb565>::vertex(&Dithered, c);
            for (x, y) in [(0, 0), (3, 3), (1, 2)] {
                let p: Rgb565 = Dithered.pixel(a.map(|x| x << ATTR_FRAC), x, y);
                assert!(p.r() <= 31 && p.g() <= 63 && p.b() <= 31);
            }
        }
    }
}
