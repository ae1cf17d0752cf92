//! Fuzz targets on the stable toolchain, driven by proptest: random and
//! half-valid input for the derivation parser and evaluator, the scene
//! parsers (numeric and simulation) and the CSV reader. Each input must be
//! accepted or refused with an error; a panic, an abort or a hang is a
//! failure. proptest shrinks a failing input to a small one and records
//! its seed in `tests/fuzz/*.proptest-regressions`.
//!
//! CI runs a few dozen cases per target (seconds). A long run:
//!
//! ```text
//! PROPTEST_CASES=100000 cargo test --release -p hdot-tests --test fuzz
//! ```
//!
//! `corpus` keeps the cases of issue 13 as plain tests.

mod corpus;
mod derivation;
mod files;
mod hostile;

use proptest::test_runner::Config;

/// The proptest configuration of every target: `PROPTEST_CASES` cases
/// (64 when unset, as in CI), no forking.
pub fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(64);
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}
