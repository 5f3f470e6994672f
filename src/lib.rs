//! **fixshade** lights and shades 3D triangles on microcontroller displays:
//! `#![no_std]`, no allocation, 32-bit fixed-point arithmetic, pixels written
//! through any embedded-graphics `DrawTarget`.
//!
//! # The frame pipeline
//!
//! One pipeline draws every triangle; data flows one way, each stage in one
//! module. Every module imports only from the modules above it in this
//! table (every stage may name the crate's errors, [`error`]; the span and
//! drawing stages write into the framebuffer's band strips); there are no
//! import cycles (`python3 measure/layout.py --check` holds CI to it):
//!
//! | stage | module | what it does |
//! |---|---|---|
//! | numbers | [`num`] | the tiers ([`Q14`](num::Q14), [`Q30`](num::Q30), `f32`, [`F32Fast`](num::F32Fast)), vectors, matrices, and the one copy of each table-driven operation (reciprocal, inverse square root, powers) |
//! | colour | [`color`] | linear RGB, output pixel formats, encoders (rounding, ordered dithering, gamma tables) |
//! | lighting | [`lighting`] | what a point reflects: lights, material, reflection model, viewer, fog, the equation once; lights placed in world coordinates and seen from the eye ([`Viewed`](lighting::Viewed)); OpenGL 1.x parameter sets in [`lighting::gl`] |
//! | texture | [`texture`] | colour textures and normal maps over borrowed texels, and their sampling |
//! | mesh | [`mesh`] | meshes in flash (`i16` positions, Q14 normals, optional Q12 texture coordinates and tangents, `u16` triangles), `const fn` generators |
//! | camera | [`camera`] | projection (a type: [`Orthographic`](camera::Orthographic) or [`Perspective`](camera::Perspective)), view, viewport; [`MeshTransform`](camera::MeshTransform) takes model space to clip space in fixed point, [`Camera::clip`](camera::Camera::clip) a program's `f32` points |
//! | clip, set-up, interpolation | [`raster`] | the one clip-space clipper (near plane and set-up window), 32-bit set-up, exact edge walking with a top-left rule, screen-linear or perspective-correct values ([`raster::interp`]) |
//! | shading | [`shade`] | the kernels that compute colours, one a file, named by the mode the user writes ([`FlatShading`](shade::FlatShading), [`GouraudShading`](shade::GouraudShading), [`PhongShading`](shade::PhongShading), [`IncrementalPhongShading`](shade::IncrementalPhongShading), [`QuadraticPhongShading`](shade::QuadraticPhongShading), `.textured(…)`, `.normal_mapped(…)`) and the one trait they implement, [`Kernel`](shade::Kernel) |
//! | spans | `span` (internal) | the row loop, the depth test and the pixel write: a set-up triangle's rows in a band, each run depth-tested and written (the simple colours of [`Fill`](shade::Fill) by the stage's own loops) |
//! | drawing | [`render`] | [`MeshDraw`](render::MeshDraw): the vertex stage (transform and light each vertex once per frame), bins by band, then per band clip, set-up and spans; [`draw_triangle`](render::draw_triangle) and [`Triangle`](render::Triangle): the same stages for one triangle a program brings |
//! | framebuffer | [`framebuffer`] | the band strip flushed to any `DrawTarget` or sent by DMA while the next band is drawn ([`Bands`](framebuffer::Bands), [`BandSink`](framebuffer::BandSink)), bands shared out between cores ([`Bands::render_bands`](framebuffer::Bands::render_bands), [`MeshDraw::share`](render::MeshDraw::share)), a whole frame in memory ([`FullFrame`](framebuffer::FullFrame)), a checksum target |
//!
//! A mesh and a single triangle take the same clipper, set-up, spans and
//! kernel: `draw_triangle` gives the mesh renderer's pixels bit for bit.
//! Under a perspective projection every value a kernel interpolates is
//! perspective-correct; an orthographic scene pays nothing for it (the
//! projection is a type).
//!
//! What a pixel reflects — the lighting equation, written once, generic over
//! the number tier and over which terms exist — lives in [`lighting`]. The
//! tests compare every tier with an `f64` model of the same equations, written
//! plainly (`testkit/src/reference.rs`).
//!
//! # Example: a lit sphere in 8-row bands
//!
//! ```
//! use fixshade::prelude::*;
//!
//! // a mesh in flash, built at compile time
//! const N: (usize, usize) = uv_sphere_counts(16, 24);
//! static SPHERE: MeshData<{ N.0 }, { N.1 }> = MeshData::uv_sphere(16, 24, 14);
//!
//! // camera, light and material
//! let camera = Camera::orthographic(-1.2, 1.2, -1.2, 1.2, 1.0, 10.0, Viewport::new(0, 0, 240, 240)?)?
//!     .with_view(Mat4::translate([0.0, 0.0, -5.0]));
//! let light = DirectionalLight::<Q14>::white([1.0, 1.0, 1.0])?; // world coordinates
//! let red = MaterialDesc::classic([1.0, 0.1, 0.1], AmbientSource::Object, 0.1, 0.7, 0.6, 32.0);
//! let lighting = Lighting::<Q14, _, BlinnPhong>::new(light, Material::new(&red)?);
//!
//! // memory the caller owns, sized from the layout and the mesh: an 8-row strip, its
//! // depth, the mesh's vertex cache, bins and resume records (two per triangle crossing
//! // the busiest band boundary: this sphere needs 48; MeshDraw::new returns
//! // BufferTooSmall { which: "carry", needed } when short)
//! const LAYOUT: Layout = match Layout::banded(240, 240, 8) {
//!     Ok(layout) => layout,
//!     Err(_) => panic!("not a layout"), // a compile-time error
//! };
//! const STRIP: usize = (LAYOUT.width() * LAYOUT.band_rows()) as usize;
//! let mut strip = [Rgb565::BLACK; STRIP];
//! let mut depth = [0u16; STRIP];
//! let mut buffers: MeshBuffers<_, { N.0 }, { bins_len(N.1, LAYOUT.bands() as usize) }, 64> =
//!     MeshBuffers::new();
//!
//! // once per frame: the lights seen from the camera; transform, light and bin
//! // the mesh, then draw band by band
//! let lit = lighting.viewed(camera.view())?;
//! let transform = camera.mesh_transform(&Mat4::rotate_y(0.3), SPHERE.frac)?;
//! let shader = Shader::new(PhongShading, &lit, Linear);
//! let mut sphere = MeshDraw::new(LAYOUT, SPHERE.mesh(), &transform, shader, buffers.memory(), DrawOptions::default())?;
//! assert_eq!(sphere.carry_needed(), 48); // of the 64 resume records
//! let mut display = Checksum::new(Size::new(240, 240)); // any DrawTarget: a display driver, the simulator
//! Bands::new(LAYOUT, &mut strip, Some(&mut depth))?.render(&mut display, Rgb565::BLACK, &mut [&mut sphere])?;
//! assert_eq!(display.pixels(), 240 * 240);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
//!
//! # Paying only for what a scene uses
//!
//! Lights are typed ([`DirectionalLight`](lighting::DirectionalLight) has no
//! attenuation and no cone), the material terms are a type
//! ([`Lambert`](lighting::Lambert), [`Phong`](lighting::Phong),
//! [`BlinnPhong`](lighting::BlinnPhong), [`Terms`](lighting::Terms)), and so are
//! the viewer, the fog, the projection and the shading mode: a scene with one
//! directional diffuse light and an orthographic camera compiles to code
//! without specular, attenuation, spot evaluation or perspective division.
//!
//! # Numbers at the extremes
//!
//! Constructors taking `f32` validate their input and return a
//! [`ParamError`](error::ParamError) (a [`MeshError`](error::MeshError),
//! [`TextureError`](error::TextureError) or
//! [`RenderError`](error::RenderError) for geometry, texels and buffers; each
//! converts into the crate's [`Error`](error::Error)). Evaluation
//! never panics and never wraps: every tier saturates (see [`num`]), powers
//! clamp their base to [0, 1], no specular term appears where `N·L ≤ 0`, and
//! output colours clamp to [0, 1].
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![warn(
    missing_debug_implementations,
    missing_copy_implementations,
    trivial_casts,
    rustdoc::broken_intra_doc_links
)]
// `add`, `mul`, … on vectors and colours saturate; they are deliberately not the
// operator traits, whose overflow semantics differ.
#![allow(clippy::should_implement_trait)]
// `!(x > 0.0)` is the NaN-aware test the float tiers mean.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

#[cfg(test)]
extern crate std;
#[cfg(test)]
mod test_rng;

pub mod camera;
pub mod color;
pub mod error;
pub mod framebuffer;
pub mod lighting;
pub mod mesh;
pub mod num;
pub mod raster;
pub mod render;
pub mod shade;
mod span;
pub mod standard;
pub mod texture;

/// The types most programs need, for `use fixshade::prelude::*`.
pub mod prelude {
    pub use crate::camera::{
        Angle, Camera, FixedCamera, MeshTransform, Orthographic, Perspective, Pose, Viewport,
    };
    pub use crate::color::{Dithered, Linear};
    pub use crate::color::{GammaTable, OutputColor, Rgb, Transfer};
    pub use crate::error::{Error, ParamError};
    pub use crate::framebuffer::Checksum;
    pub use crate::framebuffer::{Bands, FullFrame, Layout};
    pub use crate::lighting::{AmbientSource, Material, MaterialDesc};
    pub use crate::lighting::{
        AnyLight, Attenuation, DirectionalLight, LightColors, PointLight, SpotLight,
    };
    pub use crate::lighting::{
        BlinnPhong, Full, Illuminate, InfiniteViewer, Lambert, Lighting, LinearFog, LocalViewer,
        NoFog, Phong, Terms, Viewed,
    };
    pub use crate::mesh::{uv_sphere_counts, Mesh, MeshData};
    pub use crate::num::Mat4;
    pub use crate::num::Vec3;
    pub use crate::num::{F32Fast, Scalar, Q14, Q30};
    pub use crate::raster::Cull;
    pub use crate::render::{bins_len, DrawOptions, MeshBuffers, MeshDraw};
    pub use crate::shade::{
        FlatShading, GouraudShading, IncrementalPhongShading, Kernel, PhongShading,
        QuadraticPhongShading, Shader,
    };
    pub use embedded_graphics_core::geometry::Size;
    pub use embedded_graphics_core::pixelcolor::{Gray8, Rgb565, Rgb888, RgbColor};
}

/// Re-exported so that users need no direct dependency of matching versions:
/// `heapless` (light sets of a run-time length) and
/// `embedded_graphics_core` (colours, `DrawTarget`).
pub use embedded_graphics_core;
pub use heapless;

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
