//! Flat shading: one colour per triangle, lit at its centroid.

use super::{Encoder, ShadeVertex, Shading};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::{draw_triangle, DrawStats, RasterOptions, SpanShader};
use crate::target::{DepthBuffer, Framebuffer};
use crate::vector::Vec3;
use core::marker::PhantomData;

/// Flat shading: the triangle is lit once, at its centroid, with the normalised
/// average of its vertex normals (equal to the face normal when the mesh gives
/// each vertex of a face the face normal), and filled with that colour. Shows the
/// seeds' Mach bands on curved surfaces; the cheapest mode.
#[derive(Debug)]
pub struct Flat<'l, I, E, C> {
    lighting: &'l I,
    encoder: E,
    channels: [i32; 3],
    color: PhantomData<C>,
}

impl<'l, I: Illuminate, E: Encoder<C>, C: OutputColor> Flat<'l, I, E, C> {
    /// Flat shading with `lighting`, writing pixels through `encoder`.
    pub fn new(lighting: &'l I, encoder: E) -> Self {
        Self {
            lighting,
            encoder,
            channels: [0; 3],
            color: PhantomData,
        }
    }

    /// Sets the colour [`SpanShader::shade_span`] fills with (what
    /// [`Shading::draw`] does with the colour lit at the centroid).
    pub fn set_color(&mut self, color: crate::color::Rgb<I::Scalar>) {
        self.channels = self.encoder.vertex(color);
    }
}

/// Fills runs with the encoded colour of the triangle being drawn.
impl<I: Illuminate, E: Encoder<C>, C: OutputColor> SpanShader<0> for Flat<'_, I, E, C> {
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, _start: &[i32; 0], _step: &[i32; 0], out: &mut [C]) {
        for (x, p) in (x..).zip(out.iter_mut()) {
            *p = self.encoder.pixel(self.channels, x, y);
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Shading<S>
    for Flat<'_, I, E, C>
{
    type Color = C;

    fn draw<Fb: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut Fb,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
    ) -> DrawStats {
        // n = normalize((n0 + n1 + n2)/3) (each third first: the sum of three unit
        // vectors would saturate the fixed tiers); p = p0 + ((p1 − p0) + (p2 − p0))/3
        let third_s = S::from_f32(1.0 / 3.0);
        let [n0, n1, n2] = tri.map(|t| t.normal.scale(third_s));
        let n = S::normalize(n0.add(n1).add(n2));
        let third = S::geo_from_f32(1.0 / 3.0);
        let centroid = |a: S::Geo, b: S::Geo, c: S::Geo| {
            S::geo_add(
                a,
                S::geo_mul(S::geo_add(S::geo_sub(b, a), S::geo_sub(c, a)), third),
            )
        };
        let [p0, p1, p2] = tri.map(|t| t.position);
        let p = Vec3::new(
            centroid(p0.x, p1.x, p2.x),
            centroid(p0.y, p1.y, p2.y),
            centroid(p0.z, p1.z, p2.z),
        );
        self.set_color(self.lighting.shade(&p, n));
        let v = [tri[0].raster([]), tri[1].raster([]), tri[2].raster([])];
        draw_triangle(fb, depth, &v, opts, self)
    }
}
