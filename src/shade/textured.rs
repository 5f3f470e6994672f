//! Textured Gouraud shading (see [`TexturedGouraudShading`]).

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

/// Textured Gouraud shading: OpenGL's `GL_MODULATE` with
/// `GL_SEPARATE_SPECULAR_COLOR`.
/// `GL_SEPARATE_SPECULAR_COLOR`.
///
/// Each vertex is lit once ([`Illuminate::shade_parts`]): the **primary** colour
/// (emission + ambient + diffuse) and the **secondary** colour (specular), each
/// clamped to [0, 1] and encoded like a Gouraud vertex colour. Both are
/// interpolated across the triangle (Gouraud), the texture coordinates
/// perspective-correctly, and every pixel gets
///
/// `out = clamp(texel × primary + secondary)`
///
/// # Texture coordinates
///
/// The mesh renderer interpolates, per triangle, the planes of `u/w`, `v/w` and
/// `1/w` (32-bit set-up planes, see [`crate::render`]) and divides once per
/// sub-span of [`PERSPECTIVE_SPAN`](crate::raster::PERSPECTIVE_SPAN) = 8 pixels
/// (a 32-bit reciprocal: a 256-entry seed table and one Newton step, no
/// division instruction, no 64-bit arithmetic), `u` and `v` stepping linearly
/// inside the sub-span. Sub-span `j` of a run starting at column `x` runs from
/// `x + 8j` to `x + 8j + 7` and interpolates between the divided values at
/// `x + 8j` and `x + 8j + 8` (the last end, beyond the run, has its planes
/// clamped to their vertex ranges). A triangle whose three `w` are equal (an
/// orthographic transform: `w = 1`) interpolates `u`, `v` directly, without a
/// division.
///
/// Precision (`perspective_coordinates_match_the_f64_method` in this module):
/// against an `f64` evaluation of the same method (the planes' values at every
/// sub-span end divided exactly, linear in between), on squares receding in
/// depth (tilts up to 85°, depth ratios up to about 20 across a triangle,
/// texture coordinates up to ±8, 22.9 million pixels), the texture coordinates
/// are within `2^−9` of a texture (largest found: `1.65·10^−3`), the error of
/// the 32-bit set-up planes (14-bit coefficients) amplified by the depth
/// ratio. Triangles whose coordinate planes carry a larger error bound
/// (slivers, tiny triangles spanning several textures) are clamped per run:
/// their coordinates stay within the vertices' range. The 5-6-5 fast path
/// packs the coordinates in 16 bits (`v` 15) per texture: `2^−16` more, plus
/// a drift of at most `2^−17` per pixel of a piece.
///
/// The clipping paths interpolate the payload (`u`, `v`, `w` and the colours)
/// linearly: exact in clip space at the near plane; at the set-up window's
/// edges (triangles reaching more than 512 pixels beyond the frame)
/// screen-linearly, so the cut points of such triangles carry the affine
/// texture coordinates of the cut.
///
/// # Modulation
///
/// The general path reads the texel through [`Texture::sample`] (any format,
/// filter and wrap), weighs it `w(t) = t + t/128` (`t` 8-bit: 0 → 0, 255 → 256)
/// and computes `(primary·w(t))/256 + secondary` on the encoder values (so any
/// [`Encoder`]: plain rounding, dithering, gamma). The fast path (`Rgb565`
/// texels, [`Filter::Nearest`], [`Wrap::Repeat`], sides of at least 2 texels,
/// [`Linear`](super::Linear) `Rgb565` output, no specular light on the
/// triangle) multiplies the 5- and 6-bit texel channels `t` by the primary
/// channel `A` (5 or 6 integer and 6 or 4 fraction bits, the Gouraud value
/// including its rounding half) as `⌊(t + 1)·A / 32⌋` (`/64` for green): a
/// white texel gives exactly the untextured Gouraud pixel, a black one 0, and
/// any other is within 1 step of the exactly rounded `t/31·p` (tested).
///
/// # Use
///
/// A shader of this mode samples the white 1 × 1 texture until
/// [`Shader::with_texture`] gives it one. Mesh renderer:
/// [`Kernel::NEEDS_TEXCOORD`] (the mesh's `texcoords`, Q12); per triangle:
/// [`Shader::draw_textured`] with [`TexturedVertex`]es.
///
/// Measured texture-coordinate error of the mesh renderer's perspective path
/// against an `f64` evaluation of the same method (squares receding in depth,
/// grazing angles, every sub-span position): below `2^−9` of a texture
/// (see *Texture coordinates* above).
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
/// [`TexturedGouraudShading`] docs).
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

#[cfg(test)]
impl TexturedGouraudShading {
    /// `Kernel::next_row` of the textured kernel (tests).
    fn next_row_of(t: &mut TexturedTriangle) {
        for p in [&mut t.pu, &mut t.pv, &mut t.pq] {
            p.next_row();
        }
    }
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
    /// The vertices' range of `u` and of `v`, Q24 (clamped runs stay in it).
    urange: (i32, i32),
    vrange: (i32, i32),
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

/// Whether a texture-coordinate plane's error bound exceeds a quarter of its
/// vertex range plus one unit (slivers, tiny triangles with large texture
/// extents): its values are then clamped per run, which keeps the coordinates
/// near the triangle's range.
#[inline]
fn rough(s: &Setup, p: &Plane) -> bool {
    let range = p.hi.wrapping_sub(p.lo) as u32;
    s.err(p) > (range >> 2).saturating_add((1 << ATTR_FRAC) >> p.sa.min(ATTR_FRAC))
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
    /// [`TexturedGouraudShading`] docs. Never panics; returns the framebuffer's first
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
}

/// Pixels per piece of an affine run: the packed 16-bit coordinates of the
/// fast path are re-anchored this often (their rounded steps drift by at most
/// `2^−17` of a texture per pixel).
const AFFINE_CHUNK: usize = 32;

/// The texture coordinates of a run, piece by piece: [`CoordGen::next`]
/// gives `(len, u, du, v, dv)` (Q24) for the next `len` pixels, pixel `j` of
/// the piece at `u + j·du` — perspective: sub-spans of 8 pixels between
/// divided ends; affine: pieces of [`AFFINE_CHUNK`] pixels.
#[derive(Clone, Copy, Debug)]
struct CoordGen<'t> {
    t: &'t TexturedTriangle,
    /// Whether the divided coordinates are clamped to the vertex range.
    clamp: bool,
    n: usize,
    k0: usize,
    /// Perspective: plane values at the current piece's start; affine: `q`
    /// unused.
    q: i32,
    a: i32,
    b: i32,
    dq: i32,
    da: i32,
    db: i32,
    /// Coordinates at the current piece's start (Q24) and, affine, the steps.
    u: i32,
    v: i32,
    du: i32,
    dv: i32,
}

impl<'t> CoordGen<'t> {
    /// The run of `n` pixels from column `x` of the current row.
    #[inline(always)]
    fn new<const CLAMP: bool>(t: &'t TexturedTriangle, x: i32, n: usize) -> Self {
        let (a, da) = start::<CLAMP>(&t.pu, x, n);
        let (b, db) = start::<CLAMP>(&t.pv, x, n);
        let mut g = CoordGen {
            t,
            clamp: CLAMP,
            n,
            k0: 0,
            q: 0,
            a,
            b,
            dq: 0,
            da,
            db,
            u: 0,
            v: 0,
            du: 0,
            dv: 0,
        };
        if t.persp {
            let (q, dq) = start::<CLAMP>(&t.pq, x, n);
            let sh = crate::raster::PERSPECTIVE_SPAN.trailing_zeros();
            g.q = t.qbase.wrapping_add(q);
            (g.dq, g.da, g.db) = (dq << sh, da << sh, db << sh);
            (g.u, g.v) = g.coord(g.q, a, b);
        } else {
            g.u = t.u0.wrapping_add(q12_plane_to_q24(a, t.pu.sa));
            g.v = t.v0.wrapping_add(q12_plane_to_q24(b, t.pv.sa));
            g.du = q12_plane_to_q24(da, t.pu.sa);
            g.dv = q12_plane_to_q24(db, t.pv.sa);
        }
        g
    }

    /// [`TexturedTriangle::coord`], clamped to the vertex range when `clamp`.
    #[inline(always)]
    fn coord(&self, q: i32, a: i32, b: i32) -> (i32, i32) {
        let (u, v) = self.t.coord(q, a, b);
        if self.clamp {
            let t = self.t;
            (
                u.clamp_to(t.urange.0, t.urange.1),
                v.clamp_to(t.vrange.0, t.vrange.1),
            )
        } else {
            (u, v)
        }
    }

    /// The next piece: `(len, u, du, v, dv)`.
    #[inline(always)]
    fn next(&mut self) -> Option<(usize, i32, i32, i32, i32)> {
        let k0 = self.k0;
        if k0 >= self.n {
            return None;
        }
        let t = self.t;
        if !t.persp {
            let len = (self.n - k0).min(AFFINE_CHUNK);
            let r = (len, self.u, self.du, self.v, self.dv);
            // the values at the next piece's start, as if stepped
            self.u = self.u.wrapping_add(self.du.wrapping_mul(len as i32));
            self.v = self.v.wrapping_add(self.dv.wrapping_mul(len as i32));
            self.k0 = k0 + len;
            return Some(r);
        }
        let sub = crate::raster::PERSPECTIVE_SPAN;
        let sh = sub.trailing_zeros();
        self.q = self.q.wrapping_add(self.dq);
        self.a = self.a.wrapping_add(self.da);
        self.b = self.b.wrapping_add(self.db);
        let k1 = k0 + sub;
        let (u1, v1) = if k1 < self.n {
            self.coord(self.q, self.a, self.b)
        } else {
            // beyond the run: the planes clamped to their vertex ranges
            self.coord(
                self.q
                    .clamp_to(t.qbase.wrapping_add(t.pq.lo), t.qbase.wrapping_add(t.pq.hi)),
                self.a.clamp_to(t.pu.lo, t.pu.hi),
                self.b.clamp_to(t.pv.lo, t.pv.hi),
            )
        };
        let r = (
            (self.n - k0).min(sub),
            self.u,
            u1.wrapping_sub(self.u) >> sh,
            self.v,
            v1.wrapping_sub(self.v) >> sh,
        );
        (self.u, self.v) = (u1, v1);
        self.k0 = k1;
        Some(r)
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
        let range = |k: usize| {
            let c = v.map(|p| i32::from(p.uv[k]) << 12);
            (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]))
        };
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
            // q: the bound beyond 2^−12 of the farthest vertex's q
            let qmin = q[0].min(q[1]).min(q[2]) as u32;
            clamp =
                clamp || s.err(&pq) > (qmin << ATTR_FRAC) >> 12 || rough(s, &pu) || rough(s, &pv);
            (pu, pv, pq, qbase, ta)
        } else {
            let (pu, pv) = (s.plane(uv(0)), s.plane(uv(1)));
            clamp = clamp || rough(s, &pu) || rough(s, &pv);
            (pu, pv, Plane::default(), 0, 0)
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
                urange: range(0),
                vrange: range(1),
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
                let c = [rb, drb, a[1] as u32, d[1] as u32];
                let gen = CoordGen::new::<CLAMP>(t, x, n);
                let (lw, lh) = self.state.texture.log2_size();
                match (lw, lh) {
                    (4, 4) => fast_run::<C, 4, 4, 256>(words, gen, c, color),
                    (5, 5) => fast_run::<C, 5, 5, 1024>(words, gen, c, color),
                    (6, 6) => fast_run::<C, 6, 6, 4096>(words, gen, c, color),
                    (7, 7) => fast_run::<C, 7, 7, 16384>(words, gen, c, color),
                    (8, 8) => fast_run::<C, 8, 8, 65536>(words, gen, c, color),
                    _ => fast_run_any(words, (u32::from(lw), u32::from(lh)), gen, c, color),
                }
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
        let packed = C::IS_RGB565 && E::LINEAR;
        let mut prim = Steps::new(a, d, packed);
        let mut spec = Steps::new(sa, sd, packed);
        let mut gen = CoordGen::new::<CLAMP>(t, x, n);
        let mut rest = color;
        let mut px = x;
        while let Some((len, mut u, du, mut v, dv)) = gen.next() {
            let (part, tail) = rest.split_at_mut(len.min(rest.len()));
            for c in part.iter_mut() {
                let tc = TexCoord {
                    u: u >> (24 - TEX_FRAC),
                    v: v >> (24 - TEX_FRAC),
                };
                *c = self.pixel(prim.get(), spec.get(), tc, px, y);
                prim.step();
                spec.step();
                u = u.wrapping_add(du);
                v = v.wrapping_add(dv);
                px += 1;
                super::no_unroll();
            }
            rest = tail;
        }
    }
}

/// Encoder values stepped along a run: three channels, or (`packed`, linear
/// 5-6-5 output) red and blue packed as the Gouraud kernel steps them
/// (`fill565`), so that a white texture gives its pixels bit for bit.
#[derive(Clone, Copy, Debug)]
struct Steps {
    a: [i32; 3],
    d: [i32; 3],
    packed: bool,
    rb: u32,
    drb: u32,
}

impl Steps {
    #[inline(always)]
    fn new(a: [i32; 3], d: [i32; 3], packed: bool) -> Self {
        let sh = ATTR_FRAC - 1;
        let half = 1 << (sh - 1);
        Steps {
            a,
            d,
            packed,
            rb: (((a[0] >> sh) as u32) << 16) | ((a[2] >> sh) as u32 & 0xFFFF),
            drb: (((d[0].wrapping_add(half)) >> sh) as u32)
                .wrapping_shl(16)
                .wrapping_add(((d[2].wrapping_add(half)) >> sh) as u32),
        }
    }

    #[inline(always)]
    fn get(&self) -> [i32; 3] {
        if self.packed {
            let sh = ATTR_FRAC - 1;
            [
                ((self.rb >> 16) << sh) as i32,
                self.a[1],
                ((self.rb & 0xFFFF) << sh) as i32,
            ]
        } else {
            self.a
        }
    }

    #[inline(always)]
    fn step(&mut self) {
        for i in 0..3 {
            self.a[i] = self.a[i].wrapping_add(self.d[i]);
        }
        self.rb = self.rb.wrapping_add(self.drb);
    }
}

/// Q24 coordinates and steps packed for the fast path: `v` in the top 15
/// bits (2^15 per texture), a guard bit, `u` in the low 16 bits (2^16 per
/// texture). The guard bit takes `u`'s carry (or borrow, for a negative
/// step: then it starts set) when `u` wraps once within a piece, so that `v`
/// is not disturbed.
#[inline(always)]
fn pack(u: i32, du: i32, v: i32, dv: i32) -> (u32, u32) {
    let u16 = ((u >> 8) as u32) & 0xFFFF;
    let v15 = ((v >> 9) as u32) << 17;
    let guard = if du < 0 { 1 << 16 } else { 0 };
    // steps rounded to nearest
    let du16 = (du.wrapping_add(128) >> 8) as u32;
    let dv15 = ((dv.wrapping_add(256) >> 9) as u32) << 17;
    (v15 | guard | u16, dv15.wrapping_add(du16))
}

/// The 5-6-5 fast path for a `2^LW × 2^LH` texture of `N` texels (see
/// [`fill_tex565`]).
#[inline(never)]
fn fast_run<C: OutputColor, const LW: u32, const LH: u32, const N: usize>(
    words: &[u16],
    mut gen: CoordGen<'_>,
    mut c: [u32; 4],
    color: &mut [C],
) {
    let Ok(words) = <&[u16; N]>::try_from(words) else {
        return;
    };
    let mut rest = color;
    while let Some((len, u, du, v, dv)) = gen.next() {
        let uv = pack(u, du, v, dv);
        let (part, tail) = rest.split_at_mut(len.min(rest.len()));
        tex565_const::<C, LW, LH, N>(words, uv, &mut c, part);
        rest = tail;
    }
}

/// [`fill_tex565`] for constant sizes: the index is provably in the array.
#[inline(never)]
fn tex565_const<C: OutputColor, const LW: u32, const LH: u32, const N: usize>(
    words: &[u16; N],
    uv: (u32, u32),
    c: &mut [u32; 4],
    out: &mut [C],
) {
    let [rb, drb, g, dg] = *c;
    let (rb, g) = fill_tex565::<C>(
        words.as_slice(),
        (LW, LH),
        [uv.0, uv.1],
        [rb, drb],
        [g, dg],
        out,
    );
    c[0] = rb;
    c[2] = g;
}

/// [`fast_run`] for any texture size (run-time shifts).
#[inline(never)]
fn fast_run_any<C: OutputColor>(
    words: &[u16],
    size: (u32, u32),
    mut gen: CoordGen<'_>,
    c: [u32; 4],
    color: &mut [C],
) {
    let [mut rb, drb, mut g, dg] = c;
    let (lw, lh) = (size.0.clamp(1, 15), size.1.clamp(1, 15));
    let mut rest = color;
    while let Some((len, u, du, v, dv)) = gen.next() {
        let (uv, duv) = pack(u, du, v, dv);
        let (part, tail) = rest.split_at_mut(len.min(rest.len()));
        (rb, g) = fill_tex565(words, (lw, lh), [uv, duv], [rb, drb], [g, dg], part);
        rest = tail;
    }
}

/// The fast path's loop (see the [`TexturedGouraudShading`] docs): `Rgb565` texels at the
/// packed coordinates `uv` (see [`pack`]; the wrapping addition is
/// [`Wrap::Repeat`]), the Gouraud channels packed as in the Gouraud kernel
/// (red and blue in `rb`, 16 bits each with 11 fraction bits; green in `g`
/// with 23), modulated as `⌊(t + 1)·A / 2^k⌋`; `lw`, `lh` (1 to 15): the
/// texture's `log2` sides. Returns `rb`, `g` after the last pixel.
#[inline(always)]
fn fill_tex565<C: OutputColor>(
    words: &[u16],
    (lw, lh): (u32, u32),
    [mut uv, duv]: [u32; 2],
    [mut rb, drb]: [u32; 2],
    [mut g, dg]: [u32; 2],
    out: &mut [C],
) -> (u32, u32) {
    for c in out.iter_mut() {
        let col = (uv << 16) >> (32 - lw);
        let row = uv >> (32 - lh);
        let t = u32::from(
            words
                .get(((row << lw) | col) as usize)
                .copied()
                .unwrap_or(0),
        );
        // (t + 1)·A < 2^16 for every channel: the product's top bits are the
        // channel (shift pairs instead of masks: no constants to hold)
        let r = ((((t >> 11) + 1) * (rb >> 21)) >> 11) << 11;
        let gr = (((((t << 21) >> 26) + 1) * (g >> 19)) >> 10) << 5;
        let b = ((((t << 27) >> 27) + 1) * ((rb << 16) >> 21)) >> 11;
        *c = C::from_rgb565_raw((r | gr | b) as u16);
        // the values after the last pixel are not used: wrapping is harmless
        uv = uv.wrapping_add(duv);
        rb = rb.wrapping_add(drb);
        g = g.wrapping_add(dg);
        super::no_unroll();
    }
    (rb, g)
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

    use crate::light::DirectionalLight;
    use crate::lighting::{Lambert, Lighting};
    use crate::material::{Material, MaterialDesc};
    use crate::num::Q14;
    use crate::raster::Cull;
    use crate::shade::Linear;
    use embedded_graphics_core::pixelcolor::Rgb565;

    fn lcg(seed: &mut u64) -> u32 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 33) as u32
    }

    /// Per-pixel texture coordinates of one triangle through the mesh kernel's
    /// generator, and the f64 reference of the same method: `(max |Δu|, max
    /// |Δv|)` in textures and the pixel count.
    fn coord_error(
        pts: [(i32, i32); 3],
        uv: [[i16; 2]; 3],
        w: [i32; 3],
    ) -> (f64, f64, usize, bool) {
        let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
        let lit = Lighting::<Q14, _, Lambert>::new(
            light,
            Material::new(&MaterialDesc::default()).unwrap(),
        );
        let sh = Shader::<_, _, _, Rgb565>::new(TexturedGouraudShading, &lit, Linear);
        let Some(mut s) = Setup::new(pts, Cull::None) else {
            return (0.0, 0.0, 0, false);
        };
        s.prepare_planes();
        let black: [i32; 3] = Encoder::<Rgb565>::vertex(&Linear, crate::color::Rgb::<Q14>::BLACK);
        let pay = [0, 1, 2].map(|k| TexPayload {
            prim: [0; 3],
            spec: black.map(|c| c as u16),
            uv: uv[k],
            w: w[k],
        });
        let o = s.order.map(|i| at3(&pay, i));
        let (mut t, clamp) = sh.triangle(&s, o.each_ref(), [[0; 3]; 3]);
        // the reference: q_i = 1/w_i (relative scale irrelevant), planes of q,
        // u·q, v·q through the oriented vertices, in f64
        let xy =
            s.xy.map(|(x, y)| (f64::from(x) / 16.0, f64::from(y) / 16.0));
        let ow = s.order.map(|i| f64::from(w[i].max(1)));
        let ouv = s.order.map(|i| uv[i].map(|c| f64::from(c) / 4096.0));
        // u·q and v·q are relative to the top vertex (as the kernel's planes)
        let top = ouv[s.tmb[0]];
        let ouv = ouv.map(|c| [c[0] - top[0], c[1] - top[1]]);
        let area =
            (xy[1].0 - xy[0].0) * (xy[2].1 - xy[0].1) - (xy[1].1 - xy[0].1) * (xy[2].0 - xy[0].0);
        let bary = |px: f64, py: f64| {
            let e =
                |a: (f64, f64), b: (f64, f64)| (b.0 - a.0) * (py - a.1) - (b.1 - a.1) * (px - a.0);
            [
                e(xy[1], xy[2]) / area,
                e(xy[2], xy[0]) / area,
                e(xy[0], xy[1]) / area,
            ]
        };
        let wmin = ow.iter().copied().fold(f64::MAX, f64::min);
        let q = ow.map(|w| wmin / w);
        let aq = |k: usize| [0, 1, 2].map(|i| ouv[i][k] * q[i]);
        let (au, av) = (aq(0), aq(1));
        let range = |a: [f64; 3]| (a[0].min(a[1]).min(a[2]), a[0].max(a[1]).max(a[2]));
        let persp = !(w[0] == w[1] && w[1] == w[2]);
        // exact (clamped to the vertex ranges when `clamp`) coordinates at a pixel
        let exact = |px: i32, py: i32, clamp: bool| {
            let b = bary(f64::from(px) + 0.5, f64::from(py) + 0.5);
            let dot = |a: [f64; 3]| b[0] * a[0] + b[1] * a[1] + b[2] * a[2];
            if !persp {
                let (u, v) = (
                    dot([0, 1, 2].map(|i| ouv[i][0])),
                    dot([0, 1, 2].map(|i| ouv[i][1])),
                );
                return (top[0] + u, top[1] + v);
            }
            let (mut qq, mut uu, mut vv) = (dot(q), dot(au), dot(av));
            if clamp {
                let c = |x: f64, r: (f64, f64)| x.clamp(r.0, r.1);
                qq = c(qq, range(q));
                uu = c(uu, range(au));
                vv = c(vv, range(av));
            }
            (top[0] + uu / qq, top[1] + vv / qq)
        };
        let (mut eu, mut ev, mut count) = (0f64, 0f64, 0usize);
        let mut walker = s.walker(s.rows.0);
        while walker.more() {
            let y = walker.y;
            let (lo, hi) = walker.next();
            if lo <= hi {
                let n = (hi - lo + 1) as usize;
                let mut gen = if clamp {
                    CoordGen::new::<true>(&t, lo, n)
                } else {
                    CoordGen::new::<false>(&t, lo, n)
                };
                let mut k0 = 0usize;
                while let Some((len, u, du, v, dv)) = gen.next() {
                    let piece = if persp { 8 } else { AFFINE_CHUNK };
                    let x0 = lo + k0 as i32;
                    let (ua, va) = exact(x0, y, false);
                    let end = k0 + piece;
                    let (ub, vb) = if persp {
                        exact(lo + end as i32, y, end >= n)
                    } else {
                        (0.0, 0.0)
                    };
                    for j in 0..len {
                        let (ru, rv) = if persp {
                            let f = j as f64 / 8.0;
                            (ua + (ub - ua) * f, va + (vb - va) * f)
                        } else {
                            exact(x0 + j as i32, y, false)
                        };
                        let gu = f64::from(u.wrapping_add(du.wrapping_mul(j as i32)))
                            / f64::from(1 << 24);
                        let gv = f64::from(v.wrapping_add(dv.wrapping_mul(j as i32)))
                            / f64::from(1 << 24);
                        eu = eu.max((gu - ru).abs());
                        ev = ev.max((gv - rv).abs());
                        count += 1;
                    }
                    k0 += len;
                }
            }
            TexturedGouraudShading::next_row_of(&mut t);
        }
        (eu, ev, count, clamp)
    }

    /// Sub-pixel positions, uv (Q12) and clip w of a triangle.
    type TestTri = ([(i32, i32); 3], [[i16; 2]; 3], [i32; 3]);

    /// A textured square receding in depth, seen through a perspective
    /// projection (focal length 200 pixels, centre (200, 200)): its two
    /// triangles with sub-pixel positions, uv and clip w, or `None` when a
    /// corner is behind the eye or outside the set-up window.
    fn plane(
        centre: [f64; 3],
        side: f64,
        rot: f64,
        tilt: f64,
        uv: ([f64; 2], f64),
    ) -> Option<[TestTri; 2]> {
        let (c, s) = (rot.cos(), rot.sin());
        let e1 = [side * c, side * s, 0.0];
        let e2 = [
            -side * s * tilt.cos(),
            side * c * tilt.cos(),
            -side * tilt.sin(),
        ];
        let corner = |a: f64, b: f64| -> Option<((i32, i32), [i16; 2], i32)> {
            let p = [0, 1, 2].map(|k| centre[k] + (a - 0.5) * e1[k] + (b - 0.5) * e2[k]);
            let w = -p[2];
            if w < 0.5 {
                return None;
            }
            let (x, y) = (200.0 + 200.0 * p[0] / w, 200.0 - 200.0 * p[1] / w);
            let (sx, sy) = ((x * 16.0).round(), (y * 16.0).round());
            if !(-8000.0..24000.0).contains(&sx) || !(-8000.0..24000.0).contains(&sy) {
                return None;
            }
            let t = [uv.0[0] + a * uv.1, uv.0[1] + b * uv.1]
                .map(|c| (c * 4096.0).round().clamp(-32768.0, 32767.0) as i16);
            Some(((sx as i32, sy as i32), t, (w * 65536.0) as i32))
        };
        let k = [
            corner(0.0, 0.0)?,
            corner(1.0, 0.0)?,
            corner(1.0, 1.0)?,
            corner(0.0, 1.0)?,
        ];
        let tri = |i: [usize; 3]| (i.map(|j| k[j].0), i.map(|j| k[j].1), i.map(|j| k[j].2));
        Some([tri([0, 1, 2]), tri([0, 2, 3])])
    }

    #[test]
    fn perspective_coordinates_match_the_f64_method() {
        // a square receding in depth: tilts up to 85° (grazing), rotations,
        // sizes, distances (depth ratios up to about 20), uv scales up to 8
        // textures and offsets up to ±4; every pixel of every sub-span
        // (including the extrapolated ends of runs) against the f64 method
        let mut seed = 5;
        let mut worst = [0f64; 2];
        let mut pixels = 0;
        let (mut rough_tris, mut rough_worst) = (0, 0f64);
        for case in 0..4000 {
            let f = |seed: &mut u64| f64::from(lcg(seed)) / f64::from(1u32 << 31);
            let tilt = [0.0, 0.5, 1.0, 1.3, 1.45, 1.48][case % 6] + 0.02 * f(&mut seed);
            let rot = 6.3 * f(&mut seed);
            let dist = 2.0 + 20.0 * f(&mut seed);
            let side = dist * (0.05 + 1.5 * f(&mut seed));
            let centre = [
                dist * (f(&mut seed) - 0.5),
                dist * (f(&mut seed) - 0.5),
                -dist,
            ];
            let scale: f64 = [1.0, 2.0, 4.0, 7.9][(case / 6) % 4];
            let off = [8.0 * f(&mut seed) - 4.0, 8.0 * f(&mut seed) - 4.0]
                .map(|o: f64| o.min(7.99 - scale));
            let Some(tris) = plane(centre, side, rot, tilt, (off, scale)) else {
                continue;
            };
            for (pts, uv, w) in tris {
                let (eu, ev, n, clamped) = coord_error(pts, uv, w);
                if clamped {
                    // slivers: coordinates within about the triangle's extent
                    rough_tris += 1;
                    rough_worst = rough_worst.max(eu.max(ev) / scale);
                    assert!(eu.max(ev) <= scale + 1e-6, "case {case}: {eu} {ev}");
                    continue;
                }
                pixels += n;
                worst[0] = worst[0].max(eu);
                worst[1] = worst[1].max(ev);
                assert!(
                    eu.max(ev) <= BOUND,
                    "case {case}: off by {eu}, {ev} textures: {pts:?} {uv:?} {w:?}"
                );
            }
        }
        std::println!("{pixels} pixels; largest error: u {:.3e}, v {:.3e} textures; {rough_tris} clamped triangles, error / extent {rough_worst:.3}", worst[0], worst[1]);
        assert!(pixels > 1_000_000);
    }

    /// The stated bound of the perspective texture coordinates (textures).
    const BOUND: f64 = 1.0 / 512.0;

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
