//! Reactions at declared supports (issue 20, item 1): `reaction(S)` and
//! `reaction_couple(S)` measured from particle sums and the supports'
//! equilibrium alone. Files written for these tests: a rod welded to a
//! shaft in two bearings with a drive (bundled:
//! `derivations/welded-rod-on-shaft.toml`), a three-legged table on the floor, a clamped body and
//! a ball joint; a statically indeterminate set and a set that cannot hold
//! the motion.

use hdot_num::verify::{Options, check};
use hdot_sym::derivation::load_str;

use super::load;

const ROD: &str = include_str!("../../derivations/welded-rod-on-shaft.toml");

fn options() -> Options {
    Options { draws: 12, seed: 5 }
}

#[test]
fn the_welded_rod_verifies_its_six_reactions_from_the_declared_supports() {
    let d = load(ROD);
    let r = check(&d, &options()).unwrap_or_else(|e| panic!("{e}"));
    for s in &r.steps {
        assert!(s.passed, "{}: {:?}", s.step, s.worst);
    }
    let names: Vec<&str> = r.steps.iter().map(|s| s.step.as_str()).collect();
    for step in ["reactions", "R_A", "R_B", "R_B_steady"] {
        assert!(names.contains(&step), "{step} not compared: {names:?}");
    }
    let reactions = r.steps.iter().find(|s| s.step == "reactions").unwrap();
    assert!(
        reactions.against.contains("equilibrium"),
        "{}",
        reactions.against
    );
}

/// The rod's file with `from` replaced by `to` (which must occur).
fn with(from: &str, to: &str) -> String {
    assert!(ROD.contains(from), "{from}");
    ROD.replacen(from, to, 1)
}

#[test]
fn a_consistent_sign_error_in_a_reaction_fails() {
    // The moment balance written with the moment of the motion added, not
    // subtracted: the step derives, and the same slip in a hand-written
    // statics meaning would agree with it. Measured from the supports it
    // fails, naming the reactions.
    for (from, to) in [
        ("moments.x - M.x", "moments.x + M.x"),
        ("moments.y - M.y", "moments.y + M.y"),
    ] {
        let d = load(&with(from, to));
        let r = check(&d, &options()).unwrap_or_else(|e| panic!("{e}"));
        let failed = r.failed();
        assert!(failed.contains(&"reactions"), "{from} → {to}: {failed:?}");
        assert!(
            failed.contains(&"R_A") && failed.contains(&"R_B"),
            "{failed:?}"
        );
    }
    // The drive's couple with its sign slipped: only the list fails.
    let d = load(&with("moments.z - M.z", "moments.z + M.z"));
    let r = check(&d, &options()).unwrap_or_else(|e| panic!("{e}"));
    let failed = r.failed();
    assert_eq!(failed, ["reactions"]);
}

#[test]
fn a_shaft_without_its_drive_cannot_hold_an_accelerating_motion() {
    let text = with(
        "[[support]]\nname = \"motor\"",
        "[[support]]\nname = \"motor_\"",
    )
    .replace("reaction_couple(motor)", "reaction_couple(motor_)");
    // Sanity: still loads, the motor renamed.
    load(&text);
    // Without the drive: a bearing pair cannot hold φ̈ ≠ 0.
    let start = text.find("[[support]]\nname = \"motor_\"").unwrap();
    let end = start + text[start..].find("[[step]]").unwrap();
    let without = format!("{}{}", &text[..start], &text[end..])
        .replace(", along(reaction_couple(motor_), [0, 0, 1] in S))", ")")
        .replace(
            ", [A_x, A_y, B_x, B_y, B_z, M_d])",
            ", [A_x, A_y, B_x, B_y, B_z])",
        )
        .replace(
            "list(forces.x, forces.y, forces.z, moments.x - M.x, moments.y - M.y, moments.z - M.z)",
            "list(forces.x, forces.y, forces.z, moments.x - M.x, moments.y - M.y)",
        )
        // The drive's couple, the last of the six expected reactions, goes too.
        .replace(", \"m*g\", \"Ip*phi''*sin(beta)^2\"]", ", \"m*g\"]");
    let d = load(&without);
    let e = check(&d, &options()).expect_err("no support holds the shaft's turning");
    let msg = e.to_string();
    assert!(msg.contains("cannot carry"), "{msg}");
    assert!(msg.contains("A, B"), "{msg}");
}

/// A body held by `supports` (TOML tables), with `steps`.
fn held(supports: &str, steps: &str) -> String {
    format!(
        r#"
title = "A body held by supports, written for this test"
source = "test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "a", "h", "A", "C"]
time = ["phi"]
[[frame]]
name = "B"
parent = "N"
rotation = "z(phi)"
[[point]]
name = "O"
fixed = true
[[point]]
name = "L1"
fixed = true
at = "[2*a, 0, -h] in N"
[[point]]
name = "L2"
fixed = true
at = "[-a, a, -h] in N"
[[point]]
name = "L3"
fixed = true
at = "[-a, -a, -h] in N"
[[point]]
name = "P"
fixed = true
at = "[0, 0, h] in N"
[[body]]
name = "body"
frame = "B"
point = "O"
mass = "m"
mass_centre = "[0, 0, 0] in B"
inertia = "principal(A, A, C)"
symmetry = "axisymmetric z"
{supports}
{steps}
"#
    )
}

const LEGS: &str = r#"
[[support]]
name = "leg1"
kind = "floor"
point = "L1"
axis = "[0, 0, 1] in N"
[[support]]
name = "leg2"
kind = "floor"
point = "L2"
axis = "[0, 0, 1] in N"
[[support]]
name = "leg3"
kind = "floor"
point = "L3"
axis = "[0, 0, 1] in N"
"#;

#[test]
fn a_three_legged_table_at_rest_shares_its_weight_by_the_lever_rule() {
    // G above the centroid of the legs (2a, 0), (−a, ±a): a third each.
    let step = |value: &str| {
        format!(
            "[[step]]\nname = \"N1\"\nvalue = \"{value}\"\nmeans = \"reaction(leg1)\"\ngiven = [\"phi' = 0\"]\n[[step]]\nname = \"N2\"\nvalue = \"{value}\"\nmeans = \"reaction(leg2)\"\ngiven = [\"phi' = 0\"]\n"
        )
    };
    let d = load(&held(LEGS, &step("[0, 0, m*g/3] in N")));
    let r = check(&d, &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.passed() && r.steps.len() == 2, "{:?}", r.steps);
    let d = load(&held(LEGS, &step("[0, 0, m*g/2] in N")));
    let r = check(&d, &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.steps.iter().all(|s| !s.passed), "{:?}", r.steps);
}

#[test]
fn a_clamp_carries_the_moment_the_motion_requires_and_a_ball_the_force() {
    // A body spinning about its fixed centre, clamped there: the clamp's
    // couple is Ḣ_O, its force the weight's opposite.
    let clamp = "[[support]]\nname = \"weld\"\nkind = \"clamp\"\npoint = \"O\"\n";
    let steps = r#"
[[step]]
name = "couple"
value = "dt(principal(A, A, C) * angvel(B))"
means = "reaction_couple(weld)"
[[step]]
name = "force"
value = "[0, 0, m*g] in N"
means = "reaction(weld)"
"#;
    let r = check(&load(&held(clamp, steps)), &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.passed() && r.steps.len() == 2, "{:?}", r.steps);
    let wrong = steps.replace("dt(principal", "-dt(principal");
    let r = check(&load(&held(clamp, &wrong)), &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(!r.steps[0].passed && r.steps[1].passed, "{:?}", r.steps);
    // A ball joint at O with a drive about the vertical axis: the joint
    // carries the weight.
    let ball = "[[support]]\nname = \"joint\"\nkind = \"ball\"\npoint = \"O\"\n[[support]]\nname = \"motor\"\nkind = \"drive\"\naxis = \"[0, 0, 1] in N\"\n";
    let steps = r#"
[[step]]
name = "force"
value = "[0, 0, m*g] in N"
means = "reaction(joint)"
[[step]]
name = "drive"
value = "C*phi''"
means = "along(reaction_couple(motor), [0, 0, 1] in N)"
"#;
    let r = check(&load(&held(ball, steps)), &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.passed() && r.steps.len() == 2, "{:?}", r.steps);
}

#[test]
fn a_statically_indeterminate_set_of_supports_is_an_error_that_says_so() {
    // Seven components: refused when the file loads, at the last support.
    let seven = format!("{LEGS}[[support]]\nname = \"pin\"\nkind = \"clamp\"\npoint = \"P\"\n");
    let e = load_str("t.toml", &held(&seven, "")).expect_err("seven components");
    let msg = e.to_string();
    assert!(msg.contains("statically indeterminate"), "{msg}");
    assert!(msg.contains("t.toml:"), "{msg}");
    // Two ball joints on the shaft's axis: six components, but the pair
    // of forces along the line joining them is in equilibrium by itself.
    let balls = "[[support]]\nname = \"lower\"\nkind = \"ball\"\npoint = \"O\"\n[[support]]\nname = \"upper\"\nkind = \"ball\"\npoint = \"P\"\n";
    let steps = "[[step]]\nname = \"force\"\nvalue = \"[0, 0, m*g] in N\"\nmeans = \"reaction(lower)\"\ngiven = [\"phi' = 0\"]\n";
    let e = check(&load(&held(balls, steps)), &options()).expect_err("indeterminate");
    let msg = e.to_string();
    assert!(msg.contains("statically indeterminate"), "{msg}");
    assert!(msg.contains("lower, upper"), "{msg}");
}

#[test]
fn bad_supports_are_located_errors() {
    for (support, step_means, expected) in [
        (
            "kind = \"hinge\"\npoint = \"O\"",
            "",
            "unknown kind of support `hinge`",
        ),
        (
            "kind = \"bearing\"\npoint = \"O\"\naxis = \"[0, 0, 1] in N\"",
            "",
            "carries = \"radial\"",
        ),
        (
            "kind = \"bearing\"\ncarries = \"axial\"\npoint = \"O\"\naxis = \"[0, 0, 1] in N\"",
            "",
            "not `axial`",
        ),
        (
            "kind = \"bearing\"\ncarries = \"radial\"\npoint = \"O\"",
            "",
            "needs `axis`",
        ),
        (
            "kind = \"bearing\"\ncarries = \"radial\"\npoint = \"O\"\naxis = \"[0, 0, 0] in N\"",
            "",
            "zero length",
        ),
        (
            "kind = \"bearing\"\ncarries = \"radial\"\npoint = \"Q\"\naxis = \"[0, 0, 1] in N\"",
            "",
            "unknown point `Q`",
        ),
        (
            "kind = \"drive\"\npoint = \"O\"\naxis = \"[0, 0, 1] in N\"",
            "",
            "acts at no point",
        ),
        (
            "kind = \"ball\"\npoint = \"O\"\naxis = \"[0, 0, 1] in N\"",
            "",
            "no `axis`",
        ),
        (
            "kind = \"ball\"\npoint = \"O\"\nfriction = true",
            "",
            "`friction`",
        ),
        ("kind = \"ball\"", "", "add `point"),
        (
            "kind = \"ball\"\npoint = \"O\"",
            "reaction_couple(S)",
            "carries no couple",
        ),
        (
            "kind = \"drive\"\naxis = \"[0, 0, 1] in N\"",
            "reaction(S)",
            "carries a couple and no force",
        ),
        (
            "kind = \"ball\"\npoint = \"O\"",
            "reaction(T)",
            "unknown support `T`",
        ),
    ] {
        let step = if step_means.is_empty() {
            String::new()
        } else {
            format!(
                "[[step]]\nname = \"f\"\nvalue = \"[0, 0, m*g] in N\"\nmeans = \"{step_means}\"\n"
            )
        };
        let text = held(&format!("[[support]]\nname = \"S\"\n{support}\n"), &step);
        let e = load_str("t.toml", &text).expect_err(expected);
        let msg = e.to_string();
        assert!(msg.contains(expected), "{expected}: {msg}");
        assert!(msg.contains("t.toml:"), "{expected}: not located: {msg}");
    }
}

#[test]
fn declared_loads_are_taken_from_what_the_supports_carry() {
    // A ball joint at O and a drive about the vertical, with a torque
    // T_a on the body about its axis and a force F along x at O: the drive
    // supplies C φ̈ − T_a, the joint −F along x and the weight's opposite.
    let ball = "[[support]]\nname = \"joint\"\nkind = \"ball\"\npoint = \"O\"\n[[support]]\nname = \"motor\"\nkind = \"drive\"\naxis = \"[0, 0, 1] in N\"\n[[load]]\nframe = \"B\"\ntorque = \"[0, 0, T_a] in B\"\n[[load]]\npoint = \"O\"\nforce = \"[F, 0, 0] in N\"\n";
    let steps = |drive: &str| {
        format!(
            "[[step]]\nname = \"force\"\nvalue = \"[-F, 0, m*g] in N\"\nmeans = \"reaction(joint)\"\n[[step]]\nname = \"drive\"\nvalue = \"{drive}\"\nmeans = \"along(reaction_couple(motor), [0, 0, 1] in N)\"\n"
        )
    };
    let text = |drive: &str| {
        held(ball, &steps(drive)).replace(
            "constants = [\"m\", \"g\", \"a\", \"h\", \"A\", \"C\"]",
            "constants = [\"m\", \"g\", \"a\", \"h\", \"A\", \"C\", \"T_a\", \"F\"]",
        )
    };
    let r = check(&load(&text("C*phi'' - T_a")), &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.passed() && r.steps.len() == 2, "{:?}", r.steps);
    // The load left out of the statics: the drive's couple fails.
    let r = check(&load(&text("C*phi''")), &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.steps[0].passed && !r.steps[1].passed, "{:?}", r.steps);
}
