//! Flat shading: one colour per triangle, lit at its centroid.

use super::{
    eye_point, raster_draw, unit_normal, Encoder, FlatShading, Kernel, ModeState, ShadeVertex,
    Shader, Shading,
};
use crate::color::{OutputColor, Rgb};
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::{DrawStats, RasterOptions, Setup, SpanShader, ATTR_FRAC};
use crate::target::{DepthBuffer, Framebuffer};
use crate::vector::Vec3;

impl<I: Illuminate, C> ModeState<I, C> for FlatShading {
    type State = [i32; 3];
    fn state(_: &I) -> [i32; 3] {
        [0; 3]
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Shader<'_, FlatShading, I, E, C> {
    /// Sets the colour [`SpanShader::shade_span`] fills with (what
    /// [`Shading::draw`] does with the colour lit at the centroid).
    pub fn set_color(&mut self, color: Rgb<I::Scalar>) {
        self.state = self.encoder.vertex(color).map(|v| v << ATTR_FRAC);
    }
}

/// Fills runs with the encoded colour of the triangle being drawn.
impl<I: Illuminate, E: Encoder<C>, C: OutputColor> SpanShader<0>
    for Shader<'_, FlatShading, I, E, C>
{
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, _start: &[i32; 0], _step: &[i32; 0], out: &mut [C]) {
        if E::POSITIONAL {
            for (x, p) in (x..).zip(out.iter_mut()) {
                *p = self.encoder.pixel(self.state, x, y);
            }
        } else {
            out.fill(self.encoder.pixel(self.state, x, y));
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>
    Shader<'_, FlatShading, I, E, C>
{
    fn draw_any<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
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
        let color = self.lighting.shade(&p, n);
        self.set_color(color);
        let v = [tri[0].raster([]), tri[1].raster([]), tri[2].raster([])];
        raster_draw(fb, depth, &v, opts, self, perspective)
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Shading<S>
    for Shader<'_, FlatShading, I, E, C>
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

/// A flat triangle in the mesh renderer: its encoded colour.
#[derive(Clone, Copy, Debug)]
pub struct FlatTriangle<C> {
    /// Encoder vertex values with [`ATTR_FRAC`] bits.
    a: [i32; 3],
    /// The pixel, for encoders that do not depend on the position.
    color: C,
}

/// `⌊x / 3⌋` rounded toward zero for `|x| < 2^31`.
#[inline]
fn third(x: i32) -> i32 {
    x / 3
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor + core::fmt::Debug> Kernel
    for Shader<'_, FlatShading, I, E, C>
{
    type Color = C;
    /// The eye-space unit normal in Q14.
    type Vertex = [i16; 3];
    type Triangle = FlatTriangle<C>;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [i16; 3] {
        super::unit_q14(v.normal)
    }

    fn triangle(&self, _s: &Setup, v: [&[i16; 3]; 3], p: [[i32; 3]; 3]) -> (FlatTriangle<C>, bool) {
        // the normalised sum of the unit vertex normals (Q14, |sum| ≤ 3·2^14)
        let n =
            core::array::from_fn(|i| i32::from(v[0][i]) + i32::from(v[1][i]) + i32::from(v[2][i]));
        let pos = if I::NEEDS_POSITION {
            // centroid p0 + (d1 + d2)/3, the differences kept within ±2^30
            core::array::from_fn(|i| {
                let d = |k: usize| p[k][i].wrapping_sub(p[0][i]).clamp(-(1 << 30), 1 << 30);
                p[0][i].wrapping_add(third(d(1) + d(2)))
            })
        } else {
            [0; 3]
        };
        let c = self
            .lighting
            .shade(&eye_point::<I::Scalar>(pos), unit_normal::<I::Scalar>(n));
        let a = self.encoder.vertex(c).map(|v| v << ATTR_FRAC);
        let t = FlatTriangle {
            a,
            color: self.encoder.pixel(a, 0, 0),
        };
        // one colour: nothing is interpolated, nothing needs clamping
        (t, false)
    }

    #[inline(always)]
    fn skip_rows(_: &mut FlatTriangle<C>, _: i32) {}

    #[inline(always)]
    fn next_row(_: &mut FlatTriangle<C>) {}

    #[inline(always)]
    fn shade<const CLAMP: bool>(&self, t: &FlatTriangle<C>, x: i32, y: i32, color: &mut [C]) {
        if E::POSITIONAL {
            for (x, c) in (x..).zip(color.iter_mut()) {
                *c = self.encoder.pixel(t.a, x, y);
            }
        } else {
            color.fill(t.color);
        }
    }
}
