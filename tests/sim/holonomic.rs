//! Configuration constraints kept by the integrator
//! (systems/derived/holonomic.rs, the scene's `holonomic`,
//! `dependent_coordinates` and `project`): a pendulum written for this
//! test in two coordinates, the bob's x and the rod's angle θ, with
//! x = L sin θ (tests/sim/holonomic/), θ solved by Newton's method at the
//! start, the residual kept at
//! round-off with the projection and growing without, the energy
//! conserved, and the motion against the simple pendulum θ̈ = −(g/L) sin θ
//! integrated here; a guess with no solution near it, and a singular
//! Jacobian, refused naming the field and its line.

use std::path::PathBuf;

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::{Method, SimError, Step};
use hdot_tests::repo_root;

fn scene_path() -> PathBuf {
    repo_root().join("tests/sim/holonomic/sim-pendulum-x-theta.toml")
}

fn scene_text() -> String {
    std::fs::read_to_string(scene_path()).expect("the test's scene")
}

/// The test's scene with `from` replaced by `to` (which must be there).
fn scene_with(from: &str, to: &str) -> Result<Scene, SimError> {
    let text = scene_text();
    assert!(text.contains(from), "the scene has no `{from}`");
    Scene::parse(&text.replace(from, to), &scene_path())
}

fn run_scene(scene: &Scene, tol: f64) -> run::Report {
    let req = Request {
        method: Some(Method::Dop853),
        step: Some(Step::Tolerance(tol)),
        ..Request::default()
    };
    let plan = run::plan(scene, &req).expect("plan");
    run::run(scene, &plan, &mut Output::default()).expect("run")
}

/// The scene's constants and start.
pub(crate) const G: f64 = 9.81;
pub(crate) const L: f64 = 1.0;
pub(crate) const X0: f64 = 0.6;

/// The simple pendulum θ̈ = −(g/L) sin θ from rest at θ₀ = asin(x₀/L),
/// by the classical Runge–Kutta method: (θ, θ̇) at `t_end`.
pub(crate) fn simple_pendulum(t_end: f64, steps: usize) -> (f64, f64) {
    let f = |th: f64, w: f64| (w, -(G / L) * th.sin());
    let h = t_end / steps as f64;
    let (mut th, mut w) = ((X0 / L).asin(), 0.0);
    for _ in 0..steps {
        let (a1, b1) = f(th, w);
        let (a2, b2) = f(th + a1 * h / 2.0, w + b1 * h / 2.0);
        let (a3, b3) = f(th + a2 * h / 2.0, w + b2 * h / 2.0);
        let (a4, b4) = f(th + a3 * h, w + b3 * h);
        th += (a1 + 2.0 * a2 + 2.0 * a3 + a4) * h / 6.0;
        w += (b1 + 2.0 * b2 + 2.0 * b3 + b4) * h / 6.0;
    }
    (th, w)
}

/// The dependent coordinate starts on the constraint: from the guess
/// θ = 0.5, Newton's method finds θ = asin(x/L) to round-off, and x and
/// the speed are left as given; a guess beyond π/2 finds the other root,
/// π − asin(x/L).
#[test]
fn the_dependent_coordinate_is_solved_at_the_start() {
    let scene = Scene::from_file(&scene_path()).expect("scene");
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    assert_eq!(ds.state_names(), ["x", "theta", "u_1"]);
    let want = (X0 / L).asin();
    assert_eq!(ds.y0[0], X0);
    assert!(
        (ds.y0[1] - want).abs() <= 4.0 * f64::EPSILON * L,
        "y0 = {}, want {want}",
        ds.y0[1]
    );
    assert_eq!(ds.y0[2], 0.0);
    let f = ds.model.constraint_residual(0.0, &ds.y0);
    assert!(f[0].abs() <= 8.0 * f64::EPSILON * L, "f = {f:?}");
    let above = scene_with("theta = 0.5", "theta = 2.5").expect("scene");
    let SceneKind::Derived(ds) = &above.kind else {
        panic!("a derived scene")
    };
    let other = std::f64::consts::PI - want;
    assert!(
        (ds.y0[1] - other).abs() <= 4.0 * f64::EPSILON * other,
        "θ0 = {}, want {other}",
        ds.y0[1]
    );
}

/// With the projection (the default) the residual stays at round-off
/// along the run, each step's correction is the integration error (small
/// but not zero); without it the residual grows measurably — to the
/// integration error, orders of magnitude above round-off. The energy is
/// conserved either way, and the motion is the simple pendulum's.
#[test]
fn the_projection_keeps_the_constraint_and_without_it_it_drifts() {
    let tol = 1e-7;
    let kept = run_scene(&Scene::from_file(&scene_path()).expect("scene"), tol);
    let c = kept.constraints.as_ref().expect("constraints reported");
    assert_eq!(c.steps, ["rod"]);
    assert_eq!(c.dependent, ["theta"]);
    assert!(c.projected);
    let round_off = 16.0 * f64::EPSILON * L;
    assert!(
        c.max_residual <= round_off,
        "projected: max |f| = {:e}",
        c.max_residual
    );
    assert!(
        c.max_correction > 0.0 && c.max_correction < 1e3 * tol,
        "projected: largest correction {:e}",
        c.max_correction
    );
    let free = run_scene(
        &scene_with(
            "dependent_coordinates = [\"theta\"]",
            "dependent_coordinates = [\"theta\"]\nproject = false",
        )
        .expect("scene"),
        tol,
    );
    let d = free.constraints.as_ref().expect("constraints reported");
    assert!(!d.projected);
    assert_eq!(d.max_correction, 0.0);
    assert!(
        d.max_residual > 1e3 * round_off && d.max_residual < 1e3 * tol * L,
        "not projected: max |f| = {:e}",
        d.max_residual
    );
    for r in [&kept, &free] {
        let e = r.drifts.iter().find(|d| d.name == "E").expect("E reported");
        assert!(e.relative < 1e2 * tol, "energy drifts by {:e}", e.relative);
    }
    // The report prints it.
    let text = kept.to_string();
    assert!(text.contains("constraint:  max |f(q)| = "), "{text}");
    assert!(text.contains("theta projected onto f = 0"), "{text}");
    // Against the simple pendulum (RK4 at 10⁵ steps: its error ≈ 1e-13).
    let (th, w) = simple_pendulum(kept.plan.t_end, 100_000);
    let y = &kept.final_state;
    let (x, u1) = (L * th.sin(), L * th.cos() * w);
    let scale = (G * L).sqrt();
    assert!((y[0] - x).abs() < 1e3 * tol * L, "x = {} vs {x}", y[0]);
    assert!((y[1] - th).abs() < 1e3 * tol, "θ = {} vs {th}", y[1]);
    assert!(
        (y[2] - u1).abs() < 1e3 * tol * scale,
        "u_1 = {} vs {u1}",
        y[2]
    );
}

/// The field and line of a refused scene, and its message.
pub(crate) fn refusal(e: SimError) -> (String, String) {
    match e {
        SimError::BadField { field, message, .. } => (field, message),
        e => panic!("not a field's error: {e}"),
    }
}

/// No θ with L sin θ = x when |x| > L: "no solution near the initial
/// guess", naming the dependent coordinate's field and its line; and a
/// guess where ∂f/∂θ = −L cos θ vanishes (to round-off, against
/// ∂f/∂x = 1): the Jacobian is singular there.
#[test]
fn a_constraint_without_a_solution_near_the_guess_is_refused() {
    let line = scene_text()
        .lines()
        .position(|l| l.starts_with("coordinates = "))
        .expect("the coordinates' line")
        + 1;
    let (field, message) = refusal(scene_with("x = 0.6", "x = 1.5").unwrap_err());
    assert_eq!(field, "initial.coordinates.theta");
    assert!(message.starts_with(&format!("line {line}: ")), "{message}");
    assert!(
        message.contains("no solution near the initial guess (theta = 0.5)"),
        "{message}"
    );
    let half_pi = format!("theta = {:?}", std::f64::consts::FRAC_PI_2);
    let (field, message) = refusal(scene_with("theta = 0.5", &half_pi).unwrap_err());
    assert_eq!(field, "initial.coordinates.theta");
    assert!(
        message.contains(&format!("singular at {half_pi}")),
        "{message}"
    );
}

/// Bad declarations, each refused at its field: constraints without
/// dependent coordinates, a dependent coordinate that is not one, a
/// constraint with a speed in it, a step that does not exist, `project`
/// without constraints, and dependent speeds that do not come from the
/// constraint's rate (θ̇ = u₁/L instead of u₁/(L cos θ)).
#[test]
fn bad_constraint_declarations_are_refused_at_their_field() {
    let cases = [
        (
            "dependent_coordinates = [\"theta\"]",
            "",
            "derivation.holonomic",
            "dependent coordinates",
        ),
        (
            "dependent_coordinates = [\"theta\"]",
            "dependent_coordinates = [\"z\"]",
            "derivation.dependent_coordinates",
            "not a coordinate",
        ),
        (
            "dependent_coordinates = [\"theta\"]",
            "dependent_coordinates = [\"theta\", \"x\"]",
            "derivation.dependent_coordinates",
            "one dependent coordinate per constraint",
        ),
        (
            "holonomic = [\"rod\"]",
            "holonomic = [\"E\"]",
            "derivation.holonomic",
            "in the coordinates (and constants) only",
        ),
        (
            "holonomic = [\"rod\"]",
            "holonomic = [\"nothing\"]",
            "derivation.holonomic",
            "no step named `nothing`",
        ),
        (
            "holonomic = [\"rod\"]\ndependent_coordinates = [\"theta\"]",
            "project = false",
            "derivation.project",
            "name them with `holonomic`",
        ),
        (
            "dependent = \"dependent\"",
            "dependent = \"not_the_rate\"",
            "derivation.dependent",
            "does not vanish with the dependent speeds",
        ),
    ];
    for (from, to, want_field, want) in cases {
        let (field, message) = refusal(scene_with(from, to).unwrap_err());
        assert_eq!(field, want_field, "{to}: {message}");
        assert!(message.contains(want), "{to}: {message}");
    }
}
