//! The span stage: a set-up triangle's rows in a band, the depth test of
//! each row's run of pixels, and the pixel write.
//!
//! - [`rows`] walks the rows: the edge walker's columns, the depth plane, and
//!   the kernel's values along each run.
//! - `depth` tests and writes a run ([`Fill`](crate::shade::Fill)): a kernel
//!   only computes colours.
//!
//! The pixel loops are the frame's hottest code: each short, doing one thing.

mod depth;
mod rows;

pub(crate) use rows::rows;
