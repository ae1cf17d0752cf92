//! Partial derivatives, `∂x/∂q`, treating a symbol and each of its time
//! derivatives as independent variables (as Lagrange's equations do:
//! `∂T/∂θ̇` holds θ fixed).
//!
//! Through `sin` and `cos` by the chain rule (`∂ sin θ/∂θ = cos θ`), and
//! through negative powers (`∂ (1/sin θ)/∂θ = −cos θ/sin² θ`). The result
//! is canonical. Abbreviations are atoms of their own here: callers that
//! differentiate through them unfold them first.
//!
//! # Example
//! ```
//! use hdot_sym::{Atom, Symbols};
//! let s = Symbols::parse_decl(&["Ip"], &["theta", "phi"]);
//! let t = s.poly("Ip*(theta'^2 + phi'^2*sin(theta)^2)/2").unwrap();
//! let d = t.partial(Atom::time("theta", 0));
//! assert_eq!(d, s.poly("Ip*phi'^2*sin(theta)*cos(theta)").unwrap());
//! assert_eq!(t.partial(Atom::time("theta", 1)), s.poly("Ip*theta'").unwrap());
//! ```

use crate::atom::{Atom, AtomKind};
use crate::poly::{Accum, Monomial, Poly};
use crate::rational::Rational;

impl Poly {
    /// `∂self/∂q` for a symbol atom `q` (a constant, or a time symbol of
    /// any derivative order).
    pub fn partial(&self, q: Atom) -> Poly {
        let mut acc = Accum::with_capacity(self.len());
        let (sin, cos) = match q.kind() {
            AtomKind::Var { order: 0, .. } => (Atom::sin(q), Atom::cos(q)),
            _ => (None, None),
        };
        for (m, c) in self.terms() {
            for &(a, e) in m.factors() {
                let k = c * &Rational::int(i64::from(e));
                let rest = m.without(a, 1);
                if a == q {
                    acc.push(rest, k);
                } else if Some(a) == sin {
                    acc.push(rest.mul(&Monomial::atom(cos.expect("angle"), 1)), k);
                } else if Some(a) == cos {
                    acc.push(rest.mul(&Monomial::atom(sin.expect("angle"), 1)), -k);
                }
            }
        }
        acc.finish()
    }
}
