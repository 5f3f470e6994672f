//! The span stage: a set-up triangle's rows in a band, the depth test of
//! each row's run of pixels, and the pixel write.
//!
//! - [`rows`] walks the rows: the edge walker's columns, the depth plane, and
//!   the kernel's values along each run (screen-linear planes, or
//!   perspective-correct sub-spans of
//!   [`PERSPECTIVE_SPAN`](crate::raster::PERSPECTIVE_SPAN) pixels).
//! - `depth` tests and writes a run. A kernel that knows its run's colours
//!   in a simple form ([`Fill`](crate::shade::Fill): one colour, a rounded
//!   5-6-5 ramp) gets them written by the stage's own loops with the depth
//!   test fused in (one pass over the pixels); every other run is
//!   depth-tested first and the kernel shades each passing part
//!   ([`Kernel::span`](crate::shade::Kernel::span)), so that a kernel only
//!   computes colours.
//!
//! The pixel loops are the frame's hottest code: a place of their own, where
//! each loop is short and does one thing.

mod depth;
mod rows;

pub(crate) use rows::rows;
