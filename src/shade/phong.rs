//! Phong shading: normals interpolated per pixel, renormalised, lit per pixel.

use super::{Encoder, ShadeVertex, Shading};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::{draw_triangle, DrawStats, RasterOptions, SpanShader};
use crate::target::{DepthBuffer, Framebuffer};
use crate::vector::{point_from_f32, Vec3};
use core::marker::PhantomData;

/// Phong shading: the vertex normals (as [`Scalar::to_attr`] attributes) are
/// interpolated incrementally along each span, renormalised per pixel with the
/// tier's [`Scalar::normalize_interpolated`], and every pixel is lit with the full
/// lighting model. When the lighting needs the surface position (point or spot
/// lights, a local viewer, fog) the eye-space position is interpolated too.
/// Catches the highlight in the middle of a large triangle.
#[derive(Debug)]
pub struct Phong<'l, I, E, C> {
    lighting: &'l I,
    encoder: E,
    color: PhantomData<C>,
}

impl<'l, S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Phong<'l, I, E, C> {
    /// Phong shading with `lighting`, writing pixels through `encoder`.
    pub fn new(lighting: &'l I, encoder: E) -> Self {
        Self {
            lighting,
            encoder,
            color: PhantomData,
        }
    }

    /// The colour of one pixel from its interpolated attributes: normal in
    /// `a[0..3]`, position in `a[3..6]` when `N = 6`.
    #[inline(always)]
    fn pixel<const N: usize>(&self, a: &[i32; N], x: i32, y: i32) -> C {
        let n = S::normalize_interpolated(Vec3::new(
            S::from_attr(a[0]),
            S::from_attr(a[1]),
            S::from_attr(a[2]),
        ));
        let p = if N >= 6 {
            Vec3::new(
                S::geo_from_attr(a[3]),
                S::geo_from_attr(a[4]),
                S::geo_from_attr(a[5]),
            )
        } else {
            point_from_f32::<S>([0.0; 3])
        };
        self.encoder.encode(self.lighting.shade(&p, n), x, y)
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor, const N: usize>
    SpanShader<N> for Phong<'_, I, E, C>
{
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; N], step: &[i32; N], out: &mut [C]) {
        let mut a = *start;
        for (x, p) in (x..).zip(out.iter_mut()) {
            // pixel k: attributes = start + k·step
            *p = self.pixel(&a, x, y);
            for i in 0..N {
                a[i] += step[i];
            }
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Shading<S>
    for Phong<'_, I, E, C>
{
    type Color = C;

    fn draw<Fb: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut Fb,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
    ) -> DrawStats {
        let normal = |t: &ShadeVertex<S>| {
            [
                t.normal.x.to_attr(),
                t.normal.y.to_attr(),
                t.normal.z.to_attr(),
            ]
        };
        if I::NEEDS_POSITION {
            let v = tri.map(|t| {
                let [nx, ny, nz] = normal(&t);
                let p = t.position;
                t.raster([
                    nx,
                    ny,
                    nz,
                    S::geo_to_attr(p.x),
                    S::geo_to_attr(p.y),
                    S::geo_to_attr(p.z),
                ])
            });
            draw_triangle(fb, depth, &v, opts, self)
        } else {
            let v = tri.map(|t| t.raster(normal(&t)));
            draw_triangle(fb, depth, &v, opts, self)
        }
    }
}
