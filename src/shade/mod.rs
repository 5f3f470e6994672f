//! Shading: which colour each covered pixel gets, from the lighting, the
//! vertex data and the interpolated values — the span kernels of the
//! pipeline, behind one trait, [`Kernel`].
//!
//! One [`Shader`] type, generic over the mode. A mode names *what* is shaded;
//! the lighting decides *how* (the fastest kernel that serves it):
//!
//! | mode | lit | interpolated per pixel | catches a highlight inside a triangle |
//! |---|---|---|---|
//! | [`FlatShading`] | once per triangle, at the centroid | nothing | no (one colour, Mach bands) |
//! | [`GouraudShading`] | at the three vertices | encoded colour channels | no (misses or smears it) |
//! | [`PhongShading`] | at every pixel: incrementally for a `Q14` lighting of one directional light (the kernel of [`IncrementalPhongShading`]), else with the full model ([`GeneralPhongShading`]) | normal (and position when the lighting needs it) | yes |
//! | `GouraudShading.`[`textured`](GouraudShading::textured)`(…)` ([`Textured`]) | at the three vertices, primary and secondary colour apart | both colours and the texture coordinates | no (`texel × primary + secondary`, OpenGL's `GL_MODULATE`) |
//! | `PhongShading.`[`normal_mapped`](PhongShading::normal_mapped)`(…)` ([`NormalMapped`]) | at every pixel, with the normal of a [`NormalMap`](crate::texture::NormalMap) in the tangent frame (fast: Q14, one directional light) | normal and tangent (general) or `L`, `H` in tangent space (fast), texture coordinates | yes, and surface detail |
//!
//! Kernels named explicitly: [`GeneralPhongShading`] (every tier, light and
//! model), [`IncrementalPhongShading`] (Q14, up to four directional lights,
//! Lambert or Blinn-Phong), [`QuadraticPhongShading`] (anchors 4–32 pixels
//! apart, the colour quadratically in between, the specular power per pixel;
//! Q14, `f32`, `F32Fast`; directional lights; Lambert, Blinn-Phong or Phong
//! `R·V`).
//!
//! The reflection models ([`Lambert`](crate::lighting::Lambert),
//! [`Phong`](crate::lighting::Phong), [`BlinnPhong`](crate::lighting::BlinnPhong))
//! say *what light a point reflects* and live in [`lighting`](crate::lighting).
//! Every mode writes through an [`Encoder`] (plain rounding, ordered
//! dithering or a gamma table).
//!
//! Every value a kernel interpolates is perspective-correct under a
//! perspective projection ([`crate::raster::interp`]). A shader draws meshes
//! ([`MeshDraw`](crate::render::MeshDraw)) and single triangles
//! ([`draw_triangle`](crate::render::draw_triangle)) through the same
//! pipeline.

mod flat;
mod gouraud;
mod incremental;
mod normalmap;
mod perpixel;
mod phong;
mod quadratic;
mod segment;
mod textured;

pub use crate::color::{Dithered, Encoder, Linear};
pub use incremental::IncrementalModel;
pub use normalmap::NormalMapped;
pub use quadratic::QuadraticModel;
pub use textured::Textured;

use crate::color::OutputColor;
use crate::error::RenderError;
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

/// Phong shading, per-pixel lighting: the vertex normals are interpolated
/// across the triangle and every pixel is lit. Catches the highlight in the
/// middle of a large triangle.
///
/// The lighting decides how: a `Q14` lighting of one directional light, a
/// viewer at infinity and no fog, with the Lambert or Blinn-Phong model, gets
/// the incremental kernel of [`IncrementalPhongShading`] (the Cortex-M0 fast
/// path, within the general path's error bound); every other lighting gets
/// [`GeneralPhongShading`]'s. Name either of those to choose explicitly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PhongShading;

/// Phong shading with the general kernel: the vertex normals are
/// interpolated, renormalised per pixel with the tier's
/// [`Scalar::normalize_interpolated`], and every pixel is lit with the full
/// lighting model, for every tier, light kind and model. When the lighting
/// needs the surface position (point or spot lights, a local viewer, fog) the
/// eye-space position is interpolated too.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GeneralPhongShading;

/// Per-pixel Phong shading computed incrementally along each span: the Q14 fast
/// path for directional lights and a viewer at infinity: the lighting is a
/// `Lighting<Q14<NW>, [DirectionalLight<Q14<NW>>; K], M>` with `M` an
/// [`IncrementalModel`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IncrementalPhongShading;

/// Per-pixel Phong shading by re-anchored quadratic interpolation along each
/// span (see [`QuadraticModel`]; the tiers: the `Q14` tiers, `f32` and
/// [`F32Fast`](crate::num::F32Fast); the lighting: one `Lighting` of `K` directional lights):
/// the lighting is evaluated exactly at anchors 4–32 pixels apart (segment
/// lengths from bounds on the third derivatives, so the interpolation adds at
/// most 0.3 + 0.3 steps of the 8-bit output), each encoded colour channel
/// follows the quadratic through them, and the specular power `x^n` comes per
/// pixel from a table. Directional lights and a viewer at infinity; Lambert,
/// Blinn-Phong and Phong `R·V`; the `Q14` tiers, `f32` and [`F32Fast`](crate::num::F32Fast);
/// any [`Encoder`]. Cheapest where the lighting is smooth: Lambert, and the FPU
/// tiers; for `Q14` Blinn-Phong [`IncrementalPhongShading`] is cheaper
/// (`docs/tradeoff.md`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadraticPhongShading;

/// The name of a shading mode in a shader's `Debug` output: sealed, not
/// re-exported (issue 18).
mod mode {
    /// A shading mode: `FlatShading`, `GouraudShading`, `PhongShading`,
    /// `GeneralPhongShading`, `IncrementalPhongShading`,
    /// `QuadraticPhongShading`, or one of them `Textured` or `NormalMapped`.
    pub trait Mode: Copy + core::fmt::Debug {
        /// A short name for reports.
        const NAME: &'static str;
    }
}
pub(crate) use mode::Mode;

/// [`Mode`] for each plain shading mode, with its name.
macro_rules! mode_names {
    ($($mode:ty => $name:literal),* $(,)?) => {$(
        impl Mode for $mode {
            const NAME: &'static str = $name;
        }
    )*};
}
mode_names!(
    FlatShading => "flat",
    GouraudShading => "gouraud",
    PhongShading => "phong",
    GeneralPhongShading => "phong_general",
    IncrementalPhongShading => "phong_inc",
    QuadraticPhongShading => "phong_quad",
);

/// A shader: a shading mode `M` with a lighting `I`, writing colours `C`
/// through an encoder `E`.
pub struct Shader<'l, M: ModeState<I, C>, I: Illuminate, E, C> {
    pub(crate) lighting: &'l I,
    pub(crate) encoder: E,
    pub(crate) state: <M as ModeState<I, C>>::State,
    color: PhantomData<(M, C)>,
}

impl<M: ModeState<I, C>, I: Illuminate, E, C> Shader<'_, M, I, E, C> {
    /// [`Kernel::check`] of every shading mode: the lights are in eye
    /// coordinates.
    pub(crate) fn check_lights(&self) -> Result<(), RenderError> {
        if self.lighting.lights_in_eye_space() {
            Ok(())
        } else {
            Err(RenderError::WorldLights)
        }
    }
}

/// Per-mode constants a shader precomputes (the incremental mode's tables).
pub trait ModeState<I: Illuminate, C> {
    /// What is precomputed.
    type State: Copy + core::fmt::Debug;
    /// Precomputes it for `lighting` (the mode is a value: a texture or a
    /// normal map it carries goes into the state).
    fn state(self, lighting: &I) -> Self::State;
}

impl<M: ModeState<I, C>, I: Illuminate, E: Copy, C> Clone for Shader<'_, M, I, E, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: ModeState<I, C>, I: Illuminate, E: Copy, C> Copy for Shader<'_, M, I, E, C> {}

impl<M: Mode + ModeState<I, C>, I: Illuminate, E: core::fmt::Debug, C> core::fmt::Debug
    for Shader<'_, M, I, E, C>
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Shader")
            .field("mode", &M::NAME)
            .field("encoder", &self.encoder)
            .finish_non_exhaustive()
    }
}

impl<'l, M: ModeState<I, C>, I: Illuminate, E: Encoder<C>, C: OutputColor> Shader<'l, M, I, E, C> {
    /// A shader of mode `mode` lighting with `lighting`, writing pixels through
    /// `encoder`.
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
    /// A vertex with normal `normal` and eye position `eye`, no texture
    /// coordinates, `w = 1`, no tangent.
    pub const fn new(normal: [i32; 3], eye: [i32; 3]) -> Self {
        VertexIn {
            normal,
            eye,
            uv: [0; 2],
            w: 1,
            tangent: [0; 4],
        }
    }
}

/// A shading kernel: what the pipeline needs from a shader. Every shading
/// mode implements it, and so may a program's own kernel.
///
/// Per frame the pipeline calls [`Kernel::vertex`] once per vertex (the vertex
/// stage, into the vertex cache), [`Kernel::triangle`] once per visible
/// triangle (its constants and the values to interpolate at its corners), and
/// [`Kernel::span`] for every run of pixels that passed the depth test, with
/// the interpolated values at the run's first pixel and their change per
/// pixel (see [`crate::raster::interp`] for units and for how they are
/// interpolated: screen-linear, or perspective-correct in sub-spans of 8
/// pixels under a perspective projection).
pub trait Kernel {
    /// The pixel colour written.
    type Color: Copy;
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
    /// Whether [`Kernel::span_depth`] fuses the depth test into the
    /// kernel's own loop: the pipeline then hands it every screen-linear run
    /// whole (values that need clamping clamped over the whole run); else it
    /// splits runs at the depth test itself and calls [`Kernel::span`] per
    /// passing run.
    /// The default is `false`.
    const FUSED_DEPTH: bool = false;

    /// Whether the kernel can draw, checked once by
    /// [`MeshDraw::new`](crate::render::MeshDraw::new) and
    /// [`draw_triangle`](crate::render::draw_triangle) before anything is
    /// drawn. A [`Shader`] refuses a lighting whose lights are in world
    /// coordinates ([`RenderError::WorldLights`]); the default is `Ok`.
    fn check(&self) -> Result<(), RenderError> {
        Ok(())
    }

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

    /// The range (with [`ATTR_FRAC`](crate::raster::ATTR_FRAC) fraction bits)
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
    /// rounding (one unit of 2^−[`ATTR_FRAC`](crate::raster::ATTR_FRAC) per
    /// pixel stepped) rather than within the 14-bit barycentric
    /// coefficients' error: texture coordinates, whose every unit can move a
    /// pixel to the neighbouring texel. Costs the triangle's set-up one
    /// bit-serial division and four 16 × 16-bit products per such value. The
    /// default is `false`; perspective-correct values are exact to the same
    /// order anyway.
    #[inline(always)]
    fn exact(&self, i: usize) -> bool {
        let _ = i;
        false
    }

    /// Shades pixels `x..x + out.len()` of row `y` (they passed the depth
    /// test): pixel `k` has the values `start + k·step`, which stay within the
    /// range of the corners' values (with [`ATTR_FRAC`](crate::raster::ATTR_FRAC)
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

    /// Depth-tests and shades pixels `x..x + out.len()` of row `y` in one
    /// call (`depth` is as long as `out`): pixel `k` has the depth
    /// `(z.0 + k·z.1) >> ATTR_FRAC` (wrapping `u32` steps) and passes when
    /// that is less than `depth[k]`, which then takes it; a passing pixel
    /// gets the colour [`Kernel::span`] gives it with the values
    /// `start + k·step`. The default splits the run at the depth test and
    /// calls [`Kernel::span`] for each passing run; the Gouraud and flat
    /// kernels fuse the test into their loops (one pass over the pixels
    /// instead of two) and say so with [`Kernel::FUSED_DEPTH`].
    #[inline(always)]
    fn span_depth(
        &self,
        t: &Self::Triangle,
        (start, step): (&Self::Varyings, &Self::Varyings),
        (x, y): (i32, i32),
        z: (i32, i32),
        out: &mut [Self::Color],
        depth: &mut [u16],
    ) {
        use crate::raster::interp::get;
        depth_runs(z.0, z.1, depth, |k0, k1| {
            if let Some(c) = out.get_mut(k0..k1) {
                let a = Self::Varyings::from_fn(|i| {
                    get(start, i).wrapping_add(get(step, i).wrapping_mul(k0 as i32))
                });
                self.span(t, &a, step, x + k0 as i32, y, c);
            }
        });
    }
}

/// The fused loop of [`Kernel::span_depth`]: pixel `k` has depth
/// `(z.0 + k·z.1) >> ATTR_FRAC` and, when that is less than `depth[k]`,
/// takes it and gets the colour `pixel(&s)`; `step(&mut s)` moves the
/// kernel's state `s` a pixel on, passing or not. One pass, few live values
/// (the 5-6-5 Gouraud loop keeps its state in two registers).
#[inline(always)]
pub(crate) fn fused_depth<C, S>(
    z: (i32, i32),
    color: &mut [C],
    depth: &mut [u16],
    mut s: S,
    pixel: impl Fn(&S) -> C,
    step: impl Fn(&mut S),
) {
    let (mut z, dz) = (z.0 as u32, z.1 as u32);
    let n = color.len().min(depth.len());
    let (Some(color), Some(depth)) = (color.get_mut(..n), depth.get_mut(..n)) else {
        return;
    };
    for k in 0..n {
        // below 2^16: the run's depths are in range (clamped where they needed it)
        let zi = z >> crate::raster::ATTR_FRAC;
        if zi < u32::from(depth[k]) {
            depth[k] = zi as u16;
            color[k] = pixel(&s);
        }
        // the values after the last pixel are not used: wrapping is harmless
        z = z.wrapping_add(dz);
        step(&mut s);
        crate::num::no_unroll();
    }
}

/// The depth test of the leading pixels of a run: pixel `k` has depth
/// `(z + k·dz) >> 14` and passes when that is less than `depth[k]`, which then
/// takes it. Stops at the first pixel that fails; returns how many passed.
/// A loop of its own (few live values: no register spills on a Cortex-M0).
#[inline(never)]
pub(crate) fn depth_prefix(z: u32, dz: u32, depth: &mut [u16]) -> usize {
    let mut z = z;
    for (k, d) in depth.iter_mut().enumerate() {
        let zi = (z >> crate::raster::ATTR_FRAC) as u16;
        if zi >= *d {
            return k;
        }
        *d = zi;
        // the value after the last pixel is not used: wrapping is harmless
        z = z.wrapping_add(dz);
        crate::num::no_unroll();
    }
    depth.len()
}

/// How many leading pixels of a run fail the depth test (changing nothing).
#[inline(never)]
fn depth_fails(z: u32, dz: u32, depth: &[u16]) -> usize {
    let mut z = z;
    for (k, d) in depth.iter().enumerate() {
        if ((z >> crate::raster::ATTR_FRAC) as u16) < *d {
            return k;
        }
        z = z.wrapping_add(dz);
        crate::num::no_unroll();
    }
    depth.len()
}

/// The depth test of a run, split from the shading: `shade(k0, k1)` is called
/// for every maximal run `k0..k1` of passing pixels, in order (see
/// [`depth_prefix`]). In the common case (every pixel passes) that is one
/// depth loop and one call.
#[inline(always)]
pub(crate) fn depth_runs(z: i32, dz: i32, depth: &mut [u16], mut shade: impl FnMut(usize, usize)) {
    let n = depth.len();
    let dz = dz as u32;
    let mut z = z as u32;
    let mut k = 0;
    while k < n {
        let Some(rest) = depth.get_mut(k..) else {
            return;
        };
        let m = depth_prefix(z, dz, rest);
        if m > 0 {
            shade(k, k + m);
        }
        k += m;
        z = z.wrapping_add(dz.wrapping_mul(m as u32));
        let Some(rest) = depth.get(k..) else {
            return;
        };
        let f = depth_fails(z, dz, rest);
        k += f;
        z = z.wrapping_add(dz.wrapping_mul(f as u32));
    }
}

/// The range of the values of the kernels that interpolate the unit normal
/// and its dot products (Q14 with [`ATTR_FRAC`](crate::raster::ATTR_FRAC)
/// bits): the span code checks |N|² itself; the values must only stay inside
/// ±2 so that nothing wraps.
#[inline(always)]
pub(crate) const fn normal_range() -> (i32, i32) {
    let two = 1 << (15 + crate::raster::ATTR_FRAC);
    (-two, two - 1)
}

/// `acc += (k·w) ≫ 14` per channel: a light term `k` (Q14) times the
/// channel weights `w` (Q14 of the encoded channels with 8 fraction bits),
/// in the fixed-point fast kernels' pixel loops.
#[inline(always)]
pub(crate) fn add_term(acc: &mut [i32; 3], k: i32, w: &[i32; 3]) {
    acc[0] += (k * w[0]) >> 14;
    acc[1] += (k * w[1]) >> 14;
    acc[2] += (k * w[2]) >> 14;
}

/// The colour of the channel sums `acc` (8 fraction bits), each clamped to
/// `[0, max]`.
#[inline(always)]
pub(crate) fn from_acc<C: OutputColor>(acc: [i32; 3], max: [i32; 3]) -> C {
    C::from_channels([
        (acc[0] >> 8).max(0).min(max[0]) as u32,
        (acc[1] >> 8).max(0).min(max[1]) as u32,
        (acc[2] >> 8).max(0).min(max[2]) as u32,
    ])
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
