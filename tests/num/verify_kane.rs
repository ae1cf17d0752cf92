//! Kane's generalized forces measured on the particles (issue 24, item
//! 7): `generalized_active_force` and `generalized_inertia_force` with the
//! constrained partial velocities, against a `kane` step and against
//! Kane's equations written out by hand. The file written for these tests
//! (`derivations/kane-sled.toml`): a sled on an incline whose knife edge
//! makes one speed dependent, with a thrust and a torque as `[[load]]`s.
//! A slip of the kind a hand derivation makes — a sign in one term, a
//! partial velocity of the wrong point, the dependent speed left in the
//! velocity the partial velocities are taken from — must be rejected.

use hdot_num::verify::{Options, check};
use hdot_sym::derivation::load_str;

use super::{load, verified};

const SLED: &str = include_str!("derivations/kane-sled.toml");

fn options() -> Options {
    Options { draws: 12, seed: 7 }
}

/// The failed checks of `text`, by step name.
fn failed(text: &str) -> Vec<String> {
    let (compared, failed) = verified(text, &options());
    assert!(compared.len() >= 6, "{compared:?}");
    failed
}

/// `text` with `from` replaced by `to` exactly once.
fn mutate(from: &str, to: &str) -> String {
    assert_eq!(SLED.matches(from).count(), 1, "{from}");
    SLED.replace(from, to)
}

#[test]
fn the_sled_by_hand_and_by_kane_agrees_with_the_particles() {
    let r = check(&load(SLED), &options()).unwrap_or_else(|e| panic!("{e}"));
    for name in ["K", "Fr_1", "Fr_3", "Fs_1", "Fs_3", "by_hand"] {
        let s = r
            .steps
            .iter()
            .find(|s| s.step == name)
            .unwrap_or_else(|| panic!("{name} is compared"));
        assert!(s.passed, "{s:?}");
    }
    assert!(r.passed(), "{:?}", r.steps);
}

#[test]
fn a_flipped_sign_in_one_generalized_force_term_is_rejected() {
    // The torque's share of F_3.
    let text = mutate(
        "u_3), [F, 0, 0] in A) + dot(coeff(w, u_3), [0, 0, T] in A)",
        "u_3), [F, 0, 0] in A) - dot(coeff(w, u_3), [0, 0, T] in A)",
    );
    let f = failed(&text);
    assert!(
        f.contains(&"Fr_3".to_string()) && f.contains(&"by_hand".to_string()),
        "{f:?}"
    );
    // The gravity's share of F_1.
    let text = mutate(
        "dot(coeff(v_G, u_1), m*express([0, -g, 0] in N, A))",
        "dot(coeff(v_G, u_1), m*express([0, g, 0] in N, A))",
    );
    let f = failed(&text);
    assert!(
        f.contains(&"Fr_1".to_string()) && f.contains(&"by_hand".to_string()),
        "{f:?}"
    );
    // The gyroscopic term of F*_3.
    let text = mutate(
        "-dot(coeff(v_G, u_3), m*a_G) - dot(coeff(w, u_3), principal(I_1, I_2, I_3)*alpha + cross",
        "-dot(coeff(v_G, u_3), m*a_G) - dot(coeff(w, u_3), principal(I_1, I_2, I_3)*alpha - cross",
    );
    // ω × I ω vanishes for a planar turn: no measurement can tell.
    let r = check(&load(&text), &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.passed(), "{:?}", r.steps);
    let text = mutate(
        "-dot(coeff(v_G, u_3), m*a_G) -",
        "dot(coeff(v_G, u_3), m*a_G) -",
    );
    let f = failed(&text);
    assert!(
        f.contains(&"Fs_3".to_string()) && f.contains(&"by_hand".to_string()),
        "{f:?}"
    );
}

#[test]
fn a_wrong_partial_velocity_is_rejected() {
    // The weight taken with C's partial velocity for u₃, not G's.
    let text = mutate(
        "dot(coeff(v_G, u_3), m*express([0, -g, 0] in N, A))",
        "dot(coeff(v_Cc, u_3), m*express([0, -g, 0] in N, A))",
    );
    let f = failed(&text);
    assert!(f.contains(&"Fr_3".to_string()), "{f:?}");
    // The partial velocity of u₁ used in u₃'s inertia force.
    let text = mutate(
        "-dot(coeff(v_G, u_3), m*a_G)",
        "-dot(coeff(v_G, u_1), m*a_G)",
    );
    let f = failed(&text);
    assert!(f.contains(&"Fs_3".to_string()), "{f:?}");
}

#[test]
fn a_dependent_speed_left_in_is_rejected() {
    // The partial velocities taken before u₂ = a u₃ is substituted: G's
    // partial velocity for u₃ comes out zero instead of a along y.
    let text = mutate(
        "value = \"subst(express(in_speeds(velocity(G)), A), u_2 = a*u_3)\"",
        "value = \"express(in_speeds(velocity(G)), A)\"",
    );
    let f = failed(&text);
    for s in ["Fr_3", "Fs_3", "by_hand"] {
        assert!(f.contains(&s.to_string()), "{s} not rejected: {f:?}");
    }
}

#[test]
fn a_dependent_or_undeclared_speed_in_a_meaning_is_a_clear_error() {
    let text = mutate(
        "means = \"generalized_active_force(sled, u_1)\"",
        "means = \"generalized_active_force(sled, u_9)\"",
    );
    let e = load_str("kane-sled.toml", &text).expect_err("u_9 is no speed");
    let msg = e.to_string();
    assert!(
        msg.contains("u_9") && msg.contains("speed") && msg.contains("kane-sled.toml"),
        "{msg}"
    );
    let text = mutate(
        "means = \"generalized_active_force(sled, u_1)\"",
        "means = \"generalized_active_force(sled, u_2)\"",
    );
    let e = check(&load(&text), &options()).expect_err("u_2 is dependent");
    assert!(e.to_string().contains("u_2"), "{e}");
}

/// A `[[load]]` at a body's centre (`point = "G2"`, the centre named by
/// the body, no `[[point]]` of it): Kane's equations measured on the
/// particles with the load there agree.
#[test]
fn a_load_at_a_body_s_centre_is_measured_there() {
    let text = include_str!("../sym/newcomer/centre-is-a-point.toml");
    let r = check(&load(text), &options()).unwrap_or_else(|e| panic!("{e}"));
    let k = r
        .steps
        .iter()
        .find(|s| s.step == "K")
        .expect("K is compared");
    assert!(k.passed, "{k:?}");
    // The load's share flipped in the derived equations is rejected.
    let wrong = text.replace(
        "value = \"kane([u1, u2])\"",
        "value = \"list(kane([u1, u2]).1, kane([u1, u2]).2 + 2*dot(express([F, 0, 0] in N, B), coeff(vG2, u2)))\"",
    );
    assert_ne!(wrong, text);
    let r = check(&load(&wrong), &options()).unwrap_or_else(|e| panic!("{e}"));
    let k = r.steps.iter().find(|s| s.step == "K").expect("K");
    assert!(!k.passed, "{k:?}");
}
