//! Code shared by fixshade's integration tests, its benchmark, its examples and
//! its host harnesses (`conformance/`, `measure/accuracy/`), in one place instead
//! of files included by `#[path]`. Not published.
//!
//! It depends on `fixshade` as any user does: the types it
//! hands out are those of the crate the tests see. The library's own unit tests
//! (`src/`) are compiled against another instance of `fixshade`, so they share
//! only what passes no `fixshade` type: [`seeded`].

pub mod reference;
pub mod render;
pub mod scenes;
pub mod seeded;
pub mod support;
pub mod surface;
pub mod surface_scenes;
pub mod worst_case;
