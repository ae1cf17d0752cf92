//! Division by a sum of constants: the sum `s` as one factor (a sum atom,
//! [`AtomKind::Sum`]) held to negative powers, and the reduction that keeps
//! the canonical form unique when such factors occur.
//!
//! # The normal form of a sum
//!
//! A sum atom holds a polynomial `s` in constant symbols only (no rates,
//! no sin or cos) of two or more terms, with no monomial common to its
//! terms (no negative exponents either: `I′ + I L²/r²` is held as
//! `I L² + I′ r²` over `r²`), integer coefficients without a common
//! divisor, and the term printed first positive. Every sum that is not
//! zero is a number times a monomial times exactly one such `s`
//! ([`Poly::sum_factor`]), so `1/(I′ + I L²/r²)` is `r² · s⁻¹`.
//!
//! # Why the form stays unique
//!
//! With a sum atom `S` standing for `s`, a value is `N / sᴷ` with `N`
//! free of `S`. The form chosen is the one with the smallest `K`: `N` is
//! not divisible by `s` when `K > 0`. As for `sin θ` (the module doc of
//! [`crate::poly`]), two reduced forms of one value are identical: if
//! `N₁/s^K₁ = N₂/s^K₂` with `K₁ > K₂`, then `N₁ = N₂ s^(K₁−K₂)`, so
//! `s | N₁`, a contradiction. Every term of a value holding `S` therefore
//! holds it to the same power `−K`: `g sin β + F/s` is held as
//! `(g s sin β + F)/s`. Divisibility by `s` is decided exactly by the
//! division algorithm in the constants of `s` (lexicographic order, the
//! leading coefficient of `s` a number, the other atoms in the
//! coefficients): its remainder is zero exactly when `s` divides. Two
//! different sums are taken to be coprime (sums are not factored), so a
//! value is reduced by each sum atom in turn.
//! (`solve` splits a determinant's sum into the coefficients' own sums
//! where they divide it, so that each cancels against the numerators:
//! `derivation/ops/solve.rs`.)
//!
//! A sum is divided by only where it is known not to be zero: `solve`
//! asks that every term have one sign for the constants declared
//! `positive` (`derivation/ops/solve.rs`).

use super::{Exp, Monomial, Poly};
use crate::atom::{Atom, AtomKind};
use crate::expr::print_sorted;
use crate::rational::Rational;

/// Whether `a` is a sum atom.
pub(super) fn is_sum(a: Atom) -> bool {
    matches!(a.kind(), AtomKind::Sum { .. })
}

/// # Division by a sum of constants
impl Poly {
    /// `self` as `k · s` with `s` a sum of constants in normal form (module
    /// doc) and `k` a number times a monomial (of any atoms, sin and cos
    /// included): `(I L² + I′ r²) cos θ/r²` is `(cos θ/r²) · (I L² + I′ r²)`.
    /// `None` when what is left after the monomial is not such a sum (a
    /// single term, or a sum holding a rate, sin or cos).
    pub fn sum_factor(&self) -> Option<(Poly, Poly)> {
        let (first, _) = self.terms.first()?;
        let g = self
            .terms
            .iter()
            .skip(1)
            .fold(first.clone(), |g, t| g.gcd(&t.0));
        let rest: Vec<(Monomial, Rational)> = self
            .terms
            .iter()
            .map(|(m, c)| (m.div(&g), c.clone()))
            .collect();
        let constant = |a: Atom| matches!(a.kind(), AtomKind::Var { time: false, .. });
        if rest.len() < 2
            || rest
                .iter()
                .any(|(m, _)| !m.factors().iter().all(|f| constant(f.0)))
        {
            return None;
        }
        let content = rest.iter().fold(Rational::ZERO, |g, t| g.gcd(&t.1));
        let first_printed = print_sorted(&rest, false)[0].2.clone();
        let content = if first_printed.is_negative() {
            -content
        } else {
            content
        };
        let inv = content.recip()?;
        let s = Poly::from_terms(rest.into_iter().map(|(m, c)| (m, &c * &inv)));
        Some((Poly::term(g, content), s))
    }

    /// The inverse of `k · s` ([`Poly::sum_factor`]) when `k` is a divisor
    /// ([`Poly::inverse_divisor`]); the caller knows that `s` is not zero.
    pub fn inverse_with_sum(&self) -> Option<Poly> {
        let (k, s) = self.sum_factor()?;
        Some(&k.inverse_divisor()? * &Poly::recip_sum(&s))
    }

    /// `self / s` for a sum `s` in normal form ([`Poly::sum_factor`]) when
    /// `s` divides it exactly (the division algorithm of the module doc);
    /// `None` when it does not.
    pub fn div_sum(&self, s: &Poly) -> Option<Poly> {
        divide_by_sum(self, s)
    }

    /// `1/s` for a sum `s` in normal form ([`Poly::sum_factor`]), which the
    /// caller knows not to be zero.
    pub fn recip_sum(s: &Poly) -> Poly {
        Poly::term(Monomial::atom(Atom::sum(s), -1), Rational::ONE)
    }

    /// The sum a sum atom stands for, the atom itself otherwise.
    pub fn atom_value(a: Atom) -> Poly {
        match a.kind() {
            AtomKind::Sum { sum, .. } => sum.clone(),
            _ => Poly::atom(a),
        }
    }

    /// The canonical form of `terms` when one of them holds a sum atom
    /// (module doc); `None` when none does.
    pub(super) fn reduce_sums(terms: &[(Monomial, Rational)]) -> Option<Poly> {
        let atom = terms
            .iter()
            .flat_map(|t| t.0.factors())
            .find(|f| f.1 < 0 && is_sum(f.0))?
            .0;
        let AtomKind::Sum { sum, .. } = atom.kind() else {
            unreachable!("a sum atom")
        };
        let mut k: Exp = terms
            .iter()
            .map(|t| -t.0.exponent(atom))
            .max()
            .unwrap_or(0)
            .max(0);
        // N = Σ c m sᴷ⁺ᵉ over the terms c m Sᵉ (a positive power of S, left
        // by a reciprocal monomial, is the sum multiplied out).
        let mut by_exp: std::collections::BTreeMap<Exp, Vec<(Monomial, Rational)>> =
            Default::default();
        for (m, c) in terms {
            let e = m.exponent(atom);
            by_exp
                .entry(e)
                .or_default()
                .push((m.without(atom, e), c.clone()));
        }
        let mut n = Poly::zero();
        for (e, ts) in by_exp {
            let part = Poly::from_terms(ts);
            n = &n + &(&part * &sum.pow((k + e).unsigned_abs()));
        }
        while k > 0 {
            match divide_by_sum(&n, sum) {
                Some(q) => {
                    n = q;
                    k -= 1;
                }
                None => break,
            }
        }
        if k == 0 || n.is_zero() {
            return Some(n);
        }
        let d = Monomial::atom(atom, -k);
        let mut terms: Vec<_> = n.terms.into_iter().map(|(m, c)| (m.mul(&d), c)).collect();
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        Some(Poly {
            terms,
            trig_den: true,
        })
    }
}

/// `n / s` when `s` divides `n` exactly (module doc): the division
/// algorithm in the constants of `s`, after clearing their negative powers
/// in `n`. `None` when it does not divide (or after a bound on the steps).
fn divide_by_sum(n: &Poly, s: &Poly) -> Option<Poly> {
    let vars = s.atoms();
    let of_s = |a: Atom| vars.binary_search(&a).is_ok();
    let mut shift: Vec<(Atom, Exp)> = Vec::new();
    for (m, _) in n.terms() {
        for &(a, e) in m.factors() {
            if e < 0 && of_s(a) {
                match shift.iter_mut().find(|f| f.0 == a) {
                    Some(f) => f.1 = f.1.max(-e),
                    None => shift.push((a, -e)),
                }
            }
        }
    }
    let d = Monomial::from_factors(shift);
    let mut r = n * &Poly::term(d.clone(), Rational::ONE);
    let key = |m: &Monomial| -> Vec<Exp> { vars.iter().map(|&a| m.exponent(a)).collect() };
    let (lead, lead_c) = s.terms().iter().max_by_key(|t| key(&t.0))?;
    let lead_key = key(lead);
    let inv = lead_c.recip()?;
    let mut q = Poly::zero();
    // Each step lowers the leading exponents of r in the lexicographic
    // order; the bound only guards against a value too large to divide.
    for _ in 0..4096 {
        if r.is_zero() {
            return Some(&q * &Poly::term(d.recip(), Rational::ONE));
        }
        let top = r.terms().iter().map(|t| key(&t.0)).max()?;
        if top.iter().zip(&lead_key).any(|(t, l)| t < l) {
            return None;
        }
        let t = Poly::from_terms(
            r.terms()
                .iter()
                .filter(|x| key(&x.0) == top)
                .map(|(m, c)| (m.div(lead), c * &inv)),
        );
        q = &q + &t;
        r = &r - &(&t * s);
    }
    None
}
