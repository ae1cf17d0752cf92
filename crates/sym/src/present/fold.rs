//! Rule 1 of presentation: folding an abbreviation back into a result
//! (ψ̇ := ω_z − φ̇ cos θ and its derivatives), choosing the atom whose
//! elimination leaves the fewest terms.

use std::cmp::Reverse;

use crate::atom::{Atom, AtomKind};
use crate::poly::{Monomial, Poly};
use crate::rational::Rational;

/// Folds the abbreviation `name := def` into `p`: of the atoms of `def`
/// that can be eliminated (h := J (v + β̇) may give β̇ := h/J − v or
/// v := h/J − β̇), the one that leaves the fewest terms. Returns `p`
/// unchanged when no atom can be eliminated or every fold would leave more
/// terms than `p` has: folding w := ψ̇ + a cos θ into a linearised
/// b (ψ̇ + a) θ would bring back cos θ (b (w − a cos θ + a) θ), which reads
/// as a term of higher order. Nor is the component the abbreviation
/// defines folded into the abbreviation itself (ω_z = ω_z): a fold that
/// leaves `name` alone, or one of its derivatives alone, is not made, and
/// the definition is printed (ω_z = φ̇ cos θ + ψ̇). Exact: the result
/// equals `p` once `name` is replaced by `def`.
pub fn fold(p: &Poly, name: Atom, def: &Poly) -> Poly {
    let mut best: Option<Poly> = None;
    for (v, coef, c) in eliminable(def) {
        // v = (name − (def − c coef v)) / (c coef)
        let rest = def - &Poly::term(coef.mul(&Monomial::atom(v, 1)), c.clone());
        let inv = Poly::term(
            Monomial::one().div(&coef),
            c.recip().expect("non-zero coefficient"),
        );
        let v_expr = &(&Poly::atom(name) - &rest) * &inv;
        let q = p.subst(&mut |a| match a.kind() {
            AtomKind::Var {
                time: true, order, ..
            } if a.base() == v.base() && order >= v.order() => Some(v_expr.dt_n(order - v.order())),
            _ => None,
        });
        if q.len() <= p.len()
            && !is_the_abbreviation(&q, name)
            && best.as_ref().is_none_or(|b| q.len() < b.len())
        {
            best = Some(q);
        }
    }
    best.unwrap_or_else(|| p.clone())
}

/// Whether `q` is `name` alone, or one of its derivatives alone (ω_z, ω̇_z):
/// what the component that defines the abbreviation folds into.
fn is_the_abbreviation(q: &Poly, name: Atom) -> bool {
    match q.terms() {
        [(m, c)] => {
            c.is_one()
                && matches!(m.factors(), [(a, 1)] if a.base() == name.base() && a.order() >= name.order())
        }
        _ => false,
    }
}

/// The atoms of `def` that occur in exactly one term, to the first power,
/// times constants only, and whose base symbol occurs nowhere else; the
/// highest derivative first.
pub(super) fn eliminable(def: &Poly) -> Vec<(Atom, Monomial, Rational)> {
    let mut found = Vec::new();
    for (m, c) in def.terms() {
        let (timed, coef) = m.split(|a| a.is_time_dependent());
        let [(v, 1)] = timed.factors() else { continue };
        if !matches!(v.kind(), AtomKind::Var { time: true, .. }) {
            continue;
        }
        let others = def.terms().iter().filter(|(m2, _)| m2 != m);
        let clash = others
            .flat_map(|(m2, _)| m2.factors())
            .any(|(a, _)| match a.kind() {
                AtomKind::Var { .. } => a.base() == v.base(),
                AtomKind::Sin(q) | AtomKind::Cos(q) => q == v.base(),
                AtomKind::Sum { .. } => false,
            });
        if !clash {
            found.push((*v, coef, c.clone()));
        }
    }
    found.sort_by_key(|f| Reverse(f.0.order()));
    found
}
