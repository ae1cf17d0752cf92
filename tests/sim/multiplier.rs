//! The multiplier form of first-order derived models
//! (systems/derived/multiplier.rs, the scene's `constraint_matrix`,
//! `constraint_bias` and `dependent_speeds`): a pendulum written for this
//! test in Cartesian coordinates (tests/sim/holonomic/), Kane's equations
//! in both speeds before the constraint, M u̇ − f = A_cᵀ λ with
//! A_c u̇ + b = 0 solved at each evaluation. The dependent speed is solved
//! from A_c u = 0 at the start, both constraints stay at round-off along
//! the run, the energy is conserved and the motion is the simple
//! pendulum's (integrated in tests/sim/holonomic.rs); bad declarations are
//! refused at their field.

use std::path::PathBuf;

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::{Method, SimError, Step};
use hdot_tests::repo_root;

use super::holonomic::{G, L, X0, refusal, simple_pendulum};

fn scene_path() -> PathBuf {
    repo_root().join("tests/sim/holonomic/sim-pendulum-xy-multiplier.toml")
}

/// The test's scene with each `from` replaced by its `to` (which must be
/// there).
fn scene_with_all(edits: &[(&str, &str)]) -> Result<Scene, SimError> {
    let mut text = std::fs::read_to_string(scene_path()).expect("the test's scene");
    for (from, to) in edits {
        assert!(text.contains(from), "the scene has no `{from}`");
        text = text.replace(from, to);
    }
    Scene::parse(&text, &scene_path())
}

fn scene_with(from: &str, to: &str) -> Result<Scene, SimError> {
    scene_with_all(&[(from, to)])
}

/// The start: y from x² + y² = L² (below the pivot, from the guess), and
/// the dependent speed u₂ = −x u₁ / y from 2x u₁ + 2y u₂ = 0.
#[test]
fn the_dependent_speed_is_solved_at_the_start() {
    let u1 = 0.5;
    let scene = scene_with("u_1 = 0.0", &format!("u_1 = {u1}")).expect("scene");
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    assert_eq!(ds.state_names(), ["x", "y", "u_1", "u_2"]);
    let y = -(L * L - X0 * X0).sqrt();
    assert!(
        (ds.y0[1] - y).abs() <= 4.0 * f64::EPSILON * L,
        "y0 = {:?}",
        ds.y0
    );
    let u2 = -X0 * u1 / y;
    assert_eq!(ds.y0[2], u1);
    assert!(
        (ds.y0[3] - u2).abs() <= 8.0 * f64::EPSILON * u1,
        "u_2 = {}, want {u2}",
        ds.y0[3]
    );
    let a = ds.model.velocity_residual(0.0, &ds.y0);
    assert!(a[0].abs() <= 16.0 * f64::EPSILON * L * u1, "A_c u = {a:?}");
}

/// Along the run the configuration and velocity constraints stay at
/// round-off (both projected after each step), the energy is conserved to
/// the tolerance, and the motion is the simple pendulum's from rest at
/// θ₀ = asin(x₀/L): x = L sin θ, u₁ = L cos θ θ̇.
#[test]
fn the_multiplier_form_moves_as_the_simple_pendulum() {
    let tol = 1e-8;
    let scene = Scene::from_file(&scene_path()).expect("scene");
    let req = Request {
        method: Some(Method::Dop853),
        step: Some(Step::Tolerance(tol)),
        ..Request::default()
    };
    let plan = run::plan(&scene, &req).expect("plan");
    let r = run::run(&scene, &plan, &mut Output::default()).expect("run");
    let c = r.constraints.as_ref().expect("constraints reported");
    assert_eq!(c.dependent, ["y"]);
    let round_off = 16.0 * f64::EPSILON * L * L;
    assert!(
        c.max_residual <= round_off,
        "max |f| = {:e}",
        c.max_residual
    );
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    let y = &r.final_state;
    let scale = (G * L).sqrt();
    let a = ds.model.velocity_residual(r.plan.t_end, y);
    assert!(
        a[0].abs() <= 16.0 * f64::EPSILON * L * scale,
        "A_c u = {a:?} at the end"
    );
    let e = r.drifts.iter().find(|d| d.name == "E").expect("E reported");
    assert!(e.relative < 1e2 * tol, "energy drifts by {:e}", e.relative);
    let (th, w) = simple_pendulum(r.plan.t_end, 100_000);
    let (x, u1) = (L * th.sin(), L * th.cos() * w);
    assert!((y[0] - x).abs() < 1e3 * tol * L, "x = {} vs {x}", y[0]);
    assert!(
        (y[2] - u1).abs() < 1e3 * tol * scale,
        "u_1 = {} vs {u1}",
        y[2]
    );
}

/// A dependent speed given a start value, a constraint matrix without its
/// bias, a dependent speed that is not a speed, and one where the
/// constraint does not fix it (y = 0 makes ∂(A_c u)/∂u₂ = 2y vanish).
#[test]
fn bad_multiplier_declarations_are_refused_at_their_field() {
    let (field, message) = refusal(scene_with("u_1 = 0.0", "u_1 = 0.0, u_2 = 1.0").unwrap_err());
    assert_eq!(field, "initial");
    assert!(message.contains("`u_2` is a dependent speed"), "{message}");
    let (field, _) = refusal(scene_with("constraint_bias = \"A_c_rate\"\n", "").unwrap_err());
    assert_eq!(field, "derivation.constraint_bias");
    let (field, message) = refusal(
        scene_with(
            "dependent_speeds = [\"u_2\"]",
            "dependent_speeds = [\"u_3\"]",
        )
        .unwrap_err(),
    );
    assert_eq!(field, "derivation.dependent_speeds");
    assert!(message.contains("`u_3` is not a speed"), "{message}");
    let (field, message) = refusal(
        scene_with_all(&[
            (
                "holonomic = [\"rod\"]\ndependent_coordinates = [\"y\"]\n",
                "",
            ),
            ("x = 0.6, y = -0.7", "x = 1.0, y = 0.0"),
        ])
        .unwrap_err(),
    );
    assert_eq!(field, "derivation.dependent_speeds");
    assert!(message.contains("cannot be solved"), "{message}");
}
