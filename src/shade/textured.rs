//! Textured Gouraud shading (see [`Textured`]).

use super::{eye_point, unit_normal, Encoder, GouraudShading, Kernel, Mode, ModeState, Shader};
use super::VertexIn;
use crate::color::{OutputColor, Rgb};
use crate::lighting::Illuminate;
use crate::raster::{ClampTo, ATTR_FRAC};
use crate::texture::{Filter, TexCoord, Texels, Texture, Wrap, TEX_FRAC};

/// A mode with a colour texture: OpenGL's `GL_MODULATE` with
/// `GL_SEPARATE_SPECULAR_COLOR` (made by [`GouraudShading::textured`]).
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
/// The coordinates are interpolated like every other value of a kernel
/// ([`crate::raster::interp`]): screen-linearly under an orthographic
/// projection, perspective-correctly under a perspective one (exact at every
/// 8th pixel of a run, linear in between). The 5-6-5 fast path packs them in
/// 16 bits (`v` 15) per texture: `2^−16` more, plus a drift of at most
/// `2^−17` per pixel of a 32-pixel piece.
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
/// `Shader::new(GouraudShading.textured(texture, filter), &lighting,
/// encoder)`; the mesh needs texture coordinates ([`Kernel::NEEDS_TEXCOORD`]:
/// the mesh's `texcoords`, Q12; [`MeshDraw`](crate::render::MeshDraw) says
/// when it has none).
#[derive(Clone, Copy, Debug)]
pub struct Textured<'t, M> {
    mode: M,
    texture: Texture<'t>,
    filter: Filter,
}

impl<'t, M: Mode> Mode for Textured<'t, M> {
    const NAME: &'static str = "textured";
}

impl GouraudShading {
    /// Gouraud shading with the colour texture `texture`, sampled with
    /// `filter` (see [`Textured`]).
    pub fn textured(self, texture: Texture<'_>, filter: Filter) -> Textured<'_, Self> {
        Textured {
            mode: self,
            texture,
            filter,
        }
    }
}

/// The texture and filter a [`Textured`] shader samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureBinding<'t> {
    texture: Texture<'t>,
    filter: Filter,
}

impl<'t, I: Illuminate, C> ModeState<I, C> for Textured<'t, GouraudShading> {
    type State = TextureBinding<'t>;
    fn state(self, _: &I) -> TextureBinding<'t> {
        let _ = self.mode;
        TextureBinding {
            texture: self.texture,
            filter: self.filter,
        }
    }
}

/// What the vertex cache holds per vertex for a [`Textured`] Gouraud shader: the
/// encoded primary colour (without the encoder's rounding offset), the encoded
/// secondary colour and the texture coordinates (Q12): 16 bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TexPayload {
    prim: [u16; 3],
    spec: [u16; 3],
    uv: [i16; 2],
}

/// A textured triangle: whether its secondary colour differs from black
/// anywhere (else the fast path may take it).
#[derive(Clone, Copy, Debug, Default)]
pub struct TexturedTriangle {
    has_spec: bool,
}

impl<'t, I: Illuminate, E: Encoder<C>, C: OutputColor>
    Shader<'_, Textured<'t, GouraudShading>, I, E, C>
{
    /// The texture sampled.
    pub fn texture(&self) -> Texture<'t> {
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
        position: &crate::num::Point3<I::Scalar>,
        normal: crate::num::Vec3<I::Scalar>,
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
}

/// Pixels per piece of an affine run: the packed 16-bit coordinates of the
/// fast path are re-anchored this often (their rounded steps drift by at most
/// `2^−17` of a texture per pixel).
const AFFINE_CHUNK: usize = 32;

/// The texture coordinates of a run, piece by piece: [`Pieces::next`] gives
/// `(len, u, du, v, dv)` (Q24) for the next `len` pixels (at most
/// [`AFFINE_CHUNK`]), pixel `j` of the piece at `u + j·du`.
#[derive(Clone, Copy, Debug)]
struct Pieces {
    n: usize,
    k0: usize,
    u: i32,
    du: i32,
    v: i32,
    dv: i32,
}

impl Pieces {
    /// `n` pixels from `(u, v)` stepping by `(du, dv)` (Q24).
    #[inline(always)]
    fn new(n: usize, u: i32, du: i32, v: i32, dv: i32) -> Self {
        Pieces {
            n,
            k0: 0,
            u,
            du,
            v,
            dv,
        }
    }

    /// The next piece: `(len, u, du, v, dv)`.
    #[inline(always)]
    fn next(&mut self) -> Option<(usize, i32, i32, i32, i32)> {
        let k0 = self.k0;
        if k0 >= self.n {
            return None;
        }
        let len = (self.n - k0).min(AFFINE_CHUNK);
        let r = (len, self.u, self.du, self.v, self.dv);
        // the values at the next piece's start, as if stepped
        self.u = self.u.wrapping_add(self.du.wrapping_mul(len as i32));
        self.v = self.v.wrapping_add(self.dv.wrapping_mul(len as i32));
        self.k0 = k0 + len;
        Some(r)
    }
}

impl<I: Illuminate, E: Encoder<C>, C: OutputColor> Kernel
    for Shader<'_, Textured<'_, GouraudShading>, I, E, C>
{
    type Color = C;
    type Vertex = TexPayload;
    /// The primary colour, the secondary colour (encoder values), `u`, `v`
    /// (Q12).
    type Varyings = [i32; 8];
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
        }
    }

    #[inline]
    fn triangle(
        &self,
        v: [&TexPayload; 3],
        _eye: &[[i32; 3]; 3],
    ) -> (TexturedTriangle, [[i32; 8]; 3]) {
        let black = self.encoder.vertex(Rgb::<I::Scalar>::BLACK);
        let has_spec = v
            .iter()
            .any(|p| (0..3).any(|i| i32::from(p.spec[i]) != black[i]));
        let var = v.map(|p| {
            [
                i32::from(p.prim[0]),
                i32::from(p.prim[1]),
                i32::from(p.prim[2]),
                i32::from(p.spec[0]),
                i32::from(p.spec[1]),
                i32::from(p.spec[2]),
                i32::from(p.uv[0]),
                i32::from(p.uv[1]),
            ]
        });
        (TexturedTriangle { has_spec }, var)
    }

    #[inline]
    fn safe(&self, i: usize) -> (i32, i32) {
        match i {
            // the primary colour without the encoder's offset
            0..=2 => {
                let black = self.encoder.vertex(Rgb::<I::Scalar>::BLACK);
                let (lo, hi) = E::safe(i);
                let off = black.get(i).copied().unwrap_or(0) << ATTR_FRAC;
                (lo.saturating_sub(off), hi.saturating_sub(off))
            }
            3..=5 => E::safe(i - 3),
            _ => (-(1 << 30), 1 << 30),
        }
    }

    #[inline(always)]
    fn span(
        &self,
        t: &TexturedTriangle,
        a: &[i32; 8],
        d: &[i32; 8],
        x: i32,
        y: i32,
        color: &mut [C],
    ) {
        let n = color.len();
        let mut p = [a[0], a[1], a[2]];
        let dp = [d[0], d[1], d[2]];
        // Q12 with ATTR_FRAC bits (Q26) → Q24
        let coords = Pieces::new(n, a[6] >> 2, d[6] >> 2, a[7] >> 2, d[7] >> 2);
        if !t.has_spec && self.fast() {
            if let Texels::Rgb565(words) = self.state.texture.texels() {
                let black = self.encoder.vertex(Rgb::<I::Scalar>::BLACK);
                for i in 0..3 {
                    p[i] = p[i].wrapping_add(black[i] << ATTR_FRAC);
                }
                // the Gouraud kernel's packed accumulators (see `fill565`)
                let sh = ATTR_FRAC - 1;
                let half = 1 << (sh - 1);
                let rb = (((p[0] >> sh) as u32) << 16) | (p[2] >> sh) as u32;
                let drb = (((dp[0] + half) >> sh) as u32)
                    .wrapping_shl(16)
                    .wrapping_add(((dp[2] + half) >> sh) as u32);
                let c = [rb, drb, p[1] as u32, dp[1] as u32];
                let (lw, lh) = self.state.texture.log2_size();
                match (lw, lh) {
                    (4, 4) => fast_run::<C, 4, 4, 256>(words, coords, c, color),
                    (5, 5) => fast_run::<C, 5, 5, 1024>(words, coords, c, color),
                    (6, 6) => fast_run::<C, 6, 6, 4096>(words, coords, c, color),
                    (7, 7) => fast_run::<C, 7, 7, 16384>(words, coords, c, color),
                    (8, 8) => fast_run::<C, 8, 8, 65536>(words, coords, c, color),
                    _ => fast_run_any(words, (u32::from(lw), u32::from(lh)), coords, c, color),
                }
                return;
            }
        }
        let sd = if t.has_spec {
            [d[3], d[4], d[5]]
        } else {
            [0; 3]
        };
        let packed = C::IS_RGB565 && E::LINEAR;
        let mut prim = Steps::new(p, dp, packed);
        let mut spec = Steps::new([a[3], a[4], a[5]], sd, packed);
        let mut coords = coords;
        let mut rest = color;
        let mut px = x;
        while let Some((len, mut u, du, mut v, dv)) = coords.next() {
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
    mut gen: Pieces,
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
    mut gen: Pieces,
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

/// The fast path's loop (see the [`Textured`] docs): `Rgb565` texels at the
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
