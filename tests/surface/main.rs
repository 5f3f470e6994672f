//! Surface detail: texture mapping, normal mapping (hostile texels included)
//! and per-pixel modes composed with both, against `f64` evaluations of the
//! same methods.
//!
//! One test binary; each module was a test binary of its own, and keeps its
//! name.

mod normal_map_texels;
mod normal_mapping;
mod texture_mapping;
mod textured_perpixel;
