//! No panic, no wrap, no NaN, for any input (these tests run with overflow
//! checks on: the `test` profile keeps debug assertions): the distance
//! functions over their whole range, every tier's operations at their
//! extremes, drawing at the geometry range, and the inputs the fuzz targets
//! found crashing.
//!
//! One test binary; each module was a test binary of its own, and keeps its
//! name.

mod fuzz_regressions;
mod stability_distance;
mod stability_nan;
mod stability_overflow;
mod stability_span;
