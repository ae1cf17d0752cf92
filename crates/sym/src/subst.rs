//! Substitution of atoms by polynomials.
//!
//! [`Poly::subst`] replaces every atom for which a rule returns a
//! replacement; [`Poly::subst_symbol`] replaces a time-dependent symbol
//! *and its derivatives* (θ := e also gives θ̇ := ė, θ̈ := ë) and, when the
//! replacement is another angle, its sines and cosines.
//!
//! # Example
//! ```
//! use hdot_sym::{Atom, Poly, Symbols};
//! let s = Symbols::parse_decl(&["I_xz", "I_yz", "I_z"], &["omega"]);
//! let m = s.poly("-I_xz*omega' + I_yz*omega^2").unwrap();
//! let sym = m.subst(&mut |a| (a == Atom::constant("I_xz") || a == Atom::constant("I_yz")).then(Poly::zero));
//! assert!(sym.is_zero());
//! ```

use rustc_hash::FxHashMap;

use crate::atom::{Atom, AtomKind};
use crate::poly::{Accum, Exp, Monomial, Poly};
use crate::rational::Rational;

impl Poly {
    /// Replaces each atom `a` for which `rule(a)` is `Some(p)` by `p`.
    pub fn subst(&self, rule: &mut dyn FnMut(Atom) -> Option<Poly>) -> Poly {
        let mut cache: FxHashMap<Atom, Option<Poly>> = FxHashMap::default();
        for a in self.atoms() {
            let mut r = rule(a);
            // A sum of constants is replaced by its terms, substituted.
            if r.is_none()
                && let AtomKind::Sum { sum, .. } = a.kind()
            {
                r = Some(sum.subst(rule)).filter(|s| s != sum);
            }
            cache.insert(a, r);
        }
        if cache.values().all(Option::is_none) {
            return self.clone();
        }
        let mut acc = Accum::with_capacity(self.len());
        // Each power of a replacement is formed once: the terms of a long
        // polynomial hold the same few powers many times (the nonlinear
        // bicycle's speeds: 64,000 powers of 825 polynomials).
        let mut powers: FxHashMap<(Atom, Exp), Poly> = FxHashMap::default();
        for (m, c) in self.terms() {
            let (kept, replaced) = m.split(|a| cache[&a].is_none());
            let mut p = Poly::term(kept, c.clone());
            for &(a, e) in replaced.factors() {
                let f = powers.entry((a, e)).or_insert_with(|| {
                    let r = cache[&a].as_ref().expect("replaced atom");
                    if e > 0 {
                        r.pow(e.unsigned_abs())
                    } else {
                        // A constant in a denominator: only an invertible
                        // replacement can stand there; otherwise the atom
                        // stays (callers detect it, e.g. "I occurs in a
                        // denominator").
                        match r.inverse_divisor().or_else(|| r.inverse_with_sum()) {
                            Some(inv) => inv.pow(e.unsigned_abs()),
                            None => Poly::term(Monomial::atom(a, e), Rational::ONE),
                        }
                    }
                });
                p = &p * f;
            }
            for (m2, c2) in p.terms() {
                acc.push(m2.clone(), c2.clone());
            }
        }
        acc.finish()
    }

    /// Replaces the symbol `sym` (order 0) by `value`, together with its time
    /// derivatives (by differentiating `value`) and, where `value` is itself
    /// an angle symbol, `sin`/`cos` of it. Returns `None` when `sym` occurs
    /// inside `sin`/`cos` and `value` is not an angle symbol.
    pub fn subst_symbol(&self, sym: Atom, value: &Poly) -> Option<Poly> {
        let angle = value.as_atom().filter(|a| a.is_angle());
        let mut ok = true;
        let out = self.subst(&mut |a| match a.kind() {
            AtomKind::Var { .. } if a.base() == sym => Some(value.dt_n(a.order())),
            AtomKind::Sin(q) if q == sym => match angle {
                Some(v) => Some(Poly::atom(Atom::sin(v).expect("angle"))),
                None => {
                    ok = false;
                    None
                }
            },
            AtomKind::Cos(q) if q == sym => match angle {
                Some(v) => Some(Poly::atom(Atom::cos(v).expect("angle"))),
                None => {
                    ok = false;
                    None
                }
            },
            _ => None,
        });
        ok.then_some(out)
    }

    /// Sets an angle to a multiple of a quarter turn (`quarter_turns · π/2`)
    /// held constant: `sin`/`cos` become 0 or ±1 and its rates vanish.
    /// Returns `None` when the angle itself (not its sine or cosine) occurs.
    pub fn subst_quarter_turns(&self, angle: Atom, quarter_turns: i64) -> Option<Poly> {
        let (s, c) = match quarter_turns.rem_euclid(4) {
            0 => (0, 1),
            1 => (1, 0),
            2 => (0, -1),
            _ => (-1, 0),
        };
        let mut ok = true;
        let out = self.subst(&mut |a| match a.kind() {
            AtomKind::Sin(q) if q == angle => Some(Poly::int(s)),
            AtomKind::Cos(q) if q == angle => Some(Poly::int(c)),
            AtomKind::Var { .. } if a == angle => {
                ok = false;
                None
            }
            AtomKind::Var { order, .. } if order > 0 && a.base() == angle => Some(Poly::zero()),
            _ => None,
        });
        ok.then_some(out)
    }
}

/// True when `p` mentions the symbol `sym`, a derivative of it, or its
/// sine or cosine.
pub fn mentions_symbol(p: &Poly, sym: Atom) -> bool {
    p.atoms().into_iter().any(|a| match a.kind() {
        AtomKind::Var { .. } => a.base() == sym,
        AtomKind::Sin(q) | AtomKind::Cos(q) => q == sym,
        AtomKind::Sum { sum, .. } => mentions_symbol(sum, sym),
    })
}
