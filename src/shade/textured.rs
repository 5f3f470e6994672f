//! Textured Gouraud shading (see [`Textured`]).

use super::normal_mapped::NormalMapped;
use super::perpixel::{self, per_pixel_kernel, Features, PixelTriangle, Sources, TextureBinding};
use super::{eye_point, unit_normal, Encoder, GouraudShading, Kernel, Mode, Shader};
use super::{PhongShading, VertexIn};
use crate::color::{OutputColor, Rgb};
use crate::lighting::Illuminate;
use crate::num::ATTR_FRAC;
use crate::texture::{modulate_run, Filter, Pieces, TexCoord, Texels, Texture, Wrap, TEX_FRAC};

/// A mode with a colour texture: OpenGL's `GL_MODULATE` with
/// `GL_SEPARATE_SPECULAR_COLOR` (made by [`GouraudShading::textured`]).
///
/// Each vertex is lit once ([`Illuminate::shade_parts`]) into the **primary**
/// (emission + ambient + diffuse) and **secondary** (specular) colours, each
/// clamped to [0, 1] and encoded like a Gouraud vertex colour and interpolated;
/// every pixel gets `out = clamp(texel × primary + secondary)`. The mesh needs
/// texture coordinates ([`Kernel::NEEDS_TEXCOORD`]; Q12), interpolated like
/// every value ([`crate::raster::interp`]).
///
/// The general path reads [`Texture::sample`] (any format, filter, wrap),
/// weighs it `w(t) = t + t/128` (`t` 8-bit: 0 → 0, 255 → 256) and computes
/// `(primary·w(t))/256 + secondary` on the encoder values (any [`Encoder`]).
/// The 5-6-5 fast path (`Rgb565` texels, [`Filter::Nearest`],
/// [`Wrap::Repeat`], sides of at least 2 texels, [`Linear`](super::Linear)
/// `Rgb565` output, no specular light on the triangle) packs the coordinates
/// in 16 bits (`v` 15) per texture (`2^−16` more error, plus a drift of at
/// most `2^−17` per pixel of a 32-pixel piece) and multiplies the 5- and 6-bit
/// texel channels `t` by the Gouraud primary `A` (with its rounding half) as
/// `⌊(t + 1)·A / 32⌋` (`/64` for green): a white texel gives exactly the
/// untextured Gouraud pixel, a black one 0, any other is within 1 step of the
/// exactly rounded `t/31·p` (tested).
#[derive(Clone, Copy, Debug)]
pub struct Textured<'t, M> {
    mode: M,
    texture: Texture<'t>,
    filter: Filter,
}

/// `textured` on the modes a colour texture composes with.
macro_rules! textured {
    ($($(#[$doc:meta])* $mode:ty;)*) => {$(
        impl<'m> $mode {
            $(#[$doc])*
            pub fn textured(self, texture: Texture<'_>, filter: Filter) -> Textured<'_, Self> {
                Textured {
                    mode: self,
                    texture,
                    filter,
                }
            }
        }
    )*};
}

textured! {
    /// Gouraud shading with the colour texture `texture`, sampled with
    /// `filter` (see [`Textured`]).
    GouraudShading;
    /// Per-pixel lighting with the colour texture `texture`, sampled with
    /// `filter` (see [`Textured`]).
    PhongShading;
    /// Normal-mapped per-pixel lighting with the colour texture `texture`,
    /// sampled with `filter` (see [`Textured`]).
    NormalMapped<'m, PhongShading>;
}

impl<'t, M> Textured<'t, M> {
    /// The texture and filter.
    fn binding(self) -> TextureBinding<'t> {
        TextureBinding {
            texture: self.texture,
            filter: self.filter,
        }
    }
}

impl<'t, I, C> Mode<I, C> for Textured<'t, GouraudShading> {
    const NAME: &'static str = "textured";
    type State = TextureBinding<'t>;
    fn state(self, _: &I) -> TextureBinding<'t> {
        self.binding()
    }
}

impl<'t, I, C> Mode<I, C> for Textured<'t, PhongShading> {
    const NAME: &'static str = "textured_phong";
    type State = TextureBinding<'t>;
    fn state(self, _: &I) -> TextureBinding<'t> {
        self.binding()
    }
}

per_pixel_kernel!(['t] Textured<'t, PhongShading>, Features::TEX, [i16; 5], [i32; 8], |b| Sources {
    map: None,
    tex: Some(*b),
});

impl<'t, 'm, I, C> Mode<I, C> for Textured<'t, NormalMapped<'m, PhongShading>> {
    const NAME: &'static str = "textured_normal_mapped";
    type State = Sources<'m, 't>;
    fn state(self, _: &I) -> Sources<'m, 't> {
        Sources {
            map: Some(self.mode.map),
            tex: Some(self.binding()),
        }
    }
}

per_pixel_kernel!(['t, 'm] Textured<'t, NormalMapped<'m, PhongShading>>, Features::MAPPED_TEX, [i16; 9], [i32; 11], |s| *s);

/// What the vertex cache holds per vertex for a [`Textured`] Gouraud shader: the
/// encoded primary colour (without the encoder's rounding offset), the encoded
/// secondary colour and the texture coordinates (Q12): 16 bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TexPayload {
    prim: [u16; 3],
    spec: [u16; 3],
    uv: [i16; 2],
}

impl crate::num::Zeroed for TexPayload {
    const ZERO: Self = TexPayload {
        prim: [0; 3],
        spec: [0; 3],
        uv: [0; 2],
    };
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
        TextureBinding::parts(
            &self.encoder,
            self.lighting.shade_parts(position, normal, None),
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

    /// The texture coordinates.
    #[inline(always)]
    fn exact(&self, i: usize) -> bool {
        i >= 6
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
                modulate_run(words, (lw, lh), coords, c, color);
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
                *c = self
                    .state
                    .pixel(&self.encoder, prim.get(), spec.get(), tc, px, y);
                prim.step();
                spec.step();
                u = u.wrapping_add(du);
                v = v.wrapping_add(dv);
                px += 1;
                crate::num::no_unroll();
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
