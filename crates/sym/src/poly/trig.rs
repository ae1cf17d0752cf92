//! The reduction of trigonometric denominators (the module doc of
//! [`crate::poly`] proves the form unique): a value with powers of
//! `sin θ` and `cos θ` below the line is divided out until its numerator is
//! divisible by neither.

use rustc_hash::FxHashMap;

use super::{Accum, Exp, Monomial, Poly, is_trig, sort_terms};
use crate::atom::{Atom, AtomKind};
use crate::rational::Rational;

/// # The reduction of trigonometric denominators (module doc)
impl Poly {
    /// Canonical form of terms that may hold negative powers of `sin` and
    /// `cos`, each already free of `sin²` where its exponent is ≥ 2.
    pub(super) fn reduce_trig(terms: Vec<(Monomial, Rational)>) -> Poly {
        if let Some(p) = Poly::reduce_sums(&terms) {
            return p;
        }
        // The denominator D: for every trig atom, its most negative exponent.
        let mut den: Vec<(Atom, Exp)> = Vec::new();
        for (m, _) in &terms {
            for &(a, e) in m.factors() {
                if e < 0 && is_trig(a) {
                    match den.iter_mut().find(|d| d.0 == a) {
                        Some(d) => d.1 = d.1.max(-e),
                        None => den.push((a, -e)),
                    }
                }
            }
        }
        // N = P · D, in the sin² = 1 − cos² normal form with no trig
        // denominator left.
        let d = Monomial::from_factors(den.iter().copied());
        let mut acc = Accum::with_capacity(terms.len());
        for (m, c) in terms {
            acc.push(m.mul(&d), c);
        }
        debug_assert!(!acc.trig_den);
        let mut n = acc.finish().terms;
        // Divide N by each sin and cos of D as often as it divides.
        for (a, k) in &mut den {
            while *k > 0 {
                let divided = match a.kind() {
                    AtomKind::Cos(_) => divide_by_cos(&n, *a),
                    AtomKind::Sin(angle) => divide_by_sin(&n, *a, Atom::cos(angle).expect("angle")),
                    AtomKind::Var { .. } | AtomKind::Sum { .. } => {
                        unreachable!("only trig atoms are in D")
                    }
                };
                match divided {
                    Some(q) => {
                        n = q;
                        *k -= 1;
                    }
                    None => break,
                }
            }
        }
        // P = N / D′ with D′ what is left of D.
        let rest = Monomial::from_factors(den.iter().map(|&(a, k)| (a, -k)));
        let trig_den = !rest.is_one();
        let mut terms: Vec<_> = n.into_iter().map(|(m, c)| (m.mul(&rest), c)).collect();
        sort_terms(&mut terms);
        Poly { terms, trig_den }
    }
}

/// `n / cos θ` when every term has a factor `cos θ` (terms in normal form,
/// no trig denominator).
fn divide_by_cos(n: &[(Monomial, Rational)], cos: Atom) -> Option<Vec<(Monomial, Rational)>> {
    if n.iter().any(|(m, _)| m.exponent(cos) < 1) {
        return None;
    }
    Some(
        n.iter()
            .map(|(m, c)| (m.without(cos, 1), c.clone()))
            .collect(),
    )
}

/// `n / sin θ` when it divides: writing `n = Σ_R R (p_R(c) + s q_R(c))`,
/// every `p_R` must vanish at `c = ±1`; then `p_R = (1 − c²) r_R` and the
/// quotient is `Σ_R R (s r_R(c) + q_R(c))`.
pub(super) fn divide_by_sin(
    n: &[(Monomial, Rational)],
    sin: Atom,
    cos: Atom,
) -> Option<Vec<(Monomial, Rational)>> {
    // p_R as coefficient lists by power of c, keyed by R.
    let mut p: FxHashMap<Monomial, Vec<Rational>> = FxHashMap::default();
    let mut out: Vec<(Monomial, Rational)> = Vec::with_capacity(n.len());
    for (m, c) in n {
        if m.exponent(sin) == 1 {
            out.push((m.without(sin, 1), c.clone()));
            continue;
        }
        let j = m.exponent(cos) as usize;
        let r = m.without(cos, j as Exp);
        let coeffs = p.entry(r).or_default();
        if coeffs.len() <= j {
            coeffs.resize(j + 1, Rational::ZERO);
        }
        coeffs[j] = &coeffs[j] + c;
    }
    for (r, coeffs) in p {
        let at_one: Rational = coeffs.iter().fold(Rational::ZERO, |s, c| &s + c);
        let at_minus_one = coeffs.iter().enumerate().fold(Rational::ZERO, |s, (j, c)| {
            if j % 2 == 0 { &s + c } else { &s - c }
        });
        if !at_one.is_zero() || !at_minus_one.is_zero() {
            return None;
        }
        // p_j = r_j − r_{j−2}: r_j = p_j + r_{j−2} for j ≤ deg − 2.
        let deg = coeffs.len() - 1;
        let mut q: Vec<Rational> = Vec::with_capacity(deg.saturating_sub(1));
        for j in 0..deg.saturating_sub(1) {
            let prev = if j >= 2 {
                q[j - 2].clone()
            } else {
                Rational::ZERO
            };
            q.push(&coeffs[j] + &prev);
        }
        for (j, c) in q.into_iter().enumerate() {
            if !c.is_zero() {
                let m = r.mul(&Monomial::from_factors([(sin, 1), (cos, j as Exp)]));
                out.push((m, c));
            }
        }
    }
    Some(out)
}
