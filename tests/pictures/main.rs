//! The tests that compare pictures: the reference scenes against the `f64`
//! model (`golden`), the depth test, the mesh renderer's frames banded and
//! whole, and the per-triangle front against the mesh renderer, bit for bit.
//! CI runs them once more built for size (`cargo test --profile test-size
//! --test pictures`: at opt-level "z" the crate compiles its size variants).
//!
//! One test binary; each module was a test binary of its own, and keeps its
//! name.

mod golden;
mod one_pipeline;
mod raster_depth;
mod render_frame;
