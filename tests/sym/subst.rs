//! `subst(x, name = value, …)` in a derivation: an angle set to 0 (written
//! without pi) takes sin 0 = 0 and cos 0 = 1 like any multiple of pi/2; set
//! to 0 where it divides, it is a located error.

use hdot_sym::derivation::{Derivation, Value, load_str};

const FILE: &str = r#"
title = "t"
source = "s"
[symbols]
constants = ["a"]
time = ["phi", "theta"]
[[step]]
name = "s"
value = "CALL"
[[step]]
name = "want"
value = "WANT"
"#;

fn derive(call: &str, want: &str) -> Result<Derivation, hdot_sym::derivation::Diagnostic> {
    load_str(
        "subst.toml",
        &FILE.replace("CALL", call).replace("WANT", want),
    )
}

fn step<'d>(d: &'d Derivation, name: &str) -> &'d Value {
    &d.steps.iter().find(|s| s.name == name).unwrap().value
}

#[test]
fn an_angle_set_to_zero_inside_sin_and_cos() {
    for (call, want) in [
        // The angle inside sin/cos, beside its rate and outside them.
        (
            "subst(a*sin(phi)*theta' + cos(phi)^2*phi' + phi*cos(theta), phi = 0)",
            "0",
        ),
        ("subst(a*cos(phi) + sin(phi)*theta, phi = 0)", "a"),
        // Zero as the quarter turns 0*pi/2 give it.
        (
            "subst(cos(phi)*theta + sin(phi), phi = 0)",
            "subst(cos(phi)*theta + sin(phi), phi = 0*pi/2)",
        ),
        // The angle's rates follow it; a rate set alone leaves the angle.
        ("subst(cos(phi)*phi'' + a, phi = 0)", "a"),
        (
            "subst(sin(phi)*a + phi'*cos(theta), phi' = 0)",
            "sin(phi)*a",
        ),
    ] {
        let d = derive(call, want).unwrap_or_else(|e| panic!("{call}: {e}"));
        assert_eq!(step(&d, "s"), step(&d, "want"), "{call}");
    }
}

#[test]
fn an_angle_set_to_zero_where_it_divides_is_a_located_error() {
    for call in [
        "subst(a/sin(phi), phi = 0)",
        "subst(a*cos(phi)/sin(phi)^2, phi = 0)",
    ] {
        let err = derive(call, "0").expect_err(call);
        assert!(
            err.message.contains("zero where it divides"),
            "{call}: {err}"
        );
        // The line of `value = "CALL"` in FILE, the column of the value `0`.
        let (k, line) = FILE
            .lines()
            .enumerate()
            .find(|(_, l)| l.contains("CALL"))
            .unwrap();
        let col = line.find("CALL").unwrap() + call.rfind('0').unwrap() + 1;
        assert_eq!((err.line, err.column), (k + 1, col), "{call}: {err}");
    }
}
