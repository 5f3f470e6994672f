//! The mesh renderer: the call a firmware makes once per mesh per frame.
//!
//! The frame pipeline, one module per stage:
//!
//! | stage | where | per frame |
//! |---|---|---|
//! | mesh | [`crate::mesh::Mesh`] | in flash: `i16` positions, Q14 normals, `u16` triangles |
//! | vertex stage | `vertex.rs` | transform, project and (flat/Gouraud) light every vertex once, into the caller's vertex cache |
//! | refinement (optional) | [`refine`] | split the silhouette triangles into curved pieces within a budget ([`MeshDraw::new`] with [`DrawOptions::with_refine`]) |
//! | bins | `bins.rs` | cull back faces; sort the visible triangles by the band they start in |
//! | set-up | [`crate::raster`] | 32-bit set-up once per triangle; a triangle crossing a band boundary resumes from a 6-byte record |
//! | spans | [`crate::shade::Kernel`] | the mode's depth-fused span kernel |
//! | framebuffer | [`Bands`](crate::framebuffer::Bands), [`FullFrame`](crate::framebuffer::FullFrame) | a band strip flushed to any `DrawTarget`, or a whole frame in memory |
//!
//! All memory is the caller's ([`MeshDraw`] lists it); nothing is allocated,
//! nothing panics, a buffer too small is a [`RenderError`] before anything is
//! drawn. Within every band a mesh's triangles are drawn in mesh order, meshes
//! in the order given: a banded frame is bit for bit the frame drawn whole.

mod bins;
mod draw;
pub mod refine;
#[cfg(test)]
mod tests;
mod tri;
mod vertex;

pub use draw::{Carry, DrawOptions, MeshBuffers, MeshDraw, MeshMemory};
pub use tri::{draw_triangle, Corner, Triangle};
pub use vertex::CachedVertex;

use crate::error::RenderError;
use crate::framebuffer::{BandView, DrawBand, Layout};

/// The length of the bins slice [`MeshDraw`] needs for a mesh of `triangles`
/// triangles in a frame of `bands` bands: `2·(bands + 1) + triangles` (the
/// band heads, the boundary crossings and one index per visible triangle; with
/// back faces culled about half the triangles of a closed mesh are visible, so
/// a smaller slice often suffices: [`MeshDraw::new`] reports the need).
pub const fn bins_len(triangles: usize, bands: usize) -> usize {
    2 * (bands + 1) + triangles
}
