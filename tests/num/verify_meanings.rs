//! More meanings and conditions on constants (issue 20, item 4): ∂T/∂q
//! measured on the particles, abbreviations that carry a meaning and are
//! verified like steps, and a step's `given` fixing a constant (`s = 0`),
//! printed beside the step in every output format.
//! The file, written for these tests: an axisymmetric body about a fixed
//! point, turned by φ about the vertical and tilted by θ; and the bundled
//! rolling disk's contact (issue 24, item 7).

use hdot_num::verify::{Options, check};
use hdot_sym::derivation::load_str;

use super::{load, verified};

/// The tilted body; `{abbrev}` and `{extra}` are spliced in (the
/// abbreviation before the frames, the steps after the others).
fn tilted(abbrev: &str, extra: &str) -> String {
    format!(
        r#"
title = "A body tilted on a turning frame, written for this test"
source = "test"
[symbols]
constants = ["A", "C", "s"]
time = ["phi", "theta"]
{abbrev}
[[frame]]
name = "P"
parent = "N"
rotation = "z(phi)"
[[frame]]
name = "Q"
parent = "P"
rotation = "x(theta)"
[[point]]
name = "O"
fixed = true
[[body]]
name = "body"
frame = "Q"
point = "O"
mass_centre = "[0, 0, 0] in Q"
inertia = "principal(A, A, C)"
symmetry = "axisymmetric z"
[[step]]
name = "T"
value = "dot(angvel(Q), principal(A, A, C)*angvel(Q))/2"
means = "kinetic_energy(body)"
[[step]]
name = "dTdtheta"
value = "partial(T, theta)"
means = "kinetic_energy_partial(body, theta)"
{extra}
"#
    )
}

fn options() -> Options {
    Options { draws: 10, seed: 2 }
}

/// The names of the failed checks of `text`.
fn failed(text: &str) -> Vec<String> {
    let (compared, failed) = verified(text, &options());
    assert!(!compared.is_empty());
    failed
}

#[test]
fn the_partial_of_kinetic_energy_in_a_coordinate_is_measured_on_the_particles() {
    assert!(failed(&tilted("", "")).is_empty());
    // ∂T/∂θ with its sign slipped, and ∂T/∂φ (zero) claimed for θ.
    let wrong = tilted("", "").replace(
        "value = \"partial(T, theta)\"",
        "value = \"-partial(T, theta)\"",
    );
    assert_eq!(failed(&wrong), ["dTdtheta"]);
    let wrong = tilted("", "").replace(
        "value = \"partial(T, theta)\"",
        "value = \"partial(T, phi)\"",
    );
    assert_eq!(failed(&wrong), ["dTdtheta"]);
}

#[test]
fn an_abbreviation_with_a_meaning_is_verified_like_a_step() {
    let abbrev = |v: &str| {
        format!(
            "[[abbreviation]]\nname = \"w_z\"\nvalue = \"{v}\"\nmeans = \"along(angular_velocity(Q), [0, 0, 1] in Q)\"\ndoc = \"the spin component\""
        )
    };
    let r = check(&load(&tilted(&abbrev("phi'*cos(theta)"), "")), &options())
        .unwrap_or_else(|e| panic!("{e}"));
    let w = r
        .steps
        .iter()
        .find(|s| s.step == "w_z")
        .expect("the abbreviation is compared");
    assert!(w.passed, "{w:?}");
    assert_eq!(failed(&tilted(&abbrev("phi'*sin(theta)"), "")), ["w_z"]);
}

#[test]
fn a_condition_may_fix_a_constant_for_a_special_case() {
    // φ̇ = s, and the special case s = 0: ∂T/∂θ vanishes.
    let special = |given: &str| {
        format!(
            "[[step]]\nname = \"dTdtheta_0\"\nvalue = \"subst(dTdtheta, phi' = s, s = 0)\"\nmeans = \"kinetic_energy_partial(body, theta)\"\ngiven = [{given}]\n"
        )
    };
    assert!(failed(&tilted("", &special("\"s = 0\", \"phi' = s\""))).is_empty());
    // Without the special case the value is false.
    assert_eq!(
        failed(&tilted("", &special("\"phi' = s\""))),
        ["dTdtheta_0"]
    );
    // A constant the bodies bind cannot be fixed: located error.
    let e =
        load_str("t.toml", &tilted("", &special("\"A = 0\""))).expect_err("A is the body's moment");
    let msg = e.to_string();
    assert!(msg.contains("measured on the particles"), "{msg}");
    assert!(msg.contains("t.toml:"), "{msg}");
}

/// A step that holds only under its conditions prints them beside its
/// result, in every output format, and a step without conditions prints
/// none: a constant fixed (`s = 0`), a rate (`φ̇ = s`), an angle
/// (`θ = π/2`).
#[test]
fn a_steps_conditions_print_beside_it_in_every_format() {
    let text = tilted(
        "",
        "[[step]]\nname = \"dTdtheta_0\"\nvalue = \"subst(dTdtheta, phi' = s, s = 0, theta = pi/2)\"\n\
         means = \"kinetic_energy_partial(body, theta)\"\ngiven = [\"s = 0\", \"phi' = s\", \"theta = pi/2\"]\n",
    );
    let d = load(&text);
    let section = hdot_sym::document::Section::of(&d, None);
    let conditions: Vec<&str> = section.steps.iter().map(|s| s.condition.as_str()).collect();
    assert_eq!(conditions, ["", "", "$s = 0$, $φ̇ = s$, $θ = π/2$"]);
    for b in hdot_sym::notes::BACKENDS {
        let out = b.section(&section);
        assert_eq!(out.matches("(for ").count(), 1, "{}:\n{out}", b.name());
    }
    let unicode = hdot_sym::notes::backend("unicode")
        .unwrap()
        .section(&section);
    assert!(unicode.contains("(for s = 0, φ̇ = s, θ = π/2)"), "{unicode}");
    let latex = hdot_sym::notes::backend("latex").unwrap().section(&section);
    assert!(
        latex.contains(r"(for $s = 0$, $\dot{\phi} = s$, $\theta = \pi/2$)"),
        "{latex}"
    );
}

/// Issue 24, item 7: the rolling disk's constraint measured on the
/// particles — along the rolling rules its material point at C is at rest
/// — and a rule with a slipped sign fails there.
#[test]
fn the_rolling_disks_contact_is_at_rest_along_its_rules() {
    let text = include_str!("../../derivations/disk-rolling-on-plane.toml");
    let r = check(&load(text), &options()).unwrap_or_else(|e| panic!("{e}"));
    let c = r
        .steps
        .iter()
        .find(|s| s.step == "[motion] vanishes")
        .expect("the contact is measured");
    assert!(c.passed && c.means == "point_velocity(disk, C)", "{c:?}");
    let wrong = text.replace("\"x' = r*phi'*cos(psi)\"", "\"x' = -r*phi'*cos(psi)\"");
    assert_ne!(wrong, text);
    let r = check(&load(&wrong), &options()).unwrap_or_else(|e| panic!("{e}"));
    let failed = r.failed();
    // The contact moving, every step measured on that motion that holds
    // only when it rolls fails too.
    assert_eq!(
        failed,
        [
            "contact",
            "no_slip",
            "dependent",
            "K",
            "M",
            "f",
            "v_G",
            "E",
            "dE",
            "[motion] vanishes"
        ]
    );
}
