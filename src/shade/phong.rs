//! Phong shading: normals interpolated per pixel, renormalised, lit per pixel.

use super::{
    eye_point, raster_draw, Encoder, Kernel, ModeState, PhongShading, ShadeVertex, Shader, Shading,
};
use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::raster::setup::{at3, bit_length};
use crate::raster::{DrawStats, Plane, RasterOptions, Setup, SpanShader, ATTR_FRAC, ATTR_LIMIT};
use crate::target::{DepthBuffer, Framebuffer};
use crate::vector::{Point3, Vec3};

impl<I: Illuminate, C> ModeState<I, C> for PhongShading {
    /// The per-triangle API's position origin (the first vertex) and the shift
    /// of the position attributes.
    type State = PhongOrigin<I::Scalar>;
    fn state(_: &I) -> Self::State {
        PhongOrigin {
            // the origin (zero: no soft float per frame)
            origin: crate::vector::Vec3::new(
                Default::default(),
                Default::default(),
                Default::default(),
            ),
            shift: 0,
        }
    }
}

/// Where the interpolated positions of the triangle being drawn (per-triangle
/// API) are measured from.
#[derive(Clone, Copy, Debug)]
pub struct PhongOrigin<S: Scalar> {
    origin: Point3<S>,
    shift: u32,
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor>
    Shader<'_, PhongShading, I, E, C>
{
    /// The colour of one pixel from its interpolated attributes: the normal
    /// (the tier's attribute scale) in `a[0..3]`, the position relative to the
    /// triangle's first vertex in `a[3..6]` when `N = 6`.
    #[inline(always)]
    fn pixel<const N: usize>(&self, a: &[i32; N], x: i32, y: i32) -> C {
        let n = S::normalize_interpolated(Vec3::new(
            S::from_attr(a[0]),
            S::from_attr(a[1]),
            S::from_attr(a[2]),
        ));
        let o = &self.state;
        let p = if N >= 6 {
            let g = |v: i32| S::geo_from_attr(v << o.shift);
            Vec3::new(
                S::geo_add(o.origin.x, g(a[3])),
                S::geo_add(o.origin.y, g(a[4])),
                S::geo_add(o.origin.z, g(a[5])),
            )
        } else {
            o.origin
        };
        self.encoder.encode(self.lighting.shade(&p, n), x, y)
    }

    fn draw_any<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        let normal = |t: &ShadeVertex<S>| {
            [
                t.normal.x.to_attr(),
                t.normal.y.to_attr(),
                t.normal.z.to_attr(),
            ]
        };
        if !I::NEEDS_POSITION {
            let v = tri.map(|t| t.raster(normal(&t)));
            return raster_draw(fb, depth, &v, opts, self, perspective);
        }
        // positions relative to the first vertex (any magnitude in the float
        // tiers), as Q16.16 shifted right until they fit the attribute limit
        let o = tri[0].position;
        let rel = tri.map(|t| {
            [
                S::geo_to_attr(S::geo_sub(t.position.x, o.x)),
                S::geo_to_attr(S::geo_sub(t.position.y, o.y)),
                S::geo_to_attr(S::geo_sub(t.position.z, o.z)),
            ]
        });
        let big = rel
            .iter()
            .flatten()
            .fold(0u32, |m, v| m.max(v.unsigned_abs()));
        let limit_bits = bit_length(ATTR_LIMIT as u32) - 1;
        let shift = bit_length(big).saturating_sub(limit_bits);
        self.state = PhongOrigin { origin: o, shift };
        let v = core::array::from_fn(|i| {
            let [nx, ny, nz] = normal(&tri[i]);
            let r = rel[i].map(|v| v >> shift);
            tri[i].raster([nx, ny, nz, r[0], r[1], r[2]])
        });
        raster_draw(fb, depth, &v, opts, self, perspective)
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor, const N: usize>
    SpanShader<N> for Shader<'_, PhongShading, I, E, C>
{
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; N], step: &[i32; N], out: &mut [C]) {
        let mut a = *start;
        for (x, p) in (x..).zip(out.iter_mut()) {
            // pixel k: attributes = start + k·step
            *p = self.pixel(&a, x, y);
            for i in 0..N {
                a[i] = a[i].wrapping_add(step[i]);
            }
        }
    }
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Shading<S>
    for Shader<'_, PhongShading, I, E, C>
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

/// A Phong triangle in the mesh renderer: the planes of the normal (Q14
/// vertex values) and, when the lighting needs it, of the eye-space position
/// (Q16.16, relative to the top vertex).
#[derive(Clone, Copy, Debug)]
pub struct PhongTriangle {
    n: [Plane; 3],
    n_base: [i32; 3],
    p: [Plane; 3],
    p_base: [i32; 3],
}

impl<S: Scalar, I: Illuminate<Scalar = S>, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, PhongShading, I, E, C>
{
    type Color = C;
    /// The eye-space unit normal in Q14.
    type Vertex = [i16; 3];
    type Triangle = PhongTriangle;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;

    #[inline]
    fn vertex(&self, v: &super::VertexIn) -> [i16; 3] {
        super::unit_q14(v.normal)
    }

    fn triangle(&self, s: &Setup, v: [&[i16; 3]; 3], p: [[i32; 3]; 3]) -> (PhongTriangle, bool) {
        let t = s.tmb[0];
        let n = core::array::from_fn(|i| s.plane([v[0][i], v[1][i], v[2][i]].map(i32::from)));
        let top = at3(&v, t);
        let n_base = core::array::from_fn(|i| i32::from(top[i]) << ATTR_FRAC);
        let (pp, p_base) = if I::NEEDS_POSITION {
            (
                core::array::from_fn(|i| s.plane([p[0][i], p[1][i], p[2][i]])),
                at3(&p, t),
            )
        } else {
            ([Plane::default(); 3], [0; 3])
        };
        // normals must stay within [−1, 1] in Q14 (Q28 with ATTR_FRAC bits),
        // positions anywhere the tier saturates them
        let one = 1 << (14 + ATTR_FRAC);
        let clamp = (0..3).any(|i| !super::within(s, &n[i], n_base[i], (-one, one)));
        let t = PhongTriangle {
            n,
            n_base,
            p: pp,
            p_base,
        };
        (t, clamp)
    }

    #[inline]
    fn skip_rows(t: &mut PhongTriangle, rows: i32) {
        for p in t.n.iter_mut() {
            p.skip_rows(rows);
        }
        if I::NEEDS_POSITION {
            for p in t.p.iter_mut() {
                p.skip_rows(rows);
            }
        }
    }

    #[inline(always)]
    fn next_row(t: &mut PhongTriangle) {
        for p in t.n.iter_mut() {
            p.next_row();
        }
        if I::NEEDS_POSITION {
            for p in t.p.iter_mut() {
                p.next_row();
            }
        }
    }

    #[inline(always)]
    fn shade<const CLAMP: bool>(&self, t: &PhongTriangle, x: i32, y: i32, color: &mut [C]) {
        let len = color.len();
        let mut a = [0i32; 6];
        let mut d = [0i32; 6];
        for i in 0..3 {
            let (s, st) = super::start::<CLAMP>(&t.n[i], x, len);
            a[i] = t.n_base[i].wrapping_add(s);
            d[i] = st;
            if I::NEEDS_POSITION {
                let (s, st) = super::start::<CLAMP>(&t.p[i], x, len);
                a[3 + i] = s;
                d[3 + i] = st;
            }
        }
        let psh: [u32; 3] = core::array::from_fn(|i| ATTR_FRAC - t.p[i].sa.min(ATTR_FRAC));
        for (x, c) in (x..).zip(color.iter_mut()) {
            // Q14 normal with ATTR_FRAC bits → the tier's attribute (Q26)
            let n = S::normalize_interpolated(Vec3::new(
                S::from_attr(a[0] >> 2),
                S::from_attr(a[1] >> 2),
                S::from_attr(a[2] >> 2),
            ));
            let pos = if I::NEEDS_POSITION {
                let q = |i: usize| {
                    let sh = psh[i];
                    let r = if sh == 0 {
                        a[3 + i]
                    } else {
                        ((a[3 + i] >> (sh - 1)) + 1) >> 1
                    };
                    t.p_base[i].wrapping_add(r)
                };
                eye_point::<S>([q(0), q(1), q(2)])
            } else {
                eye_point::<S>([0; 3])
            };
            *c = self.encoder.encode(self.lighting.shade(&pos, n), x, y);
            let m = if I::NEEDS_POSITION { 6 } else { 3 };
            for (a, d) in a.iter_mut().zip(d).take(m) {
                // the values after the last pixel are not used: wrapping is harmless
                *a = a.wrapping_add(d);
            }
        }
    }
}
