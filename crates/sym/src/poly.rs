//! The canonical form: a polynomial in atoms with exact rational
//! coefficients, with `sin²` of every angle rewritten as `1 − cos²`, and
//! with denominators that are powers of constants, of `sin θ` and of
//! `cos θ` (the pivots of rigid-body equations: `I′ sin θ`, `cos θ`, …).
//!
//! Every symbolic result in hdot is held in this form, and two expressions
//! are equal exactly when their [`Poly`] values are identical (`==`).
//! There is no heuristic simplify.
//!
//! # Why the form is unique
//!
//! Without trigonometric denominators a [`Poly`] is an element of
//! `A[s, c]/(s² + c² − 1)` for each angle (s = sin θ, c = cos θ, A the
//! polynomials in everything else, constants allowed to negative powers),
//! written in the basis `{cᵏ, s cᵏ}`: the rewriting `s² → 1 − c²` leaves
//! at most the first power of each `s`, and those monomials are linearly
//! independent, so the representation is unique.
//!
//! With division by `s` and `c`, a value is `N / (sᵃ cᵇ)` per angle, with
//! `N` in that basis. The form chosen is the one with the **smallest**
//! `a` and `b`: `N` is not divisible by `s` when `a > 0`, nor by `c` when
//! `b > 0`. It is unique because `s` and `c` are coprime in a strong sense:
//! modulo `s` we have `c² = 1`, so `c` is a unit there, and therefore
//! `s | N cᵏ` implies `s | N` (likewise with the roles exchanged, since
//! `s² = 1` modulo `c`). If `N₁/(s^a₁ c^b₁) = N₂/(s^a₂ c^b₂)` with both
//! reduced and `a₁ > a₂`, then `s^(a₁−a₂)` divides `N₁ c^b₂`, so `s | N₁`,
//! contradicting reduction; hence `a₁ = a₂`, likewise `b₁ = b₂`, and
//! `N₁ = N₂` in the integral domain. The argument holds for each angle with
//! the others' atoms in the coefficient ring, which stays an integral domain.
//!
//! Divisibility is decided exactly on the basis: writing
//! `N = Σ_R R (p_R(c) + s q_R(c))` over the distinct monomials `R` of the
//! other atoms, `c | N` iff every term has a factor `c`, and `s | N` iff
//! every `p_R` vanishes at `c = ±1` (then `p_R = (1 − c²) r_R` and
//! `N / s = Σ_R R (s r_R(c) + q_R(c))`). A polynomial with no
//! trigonometric denominator is untouched by this reduction, so the hot
//! loops of the derivations without division pay nothing for it.
//!
//! ```
//! use hdot_sym::{Poly, Symbols};
//! let s = Symbols::parse_decl(&[], &["theta"]);
//! let lhs = s.poly("sin(theta)^2 + cos(theta)^2").unwrap();
//! assert_eq!(lhs, Poly::one());
//! ```

use rustc_hash::FxHashMap;

use crate::atom::{Atom, AtomKind};
use crate::limits;
use crate::rational::Rational;

mod monomial;
mod ops;
mod sin_squares;
mod sort;
mod sums;
mod trig;
pub use monomial::{Exp, Monomial};
pub(crate) use monomial::{Trig, trig_by_angle_of, trig_of};
use sort::sort_terms;
use trig::divide_by_sin;

/// What may be divided by, for error messages.
pub const DIVISOR_RULE: &str = "only division by a non-zero number and by products and powers of constant symbols, \
                                sin and cos of angles is allowed";

/// The variable an atom depends on: the angle of `sin θ` and `cos θ`
/// (tied by `sin² = 1 − cos²`), the atom itself otherwise.
fn variable(a: Atom) -> Atom {
    match a.kind() {
        AtomKind::Sin(angle) | AtomKind::Cos(angle) => angle,
        AtomKind::Var { .. } | AtomKind::Sum { .. } => a,
    }
}

fn is_trig(a: Atom) -> bool {
    matches!(a.kind(), AtomKind::Sin(_) | AtomKind::Cos(_))
}

/// An atom whose negative powers call for the reduction of denominators:
/// `sin`, `cos` and a sum of constants (`poly/sums.rs`).
fn reduces(a: Atom) -> bool {
    matches!(
        a.kind(),
        AtomKind::Sin(_) | AtomKind::Cos(_) | AtomKind::Sum { .. }
    )
}

/// A canonical polynomial: terms sorted by monomial, no zero coefficients.
///
/// Invariant: canonical (see the module doc), so `==` is mathematical
/// equality. `trig_den` records whether some term has a negative power of
/// `sin`, `cos` or a sum of constants (it is a function of `terms`, kept
/// so that arithmetic on polynomials without such denominators skips the
/// reduction).
#[derive(Clone, Default, PartialEq, Eq, Hash)]
pub struct Poly {
    terms: Vec<(Monomial, Rational)>,
    trig_den: bool,
}

/// Accumulates terms, applying `sin² = 1 − cos²` on the way in and, when
/// a term has a trigonometric denominator, reducing the result to the
/// smallest denominators (module doc) in [`Accum::finish`].
#[derive(Default)]
pub(crate) struct Accum {
    map: FxHashMap<Monomial, Rational>,
    trig_den: bool,
}

impl Accum {
    pub(crate) fn with_capacity(n: usize) -> Accum {
        Accum {
            map: FxHashMap::with_capacity_and_hasher(n, Default::default()),
            trig_den: false,
        }
    }

    pub(crate) fn push(&mut self, m: Monomial, c: Rational) {
        if c.is_zero() {
            return;
        }
        crate::work::term_accumulated();
        self.trig_den |= m.has_trig_denominator();
        // Find a sin atom with exponent >= 2 and rewrite sin^2 = 1 - cos^2
        // (the exponent test comes first: it is cheaper than the kind).
        if let Some(&(s, _)) =
            m.0.iter()
                .find(|f| f.1 >= 2 && matches!(f.0.kind(), AtomKind::Sin(_)))
        {
            // Every square at once (`poly/sin_squares.rs`), or one at a
            // time for a sine to the fourth power or more.
            if self.push_sin_squares(&m, &c) {
                return;
            }
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
        self.insert(m, c);
    }

    /// Adds `c · m` to the sum as it is (`m` has no sine squared).
    fn insert(&mut self, m: Monomial, c: Rational) {
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
        if !limits::allow_terms(self.map.len()) {
            return Poly::zero();
        }
        let mut terms: Vec<_> = self.map.into_iter().collect();
        if self.trig_den {
            return Poly::reduce_trig(terms);
        }
        sort_terms(&mut terms);
        Poly {
            terms,
            trig_den: false,
        }
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
                trig_den: false,
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
            trig_den: false,
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

impl Poly {
    /// The terms that `keep` accepts, as a polynomial, when no term has a
    /// trigonometric denominator (`None` otherwise: a part of a reduced
    /// fraction need not be reduced). The terms stay sorted.
    pub fn retain_terms(&self, keep: impl Fn(&Monomial) -> bool) -> Option<Poly> {
        (!self.trig_den).then(|| Poly {
            terms: self
                .terms
                .iter()
                .filter(|(m, _)| keep(m))
                .cloned()
                .collect(),
            trig_den: false,
        })
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
        Some(Poly {
            terms: vec![(m.recip(), c.recip()?)],
            trig_den: false,
        })
    }

    /// The inverse of a *divisor*: a non-zero number times powers of
    /// constants, of `sin θ` and of `cos θ` (`I′ sin θ`, `cos² θ`, and
    /// `1 − cos² θ`, which is how `sin² θ` is held). `None` for anything
    /// else — a sum such as `J + I′ sin² θ`, or a time-dependent symbol.
    ///
    /// ```
    /// use hdot_sym::Symbols;
    /// let s = Symbols::parse_decl(&["Ip"], &["theta"]);
    /// let d = s.poly("Ip*(1 - cos(theta)^2)").unwrap(); // I′ sin²θ
    /// let q = &s.poly("Ip*sin(theta)").unwrap() * &d.inverse_divisor().unwrap();
    /// assert_eq!(q, s.poly("sin(theta)").unwrap().inverse_divisor().unwrap());
    /// ```
    pub fn inverse_divisor(&self) -> Option<Poly> {
        if self.is_zero() {
            return None;
        }
        let allowed = |a: Atom| matches!(a.kind(), AtomKind::Var { time: false, .. }) || is_trig(a);
        if self.atoms().into_iter().any(|a| !allowed(a)) {
            return None;
        }
        // Repeatedly: take out the monomial common to all terms, then one
        // factor sin θ (sin²θ is held as 1 − cos²θ), until a number is left.
        let mut inv = Poly::one();
        let mut rest = self.clone();
        loop {
            let g = rest
                .terms
                .iter()
                .skip(1)
                .fold(rest.terms[0].0.clone(), |g, t| g.gcd(&t.0));
            if !g.is_one() {
                inv = &inv * &Poly::term(g.recip(), Rational::ONE);
                rest = Poly::from_terms(rest.terms.iter().map(|(m, c)| (m.div(&g), c.clone())));
            }
            if let Some(c) = rest.as_constant() {
                return Some(inv.scale(&c.recip()?));
            }
            let angles = rest.atoms().into_iter().filter_map(|a| match a.kind() {
                AtomKind::Sin(q) | AtomKind::Cos(q) => Some(q),
                AtomKind::Var { .. } | AtomKind::Sum { .. } => None,
            });
            let mut divided = false;
            for q in angles {
                let (sin, cos) = (Atom::sin(q).expect("angle"), Atom::cos(q).expect("angle"));
                if let Some(t) = divide_by_sin(&rest.terms, sin, cos) {
                    rest = Poly::from_terms(t);
                    inv = &inv * &Poly::term(Monomial::atom(sin, -1), Rational::ONE);
                    divided = true;
                    break;
                }
            }
            if !divided {
                return None;
            }
        }
    }

    /// `self / d` for a divisor `d` accepted by [`Poly::inverse_divisor`].
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        Some(self * &d.inverse_divisor()?)
    }

    /// `self / (x + s)` when it divides exactly, `self` a polynomial in the atom `x`
    /// (no negative powers of it) and `s` free of `x`: synthetic division.
    pub fn div_binomial(&self, x: Atom, s: &Poly) -> Option<Poly> {
        let mut by_power: Vec<Poly> = Vec::new();
        for (m, c) in self.terms() {
            let k = usize::try_from(m.exponent(x)).ok()?;
            if by_power.len() <= k {
                by_power.resize(k + 1, Poly::zero());
            }
            by_power[k] = &by_power[k] + &Poly::term(m.without(x, k as _), c.clone());
        }
        let d = by_power.len() - 1;
        if d == 0 {
            return None;
        }
        // self = (x + s) q: q's coefficients from the top, b_{k-1} = c_k − s b_k.
        let mut q = vec![Poly::zero(); d];
        q[d - 1] = by_power[d].clone();
        for k in (1..d).rev() {
            q[k - 1] = &by_power[k] - &(s * &q[k]);
        }
        if !(&by_power[0] - &(s * &q[0])).is_zero() {
            return None;
        }
        Some(q.iter().enumerate().fold(Poly::zero(), |acc, (k, c)| {
            &acc + &(c * &Poly::term(Monomial::atom(x, k as _), Rational::ONE))
        }))
    }

    /// True when some term holds a negative power of `sin`, `cos` or a
    /// sum of constants (`poly/sums.rs`).
    pub fn has_trig_denominator(&self) -> bool {
        self.trig_den
    }

    /// Every atom that occurs, sorted by id, without repeats.
    pub fn atoms(&self) -> Vec<Atom> {
        // Few distinct atoms, many terms: insert into a small sorted list.
        let mut v: Vec<Atom> = Vec::new();
        for t in &self.terms {
            for &(a, _) in t.0.factors() {
                if let Err(i) = v.binary_search(&a) {
                    v.insert(i, a);
                }
            }
        }
        v
    }

    /// True when `a` occurs in some term (to any power, negative ones
    /// included).
    pub fn contains(&self, a: Atom) -> bool {
        self.terms.iter().any(|t| t.0.exponent(a) != 0)
    }

    /// Evaluates in `f64` with `value` giving each atom's value.
    pub fn eval(&self, value: &mut dyn FnMut(Atom) -> f64) -> f64 {
        let mut sum = 0.0;
        for (m, c) in &self.terms {
            let mut p = c.to_f64();
            for &(a, e) in m.factors() {
                // A sum of constants (to a negative power) is its terms' sum.
                let v = if e < 0 && sums::is_sum(a) {
                    Poly::atom_value(a).eval(value)
                } else {
                    value(a)
                };
                p *= v.powi(e);
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
            trig_den: self.trig_den,
        }
    }

    /// `self^n`, by repeated squaring. Within a [`limits::scope`] an
    /// exponent or coefficient over budget trips the scope first.
    pub fn pow(&self, mut n: u32) -> Poly {
        if limits::tripped() || !limits::allow_exponent(u64::from(n)) {
            return Poly::zero();
        }
        let bits = self.terms.iter().map(|t| t.1.bits()).max().unwrap_or(0);
        if !limits::allow_bits(bits.saturating_mul(u64::from(n))) {
            return Poly::zero();
        }
        // A sum of k terms to the n-th power has up to C(n + k − 1, k − 1)
        // terms: known before any multiplication.
        let k = self.len() as f64;
        let ln_terms = ln_binomial(f64::from(n) + k - 1.0, k - 1.0);
        if self.len() > 1 && !limits::allow_terms(ln_terms.exp().min(1e18) as usize) {
            return Poly::zero();
        }
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

    /// A lower bound on the terms of the product of `factors`, known before
    /// any multiplication (the budget check of an n-ary product).
    ///
    /// Factors are grouped by the variables they share (`sin θ` and `cos θ`
    /// count as the variable θ). A factor alone in its group multiplies
    /// the rest into distinct monomials, with no `sin²` to rewrite, so it
    /// multiplies the term count exactly by its length; a group of several
    /// factors contributes at least one term (they may cancel). With a
    /// trigonometric denominator anywhere no claim is made (bound 1).
    /// `(c0 + c1)(c2 + c3)…` of thirty sums is thus known to have 2³⁰ terms
    /// before the first product is formed.
    pub fn product_terms_at_least(factors: &[&Poly]) -> u64 {
        if factors.iter().any(|p| p.is_zero()) {
            return 0;
        }
        if factors.iter().any(|p| p.trig_den) {
            return 1;
        }
        // Union–find over factors, joined through the variables they hold.
        let mut parent: Vec<usize> = (0..factors.len()).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        let mut owner: FxHashMap<Atom, usize> = FxHashMap::default();
        for (i, p) in factors.iter().enumerate() {
            for a in p.atoms() {
                match owner.entry(variable(a)) {
                    std::collections::hash_map::Entry::Vacant(e) => {
                        e.insert(i);
                    }
                    std::collections::hash_map::Entry::Occupied(e) => {
                        let (r1, r2) = (root(&mut parent, *e.get()), root(&mut parent, i));
                        parent[r1] = r2;
                    }
                }
            }
        }
        let mut size = vec![0usize; factors.len()];
        for i in 0..factors.len() {
            size[root(&mut parent, i)] += 1;
        }
        factors
            .iter()
            .enumerate()
            .filter(|&(i, _)| size[root(&mut parent, i)] == 1)
            .fold(1u64, |n, (_, p)| n.saturating_mul(p.len() as u64))
    }
}

/// ln C(n, k) for real arguments, by Stirling's series (relative error far
/// below what a budget check needs).
fn ln_binomial(n: f64, k: f64) -> f64 {
    fn ln_gamma1(x: f64) -> f64 {
        // ln Γ(x + 1) = ln x!
        if x < 1.0 {
            return 0.0;
        }
        let x1 = x + 1.0;
        (x1 - 0.5) * x1.ln() - x1 + 0.5 * (2.0 * std::f64::consts::PI).ln() + 1.0 / (12.0 * x1)
    }
    ln_gamma1(n) - ln_gamma1(k) - ln_gamma1(n - k)
}
