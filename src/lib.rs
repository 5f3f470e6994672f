//! fixshade (work in progress; crate docs are written with the lighting core).
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![warn(
    missing_debug_implementations,
    missing_copy_implementations,
    trivial_casts,
    rustdoc::broken_intra_doc_links
)]

pub mod num;
pub mod raster;
pub mod target;
pub mod vector;
