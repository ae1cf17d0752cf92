//! Generalized quantities under `[motion]`'s rules: the virtual
//! displacement of a coordinate moves the coordinates the rules tie to it
//! (the constrained partial velocities), so Lagrange's equation of the
//! constrained kinetic energy verifies as `generalized_force(body, q)`.
//! Files written here: a disk rolling down an incline (a rule in the
//! coordinates), a gear train (a chain of rules in the rates, two steps
//! long, two bodies), and a cone rolling with its apex fixed.

use crate::load;
use hdot_num::verify::{Options, check};
use hdot_tests::{fixed_point, frame, point, top_frames};

const OPTS: Options = Options {
    draws: 12,
    seed: 11,
};

/// x = r θ: the centre's position is a rule in the coordinates, so δθ
/// moves G by r along the incline.
const INCLINE: &str = concat!(
    r#"
title = "A disk rolling down an incline"
source = "test"
gravity = "[g*sin(beta), 0, -g*cos(beta)] in N"
[symbols]
constants = ["m", "g", "r", "beta", "A", "B"]
time = ["x", "theta"]
"#,
    frame!("D", "N", "y(theta)"),
    r#"[motion]
given = ["x = r*theta"]
vanishes = ["point_velocity(disk, C)"]
"#,
    fixed_point!("O"),
    point!("G", "O", "[x, 0, r] in N"),
    point!("C", "G", "[0, 0, -r] in N"),
    r#"[[body]]
name = "disk"
frame = "D"
point = "G"
mass = "m"
mass_centre = "[0, 0, 0] in D"
inertia = "principal(A, B, A)"
symmetry = "axisymmetric y"
[[step]]
name = "T"
value = "subst(m*x'^2/2 + B*theta'^2/2, x' = r*theta')"
means = "kinetic_energy(disk)"
[[step]]
name = "V"
value = "subst(-m*g*sin(beta)*x + m*g*cos(beta)*r, x = r*theta)"
means = "potential_energy(disk, O)"
[[step]]
name = "p_theta"
value = "partial(T, theta')"
means = "generalized_momentum(disk, theta)"
[[step]]
name = "L"
value = "lagrange(T, V, [theta])"
means = "list(generalized_force(disk, theta) - generalized_weight(disk, theta))"
"#,
);

#[test]
fn a_disk_rolling_down_an_incline_passes_with_the_natural_declaration() {
    let r = check(&load(INCLINE), &OPTS).unwrap();
    assert!(r.passed(), "{r:#?}");
    let names: Vec<&str> = r.steps.iter().map(|s| s.step.as_str()).collect();
    assert_eq!(names, ["T", "V", "p_theta", "L", "[motion] vanishes"]);
}

#[test]
fn lagrange_without_the_rolling_rule_fails_naming_the_step() {
    // Lagrange's equation of θ from the kinetic energy before the rule is
    // substituted (x held fixed): the unconstrained ∂r/∂θ would pass it.
    let wrong = INCLINE.replace(
        "value = \"lagrange(T, V, [theta])\"",
        "value = \"lagrange(m*x'^2/2 + B*theta'^2/2, V, [theta])\"",
    );
    let r = check(&load(&wrong), &OPTS).unwrap();
    assert_eq!(r.failed(), ["L"], "{r:#?}");
    let worst = r.worst().expect("a comparison");
    assert!(worst.quantity.starts_with("L"), "{worst:?}");
    // The weight's generalized force without the rolling rule's factor r.
    let wrong = INCLINE.replace("x = r*theta)\"", "x = theta)\"");
    let r = check(&load(&wrong), &OPTS).unwrap();
    assert_eq!(r.failed(), ["V", "L"], "{r:#?}");
}

/// Three gears on fixed axes: ψ̇ = −k φ̇ and χ̇ = −j ψ̇, so δφ turns ψ by
/// −k and χ by j k; a motor torque drives φ.
const GEARS: &str = concat!(
    r#"
title = "A gear train"
source = "test"
[symbols]
constants = ["A", "B", "C", "P_1", "P_2", "P_3", "k", "j", "a", "b"]
time = ["phi", "psi", "chi", "M_a"]
"#,
    frame!("P", "N", "z(phi)"),
    frame!("Q", "N", "z(psi)"),
    frame!("S", "N", "z(chi)"),
    r#"[motion]
given = ["psi' = -k*phi'", "chi' = -j*psi'"]
"#,
    fixed_point!("O_1"),
    r#"[[point]]
name = "O_2"
fixed = true
at = "[a, 0, 0] in N"
[[point]]
name = "O_3"
fixed = true
at = "[a, b, 0] in N"
[[body]]
name = "first"
frame = "P"
point = "O_1"
centre = "G_1"
mass_centre = "[0, 0, 0] in P"
inertia = "principal(P_1, P_1, A)"
symmetry = "axisymmetric z"
[[body]]
name = "second"
frame = "Q"
point = "O_2"
centre = "G_2"
mass_centre = "[0, 0, 0] in Q"
inertia = "principal(P_2, P_2, B)"
symmetry = "axisymmetric z"
[[body]]
name = "third"
frame = "S"
point = "O_3"
centre = "G_3"
mass_centre = "[0, 0, 0] in S"
inertia = "principal(P_3, P_3, C)"
symmetry = "axisymmetric z"
[[step]]
name = "T"
value = "subst(subst((A*phi'^2 + B*psi'^2 + C*chi'^2)/2, chi' = -j*psi'), psi' = -k*phi')"
means = "kinetic_energy(system)"
[[step]]
name = "p_phi"
value = "partial(T, phi')"
means = "generalized_momentum(system, phi)"
[[step]]
name = "L"
value = "lagrange(T, 0, [phi], list(M_a))"
means = "list(generalized_force(system, phi) - applied(M_a))"
[[step]]
name = "M"
value = "mass_matrix(L, [phi''])"
means = "mass_matrix(list(generalized_force(system, phi) - applied(M_a)), [phi''])"
[[step]]
name = "f"
value = "forcing(L, [phi''])"
means = "forcing(list(generalized_force(system, phi) - applied(M_a)), [phi''])"
"#,
);

#[test]
fn a_gear_train_passes_through_a_chain_of_rules() {
    let r = check(&load(GEARS), &OPTS).unwrap();
    assert!(r.passed(), "{r:#?}");
    assert_eq!(r.steps.len(), 5);
    // The rules in the other order: the chain is followed all the same
    // (the motion the rules draw differs, the steps hold along it).
    let swapped = GEARS.replace(
        "given = [\"psi' = -k*phi'\", \"chi' = -j*psi'\"]",
        "given = [\"chi' = j*k*phi'\", \"psi' = -k*phi'\"]",
    );
    let r = check(&load(&swapped), &OPTS).unwrap();
    assert!(r.passed(), "{r:#?}");
}

#[test]
fn mutants_of_the_gear_train_fail_at_the_mutated_step() {
    let mutants = [
        // The last gear forgotten in T (and so in everything after).
        (
            "B*psi'^2 + C*chi'^2",
            "B*psi'^2",
            &["T", "p_phi", "L", "M"][..],
        ),
        // A wrong ratio in the chain.
        (
            "chi' = -j*psi'), psi'",
            "chi' = -psi'), psi'",
            &["T", "p_phi", "L", "M"],
        ),
        // The torque's sign.
        ("list(M_a))\"", "list(-M_a))\"", &["L", "f"]),
        // Lagrange's equation of the unconstrained T (ψ, χ held fixed).
        (
            "lagrange(T, 0,",
            "lagrange((A*phi'^2 + B*psi'^2 + C*chi'^2)/2, 0,",
            &["L", "M"],
        ),
    ];
    for (from, to, expected) in mutants {
        assert!(GEARS.contains(from), "{from}");
        let r = check(&load(&GEARS.replace(from, to)), &OPTS).unwrap();
        let bad = r.failed();
        for s in expected {
            assert!(bad.contains(s), "{from} → {to}: {bad:?}");
        }
    }
}

/// A cone rolling on the floor with its apex fixed: rolling ties ψ̇ to φ̇
/// through the tilt γ, and Lagrange's equation of φ means the generalized
/// force of φ, as written most naturally.
const CONE: &str = concat!(
    r#"
title = "A cone rolling with its apex fixed"
source = "test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "c", "I", "Ip", "gamma", "s"]
time = ["phi", "psi"]
"#,
    top_frames!("gamma"),
    r#"[motion]
given = ["psi' = -phi'/cos(gamma)"]
vanishes = ["point_velocity(cone, C)"]
"#,
    fixed_point!("O"),
    point!("C", "O", "[s, 0, 0] in P"),
    r#"[[body]]
name = "cone"
frame = "R"
point = "O"
mass = "m"
mass_centre = "[0, 0, c] in R"
inertia = "principal(Ip, Ip, I)"
symmetry = "axisymmetric z"
[[step]]
name = "omega_r"
value = "subst(express(angvel(R), F), psi' = -phi'/cos(gamma))"
means = "angular_velocity(R)"
[[step]]
name = "H"
value = "principal(Ip, Ip, I) * omega_r"
means = "angular_momentum(cone, O)"
[[step]]
name = "T"
value = "dot(omega_r, H)/2"
means = "kinetic_energy(cone)"
[[step]]
name = "V"
value = "m*g*c*cos(gamma)"
means = "potential_energy(cone, O)"
[[step]]
name = "lagrange"
value = "lagrange(T, V, [phi])"
means = "list(generalized_force(cone, phi) - generalized_weight(cone, phi))"
[[step]]
name = "along_axes"
value = "lagrange(T, V, [phi])"
means = "list(along(moment(cone, O) - weight_moment(cone, O), [0, 0, 1] in P) + along(moment(cone, O) - weight_moment(cone, O), [0, 0, -1/cos(gamma)] in F))"
[[step]]
name = "mass_matrix"
value = "mass_matrix(lagrange, [phi''])"
means = "mass_matrix(list(generalized_force(cone, phi)), [phi''])"
[[step]]
name = "p_phi"
value = "partial(T, phi')"
means = "generalized_momentum(cone, phi)"
"#,
);

#[test]
fn a_rolling_cone_passes_with_the_generalized_force_of_phi() {
    let r = check(&load(CONE), &OPTS).unwrap();
    assert!(r.passed(), "{r:#?}");
    assert_eq!(r.steps.len(), 9);
    // Without the rolling rule's factor 1/cos γ in the derived ω, every
    // step from ω on fails, Lagrange's equation among them.
    let wrong = CONE.replace("psi' = -phi'/cos(gamma))\"", "psi' = -phi')\"");
    let r = check(&load(&wrong), &OPTS).unwrap();
    let bad = r.failed();
    for s in ["omega_r", "T", "lagrange", "mass_matrix", "p_phi"] {
        assert!(bad.contains(&s), "{bad:?}");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 24, rng_seed: proptest::test_runner::RngSeed::Fixed(5), ..Default::default() })]
    /// Every draw of the constrained files passes: the constrained
    /// displacement has no false alarm.
    #[test]
    fn every_draw_of_a_constrained_file_passes(seed in proptest::prelude::any::<u64>()) {
        for text in [INCLINE, GEARS, CONE] {
            let r = check(&load(text), &Options { draws: 1, seed }).unwrap();
            proptest::prop_assert!(r.passed(), "{:?}", r.worst());
        }
    }
}
