//! How a linear colour becomes a pixel: plain rounding, ordered dithering or a
//! gamma table. Gouraud shading interpolates already-encoded channel values, so
//! each encoder also says what a vertex carries and how a pixel reads it.

use crate::color::{GammaTable, OutputColor, Rgb};
use crate::num::Scalar;

/// Fraction bits of the channel values Gouraud shading interpolates.
pub const CHANNEL_FRAC: u32 = 16;

/// Turns linear colours into pixels of colour type `C`.
pub trait Encoder<C: OutputColor> {
    /// The pixel at (`x`, `y`) of linear colour `c` (flat and Phong shading).
    fn encode<S: Scalar>(&self, c: Rgb<S>, x: i32, y: i32) -> C;
    /// What a Gouraud vertex of linear colour `c` carries, per channel.
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3];
    /// The pixel at (`x`, `y`) of interpolated Gouraud channel values.
    fn pixel(&self, a: [i32; 3], x: i32, y: i32) -> C;
}

/// Channel values `v·max·2^16` of the clamped linear channels (`v` in [0, 1]).
#[inline]
fn scaled_channels<C: OutputColor, S: Scalar>(c: Rgb<S>) -> [i32; 3] {
    let l = C::linear_channels(c);
    core::array::from_fn(|i| scale_65535(l[i].to_unorm(16) * C::CHANNEL_MAX[i]) as i32)
}

/// `⌊x·2^16/65535⌋` for `x ≤ 65535·255`, as `x + ⌊(x + ⌊x/2^16⌋ + 1)/2^16⌋`: no
/// 64-bit division per vertex on a Cortex-M0 (equal for every such `x`: see the test).
#[inline(always)]
fn scale_65535(x: u32) -> u32 {
    x + ((x + (x >> 16) + 1) >> 16)
}

/// Rounds each channel to nearest; no gamma (the display receives linear values).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Linear;

impl<C: OutputColor> Encoder<C> for Linear {
    #[inline(always)]
    fn encode<S: Scalar>(&self, c: Rgb<S>, _x: i32, _y: i32) -> C {
        C::from_linear(c)
    }
    #[inline]
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3] {
        // + ½ so that the per-pixel shift rounds to nearest
        scaled_channels::<C, S>(c).map(|v| v + (1 << (CHANNEL_FRAC - 1)))
    }
    #[inline(always)]
    fn pixel(&self, a: [i32; 3], _x: i32, _y: i32) -> C {
        // channel = ⌊a / 2^16⌋ (a ≥ 0, within the vertex range)
        C::from_channels(a.map(|v| (v >> CHANNEL_FRAC) as u32))
    }
}

/// 4×4 ordered (Bayer) dithering: `⌊v·max + t(x, y)⌋` with thresholds `t` spread
/// over (0, 1), turning the banding of smooth gradients on 5-6-5 displays into a
/// fine pattern. No gamma.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dithered;

/// Bayer thresholds `(2k + 1)/32` of a channel step, in 2^-16 units.
const BAYER: [[i32; 4]; 4] = {
    const K: [[i32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    let mut t = [[0; 4]; 4];
    let mut i = 0;
    while i < 16 {
        t[i / 4][i % 4] = ((2 * K[i / 4][i % 4] + 1) << CHANNEL_FRAC) / 32;
        i += 1;
    }
    t
};

impl<C: OutputColor> Encoder<C> for Dithered {
    #[inline(always)]
    fn encode<S: Scalar>(&self, c: Rgb<S>, x: i32, y: i32) -> C {
        self.pixel(scaled_channels::<C, S>(c), x, y)
    }
    #[inline]
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3] {
        scaled_channels::<C, S>(c)
    }
    #[inline(always)]
    fn pixel(&self, a: [i32; 3], x: i32, y: i32) -> C {
        let t = BAYER[(y & 3) as usize][(x & 3) as usize];
        let max = C::CHANNEL_MAX;
        // channel = ⌊(a + t) / 2^16⌋, at most max
        C::from_channels(core::array::from_fn(|i| {
            (((a[i] + t) >> CHANNEL_FRAC) as u32).min(max[i])
        }))
    }
}

/// A gamma table: the linear channel indexes the table (8-bit encoded output),
/// then is rounded to the channel's bits. Gouraud shading interpolates linear
/// values and looks the table up per pixel.
#[derive(Clone, Copy, Debug)]
pub struct Gamma<'t, const N: usize>(pub &'t GammaTable<N>);

impl<C: OutputColor, const N: usize> Encoder<C> for Gamma<'_, N> {
    #[inline(always)]
    fn encode<S: Scalar>(&self, c: Rgb<S>, _x: i32, _y: i32) -> C {
        C::from_linear_gamma(c, self.0)
    }
    #[inline]
    fn vertex<S: Scalar>(&self, c: Rgb<S>) -> [i32; 3] {
        // linear channel in Q16 (0..=65535)
        C::linear_channels(c).map(|v| v.to_unorm(16) as i32)
    }
    #[inline(always)]
    fn pixel(&self, a: [i32; 3], _x: i32, _y: i32) -> C {
        let max = C::CHANNEL_MAX;
        C::from_channels(core::array::from_fn(|i| {
            let e = self.0.apply_unorm16(a[i].clamp(0, 65535) as u32) as u32;
            (e * max[i] + 127) / 255
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
