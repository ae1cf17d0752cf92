//! The canonical form: a polynomial in atoms with exact rational
//! coefficients, with `sin²` of every angle rewritten as `1 − cos²`.
//!
//! Every symbolic result in hdot is held in this form. Because the
//! rewriting leaves at most the first power of each `sin`, the
//! representation is unique: two expressions are equal exactly when their
//! [`Poly`] values are identical (`==`). There is no heuristic simplify.
//!
//! ```
//! use hdot_sym::{Poly, Symbols};
//! let s = Symbols::parse_decl(&[], &["theta"]);
//! let lhs = s.poly("sin(theta)^2 + cos(theta)^2").unwrap();
//! assert_eq!(lhs, Poly::one());
//! ```

use std::fmt;

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::atom::{Atom, AtomKind};
use crate::rational::Rational;

/// An exponent. Negative exponents occur only on constant symbols
/// (`H_G/Ip` is `H_G·Ip⁻¹`), so that results such as φ̇ = H_G/I′ stay
/// polynomials in everything that varies: a Laurent monomial in the
/// constants, a plain monomial in the rest. The form remains unique.
pub type Exp = i32;

/// A product of atoms with non-zero exponents, sorted by atom id.
///
/// Invariant: sorted strictly by atom, no zero exponents, negative
/// exponents only on constant symbols, at most the first power of any
/// `sin` atom (in a canonical [`Poly`]).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Monomial(SmallVec<[(Atom, Exp); 8]>);

impl Monomial {
    /// The empty product, 1.
    pub fn one() -> Monomial {
        Monomial(SmallVec::new())
    }

    /// A single atom to a power (nothing for `exp == 0`).
    pub fn atom(a: Atom, exp: Exp) -> Monomial {
        let mut v = SmallVec::new();
        if exp != 0 {
            v.push((a, exp));
        }
        Monomial(v)
    }

    /// Builds a monomial from factors in any order (exponents of repeated
    /// atoms are added).
    pub fn from_factors(factors: impl IntoIterator<Item = (Atom, Exp)>) -> Monomial {
        let mut v: SmallVec<[(Atom, Exp); 8]> = factors.into_iter().filter(|f| f.1 != 0).collect();
        v.sort_unstable_by_key(|f| f.0);
        let mut out: SmallVec<[(Atom, Exp); 8]> = SmallVec::with_capacity(v.len());
        for (a, e) in v {
            match out.last_mut() {
                Some(last) if last.0 == a => last.1 += e,
                _ => out.push((a, e)),
            }
        }
        out.retain(|f| f.1 != 0);
        Monomial(out)
    }

    /// The factors `(atom, exponent)`, sorted by atom id.
    pub fn factors(&self) -> &[(Atom, Exp)] {
        &self.0
    }

    /// True for the empty product.
    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// The exponent of `a` (0 when absent).
    pub fn exponent(&self, a: Atom) -> Exp {
        self.0.iter().find(|f| f.0 == a).map_or(0, |f| f.1)
    }

    /// Total degree.
    pub fn degree(&self) -> Exp {
        self.0.iter().map(|f| f.1).sum()
    }

    /// The product of two monomials (no trigonometric reduction).
    pub fn mul(&self, other: &Monomial) -> Monomial {
        let (a, b) = (&self.0, &other.0);
        let mut out = SmallVec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let e = a[i].1 + b[j].1;
                    if e != 0 {
                        out.push((a[i].0, e));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Monomial(out)
    }

    /// This monomial divided by `a^by`.
    pub fn without(&self, a: Atom, by: Exp) -> Monomial {
        self.mul(&Monomial::atom(a, -by))
    }

    /// Splits into the part made of atoms accepted by `keep` and the rest.
    pub fn split(&self, keep: impl Fn(Atom) -> bool) -> (Monomial, Monomial) {
        let (a, b): (SmallVec<_>, SmallVec<_>) = self.0.iter().copied().partition(|f| keep(f.0));
        (Monomial(a), Monomial(b))
    }

    /// The greatest common divisor: the minimum exponent of every atom
    /// (an absent atom has exponent 0), so a common denominator is kept.
    pub fn gcd(&self, other: &Monomial) -> Monomial {
        let mut atoms: Vec<Atom> = self.0.iter().chain(other.0.iter()).map(|f| f.0).collect();
        atoms.sort_unstable();
        atoms.dedup();
        Monomial::from_factors(
            atoms
                .into_iter()
                .map(|a| (a, self.exponent(a).min(other.exponent(a)))),
        )
    }

    /// `self / other`.
    pub fn div(&self, other: &Monomial) -> Monomial {
        self.mul(&Monomial(other.0.iter().map(|&(a, e)| (a, -e)).collect()))
    }

    /// Factors sorted by [`Atom::sort_key`], for printing.
    pub fn sorted_for_print(&self) -> Vec<(Atom, Exp)> {
        let mut v = self.0.to_vec();
        if v.len() > 1 {
            v.sort_by_cached_key(|f| f.0.sort_key());
        }
        v
    }
}

/// A canonical polynomial: terms sorted by monomial, no zero coefficients.
///
/// Invariant: canonical (see the module doc), so `==` is mathematical
/// equality.
#[derive(Clone, Default, PartialEq, Eq, Hash)]
pub struct Poly {
    terms: Vec<(Monomial, Rational)>,
}

/// Accumulates terms, applying `sin² = 1 − cos²` on the way in.
#[derive(Default)]
pub(crate) struct Accum {
    map: FxHashMap<Monomial, Rational>,
}

impl Accum {
    pub(crate) fn with_capacity(n: usize) -> Accum {
        Accum {
            map: FxHashMap::with_capacity_and_hasher(n, Default::default()),
        }
    }

    pub(crate) fn push(&mut self, m: Monomial, c: Rational) {
        if c.is_zero() {
            return;
        }
        // Find a sin atom with exponent >= 2 and rewrite sin^2 = 1 - cos^2
        // (the exponent test comes first: it is cheaper than the kind).
        if let Some(&(s, _)) =
            m.0.iter()
                .find(|f| f.1 >= 2 && matches!(f.0.kind(), AtomKind::Sin(_)))
        {
            let AtomKind::Sin(angle) = s.kind() else {
                unreachable!()
            };
            let cos = Atom::cos(angle).expect("sin argument is an angle");
            let rest = m.without(s, 2);
            let with_cos = rest.mul(&Monomial::atom(cos, 2));
            self.push(rest, c.clone());
            self.push(with_cos, -c);
            return;
        }
        match self.map.entry(m) {
            std::collections::hash_map::Entry::Occupied(mut e) => {
                let v = e.get() + &c;
                if v.is_zero() {
                    e.remove();
                } else {
                    *e.get_mut() = v;
                }
            }
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(c);
            }
        }
    }

    pub(crate) fn finish(self) -> Poly {
        let mut terms: Vec<_> = self.map.into_iter().collect();
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        Poly { terms }
    }
}

/// # Construction
impl Poly {
    /// Zero.
    pub fn zero() -> Poly {
        Poly::default()
    }

    /// One.
    pub fn one() -> Poly {
        Poly::constant(Rational::ONE)
    }

    /// A rational constant.
    pub fn constant(c: Rational) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Monomial::one(), c)],
            }
        }
    }

    /// An integer constant.
    pub fn int(n: i64) -> Poly {
        Poly::constant(Rational::int(n))
    }

    /// A single atom.
    pub fn atom(a: Atom) -> Poly {
        Poly {
            terms: vec![(Monomial::atom(a, 1), Rational::ONE)],
        }
    }

    /// A single term `c · m` (reduced to canonical form).
    pub fn term(m: Monomial, c: Rational) -> Poly {
        let mut acc = Accum::default();
        acc.push(m, c);
        acc.finish()
    }

    /// Sums terms given in any order, reducing to canonical form.
    pub fn from_terms(terms: impl IntoIterator<Item = (Monomial, Rational)>) -> Poly {
        let mut acc = Accum::default();
        for (m, c) in terms {
            acc.push(m, c);
        }
        acc.finish()
    }
}

/// # Queries
impl Poly {
    /// The terms, sorted by monomial.
    pub fn terms(&self) -> &[(Monomial, Rational)] {
        &self.terms
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// True for zero (no terms).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value, when the polynomial is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        match self.terms.as_slice() {
            [] => Some(Rational::ZERO),
            [(m, c)] if m.is_one() => Some(c.clone()),
            _ => None,
        }
    }

    /// The single atom this polynomial is, if it is one.
    pub fn as_atom(&self) -> Option<Atom> {
        match self.terms.as_slice() {
            [(m, c)] if c.is_one() && m.factors().len() == 1 && m.factors()[0].1 == 1 => {
                Some(m.factors()[0].0)
            }
            _ => None,
        }
    }

    /// The inverse of a single term whose atoms are all constants
    /// (`2·m·Ip` → `½·m⁻¹·Ip⁻¹`); `None` for anything else or zero.
    pub fn inverse_monomial(&self) -> Option<Poly> {
        let [(m, c)] = self.terms.as_slice() else {
            return None;
        };
        let constants = m
            .factors()
            .iter()
            .all(|(a, _)| matches!(a.kind(), AtomKind::Var { time: false, .. }));
        if !constants {
            return None;
        }
        let inv = Monomial(m.0.iter().map(|&(a, e)| (a, -e)).collect());
        Some(Poly {
            terms: vec![(inv, c.recip()?)],
        })
    }

    /// Every atom that occurs, sorted by id, without repeats.
    pub fn atoms(&self) -> Vec<Atom> {
        let mut v: Vec<Atom> = self
            .terms
            .iter()
            .flat_map(|t| t.0.factors().iter().map(|f| f.0))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// True when `a` occurs in some term.
    pub fn contains(&self, a: Atom) -> bool {
        self.terms.iter().any(|t| t.0.exponent(a) > 0)
    }

    /// Evaluates in `f64` with `value` giving each atom's value.
    pub fn eval(&self, value: &mut dyn FnMut(Atom) -> f64) -> f64 {
        let mut sum = 0.0;
        for (m, c) in &self.terms {
            let mut p = c.to_f64();
            for &(a, e) in m.factors() {
                p *= value(a).powi(e);
            }
            sum += p;
        }
        sum
    }
}

/// # Operations
impl Poly {
    /// `self · c`.
    pub fn scale(&self, c: &Rational) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self.terms.iter().map(|(m, k)| (m.clone(), k * c)).collect(),
        }
    }

    /// `self^n`, by repeated squaring.
    pub fn pow(&self, mut n: u32) -> Poly {
        let mut base = self.clone();
        let mut acc = Poly::one();
        while n > 0 {
            if n & 1 == 1 {
                acc = &acc * &base;
            }
            n >>= 1;
            if n > 0 {
                base = &base * &base;
            }
        }
        acc
    }

    /// Source syntax in a stable, name-sorted term order (for messages and JSON).
    pub fn to_source(&self) -> String {
        crate::expr::Expr::from_poly(self).to_string()
    }
}

impl std::ops::Add for &Poly {
    type Output = Poly;
    fn add(self, rhs: &Poly) -> Poly {
        // Merge two sorted term lists; no reduction is needed.
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
        Poly { terms: out }
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
        }
    }
}

impl std::ops::Mul for &Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        if self.is_zero() || rhs.is_zero() {
            return Poly::zero();
        }
        if let Some(c) = rhs.as_constant() {
            return self.scale(&c);
        }
        if let Some(c) = self.as_constant() {
            return rhs.scale(&c);
        }
        // One side a single term free of sin: no two products can coincide
        // and none needs the sin² rewrite, so no hashing is needed.
        for (one, many) in [(rhs, self), (self, rhs)] {
            if let [(m, c)] = one.terms.as_slice()
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
                terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
                return Poly { terms };
            }
        }
        let mut acc = Accum::with_capacity(self.len() * rhs.len());
        for (m1, c1) in &self.terms {
            for (m2, c2) in &rhs.terms {
                acc.push(m1.mul(m2), c1 * c2);
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
