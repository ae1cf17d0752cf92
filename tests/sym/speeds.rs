//! Generalized speeds and kinematic equations: `[symbols] speeds`,
//! `[kinematics]`, `in_speeds`, the speeds' rates read in the speeds'
//! order, and the located errors of bad declarations — on files written
//! for these tests.

use hdot_sym::Poly;
use hdot_sym::derivation::{Value, load_str};

/// A body turned by 3-1-3 Euler angles (ψ, θ, φ) whose body rates are the
/// speeds; the kinematic equations invert ω(q̇) = u.
const EULER: &str = r#"
title = "body rates as speeds"
source = "test"
[symbols]
constants = ["I1", "I2", "I3"]
time = ["psi", "theta", "phi"]
speeds = ["u1", "u2", "u3"]
[kinematics]
psi = "(u1*sin(phi) + u2*cos(phi))/sin(theta)"
theta = "u1*cos(phi) - u2*sin(phi)"
phi = "u3 - (u1*sin(phi) + u2*cos(phi))*cos(theta)/sin(theta)"
[[frame]]
name = "A"
parent = "N"
rotation = "z(psi)"
[[frame]]
name = "E"
parent = "A"
rotation = "x(theta)"
[[frame]]
name = "B"
parent = "E"
rotation = "z(phi)"
[[step]]
name = "omega"
value = "in_speeds(angvel(B))"
expect = ["u1", "u2", "u3"]
[[step]]
name = "M"
value = "in_speeds(dt(principal(I1, I2, I3) * angvel(B)))"
[[step]]
name = "rates"
value = "solve(M, [u3', u1', u2'])"
expect = ["(I1 - I2)*u1*u2/I3", "(I2 - I3)*u2*u3/I1", "(I3 - I1)*u3*u1/I2"]
"#;

fn p(d: &hdot_sym::derivation::Derivation, s: &str) -> Poly {
    d.symbols.poly(s).unwrap()
}

#[test]
fn kinematic_equations_invert_the_angular_velocity_and_give_eulers_equations() {
    let d = load_str("euler.toml", EULER).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
    let names: Vec<&str> = d.speeds().iter().map(|a| a.name()).collect();
    assert_eq!(names, ["u1", "u2", "u3"]);
    let coords: Vec<&str> = d
        .kinematic_equations()
        .iter()
        .map(|(q, _)| q.name())
        .collect();
    assert_eq!(coords, ["psi", "theta", "phi"], "the file's order");
    assert_eq!(
        d.kinematic_equations()[1].1,
        p(&d, "u1*cos(phi) - u2*sin(phi)")
    );
    // In the speeds' order, whatever order `solve` was given.
    let rates = d.speed_rates("rates").unwrap();
    assert_eq!(rates[0], p(&d, "(I2 - I3)*u2*u3/I1"));
    assert_eq!(rates[2], p(&d, "(I1 - I2)*u1*u2/I3"));
    let e = d.speed_rates("omega").unwrap_err();
    assert!(e.contains("not the speeds' rates"), "{e}");
    let e = d.speed_rates("nothing").unwrap_err();
    assert!(e.contains("no step called `nothing`"), "{e}");
}

#[test]
fn in_speeds_replaces_second_derivatives_through_the_derivative_of_the_rate() {
    let text = r#"
title = "t"
source = "t"
[symbols]
constants = ["r"]
time = ["x"]
speeds = ["u"]
[kinematics]
x = "r*u"
[[step]]
name = "a"
value = "in_speeds(x'' + x')"
expect = "r*u' + r*u"
"#;
    let d = load_str("t.toml", text).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
    assert!(matches!(d.steps[0].value, Value::Scalar(_)));
}

/// (file text, the text the error points at, words of the message).
fn bad(kinematics: &str, speeds: &str) -> hdot_sym::derivation::Diagnostic {
    let text = format!(
        "title = \"t\"\nsource = \"t\"\n[symbols]\nconstants = [\"r\"]\ntime = [\"x\", \"y\"]\n{speeds}\n[kinematics]\n{kinematics}\n"
    );
    load_str("bad.toml", &text).unwrap_err()
}

#[test]
fn bad_kinematics_are_located_errors() {
    let e = bad("x = \"u\"", "");
    assert!(
        e.message.contains("declare them with [symbols] speeds"),
        "{e}"
    );
    assert_eq!((e.line, e.column), (8, 1), "{e}");
    let e = bad("z = \"u\"", "speeds = [\"u\"]");
    assert!(e.message.contains("`z` is not a coordinate"), "{e}");
    assert_eq!((e.line, e.column), (8, 1), "{e}");
    let e = bad("u = \"x\"", "speeds = [\"u\"]");
    assert!(e.message.contains("`u` is a speed"), "{e}");
    let e = bad("x = \"u\"\ny = \"x' + u\"", "speeds = [\"u\"]");
    assert!(e.message.contains("not in rates such as `x'`"), "{e}");
    assert_eq!((e.line, e.column), (9, 6), "{e}");
    let e = bad("x = \"w\"", "speeds = [\"u\"]");
    assert!(e.message.contains("unknown name `w`"), "{e}");
    assert_eq!((e.line, e.column), (8, 6), "{e}");
    let e = bad("x = \"u\"", "speeds = [\"u\", \"x\"]");
    assert!(e.message.contains("declared twice"), "{e}");
}

#[test]
fn in_speeds_without_kinematics_is_an_error() {
    let text = "title = \"t\"\nsource = \"t\"\n[symbols]\ntime = [\"x\"]\n[[step]]\nname = \"a\"\nvalue = \"in_speeds(x')\"\n";
    let e = load_str("t.toml", text).unwrap_err();
    assert!(e.message.contains("no kinematic equations"), "{e}");
    assert_eq!(e.line, 7);
}
