//! Euler parameters in `hdot verify` (verify/quaternion.rs): the bundled
//! torque-free body whose attitude is a quaternion
//! (derivations/torque-free-quaternion.toml) passes on the particles over
//! several seeds — its angular velocity, angular momentum in B's and in
//! N's axes, moment and kinetic energy, drawn with the parameters on the
//! unit sphere — and a step that gives ω's components in N as if they
//! were B's fails, with the steps built on it.

use hdot_num::verify::{Options, check};

use super::load;

const TEXT: &str = include_str!("../../derivations/torque-free-quaternion.toml");

/// The compared steps of `text` that passed and failed, by name.
fn outcome(text: &str, seed: u64) -> (Vec<String>, Vec<String>) {
    let r = check(&load(text), &Options { draws: 20, seed }).unwrap_or_else(|e| panic!("{e}"));
    let names = |passed: bool| {
        r.steps
            .iter()
            .filter(|s| s.passed == passed)
            .map(|s| s.step.clone())
            .collect::<Vec<_>>()
    };
    (names(true), names(false))
}

#[test]
fn the_quaternion_body_verifies_on_the_particles() {
    for seed in 0..4 {
        let (passed, failed) = outcome(TEXT, seed);
        assert!(failed.is_empty(), "seed {seed}: {failed:?}");
        for step in ["omega_e", "H", "euler", "T", "H_N"] {
            assert!(
                passed.iter().any(|s| s == step),
                "seed {seed}: {step} not compared"
            );
        }
    }
}

#[test]
fn angular_velocity_in_the_wrong_axes_fails() {
    let wrong = TEXT.replace(
        "value = \"angvel(B)\"",
        "value = \"[express(angvel(B), N).x, express(angvel(B), N).y, express(angvel(B), N).z] in B\"",
    );
    assert_ne!(wrong, TEXT);
    let (_, failed) = outcome(&wrong, 0);
    // Everything built on ω fails with it.
    assert_eq!(
        failed.first().map(String::as_str),
        Some("omega_e"),
        "{failed:?}"
    );
    assert!(failed.iter().any(|s| s == "H_N"), "{failed:?}");
}
