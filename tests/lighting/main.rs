//! The lighting equation and the kernels that evaluate it, against the `f64`
//! reference: every tier per term and exponent band, the extremes, attenuation
//! without a constant term, lights placed in world coordinates, and the fast
//! Q14 kernels (`QuadraticPhongShading`, `IncrementalPhongShading`).
//!
//! One test binary (one link, the generic code instantiated once); each module
//! was a test binary of its own, and keeps its name.

mod attenuation_unbounded;
mod incremental_phong;
mod lighting_accuracy;
mod lighting_extremes;
mod quadratic_accuracy;
mod world_lights;
