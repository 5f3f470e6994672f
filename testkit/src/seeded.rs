//! Deterministic property tests: every `proptest!` block of the crate (the
//! integration tests and the library's unit tests) takes its configuration
//! from [`config`], so `cargo test` draws the same cases on every run and on
//! every machine, and CI fails only on a changed tree.
//!
//! - Each block has its own fixed seed (a hash of the name it passes).
//! - Failures are still kept: proptest's regression files
//!   (`tests/proptest-regressions/` for the integration tests: proptest
//!   names a file after the source file, beside the directory of the test
//!   binary's `main.rs`; `proptest-regressions/` for `src/`) are replayed
//!   first, and a new failure is written there as a `cc` line (the failing
//!   case's own seed): commit it with the fix.
//! - Fresh random cases, to look for new failures: `FIXSHADE_PROPTEST_FRESH=1
//!   cargo test` (a new random seed per test and run), or one chosen seed with
//!   proptest's own `PROPTEST_RNG_SEED=<u64>`; `PROPTEST_CASES=<n>` sets the
//!   number of cases (both applied by the `proptest!` macro over this
//!   configuration).

#![allow(dead_code)]

use proptest::test_runner::{Config, RngSeed};

/// The environment variable that asks for fresh random cases (any value but
/// empty or `0`).
pub const FRESH: &str = "FIXSHADE_PROPTEST_FRESH";

/// The configuration of the property tests of block `name`: `cases` cases
/// drawn from the block's fixed seed (fresh random ones with
/// `FIXSHADE_PROPTEST_FRESH=1`), proptest's failure persistence on.
pub fn config(name: &str, cases: u32) -> Config {
    let fresh = std::env::var_os(FRESH).is_some_and(|v| !v.is_empty() && v != "0");
    Config {
        cases,
        rng_seed: if fresh {
            RngSeed::Random
        } else {
            RngSeed::Fixed(seed_of(name))
        },
        // proptest's defaults: the regression files kept and replayed
        ..Config::default()
    }
}

/// The fixed seed of a block: FNV-1a of its name.
pub fn seed_of(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
