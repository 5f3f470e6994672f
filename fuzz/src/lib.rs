//! Shared input decoding and checks of the fuzz targets (issue 11).
//!
//! Every target reads its parameters from the fuzzer's bytes with [`Input`]:
//! `f32`s are drawn so that the special values (±0, ±∞, NaN, ±MAX, subnormals,
//! the ±32 768 geometry edge, huge and tiny) are likely, and exhausted input
//! reads as zeros. Each target asserts its own properties; a panic (overflow
//! checks are on in the fuzz profile) is a crash the fuzzer reports.

use fixshade::color::Rgb;
use fixshade::lighting::{AnyLight, LightDesc, LightKind, MaterialDesc};
use fixshade::num::Scalar;

/// The fuzzer's bytes as a stream of parameters.
pub struct Input<'a>(pub &'a [u8]);

impl Input<'_> {
    /// One byte (0 when exhausted).
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    /// Four bytes, little-endian.
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    /// Any `i32`, small ones and the edges likely.
    pub fn i32(&mut self) -> i32 {
        match self.u8() % 8 {
            0 => i32::MIN,
            1 => i32::MAX,
            2 | 3 => i32::from(self.u8() as i8),
            4 | 5 => i32::from(self.u32() as u16 as i16),
            _ => self.u32() as i32,
        }
    }

    /// Any `f32`, with the special values likely.
    pub fn f32(&mut self) -> f32 {
        let tag = self.u8();
        match tag % 16 {
            0 => f32::NAN,
            1 => f32::INFINITY,
            2 => f32::NEG_INFINITY,
            3 => f32::MAX,
            4 => -f32::MAX,
            5 => 0.0,
            6 => -0.0,
            7 => f32::MIN_POSITIVE / 4.0,
            8 => 32_768.0,
            9 => -32_768.0,
            10 => f32::from_bits(self.u32()),
            // small values: −4..4 in 1/64 steps, the common case
            _ => f32::from(self.u32() as u16 as i16) / 8192.0,
        }
    }

    /// Three `f32`s.
    pub fn f3(&mut self) -> [f32; 3] {
        [self.f32(), self.f32(), self.f32()]
    }

    /// A light description of any kind.
    pub fn light(&mut self) -> LightDesc {
        let kind = match self.u8() % 3 {
            0 => LightKind::Directional {
                towards_light: self.f3(),
            },
            1 => LightKind::Point {
                position: self.f3(),
                attenuation: self.f3(),
            },
            _ => LightKind::Spot {
                position: self.f3(),
                axis: self.f3(),
                exponent: self.f32(),
                cutoff_deg: self.f32(),
                attenuation: self.f3(),
            },
        };
        LightDesc {
            kind,
            ambient: self.f3(),
            diffuse: self.f3(),
            specular: self.f3(),
        }
    }

    /// A material description with any values.
    // the update keeps this compiling when the description gains a field
    #[allow(clippy::needless_update)]
    pub fn material(&mut self) -> MaterialDesc {
        MaterialDesc {
            emission: self.f3(),
            ambient: self.f3(),
            diffuse: self.f3(),
            specular: self.f3(),
            shininess: self.f32(),
            brilliance: self.u8(),
            fresnel_f0: self.f32(),
            transmission: self.f3(),
            transmission_exponent: self.f32(),
            refractive_index: self.f32(),
            ..MaterialDesc::default()
        }
    }

    /// Up to two lights the constructor accepts, for tier `S`.
    pub fn lights<S: Scalar>(&mut self) -> heapless::Vec<AnyLight<S>, 2> {
        let mut out = heapless::Vec::new();
        for _ in 0..1 + self.u8() % 2 {
            if let Ok(l) = AnyLight::<S>::new(&self.light()) {
                let _ = out.push(l);
            }
        }
        out
    }
}

/// A lit colour: every channel finite and within the 8-bit range once quantised.
pub fn check_color<S: Scalar>(c: Rgb<S>, what: &str) {
    for x in c.to_f32() {
        assert!(
            x.is_finite(),
            "{}: non-finite channel {c:?} ({what})",
            S::NAME
        );
    }
    for u in c.to_unorm(8) {
        assert!(u <= 255, "{}: channel {u} > 255 ({what})", S::NAME);
    }
}
