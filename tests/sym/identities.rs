//! Identities as one-line cases: `name: "input" => "expected"`, both sides
//! parsed with the same symbols and compared by canonical form.

use hdot_sym::Symbols;

fn syms() -> Symbols {
    Symbols::parse_decl(&["a", "b", "I", "Ip"], &["theta", "phi", "psi", "omega_z"])
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
    pythagoras: "sin(theta)^2 + cos(theta)^2" => "1";
    sin_squared_is_rewritten: "sin(theta)^2" => "1 - cos(theta)^2";
    sin_fourth: "sin(theta)^4" => "1 - 2*cos(theta)^2 + cos(theta)^4";
    binomial: "(a + b)^2" => "a^2 + 2*a*b + b^2";
    difference_of_squares: "(a - b)*(a + b)" => "a^2 - b^2";
    rationals_are_exact: "1/3 + 1/6" => "1/2";
    division_by_numbers: "a/4 + a/4" => "a/2";
    cancellation: "a*theta' - theta'*a" => "0";
    division_by_constants_cancels: "a/Ip*Ip" => "a";
    common_denominator: "a/(I*Ip) + b/(Ip*I)" => "(a + b)/I/Ip";
    powers_in_denominators: "a/I^2*I" => "a/I";
    two_angles_are_independent: "sin(theta)^2*cos(phi)^2 + sin(theta)^2*sin(phi)^2" => "1 - cos(theta)^2";
}

macro_rules! derivative {
    ($($name:ident: d/dt $lhs:expr => $rhs:expr;)*) => {$(
        #[test]
        fn $name() {
            let s = syms();
            assert_eq!(s.poly($lhs).unwrap().dt(), s.poly($rhs).unwrap(), "d/dt {}", $lhs);
        }
    )*};
}

derivative! {
    chain_rule_sin: d/dt "sin(theta)" => "cos(theta)*theta'";
    chain_rule_cos: d/dt "cos(theta)" => "-sin(theta)*theta'";
    constants_vanish: d/dt "I*a^2" => "0";
    higher_order_atoms: d/dt "theta''" => "theta'''";
    gyroscope_spin_component: d/dt "psi' + phi'*cos(theta)" => "psi'' + phi''*cos(theta) - phi'*sin(theta)*theta'";
    product_of_trig: d/dt "sin(theta)*cos(theta)" => "2*cos(theta)^2*theta' - theta'";
}

#[test]
fn huge_coefficients_do_not_overflow() {
    let s = syms();
    let p = s.poly("(3037000500*a + 1)^4").unwrap();
    let q = s.poly("(3037000500*a + 1)^2*(3037000500*a + 1)^2").unwrap();
    assert_eq!(p, q);
    let lead = p
        .terms()
        .iter()
        .find(|(m, _)| m.degree() == 4)
        .unwrap()
        .1
        .to_string();
    assert_eq!(
        lead, "85070591732918141055018500062500000000",
        "3037000500^4 computed exactly"
    );
}
