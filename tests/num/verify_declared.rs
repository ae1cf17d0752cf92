//! Verification from declarations (`[[body]]`, `[[point]]`, `means`) on
//! derivation files written here, and the errors of bad declarations.

use crate::load;
use hdot_num::verify::{Options, check};
use hdot_sym::derivation::load_str;

fn err(text: &str) -> String {
    load_str("test.toml", text)
        .expect_err("should fail")
        .to_string()
}

const OPTS: Options = Options { draws: 12, seed: 7 };

/// A heavy top written from the docs: moments about the fixed tip, the
/// weight's moment, energies, the solved accelerations and Lagrange's
/// equations, all against particle sums.
const TOP: &str = r#"
title = "top"
source = "test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "l", "I", "Ip"]
time = ["phi", "theta", "psi"]
[[frame]]
name = "P"
parent = "N"
rotation = "z(phi)"
[[frame]]
name = "F"
parent = "P"
rotation = "y(theta)"
[[frame]]
name = "R"
parent = "F"
rotation = "z(psi)"
[[point]]
name = "O"
fixed = true
[[body]]
name = "top"
frame = "R"
point = "O"
mass = "m"
mass_centre = "[0, 0, l] in R"
inertia = "principal(Ip, Ip, I)"
symmetry = "axisymmetric z"
[[step]]
name = "omega"
value = "express(angvel(R), F)"
means = "angular_velocity(R)"
[[step]]
name = "H"
value = "principal(Ip, Ip, I) * omega"
means = "angular_momentum(top, O)"
[[step]]
name = "M"
value = "dt_rel(H) + cross(angvel(F), H)"
means = "moment(top, O)"
[[step]]
name = "M_W"
value = "cross([0, 0, l] in F, m*express([0, 0, -g] in N, F))"
means = "weight_moment(top, O)"
[[step]]
name = "acc"
value = "solve(M - M_W, [phi'', theta'', psi''])"
means = "solves(moment(top, O) - weight_moment(top, O))"
[[step]]
name = "T"
value = "dot(omega, H)/2"
means = "kinetic_energy(top)"
[[step]]
name = "V"
value = "m*g*l*cos(theta)"
means = "potential_energy(top, O)"
[[step]]
name = "L"
value = "lagrange(T, V, [phi, theta, psi])"
means = "list(generalized_force(top, phi) - generalized_weight(top, phi), generalized_force(top, theta) - generalized_weight(top, theta), generalized_force(top, psi) - generalized_weight(top, psi))"
[[step]]
name = "M_steady"
value = "subst(M, theta' = 0, phi'' = 0, psi'' = 0)"
means = "moment(top, O)"
given = ["theta' = 0", "phi'' = 0", "psi'' = 0"]
[[step]]
name = "G_velocity"
value = "cross(omega, [0, 0, l] in F)"
means = "velocity(G)"
"#;

#[test]
fn a_heavy_top_written_here_passes_every_meaning() {
    let d = load(TOP);
    let r = check(&d, &OPTS).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.draws, 12);
    assert_eq!(r.steps.len(), 10, "{r:#?}");
    for s in &r.steps {
        assert!(s.passed, "{s:#?}");
    }
    assert!(r.not_compared.is_empty());
}

#[test]
fn a_wrong_step_fails_naming_the_step_and_component() {
    // The sign of the transport term flipped.
    let d = load(&TOP.replace(
        "dt_rel(H) + cross(angvel(F), H)",
        "dt_rel(H) - cross(angvel(F), H)",
    ));
    let r = check(&d, &OPTS).unwrap();
    assert!(!r.passed());
    let bad = r.failed();
    assert!(bad.contains(&"M"), "{bad:?}");
    let worst = r.worst().expect("a comparison");
    assert!(
        worst.quantity.starts_with("M") || worst.quantity.starts_with("acc"),
        "{worst:?}"
    );
    // The wrong frame's angular velocity in the transport theorem.
    let d = load(&TOP.replace(
        "dt_rel(H) + cross(angvel(F), H)",
        "dt_rel(H) + cross(express(angvel(R), F), H)",
    ));
    assert!(!check(&d, &OPTS).unwrap().passed());
    // A frame's rotation axis changed changes the declared motion with the
    // steps: the mutant is a consistent other problem, and passes.
    let d = load(&TOP.replace("rotation = \"y(theta)\"", "rotation = \"x(theta)\""));
    assert!(check(&d, &OPTS).unwrap().passed());
    // Two inertia arguments swapped in a step (not in the declaration).
    let d = load(&TOP.replace(
        "value = \"principal(Ip, Ip, I) * omega\"",
        "value = \"principal(Ip, I, Ip) * omega\"",
    ));
    assert!(!check(&d, &OPTS).unwrap().passed());
}

/// A free body in its own axes: the frame is given by its angular
/// velocity, G moves freely, v̄ is known.
#[test]
fn a_free_body_with_a_known_velocity_passes() {
    let d = load(
        r#"
title = "free"
source = "test"
[symbols]
constants = ["m", "I_x", "I_y", "I_z", "I_xy", "I_yz", "I_zx"]
time = ["w_x", "w_y", "w_z", "v_x", "v_y", "v_z"]
[[frame]]
name = "B"
angular_velocity = "[w_x, w_y, w_z]"
[[body]]
name = "b"
frame = "B"
mass = "m"
inertia = "inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx)"
[[known]]
value = "[v_x, v_y, v_z] in B"
means = "velocity(G)"
[[step]]
name = "H"
value = "inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx) * angvel(B)"
means = "angular_momentum(b, G)"
[[step]]
name = "M"
value = "dt_rel(H) + cross(angvel(B), H)"
means = "moment(b, G)"
[[step]]
name = "p"
value = "m*[v_x, v_y, v_z] in B"
means = "momentum(b)"
[[step]]
name = "F"
value = "m*(dt_rel([v_x, v_y, v_z] in B) + cross(angvel(B), [v_x, v_y, v_z] in B))"
means = "force(b)"
[[step]]
name = "T"
value = "m*(v_x^2 + v_y^2 + v_z^2)/2 + dot(angvel(B), H)/2"
means = "kinetic_energy(b)"
[[step]]
name = "I"
value = "inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx)"
means = "inertia(b, G, B)"
[[step]]
name = "w"
value = "angvel(B)"
"#,
    );
    let r = check(&d, &OPTS).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.steps.len(), 6);
    assert!(r.passed(), "{r:#?}");
    assert_eq!(r.not_compared, ["w"]);
}

/// A body pivoted at a point O of its own, its inertia given about G: a
/// step's `symmetry` makes the body symmetric for that step only, and
/// `O' = 0` puts the free point O at rest for that step only.
const PIVOT: &str = r#"
title = "pivot"
source = "test"
[symbols]
constants = ["m", "A", "B", "C", "D", "E", "F", "a", "b", "c"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "K"
angular_velocity = "[w_x, w_y, w_z]"
[[point]]
name = "O"
[[body]]
name = "b"
frame = "K"
point = "O"
mass = "m"
mass_centre = "[a, b, c] in K"
inertia = "inertia(A, B, C, D, E, F)"
inertia_about = "G"
[[step]]
name = "H_G"
value = "inertia(A, B, C, D, E, F) * angvel(K)"
means = "angular_momentum(b, G)"
[[step]]
name = "H_G_principal"
value = "principal(A, B, C) * angvel(K)"
means = "angular_momentum(b, G)"
symmetry = { b = "principal" }
[[step]]
name = "v_G"
value = "cross(angvel(K), [a, b, c] in K)"
means = "velocity(G)"
given = ["O' = 0"]
[[step]]
name = "H_O"
value = "cross([a, b, c] in K, m*v_G) + H_G"
means = "angular_momentum(b, O)"
given = ["O' = 0"]
"#;

#[test]
fn step_conditions_on_symmetry_and_rest_hold_for_that_step_only() {
    let r = check(&load(PIVOT), &OPTS).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.steps.len(), 4);
    assert!(r.passed(), "{r:#?}");
    // Without the condition the same step fails: the drawn body has
    // products of inertia, and O moves.
    for (from, to, step) in [
        ("symmetry = { b = \"principal\" }\n", "", "H_G_principal"),
        ("given = [\"O' = 0\"]\n", "", "v_G"),
    ] {
        let text = PIVOT.replacen(from, to, 1);
        assert_ne!(text, PIVOT);
        let r = check(&load(&text), &OPTS).unwrap_or_else(|e| panic!("{e}"));
        let s = r.steps.iter().find(|s| s.step == step).unwrap();
        assert!(!s.passed, "{step} passes without its condition");
        assert!(r.steps.iter().filter(|s| s.step != step).all(|s| s.passed));
    }
}

#[test]
fn bad_step_conditions_are_located() {
    let e = err(&PIVOT.replace("{ b = \"principal\" }", "{ rotor = \"principal\" }"));
    assert!(
        e.contains("unknown body `rotor`") && e.contains("test.toml:"),
        "{e}"
    );
    let e = err(&PIVOT.replace("{ b = \"principal\" }", "{ b = \"round\" }"));
    assert!(e.contains("expected `none`, `principal`"), "{e}");
    let e = err(&PIVOT.replacen("given = [\"O' = 0\"]", "given = [\"O' = 1\"]", 1));
    assert!(e.contains("at rest"), "{e}");
    let e = err(&PIVOT.replace(
        "[[point]]\nname = \"O\"\n",
        "[[point]]\nname = \"O\"\nfixed = true\n",
    ));
    assert!(e.contains("only a point that moves freely"), "{e}");
    let e = err(&PIVOT.replace("inertia_about = \"G\"", "inertia_about = \"Q\""));
    assert!(
        e.contains("`inertia_about` is the reference point (O) or the body's centre (G)"),
        "{e}"
    );
    let e = err(&PIVOT.replace("mass_centre = \"[a, b, c] in K\"\n", ""));
    assert!(e.contains("`mass_centre` says where the centre is"), "{e}");
    let e = err(&PIVOT.replace("means = \"angular_momentum(b, G)\"\nsymmetry", "symmetry"));
    assert!(
        e.contains("`symmetry` is the condition of a step's `means`"),
        "{e}"
    );
}

#[test]
fn a_zero_declared_without_its_symmetry_is_an_error_naming_the_entry() {
    let d = load(&TOP.replace("symmetry = \"axisymmetric z\"", ""));
    let e = check(&d, &OPTS).expect_err("no symmetry").to_string();
    assert!(
        e.contains("mass centre") || e.contains("inertia entry"),
        "{e}"
    );
}

#[test]
fn bad_declarations_are_located() {
    let e = err(&TOP.replace("means = \"moment(top, O)\"", "means = \"moment(rotor, O)\""));
    assert!(
        e.contains("unknown body `rotor`") && e.contains("test.toml:"),
        "{e}"
    );
    let e = err(&TOP.replace("means = \"moment(top, O)\"", "means = \"moment(top, Q)\""));
    assert!(e.contains("unknown point `Q`"), "{e}");
    let e = err(&TOP.replace("frame = \"R\"", "frame = \"S\""));
    assert!(e.contains("unknown frame `S`"), "{e}");
    let e = err(&TOP.replace(
        "means = \"kinetic_energy(top)\"",
        "means = \"momentum(top)\"",
    ));
    assert!(
        e.contains("the meaning is a vector, but the step is a scalar"),
        "{e}"
    );
    // The caret is under the `means` value, line and column given.
    let line = TOP.lines().position(|l| l == "means = \"momentum(top)\"");
    assert!(line.is_none());
    let text = TOP.replace(
        "means = \"kinetic_energy(top)\"",
        "means = \"momentum(top)\"",
    );
    let want = text
        .lines()
        .position(|l| l == "means = \"momentum(top)\"")
        .unwrap()
        + 1;
    assert!(e.contains(&format!("test.toml:{want}:10")), "{e}");
    let e = err(&TOP.replace("gravity = \"[0, 0, -g] in N\"", ""));
    assert!(e.contains("needs `gravity`"), "{e}");
    let e = err(&TOP.replace(
        "symmetry = \"axisymmetric z\"",
        "symmetry = \"axisymmetric w\"",
    ));
    assert!(e.contains("axisymmetric"), "{e}");
    // A constant may be fixed by a condition, but not one the bodies bind.
    let e = err(&TOP.replace("given = [\"theta' = 0\"", "given = [\"m = 0\""));
    assert!(e.contains("measured on the particles"), "{e}");
}

#[test]
fn files_without_declarations_have_no_physics_and_nothing_compared() {
    let d = load(
        r#"
title = "plain"
source = "test"
[symbols]
constants = ["I"]
time = ["w"]
[[step]]
name = "H"
value = "I*w"
"#,
    );
    assert!(d.physics.bodies.is_empty() && d.steps[0].meaning.is_none());
    let r = check(&d, &OPTS).unwrap();
    assert!(r.steps.is_empty() && r.draws == 0);
    assert!(r.hint(&d).unwrap().contains("[[body]]"));
}

#[test]
fn every_quantity_has_one_particle_sum() {
    use hdot_num::verify::quantities::REGISTRY;
    use hdot_sym::derivation::physics::QUANTITIES;
    for q in QUANTITIES {
        let n = REGISTRY.iter().filter(|m| m.quantity == q.quantity).count();
        assert_eq!(n, 1, "{}", q.name);
    }
    assert_eq!(REGISTRY.len(), QUANTITIES.len());
    // The call the docs show is the quantity's name with its arguments.
    for m in REGISTRY {
        let sig = m.quantity.sig();
        let (name, args) = m.call.split_once('(').expect("a call");
        assert_eq!(name, sig.name);
        assert_eq!(args.split(',').count(), sig.args.len(), "{}", m.call);
    }
}

#[test]
fn every_combinator_of_the_parser_has_one_entry() {
    use hdot_num::verify::means::COMBINATORS as ENTRIES;
    use hdot_sym::derivation::physics::COMBINATORS;
    for name in COMBINATORS {
        let n = ENTRIES.iter().filter(|c| c.name == *name).count();
        assert_eq!(n, 1, "{name}");
        let c = ENTRIES.iter().find(|c| c.name == *name).unwrap();
        assert!(c.call.starts_with(&format!("{name}(")), "{}", c.call);
    }
    // Besides the functions: the operators `+` and `*`.
    assert_eq!(ENTRIES.len(), COMBINATORS.len() + 2);
    assert!(ENTRIES.iter().any(|c| c.name == "+") && ENTRIES.iter().any(|c| c.name == "*"));
}

/// The tables of *Meanings* in docs/derivation-format.md are the
/// registries'.
#[test]
fn docs_list_every_meaning_of_the_registries() {
    use hdot_num::verify::means::{combinators_table, quantities_table};
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/derivation-format.md");
    let mut doc = std::fs::read_to_string(&path).unwrap();
    let mut stale = Vec::new();
    for (marker, table) in [
        ("quantities", quantities_table()),
        ("combinators", combinators_table()),
    ] {
        let begin = format!("<!-- means:{marker}:begin -->\n");
        let end = format!("<!-- means:{marker}:end -->");
        let a = doc.find(&begin).expect("begin marker") + begin.len();
        let b = doc.find(&end).expect("end marker");
        if doc[a..b] != table {
            stale.push(marker);
            doc = format!("{}{}{}", &doc[..a], table, &doc[b..]);
        }
    }
    if !stale.is_empty() {
        if std::env::var_os("HDOT_UPDATE_DOCS").is_some() {
            std::fs::write(&path, doc).unwrap();
        } else {
            panic!(
                "docs/derivation-format.md's {stale:?} table differs from the registry; rerun with \
                 HDOT_UPDATE_DOCS=1 to regenerate it"
            );
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 24, rng_seed: proptest::test_runner::RngSeed::Fixed(3), ..Default::default() })]
    /// As a user's own property test would: every draw (a body with the
    /// declared symmetry and a motion) of the heavy top written above passes.
    #[test]
    fn every_draw_of_a_declared_body_passes(seed in proptest::prelude::any::<u64>()) {
        let d = load(TOP);
        let r = check(&d, &Options { draws: 1, seed }).unwrap();
        proptest::prop_assert!(r.passed(), "{:?}", r.worst());
    }
}

/// A wheel rolling along a straight line, driven by a torque: the rolling
/// rule under `[motion]`, the contact point's material velocity declared
/// to vanish, and Lagrange's equation with the torque as `applied(…)`.
const WHEEL: &str = r#"
title = "wheel"
source = "test"
[symbols]
constants = ["m", "r", "A", "B", "C"]
time = ["x", "theta", "M_a"]
[[frame]]
name = "W"
parent = "N"
rotation = "y(theta)"
[motion]
given = ["x' = r*theta'"]
vanishes = ["point_velocity(wheel, C)"]
[[point]]
name = "O"
fixed = true
[[point]]
name = "G"
from = "O"
at = "[x, 0, r] in N"
[[point]]
name = "C"
from = "G"
at = "[0, 0, -r] in N"
[[body]]
name = "wheel"
frame = "W"
point = "G"
mass = "m"
mass_centre = "[0, 0, 0] in W"
inertia = "principal(A, B, C)"
symmetry = "principal"
[[step]]
name = "v_C"
value = "[x', 0, 0] in N + cross(express(angvel(W), N), [0, 0, -r] in N)"
means = "point_velocity(wheel, C)"
[[step]]
name = "T"
value = "subst(m*x'^2/2 + B*theta'^2/2, x' = r*theta')"
means = "kinetic_energy(wheel)"
[[step]]
name = "L"
value = "lagrange(T, 0, [theta], list(M_a))"
means = "list(along(moment(wheel, G), [0, 1, 0] in N) + along(force(wheel), [r, 0, 0] in N) - applied(M_a))"
"#;

#[test]
fn a_rolling_wheel_with_a_driving_torque_passes() {
    let r = check(&load(WHEEL), &OPTS).unwrap();
    assert!(r.passed(), "{r:#?}");
    let names: Vec<&str> = r.steps.iter().map(|s| s.step.as_str()).collect();
    assert_eq!(names, ["v_C", "T", "L", "[motion] vanishes"]);
    // A wrong rolling rule fails at the constraint (and where it is used).
    let wrong = WHEEL.replace("x' = r*theta'", "x' = -r*theta'");
    let r = check(&load(&wrong), &OPTS).unwrap();
    let failed = r.failed();
    assert!(failed.contains(&"[motion] vanishes"), "{failed:?}");
    // The torque with the wrong sign fails in Lagrange's equation only.
    let wrong = WHEEL.replace("list(M_a))\"", "list(-M_a))\"");
    let r = check(&load(&wrong), &OPTS).unwrap();
    let failed = r.failed();
    assert_eq!(failed, ["L"]);
}

#[test]
fn the_point_of_a_body_is_of_one_body_and_applied_is_scalar() {
    let text = WHEEL.replace(
        "point_velocity(wheel, C)\"\n[[step]]",
        "point_velocity(system, C)\"\n[[step]]",
    );
    let e = err(&text);
    assert!(e.contains("test.toml:") && e.contains("one body"), "{e}");
    let text = WHEEL.replace(
        "vanishes = [\"point_velocity(wheel, C)\"]",
        "vanishes = [\"inertia(wheel, G, W)\"]",
    );
    let e = err(&text);
    assert!(e.contains("test.toml:") && e.contains("`vanishes`"), "{e}");
    let text = WHEEL.replace("- applied(M_a))", "- applied([M_a, 0, 0] in N))");
    let e = err(&text);
    assert!(e.contains("test.toml:") && e.contains("scalar"), "{e}");
}

/// A plate at rest, its principal axes B turned by a fixed angle β from N,
/// struck at a point given in B by an impulse given in N: v̄ and ω after
/// the blow against the particles' impulse–momentum solve.
const STRUCK: &str = r#"
title = "struck plate"
source = "test"
[symbols]
constants = ["m", "A", "Bm", "C", "beta", "F_1", "F_2", "F_3", "a", "b", "c", "u_1", "u_2", "u_3", "w_1", "w_2", "w_3"]
[[frame]]
name = "B"
parent = "N"
rotation = "z(beta)"
[[point]]
name = "Q"
from = "G"
at = "[a, b, c] in B"
[[body]]
name = "plate"
frame = "B"
point = "G"
mass = "m"
inertia = "principal(A, Bm, C)"
symmetry = "principal"
[[step]]
name = "J"
value = "[F_1, F_2, F_3] in N"
[[step]]
name = "v"
value = "solve(m*[u_1, u_2, u_3] in N - J, [u_1, u_2, u_3])"
means = "velocity_after_impulse(plate, Q, [F_1, F_2, F_3] in N)"
[[step]]
name = "w"
value = "solve(principal(A, Bm, C) * ([w_1, w_2, w_3] in B) - cross([a, b, c] in B, express(J, B)), [w_1, w_2, w_3])"
means = "angular_velocity_after_impulse(plate, Q, [F_1, F_2, F_3] in N)"
"#;

#[test]
fn a_struck_body_written_here_passes_and_a_wrong_one_fails() {
    let r = check(&load(STRUCK), &OPTS).unwrap_or_else(|e| panic!("{e}"));
    let compared: Vec<&str> = r.steps.iter().map(|s| s.step.as_str()).collect();
    assert_eq!(compared, ["v", "w"]);
    assert!(r.passed(), "{r:#?}");
    // Two moments swapped in the step (not in the declaration).
    let d = load(&STRUCK.replace(
        "value = \"solve(principal(A, Bm, C)",
        "value = \"solve(principal(Bm, A, C)",
    ));
    let r = check(&d, &OPTS).unwrap();
    let failed = r.failed();
    assert_eq!(failed, ["w"]);
    assert!(r.worst().unwrap().quantity.starts_with("w."));
    // The moment arm about the wrong point (r_P taken as zero).
    let d = load(&STRUCK.replace("cross([a, b, c] in B", "cross([0, b, c] in B"));
    assert!(!check(&d, &OPTS).unwrap().passed());
    // The response of one body, to a vector impulse.
    let e = err(&STRUCK.replace(
        "velocity_after_impulse(plate, Q,",
        "velocity_after_impulse(system, Q,",
    ));
    assert!(
        e.contains("test.toml:") && e.contains("one free body"),
        "{e}"
    );
    let e = err(&STRUCK.replace("Q, [F_1, F_2, F_3] in N)\"\n[[step]]", "Q, m)\"\n[[step]]"));
    assert!(e.contains("test.toml:") && e.contains("vector"), "{e}");
}

/// The bundled impulse file on many bodies and seeds: the measured response
/// carries the round-off of the inertia it is divided by and of the moment
/// arm, and no draw is a false alarm (a 6 × 6 solve once coupled the
/// round-off of Σ m ρ into v̄ and failed at 2000 bodies, seed 1).
#[test]
fn the_impulse_response_has_no_false_alarm_over_many_bodies() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../derivations/impulse-momentum.toml"
    );
    let d =
        hdot_sym::derivation::load(std::path::Path::new(path)).unwrap_or_else(|e| panic!("{e}"));
    for seed in 1..=2 {
        let r = check(&d, &Options { draws: 2000, seed }).unwrap();
        assert!(r.passed(), "seed {seed}: {:?}", r.worst());
    }
}

/// A gyrostat (a platform with a rotor spun at the rate s on its z axis)
/// whose Euler equations are written in the moments A, B, C of the whole:
/// a `[[known]]` whose value is a matrix binds them from the system's
/// inertia (trial 2 §10), so the step verifies, and a wrong sign fails
/// naming it.
const GYROSTAT: &str = r#"
title = "gyrostat"
source = "test"
[symbols]
constants = ["Ap", "Bp", "Cp", "J", "Jt", "A", "B", "C", "s"]
time = ["w_x", "w_y", "w_z", "beta"]
[motion]
given = ["beta' = s"]
[[frame]]
name = "P"
angular_velocity = "[w_x, w_y, w_z]"
[[frame]]
name = "W"
parent = "P"
rotation = "z(beta)"
[[point]]
name = "G"
fixed = true
[[body]]
name = "platform"
frame = "P"
point = "G"
mass_centre = "[0, 0, 0] in P"
inertia = "principal(Ap, Bp, Cp)"
symmetry = "principal"
[[body]]
name = "rotor"
frame = "W"
point = "G"
mass_centre = "[0, 0, 0] in W"
inertia = "principal(Jt, Jt, J)"
symmetry = "axisymmetric z"
[[known]]
value = "principal(A, B, C)"
means = "inertia(system, G, P)"
[[step]]
name = "H"
value = "subst(principal(Ap, Bp, Cp)*angvel(P) + express(principal(Jt, Jt, J)*angvel(W), P), beta' = s)"
means = "angular_momentum(system, G)"
[[step]]
name = "euler"
value = "subst(dt(H), Ap = A - Jt, Bp = B - Jt, Cp = C - J)"
means = "moment(system, G)"
"#;

#[test]
fn a_matrix_known_binds_the_moments_of_the_whole() {
    let r = check(&load(GYROSTAT), &OPTS).unwrap();
    assert!(r.passed() && r.steps.len() == 2, "{r:#?}");

    let wrong = GYROSTAT.replace("Cp = C - J)", "Cp = C + J)");
    assert_ne!(wrong, GYROSTAT);
    let r = check(&load(&wrong), &OPTS).unwrap();
    let failed = r.failed();
    assert_eq!(failed, ["euler"], "{r:#?}");

    // A matrix known that the bodies contradict is an error naming it.
    let e = check(
        &load(&GYROSTAT.replace("principal(A, B, C)\"", "principal(A, A, C)\"")),
        &OPTS,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("inertia(system, G, P)"), "{e}");
}
