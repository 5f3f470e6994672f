//! Meshes: the compact format the renderer reads from flash ([`Mesh`],
//! [`MeshData`]: `i16` positions, Q14 normals, `u16` triangles, optional
//! texture coordinates and tangents), `const fn` generators (UV spheres,
//! textured spheres and planes, torus knots), and load-time preparation:
//! vertex normals by face averaging, tangents, displacement mapping
//! ([`displace`]) and conversion to the compact format ([`to_compact`]).
//!
//! Everything writes into caller-owned arrays and reports bad sizes, indices
//! and parameters as a [`MeshError`](crate::error::MeshError), never panicking.
//!
//! # Conventions
//!
//! - **Space**: right-handed; the eye looks down −z with +y up (OpenGL), as in
//!   [`crate::lighting::gl`] and the lighting core.
//! - **Winding**: `[a, b, c]` faces the side from which `a → b → c` is
//!   counter-clockwise (normal `(b − a) × (c − a)`); generated meshes face
//!   outwards, and [`crate::raster::Cull::Back`] keeps front faces.
//! - **Load time vs frame time**: normals, tangents and generated meshes are
//!   computed once in `f32` (`f64` where it buys robustness) or at compile
//!   time; the per-frame work is [`crate::render`]'s vertex stage.
//!
//! ```
//! use fixshade::mesh::*;
//! // load time: a sphere in static-sized arrays
//! const N: (usize, usize) = icosphere_counts(1);
//! let mut pos = [[0.0f32; 3]; N.0];
//! let mut nrm = [[0.0f32; 3]; N.0];
//! let mut tris = [[0u16; 3]; N.1];
//! icosphere(1, [0.0; 3], 1.0, &mut pos, &mut nrm, &mut tris)?;
//! assert_eq!(tris.len(), 80);
//! # Ok::<(), fixshade::error::MeshError>(())
//! ```

mod compact;
mod displace;
mod normals;
mod sphere;
mod tangents;
mod textured;
mod torus_knot;
mod uv;

pub use compact::{Mesh, MeshData, NORMAL_ONE, TEXCOORD_FRAC};
pub use displace::{displace, to_compact};
pub use normals::{face_normals, vertex_normals, Weighting};
pub use sphere::{icosphere, icosphere_counts, uv_sphere_counts};
pub use tangents::vertex_tangents;
pub use textured::{plane_counts, textured_sphere_counts, TexturedMeshData};
pub use torus_knot::TorusKnot;
