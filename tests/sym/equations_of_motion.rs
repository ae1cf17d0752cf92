//! Equations of motion: accelerations solved with division by sin θ,
//! Lagrange's equations, the mass-matrix form, and the resource limits —
//! on derivation files written for these tests.

use hdot_sym::derivation::{Value, load_str};
use hdot_sym::limits::{self, LimitError, Limits};
use hdot_sym::{Poly, Symbols};
use proptest::prelude::*;

/// The heavy top (axisymmetric, fixed tip O, G at l on the axis): its
/// moments from the transport theorem and from Lagrange's T and V.
const TOP: &str = r#"
title = "heavy top"
source = "test"
[symbols]
constants = ["I", "Ip", "m", "g", "l"]
time = ["phi", "theta", "psi"]
[[abbreviation]]
name = "omega_z"
value = "psi' + phi'*cos(theta)"
[[frame]]
name = "P"
parent = "N"
rotation = "z(phi)"
[[frame]]
name = "F"
parent = "P"
rotation = "y(theta)"
[[step]]
name = "H"
value = "principal(Ip, Ip, I) * (angvel(F) + [0, 0, psi'] in F)"
[[step]]
name = "M"
value = "dt(H)"
[[step]]
name = "W"
value = "cross([0, 0, l] in F, express([0, 0, -m*g] in N, F))"
[[step]]
name = "acc"
value = "solve(M - W, [phi'', theta'', psi''])"
expect = [
  "(I*omega_z - 2*Ip*phi'*cos(theta))*theta'/(Ip*sin(theta))",
  "phi'^2*sin(theta)*cos(theta) - (I/Ip)*omega_z*phi'*sin(theta) + (m*g*l/Ip)*sin(theta)",
  "phi'*theta'*sin(theta) - cos(theta)*(I*omega_z - 2*Ip*phi'*cos(theta))*theta'/(Ip*sin(theta))",
]
[[step]]
name = "T"
value = "dot(angvel(F) + [0, 0, psi'] in F, H)/2"
[[step]]
name = "V"
value = "m*g*l*cos(theta)"
[[step]]
name = "L"
value = "lagrange(T, V, [phi, theta, psi])"
[[step]]
name = "acc_lagrange"
value = "solve(L, [phi'', theta'', psi''])"
expect = ["acc.1", "acc.2", "acc.3"]
[[step]]
name = "Mass"
value = "mass_matrix(L, [phi'', theta'', psi''])"
[[step]]
name = "f"
value = "forcing(L, [phi'', theta'', psi''])"
"#;

#[test]
fn heavy_top_accelerations_by_newton_euler_and_lagrange_agree() {
    let d = load_str("top.toml", TOP).unwrap();
    assert!(d.all_hold(), "{:?}", d.failures());
    let step = |n: &str| d.steps.iter().find(|s| s.name == n).unwrap();
    // The list is labelled by the unknowns.
    let Value::List { labels, items } = &step("acc").value else {
        panic!("acc is not a list")
    };
    assert_eq!(
        labels.iter().map(|a| a.to_string()).collect::<Vec<_>>(),
        ["phi''", "theta''", "psi''"]
    );
    // φ̈ and ψ̈ have sin θ in the denominator, θ̈ none.
    assert!(items[0].has_trig_denominator() && items[2].has_trig_denominator());
    assert!(!items[1].has_trig_denominator());
    // Lagrange's equations are the moment equations: L₂ (θ) is ΣM_y − W_y
    // of the frame F, and M q̈ − f = L.
    let Value::Array(m) = &step("Mass").value else {
        panic!()
    };
    let Value::List { items: f, .. } = &step("f").value else {
        panic!()
    };
    let Value::List { items: l, .. } = &step("L").value else {
        panic!()
    };
    let s = Symbols::parse_decl(&[], &["phi", "theta", "psi"]);
    let q: Vec<Poly> = ["phi''", "theta''", "psi''"]
        .iter()
        .map(|x| s.poly(x).unwrap())
        .collect();
    for i in 0..3 {
        let mq: Poly = (0..3).map(|j| &m[i][j] * &q[j]).sum();
        assert_eq!(d.unfold(&(&mq - &f[i])), d.unfold(&l[i]));
    }
    // M is symmetric.
    assert_eq!(m[0][2], m[2][0]);
}

#[test]
fn a_gimbal_needs_the_mass_matrix_form() {
    // A gimbal of moment J about the vertical carrying a rotor: φ̈'s
    // coefficient J + I′ sin²θ is a sum, so `solve` refuses and names it,
    // while mass_matrix and forcing give M q̈ = f.
    let text = r#"
title = "gimbal"
source = "test"
[symbols]
constants = ["J", "I", "Ip"]
time = ["phi", "theta"]
[[step]]
name = "T"
value = "(J*phi'^2 + Ip*(theta'^2 + phi'^2*sin(theta)^2) + I*phi'^2*cos(theta)^2)/2"
[[step]]
name = "L"
value = "lagrange(T, 0, [phi, theta])"
[[step]]
name = "Mass"
value = "mass_matrix(L, [phi'', theta''])"
"#;
    let d = load_str("gimbal.toml", text)
        .map_err(|e| e.to_string())
        .unwrap();
    let Value::Array(m) = &d.steps[2].value else {
        panic!("not an array")
    };
    let s = Symbols::parse_decl(&["J", "I", "Ip"], &["theta"]);
    let want = [["J + Ip*sin(theta)^2 + I*cos(theta)^2", "0"], ["0", "Ip"]];
    for i in 0..2 {
        for j in 0..2 {
            assert_eq!(m[i][j], s.poly(want[i][j]).unwrap(), "M[{i}][{j}]");
        }
    }
    let bad = text.replace(
        "mass_matrix(L, [phi'', theta''])",
        "solve(L, [phi'', theta''])",
    );
    let err = load_str("gimbal.toml", &bad).unwrap_err();
    assert!(err.message.contains("mass_matrix"), "{}", err.message);
    assert!(err.message.contains("J"), "{}", err.message);
}

/// A gyrostat-like system written for the test: the determinant `solve`
/// cannot divide by is A_3 J (A_1 + J_t)(A_2 + J_t). The error prints it
/// factored, and what it prints is that determinant.
#[test]
fn the_determinant_solve_cannot_divide_by_is_printed_factored() {
    let text = r#"
title = "gyrostat-like"
source = "written for the test"
[symbols]
constants = ["A_1", "A_2", "A_3", "J", "J_t", "M"]
time = ["u", "v", "w", "b"]
[[step]]
name = "eqs"
value = "list((A_1 + J_t)*u'' - M, (A_2 + J_t)*v'' - M, A_3*w'' - M, J*(w'' + b'') - M)"
[[step]]
name = "acc"
value = "solve(eqs, [u'', v'', w'', b''])"
"#;
    let err = load_str("gyrostat.toml", text).unwrap_err();
    let msg = &err.message;
    let printed = msg
        .split_once(" is ")
        .and_then(|(_, r)| r.split_once(", which cannot be divided by"))
        .map(|(d, _)| d)
        .unwrap_or_else(|| panic!("{msg}"));
    assert!(
        printed.contains("(A_1 + J_t)") && printed.contains("(A_2 + J_t)"),
        "{printed}"
    );
    assert!(!printed.contains("A_1*A_2"), "expanded: {printed}");
    let s = Symbols::parse_decl(&["A_1", "A_2", "A_3", "J", "J_t"], &[]);
    assert_eq!(
        s.poly(printed).unwrap(),
        s.poly("A_3*J*(A_1 + J_t)*(A_2 + J_t)").unwrap(),
        "{printed}"
    );
}

#[test]
fn absurd_sizes_fail_fast_with_the_limit_named() {
    for (value, setting) in [
        ("a^2147483648 * a^2147483648", "max_exponent"),
        ("(a + b)^100000", "max_exponent"),
        ("(a + b + c + d + e + f)^60", "max_terms"),
        (&product_of_sums(30), "max_"),
    ] {
        let names: Vec<String> = (1..=30)
            .flat_map(|k| [format!("\"x{k}\""), format!("\"y{k}\"")])
            .collect();
        let text = format!(
            "title = \"t\"\nsource = \"s\"\n[symbols]\nconstants = [\"a\", \"b\", \"c\", \"d\", \"e\", \"f\", {}]\n\
             [[step]]\nname = \"x\"\nvalue = \"{value}\"\n",
            names.join(", ")
        );
        let started = std::time::Instant::now();
        let err = match load_str("limits.toml", &text) {
            Ok(_) => panic!("{value}: accepted"),
            Err(e) => e,
        };
        // Not a timing assertion of speed, a guard against a hang: the
        // limits are checked before the work that would exceed them.
        assert!(
            started.elapsed().as_secs() < 60,
            "{value}: took {:?}",
            started.elapsed()
        );
        assert!(err.message.contains(setting), "{value}: {}", err.message);
        assert_eq!(err.line, 6, "{value}: the step is named");
    }
    // A file may raise a limit.
    let text = "title = \"t\"\nsource = \"s\"\n[limits]\nmax_exponent = 20000\n[symbols]\nconstants = [\"a\"]\n\
                [[step]]\nname = \"x\"\nvalue = \"a^15000\"\n";
    assert!(
        load_str("limits.toml", text)
            .map_err(|e| e.to_string())
            .is_ok()
    );
}

/// (x1 + y1)(x2 + y2)…: 2ⁿ terms.
fn product_of_sums(n: usize) -> String {
    (1..=n)
        .map(|k| format!("(x{k} + y{k})"))
        .collect::<Vec<_>>()
        .join("*")
}

proptest! {
    #![proptest_config(ProptestConfig { failure_persistence: None, ..hdot_tests::proptest_config(64) })]

    /// Exponents near the integer limits never wrap: a product either
    /// holds the exact sum or fails with the exponent limit.
    #[test]
    fn exponents_never_wrap(e1 in (i32::MAX as i64 - 1000)..=(i32::MAX as i64), e2 in 0i64..2000, neg in any::<bool>()) {
        let a = hdot_sym::Atom::constant("a");
        let sign = if neg { -1 } else { 1 };
        let big = Limits { max_exponent: u32::MAX, ..Limits::DEFAULT };
        let r = limits::scope(big, || {
            let x = Poly::term(hdot_sym::Monomial::atom(a, (sign * e1) as i32), hdot_sym::Rational::ONE);
            let y = Poly::term(hdot_sym::Monomial::atom(a, (sign * e2) as i32), hdot_sym::Rational::ONE);
            &x * &y
        });
        let sum = sign * (e1 + e2);
        match r {
            Ok(p) => {
                prop_assert!(i32::try_from(sum).is_ok());
                prop_assert_eq!(p.terms()[0].0.exponent(a) as i64, sum);
            }
            Err(e) => {
                prop_assert!(i32::try_from(sum).is_err());
                let is_exponent = matches!(e, LimitError::Exponent { .. });
                prop_assert!(is_exponent, "{e}");
            }
        }
    }
}
