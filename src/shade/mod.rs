//! Shading: which colour each covered pixel gets, from the lighting, the
//! vertex data and the interpolated values — the span kernels of the
//! pipeline, behind one trait, [`Kernel`].
//!
//! One [`Shader`] type, generic over the mode. The mode the user writes
//! names the kernel that runs, each in its own file:
//!
//! | mode | kernel (file) | lit | interpolated per pixel | catches a highlight inside a triangle |
//! |---|---|---|---|---|
//! | [`FlatShading`] | `flat.rs` | once per triangle, at the centroid | nothing | no (one colour, Mach bands) |
//! | [`GouraudShading`] | `gouraud.rs` | at the three vertices | encoded colour channels | no (misses or smears it) |
//! | [`PhongShading`] | `phong.rs` | at every pixel with the full model: every tier, light kind and model | normal (and position when the lighting needs it) | yes |
//! | [`IncrementalPhongShading`] | `incremental.rs` | at every pixel, incrementally: `Q14`, up to four directional lights, Lambert or Blinn-Phong (the Cortex-M0 fast path) | normal, `N·L`, `N·H` | yes |
//! | [`QuadraticPhongShading`] | `quadratic.rs` | exactly at anchors 4–32 pixels apart, quadratically in between, the specular power per pixel: directional lights, Lambert, Blinn-Phong or Phong `R·V`, `Q14`, `f32`, `F32Fast` | normal, `N·L`, `N·H` | yes |
//! | `GouraudShading.`[`textured`](GouraudShading::textured)`(…)`, `PhongShading.textured(…)` ([`Textured`]) | `textured.rs` | per vertex or per pixel, primary and secondary colour apart | colours or normal, texture coordinates | as the mode (`texel × primary + secondary`, OpenGL's `GL_MODULATE`) |
//! | `PhongShading.`[`normal_mapped`](PhongShading::normal_mapped)`(…)`, `IncrementalPhongShading.normal_mapped(…)` ([`NormalMapped`]) | `normal_mapped.rs` | at every pixel with the normal of a [`NormalMap`](crate::texture::NormalMap) in the tangent frame: the full model, or incrementally (`Q14`, one directional light) | normal and tangent, or `L`, `H` in tangent space; texture coordinates | yes, and surface detail |
//!
//! A mode that cannot shade a lighting does not compile with it, and nothing
//! chooses a kernel behind the user's back: each kernel is a plain `impl
//! Kernel` (the per-pixel modes share `perpixel.rs`). *What light a point
//! reflects* is the reflection model's ([`lighting`](crate::lighting)). Every
//! mode writes through an [`Encoder`] (rounding, ordered dithering or a gamma
//! table); every interpolated value is perspective-correct under a perspective
//! projection ([`crate::raster::interp`]). A shader draws meshes
//! ([`MeshDraw`](crate::render::MeshDraw)) and single triangles
//! ([`draw_triangle`](crate::render::draw_triangle)) alike.

mod flat;
mod gouraud;
mod incremental;
mod normal_mapped;
mod perpixel;
mod phong;
mod quadratic;
mod textured;

use crate::color::{Encoder, Linear};
use embedded_graphics_core::pixelcolor::Rgb565;
pub use incremental::IncrementalModel;
pub use normal_mapped::NormalMapped;
pub use quadratic::QuadraticModel;
pub use textured::Textured;

use crate::color::OutputColor;
use crate::lighting::Illuminate;
use crate::num::Scalar;
use crate::num::{Point3, Vec3};
use crate::raster::interp::Varyings;
use core::marker::PhantomData;

/// Flat shading: the triangle is lit once, at its centroid, with the normalised
/// average of its vertex normals, and filled with that colour. Shows the seeds'
/// Mach bands on curved surfaces; the cheapest mode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FlatShading;

/// Gouraud shading: each vertex is lit with its own normal, the encoded colour
/// channels are interpolated across the triangle and each pixel only reads
/// them. Misses a highlight that falls inside a large triangle and smears
/// highlights near vertices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GouraudShading;

/// Phong shading, per-pixel lighting: the interpolated vertex normal is
/// renormalised per pixel ([`Scalar::normalize_interpolated`]) and lit with the
/// full model, for every tier, light kind and model (the eye-space position is
/// interpolated too when the lighting needs it). Catches the highlight inside
/// a large triangle. For `Q14` directional lights, [`IncrementalPhongShading`]
/// gives the same pictures within the same bound, far cheaper on a Cortex-M0.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PhongShading;

/// Per-pixel Phong shading computed incrementally along each span, the
/// Cortex-M0 fast path: `Lighting<Q14<NW>, [DirectionalLight<Q14<NW>>; K], M>`
/// (`K` 1 to 4, a viewer at infinity, no fog, `M` an [`IncrementalModel`]:
/// Lambert or Blinn-Phong), the same images as [`PhongShading`] up to the
/// error stated below, for a fraction of the cost:
///
/// - `N·L` and `N·H` of the *unnormalised* normal are affine: interpolated as
///   attributes (`3 + 2K`: the normal, then both per light), one addition each;
/// - `|N|²` by second-order forward differences, two additions;
/// - `1/|N|` by one Newton step (three multiplications) from the previous
///   pixel's (exact at each span start; two where `|N|` changes by over 2^-8
///   per pixel);
/// - `(N·H)^n` from a 65-entry table over `[x0, 1]`, `x0 = 4096^(−1/n)`,
///   linearly interpolated: one multiplication;
/// - the colour accumulated in output channel units, one multiplication per
///   channel and term.
///
/// Output is rounded to nearest like [`Linear`] (the shader's encoder is not
/// used). A span whose interpolated normal gets shorter than ½ or longer than 2
/// (normals ~120° apart), or whose `|N|²` changes by more than 1/8 per pixel,
/// falls back to [`PhongShading`]'s per-pixel lighting: same bound, slower.
///
/// Error against the `f64` reference (8-bit LSBs, worst channel, `Q14<2>`,
/// `ks·Is = 0.7`), by shininess `n`: ≤ 3 for `n` ≤ 64, ≤ 10 up to 256, ≤ 34 up
/// to 1024, against 1 / 3 / 9 for [`PhongShading`] in `Q14`: the truncated
/// `N·H` attribute and the Newton step of `1/|N|` are amplified `n`-fold by
/// `x^n` (tested by random spans and a targeted worst-case search per band,
/// `tests/lighting/incremental_phong.rs`). Within 2 LSB on the reference
/// scenes it supports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IncrementalPhongShading;

/// Per-pixel Phong shading by re-anchored quadratic interpolation along each
/// span ([`QuadraticModel`]): the lighting is evaluated exactly at anchors
/// 4–32 pixels apart (segment lengths from bounds on the third derivatives, so
/// the interpolation adds at most 0.3 + 0.3 steps of the 8-bit output), each
/// encoded channel follows the quadratic through them, and `x^n` comes per
/// pixel from a table. `K` directional lights, a viewer at infinity; Lambert,
/// Blinn-Phong and Phong `R·V`; the `Q14` tiers, `f32` and
/// [`F32Fast`](crate::num::F32Fast); any [`Encoder`]. Cheapest where the
/// lighting is smooth (Lambert, the FPU tiers); for `Q14` Blinn-Phong
/// [`IncrementalPhongShading`] is cheaper (`docs/tradeoff.md`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadraticPhongShading;

/// A shading mode: what [`Shader::new`] takes — one of the modes above, or
/// one of them [`textured`](GouraudShading::textured) or
/// [`normal_mapped`](PhongShading::normal_mapped) — for a lighting `I` and
/// output colour `C`, with what its shader precomputes.
#[diagnostic::on_unimplemented(
    message = "`{Self}` cannot shade with the lighting `{I}`",
    label = "this shading mode",
    note = "a lighting built by `Lighting::new` has its lights in world coordinates: draw with `lighting.viewed(camera.view())?` (or `.eye_space()` for lights given in eye coordinates)",
    note = "`IncrementalPhongShading` takes `Lighting<Q14<_>, [DirectionalLight<Q14<_>>; K], Lambert or BlinnPhong>` (K = 1 to 4, a viewer at infinity, no fog); `QuadraticPhongShading` the same in `Q14`, `f32` or `F32Fast`, and `Phong`; `PhongShading`, `GouraudShading` and `FlatShading` take every lighting"
)]
pub trait Mode<I, C>: Copy {
    /// A short name for reports.
    const NAME: &'static str;
    /// What the shader precomputes (the incremental kernel's tables, a
    /// texture or normal map the mode carries).
    type State: Copy + core::fmt::Debug;
    /// Precomputes it for `lighting`.
    fn state(self, lighting: &I) -> Self::State;
}

/// A shader: a shading mode `M` with a lighting `I`, writing colours `C`
/// through an encoder `E`.
pub struct Shader<'l, M: Mode<I, C>, I: Illuminate, E, C> {
    pub(crate) lighting: &'l I,
    pub(crate) encoder: E,
    pub(crate) state: M::State,
    color: PhantomData<(M, C)>,
}

impl<M: Mode<I, C>, I: Illuminate, E: Copy, C> Clone for Shader<'_, M, I, E, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: Mode<I, C>, I: Illuminate, E: Copy, C> Copy for Shader<'_, M, I, E, C> {}

impl<M: Mode<I, C>, I: Illuminate, E: core::fmt::Debug, C> core::fmt::Debug
    for Shader<'_, M, I, E, C>
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Shader")
            .field("mode", &M::NAME)
            .field("encoder", &self.encoder)
            .finish_non_exhaustive()
    }
}

impl<'l, M: Mode<I, C>, I: Illuminate, E: Encoder<C>, C: OutputColor> Shader<'l, M, I, E, C> {
    /// A shader of mode `mode` lighting with `lighting`, writing pixels through
    /// `encoder`.
    ///
    /// The output colour `C` is inferred from the target the shader first
    /// draws into. A shader that is built but never drawn (stored in a
    /// `static`, returned from a function, drawn only behind a generic
    /// parameter) has nothing to infer it from and fails with E0283
    /// ``cannot satisfy `_: OutputColor` ``: name the colour in the type.
    ///
    /// ```
    /// use fixshade::prelude::*;
    /// use embedded_graphics_core::pixelcolor::Rgb565;
    /// let light = DirectionalLight::<Q14>::white([1.0, 1.0, 1.0])?;
    /// let red = MaterialDesc::classic([1.0, 0.1, 0.1], AmbientSource::Object, 0.1, 0.7, 0.6, 32.0);
    /// let lighting = Lighting::<Q14, _, BlinnPhong>::new(light, Material::new(&red)?).eye_space();
    /// let shader: Shader<_, _, _, Rgb565> = Shader::new(GouraudShading, &lighting, Linear);
    /// # let _ = shader;
    /// # Ok::<(), fixshade::error::ParamError>(())
    /// ```
    pub fn new(mode: M, lighting: &'l I, encoder: E) -> Self {
        Shader {
            lighting,
            encoder,
            state: mode.state(lighting),
            color: PhantomData,
        }
    }

    /// The lighting.
    pub fn lighting(&self) -> &'l I {
        self.lighting
    }
}

/// The vertex payload of shading mode `M` (whatever the lighting, encoder and
/// output colour): what the vertex cache ([`MeshBuffers`](crate::render::MeshBuffers))
/// holds per vertex. `[u16; 3]` for [`GouraudShading`], `[i16; 3]` for
/// [`FlatShading`] and the per-pixel modes, 16 bytes for
/// `GouraudShading.textured(…)`, …; a firmware sizes its `static` buffers with it:
///
/// ```
/// use fixshade::prelude::*;
/// use fixshade::shade::{Payload, Textured};
/// use fixshade::render::bins_len;
/// // the rocket of the QEMU firmware: 687 vertices, 784 triangles, 2-row bands
/// static BUFFERS: MeshBuffers<Payload<Textured<'static, GouraudShading>>, 687, { bins_len(784, 120) }, 136> =
///     MeshBuffers::new();
/// assert_eq!(core::mem::size_of::<Payload<Textured<'static, GouraudShading>>>(), 16);
/// assert_eq!(core::mem::size_of::<Payload<GouraudShading>>(), 6);
/// ```
pub type Payload<M> = <Shader<'static, M, PayloadLighting, Linear, Rgb565> as Kernel>::Vertex;

/// A lighting every mode shades, for [`Payload`] (payloads do not depend on
/// the lighting).
type PayloadLighting = crate::lighting::Viewed<
    crate::lighting::Lighting<
        crate::num::Q14,
        [crate::lighting::DirectionalLight<crate::num::Q14>; 1],
        crate::lighting::BlinnPhong,
    >,
>;

/// What the vertex stage hands a [`Kernel`] for one vertex.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct VertexIn {
    /// Eye-space normal, Q14, not normalised.
    pub normal: [i32; 3],
    /// Eye-space position, Q16.16 (zeros unless [`Kernel::NEEDS_POSITION`]).
    pub eye: [i32; 3],
    /// Texture coordinates with [`TEXCOORD_FRAC`](crate::mesh::TEXCOORD_FRAC)
    /// fraction bits (zeros unless [`Kernel::NEEDS_TEXCOORD`] and the mesh has
    /// them).
    pub uv: [i32; 2],
    /// Clip-space `w` of a perspective transform, in the unit of
    /// [`Clip::w`](crate::camera::Clip::w) (1 for an orthographic transform,
    /// or unless [`Kernel::NEEDS_TEXCOORD`]).
    pub w: i32,
    /// Eye-space tangent (Q14, not normalised; transformed like the normal,
    /// exact for rotations and uniform scales) and in `[3]` the handedness
    /// `±16384` (zeros unless [`Kernel::NEEDS_TANGENT`] and the mesh has them).
    pub tangent: [i32; 4],
}

impl VertexIn {
    /// A vertex with eye-space normal `normal` (Q14, any length) and eye
    /// position `eye` (Q16.16), no texture coordinates, `w = 1`, no tangent
    /// ([`Camera::eye`](crate::camera::Camera::eye) gives both from `f32`
    /// world coordinates).
    pub const fn new(normal: [i32; 3], eye: [i32; 3]) -> Self {
        VertexIn {
            normal,
            eye,
            uv: [0; 2],
            w: 1,
            tangent: [0; 4],
        }
    }

    /// The same vertex with texture coordinates `uv` (Q12,
    /// [`TEXCOORD_FRAC`](crate::mesh::TEXCOORD_FRAC) fraction bits).
    pub const fn with_uv(mut self, uv: [i32; 2]) -> Self {
        self.uv = uv;
        self
    }

    /// The same vertex with eye-space tangent `tangent` (Q14) and
    /// handedness `hand` (`±1`).
    pub const fn with_tangent(mut self, tangent: [i32; 3], hand: i32) -> Self {
        self.tangent = [
            tangent[0],
            tangent[1],
            tangent[2],
            if hand < 0 { -16384 } else { 16384 },
        ];
        self
    }

    /// The same vertex with the clip-space `w` of a perspective transform
    /// (the unit of [`Clip::w`](crate::camera::Clip::w)).
    pub const fn with_w(mut self, w: i32) -> Self {
        self.w = w;
        self
    }
}

/// A shading kernel: what the pipeline needs from a shader. Every shading
/// mode implements it, and so may a program's own kernel.
///
/// Per frame the pipeline calls [`Kernel::vertex`] once per vertex (into the
/// vertex cache), [`Kernel::triangle`] once per visible triangle (its constants
/// and corner values), and [`Kernel::span`] for every run of pixels that passed
/// the depth test, with the values at its first pixel and their change per
/// pixel (units and interpolation: [`crate::raster::interp`]).
pub trait Kernel {
    /// The pixel colour written.
    type Color: OutputColor;
    /// What the vertex cache holds per vertex.
    type Vertex: Copy + Default + core::fmt::Debug;
    /// The values interpolated across a triangle: `[i32; N]`, each within
    /// ±[`VARYING_LIMIT`](crate::raster::interp::VARYING_LIMIT) at the
    /// vertices.
    type Varyings: Varyings;
    /// The constants of one triangle (its flat colour, the origin of its
    /// interpolated positions, …).
    type Triangle: Copy + core::fmt::Debug;
    /// How many of the [`Kernel::Varyings`] are used (the first ones; the
    /// others are zero and not interpolated).
    const USED: usize = <Self::Varyings as Varyings>::LEN;
    /// Whether [`Kernel::vertex`] or [`Kernel::triangle`] read eye-space
    /// positions (else the pipeline passes zeros and skips computing them).
    const NEEDS_POSITION: bool;
    /// Whether [`Kernel::vertex`] reads [`VertexIn::uv`] (else the pipeline
    /// passes zeros).
    const NEEDS_TEXCOORD: bool = false;
    /// Whether [`Kernel::vertex`] reads [`VertexIn::tangent`] (else the
    /// pipeline passes zeros and skips transforming the mesh's tangents).
    const NEEDS_TANGENT: bool = false;
    /// Whether the span stage asks [`Kernel::fill`] how to write a whole
    /// screen-linear run; else (the default) it calls [`Kernel::span`] for each
    /// run that passes the depth test.
    const FILLS: bool = false;

    /// The payload of vertex `v`.
    fn vertex(&self, v: &VertexIn) -> Self::Vertex;

    /// The constants of the triangle with payloads `v` and eye-space positions
    /// `eye` (Q16.16; zeros unless [`Kernel::NEEDS_POSITION`]), and the values
    /// to interpolate at its three corners.
    fn triangle(
        &self,
        v: [&Self::Vertex; 3],
        eye: &[[i32; 3]; 3],
    ) -> (Self::Triangle, [Self::Varyings; 3]);

    /// The range (with [`ATTR_FRAC`](crate::num::ATTR_FRAC) fraction bits)
    /// that value `i` must stay in when handed to [`Kernel::span`]: where the
    /// screen-linear interpolation's error bound could carry it out, the
    /// pipeline clamps the run to the vertices' range. The default is
    /// ±2^30 (no `i32` overflow in a kernel that adds steps).
    #[inline(always)]
    fn safe(&self, i: usize) -> (i32, i32) {
        let _ = i;
        (-(1 << 30), 1 << 30)
    }

    /// Whether value `i` needs its screen-linear interpolation exact to
    /// rounding (one unit of 2^−[`ATTR_FRAC`](crate::num::ATTR_FRAC) per pixel
    /// stepped) rather than within the 14-bit barycentric coefficients' error:
    /// texture coordinates, where one unit can change the texel. Costs the
    /// set-up a bit-serial division and four 16 × 16-bit products per value.
    /// Default `false` (perspective-correct values are that exact anyway).
    #[inline(always)]
    fn exact(&self, i: usize) -> bool {
        let _ = i;
        false
    }

    /// Shades pixels `x..x + out.len()` of row `y` (they passed the depth
    /// test): pixel `k` has the values `start + k·step`, which stay within the
    /// range of the corners' values (with [`ATTR_FRAC`](crate::num::ATTR_FRAC)
    /// fraction bits) up to the interpolation's error.
    fn span(
        &self,
        t: &Self::Triangle,
        start: &Self::Varyings,
        step: &Self::Varyings,
        x: i32,
        y: i32,
        out: &mut [Self::Color],
    );

    /// How the span stage writes the run of `n` pixels whose values start at
    /// `start` and step by `step` (asked when [`Kernel::FILLS`]): see [`Fill`].
    #[inline(always)]
    fn fill(
        &self,
        t: &Self::Triangle,
        start: &Self::Varyings,
        step: &Self::Varyings,
    ) -> Fill<Self::Color> {
        let _ = (t, start, step);
        Fill::Shaded
    }
}

/// How the span stage writes a run of a kernel's pixels ([`Kernel::fill`]):
/// the first two in its own loops with the depth test fused in (one pass over
/// the pixels instead of two).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fill<C> {
    /// Every pixel this colour.
    Solid(C),
    /// Rounded 5-6-5 Gouraud pixels from packed channel accumulators: red in
    /// the high and blue in the low half of `rb`, 11 fraction bits each,
    /// green in `g` (`g >> 23` is the channel); each steps by its `d…` per
    /// pixel (wrapping). Pixel: `(rb >> 27) << 11 | (rb << 16) >> 27 | (g >> 23) << 5`.
    Ramp565 {
        /// Red and blue.
        rb: u32,
        /// Their step.
        drb: u32,
        /// Green.
        g: u32,
        /// Its step.
        dg: u32,
    },
    /// The default: [`Kernel::span`] on each run of pixels that pass the depth
    /// test.
    Shaded,
}

/// The 5-6-5 pixel of packed red-blue `rb` and green `g` ([`Fill::Ramp565`]).
#[inline(always)]
pub(crate) fn pixel565(rb: u32, g: u32) -> u16 {
    // r = rb >> 27, b = bits 27..32 of rb << 16, g = g >> 23
    (((rb >> 27) << 11) | ((rb << 16) >> 27) | ((g >> 23) << 5)) as u16
}

/// The range of the values of the kernels that interpolate the unit normal
/// and its dot products (Q14 with [`ATTR_FRAC`](crate::num::ATTR_FRAC)
/// bits): the span code checks |N|² itself; the values must only stay inside
/// ±2 so that nothing wraps.
#[inline(always)]
pub(crate) const fn normal_range() -> (i32, i32) {
    let two = 1 << (15 + crate::num::ATTR_FRAC);
    (-two, two - 1)
}

/// The [`Kernel`] items shared by the kernels that interpolate the eye-space
/// unit normal (and `$n − 3` values derived from it) without a position:
/// the colour, the vertex payload (the unit normal in Q14), the triangle
/// constants (none) and the range of the values ([`normal_range`]).
macro_rules! normal_kernel_items {
    ($n:literal) => {
        type Color = C;
        /// The eye-space unit normal in Q14.
        type Vertex = [i16; 3];
        type Triangle = ();
        const NEEDS_POSITION: bool = false;

        #[inline]
        fn vertex(&self, v: &$crate::shade::VertexIn) -> [i16; 3] {
            $crate::shade::unit_q14(v.normal)
        }

        #[inline(always)]
        fn safe(&self, _i: usize) -> (i32, i32) {
            $crate::shade::normal_range()
        }
    };
}
pub(crate) use normal_kernel_items;

/// `n / |n|` in Q14 for a vector of `i32` components (any length): 32-bit
/// arithmetic only (the inverse square root of `crate::num::Q14`: a seed and
/// two Newton steps, about the Q14 resolution). The zero vector stays zero.
#[inline]
pub(crate) fn unit_q14(n: [i32; 3]) -> [i16; 3] {
    use crate::num::rsqrt::{rsqrt_q14_mantissa, split_u32};
    // components below 2^15, so that the squares and c·y fit 32 bits
    let m = n[0].unsigned_abs() | n[1].unsigned_abs() | n[2].unsigned_abs();
    let sh = (crate::raster::setup::bit_length(m) as i32 - 15).max(0) as u32;
    let c = n.map(|v| v >> sh);
    // each square < 2^30: the sum < 3·2^30 < 2^32
    let s = c.iter().fold(0u32, |a, &v| a + (v * v) as u32);
    if s == 0 {
        return [0; 3];
    }
    let (t, k) = split_u32(s);
    let y = rsqrt_q14_mantissa(t, 2) as i32; // ≤ 2^15
                                             // c/|c| in Q14 = c·y >> (16 − k/2), rounded; |c·y| < 2^30
    let sh = 16 - k / 2;
    c.map(|v| {
        let r = ((v * y) >> (sh - 1)) + 1;
        (r >> 1).clamp(-(1 << 14), 1 << 14) as i16
    })
}

/// Converts a Q14 eye-space normal (any length) to a unit normal of tier `S`
/// (normalised in Q14, see [`unit_q14`]).
#[inline(always)]
pub(crate) fn unit_normal<S: Scalar>(n: [i32; 3]) -> Vec3<S> {
    let u = unit_q14(n);
    // Q14 → the tier's attribute (Q26) scale
    let c = |v: i16| S::from_attr(i32::from(v) << 12);
    Vec3::new(c(u[0]), c(u[1]), c(u[2]))
}

/// A Q16.16 eye-space position in tier `S`'s geometry type.
#[inline(always)]
pub(crate) fn eye_point<S: Scalar>(p: [i32; 3]) -> Point3<S> {
    Vec3::new(
        S::geo_from_attr(p[0]),
        S::geo_from_attr(p[1]),
        S::geo_from_attr(p[2]),
    )
}
