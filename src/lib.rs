//! fixshade (crate docs are written at the end of the lighting core).
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
pub mod shade;
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
    pub use crate::vector::Vec3;
    pub use embedded_graphics_core::pixelcolor::RgbColor as _;
}
