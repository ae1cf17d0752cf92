//! Kane's method (`kane`): the heavy top three ways — Newton–Euler,
//! Lagrange and Kane with the angle rates as speeds, and Kane with the
//! body rates as speeds — equal by canonical equality; and the located
//! errors of what Kane's method cannot take.

use hdot_sym::derivation::{Value, load_str};
use hdot_tests::{disk_frames, fixed_point, point, top_frames};

/// The heavy top with fixed tip O, G at l on the axis, inertia about O;
/// `SPEEDS` and `KINEMATICS` are spliced in.
const TOP: &str = concat!(
    r#"
title = "heavy top"
source = "test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["I", "Ip", "m", "g", "l"]
time = ["phi", "theta", "psi"]
SPEEDS
[kinematics]
KINEMATICS
"#,
    top_frames!("theta"),
    fixed_point!("O"),
    r#"[[body]]
name = "top"
frame = "R"
point = "O"
mass = "m"
mass_centre = "[0, 0, l] in R"
inertia = "principal(Ip, Ip, I)"
[[step]]
name = "H"
value = "express(principal(Ip, Ip, I) * angvel(R), F)"
[[step]]
name = "newton_euler"
value = "solve(dt(H) - cross([0, 0, l] in F, m*express([0, 0, -g] in N, F)), [phi'', theta'', psi''])"
[[step]]
name = "T"
value = "dot(angvel(R), principal(Ip, Ip, I) * angvel(R))/2"
[[step]]
name = "L"
value = "lagrange(T, m*g*l*cos(theta), [phi, theta, psi])"
"#,
);

fn top(speeds: &str, kinematics: &str, steps: &str) -> hdot_sym::derivation::Derivation {
    let text = TOP
        .replace("SPEEDS", speeds)
        .replace("KINEMATICS", kinematics)
        + steps;
    load_str("top.toml", &text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn kane_with_the_angle_rates_as_speeds_is_lagrange() {
    let d = top(
        "speeds = [\"u1\", \"u2\", \"u3\"]",
        "phi = \"u1\"\ntheta = \"u2\"\npsi = \"u3\"",
        r#"
[[step]]
name = "K"
value = "kane([u1, u2, u3])"
expect = ["in_speeds(L).1", "in_speeds(L).2", "in_speeds(L).3"]
[[step]]
name = "rates"
value = "solve(K, [u1', u2', u3'])"
expect = ["in_speeds(newton_euler).1", "in_speeds(newton_euler).2", "in_speeds(newton_euler).3"]
"#,
    );
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_eq!(d.check_count(), 6);
    let Value::List { items, .. } = &d.steps.iter().find(|s| s.name == "K").unwrap().value else {
        panic!("a list")
    };
    assert!(items.iter().all(|p| !p.is_zero()));
}

#[test]
fn kane_with_body_rates_as_speeds_gives_the_same_motion() {
    // u = Ω of the axes F (which do not spin) plus the spin rate: u1, u2
    // transverse, u3 = ω_z, the axial component of the top's ω.
    let d = top(
        "speeds = [\"u1\", \"u2\", \"u3\"]",
        "phi = \"-u1/sin(theta)\"\ntheta = \"u2\"\npsi = \"u3 + u1*cos(theta)/sin(theta)\"",
        r#"
[[step]]
name = "omega"
value = "in_speeds(express(angvel(R), F))"
expect = ["u1", "u2", "u3"]
[[step]]
name = "rates"
value = "solve(kane([u1, u2, u3]), [u1', u2', u3'])"
"#,
    );
    assert!(d.all_hold(), "{:?}", d.failures());
    // u̇ from Kane equals the rate of u along Newton–Euler's motion: the
    // rates of the F-components of ω with the accelerations substituted.
    let sym = &d.symbols;
    let get = |n: &str| d.steps.iter().find(|s| s.name == n).unwrap();
    let Value::List {
        items: rates,
        labels,
    } = &get("rates").value
    else {
        panic!()
    };
    assert_eq!(labels.len(), 3);
    let Value::List { items: acc, .. } = &get("newton_euler").value else {
        panic!()
    };
    // ω in F: (−φ̇ sin θ, θ̇, ψ̇ + φ̇ cos θ); its components' rates with
    // φ̈, θ̈, ψ̈ from Newton–Euler, then written in the speeds.
    let w = ["-phi'*sin(theta)", "theta'", "psi' + phi'*cos(theta)"];
    for (k, wk) in w.iter().enumerate() {
        let wd = sym.poly(wk).unwrap().dt();
        let wd = wd.subst(&mut |a| match a.name() {
            "phi" if a.order() == 2 => Some(acc[0].clone()),
            "theta" if a.order() == 2 => Some(acc[1].clone()),
            "psi" if a.order() == 2 => Some(acc[2].clone()),
            _ => None,
        });
        let wd = d.speeds.in_speeds(&wd);
        assert_eq!(rates[k], wd, "u{}'", k + 1);
    }
}

fn err(speeds: &str, kinematics: &str, step: &str) -> hdot_sym::derivation::Diagnostic {
    let text = TOP
        .replace("SPEEDS", speeds)
        .replace("KINEMATICS", kinematics)
        + &format!("[[step]]\nname = \"K\"\nvalue = \"{step}\"\n");
    load_str("top.toml", &text).unwrap_err()
}

#[test]
fn what_kane_cannot_take_is_a_located_error() {
    let s = "speeds = [\"u1\", \"u2\", \"u3\"]";
    let k = "phi = \"u1\"\ntheta = \"u2\"\npsi = \"u3\"";
    let e = err(s, "phi = \"u1\"\ntheta = \"u2\"", "kane([u1, u2, u3])");
    assert!(e.message.contains("give `psi` a kinematic equation"), "{e}");
    assert!(e.source_line.contains("kane("), "{e}");
    let e = err(s, k, "kane([u1, g])");
    assert!(e.message.contains("`g` is not a declared speed"), "{e}");
    assert_eq!(e.column, 20, "{e}");
    let e = err(
        s,
        "phi = \"u1^2\"\ntheta = \"u2\"\npsi = \"u3\"",
        "kane([u1, u2, u3])",
    );
    assert!(e.message.contains("not linear in the speeds"), "{e}");
    let text = TOP
        .replace("SPEEDS", s)
        .replace("KINEMATICS", k)
        .replace("fixed = true", "")
        + "[[step]]\nname = \"K\"\nvalue = \"kane([u1, u2, u3])\"\n";
    let e = load_str("top.toml", &text).unwrap_err();
    assert!(e.message.contains("point `O` moves freely"), "{e}");
    let text = TOP
        .replace("SPEEDS", s)
        .replace("KINEMATICS", k)
        .replace("mass = \"m\"\n", "")
        + "[[step]]\nname = \"K\"\nvalue = \"kane([u1, u2, u3])\"\n";
    let e = load_str("top.toml", &text).unwrap_err();
    assert!(e.message.contains("body `top` has no `mass`"), "{e}");
    let text = TOP
        .replace("SPEEDS", "")
        .replace("[kinematics]\nKINEMATICS", "")
        + "[[step]]\nname = \"K\"\nvalue = \"kane([phi])\"\n";
    let e = load_str("top.toml", &text).unwrap_err();
    assert!(e.message.contains("needs generalized speeds"), "{e}");
}

/// A uniform disk rolling without slipping on a plane: yaw ψ, lean θ,
/// spin φ and the contact point (x, y); speeds u1–u3 the disk's angular
/// velocity in the lean frame L, u4, u5 the contact point's rates,
/// dependent through the no-slip constraint.
const DISK: &str = concat!(
    r#"
title = "A disk rolling on a plane: Kane's equations"
source = "test"
gravity = "[0, 0, -g] in N"

[symbols]
constants = ["m", "g", "r"]
time = ["x", "y", "psi", "theta", "phi"]
speeds = ["u1", "u2", "u3", "u4", "u5"]

[kinematics]
x = "u4"
y = "u5"
theta = "u1"
psi = "u3/cos(theta)"
phi = "u2 - u3*sin(theta)/cos(theta)"

"#,
    disk_frames!(),
    fixed_point!("O"),
    point!("C", "O", "[x, y, 0] in N"),
    point!("G", "C", "[0, 0, r] in L"),
    r#"
[[body]]
name = "disk"
frame = "D"
point = "G"
mass = "m"
mass_centre = "[0, 0, 0] in D"
inertia = "principal(m*r^2/4, m*r^2/2, m*r^2/4)"

[[step]]
name = "omega"
value = "in_speeds(express(angvel(D), L))"
expect = ["u1", "u2", "u3"]

[[step]]
name = "contact"
value = "express(rolling(disk, C), A)"

[[step]]
name = "contact_z"
value = "contact.z"
expect = "0"

[[step]]
name = "no_slip"
value = "list(contact.x, contact.y)"

[[step]]
name = "dependent"
value = "solve(no_slip, [u4, u5])"

[[step]]
name = "K"
value = "kane([u1, u2, u3], no_slip, [u4, u5])"

[[step]]
name = "rates"
value = "solve(K, [u1', u2', u3'])"

[[step]]
name = "v_G"
value = "subst(velocity(G), u4 = dependent.1, u5 = dependent.2)"

[[step]]
name = "E"
value = "m*dot(v_G, v_G)/2 + dot(omega, principal(m*r^2/4, m*r^2/2, m*r^2/4)*omega)/2 + m*g*r*cos(theta)"

[[step]]
name = "dE"
value = "subst(in_speeds(dt(E)), u1' = rates.1, u2' = rates.2, u3' = rates.3)"
expect = "0"
"#,
);

#[test]
fn the_rolling_disk_eliminates_its_dependent_speeds_and_conserves_energy() {
    let d = load_str("disk.toml", DISK).unwrap_or_else(|e| panic!("{e}"));
    // The contact's vertical velocity vanishes identically, and the energy
    // is constant along the motion Kane's equations give (dE = 0).
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_eq!(d.check_count(), 5);
    let step = |n: &str| &d.steps.iter().find(|s| s.name == n).unwrap().value;
    let Value::List { items, labels } = step("rates") else {
        panic!()
    };
    assert_eq!(labels.len(), 3);
    // Eliminated: no dependent speed is left in the rates.
    for p in items {
        assert!(
            p.atoms().iter().all(|a| !["u4", "u5"].contains(&a.name())),
            "{p:?}"
        );
    }
    // A wrong inertia breaks the energy balance: the check can fail.
    let wrong = DISK.replace(
        "principal(m*r^2/4, m*r^2/2, m*r^2/4)\"\n\n[[step]]",
        "principal(m*r^2/4, m*r^2/3, m*r^2/4)\"\n\n[[step]]",
    );
    assert_ne!(wrong, DISK);
    let d = load_str("disk.toml", &wrong).unwrap();
    assert_eq!(d.failures().len(), 1, "{:?}", d.failures());
    assert_eq!(d.failures()[0].0, "dE");
}

fn disk_err(call: &str) -> hdot_sym::derivation::Diagnostic {
    let text = DISK.replace("kane([u1, u2, u3], no_slip, [u4, u5])", call);
    assert_ne!(text, DISK);
    load_str("disk.toml", &text).unwrap_err()
}

#[test]
fn bad_constraints_are_located_errors() {
    let e = disk_err("kane([u1, u2, u3], list(no_slip.1*u4, no_slip.2), [u4, u5])");
    assert!(
        e.message
            .contains("a constraint is not linear in the speeds"),
        "{e}"
    );
    assert!(e.source_line.contains("list(no_slip.1*u4"), "{e}");
    let e = disk_err("kane([u1, u2, u3], list(u1 + u2, u1 - u2), [u4, u5])");
    assert!(e.message.contains("cannot be eliminated"), "{e}");
    let e = disk_err("kane([u1, u2, u3], no_slip, [u4])");
    assert!(
        e.message
            .contains("2 independent constraint equations for 1 dependent speed"),
        "{e}"
    );
    let e = disk_err("kane([u1, u2, u3], no_slip, [u3, u4])");
    assert!(
        e.message
            .contains("`u3` is listed as independent and as dependent"),
        "{e}"
    );
    let e = disk_err("kane([u1, u2, u3])");
    assert!(
        e.message
            .contains("`u4` occurs in the velocities of disk but is not listed"),
        "{e}"
    );
    let e = disk_err("kane([u1, u2, u3], omega, [u4, u5, x])");
    assert!(e.message.contains("`x` is not a declared speed"), "{e}");
    let e = disk_err("kane([u1, u2, u3], rolling(G, C), [u4, u5])");
    assert!(e.message.contains("expected a declared body"), "{e}");
}

/// The worked example of docs/multibody.md, the TOML blocks of its
/// sections 1–6 in order (section 7 is the scene that simulates it), is a
/// derivation whose expectations hold and whose Kane's equations equal the
/// bundled file's.
#[test]
fn the_worked_example_in_the_docs_derives() {
    let root = hdot_tests::repo_root();
    let doc = std::fs::read_to_string(root.join("docs/multibody.md")).unwrap();
    let mut text = String::from("title = \"worked example\"\nsource = \"docs/multibody.md\"\n");
    let derivation = doc
        .split("\n## 7.")
        .next()
        .expect("the worked example has its sections");
    for block in derivation.split("```toml\n").skip(1) {
        text.push_str(block.split("```").next().unwrap());
    }
    let d = load_str("multibody.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_eq!(d.check_count(), 5);
    let path = root.join("derivations/disk-rolling-on-plane.toml");
    let bundled = load_str(
        "disk-rolling-on-plane.toml",
        &std::fs::read_to_string(path).unwrap(),
    )
    .unwrap();
    let k = |d: &hdot_sym::derivation::Derivation| {
        d.steps
            .iter()
            .find(|s| s.name == "K")
            .unwrap()
            .value
            .clone()
    };
    assert_eq!(k(&d), k(&bundled));
}

/// Loads: a torque M about the top's axis and a horizontal force at
/// the point Q on the axis at height a (force F_h). Kane's equations with the loads
/// equal Lagrange's with the generalized forces computed from the power of
/// the loads (∂/∂q̇ of T·ω + F·v_Q).
#[test]
fn loads_enter_kane_as_their_generalized_active_forces() {
    let text = TOP
        .replace("SPEEDS", "speeds = [\"u1\", \"u2\", \"u3\"]")
        .replace("KINEMATICS", "phi = \"u1\"\ntheta = \"u2\"\npsi = \"u3\"")
        .replace(
            "constants = [\"I\", \"Ip\", \"m\", \"g\", \"l\"]",
            "constants = [\"I\", \"Ip\", \"m\", \"g\", \"l\", \"a\", \"F_h\"]\ntime = [\"M\"]",
        )
        .replace("time = [\"phi\", \"theta\", \"psi\"]", "")
        .replace(
            "time = [\"M\"]",
            "time = [\"M\", \"phi\", \"theta\", \"psi\"]",
        )
        .replace(
            "[[body]]",
            "[[point]]\nname = \"Q\"\nfrom = \"O\"\nat = \"[0, 0, a] in R\"\n\
             [[load]]\nframe = \"R\"\ntorque = \"[0, 0, M] in R\"\n\
             [[load]]\npoint = \"Q\"\nforce = \"[F_h, 0, 0] in N\"\n[[body]]",
        )
        + r#"
[[step]]
name = "power"
value = "dot(angvel(R), [0, 0, M] in R) + dot(dt(express([0, 0, a] in R, N)), [F_h, 0, 0] in N)"
[[step]]
name = "L_loaded"
value = "lagrange(T, m*g*l*cos(theta), [phi, theta, psi], list(partial(power, phi'), partial(power, theta'), partial(power, psi')))"
[[step]]
name = "K"
value = "kane([u1, u2, u3])"
expect = ["in_speeds(L_loaded).1", "in_speeds(L_loaded).2", "in_speeds(L_loaded).3"]
[[step]]
name = "K_free"
value = "kane([u1, u2, u3]) - in_speeds(L)"
"#;
    let d = load_str("top.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_eq!(d.check_count(), 3);
    // Without the loads' share the equations differ: the loads count.
    let Value::List { items, .. } = &d.steps.iter().find(|s| s.name == "K_free").unwrap().value
    else {
        panic!()
    };
    assert!(items.iter().all(|p| !p.is_zero()));
    // A load that names an unknown point, or mixes force and torque.
    let bad = text.replace("point = \"Q\"\nforce", "point = \"Z\"\nforce");
    let e = load_str("top.toml", &bad).unwrap_err();
    assert!(e.message.contains("`Z` is not a declared point"), "{e}");
    let bad = text.replace("point = \"Q\"\nforce", "frame = \"R\"\nforce");
    let e = load_str("top.toml", &bad).unwrap_err();
    assert!(e.message.contains("either `point` with `force`"), "{e}");
}
