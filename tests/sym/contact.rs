//! Rolling contacts (`[[contact]]`): the disk rolling on a plane written
//! with a declared contact gives the bundled file's Kane's equations; the
//! same disk with an auxiliary angle χ for its contact direction (a
//! configuration constraint keeps the rim's lowest point) gives them too
//! where that constraint holds, and to first order about upright rolling;
//! the nonlinear bicycle's linearized lean and steer matrices are the
//! linear bicycle's; bad declarations are located errors.

use hdot_sym::derivation::{Derivation, Value, load, load_str};
use hdot_tests::repo_root;

fn step<'d>(d: &'d Derivation, name: &str) -> &'d Value {
    &d.steps
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("{}: no step {name}", d.name))
        .value
}

fn bundled(path: &str) -> Derivation {
    load(&repo_root().join(path)).unwrap_or_else(|e| panic!("{e}"))
}

/// The rolling disk (yaw ψ, lean θ, spin φ; the wheel's place (x, y) on
/// the ground) declared with a `[[contact]]`; `SPEEDS`, `KINEMATICS`,
/// `CONTACT` and `STEPS` are spliced in.
const DISK: &str = r#"
title = "a disk rolling on a plane, its contact declared"
source = "written for the test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "r", "I", "J", "Omega"]
time = ["x", "y", "psi", "theta", "phi"TIME]
speeds = ["u_1", "u_2", "u_3", "u_4", "u_5"SPEEDS]
[kinematics]
x = "u_4"
y = "u_5"
theta = "u_1"
psi = "u_3/cos(theta)"
phi = "u_2 - u_3*sin(theta)/cos(theta)"
KINEMATICS
[[frame]]
name = "A"
parent = "N"
rotation = "z(psi)"
[[frame]]
name = "L"
parent = "A"
rotation = "x(theta)"
[[frame]]
name = "D"
parent = "L"
rotation = "y(phi)"
[[point]]
name = "O"
fixed = true
[[point]]
name = "P"
from = "O"
at = "[x, y, 0] in N"
[[point]]
name = "G"
from = "P"
at = "[0, 0, r] in L"
[[body]]
name = "disk"
frame = "D"
point = "G"
mass = "m"
mass_centre = "[0, 0, 0] in D"
inertia = "principal(J, I, J)"
symmetry = "axisymmetric y"
[[contact]]
name = "C"
wheel = "disk"
axle = "y"
down = "-z"
radius = "r"
CONTACT
STEPS
"#;

fn disk(time: &str, speeds: &str, kinematics: &str, contact: &str, steps: &str) -> Derivation {
    let text = DISK
        .replace("TIME", time)
        .replace("SPEEDS", speeds)
        .replace("KINEMATICS", kinematics)
        .replace("CONTACT", contact)
        .replace("STEPS", steps);
    load_str("disk.toml", &text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_declared_contact_gives_the_bundled_rolling_disk() {
    let want = bundled("derivations/disk-rolling-on-plane.toml");
    for plane in ["", "plane = \"A\""] {
        let d = disk(
            "",
            "",
            "",
            plane,
            r#"
[[step]]
name = "height"
value = "contact_height(C)"
expect = "0"
[[step]]
name = "tangent"
value = "contact_tangent(C)"
expect = "0"
[[step]]
name = "v_z"
value = "contact_velocity(C).z"
expect = "0"
[[step]]
name = "K"
value = "kane([u_1, u_2, u_3], contact_constraints(C), [u_4, u_5])"
"#,
        );
        assert!(d.all_hold(), "{plane}: {:?}", d.failures());
        assert_eq!(step(&d, "K"), step(&want, "K"), "{plane}");
    }
    // Without the plane frame the constraints are written in N's x and y,
    // with A's they are the bundled file's own.
    let d = disk(
        "",
        "",
        "",
        "plane = \"A\"",
        "[[step]]\nname = \"no_slip\"\nvalue = \"rolling_constraints(C)\"\n",
    );
    assert_eq!(step(&d, "no_slip"), step(&want, "no_slip"));
}

/// The contact's direction in the wheel's plane as g = cos χ (−z_L) +
/// sin χ (−x_L) with χ kept by the tangent constraint sin χ cos θ = 0:
/// where it holds (χ = 0) the equations are the bundled disk's, and to
/// first order about upright rolling the linearized ones too.
#[test]
fn an_auxiliary_angle_keeps_the_lowest_point() {
    let want = bundled("derivations/disk-rolling-on-plane.toml");
    let d = disk(
        ", \"chi\"",
        ", \"u_6\"",
        "chi = \"u_6\"",
        "angle = \"chi\"\nplane = \"A\"",
        r#"
[[step]]
name = "tangent"
value = "contact_tangent(C)"
expect = "sin(chi)*cos(theta)"
[[step]]
name = "height"
value = "contact_height(C)"
expect = "r*cos(theta)*(1 - cos(chi))"
[[step]]
name = "rc"
value = "rolling_constraints(C)"
[[step]]
name = "K"
value = "kane([u_1, u_2, u_3], list(rc.1, rc.2, tangent), [u_4, u_5, u_6], [chi])"
[[step]]
name = "K_0"
value = "subst(K, chi = 0*pi)"
[[step]]
name = "KL"
value = "kane([u_1, u_2, u_3], list(rc.1, rc.2, tangent), [u_4, u_5, u_6], [chi], theta = 0, chi = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
"#,
    );
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_eq!(step(&d, "K_0"), step(&want, "K"));
    // χ is not vacuous: away from χ = 0 the equations differ.
    assert_ne!(step(&d, "K"), step(&want, "K"));
    let linear = load_str(
        "disk.toml",
        &(std::fs::read_to_string(repo_root().join("derivations/disk-rolling-on-plane.toml"))
            .unwrap()
            .replace("\"I\", \"J\"]", "\"I\", \"J\", \"Omega\"]")
            + r#"
[[step]]
name = "KL"
value = "kane([u_1, u_2, u_3], no_slip, [u_4, u_5], theta = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
"#),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(step(&d, "KL"), step(&linear, "KL"));
}

/// Bad declarations: each a located error naming what is wrong.
#[test]
fn bad_contacts_are_located_errors() {
    let cases: [(&str, &str, &str); 6] = [
        (
            "wheel = \"disk\"",
            "wheel = \"wheel\"",
            "`wheel` is not a declared body",
        ),
        ("radius = \"r\"", "radius = \"0\"", "radius is zero"),
        ("radius = \"r\"", "radius = \"r*theta\"", "varies in time"),
        (
            "axle = \"y\"",
            "axle = \"w\"",
            "`axle` is an axis of frame L",
        ),
        ("down = \"-z\"", "down = \"y\"", "square to the axle"),
        (
            "name = \"C\"\nwheel",
            "name = \"G\"\nwheel",
            "already a point",
        ),
    ];
    for (from, to, fragment) in cases {
        let text = DISK
            .replace("TIME", "")
            .replace("SPEEDS", "")
            .replace("KINEMATICS", "")
            .replace("CONTACT", "")
            .replace("STEPS", "");
        assert!(text.contains(from), "{from}");
        let text = text.replacen(from, to, 1);
        let err = load_str("disk.toml", &text).expect_err(to);
        assert!(err.message.contains(fragment), "{to}: {}", err.message);
        let first = to.lines().next().unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let line = 1 + lines.iter().rposition(|l| *l == first).unwrap();
        assert_eq!(err.line, line, "{to}: {err}");
        assert!(err.to_string().contains("--> disk.toml:"), "{err}");
    }
    // A centre that is not a declared point, a direction that needs an
    // auxiliary angle, and a name that is not a contact.
    let base = DISK
        .replace("TIME", "")
        .replace("SPEEDS", "")
        .replace("KINEMATICS", "");
    let more = [
        ("centre = \"Z\"", "", "`Z` is not a declared point"),
        ("angle = \"r\"", "", "declare it under [symbols] time"),
        ("frame = \"D\"\ndown = \"z\"", "", "auxiliary angle"),
        ("down = \"z\"", "", "the rim's highest point"),
        (
            "",
            "[[step]]\nname = \"h\"\nvalue = \"contact_height(G)\"",
            "expected a declared contact",
        ),
    ];
    for (contact, steps, fragment) in more {
        let text = base.replace("CONTACT", contact).replace("STEPS", steps);
        let text = if contact.contains("down") {
            text.replacen("down = \"-z\"\n", "", 1)
        } else {
            text
        };
        let err = load_str("disk.toml", &text).expect_err(contact);
        assert!(
            err.message.contains(fragment),
            "{contact}{steps}: {}",
            err.message
        );
        let first = if contact.is_empty() {
            "value = \"contact_height(G)\""
        } else {
            contact.lines().last().unwrap()
        };
        let lines: Vec<&str> = text.lines().collect();
        let line = 1 + lines.iter().rposition(|l| *l == first).unwrap();
        assert_eq!(err.line, line, "{contact}{steps}: {err}");
    }
}

/// The nonlinear bicycle (both contacts declared, the front one with an
/// auxiliary angle) linearized about upright running: its lean and steer
/// matrices are those of the linear bicycle, which tests/sim/bicycle.rs
/// checks against the benchmark's published values.
#[test]
fn the_nonlinear_bicycle_linearizes_to_the_benchmark_matrices() {
    let exact = bundled("docs/examples/derivations/bicycle-nonlinear.toml");
    let linear = bundled("docs/examples/derivations/bicycle.toml");
    assert!(exact.all_hold(), "{:?}", exact.failures());
    for m in ["M", "C_1", "K_0", "K_2"] {
        assert_eq!(step(&exact, m), step(&linear, m), "{m}");
    }
    // The front contact's constraints are exact: its tangent constraint
    // holds χ, the height the pitch, and neither is the squared form.
    for (s, atom) in [("tangent", "chi"), ("ground", "theta")] {
        let Value::Scalar(p) = step(&exact, s) else {
            panic!("{s}: a scalar")
        };
        assert!(p.atoms().iter().any(|a| a.name() == atom), "{s}: {p}");
    }
    // The nonlinear equations before the constraints: 8 × 8 in the rates
    // of the speeds that move a body, and the power balance (checked by
    // the file's `expect`) is not vacuous.
    let Value::Array(m) = step(&exact, "M_all") else {
        panic!("M_all: an array")
    };
    assert_eq!((m.len(), m[0].len()), (8, 8));
    let Value::Array(a) = step(&exact, "A_c") else {
        panic!("A_c: an array")
    };
    assert_eq!((a.len(), a[0].len()), (6, 9));
    let power = exact.steps.iter().find(|s| s.name == "power").unwrap();
    assert_eq!(power.checks.len(), 1);
    let Value::Scalar(e) = step(&exact, "E") else {
        panic!("E: a scalar")
    };
    assert!(e.terms().len() > 50, "{e}");
}
