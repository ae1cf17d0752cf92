//! Laws of the algebra, for every input (proptest, from the fixed seed of
//! `hdot_tests::proptest_config`).

use hdot_sym::{Atom, AtomKind, Expr, Node, Poly};
use proptest::prelude::*;

use crate::strategies::{Tree, build, expr, point, symbols, tree, value_at};

fn config() -> ProptestConfig {
    ProptestConfig {
        failure_persistence: None,
        ..hdot_tests::proptest_config(192)
    }
}

/// Σ |c| Π |x|^e: an upper bound on the magnitudes summed when evaluating `p`.
fn poly_scale(p: &Poly, v: &mut dyn FnMut(Atom) -> f64) -> f64 {
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

/// The tree evaluated with every intermediate replaced by its absolute value.
fn tree_scale(e: &Expr, v: &mut dyn FnMut(Atom) -> f64) -> f64 {
    let mut abs = |a: Atom| v(a).abs();
    // Evaluating with |x| and without negation bounds every intermediate.
    let mut positive = Expr::new();
    fn copy(src: &Expr, id: hdot_sym::expr::Id, dst: &mut Expr) -> hdot_sym::expr::Id {
        match src.node(id).clone() {
            Node::Neg(i) => copy(src, i, dst),
            Node::Add(c) => {
                let ids = c.iter().map(|i| copy(src, *i, dst)).collect();
                dst.push(Node::Add(ids))
            }
            Node::Mul(c) => {
                let ids = c.iter().map(|i| copy(src, *i, dst)).collect();
                dst.push(Node::Mul(ids))
            }
            Node::Pow(i, k) => {
                let j = copy(src, i, dst);
                dst.push(Node::Pow(j, k))
            }
            n => dst.push(n),
        }
    }
    copy(e, e.root(), &mut positive);
    positive.eval(&mut abs)
}

/// The same atom with the name `…_r` (a symbol none of the strategies
/// draw), so that `renamed(p)` shares no variable with `p`.
fn renamed(a: Atom) -> Atom {
    let name = |n: &str| format!("{n}_r");
    match a.kind() {
        AtomKind::Var {
            name: n,
            time: false,
            ..
        } => Atom::constant(&name(n)),
        AtomKind::Var { name: n, order, .. } => Atom::time(&name(n), order),
        AtomKind::Sin(q) => Atom::sin(renamed(q)).expect("angle"),
        AtomKind::Cos(q) => Atom::cos(renamed(q)).expect("angle"),
        AtomKind::Sum { .. } => unreachable!("the strategies draw no sum atoms"),
    }
}

proptest! {
    #![proptest_config(config())]

    /// A product of polynomials that share no variable (its own path,
    /// without hashing) has exactly `n · m` terms, as
    /// `product_terms_at_least` predicts, and renaming back gives the
    /// product computed with the variables shared.
    #[test]
    fn products_of_unrelated_factors_are_known_in_advance(a in expr(), b in expr()) {
        let (a, b) = (a.to_poly(), b.to_poly());
        let r = b.subst(&mut |x| Some(Poly::atom(renamed(x))));
        let product = &a * &r;
        prop_assert_eq!(Poly::product_terms_at_least(&[&a, &r]), product.len() as u64);
        let back = product.subst(&mut |x| {
            b.atoms().into_iter().find(|&y| renamed(y) == x).map(Poly::atom)
        });
        prop_assert_eq!(back, &a * &b);
    }

    /// The advance bound of a product never exceeds its real term count.
    #[test]
    fn the_product_bound_is_a_lower_bound(a in expr(), b in expr(), c in expr()) {
        let (a, b, c) = (a.to_poly(), b.to_poly(), c.to_poly());
        let bound = Poly::product_terms_at_least(&[&a, &b, &c]);
        prop_assert!(bound <= (&(&a * &b) * &c).len() as u64);
    }

    /// `Poly::sum_of_products` (every term product into one sum, as Kane's
    /// dot products use it) is the sum of the products formed one by one,
    /// for factors sharing variables, sines and cosines, and with zeros.
    #[test]
    fn a_sum_of_products_is_the_sum_of_the_products(
        a in expr(), b in expr(), c in expr(), d in expr(), e in expr()
    ) {
        let (a, b, c, d, e) = (a.to_poly(), b.to_poly(), c.to_poly(), d.to_poly(), e.to_poly());
        let zero = Poly::zero();
        let pairs = [(&a, &b), (&c, &d), (&zero, &e), (&e, &a)];
        let expected = pairs.iter().fold(Poly::zero(), |s, (x, y)| &s + &(*x * *y));
        prop_assert_eq!(Poly::sum_of_products(pairs), expected);
    }

    /// Expanding the default presentation of a canonical form gives it back.
    #[test]
    fn canonical_form_is_idempotent(e in expr()) {
        let p = e.to_poly();
        prop_assert_eq!(Expr::from_poly(&p).to_poly(), p);
    }

    /// (a + b) c = a c + b c.
    #[test]
    fn multiplication_distributes_over_addition(a in expr(), b in expr(), c in expr()) {
        let (a, b, c) = (a.to_poly(), b.to_poly(), c.to_poly());
        prop_assert_eq!(&(&a + &b) * &c, &(&a * &c) + &(&b * &c));
    }

    /// d/dt (a b) = ȧ b + a ḃ.
    #[test]
    fn time_derivative_obeys_the_product_rule(a in expr(), b in expr()) {
        let (a, b) = (a.to_poly(), b.to_poly());
        prop_assert_eq!((&a * &b).dt(), &(&a.dt() * &b) + &(&a * &b.dt()));
    }

    /// A random tree evaluated in floating point equals its canonical form
    /// evaluated at the same point, within round-off scaled by magnitudes.
    #[test]
    fn canonical_form_evaluates_like_the_tree(e in expr(), p in point()) {
        let mut v = |a: Atom| value_at(&p, a);
        let direct = e.eval(&mut v);
        let poly = e.to_poly();
        let expanded = poly.eval(&mut v);
        let scale = tree_scale(&e, &mut v) + poly_scale(&poly, &mut v);
        prop_assert!((direct - expanded).abs() <= 256.0 * f64::EPSILON * scale,
            "tree {direct} vs canonical {expanded} (scale {scale}) for {e}");
    }

    /// Printing in source syntax and parsing back gives the same tree.
    #[test]
    fn print_then_parse_is_the_identity(e in expr()) {
        let text = e.to_string();
        let back = symbols().expr(&text).map_err(|err| TestCaseError::fail(format!("{text}: {err}")))?;
        prop_assert_eq!(back, e);
    }

    /// The canonical form never holds sin² of an angle.
    #[test]
    fn canonical_form_has_no_sin_squared(e in expr()) {
        let p = e.to_poly();
        for (m, _) in p.terms() {
            for &(a, k) in m.factors() {
                prop_assert!(!(matches!(a.kind(), AtomKind::Sin(_)) && k >= 2), "{p}");
            }
        }
    }

    /// Substituting `a := f` in the canonical form equals expanding the tree
    /// in which every leaf `a` was replaced by the tree of `f` (exact).
    #[test]
    fn substitution_commutes_with_expansion(t in tree(), f in tree()) {
        let a = Atom::constant("a");
        let replaced = replace_leaf(&t, a, &f);
        let lhs = build(&t).to_poly().subst(&mut |x| (x == a).then(|| build(&f).to_poly()));
        prop_assert_eq!(lhs, build(&replaced).to_poly());
    }
}

fn replace_leaf(t: &Tree, a: Atom, f: &Tree) -> Tree {
    match t {
        Tree::Atom(x) if *x == a => f.clone(),
        Tree::Add(v) => Tree::Add(v.iter().map(|c| replace_leaf(c, a, f)).collect()),
        Tree::Mul(v) => Tree::Mul(v.iter().map(|c| replace_leaf(c, a, f)).collect()),
        Tree::Neg(c) => Tree::Neg(Box::new(replace_leaf(c, a, f))),
        Tree::Pow(c, k) => Tree::Pow(Box::new(replace_leaf(c, a, f)), *k),
        other => other.clone(),
    }
}

/// The angles, rates and constant of `sines_squared_expand_as_one_minus_cosines_squared`.
const ANGLES: [&str; 3] = ["theta", "phi", "psi"];

/// One factor `sin(q)^s cos(q)^c` per angle and a constant to a power, as
/// text (exponents `[s, c]` per angle, then the constant's).
fn monomial_text(exps: &[[u32; 2]], k: u32) -> String {
    let mut t = format!("a^{k}");
    for (q, [s, c]) in ANGLES.iter().zip(exps) {
        t.push_str(&format!("*sin({q})^{s}*cos({q})^{c}"));
    }
    t
}

proptest! {
    #![proptest_config(config())]

    /// A product whose monomial holds several sines squared (or cubed, or to
    /// the fourth power) enters the sum as the expansion of
    /// sin^(e mod 2) q (1 − cos² q)^(e div 2) over its angles, the same
    /// polynomial as that expansion built with no sine squared anywhere:
    /// every square rewritten at once or one at a time alike.
    #[test]
    fn sines_squared_expand_as_one_minus_cosines_squared(
        left in proptest::collection::vec([0u32..=3, 0u32..=2], 3),
        right in proptest::collection::vec([0u32..=3, 0u32..=2], 3),
        k in 0u32..=2,
        c in -5i32..=5,
    ) {
        let s = hdot_sym::Symbols::parse_decl(&["a"], &ANGLES);
        let product = format!("({c})*({})*({})", monomial_text(&left, k), monomial_text(&right, 1));
        let mut expanded = format!("({c})*a^{}", k + 1);
        for (q, (l, r)) in ANGLES.iter().zip(left.iter().zip(&right)) {
            let (sin, cos) = (l[0] + r[0], l[1] + r[1]);
            expanded.push_str(&format!(
                "*sin({q})^{}*(1 - cos({q})^2)^{}*cos({q})^{cos}",
                sin % 2,
                sin / 2
            ));
        }
        prop_assert_eq!(s.poly(&product).unwrap(), s.poly(&expanded).unwrap(), "{} ≠ {}", product, expanded);
    }
}
