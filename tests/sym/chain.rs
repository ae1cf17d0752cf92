//! The generated scaling family `chain-K`.

use hdot_sym::derivation::Value;
use hdot_sym::{Poly, Symbols, chain};

fn hdot(k: usize) -> [Poly; 3] {
    let d = chain::derivation(k).unwrap_or_else(|e| panic!("{e}"));
    let s = d.steps.iter().find(|s| s.name == "Hdot").unwrap();
    let Value::Vector(v, f) = &s.value else {
        panic!("Ḣ is a vector")
    };
    assert_eq!(f, "N");
    v.0.clone()
}

/// One body turning about the fixed z axis: Ḣ in N is the fixed-axis moment
/// (reference §6, in body axes) turned by q_1 into N.
#[test]
fn chain_1_is_the_fixed_axis_result_turned_into_n() {
    let s = Symbols::parse_decl(
        &["I_1x", "I_1y", "I_1z", "I_1xy", "I_1yz", "I_1zx"],
        &["q_1"],
    );
    let p = |t: &str| s.poly(t).unwrap();
    let (mx, my) = (
        p("-I_1zx*q_1'' + I_1yz*q_1'^2"),
        p("-I_1yz*q_1'' - I_1zx*q_1'^2"),
    );
    let (c, sn) = (p("cos(q_1)"), p("sin(q_1)"));
    let [hx, hy, hz] = hdot(1);
    assert_eq!(hx, &(&c * &mx) - &(&sn * &my));
    assert_eq!(hy, &(&sn * &mx) + &(&c * &my));
    assert_eq!(hz, p("I_1z*q_1''"));
}

#[test]
fn the_family_grows_with_k_and_every_component_is_canonical() {
    let mut last = 0;
    for k in 1..=3 {
        let h = hdot(k);
        let terms: usize = h.iter().map(Poly::len).sum();
        assert!(
            terms > last,
            "chain-{k}: {terms} terms, not more than chain-{}",
            k - 1
        );
        last = terms;
        for c in &h {
            assert_eq!(hdot_sym::Expr::from_poly(c).to_poly(), *c);
        }
    }
}

#[test]
fn names_outside_the_family_are_not_chains() {
    assert_eq!(chain::parse_name("chain-6"), Some(6));
    assert_eq!(chain::parse_name("chain-0"), None);
    assert_eq!(chain::parse_name("chain-9"), None);
    assert_eq!(chain::parse_name("chainsaw"), None);
}
