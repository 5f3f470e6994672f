//! Gouraud shading: lit per vertex, encoded colour channels interpolated.

use super::{eye_point, unit_normal, Encoder, GouraudShading, Kernel, ModeState, Shader};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::raster::ATTR_FRAC;

impl<I: Illuminate, C> ModeState<I, C> for GouraudShading {
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
    const FUSED_DEPTH: bool = true;
    fn check(&self) -> Result<(), crate::error::RenderError> {
        self.check_lights()
    }

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

    #[inline(always)]
    fn span_depth(
        &self,
        _t: &(),
        (a, d): (&[i32; 3], &[i32; 3]),
        (x, y): (i32, i32),
        z: (i32, i32),
        color: &mut [C],
        depth: &mut [u16],
    ) {
        if C::IS_RGB565 && E::LINEAR {
            return fill565_depth(Channels565::new(a, d), z, color, depth);
        }
        let enc = self.encoder;
        super::fused_depth(
            z,
            color,
            depth,
            (*a, x),
            |(a, x)| enc.pixel(*a, *x, y),
            |(a, x)| {
                for (a, d) in a.iter_mut().zip(d) {
                    *a = a.wrapping_add(*d);
                }
                if E::POSITIONAL {
                    *x += 1;
                }
            },
        );
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
/// Each field stays inside its 16 bits: the vertex values are
/// `c·2^s + 2^(s−1)` with `(c + ½)·2^s < 2^15` (see [`Linear`](super::Linear)), the
/// run's values are within the range [`Encoder::safe`] allows, and rounding
/// the steps to 2^−11 of a channel moves a value by at most `len/2` such units
/// over a run, far less than the half-step margin (1024 units) for any run of
/// the window.
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

/// The 5-6-5 pixel of packed red-blue `rb` and green `g` ([`Channels565`]).
#[inline(always)]
fn pixel565(rb: u32, g: u32) -> u16 {
    // r = rb >> 27, b = bits 27..32 of rb << 16, g = g >> 23
    (((rb >> 27) << 11) | ((rb << 16) >> 27) | ((g >> 23) << 5)) as u16
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

/// The Gouraud loop for rounded 5-6-5 pixels with the depth test fused in
/// ([`fused_depth`](super::fused_depth)): a function of its own, so that the
/// loop's values fit the Cortex-M0's registers.
#[inline(never)]
fn fill565_depth<C: OutputColor>(
    ch: Channels565,
    z: (i32, i32),
    color: &mut [C],
    depth: &mut [u16],
) {
    let (drb, dg) = (ch.drb, ch.dg);
    super::fused_depth(
        z,
        color,
        depth,
        (ch.rb, ch.g),
        |&(rb, g)| C::from_rgb565_raw(pixel565(rb, g)),
        |(rb, g)| {
            *rb = rb.wrapping_add(drb);
            *g = g.wrapping_add(dg);
        },
    );
}

#[cfg(test)]
mod tests {
    use super::{fill565, fill565_depth, Channels565};
    use crate::raster::ATTR_FRAC;
    use crate::test_rng::Rng;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use embedded_graphics_core::prelude::RgbColor;

    /// The fused loop equals the two passes it replaces: the depth test of
    /// every pixel, then the colour of the whole run kept where it passed.
    /// Runs of 1 to 240 pixels, rising and falling depths, strips whose
    /// pixels pass, fail and tie in stretches.
    #[test]
    fn fused_span_equals_test_then_colour() {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let (mut passed, mut failed) = (0, 0);
        // every run length from 1 to 240, eight times over
        for (case, n) in (0..1920).map(|c| (c, 1 + c % 240)) {
            let ch = |rng: &mut Rng, bits: u32| (rng.next() % (1 << bits)) as i32;
            // encoded channels with ATTR_FRAC bits inside the vertex range
            let a = [0; 3].map(|_| (ch(&mut rng, 15) << ATTR_FRAC) / 2);
            let d = [0; 3].map(|_| ch(&mut rng, 12) - (1 << 11));
            let c = Channels565::new(&a, &d);
            let z0 = (ch(&mut rng, 15) + 16384) << ATTR_FRAC;
            let dz = ch(&mut rng, 16) - (1 << 15);
            let z = (z0, dz);
            let mut depth: std::vec::Vec<u16> = (0..n)
                .map(|k| {
                    let at = ((z0 as u32).wrapping_add((dz as u32).wrapping_mul(k as u32))
                        >> ATTR_FRAC) as i32;
                    // ties, passes and fails in stretches of 8
                    (at + (((k / 8 + case) % 3) as i32 - 1) * 5).clamp(0, 65535) as u16
                })
                .collect();
            let mut want_depth = depth.clone();
            let mut all = std::vec![Rgb565::BLACK; n];
            fill565(c, &mut all);
            let mut want = std::vec![Rgb565::WHITE; n];
            for k in 0..n {
                let zk = (z0 as u32).wrapping_add((dz as u32).wrapping_mul(k as u32)) >> ATTR_FRAC;
                if zk < u32::from(want_depth[k]) {
                    want_depth[k] = zk as u16;
                    want[k] = all[k];
                }
            }
            let mut got = std::vec![Rgb565::WHITE; n];
            fill565_depth(c, z, &mut got, &mut depth);
            assert_eq!(got, want, "case {case}");
            assert_eq!(depth, want_depth, "case {case}");
            passed += want.iter().filter(|p| **p != Rgb565::WHITE).count();
            failed += want.iter().filter(|p| **p == Rgb565::WHITE).count();
        }
        // the sweep tests both branches many times
        assert!(passed > 50_000 && failed > 50_000, "{passed} {failed}");
    }
}
