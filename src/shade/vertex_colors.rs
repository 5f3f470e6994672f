//! Triangles of colours the caller lit per vertex (the per-triangle API): what
//! OpenGL's per-vertex pipeline needs beyond [`Shading::draw`](super::Shading::draw)
//! — `GL_FLAT`'s provoking vertex, `GL_COLOR_MATERIAL` (vertex colours through
//! [`Illuminate::shade_parts`]) and `GL_SEPARATE_SPECULAR_COLOR` (two clamped
//! colours interpolated apart).

use super::{raster_draw, Encoder, FlatShading, GouraudShading, ShadeVertex, Shader};
use crate::color::{OutputColor, Rgb};
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::{DrawStats, RasterOptions, SpanShader};
use crate::target::{DepthBuffer, Framebuffer};

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>
    Shader<'_, FlatShading, I, E, C>
{
    /// Fills the triangle with `color` (linear; clamped and encoded like a lit
    /// colour). `perspective` selects
    /// [`draw_triangle_perspective`](crate::raster::draw_triangle_perspective)'s
    /// rasterization, as [`Shading::draw_perspective`](super::Shading::draw_perspective) does.
    pub fn draw_color<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        color: Rgb<S>,
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        self.set_color(color);
        let v = [tri[0].raster([]), tri[1].raster([]), tri[2].raster([])];
        raster_draw(fb, depth, &v, opts, self, perspective)
    }

    /// OpenGL's `GL_FLAT`: the triangle takes the colour lit at its provoking
    /// vertex, the last one (`tri[2]`, with its own normal and position), where
    /// [`Shading::draw`](super::Shading::draw) lights the centroid with the
    /// averaged normal. The two agree for face normals, directional lights and a
    /// viewer at infinity.
    pub fn draw_provoking<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        let c = self.lighting.shade(&tri[2].position, tri[2].normal);
        self.draw_color(fb, depth, tri, c, opts, perspective)
    }
}

/// Interpolates linear colours (in the tier's attribute scale) and encodes each
/// pixel.
struct LinearColors<'e, E, S, C> {
    encoder: &'e E,
    tier: core::marker::PhantomData<(S, C)>,
}

impl<S: Scalar, E: Encoder<C>, C: OutputColor> SpanShader<3> for LinearColors<'_, E, S, C> {
    type Color = C;
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; 3], step: &[i32; 3], out: &mut [C]) {
        let mut a = *start;
        for (x, p) in (x..).zip(out.iter_mut()) {
            let c = Rgb::new(S::from_attr(a[0]), S::from_attr(a[1]), S::from_attr(a[2]));
            *p = self.encoder.encode(c, x, y);
            for i in 0..3 {
                a[i] = a[i].wrapping_add(step[i]);
            }
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>
    Shader<'_, GouraudShading, I, E, C>
{
    /// Gouraud shading of vertex colours the caller computed: the linear colours are
    /// interpolated (each channel limited to [−2, 2] at the vertex) and every pixel's
    /// colour is clamped to [0, 1] and encoded. Slower per pixel than
    /// [`Shading::draw`](super::Shading::draw), which interpolates encoded
    /// channels, but it takes any colour a vertex stage makes:
    ///
    /// - `GL_COLOR_MATERIAL`: `lighting.shade_parts(p, n, Some(vertex_colour)).sum()`
    ///   clamped to [0, 1];
    /// - `GL_SEPARATE_SPECULAR_COLOR`: `shade_parts(…).separate()` (in [0, 2]: the
    ///   primary and secondary colours clamped apart; interpolating their sum and
    ///   clamping per pixel is what OpenGL's separate interpolation and sum give);
    /// - two-sided lighting with a per-vertex choice of face.
    pub fn draw_vertex_colors<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        colors: &[Rgb<S>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        let (lo, hi) = (S::from_f32(-2.0), S::from_f32(2.0));
        let attr = |v: S| {
            let v = if v < lo {
                lo
            } else if v > hi {
                hi
            } else {
                v
            };
            v.to_attr()
        };
        let v = core::array::from_fn(|k| {
            let c = colors[k];
            tri[k].raster([attr(c.r), attr(c.g), attr(c.b)])
        });
        let mut s = LinearColors::<E, S, C> {
            encoder: &self.encoder,
            tier: core::marker::PhantomData,
        };
        raster_draw(fb, depth, &v, opts, &mut s, perspective)
    }
}
