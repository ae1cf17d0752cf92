//! Issue 24's trial findings on `simulate` and `stability`, each on a
//! problem written for the test (tests/sim/trial/): a two-link arm
//! released from the horizontal, whose energy starts at zero
//! (models/derived.rs, the drifts' scale) and which from a higher start
//! misses the default error with the first fitted tolerance (the fit
//! confirmed and tightened); a pendulum under tilted gravity
//! (scene/bind.rs, gravity's symbols); a stability sweep whose values are
//! decimals (stability/grid.rs).

use std::path::PathBuf;

use hdot_sim::SimError;
use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::{DerivedScene, Scene, SceneKind};
use hdot_tests::repo_root;

fn trial(name: &str) -> PathBuf {
    repo_root().join("tests/sim/trial").join(name)
}

/// The scene `name` of tests/sim/trial/ with each `from` replaced by its
/// `to` (which must be there).
fn scene_with(name: &str, edits: &[(&str, &str)]) -> Result<Scene, SimError> {
    let mut text = std::fs::read_to_string(trial(name)).expect("the test's scene");
    for (from, to) in edits {
        assert!(text.contains(from), "{name} has no `{from}`");
        text = text.replace(from, to);
    }
    Scene::parse(&text, &trial(name))
}

fn derived(scene: &Scene) -> &DerivedScene {
    match &scene.kind {
        SceneKind::Derived(ds) => ds,
        _ => panic!("a derived scene"),
    }
}

/// A run as `hdot simulate` makes it without options (the default target).
fn run_default(scene: &Scene) -> run::Report {
    let plan = run::plan(scene, &Request::default()).expect("plan");
    run::run(scene, &plan, &mut Output::default()).expect("run")
}

/// The arm's energy is exactly zero at the start (at rest, its potential
/// measured from the shoulder's height), so a drift relative to its value
/// was `|ΔE| / |ΔE|` = 1 and the run failed; relative to its size along
/// the run (the kinetic and potential energies it exchanges, here several
/// joules) it is round-off, within the bound the run's error sets.
#[test]
fn an_energy_that_starts_at_zero_drifts_relative_to_its_terms() {
    let scene = Scene::from_file(&trial("sim-two-link-arm.toml")).expect("scene");
    let ds = derived(&scene);
    let e = &ds.model.conserved()[0];
    assert_eq!(e.name, "E");
    assert_eq!(ds.model.conserved_value(e, 0.0, &ds.y0), [0.0]);
    assert_eq!(ds.model.conserved_size(e, 0.0, &ds.y0), [0.0]);
    let r = run_default(&scene);
    let drift = r.drifts.iter().find(|d| d.name == "E").expect("E's drift");
    let error = r.error.expect("an error at T");
    assert!(
        drift.relative < run::DRIFT_FACTOR * error.max(run::DRIFT_FLOOR),
        "drift {:e} against error {error:e}",
        drift.relative
    );
    assert!(r.failed_drifts().is_empty());
    // The size it is relative to: the terms at T are of the weights'
    // potential, m g l ~ 10 J, not round-off.
    let at_t = ds.model.conserved_size(e, r.plan.t_end, &r.final_state)[0];
    assert!(at_t > 1.0, "{at_t}");
}

/// A false claim still fails with the new scale: the arm's forcing (its
/// weights' moments and the velocity terms) is declared conserved; it
/// changes by as much as its size along the run.
#[test]
fn a_forcing_declared_conserved_still_fails() {
    let scene = scene_with(
        "sim-two-link-arm.toml",
        &[("frame = \"B\"\n", "frame = \"B\"\nconserved = [\"f\"]\n")],
    )
    .expect("scene");
    let r = run_default(&scene);
    let failed: Vec<&str> = r.failed_drifts().iter().map(|d| d.name.as_str()).collect();
    assert_eq!(failed, ["f"], "{:?}", r.drifts);
    assert_eq!(
        r.drifts
            .iter()
            .find(|d| d.name == "E")
            .map(|d| d.relative < 1e-9),
        Some(true)
    );
}

/// From q1 = 2, q2 = 0.5 over 2 s, the two pilots' fit predicts
/// tol = 1.2e-9, whose error at T is 1.03e-8: the default 1e-8 was missed
/// and `hdot simulate` exited 1 without a --tol. A pilot at the fitted
/// tolerance now confirms it, and it is tightened until the target is met.
#[test]
fn a_fitted_tolerance_that_misses_the_default_is_tightened() {
    let scene = scene_with(
        "sim-two-link-arm.toml",
        &[
            ("q1 = 0.0, q2 = 0.0", "q1 = 2.0, q2 = 0.5"),
            ("t_end = 3.0", "t_end = 2.0"),
        ],
    )
    .expect("scene");
    let r = run_default(&scene);
    let target = r.plan.fit_error.expect("a default target");
    let e = r.error.expect("an error at T");
    assert!(
        e <= target,
        "error {e:e} above {target:e}: {}",
        r.plan.reason
    );
    assert!(
        r.plan.reason.contains("tightened to tol="),
        "{}",
        r.plan.reason
    );
}

/// The pendulum's gravity is tilted, `[g sin(beta), 0, -g cos(beta)]`;
/// the scene gives g as a vector and the tilt as a constant (the scene's
/// errors used to contradict each other: beta "also bound by the scene's
/// g" under `[constants]`, "more than one symbol not bound yet" at
/// `body[0]` without). g is bound from the vector; started at the tilted
/// bottom q = −beta at rest, the bob stays there; and the same scene with
/// g and beta as constants runs the same motion.
#[test]
fn tilted_gravity_binds_g_from_the_scene_and_the_tilt_from_a_constant() {
    let scene = Scene::from_file(&trial("sim-tilted-pendulum.toml")).expect("scene");
    let g = derived(&scene).spec.constants["g"];
    assert!((g - 9.81).abs() <= 1e-14 * 9.81, "{g}");
    let at_rest =
        scene_with("sim-tilted-pendulum.toml", &[("q = 0.0", "q = -0.3")]).expect("scene");
    let r = run_default(&at_rest);
    assert!(
        (r.final_state[0] + 0.3).abs() <= 1e-12,
        "{:?}",
        r.final_state
    );
    assert!(r.final_state[1].abs() <= 1e-12, "{:?}", r.final_state);
    let swinging = run_default(&scene);
    let by_constants = scene_with(
        "sim-tilted-pendulum.toml",
        &[
            ("g = [2.899053227347741, 0.0, -9.371850958322195]\n", ""),
            ("beta = 0.3", "beta = 0.3\ng = 9.81"),
        ],
    )
    .expect("scene");
    let same = run_default(&by_constants);
    for (a, b) in swinging.final_state.iter().zip(&same.final_state) {
        assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()), "{a} against {b}");
    }
    // Untilted, g*sin(beta) fixes nothing: g comes from the third component.
    let flat = scene_with(
        "sim-tilted-pendulum.toml",
        &[
            (
                "g = [2.899053227347741, 0.0, -9.371850958322195]",
                "g = [0.0, 0.0, -9.81]",
            ),
            ("beta = 0.3", "beta = 0.0"),
        ],
    )
    .expect("scene");
    assert_eq!(derived(&flat).spec.constants["g"], 9.81);
}

/// Tilted gravity given wrongly: one error, at the field `g`, saying what
/// to write.
#[test]
fn tilted_gravity_errors_name_g_and_what_to_write() {
    let err = |edits: &[(&str, &str)]| {
        scene_with("sim-tilted-pendulum.toml", edits)
            .expect_err("refused")
            .to_string()
    };
    // Both symbols left to the vector.
    let e = err(&[("[constants]\nbeta = 0.3\n", "")]);
    assert!(e.contains("field `g`: line 7:"), "{e}");
    assert!(
        e.contains("give all of them but one under `[constants]`"),
        "{e}"
    );
    assert!(!e.contains("body[0]"), "{e}");
    // A vector that is not along the tilt the constant gives.
    let e = err(&[("beta = 0.3", "beta = 0.5")]);
    assert!(
        e.contains("field `g`") && e.contains("must point along it"),
        "{e}"
    );
    assert!(!e.contains("body[0]"), "{e}");
    // g given twice: under `[constants]` and by the vector.
    let e = err(&[("beta = 0.3", "beta = 0.3\ng = 9.81")]);
    assert!(
        e.contains("field `g`") && e.contains("give each once"),
        "{e}"
    );
}
