//! The revolute-joint shorthand `rotation = "about([k_x, k_y, k_z], q)"`:
//! about a coordinate axis it is that axis's rotation; about a tilted axis
//! the angular velocity is q̇ k; a zero, non-unit or moving axis is a
//! located error.

use hdot_sym::derivation::{Diagnostic, Value, load_str};
use hdot_tests::frame;

const FILE: &str = concat!(
    r#"
title = "a hinge"
source = "written for the test"
[symbols]
constants = ["lambda"]
time = ["q"]
"#,
    frame!("A", "N", "ROTATION"),
    r#"[[step]]
name = "w"
value = "express(angvel(A), N)"
[[step]]
name = "e"
value = "express([1, 0, 0] in A, N)"
"#,
);

fn load(rotation: &str) -> Result<hdot_sym::derivation::Derivation, Diagnostic> {
    load_str("hinge.toml", &FILE.replace("ROTATION", rotation))
}

fn step(rotation: &str, name: &str) -> Value {
    let d = load(rotation).unwrap_or_else(|e| panic!("{e}"));
    d.steps
        .iter()
        .find(|s| s.name == name)
        .unwrap()
        .value
        .clone()
}

#[test]
fn a_hinge_about_a_coordinate_axis_is_that_axis_rotation() {
    for (k, axis) in [("[1, 0, 0]", "x"), ("[0, 1, 0]", "y"), ("[0, 0, 1]", "z")] {
        for s in ["w", "e"] {
            assert_eq!(
                step(&format!("about({k}, q)"), s),
                step(&format!("{axis}(q)"), s),
                "{k} {s}"
            );
        }
    }
}

#[test]
fn a_tilted_hinge_turns_about_its_axis() {
    let w = step("about([sin(lambda), 0, cos(lambda)], q)", "w");
    let want = load_str(
        "want.toml",
        &FILE.replace("ROTATION", "z(q)").replace(
            "value = \"express(angvel(A), N)\"",
            "value = \"[q'*sin(lambda), 0, q'*cos(lambda)] in N\"",
        ),
    )
    .unwrap();
    assert_eq!(w, want.steps[0].value);
}

#[test]
fn a_bad_hinge_axis_is_a_located_error() {
    for (rotation, want) in [
        ("about([0, 0, 0], q)", "the hinge axis has zero length"),
        ("about([1, 1, 0], q)", "must be a unit vector"),
        ("about([sin(q), 0, cos(q)], q)", "fixed in the parent frame"),
        (
            "about([0, 0, 1], 2*q)",
            "the rotation angle must be a declared symbol",
        ),
        ("about(q)", "a hinge is written about("),
    ] {
        let e = load(rotation)
            .err()
            .unwrap_or_else(|| panic!("{rotation} loads"));
        assert!(e.message.contains(want), "{rotation}: {e}");
        assert_eq!(
            (e.path.as_str(), e.line),
            ("hinge.toml", 10),
            "{rotation}: {e}"
        );
    }
}
