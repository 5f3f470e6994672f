//! The error of every fallible mesh operation.

use core::fmt;

/// Why a mesh operation was rejected. Nothing is written to the outputs when an
/// error is returned, except where a function documents otherwise.
///
/// ```
/// use fixshade::mesh::{face_normals, MeshError};
/// let pos = [[0.0f32; 3]; 3];
/// let mut out = [[0.0f32; 3]; 1];
/// let err = face_normals(&pos, &[[0, 1, 3]], &mut out).unwrap_err();
/// assert_eq!(err, MeshError::IndexOutOfRange { triangle: 0, index: 3 });
/// assert_eq!(err.to_string(), "triangle 0: vertex index 3 out of range");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum MeshError {
    /// An output (or scratch) slice holds fewer elements than needed.
    BufferTooSmall {
        /// Elements required.
        needed: usize,
        /// Elements provided.
        got: usize,
    },
    /// A triangle refers to a vertex beyond the end of the positions.
    IndexOutOfRange {
        /// Index of the offending triangle.
        triangle: usize,
        /// The vertex index it holds.
        index: u16,
    },
    /// The mesh would need more vertices than a `u16` index can address (65536).
    TooManyVertices {
        /// Vertices the mesh would need.
        needed: usize,
    },
    /// The named parameter is NaN or infinite.
    NotFinite(&'static str),
    /// The named parameter is outside its documented range.
    OutOfRange(&'static str),
    /// The named parameters describe a degenerate configuration (zero-length
    /// direction, parallel vectors, empty volume).
    Degenerate(&'static str),
    /// The mesh lacks the named per-vertex attribute (texture coordinates,
    /// tangents) the operation reads.
    MissingAttribute(&'static str),
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BufferTooSmall { needed, got } => {
                write!(f, "buffer too small: {needed} elements needed, {got} given")
            }
            Self::IndexOutOfRange { triangle, index } => {
                write!(f, "triangle {triangle}: vertex index {index} out of range")
            }
            Self::TooManyVertices { needed } => {
                write!(f, "{needed} vertices exceed the u16 index range")
            }
            Self::NotFinite(p) => write!(f, "{p}: NaN or infinite"),
            Self::OutOfRange(p) => write!(f, "{p}: out of range"),
            Self::Degenerate(p) => write!(f, "{p}: degenerate"),
            Self::MissingAttribute(p) => write!(f, "the mesh has no {p}"),
        }
    }
}

impl core::error::Error for MeshError {}

/// `Ok` when `got ≥ needed`.
pub(crate) fn check_len(needed: usize, got: usize) -> Result<(), MeshError> {
    if got < needed {
        Err(MeshError::BufferTooSmall { needed, got })
    } else {
        Ok(())
    }
}

/// Checks that `v` is finite.
pub(crate) fn finite(name: &'static str, v: f32) -> Result<f32, MeshError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(MeshError::NotFinite(name))
    }
}
