//! The mesh renderer around the rasterizer: mesh generators and the vertex
//! stage, meshes through any transform, frames split into bands or among
//! several renderers, framebuffers and their errors, silhouette refinement.
//!
//! One test binary; each module was a test binary of its own, and keeps its
//! name.

mod band_renderers;
mod framebuffer_pieces;
mod mesh_geometry;
mod mesh_pipeline;
mod mesh_robust;
mod render_refine;
mod target_framebuffers;
