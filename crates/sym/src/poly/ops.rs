//! Arithmetic on [`Poly`] by the operators: `+`, `−`, `×` (with the
//! accumulating sum) on references and owned values, and its printing.

use std::fmt;

use super::{Accum, Monomial, Poly, sort_terms, variable};
use crate::atom::{Atom, AtomKind};
use crate::limits;
use crate::rational::Rational;

impl std::ops::Add for &Poly {
    type Output = Poly;
    fn add(self, rhs: &Poly) -> Poly {
        if limits::tripped() {
            return Poly::zero();
        }
        // Merge two sorted term lists; no reduction is needed unless a
        // trigonometric denominator is involved.
        let (a, b) = (&self.terms, &rhs.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j].clone());
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let c = &a[i].1 + &b[j].1;
                    if !c.is_zero() {
                        out.push((a[i].0.clone(), c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        crate::work::terms_merged(out.len());
        if !limits::allow_terms(out.len()) {
            return Poly::zero();
        }
        if self.trig_den || rhs.trig_den {
            return Poly::reduce_trig(out);
        }
        Poly {
            terms: out,
            trig_den: false,
        }
    }
}

impl std::ops::Sub for &Poly {
    type Output = Poly;
    fn sub(self, rhs: &Poly) -> Poly {
        self + &(-rhs)
    }
}

impl std::ops::Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect(),
            trig_den: self.trig_den,
        }
    }
}

impl std::ops::Mul for &Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        if self.is_zero() || rhs.is_zero() || limits::tripped() {
            return Poly::zero();
        }
        if let Some(c) = rhs.as_constant() {
            return self.scale(&c);
        }
        if let Some(c) = self.as_constant() {
            return rhs.scale(&c);
        }
        if !allow_product(self, rhs) {
            return Poly::zero();
        }
        // One side a single term free of sin: no two products can coincide
        // and none needs the sin² rewrite, so no hashing is needed (unless
        // a trigonometric denominator needs reducing).
        for (one, many) in [(rhs, self), (self, rhs)] {
            if !self.trig_den
                && !rhs.trig_den
                && let [(m, c)] = one.terms.as_slice()
                && !m
                    .factors()
                    .iter()
                    .any(|f| matches!(f.0.kind(), AtomKind::Sin(_)))
            {
                let mut terms: Vec<(Monomial, Rational)> = many
                    .terms
                    .iter()
                    .map(|(m2, c2)| (m2.mul(m), c2 * c))
                    .collect();
                sort_terms(&mut terms);
                return Poly {
                    terms,
                    trig_den: false,
                };
            }
        }
        // No variable in common (sin θ and cos θ count as θ) and no
        // trigonometric denominator: every term product is a distinct
        // canonical monomial, so the result has exactly `n · m` terms
        // (checked before they are formed) and needs no hashing.
        if !self.trig_den && !rhs.trig_den {
            let vars = |p: &Poly| {
                let mut v: Vec<Atom> = p.atoms().into_iter().map(variable).collect();
                v.sort_unstable();
                v.dedup();
                v
            };
            let (va, vb) = (vars(self), vars(rhs));
            if va.iter().all(|a| vb.binary_search(a).is_err()) {
                if !limits::allow_terms(self.len().saturating_mul(rhs.len())) {
                    return Poly::zero();
                }
                let mut terms = Vec::with_capacity(self.len() * rhs.len());
                for (m1, c1) in &self.terms {
                    for (m2, c2) in &rhs.terms {
                        terms.push((m1.mul(m2), c1 * c2));
                    }
                }
                sort_terms(&mut terms);
                return Poly {
                    terms,
                    trig_den: false,
                };
            }
        }
        // Room for the larger factor's terms, not for every product: a
        // dense product (`(a + … + f)⁹ · (a − … − f)⁹`, 4·10⁶ products into
        // 3·10⁴ terms) spent most of its time missing the cache of a table
        // sized for all of them; the table grows as needed.
        let mut acc = Accum::with_capacity(self.len().max(rhs.len()));
        for (m1, c1) in &self.terms {
            for (m2, c2) in &rhs.terms {
                acc.push(m1.mul(m2), c1 * c2);
            }
        }
        acc.finish()
    }
}

/// Whether the product of `a` and `b` is within the scope's work limit
/// (`limits::allow_product`; long coefficients make each term product
/// dearer).
fn allow_product(a: &Poly, b: &Poly) -> bool {
    let words = |p: &Poly| {
        p.terms
            .iter()
            .map(|t| t.1.bits())
            .max()
            .unwrap_or(0)
            .div_ceil(64)
    };
    let weight = if a.len().min(b.len()) > 1 {
        words(a) * words(b)
    } else {
        1
    };
    limits::allow_product(a.len(), b.len(), weight)
}

impl Poly {
    /// `Σ aᵢ · bᵢ` over `pairs`, every term product accumulated into one
    /// sum: the value of `&(&a₁ * &b₁) + &(&a₂ * &b₂) + …` (the canonical
    /// form is unique), without forming each product, sorting it and
    /// merging it into the partial sums. Kane's `v_r · F + ω_r · Ḣ` is six
    /// products and five sums per generalized speed.
    pub fn sum_of_products<'a>(pairs: impl IntoIterator<Item = (&'a Poly, &'a Poly)>) -> Poly {
        let mut acc = Accum::default();
        for (a, b) in pairs {
            if a.is_zero() || b.is_zero() {
                continue;
            }
            if limits::tripped() || !allow_product(a, b) {
                return Poly::zero();
            }
            for (m1, c1) in &a.terms {
                for (m2, c2) in &b.terms {
                    acc.push(m1.mul(m2), c1 * c2);
                }
            }
        }
        acc.finish()
    }
}

macro_rules! forward_owned {
    ($($tr:ident $f:ident),*) => {$(
        impl std::ops::$tr for Poly {
            type Output = Poly;
            fn $f(self, rhs: Poly) -> Poly { std::ops::$tr::$f(&self, &rhs) }
        }
    )*};
}
forward_owned!(Add add, Sub sub, Mul mul);

impl std::ops::Neg for Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        -&self
    }
}

/// Sums many polynomials in one pass (pairwise merging would be quadratic).
impl std::iter::Sum for Poly {
    fn sum<I: Iterator<Item = Poly>>(iter: I) -> Poly {
        let mut acc = Accum::default();
        for p in iter {
            for (m, c) in p.terms {
                acc.push(m, c);
            }
        }
        acc.finish()
    }
}

impl fmt::Display for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_source())
    }
}

impl fmt::Debug for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Poly({self})")
    }
}
