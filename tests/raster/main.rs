//! The rasterizer through the per-triangle front (`render::draw_triangle`):
//! fill rule and coverage, perspective-correct interpolation, the precision of
//! interpolated values, any input without a panic or a write outside the frame,
//! and watertight meshes.
//!
//! One test binary; each module was a test binary of its own, and keeps its
//! name.

mod raster_fill;
mod raster_perspective;
mod raster_precision;
mod raster_robust;
mod raster_watertight;
