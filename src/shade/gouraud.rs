//! Gouraud shading: lit per vertex, colours interpolated along the span.

use super::{Encoder, ShadeVertex, Shading};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::{draw_triangle, DrawStats, RasterOptions, SpanShader};
use crate::target::{DepthBuffer, Framebuffer};
use core::marker::PhantomData;

/// Gouraud shading: each vertex is lit with its own normal, the encoded colour
/// channels are interpolated across the triangle (incrementally along each span:
/// three additions per pixel) and each pixel only reads them. Misses a highlight
/// that falls inside a large triangle and smears highlights near vertices.
#[derive(Debug)]
pub struct Gouraud<'l, I, E, C> {
    lighting: &'l I,
    encoder: E,
    color: PhantomData<C>,
}

impl<'l, I: Illuminate, E: Encoder<C>, C: OutputColor> Gouraud<'l, I, E, C> {
    /// The encoded channel attributes of a vertex lit with `lighting` (what
    /// [`Shading::draw`] hands to the rasterizer).
    pub fn vertex_attrs(&self, v: &ShadeVertex<I::Scalar>) -> [i32; 3] {
        self.encoder
            .vertex(self.lighting.shade(&v.position, v.normal))
    }

    /// Gouraud shading with `lighting`, writing pixels through `encoder`.
    pub fn new(lighting: &'l I, encoder: E) -> Self {
        Self {
            lighting,
            encoder,
            color: PhantomData,
        }
    }
}

/// Steps the encoded channels along a run.
impl<I: Illuminate, E: Encoder<C>, C: OutputColor> SpanShader<3> for Gouraud<'_, I, E, C> {
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; 3], step: &[i32; 3], out: &mut [C]) {
        let [mut r, mut g, mut b] = *start;
        for (x, p) in (x..).zip(out.iter_mut()) {
            // pixel k: channels = start + k·step
            *p = self.encoder.pixel([r, g, b], x, y);
            r += step[0];
            g += step[1];
            b += step[2];
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Shading<S>
    for Gouraud<'_, I, E, C>
{
    type Color = C;

    fn draw<Fb: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut Fb,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
    ) -> DrawStats {
        let v = tri.map(|t| t.raster(self.vertex_attrs(&t)));
        draw_triangle(fb, depth, &v, opts, self)
    }
}
