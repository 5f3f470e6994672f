//! Rasterization in 32-bit integer arithmetic: the one clipper, triangle
//! set-up, exact edge walking with a top-left fill rule, and the
//! interpolation of the shading kernels' values across a triangle.
//!
//! # Conventions
//!
//! - **Coordinates**: `x`, `y` in screen pixels with [`SUBPIXEL_BITS`]
//!   fractional bits, `y` pointing down. Pixel `(x, y)` is sampled at its
//!   centre `(x + ½, y + ½)`.
//! - **Fill rule**: top-left. A pixel centre exactly on an edge belongs to the
//!   triangle only if the edge is a top edge (horizontal, triangle below) or a
//!   left edge. Triangles that share an edge (same two vertices) therefore
//!   cover every pixel along it exactly once: a mesh is watertight.
//! - **Winding**: a triangle is *front-facing* when its vertices run
//!   counter-clockwise as seen on the screen (y down), e.g. `(0,0) → (0,10) →
//!   (10,0)`. [`Cull::Back`] drops the others; with [`Cull::None`] both draw.
//! - **Window**: set-up works on vertices inside a window of 2^15 sub-pixels
//!   per axis, `WINDOW_MIN..=WINDOW_MAX` (−512 to 1536 pixels), so that its
//!   products fit 32 bits; a triangle reaching beyond it, or behind a
//!   perspective near plane, is clipped in clip space first, with canonical
//!   cuts so that neighbours stay watertight. Frames up to 1024 × 1024 have a
//!   guard band of at least 512 pixels; nothing beyond 1536 is drawn.
//! - **Depth**: `z` (0 near to 65535 far) is interpolated linearly in screen
//!   space (it is `z/w` under a perspective projection); smaller is nearer; a
//!   pixel passes when `z < stored`.
//!
//! # Arithmetic
//!
//! A triangle's set-up takes one 32-bit division (the reciprocal of its area)
//! and a few dozen 32 × 32 → 32-bit multiplications; edges are walked column
//! by column without division, exactly. Attribute planes carry 14-bit
//! barycentric coefficients with a bounded error ([`interp`]). Clipping builds
//! 64-bit values from 32-bit operations (no 64-bit routine is linked).

pub(crate) mod clip;
mod edge;
pub mod interp;
pub(crate) mod setup;

pub(crate) use crate::num::ATTR_FRAC;
pub(crate) use edge::Walker;
pub(crate) use setup::ClampTo;
pub(crate) use setup::{Plane, Setup};

pub(crate) use crate::camera::SUBPIXEL_BITS;

/// The smallest sub-pixel coordinate set-up works on: −512 pixels.
pub(crate) const WINDOW_MIN: i32 = -(1 << 13);
/// The largest sub-pixel coordinate set-up works on: just below 1536 pixels
/// (`WINDOW_MAX − WINDOW_MIN = 2^15 − 1`).
pub(crate) const WINDOW_MAX: i32 = (3 << 13) - 1;

/// Length of the sub-spans whose ends are interpolated perspective-correctly
/// under a perspective projection (8 pixels; see [`interp`]). Crate-private
/// (issue 18): the value is stated in the [`interp`] docs.
pub(crate) const PERSPECTIVE_SPAN: usize = 8;

/// Which triangles are skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Cull {
    /// Draw both windings.
    #[default]
    None,
    /// Skip back faces: vertices clockwise as seen on the screen.
    Back,
    /// Skip front faces: vertices counter-clockwise as seen on the screen.
    Front,
}

impl Cull {
    /// Whether a triangle facing the viewer (`front`) or not is skipped.
    #[inline(always)]
    pub(crate) fn skips(self, front: bool) -> bool {
        match self {
            Cull::None => false,
            Cull::Back => !front,
            Cull::Front => front,
        }
    }
}
