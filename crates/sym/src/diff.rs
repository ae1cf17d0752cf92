//! Time derivatives, `d/dt`, by the product and chain rules.
//!
//! A time-dependent symbol of order k differentiates to the same symbol of
//! order k + 1; `d/dt sin θ = cos θ · θ̇`, `d/dt cos θ = −sin θ · θ̇`;
//! constants differentiate to zero. The result is canonical.
//!
//! # Example
//! ```
//! use hdot_sym::Symbols;
//! let s = Symbols::parse_decl(&["I"], &["theta", "omega"]);
//! let e = s.poly("I*omega*sin(theta)").unwrap();
//! let expected = s.poly("I*omega'*sin(theta) + I*omega*cos(theta)*theta'").unwrap();
//! assert_eq!(e.dt(), expected);
//! ```

use crate::atom::{Atom, AtomKind};
use crate::poly::{Accum, Monomial, Poly};
use crate::rational::Rational;

/// The derivative of a single atom, as a list of `(monomial, coefficient)`.
fn atom_dt(a: Atom) -> Vec<(Monomial, Rational)> {
    match a.kind() {
        AtomKind::Var { time: false, .. } | AtomKind::Sum { .. } => vec![],
        AtomKind::Var { time: true, .. } => {
            vec![(
                Monomial::atom(a.derivative().expect("time symbol"), 1),
                Rational::ONE,
            )]
        }
        AtomKind::Sin(q) => match q.derivative() {
            Some(qd) => vec![(
                Monomial::from_factors([(Atom::cos(q).expect("angle"), 1), (qd, 1)]),
                Rational::ONE,
            )],
            None => vec![],
        },
        AtomKind::Cos(q) => match q.derivative() {
            Some(qd) => vec![(
                Monomial::from_factors([(Atom::sin(q).expect("angle"), 1), (qd, 1)]),
                -Rational::ONE,
            )],
            None => vec![],
        },
    }
}

impl Poly {
    /// The total time derivative `d/dt`.
    pub fn dt(&self) -> Poly {
        // As many terms as time-dependent factors (fewer where some meet,
        // more where sin² is rewritten): a table sized for them does not
        // grow and rehash on the way (chain-8: three tables of 42,000).
        let products = self
            .terms()
            .iter()
            .map(|(m, _)| {
                m.factors()
                    .iter()
                    .filter(|f| f.0.is_time_dependent())
                    .count()
            })
            .sum();
        let mut acc = Accum::with_capacity(products);
        // A long polynomial names a few atoms many times: differentiate
        // each once (interning the derivative atoms is a table lookup).
        let mut cache: rustc_hash::FxHashMap<Atom, Vec<(Monomial, Rational)>> = Default::default();
        for (m, c) in self.terms() {
            for &(a, e) in m.factors() {
                if !a.is_time_dependent() {
                    continue;
                }
                let k = c * &Rational::int(i64::from(e));
                for (dm, dc) in cache.entry(a).or_insert_with(|| atom_dt(a)).iter() {
                    // (m / a) · d/dt a, one product.
                    acc.push(m.mul_without(a, dm), &k * dc);
                }
            }
        }
        acc.finish()
    }

    /// The `n`-th time derivative.
    pub fn dt_n(&self, n: u32) -> Poly {
        let mut p = self.clone();
        for _ in 0..n {
            p = p.dt();
        }
        p
    }
}
