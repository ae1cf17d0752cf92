//! A new user's trial of `hdot verify` (issue 24, findings on verify),
//! each on a file written for it: bodies whose declared inertia has a zero
//! moment along x or y, three equal moments, or symbols (and a mass of 1)
//! shared between bodies are drawn as declared; a conserved energy along
//! the speeds' rates solved from a constrained `kane` step is checked along
//! them, the dependent speeds' rates following the constraints; a failed
//! check names the step that failed.

use hdot_num::verify::{Options, check};

use super::{load, verified};

const OPTS: Options = Options { draws: 8, seed: 24 };

/// A body in a frame turning freely, with its angular momentum and kinetic
/// energy about its reference point: `{inertia}`, `{symmetry}`, `{centre}`
/// filled in.
fn spinning(inertia: &str, symmetry: &str, centre: &str) -> String {
    format!(
        r#"
title = "A body turning about a fixed point"
source = "test"
[symbols]
constants = ["m", "l", "I", "J"]
time = ["w_1", "w_2", "w_3"]
[[frame]]
name = "B"
angular_velocity = "[w_1, w_2, w_3]"
[[point]]
name = "O"
fixed = true
[[body]]
name = "body"
frame = "B"
point = "O"
mass = "m"
mass_centre = "{centre}"
inertia = "{inertia}"
symmetry = "{symmetry}"
[[step]]
name = "H"
value = "{inertia} * angvel(B)"
means = "angular_momentum(body, O)"
[[step]]
name = "T"
value = "dot(angvel(B), H)/2"
means = "kinetic_energy(body)"
"#
    )
}

#[test]
fn a_slender_rod_along_any_axis_is_drawn_on_it() {
    for (inertia, symmetry, centre) in [
        ("principal(0, J, J)", "axisymmetric x", "[l, 0, 0] in B"),
        ("principal(J, 0, J)", "axisymmetric y", "[0, l, 0] in B"),
        ("principal(J, J, 0)", "axisymmetric z", "[0, 0, l] in B"),
        ("principal(0, J, J)", "principal", "[0, 0, 0] in B"),
    ] {
        let (compared, failed) = verified(&spinning(inertia, symmetry, centre), &OPTS);
        assert_eq!(compared, ["H", "T"], "{inertia} {symmetry}");
        assert!(failed.is_empty(), "{inertia} {symmetry}: {failed:?}");
    }
}

#[test]
fn equal_moments_are_drawn_equal() {
    for (inertia, symmetry) in [
        ("principal(I, I, I)", "principal"),
        ("principal(I, I, J)", "principal"),
        ("principal(J, I, I)", "principal"),
        ("principal(I, J, I)", "principal"),
    ] {
        let text = spinning(inertia, symmetry, "[0, 0, 0] in B");
        let (compared, failed) = verified(&text, &OPTS);
        assert_eq!(compared, ["H", "T"], "{inertia} {symmetry}");
        assert!(failed.is_empty(), "{inertia} {symmetry}: {failed:?}");
    }
}

/// Two wheels on one axle sharing their symbols, and a frame of mass 1.
const TWO_WHEELS: &str = r#"
title = "Two equal wheels on a turning axle"
source = "test"
[symbols]
constants = ["m_w", "I_w", "J_w", "d", "A", "C"]
time = ["w_1", "w_2", "w_3"]
[[frame]]
name = "B"
angular_velocity = "[w_1, w_2, w_3]"
[[point]]
name = "O"
fixed = true
[[point]]
name = "L"
from = "O"
at = "[0, -d, 0] in B"
[[point]]
name = "R"
from = "O"
at = "[0, d, 0] in B"
[[body]]
name = "left"
frame = "B"
point = "L"
mass = "m_w"
mass_centre = "[0, 0, 0] in B"
inertia = "principal(J_w, I_w, J_w)"
symmetry = "axisymmetric y"
[[body]]
name = "right"
frame = "B"
point = "R"
mass = "m_w"
mass_centre = "[0, 0, 0] in B"
inertia = "principal(J_w, I_w, J_w)"
symmetry = "axisymmetric y"
[[body]]
name = "axle"
frame = "B"
point = "O"
mass = "1"
mass_centre = "[0, 0, 0] in B"
inertia = "principal(A, C, A)"
symmetry = "axisymmetric y"
[[step]]
name = "T"
value = "dot(angvel(B), principal(2*J_w + 2*m_w*d^2 + A, 2*I_w + C, 2*J_w + 2*m_w*d^2 + A)*angvel(B))/2"
means = "kinetic_energy(system)"
[[step]]
name = "m"
value = "2*m_w + 1"
means = "mass(system)"
"#;

#[test]
fn bodies_sharing_symbols_or_a_numeric_mass_are_drawn_alike() {
    let (compared, failed) = verified(TWO_WHEELS, &OPTS);
    assert_eq!(compared, ["T", "m"]);
    assert!(failed.is_empty(), "{failed:?}");
}

/// The Chaplygin sled: a knife edge a behind the centre, the sideways
/// speed dependent; its energy, written in all three speeds, is conserved
/// along the independent speeds' rates solved from Kane's equations.
const SLED: &str = r#"
title = "The Chaplygin sled"
source = "test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "a", "A", "Bm", "C"]
positive = ["m", "a", "C"]
time = ["x", "y", "psi"]
speeds = ["u_1", "u_2", "u_3"]
[kinematics]
x = "u_1"
y = "u_2"
psi = "u_3"
[[frame]]
name = "B"
parent = "N"
rotation = "z(psi)"
[[point]]
name = "O"
fixed = true
[[point]]
name = "G"
from = "O"
at = "[x, y, 0] in N"
[[point]]
name = "P"
from = "G"
at = "[-a, 0, 0] in B"
[[body]]
name = "sled"
frame = "B"
point = "G"
mass = "m"
mass_centre = "[0, 0, 0] in B"
inertia = "principal(A, Bm, C)"
symmetry = "principal"
[[step]]
name = "edge"
value = "express(velocity(P), B).y"
[[step]]
name = "K"
value = "kane([u_1, u_3], list(edge), [u_2])"
means = "list(-generalized_active_force(sled, u_1) - generalized_inertia_force(sled, u_1), -generalized_active_force(sled, u_3) - generalized_inertia_force(sled, u_3))"
[[step]]
name = "rates"
value = "solve(K, [u_1', u_3'])"
[[step]]
name = "E"
value = "m*(u_1^2 + u_2^2)/2 + C*u_3^2/2"
conserved = true
"#;

#[test]
fn a_conserved_energy_along_a_constrained_kane_step_s_rates_passes() {
    let (compared, failed) = verified(SLED, &OPTS);
    assert_eq!(compared, ["K", "E"]);
    assert!(failed.is_empty(), "{failed:?}");
    // Written in the coordinates' rates, too.
    let text = SLED.replace(
        "value = \"m*(u_1^2 + u_2^2)/2 + C*u_3^2/2\"",
        "value = \"m*(x'^2 + y'^2)/2 + C*psi'^2/2\"",
    );
    let (_, failed) = verified(&text, &OPTS);
    assert!(failed.is_empty(), "{failed:?}");
}

#[test]
fn accelerations_free_of_a_constant_still_state_the_motion() {
    // Without the knife edge's offset the sled coasts: u₁' = u₃' = 0 hold
    // none of E's constants, and are still its equations of motion.
    let text = SLED.replace("at = \"[-a, 0, 0] in B\"", "at = \"[0, 0, 0] in B\"");
    let (compared, failed) = verified(&text, &OPTS);
    assert_eq!(compared, ["K", "E"]);
    assert!(failed.is_empty(), "{failed:?}");
}

#[test]
fn a_wrong_energy_fails_at_its_own_step() {
    // The spin's inertia of the wrong axis: E is not conserved, and the
    // verdict names E, not a step that agrees.
    let text = SLED.replace("+ C*u_3^2/2\"", "+ A*u_3^2/2\"");
    let r = check(&load(&text), &OPTS).unwrap_or_else(|e| panic!("{e}"));
    assert!(!r.passed());
    let worst = r.worst().expect("a comparison");
    assert!(worst.quantity.contains("d(E)/dt"), "{worst:?}");
    assert_eq!(r.first_failure().map(|s| s.step.as_str()), Some("E"));
    // A conserved step with no equations to take its rate along fails
    // without a comparison: none of a step that passed is named.
    let text = SLED.replace("value = \"solve(K, [u_1', u_3'])\"", "value = \"K\"");
    let r = check(&load(&text), &OPTS).unwrap_or_else(|e| panic!("{e}"));
    assert!(!r.passed());
    assert!(r.worst().is_none(), "{:?}", r.worst());
    assert_eq!(r.first_failure().map(|s| s.step.as_str()), Some("E"));
}
