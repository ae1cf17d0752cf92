//! A monomial: a product of atoms to integer powers, kept sorted by atom
//! (the key of a [`Poly`](super::Poly)'s terms), with its products,
//! quotients and print order.

use smallvec::SmallVec;

use super::reduces;
use crate::atom::{Atom, AtomKind};
use crate::limits;

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
pub struct Monomial(pub(super) SmallVec<[(Atom, Exp); 12]>);

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
        self.merge(other, 1)
    }

    /// `self · other^sign` (`sign` is 1 or −1) in one merge of the two
    /// sorted factor lists. The result starts inline and spills to the
    /// heap only when it has more factors than the inline room: reserving
    /// the two lengths' sum put every product or quotient of long
    /// monomials on the heap (a chain-6 term divided by its rates has
    /// 13 + 10 factors in and 3 out).
    fn merge(&self, other: &Monomial, sign: Exp) -> Monomial {
        crate::work::monomial_product();
        let (a, b) = (&self.0, &other.0);
        let mut out: SmallVec<[(Atom, Exp); 12]> = SmallVec::new();
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push((b[j].0, sign * b[j].1));
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let e = limits::add_exponents(a[i].1, sign * b[j].1);
                    if e != 0 {
                        out.push((a[i].0, e));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        if sign == 1 {
            out.extend_from_slice(&b[j..]);
        } else {
            out.extend(b[j..].iter().map(|&(x, e)| (x, -e)));
        }
        Monomial(out)
    }

    /// `self / a · other` in one merge (one product, not two): the
    /// derivative of factor `a` of a term is the rest of the term times
    /// the derivative of `a`. `a` must be a factor of `self`.
    pub(crate) fn mul_without(&self, a: Atom, other: &Monomial) -> Monomial {
        crate::work::monomial_product();
        let (x, y) = (&self.0, &other.0);
        let mut out = SmallVec::new();
        let (mut i, mut j) = (0, 0);
        // The exponent of x[i] once a is divided out.
        let own = |i: usize| if x[i].0 == a { x[i].1 - 1 } else { x[i].1 };
        while i < x.len() && j < y.len() {
            match x[i].0.cmp(&y[j].0) {
                std::cmp::Ordering::Less => {
                    if own(i) != 0 {
                        out.push((x[i].0, own(i)));
                    }
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(y[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let e = limits::add_exponents(own(i), y[j].1);
                    if e != 0 {
                        out.push((x[i].0, e));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        while i < x.len() {
            if own(i) != 0 {
                out.push((x[i].0, own(i)));
            }
            i += 1;
        }
        out.extend_from_slice(&y[j..]);
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
        // One merge of the two sorted factor lists.
        let (a, b) = (&self.0, &other.0);
        let mut out = SmallVec::new();
        let (mut i, mut j) = (0, 0);
        while i < a.len() || j < b.len() {
            let (atom, e) = match (a.get(i), b.get(j)) {
                (Some(x), Some(y)) if x.0 == y.0 => {
                    i += 1;
                    j += 1;
                    (x.0, x.1.min(y.1))
                }
                (Some(x), Some(y)) if x.0 < y.0 => {
                    i += 1;
                    (x.0, x.1.min(0))
                }
                (Some(x), None) => {
                    i += 1;
                    (x.0, x.1.min(0))
                }
                (_, Some(y)) => {
                    j += 1;
                    (y.0, y.1.min(0))
                }
                (None, None) => break,
            };
            if e != 0 {
                out.push((atom, e));
            }
        }
        Monomial(out)
    }

    /// `self / other`.
    pub fn div(&self, other: &Monomial) -> Monomial {
        self.merge(other, -1)
    }

    /// True when some `sin`, `cos` or sum atom has a negative exponent.
    pub fn has_trig_denominator(&self) -> bool {
        self.0.iter().any(|f| f.1 < 0 && reduces(f.0))
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

/// Factors in print order (sorted by [`Atom::sort_key`]: the sines by
/// angle, then the cosines) with the cosine of an angle moved next to the
/// sine of the same angle, so that factors of one angle stay together:
/// `sin θ cos θ cos² λ`, `sin ψ cos ψ sin θ`; a cosine whose sine is
/// absent keeps its place after the sines (`sin θ cos ψ`).
pub(crate) fn trig_by_angle<E>(fs: &mut [(Atom, E)]) {
    // Each factor's kind is read once.
    let mut trig: SmallVec<[Trig; 16]> = fs.iter().map(|f| trig_of(f.0)).collect();
    trig_by_angle_of(fs, &mut trig);
}

/// An atom as [`trig_by_angle`] sees it: (is a cosine, its angle) for sin
/// and cos, `None` for the others.
pub(crate) type Trig = Option<(bool, Atom)>;

/// The [`Trig`] of an atom.
pub(crate) fn trig_of(a: Atom) -> Trig {
    match a.kind() {
        AtomKind::Sin(q) => Some((false, q)),
        AtomKind::Cos(q) => Some((true, q)),
        AtomKind::Var { .. } | AtomKind::Sum { .. } => None,
    }
}

/// [`trig_by_angle`] with each factor's [`Trig`] given (`trig[k]` of
/// `fs[k]`, moved with it), for a caller that knows them already.
pub(crate) fn trig_by_angle_of<E>(fs: &mut [(Atom, E)], trig: &mut [Trig]) {
    // Nothing moves without a sine.
    if !trig.iter().any(|t| matches!(t, Some((false, _)))) {
        return;
    }
    for k in 0..fs.len() {
        let Some((true, q)) = trig[k] else {
            continue;
        };
        if let Some(j) = trig[..k].iter().position(|t| *t == Some((false, q)))
            && j + 1 < k
        {
            // Moving it forward shifts the factors between, all already seen.
            fs[j + 1..=k].rotate_right(1);
            trig[j + 1..=k].rotate_right(1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The merge of `gcd` gives the minimum exponent of every atom, an
    /// absent atom counting as exponent 0, over pairs of monomials with
    /// shared, missing and negative powers (seeded, exhaustive over a small
    /// grid of exponents).
    #[test]
    fn gcd_is_the_minimum_of_every_exponent() {
        let s = crate::Symbols::parse_decl(&["a", "b", "c", "d"], &["x"]);
        let atoms: Vec<Atom> = ["a", "b", "c", "d"]
            .iter()
            .map(|n| s.poly(n).unwrap().terms()[0].0.factors()[0].0)
            .collect();
        let exps = [-2, -1, 0, 1, 3];
        let monomial = |code: usize| {
            Monomial::from_factors(
                atoms
                    .iter()
                    .enumerate()
                    .map(|(k, &a)| (a, exps[(code / exps.len().pow(k as u32)) % exps.len()])),
            )
        };
        let n = exps.len().pow(atoms.len() as u32);
        let mut checked = 0;
        for i in (0..n).step_by(7) {
            for j in (0..n).step_by(11) {
                let (p, q) = (monomial(i), monomial(j));
                let want = Monomial::from_factors(
                    atoms.iter().map(|&a| (a, p.exponent(a).min(q.exponent(a)))),
                );
                assert_eq!(p.gcd(&q), want, "gcd of {p:?} and {q:?}");
                checked += 1;
            }
        }
        assert!(checked > 1_000);
    }
}
