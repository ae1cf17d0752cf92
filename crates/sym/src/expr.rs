//! Expression trees for presentation and for the parser: a flat node store.
//!
//! [`Expr`] keeps its nodes in one `Vec` in which every child comes before
//! its parent and the root is last (the layout of egg's `RecExpr`). It is
//! the *shape* of an expression as written or as it should be printed;
//! arithmetic happens on the canonical [`Poly`], reached by
//! [`Expr::to_poly`]. `Display` (in the printer, `print.rs`, which this
//! file does not import) prints source syntax that
//! [`crate::Symbols::expr`] parses back to an identical tree.
//!
//! Invariant: `Num` holds non-negative rationals (signs are `Neg` nodes);
//! `Add` and `Mul` have at least two children; `Pow` exponents are ≥ 2.

use smallvec::SmallVec;

use crate::atom::{Atom, AtomKind};
use crate::poly::{Monomial, Poly};
use crate::rational::Rational;

/// Index of a node in an [`Expr`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Id(u32);

/// One node of an [`Expr`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Node {
    /// A non-negative rational number.
    Num(Rational),
    /// A symbol, a derivative of one, or sin/cos of an angle.
    Atom(Atom),
    /// A sum of two or more terms.
    Add(Vec<Id>),
    /// A product of two or more factors.
    Mul(Vec<Id>),
    /// Negation.
    Neg(Id),
    /// A power with an integer exponent ≥ 2, or a negative one (a
    /// denominator; only of constant symbols).
    Pow(Id, i32),
}

/// A flat expression tree; the root is the last node.
#[derive(Clone, Default)]
pub struct Expr {
    nodes: Vec<Node>,
}

/// # Construction
impl Expr {
    /// An empty store; add nodes, the last one added is the root.
    pub fn new() -> Expr {
        Expr::default()
    }

    /// Appends a node and returns its id. Children must already be present.
    pub fn push(&mut self, node: Node) -> Id {
        debug_assert!(match &node {
            Node::Num(r) => !r.is_negative(),
            Node::Add(v) | Node::Mul(v) => v.len() >= 2,
            Node::Pow(_, e) => *e >= 2 || *e < 0,
            _ => true,
        });
        self.nodes.push(node);
        Id(self.nodes.len() as u32 - 1)
    }

    /// Gives back the store's spare capacity (a large tree, once built).
    pub(crate) fn shrink_to_fit(&mut self) {
        self.nodes.shrink_to_fit();
    }

    /// A number node; negative values become `Neg(Num)`.
    pub fn num(&mut self, r: &Rational) -> Id {
        if r.is_negative() {
            let n = self.push(Node::Num(r.abs()));
            self.push(Node::Neg(n))
        } else {
            self.push(Node::Num(r.clone()))
        }
    }

    /// A sum; a single term is returned as it is, an empty one is `0`.
    pub fn add(&mut self, terms: Vec<Id>) -> Id {
        match terms.len() {
            0 => self.push(Node::Num(Rational::ZERO)),
            1 => terms[0],
            _ => self.push(Node::Add(terms)),
        }
    }

    /// A product; a single factor is returned as it is, an empty one is `1`.
    pub fn mul(&mut self, factors: Vec<Id>) -> Id {
        match factors.len() {
            0 => self.push(Node::Num(Rational::ONE)),
            1 => factors[0],
            _ => self.push(Node::Mul(factors)),
        }
    }

    /// `atom^exp` (just the atom when `exp == 1`).
    pub fn atom_pow(&mut self, a: Atom, exp: i32) -> Id {
        let id = self.push(Node::Atom(a));
        if exp == 1 {
            id
        } else {
            self.push(Node::Pow(id, exp))
        }
    }

    /// The default presentation of a canonical polynomial: terms in a stable
    /// order that depends only on names, each as `±c · atoms`.
    pub fn from_poly(p: &Poly) -> Expr {
        let mut e = Expr::new();
        let root = e.poly_node(p);
        debug_assert_eq!(root.0 as usize, e.nodes.len() - 1);
        e
    }

    /// Adds the default presentation of `p` and returns its id.
    pub fn poly_node(&mut self, p: &Poly) -> Id {
        let ids = print_sorted(p.terms(), false)
            .into_iter()
            .map(|(fs, _, c)| self.term_node(&fs, c))
            .collect();
        self.add(ids)
    }

    /// `c · Π atoms` with the sign as a `Neg` node.
    pub fn term_node(&mut self, factors: &[(Atom, i32)], c: &Rational) -> Id {
        let mut ids = Vec::with_capacity(factors.len() + 1);
        let mag = c.abs();
        if !mag.is_one() || factors.is_empty() {
            ids.push(self.push(Node::Num(mag)));
        }
        for &(a, e) in factors {
            ids.push(self.atom_pow(a, e));
        }
        let m = self.mul(ids);
        if c.is_negative() {
            self.push(Node::Neg(m))
        } else {
            m
        }
    }
}

/// A term in print order: its factors sorted for printing, and the term.
pub(crate) type PrintTerm<'a> = (SmallVec<[(Atom, i32); 12]>, &'a Monomial, &'a Rational);

/// `terms` sorted for printing, each with its factors in print order: by
/// [`print_order`] of the sorted factors, preceded, when `derivative_first`,
/// by the highest derivative order in the term (descending), which is the
/// order of terms inside a presented bracket.
///
/// The order is computed with integer keys: each distinct atom's print rank
/// is found once (one sort of the atoms by [`Atom::sort_key`], see
/// [`PrintRanks`]), so the comparisons of the term sort compare integers,
/// not names. A key is `[u32::MAX − top order, (rank, −exp)…]` (without the
/// first entry unless `derivative_first`) with the factor codes sorted,
/// which orders lexicographically exactly as the comparisons do, and the
/// sorted codes are the factors in print order (then, as in
/// [`Monomial::sorted_for_print`], a cosine is moved next to the sine of
/// its angle).
pub(crate) fn print_sorted(
    terms: &[(Monomial, Rational)],
    derivative_first: bool,
) -> Vec<PrintTerm<'_>> {
    PrintRanks::of(terms.iter().map(|t| &t.0)).sort(terms, derivative_first)
}

/// The print rank of each atom of a set of monomials (its place in the
/// order of [`Atom::sort_key`]), read by the atom's id. Made once for a
/// whole result, it orders the factors and terms of every part of it —
/// the presentation's brackets are quotients of the result's terms, so
/// their atoms are among the result's — without sorting names again.
pub(crate) struct PrintRanks {
    /// The rank of an atom by its id (`u32::MAX`: not among the atoms).
    rank: Vec<u32>,
    /// The atoms in print order.
    atoms: Vec<Atom>,
    /// Each atom's sin/cos kind, in print order.
    trig: Vec<crate::poly::Trig>,
    /// Each atom's derivative order, in print order.
    order: Vec<u32>,
}

impl PrintRanks {
    /// The ranks of the atoms of `monomials`.
    pub(crate) fn of<'a>(monomials: impl Iterator<Item = &'a Monomial>) -> PrintRanks {
        // A table as long as the largest id, not a hash map: looked up for
        // every factor of every term. The distinct atoms are found by
        // marking that table, in one pass over the factors.
        let mut rank: Vec<u32> = Vec::new();
        let mut atoms: Vec<Atom> = Vec::new();
        for m in monomials {
            for &(a, _) in m.factors() {
                let i = a.id() as usize;
                if i >= rank.len() {
                    rank.resize(i + 1, u32::MAX);
                }
                if rank[i] == u32::MAX {
                    rank[i] = 0;
                    atoms.push(a);
                }
            }
        }
        // Sort keys are distinct (names), so the order found is immaterial.
        atoms.sort_by_cached_key(|a| a.sort_key());
        let trig = atoms.iter().map(|&a| crate::poly::trig_of(a)).collect();
        let order = atoms.iter().map(|&a| a.order()).collect();
        for (k, a) in atoms.iter().enumerate() {
            rank[a.id() as usize] = k as u32;
        }
        PrintRanks {
            rank,
            atoms,
            trig,
            order,
        }
    }

    /// The rank of `a`, `None` when it is not among the atoms.
    pub(crate) fn rank(&self, a: Atom) -> Option<u32> {
        self.rank
            .get(a.id() as usize)
            .copied()
            .filter(|&r| r != u32::MAX)
    }

    /// The atoms, in print order.
    pub(crate) fn atoms(&self) -> &[Atom] {
        &self.atoms
    }

    /// Whether every atom of `m` has a rank.
    pub(crate) fn covers(&self, m: &Monomial) -> bool {
        m.factors().iter().all(|f| self.rank(f.0).is_some())
    }

    fn code(&self, a: Atom, x: i32) -> u64 {
        (u64::from(self.rank[a.id() as usize]) << 32) | (i64::from(i32::MAX) - i64::from(x)) as u64
    }

    /// The factors of sorted codes, a cosine next to the sine of its angle.
    fn factors_of(&self, codes: &[u64]) -> SmallVec<[(Atom, i32); 12]> {
        let mut factors: SmallVec<[(Atom, i32); 12]> = codes
            .iter()
            .map(|&c| {
                let atom = self.atoms[(c >> 32) as usize];
                let x = i64::from(i32::MAX) - (c & 0xffff_ffff) as i64;
                (atom, x as i32)
            })
            .collect();
        let mut kinds: SmallVec<[crate::poly::Trig; 16]> = codes
            .iter()
            .map(|&c| self.trig[(c >> 32) as usize])
            .collect();
        crate::poly::trig_by_angle_of(&mut factors, &mut kinds);
        factors
    }

    /// The factors of `m` in print order, as [`Monomial::sorted_for_print`]
    /// gives them.
    pub(crate) fn sorted(&self, m: &Monomial) -> SmallVec<[(Atom, i32); 12]> {
        if !self.covers(m) {
            return m.sorted_for_print().into_iter().collect();
        }
        let mut codes: SmallVec<[u64; 16]> =
            m.factors().iter().map(|&(a, x)| self.code(a, x)).collect();
        codes.sort_unstable();
        self.factors_of(&codes)
    }

    /// [`print_sorted`] of `terms` with these ranks (made anew when some
    /// atom of `terms` has none).
    pub(crate) fn sort<'t>(
        &self,
        terms: &'t [(Monomial, Rational)],
        derivative_first: bool,
    ) -> Vec<PrintTerm<'t>> {
        self.sort_with(terms, derivative_first, true)
    }

    /// [`PrintRanks::sort`] without each term's factors in print order
    /// (every factor list empty): the order alone, for a caller that
    /// writes few of the terms itself and finds their factors with
    /// [`PrintRanks::sorted`] (a presented bracket whose terms mostly go
    /// into sub-brackets that sort their own).
    pub(crate) fn sort_unfactored<'t>(
        &self,
        terms: &'t [(Monomial, Rational)],
        derivative_first: bool,
    ) -> Vec<PrintTerm<'t>> {
        self.sort_with(terms, derivative_first, false)
    }

    fn sort_with<'t>(
        &self,
        terms: &'t [(Monomial, Rational)],
        derivative_first: bool,
        factors: bool,
    ) -> Vec<PrintTerm<'t>> {
        if !terms.iter().all(|t| self.covers(&t.0)) {
            return PrintRanks::of(terms.iter().map(|t| &t.0)).sort_with(
                terms,
                derivative_first,
                factors,
            );
        }
        // Every term's key in one flat array (its slice `start..end`), so
        // that no key is allocated on its own; beside it, the key's first
        // entries packed into one integer that orders as they do
        // ([`packed_prefix`]): most comparisons of the sort are one integer
        // comparison, the slices compared only where the prefixes tie.
        let mut codes: Vec<u64> =
            Vec::with_capacity(terms.iter().map(|t| t.0.factors().len() + 1).sum());
        let mut keyed: Vec<(u128, u32, u32, u32)> = Vec::with_capacity(terms.len());
        // (A few terms are sorted in a few comparisons: not packed.)
        let mut packed = terms.len() >= 32;
        for (i, (m, _)) in terms.iter().enumerate() {
            let top = if derivative_first {
                m.factors()
                    .iter()
                    .map(|f| self.order[self.rank[f.0.id() as usize] as usize])
                    .max()
                    .unwrap_or(0)
            } else {
                0
            };
            let start = codes.len();
            codes.push(u64::from(u32::MAX - top));
            codes.extend(m.factors().iter().map(|&(a, x)| self.code(a, x)));
            codes[start + 1..].sort_unstable();
            let prefix = if packed {
                packed_prefix(&codes[start..])
            } else {
                None
            };
            packed &= prefix.is_some();
            keyed.push((
                prefix.unwrap_or(0),
                start as u32,
                codes.len() as u32,
                i as u32,
            ));
        }
        let key = |k: &(u128, u32, u32, u32)| &codes[k.1 as usize..k.2 as usize];
        if packed {
            keyed.sort_unstable_by(|a, b| a.0.cmp(&b.0).then_with(|| key(a).cmp(key(b))));
        } else {
            keyed.sort_unstable_by(|a, b| key(a).cmp(key(b)));
        }
        keyed
            .iter()
            .map(|k| {
                let i = k.3 as usize;
                let fs = if factors {
                    self.factors_of(&key(k)[1..])
                } else {
                    SmallVec::new()
                };
                (fs, &terms[i].0, &terms[i].1)
            })
            .collect()
    }
}

/// The first entries of a term's sort key (`[u32::MAX − top order,
/// codes…]`, see [`PrintRanks::sort`]) packed into one integer that orders
/// as the slices do on those entries: 8 bits for the top order, then 16
/// bits for each of the first seven codes (0 where the key has ended, which
/// orders a key before its extensions, as slices are ordered), each code
/// its rank and exponent in the code's order. Two keys whose prefixes
/// differ are ordered by them; equal prefixes leave the rest to the
/// slices. `None` when some entry does not fit (a top order of 255 or
/// more, a rank of 512 or more, an exponent outside −31 … 32).
fn packed_prefix(key: &[u64]) -> Option<u128> {
    const FIELDS: usize = 7;
    let top = u64::from(u32::MAX) - key[0];
    if top >= 255 {
        return None;
    }
    let mut packed = u128::from(255 - top);
    for k in 0..FIELDS {
        let field = match key.get(k + 1) {
            None => 0,
            Some(&code) => {
                let rank = code >> 32;
                // The code's low half is i32::MAX − x.
                let x = i64::from(i32::MAX) - (code & 0xffff_ffff) as i64;
                if rank >= 512 || !(-31..=32).contains(&x) {
                    return None;
                }
                1 + ((rank << 6) | (32 - x) as u64)
            }
        };
        packed = (packed << 16) | u128::from(field);
    }
    Some(packed)
}

/// Orders printed terms: by their factors' name keys, then exponents.
#[cfg(test)]
pub(crate) fn print_order(a: &[(Atom, i32)], b: &[(Atom, i32)]) -> std::cmp::Ordering {
    let ka = a.iter().map(|f| (f.0.sort_key(), std::cmp::Reverse(f.1)));
    let kb = b.iter().map(|f| (f.0.sort_key(), std::cmp::Reverse(f.1)));
    ka.cmp(kb)
}

/// # Queries
impl Expr {
    /// The root's id.
    pub fn root(&self) -> Id {
        Id(self.nodes.len() as u32 - 1)
    }

    /// The node at `id`.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.0 as usize]
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True for a store with no nodes.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Expands to the canonical form.
    pub fn to_poly(&self) -> Poly {
        let mut vals: Vec<Poly> = Vec::with_capacity(self.nodes.len());
        for n in &self.nodes {
            let v = match n {
                Node::Num(r) => Poly::constant(r.clone()),
                Node::Atom(a) => match a.kind() {
                    // A sum of constants stands for its terms.
                    AtomKind::Sum { sum, .. } => sum.clone(),
                    _ => Poly::term(Monomial::atom(*a, 1), Rational::ONE),
                },
                Node::Add(c) => c.iter().map(|i| vals[i.0 as usize].clone()).sum(),
                Node::Mul(c) => c
                    .iter()
                    .fold(Poly::one(), |acc, i| &acc * &vals[i.0 as usize]),
                Node::Neg(i) => -&vals[i.0 as usize],
                Node::Pow(i, e) if *e >= 0 => vals[i.0 as usize].pow(e.unsigned_abs()),
                // Negative powers are of divisors (the invariant); anything
                // else has no polynomial value and expands to zero.
                Node::Pow(i, e) => {
                    let base = &vals[i.0 as usize];
                    base.inverse_divisor()
                        .or_else(|| base.inverse_with_sum())
                        .map_or_else(Poly::zero, |p| p.pow(e.unsigned_abs()))
                }
            };
            vals.push(v);
        }
        vals.pop().unwrap_or_default()
    }

    /// Evaluates in `f64` without expanding.
    pub fn eval(&self, value: &mut dyn FnMut(Atom) -> f64) -> f64 {
        let mut vals: Vec<f64> = Vec::with_capacity(self.nodes.len());
        for n in &self.nodes {
            let v = match n {
                Node::Num(r) => r.to_f64(),
                Node::Atom(a) => match a.kind() {
                    AtomKind::Sum { sum, .. } => sum.eval(value),
                    _ => value(*a),
                },
                Node::Add(c) => c.iter().map(|i| vals[i.0 as usize]).sum(),
                Node::Mul(c) => c.iter().map(|i| vals[i.0 as usize]).product(),
                Node::Neg(i) => -vals[i.0 as usize],
                Node::Pow(i, e) => vals[i.0 as usize].powi(*e),
            };
            vals.push(v);
        }
        vals.pop().unwrap_or(0.0)
    }

    fn same_tree(&self, a: Id, other: &Expr, b: Id) -> bool {
        match (self.node(a), other.node(b)) {
            (Node::Num(x), Node::Num(y)) => x == y,
            (Node::Atom(x), Node::Atom(y)) => x == y,
            (Node::Add(x), Node::Add(y)) | (Node::Mul(x), Node::Mul(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(i, j)| self.same_tree(*i, other, *j))
            }
            (Node::Neg(x), Node::Neg(y)) => self.same_tree(*x, other, *y),
            (Node::Pow(x, e), Node::Pow(y, f)) => e == f && self.same_tree(*x, other, *y),
            _ => false,
        }
    }
}

/// Two expressions are equal when their trees have the same shape and
/// leaves (node numbering and sharing do not matter).
impl PartialEq for Expr {
    fn eq(&self, other: &Expr) -> bool {
        !self.is_empty() && !other.is_empty() && self.same_tree(self.root(), other, other.root())
    }
}
