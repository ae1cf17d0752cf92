//! Linearization about an operating point: `linearize(x, q = q0, …)` of
//! the nonlinear heavy top gives the sleeping top's M, C and K; Kane's
//! equations to first order (`kane(…, q = q0, …)`) equal the nonlinear
//! ones linearized, for the rolling disk; a configuration constraint's
//! dependent coordinate is eliminated by implicit differentiation (two
//! pendulums geared 2 : 1); and what cannot be linearized is a located
//! error.

use hdot_sym::derivation::{Derivation, Value, load_str};
use hdot_tests::repo_root;

fn step<'d>(d: &'d Derivation, name: &str) -> &'d Value {
    &d.steps
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("no step {name}"))
        .value
}

/// The heavy top in the sleeping top's tilts a (about N's x) and b (about
/// the tilted y), spinning by c about its axis: Lagrange's equations,
/// nonlinear, then linearized about the vertical at spin rate ω.
const HEAVY_TOP: &str = r#"
title = "the heavy top, tilted by a and b"
source = "written for the test"
[symbols]
constants = ["I", "Ip", "m", "g", "l", "omega"]
time = ["a", "b", "c"]
[[frame]]
name = "A"
parent = "N"
rotation = "x(a)"
[[frame]]
name = "B"
parent = "A"
rotation = "y(b)"
[[frame]]
name = "S"
parent = "B"
rotation = "z(c)"
[[step]]
name = "T"
value = "dot(angvel(S), principal(Ip, Ip, I)*angvel(S))/2"
[[step]]
name = "V"
value = "m*g*express([0, 0, l] in B, N).z"
[[step]]
name = "L"
value = "lagrange(T, V, [a, b, c])"
[[step]]
name = "eqs"
value = "linearize(list(L.1, L.2), a = 0, b = 0, c' = omega)"
[[step]]
name = "M"
value = "jacobian(eqs, [a'', b''])"
[[step]]
name = "C"
value = "jacobian(eqs, [a', b'])"
[[step]]
name = "K"
value = "jacobian(eqs, [a, b])"
"#;

#[test]
fn the_heavy_top_linearized_is_the_sleeping_top() {
    let top = load_str("heavy-top.toml", HEAVY_TOP).unwrap_or_else(|e| panic!("{e}"));
    let path = repo_root().join("docs/examples/derivations/sleeping-top.toml");
    let sleeping = hdot_sym::derivation::load(&path).unwrap_or_else(|e| panic!("{e}"));
    for m in ["M", "C", "K"] {
        assert_eq!(step(&top, m), step(&sleeping, m), "{m}");
    }
    // Linear: the linearized equations are their own linearization, and
    // they hold no second power of a small symbol.
    let Value::List { items, .. } = step(&top, "eqs") else {
        panic!("a list")
    };
    for p in items {
        for (mono, _) in p.terms() {
            let small: i32 = mono
                .factors()
                .iter()
                .filter(|(a, _)| ["a", "b"].contains(&a.name()) && a.is_time_dependent())
                .map(|f| f.1)
                .sum();
            assert!(small <= 1, "{p}");
        }
    }
}

/// The bundled rolling disk with a spin rate Ω: Kane's equations to first
/// order about upright rolling equal its nonlinear Kane's equations
/// linearized there.
#[test]
fn linearized_kane_is_kane_linearized_for_the_rolling_disk() {
    let text = std::fs::read_to_string(repo_root().join("derivations/disk-rolling-on-plane.toml"))
        .unwrap();
    let text = text.replace(
        "constants = [\"m\", \"g\", \"r\", \"I\", \"J\"]",
        "constants = [\"m\", \"g\", \"r\", \"I\", \"J\", \"Omega\"]",
    ) + r#"
[[step]]
name = "KN"
value = "linearize(K, theta = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
[[step]]
name = "KL"
value = "kane([u_1, u_2, u_3], no_slip, [u_4, u_5], theta = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
expect = ["KN.1", "KN.2", "KN.3"]
"#;
    assert!(text.contains("\"Omega\"]"));
    let d = load_str("disk.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
    // Not vacuous: the lean equation keeps its gyroscopic and gravity terms.
    let Value::List { items, .. } = step(&d, "KL") else {
        panic!("a list")
    };
    let names: Vec<&str> = items[0].atoms().iter().map(|a| a.name()).collect();
    for n in ["Omega", "theta", "g"] {
        assert!(names.contains(&n), "{n} in {}", items[0]);
    }
}

/// Two pendulums on one pivot, a about N's x and b about it too, tied by
/// sin b = 2 sin a: to first order b = 2a, so the system is one pendulum
/// with inertia I₁ + 4 I₂ and stiffness m₁ g l₁ + 4 m₂ g l₂.
const GEARED: &str = r#"
title = "two pendulums geared 2 : 1"
source = "written for the test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m_1", "m_2", "l_1", "l_2", "I_1", "I_2", "J", "g"]
time = ["a", "b"]
speeds = ["u_a", "u_b"]
[kinematics]
a = "u_a"
b = "u_b"
[[frame]]
name = "A"
parent = "N"
rotation = "x(a)"
[[frame]]
name = "B"
parent = "N"
rotation = "x(b)"
[[point]]
name = "O"
fixed = true
[[body]]
name = "one"
frame = "A"
point = "O"
mass = "m_1"
mass_centre = "[0, 0, -l_1] in A"
inertia = "principal(I_1, J, J)"
[[body]]
name = "two"
frame = "B"
point = "O"
mass = "m_2"
mass_centre = "[0, 0, -l_2] in B"
inertia = "principal(I_2, J, J)"
[[step]]
name = "K"
value = "CALL"
"#;

fn geared(call: &str) -> Result<Derivation, hdot_sym::derivation::Diagnostic> {
    load_str("geared.toml", &GEARED.replace("CALL", call))
}

#[test]
fn a_dependent_coordinate_is_eliminated_by_implicit_differentiation() {
    let d = geared("kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 0, b = 0, u_a = 0)")
        .unwrap_or_else(|e| panic!("{e}"));
    let want = load_str(
        "want.toml",
        &GEARED.replace(
            "CALL",
            "list((I_1 + 4*I_2)*u_a' + (m_1*g*l_1 + 4*m_2*g*l_2)*a)",
        ),
    )
    .unwrap();
    assert_eq!(step(&d, "K"), step(&want, "K"));
    // Exactly (no operating point), the constraint's rate joins the
    // velocity constraints: the same as writing the rate by hand.
    let exact = geared("kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b])").unwrap();
    let by_hand = geared("kane([u_a], list(cos(b)*u_b - 2*cos(a)*u_a), [u_b])").unwrap();
    assert_eq!(step(&exact, "K"), step(&by_hand, "K"));
}

#[test]
fn what_cannot_be_linearized_is_a_located_error() {
    let cases = [
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], a = 0, b = 0, u_a = 0)",
            "1 configuration constraint (free of the speeds) for 0 dependent coordinates",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a) - 1), [u_b], [b], a = 0, b = 0, u_a = 0)",
            "is -1 at the operating point, not 0",
        ),
        (
            "kane([u_a], list(cos(b) - cos(a)), [u_b], [b], a = 0, b = 0, u_a = 0)",
            "cannot be eliminated at the operating point",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 0, u_a = 0)",
            "the dependent coordinate `b` needs an operating value",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [u_a], a = 0, b = 0)",
            "`u_a` is not a coordinate",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = u_a, b = 0)",
            "an operating value is written in constants",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 0, b = 0, g = 1)",
            "`g` is a constant",
        ),
        (
            "kane([u_a], list(sin(b) - 2*sin(a)), [u_b], [b], a = 1/2, b = 0, u_a = 0)",
            "cannot be expanded about its operating value",
        ),
        (
            "kane([u_a], list(u_a*u_b), [u_b])",
            "not linear in the speeds",
        ),
    ];
    for (call, want) in cases {
        let e = geared(call)
            .err()
            .unwrap_or_else(|| panic!("{call} derives"));
        assert!(e.message.contains(want), "{call}: {e}");
        assert!(e.source_line.contains("kane("), "{call}: {e}");
        assert_eq!(e.path, "geared.toml");
    }
}
