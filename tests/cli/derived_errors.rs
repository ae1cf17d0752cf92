//! Errors of a derived scene name the scene first — its file, the field
//! and the line the user edits — and then the derivation and its step
//! (issue 21, item 9): a constant with no value, a step that does not
//! exist, a conserved step that does not exist, an input that is a
//! coordinate.

use super::{hdot, text};

/// A derived scene of the bundled heavy top with every constant given.
const SCENE: &str = r#"name = "heavy top with its constants"
kind = "derived"
t_end = 0.01

[derivation]
file = "heavy-top"
accelerations = "accelerations"

[constants]
I = 0.0004
Ip = 0.0015
m = 0.5
g = 9.81
l = 0.05

[initial]
coordinates = { phi = 0.0, theta = 0.5, psi = 0.0 }
rates = { phi = 0.0, theta = 0.0, psi = 60.0 }
"#;

/// The 1-based line of the first line of `scene` that starts with `start`.
fn line_starting(scene: &str, start: &str) -> usize {
    scene
        .lines()
        .position(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no line starts with {start:?}"))
        + 1
}

/// Runs `hdot simulate` on `scene` written to a fresh folder: the exit
/// code and stderr.
fn simulate(scene: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, scene).expect("write");
    let out = hdot(&["simulate", path.to_str().expect("utf-8 path")]);
    (out.status.code(), text(&out.stderr))
}

/// The message names the scene, the field and the line before the
/// derivation, and says `then` after them.
fn assert_located(scene: &str, field: &str, line: usize, then: &str) {
    let (code, err) = simulate(scene);
    assert_eq!(code, Some(2), "{err}");
    let at = format!("scene.toml: field `{field}`: line {line}: ");
    let start = err
        .find(&at)
        .unwrap_or_else(|| panic!("`{at}` missing from:\n{err}"));
    let rest = &err[start + at.len()..];
    assert!(rest.contains(then), "`{then}` missing after `{at}`:\n{err}");
}

#[test]
fn the_scene_itself_runs() {
    let (code, err) = simulate(SCENE);
    assert_eq!(code, Some(0), "{err}");
}

#[test]
fn a_constant_without_value_names_the_constants_table_and_the_step() {
    let scene = SCENE.replace("l = 0.05\n", "");
    assert_located(
        &scene,
        "constants",
        line_starting(&scene, "[constants]"),
        "the constant `l` has no value",
    );
    let (_, err) = simulate(&scene);
    assert!(err.contains("(in step `accelerations`)"), "{err}");
}

#[test]
fn a_step_that_does_not_exist_names_the_accelerations_field() {
    let scene = SCENE.replace(
        "accelerations = \"accelerations\"",
        "accelerations = \"nope\"",
    );
    assert_located(
        &scene,
        "derivation.accelerations",
        line_starting(&scene, "accelerations ="),
        "no step named `nope`",
    );
}

#[test]
fn a_conserved_step_that_does_not_exist_names_the_conserved_field() {
    let scene = SCENE.replace(
        "accelerations = \"accelerations\"",
        "accelerations = \"accelerations\"\nconserved = [\"ZZ\"]",
    );
    assert_located(
        &scene,
        "derivation.conserved",
        line_starting(&scene, "conserved ="),
        "no step named `ZZ`",
    );
}

#[test]
fn an_input_that_is_a_coordinate_names_the_input() {
    let scene = SCENE.replace("[initial]", "[inputs]\ntheta = \"t\"\n\n[initial]");
    assert_located(
        &scene,
        "inputs.theta",
        line_starting(&scene, "theta ="),
        "`theta` is a coordinate of the equations",
    );
    // A name that is no time symbol of the derivation is not ignored.
    let scene = SCENE.replace("[initial]", "[inputs]\nm = \"t\"\n\n[initial]");
    assert_located(
        &scene,
        "inputs.m",
        line_starting(&scene, "m = \"t\""),
        "`m` is not a time symbol",
    );
}

/// Item 8 on a derived scene: a huge initial rate names its own field and
/// line, not the end time it makes too long to resolve.
#[test]
fn a_huge_initial_rate_names_its_field() {
    let scene = SCENE.replace("psi = 60.0", "psi = 1e200");
    let line = line_starting(&scene, "rates = ");
    assert_located(&scene, "initial.rates.psi", line, "|ω| = 1e200");
}
