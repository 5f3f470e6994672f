//! Checks shared by the mesh operations (the error type is
//! [`MeshError`](crate::error::MeshError)).

use crate::error::MeshError;

/// `Ok` when `got ≥ needed` (a `const fn`: [`Mesh`](super::Mesh)'s
/// constructors use it).
pub(crate) const fn check_len(
    which: &'static str,
    needed: usize,
    got: usize,
) -> Result<(), MeshError> {
    if got < needed {
        Err(MeshError::BufferTooSmall { which, needed, got })
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
