//! Tests of hdot-num. One module per source module.

// Named proptest strategies (particle_cloud, rigid_body, angular_velocity…).
mod strategies;
// Inertia invariant, parallel axes, principal axes.
mod inertia;
// Primitives: analytic vs discretised mass properties, convergence.
mod discretize;
// Particle sums: determinism, kinetics against rigid-body formulas.
mod sums;
// Bad input: CSV, bodies.
mod bad_input;
// Scenes and worked problems.
mod scenes;
// A scene of many bodies against the sums of its bodies.
mod many_bodies;
// Strict scene input, no false alarms (issue 13).
mod strict_scenes;
// Convergence sweeps and the cheapest discretisation.
mod convergence;
// insta snapshots of the reports.
mod snapshots;
// The polynomial tape evaluator.
mod eval;
// Derived equations against particle sums (hdot verify).
mod verify;
// Verification from declarations.
mod verify_declared;
// Conserved steps and steps labelled 0, checked along the file's equations.
mod verify_claims;
// Reactions at declared supports, from particle sums and their equilibrium.
mod verify_supports;
// ∂T/∂q, abbreviations with a meaning, conditions fixing a constant.
mod verify_meanings;
// Generalized quantities under [motion]'s rules (constrained partial velocities).
mod constrained;
// Kane's generalized active and inertia forces on the particles.
mod verify_kane;
// Rolling constraints met by the draw, Kane's forces of the disk and the bicycles.
mod verify_rolling;
// verify/linearized.rs: the linearized Kane equations and their matrices, on the particles.
mod verify_linearized;
// verify/expressed.rs: a frame's vector in another's axes, from the drawn rotations.
mod verify_expressed;
// A new user's trial: line bodies along x or y, equal moments, shared symbols, conserved along Kane's rates.
mod verify_trials;
// verify/quaternion.rs: frames turned by Euler parameters, drawn on the unit sphere.
mod verify_quaternion;
// verify/speeds.rs: draws kept away from the kinematic equations' singular angles.
mod verify_singular_draws;
// Line bodies and point masses: moments of inertia declared zero.
mod line_bodies;
// The bundled multibody derivations' steps on the particles (issue 24, item 7).
mod verify_bundled;
// Mutated derivations rejected by verification (issue 9).
mod mutation;
// A user's own crate: check(&derivation, &Options) and verify::strategy.
mod user_crate;

/// A derivation written in a test, loaded or the test fails with its
/// diagnostic.
fn load(text: &str) -> hdot_sym::derivation::Derivation {
    hdot_sym::derivation::load_str("test.toml", text).unwrap_or_else(|e| panic!("{e}"))
}

/// `hdot verify` of a derivation written in a test: the steps it
/// compared, and those of them that failed.
fn verified(text: &str, options: &hdot_num::verify::Options) -> (Vec<String>, Vec<String>) {
    let r = hdot_num::verify::check(&load(text), options).unwrap_or_else(|e| panic!("{e}"));
    let names = |pass: bool| {
        r.steps
            .iter()
            .filter(|s| s.passed == pass)
            .map(|s| s.step.clone())
            .collect::<Vec<_>>()
    };
    let failed = names(false);
    let mut compared = names(true);
    compared.extend(failed.iter().cloned());
    (compared, failed)
}
