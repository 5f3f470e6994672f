//! Surface detail with any parameters (issue 21, item 7), on small spheres
//! (texture-mapped: a seam of duplicated vertices; and seamless) in any
//! orientation, orthographic or perspective:
//!
//! - textures of any size (1 to 16 texels a side), wrap, filter, format
//!   (Rgb565, Gray8, a palette of any length with any indices) and texels,
//!   sampled at any coordinates and drawn with `GouraudShading.textured(…)`;
//! - normal maps of any `i16` texels: `NormalMap::new` accepts them or
//!   returns `NotUnit`, `normalize_texels` makes every non-zero map
//!   acceptable, and every accepted map is drawn by the fast and the general
//!   normal-mapping kernels;
//! - `displace` with any height texture and scale, then `to_compact`, drawn;
//! - silhouette refinement with any budget and threshold: on the closed
//!   spheres no pixel inside the outline is left uncovered (the frame with
//!   back faces culled covers what the frame without culling covers, away
//!   from the outline), whatever the budget.
//!
//! Every frame is drawn whole and in bands: the same pixels. No panic, no
//! wrap (overflow checks on).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| fixshade_fuzz::surface::run(data));
