//! Mesh preparation and the per-vertex stage: vertex normals by face averaging,
//! sphere generators (plain, and textured with texture coordinates and
//! tangents: [`TexturedMeshData`]), displacement mapping ([`displace`]),
//! transforms, projection to the rasterizer and near-plane clipping.
//!
//! Everything writes into caller-owned arrays (no allocation) and reports bad
//! sizes, indices and parameters as a [`MeshError`] instead of panicking.
//!
//! # Conventions
//!
//! - **Space**: right-handed; the eye looks down −z with +y up (OpenGL), as in
//!   [`crate::gl`] and the lighting core.
//! - **Winding**: a triangle `[a, b, c]` is front-facing when `a → b → c` runs
//!   counter-clockwise as seen from the side its normal points to, i.e. its
//!   geometric normal is `(b − a) × (c − a)`. Generated spheres wind
//!   counter-clockwise seen from outside. After [`ScreenTransform::project`]
//!   (y down on the screen) front faces are counter-clockwise on the screen,
//!   which is what [`crate::raster::Cull::Back`] keeps.
//! - **Load time vs frame time**: normals and spheres are computed once, in
//!   `f32` (and `f64` where it buys robustness). Matrices are built in `f32` once
//!   per frame ([`Mat4`]) and converted to fixed point ([`FixedMat4`]); the
//!   per-vertex work ([`ScreenTransform::project`], [`EyeTransform`]) is integer
//!   arithmetic with `i64` accumulation.
//!
//! # A frame, end to end
//!
//! ```
//! use fixshade::mesh::*;
//! use fixshade::raster::SUBPIXEL_BITS;
//! // load time: a sphere in static-sized arrays
//! const N: (usize, usize) = icosphere_counts(1);
//! let mut pos = [[0.0f32; 3]; N.0];
//! let mut nrm = [[0.0f32; 3]; N.0];
//! let mut tris = [[0u16; 3]; N.1];
//! icosphere(1, [0.0; 3], 1.0, &mut pos, &mut nrm, &mut tris)?;
//! // per frame: camera 4 units back, 60° field of view
//! let proj = Mat4::perspective(1.047, 1.0, 0.5, 20.0)?;
//! let view = Mat4::translate([0.0, 0.0, -4.0]);
//! let screen = ScreenTransform::new(&proj.mul(&view), Viewport::new(0, 0, 128, 128)?, 0.5)?;
//! let v = screen.project_f32(pos[0]).expect("in front of the near plane");
//! assert!(v.x >= 0 && v.x < 128 << SUBPIXEL_BITS);
//! # Ok::<(), MeshError>(())
//! ```

mod clip;
mod compact;
mod displace;
mod error;
mod matrix;
mod normals;
mod screen;
mod sphere;
mod tangents;
mod textured;
mod torus_knot;

pub use clip::{clip_near, ClipVertex};
pub(crate) use compact::sin_cos;
pub use compact::{Mesh, MeshData, NORMAL_ONE, TEXCOORD_FRAC};
pub use displace::{displace, to_compact, weld_by_position};
pub use error::MeshError;
pub use matrix::Mat4;
pub use normals::{face_normals, normals_to_tier, positions_to_geo16, vertex_normals, Weighting};
pub use screen::{EyeTransform, FixedMat4, ScreenTransform, ScreenVertex, Viewport, INV_W_ONE};
pub use sphere::{icosphere, icosphere_counts, uv_sphere, uv_sphere_counts, MAX_ICOSPHERE_LEVEL};
pub use tangents::{tangents_to_q14, vertex_tangents};
pub use textured::{plane_counts, textured_sphere_counts, TexturedMeshData};
pub use torus_knot::{torus_knot_counts, TorusKnot};
