//! Division by sin, cos and constants (the canonical form with the
//! smallest trigonometric denominators, `crates/sym/src/poly.rs`) and
//! partial derivatives: laws that hold for every input (proptest), and
//! one-line identities.

use hdot_sym::{Atom, AtomKind, Expr, Poly, Symbols};
use proptest::prelude::*;

use crate::strategies::{expr, point, value_at};

fn config() -> ProptestConfig {
    ProptestConfig {
        failure_persistence: None,
        ..hdot_tests::proptest_config(160)
    }
}

fn syms() -> Symbols {
    Symbols::parse_decl(&["a", "b", "I", "Ip"], &["theta", "phi", "psi", "omega_z"])
}

/// A divisor the canonical form can divide by: a number times powers of
/// constants, of sin and cos, and of 1 − cos² (sin², as it is held).
fn divisor() -> impl Strategy<Value = Poly> {
    let factor = prop_oneof![
        Just("sin(theta)"),
        Just("cos(theta)"),
        Just("sin(phi)"),
        Just("cos(phi)"),
        Just("a"),
        Just("I_x"),
        Just("(1 - cos(theta)^2)"),
        Just("(1 - sin(phi)^2)"),
    ];
    (
        prop::collection::vec((factor, 1u32..3), 1..4),
        prop_oneof![Just("1"), Just("2"), Just("(-3/2)")],
    )
        .prop_map(|(fs, k)| {
            let s = crate::strategies::symbols();
            let text = fs
                .iter()
                .map(|(f, e)| format!("{f}^{e}"))
                .chain([k.to_string()])
                .collect::<Vec<_>>()
                .join("*");
            s.poly(&text).unwrap()
        })
}

fn inv(d: &Poly) -> Poly {
    d.inverse_divisor().expect("a divisor")
}

/// Σ |c| Π |x|^e over the terms.
fn scale(p: &Poly, v: &mut dyn FnMut(Atom) -> f64) -> f64 {
    p.terms()
        .iter()
        .map(|(m, c)| {
            c.to_f64().abs()
                * m.factors()
                    .iter()
                    .map(|&(a, e)| v(a).abs().powi(e))
                    .product::<f64>()
        })
        .sum()
}

proptest! {
    #![proptest_config(config())]

    /// (p / d) d = p and (p d) / d = p, exactly.
    #[test]
    fn division_undoes_multiplication(e in expr(), d in divisor()) {
        let p = e.to_poly();
        prop_assert_eq!(&(&p * &inv(&d)) * &d, p.clone());
        prop_assert_eq!(&(&p * &d) * &inv(&d), p);
    }

    /// Two ways to write the same quotient give the same canonical form:
    /// p/d₁ + q/d₂ = (p d₂ + q d₁)/(d₁ d₂).
    #[test]
    fn equal_quotients_have_one_form(a in expr(), b in expr(), d1 in divisor(), d2 in divisor()) {
        let (p, q) = (a.to_poly(), b.to_poly());
        let lhs = &(&p * &inv(&d1)) + &(&q * &inv(&d2));
        let rhs = &(&(&p * &d2) + &(&q * &d1)) * &inv(&(&d1 * &d2));
        prop_assert_eq!(lhs, rhs);
    }

    /// The canonical quotient evaluates like p(x)/d(x).
    #[test]
    fn quotient_evaluates_like_the_division(e in expr(), d in divisor(), pt in point()) {
        let mut v = |a: Atom| value_at(&pt, a);
        let p = e.to_poly();
        let dv = d.eval(&mut v);
        prop_assume!(dv.abs() > 1e-3 * scale(&d, &mut v));
        let q = &p * &inv(&d);
        let direct = p.eval(&mut v) / dv;
        let tol = 1e-10 * (scale(&q, &mut v) + (scale(&p, &mut v) / dv.abs()));
        prop_assert!((q.eval(&mut v) - direct).abs() <= tol, "{q} vs {direct}");
    }

    /// d/dt obeys the product rule through denominators.
    #[test]
    fn time_derivative_of_quotients(a in expr(), d in divisor()) {
        let (p, i) = (a.to_poly(), inv(&d));
        prop_assert_eq!((&p * &i).dt(), &(&p.dt() * &i) + &(&p * &i.dt()));
        // d/dt(1/d) = −ḋ/d².
        prop_assert_eq!(i.dt(), -&(&d.dt() * &(&i * &i)));
    }

    /// The chain rule ties ∂ to d/dt: ṗ = Σ ∂p/∂q⁽ᵏ⁾ q⁽ᵏ⁺¹⁾ over every
    /// time symbol and derivative order.
    #[test]
    fn partial_derivatives_sum_to_the_time_derivative(e in expr(), d in divisor()) {
        let p = &e.to_poly() * &inv(&d);
        let mut vars: Vec<Atom> = Vec::new();
        for a in p.atoms() {
            let base = match a.kind() {
                AtomKind::Sin(q) | AtomKind::Cos(q) => q,
                _ => a,
            };
            if base.is_time_dependent() && !vars.contains(&base) {
                vars.push(base);
            }
        }
        let chain: Poly = vars
            .iter()
            .map(|&q| &p.partial(q) * &Poly::atom(q.derivative().unwrap()))
            .sum();
        prop_assert_eq!(p.dt(), chain);
    }

    /// Mixed partial derivatives commute.
    #[test]
    fn mixed_partials_commute(e in expr(), d in divisor()) {
        let p = &e.to_poly() * &inv(&d);
        let (x, y) = (Atom::time("theta", 0), Atom::time("phi", 1));
        prop_assert_eq!(p.partial(x).partial(y), p.partial(y).partial(x));
    }
}

macro_rules! identity {
    ($($name:ident: $lhs:expr => $rhs:expr;)*) => {$(
        #[test]
        fn $name() {
            let s = syms();
            let l = s.poly($lhs).unwrap();
            let r = s.poly($rhs).unwrap();
            assert_eq!(l, r, "{} ≠ {}", $lhs, $rhs);
        }
    )*};
}

identity! {
    sin_squared_over_sin: "(1 - cos(theta)^2)/sin(theta)" => "sin(theta)";
    sin_cubed_over_sin_squared: "sin(theta)^3/(1 - cos(theta)^2)" => "sin(theta)";
    pythagoras_over_sin: "cos(theta)^2/sin(theta) + sin(theta)" => "1/sin(theta)";
    cos_cancels: "cos(theta)^2*Ip/cos(theta)" => "Ip*cos(theta)";
    tangent_times_cotangent: "sin(theta)/cos(theta)*cos(theta)/sin(theta)" => "1";
    two_angles_divide_separately: "sin(theta)*cos(phi)/(sin(theta)*cos(phi))" => "1";
    divisor_with_constant: "Ip*sin(theta)*a/(Ip*sin(theta))" => "a";
    not_divisible_stays: "(1 + cos(theta))/sin(theta)" => "1/sin(theta) + cos(theta)/sin(theta)";
}

#[test]
fn a_sum_is_not_a_divisor() {
    let s = syms();
    for text in ["I + Ip*sin(theta)^2", "1 + cos(theta)", "theta'", "0"] {
        assert!(
            s.poly(text).unwrap().inverse_divisor().is_none(),
            "{text} was accepted as a divisor"
        );
    }
}

#[test]
fn partial_derivatives_of_the_tops_kinetic_energy() {
    let s = syms();
    let t = s
        .poly("Ip*(theta'^2 + phi'^2*sin(theta)^2)/2 + I*(psi' + phi'*cos(theta))^2/2")
        .unwrap();
    let p = |x: &str| s.poly(x).unwrap();
    assert_eq!(
        t.partial(Atom::time("phi", 1)),
        p("Ip*phi'*sin(theta)^2 + I*(psi' + phi'*cos(theta))*cos(theta)")
    );
    assert_eq!(
        t.partial(Atom::time("theta", 0)),
        p("Ip*phi'^2*sin(theta)*cos(theta) - I*(psi' + phi'*cos(theta))*phi'*sin(theta)")
    );
    assert_eq!(t.partial(Atom::time("psi", 0)), Poly::zero());
    // Through a denominator: ∂(1/sin θ)/∂θ = −cos θ/sin² θ.
    assert_eq!(
        p("1/sin(theta)").partial(Atom::time("theta", 0)),
        p("-cos(theta)/sin(theta)^2")
    );
    let _ = Expr::from_poly(&t);
}

/// The function table of docs/derivation-format.md is the registry's.
#[test]
fn docs_list_every_operation_of_the_registry() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/derivation-format.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let (begin, end) = ("<!-- ops:begin -->\n", "<!-- ops:end -->");
    let a = doc.find(begin).expect("ops:begin marker") + begin.len();
    let b = doc.find(end).expect("ops:end marker");
    let table = hdot_sym::derivation::ops::docs_table();
    if doc[a..b] != table {
        if std::env::var_os("HDOT_UPDATE_DOCS").is_some() {
            std::fs::write(&path, format!("{}{}{}", &doc[..a], table, &doc[b..])).unwrap();
        } else {
            panic!(
                "docs/derivation-format.md's function table differs from the registry; rerun with \
                 HDOT_UPDATE_DOCS=1 to regenerate it:\n{table}"
            );
        }
    }
}
