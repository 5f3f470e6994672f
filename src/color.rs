//! Linear RGB in a tier's format and its conversion to embedded-graphics colours,
//! with optional table-driven gamma and ordered dithering.

use crate::error::{non_negative3, ParamError};
use crate::num::Scalar;
use embedded_graphics_core::pixelcolor::{Gray8, Rgb565, Rgb888};

/// A linear RGB triple: a colour, an intensity or a reflection coefficient per
/// channel. Channels are not clamped while lighting is summed; conversion to an
/// output colour clamps each channel to [0, 1].
///
/// ```
/// use fixshade::color::Rgb;
/// use embedded_graphics_core::pixelcolor::Rgb888;
/// let c = Rgb::<f32>::new(1.0, 0.5, 0.0).mul(Rgb::splat(0.5));
/// assert_eq!(c.to_rgb888(), Rgb888::new(128, 64, 0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rgb<S> {
    /// Red.
    pub r: S,
    /// Green.
    pub g: S,
    /// Blue.
    pub b: S,
}

impl<S> Rgb<S> {
    /// A colour from its channels.
    #[inline(always)]
    pub const fn new(r: S, g: S, b: S) -> Self {
        Self { r, g, b }
    }
}

impl<S: Scalar> Rgb<S> {
    /// Black (all channels zero).
    pub const BLACK: Self = Self::new(S::ZERO, S::ZERO, S::ZERO);
    /// White (all channels one).
    pub const WHITE: Self = Self::new(S::ONE, S::ONE, S::ONE);

    /// All three channels equal to `v`.
    #[inline(always)]
    pub const fn splat(v: S) -> Self {
        Self::new(v, v, v)
    }

    /// Converts `f32` channels without validation (saturating; NaN becomes zero).
    #[inline]
    pub fn from_f32(c: [f32; 3]) -> Self {
        Self::new(S::from_f32(c[0]), S::from_f32(c[1]), S::from_f32(c[2]))
    }

    /// Converts `f32` channels, rejecting NaN, infinities and negative values.
    /// Values beyond the tier's range saturate.
    pub fn try_from_f32(name: &'static str, c: [f32; 3]) -> Result<Self, ParamError> {
        non_negative3(name, c).map(Self::from_f32)
    }

    /// The channels as `f32`.
    #[inline]
    pub fn to_f32(self) -> [f32; 3] {
        [self.r.to_f32(), self.g.to_f32(), self.b.to_f32()]
    }

    /// Channel-wise sum, saturating.
    #[inline(always)]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.r.add(o.r), self.g.add(o.g), self.b.add(o.b))
    }

    /// Channel-wise product, saturating.
    #[inline(always)]
    pub fn mul(self, o: Self) -> Self {
        Self::new(self.r.mul(o.r), self.g.mul(o.g), self.b.mul(o.b))
    }

    /// Every channel times `k`, saturating.
    #[inline(always)]
    pub fn scale(self, k: S) -> Self {
        Self::new(self.r.mul(k), self.g.mul(k), self.b.mul(k))
    }

    /// `self + o·k`, saturating.
    #[inline(always)]
    pub fn add_scaled(self, o: Self, k: S) -> Self {
        self.add(o.scale(k))
    }

    /// `a·(1 − t) + b·t` per channel, for `t` in [0, 1].
    #[inline(always)]
    pub fn lerp(self, b: Self, t: S) -> Self {
        self.scale(S::ONE.sub(t)).add(b.scale(t))
    }

    /// Each channel quantised to `bits` (clamped to [0, 1], rounded to nearest).
    #[inline(always)]
    pub fn to_unorm(self, bits: u32) -> [u32; 3] {
        [
            self.r.to_unorm(bits),
            self.g.to_unorm(bits),
            self.b.to_unorm(bits),
        ]
    }

    /// 8 bits per channel, no gamma.
    #[inline]
    pub fn to_rgb888(self) -> Rgb888 {
        let [r, g, b] = self.to_unorm(8);
        Rgb888::new(r as u8, g as u8, b as u8)
    }

    /// 5-6-5 bits, each channel rounded to nearest, no gamma.
    #[inline]
    pub fn to_rgb565(self) -> Rgb565 {
        Rgb565::new(
            self.r.to_unorm(5) as u8,
            self.g.to_unorm(6) as u8,
            self.b.to_unorm(5) as u8,
        )
    }

    /// 5-6-5 bits with 4×4 ordered (Bayer) dithering at pixel (`x`, `y`): each
    /// channel becomes `floor(v·(2^bits − 1) + threshold(x, y))`, which turns the
    /// banding of smooth gradients into a fine pattern. No gamma.
    #[inline]
    pub fn to_rgb565_dithered(self, x: i32, y: i32) -> Rgb565 {
        let t = BAYER4[(y & 3) as usize][(x & 3) as usize] as u32;
        // threshold in 16-bit units: (2t + 1)/32 of a step
        let d = ((2 * t + 1) << 16) / 32;
        let q = |v: S, max: u32| (((v.to_unorm(16) * max) + d) >> 16) as u8;
        Rgb565::new(q(self.r, 31), q(self.g, 63), q(self.b, 31))
    }

    /// 8-bit grey from the Rec. 709 luminance `0.2126 R + 0.7152 G + 0.0722 B`.
    #[inline]
    pub fn to_gray8(self) -> Gray8 {
        Gray8::new(self.luminance().to_unorm(8) as u8)
    }

    /// Rec. 709 luminance of a linear colour.
    #[inline]
    pub fn luminance(self) -> S {
        self.r
            .mul(S::from_f32(0.2126))
            .add(self.g.mul(S::from_f32(0.7152)))
            .add(self.b.mul(S::from_f32(0.0722)))
    }
}

/// The 4×4 Bayer threshold matrix (values 0..16).
const BAYER4: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// An embedded-graphics colour that linear RGB converts to.
///
/// A colour has up to three integer channels with maxima [`OutputColor::CHANNEL_MAX`]
/// (a grey colour uses only the first, holding the luminance); shading stages
/// quantise into these channels and build the colour with
/// [`OutputColor::from_channels`].
pub trait OutputColor: embedded_graphics_core::pixelcolor::PixelColor {
    /// The largest value of each channel (0 for an unused channel).
    const CHANNEL_MAX: [u32; 3];
    /// The linear quantities the channels encode: `[r, g, b]`, or
    /// `[luminance, 0, 0]` for grey.
    #[inline(always)]
    fn linear_channels<S: Scalar>(c: Rgb<S>) -> [S; 3] {
        [c.r, c.g, c.b]
    }
    /// The colour of channel values already within [`OutputColor::CHANNEL_MAX`].
    fn from_channels(ch: [u32; 3]) -> Self;

    /// Whether this is the 5-6-5 format, built by [`OutputColor::from_rgb565_raw`]
    /// (the fast kernels pack the channels themselves then).
    const IS_RGB565: bool = false;

    /// The colour of a raw 5-6-5 value `r << 11 | g << 5 | b` (used only when
    /// [`OutputColor::IS_RGB565`]).
    #[inline(always)]
    fn from_rgb565_raw(raw: u16) -> Self {
        let raw = u32::from(raw);
        Self::from_channels([raw >> 11, (raw >> 5) & 63, raw & 31])
    }

    /// Quantises a linear colour (no gamma): each channel rounded to nearest.
    #[inline]
    fn from_linear<S: Scalar>(c: Rgb<S>) -> Self {
        let l = Self::linear_channels(c);
        let q = |v: S, max: u32| {
            if max == 0 {
                0
            } else {
                (v.to_unorm(16) * max + 32767) / 65535
            }
        };
        Self::from_channels([
            q(l[0], Self::CHANNEL_MAX[0]),
            q(l[1], Self::CHANNEL_MAX[1]),
            q(l[2], Self::CHANNEL_MAX[2]),
        ])
    }

    /// Quantises a linear colour through a gamma table (8-bit encoded value, then
    /// rounded to the channel's bits).
    #[inline]
    fn from_linear_gamma<S: Scalar, const N: usize>(c: Rgb<S>, gamma: &GammaTable<N>) -> Self {
        let l = Self::linear_channels(c);
        let q = |v: S, max: u32| (gamma.apply(v) as u32 * max + 127) / 255;
        Self::from_channels([
            q(l[0], Self::CHANNEL_MAX[0]),
            q(l[1], Self::CHANNEL_MAX[1]),
            q(l[2], Self::CHANNEL_MAX[2]),
        ])
    }
}

impl OutputColor for Rgb888 {
    const CHANNEL_MAX: [u32; 3] = [255, 255, 255];
    #[inline(always)]
    fn from_channels(ch: [u32; 3]) -> Self {
        Rgb888::new(ch[0] as u8, ch[1] as u8, ch[2] as u8)
    }
    #[inline]
    fn from_linear<S: Scalar>(c: Rgb<S>) -> Self {
        c.to_rgb888()
    }
}

impl OutputColor for Rgb565 {
    const CHANNEL_MAX: [u32; 3] = [31, 63, 31];
    #[inline(always)]
    fn from_channels(ch: [u32; 3]) -> Self {
        Rgb565::new(ch[0] as u8, ch[1] as u8, ch[2] as u8)
    }
    const IS_RGB565: bool = true;
    #[inline(always)]
    fn from_rgb565_raw(raw: u16) -> Self {
        Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(raw))
    }
    #[inline]
    fn from_linear<S: Scalar>(c: Rgb<S>) -> Self {
        c.to_rgb565()
    }
}

impl OutputColor for Gray8 {
    const CHANNEL_MAX: [u32; 3] = [255, 0, 0];
    #[inline(always)]
    fn linear_channels<S: Scalar>(c: Rgb<S>) -> [S; 3] {
        [c.luminance(), S::ZERO, S::ZERO]
    }
    #[inline(always)]
    fn from_channels(ch: [u32; 3]) -> Self {
        Gray8::new(ch[0] as u8)
    }
    #[inline]
    fn from_linear<S: Scalar>(c: Rgb<S>) -> Self {
        c.to_gray8()
    }
}

/// The transfer function a [`GammaTable`] encodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Transfer {
    /// `out = value^(1/γ)` (γ commonly 2.2 or 2.222; accepted range 1..=4).
    Power(f32),
    /// The piecewise sRGB curve (IEC 61966-2-1).
    Srgb,
}

impl Transfer {
    /// The encoded value of a linear value in [0, 1], in `f64`.
    pub fn encode(self, v: f64) -> f64 {
        let v = v.clamp(0.0, 1.0);
        match self {
            Transfer::Power(g) => libm::pow(v, 1.0 / g as f64),
            Transfer::Srgb => {
                if v <= 0.003_130_8 {
                    12.92 * v
                } else {
                    1.055 * libm::pow(v, 1.0 / 2.4) - 0.055
                }
            }
        }
    }
}

/// A gamma lookup table with `N` entries (a power of two from 2 to 65536): a linear
/// value is quantised to `log2(N)` bits and mapped to 8-bit output.
///
/// The table size is the accuracy/memory trade. The largest error against the exact
/// curve is always at the darkest step, where the curve is steepest (measured by
/// `cargo test --lib gamma_table_error -- --nocapture`, 8-bit LSBs):
///
/// | entries | sRGB | power 2.2 |
/// |---|---|---|
/// | 256 | 6.42 | 14.95 |
/// | 1024 | 1.93 | 7.68 |
/// | 4096 | 0.80 | 3.88 |
///
/// ```
/// use fixshade::color::{GammaTable, Transfer};
/// let g = GammaTable::<1024>::new(Transfer::Power(2.2)).unwrap();
/// assert_eq!(g.apply(0.5f32), 186); // 0.5^(1/2.2) · 255
/// assert!(GammaTable::<1000>::new(Transfer::Srgb).is_err()); // not a power of two
/// ```
#[derive(Clone, Debug)]
pub struct GammaTable<const N: usize> {
    table: [u8; N],
    bits: u32,
}

impl<const N: usize> GammaTable<N> {
    /// Builds the table (uses `f64` math once, at construction).
    ///
    /// Errors: [`ParamError::GammaOutOfRange`] for a power outside 1..=4 or a table
    /// size that is not a power of two in 2..=65536.
    pub fn new(transfer: Transfer) -> Result<Self, ParamError> {
        if let Transfer::Power(g) = transfer {
            if !(1.0..=4.0).contains(&g) {
                return Err(ParamError::GammaOutOfRange);
            }
        }
        if !N.is_power_of_two() || !(2..=65536).contains(&N) {
            return Err(ParamError::GammaOutOfRange);
        }
        let mut table = [0u8; N];
        let max = (N - 1) as f64;
        for (i, t) in table.iter_mut().enumerate() {
            *t = libm::round(transfer.encode(i as f64 / max) * 255.0) as u8;
        }
        Ok(Self {
            table,
            bits: N.trailing_zeros(),
        })
    }

    /// The 8-bit encoded value of a linear value given as `u16`-scaled integer
    /// (`v·65535`, values above 65535 clamp).
    #[inline(always)]
    pub fn apply_unorm16(&self, v: u32) -> u8 {
        let sh = 16 - self.bits;
        // nearest of the N entries: ⌊(v + half a step) / 2^(16 − bits)⌋, at most N − 1
        let i = ((v.min(65535) + ((1 << sh) >> 1)) >> sh) as usize;
        self.table.get(i.min(N - 1)).copied().unwrap_or(255)
    }

    /// The 8-bit encoded value of a linear value (clamped to [0, 1]).
    #[inline(always)]
    pub fn apply<S: Scalar>(&self, v: S) -> u8 {
        // to_unorm(bits) ≤ N − 1: `get` never fails, the fallback is unreachable.
        self.table
            .get(v.to_unorm(self.bits) as usize)
            .copied()
            .unwrap_or(255)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Q14, Q30};
    use embedded_graphics_core::pixelcolor::RgbColor;

    #[test]
    fn rgb565_rounding_and_clamping() {
        let c = Rgb::<Q14>::from_f32([1.5, 0.5, -0.2]).to_rgb565();
        assert_eq!((c.r(), c.g(), c.b()), (31, 32, 0));
        let c = Rgb::<Q30>::from_f32([0.0, 1.0, 1.0]).to_rgb565();
        assert_eq!((c.r(), c.g(), c.b()), (0, 63, 31));
    }

    #[test]
    fn dithering_averages_to_the_value() {
        // The mean of the dithered 4×4 block equals the value to within 1/32 step.
        for v in [0.1f32, 0.33, 0.5, 0.77, 0.95] {
            let c = Rgb::<Q14>::from_f32([v, v, v]);
            let mut sum = 0u32;
            for y in 0..4 {
                for x in 0..4 {
                    sum += c.to_rgb565_dithered(x, y).r() as u32;
                }
            }
            let mean = sum as f32 / 16.0;
            assert!(
                (mean - v * 31.0).abs() <= 1.0 / 16.0 + 1.0e-3,
                "{v}: {mean}"
            );
        }
        let w = Rgb::<f32>::WHITE.to_rgb565_dithered(3, 3);
        assert_eq!((w.r(), w.g(), w.b()), (31, 63, 31));
    }

    #[test]
    fn gamma_table_error() {
        // Largest error (8-bit LSB) of the table against the exact curve, per size.
        fn worst<const N: usize>(t: Transfer) -> f64 {
            let g = GammaTable::<N>::new(t).unwrap();
            let mut worst = 0.0f64;
            for i in 0..=20000 {
                let v = i as f64 / 20000.0;
                let exact = t.encode(v) * 255.0;
                worst = worst.max((g.apply(v as f32) as f64 - exact).abs());
            }
            worst
        }
        // Measured (cargo test --lib gamma_table_error -- --nocapture):
        // 256: sRGB 6.42, power 2.2 14.95; 1024: 1.93, 7.68; 4096: 0.80, 3.88 LSB.
        // The worst case is always the darkest step, where the curve is steepest.
        for (n, s, p) in [
            (
                256,
                worst::<256>(Transfer::Srgb),
                worst::<256>(Transfer::Power(2.2)),
            ),
            (
                1024,
                worst::<1024>(Transfer::Srgb),
                worst::<1024>(Transfer::Power(2.2)),
            ),
            (
                4096,
                worst::<4096>(Transfer::Srgb),
                worst::<4096>(Transfer::Power(2.2)),
            ),
        ] {
            std::println!("gamma table {n}: sRGB {s:.2} LSB, power 2.2 {p:.2} LSB");
        }
        assert!(worst::<256>(Transfer::Srgb) <= 6.5);
        assert!(worst::<256>(Transfer::Power(2.2)) <= 15.0);
        assert!(worst::<1024>(Transfer::Srgb) <= 2.0);
        assert!(worst::<1024>(Transfer::Power(2.2)) <= 7.7);
        assert!(worst::<4096>(Transfer::Srgb) <= 0.81);
        assert!(worst::<4096>(Transfer::Power(2.2)) <= 3.9);
    }

    #[test]
    fn gamma_rejects_bad_parameters() {
        assert_eq!(
            GammaTable::<256>::new(Transfer::Power(0.5)).unwrap_err(),
            ParamError::GammaOutOfRange
        );
        assert!(GammaTable::<256>::new(Transfer::Power(f32::NAN)).is_err());
        assert!(GammaTable::<100>::new(Transfer::Srgb).is_err());
    }
}
