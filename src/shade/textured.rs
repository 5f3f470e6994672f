//! Textured Gouraud shading: OpenGL's `GL_MODULATE` with
//! `GL_SEPARATE_SPECULAR_COLOR`.
//!
//! Each vertex is lit once ([`Illuminate::shade_parts`]): the **primary** colour
//! (emission + ambient + diffuse) and the **secondary** colour (specular), each
//! clamped to [0, 1] and encoded like a Gouraud vertex colour. Both are
//! interpolated across the triangle (Gouraud), the texture coordinates
//! perspective-correctly, and every pixel gets
//!
//! `out = clamp(texel × primary + secondary)`
//!
//! # Texture coordinates
//!
//! The mesh renderer interpolates, per triangle, the planes of `u/w`, `v/w` and
//! `1/w` (32-bit set-up planes, see [`crate::render`]) and divides once per
//! sub-span of [`PERSPECTIVE_SPAN`](crate::raster::PERSPECTIVE_SPAN) = 8 pixels
//! (a 32-bit reciprocal: a 256-entry seed table and one Newton step, no
//! division instruction, no 64-bit arithmetic), `u` and `v` stepping linearly
//! inside the sub-span. Sub-span `j` of a run starting at column `x` runs from
//! `x + 8j` to `x + 8j + 7` and interpolates between the divided values at
//! `x + 8j` and `x + 8j + 8` (the last end, beyond the run, has its planes
//! clamped to their vertex ranges). A triangle whose three `w` are equal (an
//! orthographic transform: `w = 1`) interpolates `u`, `v` directly, without a
//! division.
//!
//! Precision (tests in this module and `tests/texture_mapping.rs`): against an
//! `f64` evaluation of the same method (exact `u`, `v` at every sub-span end,
//! linear in between) the texture coordinates are within `2^−10` of a
//! texture... see [`TexturedGouraudShading`] for the measured bound.
//!
//! The clipping paths interpolate the payload (`u`, `v`, `w` and the colours)
//! linearly: exact in clip space at the near plane; at the set-up window's
//! edges (triangles reaching more than 512 pixels beyond the frame)
//! screen-linearly, so the cut points of such triangles carry the affine
//! texture coordinates of the cut.
//!
//! # Modulation
//!
//! The general path reads the texel through [`Texture::sample`] (any format,
//! filter and wrap), weighs it `w(t) = t + t/128` (`t` 8-bit: 0 → 0, 255 → 256)
//! and computes `(primary·w(t))/256 + secondary` on the encoder values (so any
//! [`Encoder`]: plain rounding, dithering, gamma). The fast path (`Rgb565`
//! texels, [`Filter::Nearest`], [`Wrap::Repeat`], sides of at least 2 texels,
//! [`Linear`](super::Linear) `Rgb565` output, no specular light on the
//! triangle) multiplies the 5- and 6-bit texel channels `t` by the primary
//! channel `A` (5 or 6 integer and 6 or 4 fraction bits, the Gouraud value
//! including its rounding half) as `⌊(t + 1)·A / 32⌋` (`/64` for green): a
//! white texel gives exactly the untextured Gouraud pixel, a black one 0, and
//! any other is within 1 step of the exactly rounded `t/31·p` (tested).

use super::{eye_point, raster_draw, start, unit_normal, within, Encoder, Kernel, Mode};
use super::{ModeState, ShadeVertex, Shader, VertexIn};
use crate::color::{OutputColor, Rgb};
use crate::lighting::Illuminate;
use crate::num::wide::lerp_i32;
use crate::num::Scalar;
use crate::raster::setup::{at3, bit_length};
use crate::raster::{ClampTo, DrawStats, Plane, RasterOptions, Setup, SpanShader, ATTR_FRAC};
use crate::render::Lerp;
use crate::target::{DepthBuffer, Framebuffer};
use crate::texture::{Filter, TexCoord, Texels, Texture, Wrap, TEX_FRAC};

/// Textured Gouraud shading (`GL_MODULATE`, `GL_SEPARATE_SPECULAR_COLOR`):
/// lit per vertex in a primary and a secondary colour, both interpolated, and
/// per pixel `texel × primary + secondary` (see the [module docs](self)).
///
/// A shader of this mode samples the white 1 × 1 texture until
/// [`Shader::with_texture`] gives it one. Mesh renderer:
/// [`Kernel::NEEDS_TEXCOORD`] (the mesh's `texcoords`, Q12); per triangle:
/// [`Shader::draw_textured`] with [`TexturedVertex`]es.
///
/// Measured texture-coordinate error of the mesh renderer's perspective path
/// against an `f64` evaluation of the same method (a plane receding in depth,
/// depth ratios up to 16 across a triangle, grazing angles, every sub-span
/// position): below `2^−12` of a texture plus `2^−15` of the triangle's
/// texture-coordinate extent times its depth ratio
/// (`perspective_coordinates_match_the_f64_method`).
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::raster::SUBPIXEL_BITS;
/// use fixshade::shade::{TexturedGouraudShading, TexturedVertex};
/// use fixshade::texture::{Filter, TexCoord, Texels, Texture, Wrap};
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
///
/// static CHECKER: [u16; 4] = [0xFFFF, 0x0000, 0x0000, 0xFFFF];
/// let tex = Texture::new(Texels::Rgb565(&CHECKER), 1, 1, Wrap::Repeat).unwrap();
/// let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
/// let mat = Material::new(&MaterialDesc::classic([1.0, 1.0, 1.0], AmbientSource::Object, 0.0, 1.0, 0.0, 1.0)).unwrap();
/// let lighting = Lighting::<Q14, _, Lambert>::new(light, mat);
/// let mut shader = Shader::<_, _, _, Rgb565>::new(TexturedGouraudShading, &lighting, Linear)
///     .with_texture(tex, Filter::Nearest);
/// let v = |x: i32, y: i32, u: f32, w: f32| TexturedVertex::new(
///     ShadeVertex::new([x << SUBPIXEL_BITS, y << SUBPIXEL_BITS], 0, 1, [0.0; 3], [0.0, 0.0, 1.0]),
///     TexCoord::from_f32(u, w));
/// let tri = [v(0, 0, 0.0, 0.0), v(0, 16, 0.0, 1.0), v(16, 0, 1.0, 0.0)];
/// let mut pixels = [Rgb565::BLACK; 16 * 16];
/// let mut fb = SliceFramebuffer::new(&mut pixels, 16, 16).unwrap();
/// shader.draw_textured(&mut fb, None, &tri, &RasterOptions::default(), false)?;
/// assert_eq!(fb.get(1, 1), Some(Rgb565::WHITE)); // texel (0, 0), fully lit
/// assert_eq!(fb.get(9, 1), Some(Rgb565::BLACK)); // texel (1, 0)
/// # Ok::<(), core::convert::Infallible>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexturedGouraudShading;

impl Mode for TexturedGouraudShading {
    const NAME: &'static str = "tex_gouraud";
}

/// The texture and filter a [`TexturedGouraudShading`] shader samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureBinding {
    texture: Texture<'static>,
    filter: Filter,
}

impl<I: Illuminate, C> ModeState<I, C> for TexturedGouraudShading {
    type State = TextureBinding;
    fn state(_: &I) -> TextureBinding {
        TextureBinding {
            texture: Texture::WHITE,
            filter: Filter::Nearest,
        }
    }
}

/// One vertex of a textured triangle for the per-triangle API: the shading
/// vertex and its texture coordinates (Q16, see [`TexCoord`]; coordinates
/// beyond ±32 textures are clamped to ±32).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturedVertex<S: Scalar> {
    /// Screen position, depth, `1/w`, eye-space position and normal.
    pub vertex: ShadeVertex<S>,
    /// Texture coordinates.
    pub uv: TexCoord,
}

impl<S: Scalar> TexturedVertex<S> {
    /// A vertex with texture coordinates `uv`.
    pub fn new(vertex: ShadeVertex<S>, uv: TexCoord) -> Self {
        Self { vertex, uv }
    }
}

/// What the vertex cache holds per vertex for [`TexturedGouraudShading`]: the
/// encoded primary colour (without the encoder's rounding offset), the encoded
/// secondary colour, the texture coordinates (Q12) and the clip `w` (20 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TexPayload {
    prim: [u16; 3],
    spec: [u16; 3],
    uv: [i16; 2],
    w: i32,
}

/// Interpolated linearly by the clipping paths: exact in clip space (near
/// plane), screen-linear at the set-up window's edges (see the
/// [module docs](self)).
impl Lerp for TexPayload {
    fn lerp(&self, o: &Self, num: u32, den: u32) -> Self {
        let l = |a: i32, b: i32| lerp_i32(a, b, num, den);
        TexPayload {
            prim: core::array::from_fn(|i| {
                l(i32::from(self.prim[i]), i32::from(o.prim[i])).clamp(0, 0x7FFF) as u16
            }),
            spec: core::array::from_fn(|i| {
                l(i32::from(self.spec[i]), i32::from(o.spec[i])).clamp(0, 0x7FFF) as u16
            }),
            uv: core::array::from_fn(|i| {
                l(i32::from(self.uv[i]), i32::from(o.uv[i])).clamp(-32768, 32767) as i16
            }),
            w: l(self.w, o.w).max(1),
        }
    }
}

/// `2^31 / ((256 + i)·128 + 64)` rounded: the reciprocal seed of `q` in
/// `[2^15, 2^16)` by its top 9 bits (relative error below 2^−9).
const RECIP: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let d = ((256 + i as u64) << 7) + 64;
        t[i] = (((1u64 << 31) + d / 2) / d) as u16;
        i += 1;
    }
    t
};

/// `≈ 2^31 / q` for `q` in `[2^15, 2^16)`: the seed and one Newton step
/// (relative error about 2^−16; 32-bit products only).
#[inline(always)]
fn recip16(q: u32) -> u32 {
    let i = ((q >> 7).wrapping_sub(256) as usize).min(255);
    let r0 = u32::from(RECIP[i]);
    // q·r0 ≈ 2^31 within 2^22; d·r0/2^31 is the Newton correction
    let d = (1u32 << 31).wrapping_sub(q.wrapping_mul(r0)) as i32;
    (r0 as i32).wrapping_add(((d >> 7).wrapping_mul(r0 as i32)) >> 24) as u32
}

/// `(r, m)` with `1/q ≈ r·2^(m − 44)` for `q ≥ 1` (`q` is normalised to
/// `[2^28, 2^29)` by `m` doublings, `r ≈ 2^31 / (q·2^m / 2^13)`).
#[inline(always)]
fn recip(q: i32) -> (u32, i32) {
    let mut qs = q.max(1) as u32;
    let mut m = 0i32;
    while qs >= 1 << 29 {
        qs >>= 1;
        m -= 1;
    }
    if qs < 1 << 28 {
        if qs < 1 << 13 {
            qs <<= 16;
            m += 16;
        }
        if qs < 1 << 21 {
            qs <<= 8;
            m += 8;
        }
        if qs < 1 << 25 {
            qs <<= 4;
            m += 4;
        }
        if qs < 1 << 27 {
            qs <<= 2;
            m += 2;
        }
        if qs < 1 << 28 {
            qs <<= 1;
            m += 1;
        }
    }
    (recip16(qs >> 13), m)
}

/// `x·2^e` (wrapping for large `e`, arithmetic right shift for negative `e`).
#[inline(always)]
fn shift(x: i32, e: i32) -> i32 {
    if e >= 0 {
        if e > 31 {
            0
        } else {
            x << e
        }
    } else if e < -31 {
        x >> 31
    } else {
        x >> (-e)
    }
}

/// A plane value (in `2^ATTR_FRAC` units of `attribute >> sa`, the attribute a
/// Q12 texture coordinate) in Q24.
#[inline(always)]
fn q12_plane_to_q24(v: i32, sa: u32) -> i32 {
    shift(v, sa as i32 + 12 - ATTR_FRAC as i32)
}

/// A textured triangle in the mesh renderer.
#[derive(Clone, Copy, Debug)]
pub struct TexturedTriangle {
    prim: [Plane; 3],
    /// Top vertex primary values (without the rounding offset), ATTR_FRAC bits.
    pbase: [i32; 3],
    spec: [Plane; 3],
    /// Top vertex secondary values (with the encoder's offset), ATTR_FRAC bits.
    sbase: [i32; 3],
    /// Whether the secondary colour varies or differs from black.
    has_spec: bool,
    /// Affine: the planes of `u`, `v` (Q12, relative to the top vertex);
    /// perspective: of `u·q`, `v·q`.
    pu: Plane,
    pv: Plane,
    /// Perspective: the plane of `q = 1/w` (relative) and the top vertex's
    /// `q` with ATTR_FRAC bits.
    pq: Plane,
    qbase: i32,
    persp: bool,
    /// Perspective: `u·q` and `v·q` plane values are shifted right by `ta`
    /// before the multiplication by the reciprocal (below 2^15).
    ta: u32,
    /// Top vertex texture coordinates, Q24.
    u0: i32,
    v0: i32,
}

/// `q_i = 32767·w_min / w_i` (at least 1) for positive `w`: `1/w` scaled so
/// that the nearest vertex has 32767. Two 32-bit divisions.
fn inverse_w(w: [i32; 3]) -> [i32; 3] {
    let w = w.map(|v| v.max(1) as u32);
    let wmin = w[0].min(w[1]).min(w[2]);
    // keep w_min below 2^16 so that 32767·w_min fits 32 bits
    let sh = bit_length(wmin).saturating_sub(16);
    let num = (wmin >> sh) * 32767;
    w.map(|v| (num / (v >> sh).max(1)).clamp(1, 32767) as i32)
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Shader<'_, TexturedGouraudShading, I, E, C> {
    /// The shader sampling `texture` with `filter`.
    pub fn with_texture(mut self, texture: Texture<'static>, filter: Filter) -> Self {
        self.state = TextureBinding { texture, filter };
        self
    }

    /// The texture sampled.
    pub fn texture(&self) -> Texture<'static> {
        self.state.texture
    }

    /// The filter.
    pub fn filter(&self) -> Filter {
        self.state.filter
    }

    /// The encoded primary (without the encoder's rounding offset) and
    /// secondary (with it) colours of a vertex (each value below 2^15).
    pub fn vertex_parts(
        &self,
        position: &crate::vector::Point3<I::Scalar>,
        normal: crate::vector::Vec3<I::Scalar>,
    ) -> ([i32; 3], [i32; 3]) {
        let parts = self.lighting.shade_parts(position, normal, None);
        let black = self.encoder.vertex(Rgb::<I::Scalar>::BLACK);
        let p = self.encoder.vertex(parts.primary);
        let s = self.encoder.vertex(parts.secondary);
        (
            core::array::from_fn(|i| (p[i] - black[i]).clamp(0, 0x7FFF)),
            s.map(|v| v.clamp(0, 0x7FFF)),
        )
    }

    /// Whether the mesh kernel may take the 5-6-5 fast path.
    #[inline(always)]
    fn fast(&self) -> bool {
        let t = &self.state.texture;
        let (lw, lh) = t.log2_size();
        C::IS_RGB565
            && E::LINEAR
            && self.state.filter == Filter::Nearest
            && t.wrap() == Wrap::Repeat
            && lw >= 1
            && lh >= 1
            && matches!(t.texels(), Texels::Rgb565(_))
    }

    /// The general pixel: texel × primary + secondary on encoder values,
    /// clamped to the encoder's range.
    #[inline(always)]
    fn pixel(&self, p: [i32; 3], s: [i32; 3], c: TexCoord, x: i32, y: i32) -> C {
        let t = self.state.texture.sample(c, self.state.filter);
        let a = core::array::from_fn(|i| {
            let t = i32::from(t[i]);
            let w = t + (t >> 7);
            let (lo, hi) = E::safe(i);
            (p[i] >> 8)
                .wrapping_mul(w)
                .wrapping_add(s[i])
                .clamp_to(lo, hi)
        });
        self.encoder.pixel(a, x, y)
    }

    /// Draws one textured triangle (the per-triangle API): colours and texture
    /// coordinates interpolated screen-linearly, or with `perspective`
    /// perspective-correctly by
    /// [`draw_triangle_perspective`](crate::raster::draw_triangle_perspective)
    /// (colours too: exact at the ends of every 8-pixel sub-span, 64-bit
    /// arithmetic). Every pixel takes the general path of the
    /// [module docs](self). Never panics; returns the framebuffer's first
    /// error.
    pub fn draw_textured<F: Framebuffer<Color = C>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[TexturedVertex<I::Scalar>; 3],
        opts: &RasterOptions,
        perspective: bool,
    ) -> Result<DrawStats, F::Error> {
        let lim = 1 << 21;
        let v = tri.map(|t| {
            let (p, s) = self.vertex_parts(&t.vertex.position, t.vertex.normal);
            let q24 = |c: i32| c.clamp(-lim, lim) << (24 - TEX_FRAC);
            t.vertex.raster([
                p[0] << ATTR_FRAC,
                p[1] << ATTR_FRAC,
                p[2] << ATTR_FRAC,
                s[0] << ATTR_FRAC,
                s[1] << ATTR_FRAC,
                s[2] << ATTR_FRAC,
                q24(t.uv.u),
                q24(t.uv.v),
            ])
        });
        raster_draw(fb, depth, &v, opts, self, perspective)
    }

    /// The texture coordinates (Q24) of the pixels of one sub-span after
    /// another: `f(k0, len, u, du, v, dv)` for pixels `k0..k0 + len` of the
    /// run of `n` pixels from column `x`, pixel `k0 + j` at `u + j·du`.
    #[inline(always)]
    fn subspans<const CLAMP: bool>(
        t: &TexturedTriangle,
        x: i32,
        n: usize,
        mut f: impl FnMut(usize, usize, i32, i32, i32, i32),
    ) {
        let (su, du) = start::<CLAMP>(&t.pu, x, n);
        let (sv, dv) = start::<CLAMP>(&t.pv, x, n);
        if !t.persp {
            f(
                0,
                n,
                t.u0.wrapping_add(q12_plane_to_q24(su, t.pu.sa)),
                q12_plane_to_q24(du, t.pu.sa),
                t.v0.wrapping_add(q12_plane_to_q24(sv, t.pv.sa)),
                q12_plane_to_q24(dv, t.pv.sa),
            );
            return;
        }
        let (sq, dq) = start::<CLAMP>(&t.pq, x, n);
        let (mut q, mut a, mut b) = (t.qbase.wrapping_add(sq), su, sv);
        let sub = crate::raster::PERSPECTIVE_SPAN;
        let sh = sub.trailing_zeros();
        let (dq8, da8, db8) = (dq << sh, du << sh, dv << sh);
        let (mut u0, mut v0) = t.coord(q, a, b);
        let mut k0 = 0;
        while k0 < n {
            q = q.wrapping_add(dq8);
            a = a.wrapping_add(da8);
            b = b.wrapping_add(db8);
            let k1 = k0 + sub;
            let (u1, v1) = if k1 < n {
                t.coord(q, a, b)
            } else {
                // beyond the run: the planes clamped to their vertex ranges
                t.coord(
                    q.clamp_to(t.qbase.wrapping_add(t.pq.lo), t.qbase.wrapping_add(t.pq.hi)),
                    a.clamp_to(t.pu.lo, t.pu.hi),
                    b.clamp_to(t.pv.lo, t.pv.hi),
                )
            };
            let len = (n - k0).min(sub);
            f(
                k0,
                len,
                u0,
                u1.wrapping_sub(u0) >> sh,
                v0,
                v1.wrapping_sub(v0) >> sh,
            );
            (u0, v0) = (u1, v1);
            k0 = k1;
        }
    }
}

impl TexturedTriangle {
    /// The texture coordinates (Q24) at absolute `q` and plane values `a`
    /// (`u·q`) and `b` (`v·q`): one reciprocal, two products.
    #[inline(always)]
    fn coord(&self, q: i32, a: i32, b: i32) -> (i32, i32) {
        let (r, m) = recip(q);
        // u_rel (Q24) = A·2^(sa + 12)/Q = (A >> ta)·r·2^(ta + sa + m − 32)
        let e = self.ta as i32 + m - 32;
        let u = shift((a >> self.ta).wrapping_mul(r as i32), e + self.pu.sa as i32);
        let v = shift((b >> self.ta).wrapping_mul(r as i32), e + self.pv.sa as i32);
        (self.u0.wrapping_add(u), self.v0.wrapping_add(v))
    }
}

/// The per-triangle API's pixels: attributes `[primary; 3, secondary; 3, u,
/// v]` (encoder values with [`ATTR_FRAC`] bits, Q24 texture coordinates).
impl<I: Illuminate, E: Encoder<C>, C: OutputColor> SpanShader<8>
    for Shader<'_, TexturedGouraudShading, I, E, C>
{
    type Color = C;
    #[inline]
    fn shade_span(&mut self, x: i32, y: i32, start: &[i32; 8], step: &[i32; 8], out: &mut [C]) {
        let mut a = *start;
        for (x, px) in (x..).zip(out.iter_mut()) {
            let c = TexCoord {
                u: a[6] >> (24 - TEX_FRAC),
                v: a[7] >> (24 - TEX_FRAC),
            };
            *px = self.pixel([a[0], a[1], a[2]], [a[3], a[4], a[5]], c, x, y);
            for i in 0..8 {
                a[i] = a[i].wrapping_add(step[i]);
            }
        }
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, TexturedGouraudShading, I, E, C>
{
    type Color = C;
    type Vertex = TexPayload;
    type Triangle = TexturedTriangle;
    const NEEDS_POSITION: bool = I::NEEDS_POSITION;
    const NEEDS_TEXCOORD: bool = true;

    #[inline]
    fn vertex(&self, v: &VertexIn) -> TexPayload {
        let (p, s) = self.vertex_parts(
            &eye_point::<I::Scalar>(v.eye),
            unit_normal::<I::Scalar>(v.normal),
        );
        TexPayload {
            prim: p.map(|c| c as u16),
            spec: s.map(|c| c as u16),
            uv: v.uv.map(|c| c.clamp(-32768, 32767) as i16),
            w: v.w.max(1),
        }
    }

    #[inline]
    fn triangle(
        &self,
        s: &Setup,
        v: [&TexPayload; 3],
        _p: [[i32; 3]; 3],
    ) -> (TexturedTriangle, bool) {
        let top = *at3(&v, s.tmb[0]);
        let black = self.encoder.vertex(Rgb::<I::Scalar>::BLACK);
        let prim: [Plane; 3] = core::array::from_fn(|i| s.plane(v.map(|p| i32::from(p.prim[i]))));
        let spec: [Plane; 3] = core::array::from_fn(|i| s.plane(v.map(|p| i32::from(p.spec[i]))));
        let pbase = core::array::from_fn(|i| i32::from(top.prim[i]) << ATTR_FRAC);
        let sbase = core::array::from_fn(|i| i32::from(top.spec[i]) << ATTR_FRAC);
        let has_spec = v
            .iter()
            .any(|p| (0..3).any(|i| i32::from(p.spec[i]) != black[i]));
        let mut clamp = (0..3).any(|i| {
            !within(s, &prim[i], pbase[i] + (black[i] << ATTR_FRAC), E::safe(i))
                || !within(s, &spec[i], sbase[i], E::safe(i))
        });
        let uv = |k: usize| v.map(|p| i32::from(p.uv[k]) - i32::from(top.uv[k]));
        let w = v.map(|p| p.w.max(1));
        let persp = !(w[0] == w[1] && w[1] == w[2]);
        let (pu, pv, pq, qbase, ta) = if persp {
            let q = inverse_w(w);
            let pq = s.plane(q);
            let qbase = at3(&q, s.tmb[0]) << ATTR_FRAC;
            // |uv_rel| ≤ 65535, q ≤ 32767: products below 2^31
            let (u, vv) = (uv(0), uv(1));
            let pu = s.plane(core::array::from_fn(|i| u[i] * q[i]));
            let pv = s.plane(core::array::from_fn(|i| vv[i] * q[i]));
            clamp = clamp || !within(s, &pq, qbase, (1 << ATTR_FRAC, (1 << 29) - 1));
            // the largest |u·q|, |v·q| plane value inside the triangle
            let big = [pu.lo, pu.hi, pv.lo, pv.hi]
                .iter()
                .fold(0u32, |m, x| m.max(x.unsigned_abs()))
                .saturating_add(s.err(&pu).max(s.err(&pv)));
            let ta = bit_length(big).saturating_sub(15);
            (pu, pv, pq, qbase, ta)
        } else {
            (s.plane(uv(0)), s.plane(uv(1)), Plane::default(), 0, 0)
        };
        (
            TexturedTriangle {
                prim,
                pbase,
                spec,
                sbase,
                has_spec,
                pu,
                pv,
                pq,
                qbase,
                persp,
                ta,
                u0: i32::from(top.uv[0]) << 12,
                v0: i32::from(top.uv[1]) << 12,
            },
            clamp,
        )
    }

    #[inline]
    fn skip_rows(t: &mut TexturedTriangle, rows: i32) {
        for p in t.prim.iter_mut().chain(t.spec.iter_mut()) {
            p.skip_rows(rows);
        }
        t.pu.skip_rows(rows);
        t.pv.skip_rows(rows);
        t.pq.skip_rows(rows);
    }

    #[inline(always)]
    fn next_row(t: &mut TexturedTriangle) {
        for p in t.prim.iter_mut() {
            p.next_row();
        }
        if t.has_spec {
            for p in t.spec.iter_mut() {
                p.next_row();
            }
        }
        t.pu.next_row();
        t.pv.next_row();
        t.pq.next_row();
    }

    #[inline(always)]
    fn shade<const CLAMP: bool>(&self, t: &TexturedTriangle, x: i32, y: i32, color: &mut [C]) {
        let n = color.len();
        let mut a = [0i32; 3];
        let mut d = [0i32; 3];
        for i in 0..3 {
            let (s, st) = start::<CLAMP>(&t.prim[i], x, n);
            a[i] = t.pbase[i].wrapping_add(s);
            d[i] = st;
        }
        if !t.has_spec && self.fast() {
            if let Texels::Rgb565(words) = self.state.texture.texels() {
                let black = self.encoder.vertex(Rgb::<I::Scalar>::BLACK);
                let (lw, lh) = self.state.texture.log2_size();
                for i in 0..3 {
                    a[i] = a[i].wrapping_add(black[i] << ATTR_FRAC);
                }
                // the Gouraud kernel's packed accumulators (see `fill565`)
                let sh = ATTR_FRAC - 1;
                let half = 1 << (sh - 1);
                let rb = (((a[0] >> sh) as u32) << 16) | (a[2] >> sh) as u32;
                let drb = (((d[0] + half) >> sh) as u32)
                    .wrapping_shl(16)
                    .wrapping_add(((d[2] + half) >> sh) as u32);
                let (g, dg) = (a[1] as u32, d[1] as u32);
                Self::subspans::<CLAMP>(t, x, n, |k0, len, u, du, v, dv| {
                    let k = k0 as u32;
                    if let Some(out) = color.get_mut(k0..k0 + len) {
                        fill_tex565(
                            words,
                            (u32::from(lw), u32::from(lh)),
                            [(u as u32) << 8, (du as u32) << 8],
                            [(v as u32) << 8, (dv as u32) << 8],
                            [rb.wrapping_add(drb.wrapping_mul(k)), drb],
                            [g.wrapping_add(dg.wrapping_mul(k)), dg],
                            out,
                        );
                    }
                });
                return;
            }
        }
        let mut sa = [0i32; 3];
        let mut sd = [0i32; 3];
        for i in 0..3 {
            let (s, st) = start::<CLAMP>(&t.spec[i], x, n);
            sa[i] = t.sbase[i].wrapping_add(s);
            sd[i] = if t.has_spec { st } else { 0 };
        }
        Self::subspans::<CLAMP>(t, x, n, |k0, len, u, du, v, dv| {
            let k = k0 as i32;
            let mut p: [i32; 3] = core::array::from_fn(|i| a[i].wrapping_add(d[i].wrapping_mul(k)));
            let mut s: [i32; 3] =
                core::array::from_fn(|i| sa[i].wrapping_add(sd[i].wrapping_mul(k)));
            let (mut u, mut v) = (u, v);
            let mut px = x + k;
            if let Some(out) = color.get_mut(k0..k0 + len) {
                for c in out.iter_mut() {
                    let tc = TexCoord {
                        u: u >> (24 - TEX_FRAC),
                        v: v >> (24 - TEX_FRAC),
                    };
                    *c = self.pixel(p, s, tc, px, y);
                    for i in 0..3 {
                        p[i] = p[i].wrapping_add(d[i]);
                        s[i] = s[i].wrapping_add(sd[i]);
                    }
                    u = u.wrapping_add(du);
                    v = v.wrapping_add(dv);
                    px += 1;
                    super::no_unroll();
                }
            }
        });
    }
}

/// The fast path's loop (see the [module docs](self)): `Rgb565` texels at Q32
/// coordinates `u`, `v` (`[value, step]`; a whole texture is 2^32, so the
/// wrapping addition is [`Wrap::Repeat`]), the Gouraud channels packed as in
/// the Gouraud kernel (red and blue in `rb`, 16 bits each with 11 fraction
/// bits; green in `g` with 23), modulated as `⌊(t + 1)·A / 2^k⌋`.
#[inline(never)]
fn fill_tex565<C: OutputColor>(
    words: &[u16],
    (lw, lh): (u32, u32),
    [mut u, du]: [u32; 2],
    [mut v, dv]: [u32; 2],
    [mut rb, drb]: [u32; 2],
    [mut g, dg]: [u32; 2],
    out: &mut [C],
) {
    // sides of at least 2 texels: shifts below 32
    let (su, sv) = (32 - lw.max(1), 32 - lh.max(1));
    for c in out.iter_mut() {
        let i = (((v >> sv) << lw) | (u >> su)) as usize;
        let t = u32::from(words.get(i).copied().unwrap_or(0));
        // (t + 1)·A < 2^16 for every channel: the result's top bits are the channel
        let r = (((t >> 11) + 1) * (rb >> 21)) & 0xF800;
        let gr = (((((t >> 5) & 63) + 1) * (g >> 19)) >> 5) & 0x07E0;
        let b = (((t & 31) + 1) * ((rb << 16) >> 21)) >> 11;
        *c = C::from_rgb565_raw((r | gr | b) as u16);
        // the values after the last pixel are not used: wrapping is harmless
        u = u.wrapping_add(du);
        v = v.wrapping_add(dv);
        rb = rb.wrapping_add(drb);
        g = g.wrapping_add(dg);
        super::no_unroll();
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Shader<'_, TexturedGouraudShading, I, E, C> {
    /// Shades one span of `out.len()` pixels through the mesh kernel, the
    /// attributes going from `v0` at its first pixel to `v1` at pixel
    /// `max(len, out.len())` (a triangle set up for it; for instruction
    /// counts).
    #[doc(hidden)]
    pub fn shade_ramp(&self, v0: &VertexIn, v1: &VertexIn, len: u32, out: &mut [C]) {
        let len = (len.max(out.len() as u32).clamp(1, 1024)) as i32;
        let (p0, p1) = (self.vertex(v0), self.vertex(v1));
        let half = 1 << (crate::raster::SUBPIXEL_BITS - 1);
        let sub = 1 << crate::raster::SUBPIXEL_BITS;
        let Some(mut s) = Setup::new(
            [
                (half, half),
                (half, half + sub * len),
                (half + sub * len, half),
            ],
            crate::raster::Cull::None,
        ) else {
            return;
        };
        s.prepare_planes();
        let pay = [p0, p0, p1];
        let o = s.order.map(|i| at3(&pay, i));
        let (t, _) = self.triangle(&s, o.each_ref(), [[0; 3]; 3]);
        self.shade::<false>(&t, 0, 0, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recip_is_within_2_pow_minus_15() {
        let mut q = 1u32;
        while q < 1 << 29 {
            for d in [0u32, 1, 7, 255, 4097] {
                let x = (q + d.min(q)) as i32;
                let (r, m) = recip(x);
                let got = f64::from(r) * 2f64.powi(m - 44);
                let want = 1.0 / f64::from(x);
                assert!(
                    ((got - want) / want).abs() < 2f64.powi(-15),
                    "{x}: {got} vs {want}"
                );
            }
            q = q * 3 / 2 + 1;
        }
        for qn in (1u32 << 15)..(1 << 16) {
            let r = recip16(qn);
            let want = 2f64.powi(31) / f64::from(qn);
            assert!((f64::from(r) - want).abs() <= 2.0, "{qn}: {r} vs {want}");
        }
    }

    #[test]
    fn inverse_w_is_the_scaled_reciprocal() {
        for w in [
            [1, 1, 2],
            [100, 200, 400],
            [70000, 1 << 30, 123456],
            [5, 5, 5],
        ] {
            let q = inverse_w(w);
            let wmin = w.iter().copied().min().unwrap();
            for k in 0..3 {
                let want = 32767.0 * f64::from(wmin) / f64::from(w[k]);
                assert!((f64::from(q[k]) - want).abs() <= 1.0 + want * 1e-4, "{w:?}");
            }
        }
    }
}
