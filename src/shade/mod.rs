//! Flat, Gouraud and Phong shading behind one trait, [`Shading`].
//!
//! | mode | lit | interpolated per pixel | catches a highlight inside a triangle |
//! |---|---|---|---|
//! | [`Flat`] | once per triangle, at the centroid | nothing | no (one colour, Mach bands) |
//! | [`Gouraud`] | at the three vertices | encoded colour channels | no (misses or smears it) |
//! | [`Phong`] | at every pixel | normal (and position when the lighting needs it) | yes |
//! | [`IncrementalPhong`] | at every pixel, incrementally (Q14, directional lights, Lambert or Blinn-Phong) | `N·L`, `N·H`, `|N|²` by differences | yes |
//!
//! Every mode takes the same [`ShadeVertex`]es (screen position from the transform
//! stage, eye-space position and unit normal for lighting), works with every
//! number tier and every [`Model`](crate::lighting::Model) (Phong or Blinn-Phong
//! specular), and writes through an [`Encoder`] (plain rounding, ordered dithering
//! or a gamma table).
//!
//! ```
//! use fixshade::prelude::*;
//! use fixshade::raster::{RasterOptions, SUBPIXEL_BITS};
//! use fixshade::shade::{Linear, Phong, ShadeVertex, Shading};
//! use fixshade::target::SliceFramebuffer;
//! use embedded_graphics_core::pixelcolor::Rgb565;
//!
//! let light = DirectionalLight::<Q14>::white([0.0, 0.0, 1.0]).unwrap();
//! let mat = Material::new(&MaterialDesc::classic([1.0, 0.2, 0.2], AmbientSource::Object, 0.1, 0.7, 0.5, 32.0)).unwrap();
//! let lighting = Lighting::<Q14, _, BlinnPhong>::new(light, mat);
//!
//! let v = |x: i32, y: i32, n: [f32; 3]| ShadeVertex::<Q14>::new(
//!     [x << SUBPIXEL_BITS, y << SUBPIXEL_BITS], 0, 1, [0.0; 3], n);
//! let tri = [v(0, 0, [-0.5, -0.5, 0.7]), v(0, 32, [-0.5, 0.5, 0.7]), v(32, 16, [0.6, 0.0, 0.8])];
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 32];
//! let mut fb = SliceFramebuffer::new(&mut pixels, 32, 32).unwrap();
//! let stats = Phong::new(&lighting, Linear).draw(&mut fb, None, &tri, &RasterOptions::default());
//! assert!(stats.pixels > 400);
//! ```

mod encode;
mod flat;
mod gouraud;
mod incremental;
mod phong;

pub use encode::{Dithered, Encoder, Gamma, Linear, CHANNEL_FRAC};
pub use flat::Flat;
pub use gouraud::Gouraud;
pub use incremental::{DirectionalLighting, IncrementalModel, IncrementalPhong};
pub use phong::Phong;

use crate::num::Scalar;
use crate::raster::{DrawStats, RasterOptions, RasterVertex};
use crate::target::{DepthBuffer, Framebuffer};
use crate::vector::{point_from_f32, Point3, Vec3};

/// One vertex of a triangle to shade.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadeVertex<S: Scalar> {
    /// Screen position in pixels with [`SUBPIXEL_BITS`](crate::raster::SUBPIXEL_BITS)
    /// fractional bits, y down.
    pub screen: [i32; 2],
    /// Depth for the depth test (smaller is nearer).
    pub z: u16,
    /// `1/w` for perspective-correct interpolation (any positive scale shared by
    /// the triangle; see [`RasterVertex::inv_w`]).
    pub inv_w: i32,
    /// Eye-space position (used by point and spot lights, a local viewer, fog).
    pub position: Point3<S>,
    /// Eye-space unit normal.
    pub normal: Vec3<S>,
}

impl<S: Scalar> ShadeVertex<S> {
    /// A vertex from `f32` eye-space position and normal (the normal is normalised).
    pub fn new(screen: [i32; 2], z: u16, inv_w: i32, position: [f32; 3], normal: [f32; 3]) -> Self {
        Self {
            screen,
            z,
            inv_w,
            position: point_from_f32::<S>(position),
            normal: Vec3::from_f32(normal).normalize(),
        }
    }

    /// The rasterizer vertex carrying `attrs`.
    #[inline]
    pub fn raster<const N: usize>(&self, attrs: [i32; N]) -> RasterVertex<N> {
        RasterVertex {
            x: self.screen[0],
            y: self.screen[1],
            z: self.z,
            inv_w: self.inv_w,
            attrs,
        }
    }
}

/// A shading method: draws lit triangles into a framebuffer.
pub trait Shading<S: Scalar> {
    /// The pixel colour written.
    type Color;

    /// Rasterizes and shades one triangle (see
    /// [`draw_triangle`](crate::raster::draw_triangle) for coverage, clipping,
    /// culling and depth). Never panics.
    fn draw<F: Framebuffer<Color = Self::Color>>(
        &mut self,
        fb: &mut F,
        depth: Option<&mut DepthBuffer<'_>>,
        tri: &[ShadeVertex<S>; 3],
        opts: &RasterOptions,
    ) -> DrawStats;
}
