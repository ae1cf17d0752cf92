//! Rule 3 of presentation: a bracket equal to a product of the step's
//! known factors (A − B, A − C) times a monomial and a number, printed as
//! that product — as the file writes each factor when it can — and checked
//! by canonical equality, never assumed.

use super::Presentation;
use crate::expr::{Expr, Id, Node};
use crate::poly::{Monomial, Poly};
use crate::rational::Rational;

/// A known factor as the file writes it (`J s + (C − A) Ω`, the author's
/// grouping and order), when its written form expands to it; otherwise in
/// the default presentation.
pub(super) fn known_factor_node(e: &mut Expr, f: &Poly, pres: &Presentation) -> Id {
    let written = pres
        .factors
        .iter()
        .position(|k| k == f)
        .and_then(|k| pres.factor_forms.get(k))
        .filter(|w| !w.is_empty() && w.to_poly() == *f);
    match written {
        Some(w) => graft(e, w, w.root()),
        None => e.poly_node(f),
    }
}

/// Copies the subtree of `src` at `id` into `e`; returns its new id.
pub(super) fn graft(e: &mut Expr, src: &Expr, id: Id) -> Id {
    let node = match src.node(id) {
        Node::Add(ts) => Node::Add(ts.iter().map(|&t| graft(e, src, t)).collect()),
        Node::Mul(fs) => Node::Mul(fs.iter().map(|&f| graft(e, src, f)).collect()),
        Node::Neg(x) => Node::Neg(graft(e, src, *x)),
        Node::Pow(x, k) => Node::Pow(graft(e, src, *x), *k),
        leaf => leaf.clone(),
    };
    e.push(node)
}

/// Writes `p` as `c · m · Π fs` with `fs` all the known factors (or a single
/// one), `m` a monomial and `c` a number, when that is exact.
pub(super) fn factor_by(p: &Poly, known: &[Poly]) -> Option<(Vec<Poly>, Monomial, Rational)> {
    if known.is_empty() {
        return None;
    }
    let mut candidates: Vec<Vec<Poly>> = vec![known.to_vec()];
    if known.len() > 1 {
        candidates.extend(known.iter().map(|f| vec![f.clone()]));
    }
    for fs in candidates {
        let product = fs.iter().fold(Poly::one(), |a, f| &a * f);
        if product.len() != p.len() || product.is_zero() {
            continue;
        }
        let (m0, c0) = &p.terms()[0];
        for (m1, c1) in product.terms() {
            let m = m0.div(m1);
            let c = c0 * &c1.recip().expect("non-zero coefficient");
            if &product * &Poly::term(m.clone(), c.clone()) == *p {
                return Some((fs, m, c));
            }
        }
    }
    None
}
