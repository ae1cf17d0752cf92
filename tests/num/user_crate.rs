//! What a user's own crate would write (issue 9, item 5): a derivation
//! written here, checked with the library entry point
//! `hdot_num::verify::check(&derivation, &Options)`, and as a proptest
//! property over the random declared bodies of
//! `hdot_num::verify::strategy` (feature `proptest`).

use std::sync::LazyLock;

use hdot_num::verify::strategy::declared_bodies;
use hdot_num::verify::{Options, check, check_bodies};
use hdot_sym::derivation::{Derivation, load_str};
use proptest::prelude::*;

/// A body of any shape turning about a fixed point O, its frame given by
/// the angular velocity: H_O, the moment about O, the momentum, T.
const FIXED_POINT: &str = r#"
title = "A body turning about a fixed point"
source = "test"
[symbols]
constants = ["m", "a", "b", "c", "A", "B", "C", "D", "E", "F"]
time = ["w_1", "w_2", "w_3"]
[[frame]]
name = "K"
angular_velocity = "[w_1, w_2, w_3]"
[[point]]
name = "O"
fixed = true
[[body]]
name = "body"
frame = "K"
point = "O"
mass = "m"
mass_centre = "[a, b, c] in K"
inertia = "inertia(A, B, C, D, E, F)"
[[step]]
name = "H"
value = "inertia(A, B, C, D, E, F) * angvel(K)"
means = "angular_momentum(body, O)"
[[step]]
name = "M"
value = "dt(H)"
means = "moment(body, O)"
[[step]]
name = "p"
value = "m*cross(angvel(K), [a, b, c] in K)"
means = "momentum(body)"
[[step]]
name = "T"
value = "dot(angvel(K), H)/2"
means = "kinetic_energy(body)"
"#;

static GOOD: LazyLock<Derivation> =
    LazyLock::new(|| load_str("fixed-point.toml", FIXED_POINT).unwrap_or_else(|e| panic!("{e}")));

/// The products of inertia entering with a plus sign.
static WRONG: LazyLock<Derivation> = LazyLock::new(|| {
    let text = FIXED_POINT.replace(
        "value = \"inertia(A, B, C, D, E, F) * angvel(K)\"",
        "value = \"inertia(A, B, C, -D, -E, -F) * angvel(K)\"",
    );
    load_str("fixed-point.toml", &text).unwrap_or_else(|e| panic!("{e}"))
});

#[test]
fn the_library_entry_point_checks_a_derivation_written_here() {
    let r = check(&GOOD, &Options { draws: 20, seed: 5 }).unwrap();
    assert!(r.passed(), "{r:#?}");
    assert_eq!(r.steps.len(), 4);
    let r = check(&WRONG, &Options { draws: 20, seed: 5 }).unwrap();
    let failed = r.failed();
    // H and what is built from it; the momentum does not use the tensor.
    assert_eq!(failed, ["H", "M", "T"]);
}

#[test]
fn the_bodies_given_must_match_the_declarations() {
    let e = check_bodies(&GOOD, &[], &Options::default()).unwrap_err();
    assert!(
        e.to_string().contains("0 bodies given for 1 declared"),
        "{e}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        rng_seed: proptest::test_runner::RngSeed::Fixed(11),
        ..ProptestConfig::default()
    })]

    /// For every body the strategy draws (and random motions): the
    /// derived steps equal the particle sums.
    #[test]
    fn every_declared_body_satisfies_the_derivation(
        bodies in declared_bodies(&GOOD),
        seed in any::<u64>(),
    ) {
        let r = check_bodies(&GOOD, &bodies, &Options { draws: 3, seed }).unwrap();
        prop_assert!(r.passed(), "{:?}", r.worst());
    }

    /// … and the wrong tensor fails on every one of them.
    #[test]
    fn the_wrong_tensor_fails_on_every_declared_body(
        bodies in declared_bodies(&WRONG),
        seed in any::<u64>(),
    ) {
        let r = check_bodies(&WRONG, &bodies, &Options { draws: 3, seed }).unwrap();
        prop_assert!(r.steps.iter().any(|s| s.step == "H" && !s.passed));
    }
}
