//! Gouraud shading: lit per vertex, encoded colour channels interpolated.

use super::{
    eye_point, raster_draw, unit_normal, Encoder, GouraudShading, Kernel, ModeState, ShadeVertex,
    Shader, Shading,
};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::setup::at3;
use crate::raster::{DrawStats, Plane, RasterOptions, Setup, SpanShader, ATTR_FRAC};
use crate::target::{DepthBuffer, Framebuffer};

impl<I: Illuminate, C> ModeState<I, C> for GouraudShading {
    type State = ();
    fn state(_: &I) {}
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Shader<'_, GouraudShading, I, E, C> {
    /// The encoded channel values of a vertex lit with the shader's lighting
    /// (what a Gouraud vertex carries; each below 2^15).
    pub fn vertex_values(
        &self,
        position: &crate::vector::Point3<I::Scalar>,
        normal: crate::vector::Vec3<I::Scalar>,
    ) -> [i32; 3] {
        self.encoder.vertex(self.lighting.shade(position, normal))
    }
}

/// Steps the encoded channels along a run (per-triangle API: the values carry
/// [`ATTR_FRAC`] fraction bits, see [`Shading::draw`]).
impl<I: Illuminate, E: Encoder<C>, C: OutputColor> SpanShader<3>
    for Shader<'_, GouraudShading, I, E, C>
{
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; 3], step: &[i32; 3], out: &mut [C]) {
        let mut a = *start;
        for (x, p) in (x..).zip(out.iter_mut()) {
            // pixel k: channels = start + k·step
            *p = self.encoder.pixel(a, x, y);
            for i in 0..3 {
                a[i] = a[i].wrapping_add(step[i]);
            }
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>
    Shader<'_, GouraudShading, I, E, C>
{
    fn draw_any<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        // vertex values < 2^15, with ATTR_FRAC bits: < 2^29 (the attribute limit)
        let v = tri.map(|t| {
            t.raster(
                self.vertex_values(&t.position, t.normal)
                    .map(|a| a << ATTR_FRAC),
            )
        });
        raster_draw(fb, depth, &v, opts, self, perspective)
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Shading<S>
    for Shader<'_, GouraudShading, I, E, C>
{
    type Color = C;

    fn draw<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
    ) -> Result<DrawStats, F::Error> {
        self.draw_any(fb, depth, tri, opts, false)
    }

    fn draw_perspective<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
    ) -> Result<DrawStats, F::Error> {
        self.draw_any(fb, depth, tri, opts, true)
    }
}

/// A Gouraud triangle in the mesh renderer: the planes of the three channels.
#[derive(Clone, Copy, Debug)]
pub struct GouraudTriangle {
    planes: [Plane; 3],
    /// Top vertex values with [`ATTR_FRAC`] bits.
    base: [i32; 3],
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel for Shader<'_, GouraudShading, I, E, C> {
    type Color = C;
    type Vertex = [u16; 3];
    type Triangle = GouraudTriangle;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [u16; 3] {
        let c = self.lighting.shade(
            &eye_point::<I::Scalar>(v.eye),
            unit_normal::<I::Scalar>(v.normal),
        );
        // every value is in 0..2^15
        self.encoder.vertex(c).map(|v| v.clamp(0, 0x7FFF) as u16)
    }

    #[inline]
    fn triangle(&self, s: &Setup, v: [&[u16; 3]; 3], _p: [[i32; 3]; 3]) -> (GouraudTriangle, bool) {
        let t = s.tmb[0];
        let planes = core::array::from_fn(|i| s.plane([v[0][i], v[1][i], v[2][i]].map(i32::from)));
        let top = at3(&v, t);
        let base: [i32; 3] = core::array::from_fn(|i| i32::from(top[i]) << ATTR_FRAC);
        let clamp = (0..3).any(|i| !super::within(s, &planes[i], base[i], E::safe(i)));
        (GouraudTriangle { planes, base }, clamp)
    }

    #[inline]
    fn skip_rows(t: &mut GouraudTriangle, rows: i32) {
        for p in t.planes.iter_mut() {
            p.skip_rows(rows);
        }
    }

    #[inline(always)]
    fn next_row(t: &mut GouraudTriangle) {
        for p in t.planes.iter_mut() {
            p.next_row();
        }
    }

    #[inline(always)]
    fn shade<const CLAMP: bool>(&self, t: &GouraudTriangle, x: i32, y: i32, color: &mut [C]) {
        let n = color.len();
        let mut a = [0i32; 3];
        let mut d = [0i32; 3];
        for i in 0..3 {
            let (s, st) = super::start::<CLAMP>(&t.planes[i], x, n);
            a[i] = t.base[i].wrapping_add(s);
            d[i] = st;
        }
        if C::IS_RGB565 && E::LINEAR {
            return fill565(a, d, color);
        }
        let enc = self.encoder;
        let mut x = x;
        for c in color.iter_mut() {
            *c = enc.pixel(a, x, y);
            for (a, d) in a.iter_mut().zip(d) {
                // the values after the last pixel are not used: wrapping is harmless
                *a = a.wrapping_add(d);
            }
            if E::POSITIONAL {
                x += 1;
            }
            super::no_unroll();
        }
    }
}

/// The Gouraud loop for rounded 5-6-5 pixels: red and blue interpolated in one
/// `u32` (red in the high half, blue in the low half, 11 fraction bits each),
/// green in another: two additions instead of three, and no masks; a function
/// of its own, so that its six live values fit the Cortex-M0's registers.
///
/// Each field stays inside its 16 bits: the vertex values are
/// `c·2^s + 2^(s−1)` with `(c + ½)·2^s < 2^15` (see [`Linear`](super::Linear)), the
/// run's values are within the range [`Encoder::safe`] allows, and rounding
/// the steps to 2^−11 of a channel moves a value by at most `len/2` such units
/// over a run, far less than the half-step margin (1024 units) for any run of
/// the window.
#[inline(never)]
fn fill565<C: OutputColor>(a: [i32; 3], d: [i32; 3], color: &mut [C]) {
    // 5-bit channels: vertex values c·2^10 (+½) with ATTR_FRAC bits → c·2^11 in 16 bits
    let sh = ATTR_FRAC - 1;
    let half = 1 << (sh - 1);
    let mut rb = (((a[0] >> sh) as u32) << 16) | (a[2] >> sh) as u32;
    let drb = (((d[0] + half) >> sh) as u32)
        .wrapping_shl(16)
        .wrapping_add(((d[2] + half) >> sh) as u32);
    // 6-bit green: vertex values c·2^9 (+½) with ATTR_FRAC bits: c = g >> 23
    let (mut g, dg) = (a[1] as u32, d[1] as u32);
    for c in color.iter_mut() {
        // r = rb >> 27, b = bits 27..32 of rb << 16, g = g >> 23
        let raw = ((rb >> 27) << 11) | ((rb << 16) >> 27) | ((g >> 23) << 5);
        *c = C::from_rgb565_raw(raw as u16);
        // the values after the last pixel are not used: wrapping is harmless
        rb = rb.wrapping_add(drb);
        g = g.wrapping_add(dg);
        crate::shade::no_unroll();
    }
}
