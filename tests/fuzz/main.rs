//! Fuzz targets on the stable toolchain, driven by proptest: random and
//! half-valid input for the derivation parser and evaluator, the scene
//! parsers (numeric and simulation) and the CSV reader. Each input must be
//! accepted or refused with an error; a panic, an abort or a hang is a
//! failure. proptest shrinks a failing input to a small one and prints it;
//! a failure worth keeping becomes a plain test in `corpus`.
//!
//! CI runs a few dozen cases per target (seconds), always the same ones
//! (one fixed seed, [`hdot_tests::proptest_config`]). A long run with a
//! new seed:
//!
//! ```text
//! PROPTEST_RNG_SEED=$RANDOM PROPTEST_CASES=100000 cargo test --release -p hdot-tests --test fuzz
//! ```
//!
//! `corpus` keeps the cases of issue 13 as plain tests.

mod corpus;
mod derivation;
mod files;
mod hostile;

use proptest::test_runner::Config;

/// The proptest configuration of every target: 64 cases from the fixed
/// seed unless `PROPTEST_CASES` and `PROPTEST_RNG_SEED` say otherwise, no
/// failure files.
pub fn config() -> Config {
    Config {
        failure_persistence: None,
        ..hdot_tests::proptest_config(64)
    }
}
