//! Gouraud shading: lit per vertex, encoded colour channels interpolated.

use super::{
    eye_point, pixel565, unit_normal, Encoder, Fill, GouraudShading, Kernel, Mode, Shader,
};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::ATTR_FRAC;

impl<I, C> Mode<I, C> for GouraudShading {
    const NAME: &'static str = "gouraud";
    type State = ();
    fn state(self, _: &I) {}
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel for Shader<'_, GouraudShading, I, E, C> {
    type Color = C;
    /// The encoded channel values of the lit vertex.
    type Vertex = [u16; 3];
    type Varyings = [i32; 3];
    type Triangle = ();
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;
    const FILLS: bool = true;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [u16; 3] {
        let c = self.lighting.shade(
            &eye_point::<I::Scalar>(v.eye),
            unit_normal::<I::Scalar>(v.normal),
        );
        // every value is in 0..2^15
        self.encoder.vertex(c).map(|v| v.clamp(0, 0x7FFF) as u16)
    }

    #[inline(always)]
    fn triangle(&self, v: [&[u16; 3]; 3], _eye: &[[i32; 3]; 3]) -> ((), [[i32; 3]; 3]) {
        ((), v.map(|c| c.map(i32::from)))
    }

    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        E::safe(i)
    }

    /// Rounded 5-6-5 pixels through [`Linear`](super::Linear): the packed
    /// ramp; else the kernel's own pixels.
    #[inline(always)]
    fn fill(&self, _t: &(), a: &[i32; 3], d: &[i32; 3]) -> Fill<C> {
        if C::IS_RGB565 && E::LINEAR {
            Channels565::new(a, d).fill()
        } else {
            Fill::Shaded
        }
    }

    #[inline(always)]
    fn span(&self, _t: &(), a: &[i32; 3], d: &[i32; 3], x: i32, y: i32, color: &mut [C]) {
        if C::IS_RGB565 && E::LINEAR {
            return fill565(Channels565::new(a, d), color);
        }
        let enc = self.encoder;
        let (mut a, mut x) = (*a, x);
        for c in color.iter_mut() {
            // pixel k: channels = start + k·step
            *c = enc.pixel(a, x, y);
            for (a, d) in a.iter_mut().zip(d) {
                // the values after the last pixel are not used: wrapping is harmless
                *a = a.wrapping_add(*d);
            }
            if E::POSITIONAL {
                x += 1;
            }
            crate::num::no_unroll();
        }
    }
}

/// The Gouraud channels of a run of rounded 5-6-5 pixels: red and blue
/// interpolated in one `u32` (red in the high half, blue in the low half, 11
/// fraction bits each), green in another: two additions per pixel instead of
/// three, and no masks.
///
/// Each field stays inside its 16 bits: vertex values `c·2^s + 2^(s−1)` with
/// `(c + ½)·2^s < 2^15` ([`Linear`](super::Linear)), run values within
/// [`Encoder::safe`], and steps rounded to 2^−11 of a channel drift by at most
/// `len/2` units over a run, far below the 1024-unit half-step margin.
#[derive(Clone, Copy)]
struct Channels565 {
    rb: u32,
    drb: u32,
    g: u32,
    dg: u32,
}

impl Channels565 {
    /// The channels of the run starting at `a` with steps `d` (the encoded
    /// channels with [`ATTR_FRAC`] fraction bits).
    #[inline(always)]
    fn new(a: &[i32; 3], d: &[i32; 3]) -> Self {
        // 5-bit channels: vertex values c·2^10 (+½) with ATTR_FRAC bits → c·2^11 in 16 bits
        let sh = ATTR_FRAC - 1;
        let half = 1 << (sh - 1);
        Channels565 {
            rb: (((a[0] >> sh) as u32) << 16) | (a[2] >> sh) as u32,
            drb: (((d[0] + half) >> sh) as u32)
                .wrapping_shl(16)
                .wrapping_add(((d[2] + half) >> sh) as u32),
            // 6-bit green: vertex values c·2^9 (+½) with ATTR_FRAC bits: c = g >> 23
            g: a[1] as u32,
            dg: d[1] as u32,
        }
    }
}

impl Channels565 {
    /// The run as the span stage writes it.
    #[inline(always)]
    fn fill<C>(self) -> Fill<C> {
        Fill::Ramp565 {
            rb: self.rb,
            drb: self.drb,
            g: self.g,
            dg: self.dg,
        }
    }
}

/// The Gouraud loop for rounded 5-6-5 pixels ([`Channels565`]): a function
/// of its own, so that its six live values fit the Cortex-M0's registers.
#[inline(never)]
fn fill565<C: OutputColor>(ch: Channels565, color: &mut [C]) {
    let Channels565 {
        mut rb,
        drb,
        mut g,
        dg,
    } = ch;
    for c in color.iter_mut() {
        *c = C::from_rgb565_raw(pixel565(rb, g));
        // the values after the last pixel are not used: wrapping is harmless
        rb = rb.wrapping_add(drb);
        g = g.wrapping_add(dg);
        crate::num::no_unroll();
    }
}
