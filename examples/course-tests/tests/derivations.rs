//! The course's derivations under test — the review loop of a lecturer's
//! own crate (docs/user-crate.md):
//!
//! - every expectation of every file holds;
//! - for random bodies with the declared symmetry (proptest), every step
//!   that says what it means equals the particle sums;
//! - the derived forms of every file are an insta snapshot, so that a
//!   change of a derivation shows in `cargo insta review` as a diff of its
//!   equations in textbook form.

use std::path::{Path, PathBuf};
use std::sync::LazyLock;

use hdot_num::verify::strategy::declared_bodies;
use hdot_num::verify::{Options, check_bodies};
use hdot_sym::derivation::{Derivation, load};
use hdot_sym::render::{Format, render};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

/// The course's derivation files, in name order.
fn files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    v.sort();
    assert!(!v.is_empty(), "no derivations in {}", dir.display());
    v
}

/// Every derivation, loaded once (a file that does not load fails with
/// its file:line:column).
static DERIVATIONS: LazyLock<Vec<Derivation>> = LazyLock::new(|| {
    files()
        .iter()
        .map(|p| load(p).unwrap_or_else(|e| panic!("{e}")))
        .collect()
});

#[test]
fn every_expectation_holds() {
    for d in DERIVATIONS.iter() {
        let failed: Vec<String> = d
            .failures()
            .iter()
            .map(|(s, c)| format!("{s}.{}: derived − expected = {}", c.component, c.difference))
            .collect();
        assert!(failed.is_empty(), "{}: {failed:#?}", d.path);
    }
}

/// The derived forms, one snapshot per file (`tests/snapshots/`): review a
/// change with `cargo insta review`.
#[test]
fn derived_forms() {
    for d in DERIVATIONS.iter() {
        insta::assert_snapshot!(d.name.clone(), render(d, Format::Unicode));
    }
}

/// For random bodies with each file's declared symmetry (one per
/// `[[body]]`) and random motions, every step that says what it means
/// equals the particle sums of exactly those bodies; a failure shrinks to
/// a small body.
#[test]
fn every_declared_body_satisfies_every_derivation() {
    for d in DERIVATIONS.iter() {
        let mut runner = TestRunner::new(Config {
            cases: 32,
            rng_seed: RngSeed::Fixed(0),
            failure_persistence: None,
            ..Config::default()
        });
        runner
            .run(&(declared_bodies(d), any::<u64>()), |(bodies, seed)| {
                let r = check_bodies(d, &bodies, &Options { draws: 3, seed }).unwrap();
                prop_assert!(!r.steps.is_empty(), "no step says what it means");
                prop_assert!(r.passed(), "{:?}", r.worst());
                Ok(())
            })
            .unwrap_or_else(|e| panic!("{}: {e}", d.path));
    }
}
