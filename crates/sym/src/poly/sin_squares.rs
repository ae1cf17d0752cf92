//! `sin² = 1 − cos²` applied to a term in one step: a term with k sines
//! squared is the sum of the 2ᵏ terms of the expansion of
//! `Π (1 − cos² qⱼ)`, each built by one merge of the term less its
//! squares with the cosines squared it takes. Rewriting one square at a
//! time (a push per square, each dividing and multiplying the monomial
//! again) built 2ᵏ⁺¹ − 2 monomials and scanned 2ᵏ⁺¹ − 1 for the same
//! 2ᵏ terms: most of the term products of Kane's dot products in the
//! nonlinear bicycle, where a partial velocity and a force share the
//! sines of the steer and of the steer axis's tilt.

use smallvec::SmallVec;

use super::{Accum, Exp, Monomial};
use crate::atom::{Atom, AtomKind};
use crate::limits;
use crate::rational::Rational;

/// The most squares expanded at once (2⁸ terms); a term with more, or
/// with a sine to the fourth power or higher, is rewritten one square at
/// a time ([`Accum::push`]).
const MAX_SQUARES: usize = 8;

impl Accum {
    /// Puts `c · m` into the sum with every `sinᵉ q` of `m` with `e` 2 or 3
    /// written `sinᵉ⁻² q (1 − cos² q)`, expanded: the terms
    /// [`Accum::push`] reaches by rewriting one square at a time, each
    /// built once. `false` (nothing done) when `m` has no such sine, a sine
    /// to a higher power, or more than [`MAX_SQUARES`] of them.
    pub(super) fn push_sin_squares(&mut self, m: &Monomial, c: &Rational) -> bool {
        // `m` less its squares, still sorted, and the cosines squared.
        let mut base: SmallVec<[(Atom, Exp); 12]> = SmallVec::new();
        let mut cos: SmallVec<[Atom; MAX_SQUARES]> = SmallVec::new();
        for &(a, e) in m.factors() {
            if e >= 2
                && let AtomKind::Sin(q) = a.kind()
            {
                if e > 3 || cos.len() == MAX_SQUARES {
                    return false;
                }
                cos.push(Atom::cos(q).expect("sin argument is an angle"));
                if e == 3 {
                    base.push((a, 1));
                }
                continue;
            }
            base.push((a, e));
        }
        if cos.is_empty() {
            return false;
        }
        cos.sort_unstable();
        let k = cos.len();
        let minus = -c;
        for mask in 0u32..(1 << k) {
            crate::work::term_accumulated();
            let mut out: SmallVec<[(Atom, Exp); 12]> = SmallVec::new();
            let mut i = 0;
            if mask != 0 {
                crate::work::monomial_product();
            }
            for (j, &ca) in cos.iter().enumerate() {
                if mask >> j & 1 == 0 {
                    continue;
                }
                while i < base.len() && base[i].0 < ca {
                    out.push(base[i]);
                    i += 1;
                }
                if i < base.len() && base[i].0 == ca {
                    let e = limits::add_exponents(base[i].1, 2);
                    if e != 0 {
                        out.push((ca, e));
                    }
                    i += 1;
                } else {
                    out.push((ca, 2));
                }
            }
            out.extend_from_slice(&base[i..]);
            let coef = if mask.count_ones() % 2 == 0 {
                c
            } else {
                &minus
            };
            self.insert(Monomial(out), coef.clone());
        }
        true
    }
}
