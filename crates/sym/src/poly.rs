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

use std::fmt;

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::atom::{Atom, AtomKind};
use crate::limits;
use crate::rational::Rational;

/// An exponent. Negative exponents occur only on constant symbols
/// (`H_G/Ip` is `H_G·Ip⁻¹`) and on `sin`/`cos` atoms (`1/sin θ`), so
/// that results such as φ̇ = H_G/I′ or φ̈ = (…)/sin θ stay polynomials in
/// every time-dependent symbol. The form remains unique (module doc).
pub type Exp = i32;

/// A product of atoms with non-zero exponents, sorted by atom id.
///
/// Twelve factors are held inline: a term of chain-8's Ḣ has up to a
/// constant, two rates and a sine or cosine of each of eight angles, and a
/// monomial spilled to the heap costs an allocation and more memory than
/// the inline room it leaves unused.
///
/// Invariant: sorted strictly by atom, no zero exponents, negative
/// exponents only on constant symbols and trigonometric atoms, at most the
/// first power of any `sin` atom (in a canonical [`Poly`]).
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub struct Monomial(SmallVec<[(Atom, Exp); 12]>);

/// One well-mixed word per monomial. The derived hash fed the factors to
/// `FxHasher` one by one, a linear function of small integers that put
/// the terms of a dense product (`(a + … + f)⁹ · (a − … − f)⁹`) into long
/// probe sequences: 80 % of the time of such a product went to the hash
/// map.
impl std::hash::Hash for Monomial {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        let mut h: u64 = 0x243F_6A88_85A3_08D3;
        for &(a, e) in &self.0 {
            let w = (u64::from(a.id()) << 32) | u64::from(e as u32);
            h = (h ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            h ^= h >> 29;
        }
        state.write_u64(h);
    }
}

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
        let mut v: SmallVec<[(Atom, Exp); 12]> = factors.into_iter().filter(|f| f.1 != 0).collect();
        v.sort_unstable_by_key(|f| f.0);
        let mut out: SmallVec<[(Atom, Exp); 12]> = SmallVec::with_capacity(v.len());
        for (a, e) in v {
            match out.last_mut() {
                Some(last) if last.0 == a => last.1 = limits::add_exponents(last.1, e),
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
        crate::work::monomial_product();
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
                    let e = limits::add_exponents(a[i].1, b[j].1);
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

    /// True when some `sin` or `cos` atom has a negative exponent.
    pub fn has_trig_denominator(&self) -> bool {
        self.0.iter().any(|f| f.1 < 0 && is_trig(f.0))
    }

    /// The same monomial with every exponent negated.
    pub fn recip(&self) -> Monomial {
        Monomial(self.0.iter().map(|&(a, e)| (a, -e)).collect())
    }

    /// Factors sorted by [`Atom::sort_key`], for printing, with the cos of
    /// an angle next to its sin ([`trig_by_angle`]).
    pub fn sorted_for_print(&self) -> Vec<(Atom, Exp)> {
        let mut v = self.0.to_vec();
        if v.len() > 1 {
            v.sort_by_cached_key(|f| f.0.sort_key());
            trig_by_angle(&mut v);
        }
        v
    }
}

/// What may be divided by, for error messages.
pub const DIVISOR_RULE: &str = "only division by a non-zero number and by products and powers of constant symbols, \
                                sin and cos of angles is allowed";

/// The variable an atom depends on: the angle of `sin θ` and `cos θ`
/// (tied by `sin² = 1 − cos²`), the atom itself otherwise.
fn variable(a: Atom) -> Atom {
    match a.kind() {
        AtomKind::Sin(angle) | AtomKind::Cos(angle) => angle,
        AtomKind::Var { .. } => a,
    }
}

fn is_trig(a: Atom) -> bool {
    matches!(a.kind(), AtomKind::Sin(_) | AtomKind::Cos(_))
}

/// A canonical polynomial: terms sorted by monomial, no zero coefficients.
///
/// Invariant: canonical (see the module doc), so `==` is mathematical
/// equality. `trig_den` records whether some term has a negative power of
/// `sin` or `cos` (it is a function of `terms`, kept so that arithmetic
/// on polynomials without trigonometric denominators skips the reduction).
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
        if !limits::allow_terms(self.map.len()) {
            return Poly::zero();
        }
        let mut terms: Vec<_> = self.map.into_iter().collect();
        if self.trig_den {
            return Poly::reduce_trig(terms);
        }
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        Poly {
            terms,
            trig_den: false,
        }
    }
}

/// # The reduction of trigonometric denominators (module doc)
impl Poly {
    /// Canonical form of terms that may hold negative powers of `sin` and
    /// `cos`, each already free of `sin²` where its exponent is ≥ 2.
    fn reduce_trig(terms: Vec<(Monomial, Rational)>) -> Poly {
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
                    AtomKind::Var { .. } => unreachable!("only trig atoms are in D"),
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
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        Poly { terms, trig_den }
    }
}

/// Factors in print order (sorted by [`Atom::sort_key`]: the sines by
/// angle, then the cosines) with the cosine of an angle moved next to the
/// sine of the same angle, so that factors of one angle stay together:
/// `sin θ cos θ cos² λ`, `sin ψ cos ψ sin θ`; a cosine whose sine is
/// absent keeps its place after the sines (`sin θ cos ψ`).
pub(crate) fn trig_by_angle<E>(fs: &mut [(Atom, E)]) {
    for k in 0..fs.len() {
        let AtomKind::Cos(q) = fs[k].0.kind() else {
            continue;
        };
        if let Some(j) = fs[..k].iter().position(|f| f.0.kind() == AtomKind::Sin(q))
            && j + 1 < k
        {
            // Moving it forward shifts the factors between, all already seen.
            fs[j + 1..=k].rotate_right(1);
        }
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
fn divide_by_sin(
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
                AtomKind::Var { .. } => None,
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

    /// True when some term holds a negative power of `sin` or `cos`.
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
        // Long coefficients make each term product dearer.
        let words = |p: &Poly| {
            p.terms
                .iter()
                .map(|t| t.1.bits())
                .max()
                .unwrap_or(0)
                .div_ceil(64)
        };
        let weight = if self.len().min(rhs.len()) > 1 {
            words(self) * words(rhs)
        } else {
            1
        };
        if !limits::allow_product(self.len(), rhs.len(), weight) {
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
                terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
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
                terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
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
