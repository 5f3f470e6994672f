//! **fixshade** lights and shades 3D triangles on microcontroller displays:
//! `#![no_std]`, no allocation, fixed-point arithmetic, pixels written through any
//! embedded-graphics `DrawTarget`.
//!
//! # The pipeline
//!
//! Data flows one way; each stage lives in one module:
//!
//! | stage | module | what it does |
//! |---|---|---|
//! | numbers | [`num`] | the tiers a pipeline computes in: [`Q14`](num::Q14) (16-bit products, the Cortex-M0 fast path), [`Q30`](num::Q30) (64-bit products, ≤ 1 LSB), `f32` and [`F32Fast`](num::F32Fast) (FPU targets) |
//! | scene | [`light`], [`material`], [`gl`] | validated lights (directional, point, spot), materials, OpenGL 1.x parameter sets |
//! | lighting | [`lighting`] | the lighting equation, once, generic over the tier and over which terms exist |
//! | geometry | [`mesh`] | vertex normals, sphere generators, fixed-point transforms and projection, near-plane clipping |
//! | shading | [`shade`] | [`Flat`](shade::Flat), [`Gouraud`](shade::Gouraud) and [`Phong`](shade::Phong) behind the [`Shading`](shade::Shading) trait; encoders for rounding, dithering and gamma ([`color`]) |
//! | rasterizer | [`raster`] | sub-pixel triangle setup, top-left fill rule, watertight edges, depth runs, perspective-correct attributes |
//! | framebuffer | [`target`] | a span-oriented [`Framebuffer`](target::Framebuffer) trait: slice framebuffer, band buffer for RAM-poor MCUs, adapter for any `DrawTarget` |
//!
//! The `f64` reference model ([`reference`], feature `reference`) evaluates the
//! same equations plainly; the tests compare every tier with it.
//!
//! # Paying only for what a scene uses
//!
//! Lights are typed ([`DirectionalLight`](light::DirectionalLight) has no
//! attenuation and no cone), the material terms are a type
//! ([`Lambert`](lighting::Lambert), [`Phong`](lighting::Phong),
//! [`BlinnPhong`](lighting::BlinnPhong), [`Terms`](lighting::Terms)), and so are
//! the viewer and the fog: a scene with one directional diffuse light compiles to
//! code without specular, attenuation or spot evaluation.
//!
//! # Numbers at the extremes
//!
//! Constructors taking `f32` validate their input and return a
//! [`ParamError`](error::ParamError). Evaluation never panics and never wraps:
//! every tier saturates (see [`num`]), powers clamp their base to [0, 1], no
//! specular term appears where `N·L ≤ 0`, and output colours clamp to [0, 1].
//!
//! # Example
//!
//! ```
//! use fixshade::prelude::*;
//! use fixshade::raster::{RasterOptions, SUBPIXEL_BITS};
//! use fixshade::shade::{Linear, Phong, ShadeVertex, Shading};
//! use fixshade::target::SliceFramebuffer;
//! use embedded_graphics_core::pixelcolor::Rgb565;
//!
//! // one white light from the upper left, a red plastic material
//! let light = DirectionalLight::<Q14>::white([-0.4, 0.5, 0.77])?;
//! let red = MaterialDesc::classic([1.0, 0.1, 0.1], AmbientSource::Object, 0.1, 0.7, 0.6, 32.0);
//! let lighting = Lighting::<Q14, _, BlinnPhong>::new(light, Material::new(&red)?);
//!
//! // a triangle in screen space (1/16 pixel) with eye-space positions and normals
//! let v = |x: i32, y: i32, n: [f32; 3]| {
//!     ShadeVertex::<Q14>::new([x << SUBPIXEL_BITS, y << SUBPIXEL_BITS], 0, 1, [0.0; 3], n)
//! };
//! let tri = [v(4, 4, [-0.6, 0.6, 0.5]), v(4, 60, [-0.6, -0.6, 0.5]), v(60, 32, [0.7, 0.0, 0.7])];
//!
//! let mut pixels = [Rgb565::BLACK; 64 * 64];
//! let mut fb = SliceFramebuffer::new(&mut pixels, 64, 64)?;
//! Phong::new(&lighting, Linear).draw(&mut fb, None, &tri, &RasterOptions::default());
//! assert_ne!(fb.get(20, 32), Some(Rgb565::BLACK));
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
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

pub mod camera;
pub mod color;
pub mod error;
pub mod gl;
pub mod light;
pub mod lighting;
pub mod material;
pub mod mesh;
pub mod num;
pub mod raster;
#[cfg(feature = "reference")]
pub mod reference;
pub mod render;
pub mod shade;
pub mod standard;
pub mod target;
pub mod vector;

/// The types most programs need, for `use fixshade::prelude::*`.
pub mod prelude {
    pub use crate::color::{GammaTable, OutputColor, Rgb, Transfer};
    pub use crate::error::ParamError;
    pub use crate::light::{
        AnyLight, Attenuation, DirectionalLight, LightColors, PointLight, SpotLight,
    };
    pub use crate::lighting::{
        BlinnPhong, Full, InfiniteViewer, Lambert, Lighting, LinearFog, LocalViewer, NoFog, Phong,
        Terms,
    };
    pub use crate::material::{AmbientSource, Material, MaterialDesc};
    pub use crate::num::{F32Fast, Scalar, Q14, Q30};
    pub use crate::raster::{Cull, RasterOptions};
    pub use crate::shade::{
        Dithered, FlatShading, Gamma, GouraudShading, IncrementalPhongShading, Linear,
        PhongShading, ShadeVertex, Shader, Shading,
    };
    pub use crate::target::{
        BandBuffer, DepthBuffer, DrawTargetAdapter, Framebuffer, SliceFramebuffer,
    };
    pub use crate::vector::Vec3;
    pub use embedded_graphics_core::pixelcolor::RgbColor as _;
}
