//! Presentation: turning a canonical polynomial into the textbook's form.
//!
//! Three steps, all exact (the presented tree expands back to the input):
//!
//! 1. **Fold abbreviations.** For ω_z := ψ̇ + φ̇ cos θ, an atom of the
//!    definition that occurs linearly with a constant coefficient (ψ̇) is
//!    eliminated: ψ̇ := ω_z − φ̇ cos θ, and its derivatives likewise
//!    (ψ̈ := ω̇_z + φ̇ θ̇ sin θ − φ̈ cos θ).
//! 2. **Collect** the terms by a chosen list of atoms (the kinematic ones,
//!    ω, ω̇, or the inertia ones, I, I′): each group's coefficient is
//!    factored (rational content, common monomial, and the sign pulled out
//!    only when that leaves fewer negative terms inside and the bracket does
//!    not mix kinds of terms of opposite signs) and printed as
//!    `[number] [constant symbols] [bracket] [rates, sin and cos]` (sin and
//!    cos follow the bracket even of a constant angle). A bracket whose
//!    terms have different constant divisors (a solved form) is not put
//!    over one divisor: each term keeps its own ratio, `(m g l/I′) sin θ`.
//!    Inside a bracket, terms with the same rates (and sin, cos) are one
//!    term with a bracket of constants, ((I_2 − A_3) ω_3 − h) ω_2/I_1;
//!    terms with the same constants and rates that differ in sin and cos
//!    are one term, I′ φ̇ (1 + cos² θ); constants sharing a coefficient
//!    are one term, a (A_x − B_x); what the collect list leaves over is
//!    grouped the same way and written as terms of the sum, not as one
//!    more bracket. Whether divisors go term by term is decided once for
//!    the whole result: every term divided by constants then carries its
//!    ratio in front, alone or in a bracket (one rule for a ratio).
//! 3. **Factor by known factors** (a step's `factor` list, such as A − B
//!    and A − C): a bracket equal to their product, or to one of them,
//!    times a monomial and a number is printed as that product; the
//!    product is checked by canonical equality, never assumed.
//!
//! Where each part lives: this file the whole (fold, group by the collect
//! list, order the groups, split fractions by content); `present/fold.rs`
//! rule 1; `present/bracket.rs` one group with its bracket
//! (`present/gather.rs` the sum inside the bracket;
//! `present/constants.rs` a bracket of constants, directly;
//! `present/trig.rs` a bracket of sines and cosines, directly;
//! `present/timed.rs` its parts classed by their time-dependent part);
//! `present/known.rs` rule 3; `present/order.rs` the order of factors;
//! `present/sin_squares.rs` the choice of sin² θ or 1 − cos² θ.
//!
//! Groups are ordered by the position of their atoms in the collect list;
//! terms inside a bracket by highest derivative first, then terms of
//! constants only (J + I′ sin² θ), then by name. The
//! order depends only on names, never on interning order.
//!
//! # Example
//! ```
//! use hdot_sym::{present::{present, Presentation}, print, Atom, Symbols};
//! let s = Symbols::parse_decl(&["I_x", "I_y", "I_z"], &["omega_x", "omega_y", "omega_z"]);
//! let p = s.poly("I_x*omega_x' - I_y*omega_y*omega_z + I_z*omega_z*omega_y").unwrap();
//! let keys = ["omega_x", "omega_y", "omega_z"].iter()
//!     .flat_map(|n| [Atom::time(n, 1), Atom::time(n, 0)]).collect();
//! let e = present(&p, &Presentation { collect: keys, ..Default::default() });
//! assert_eq!(print::unicode(&e), "I_x ω̇_x − (I_y − I_z) ω_y ω_z");
//! assert_eq!(e.to_poly(), p);
//! ```

use std::cmp::Reverse;
use std::collections::BTreeMap;

use crate::atom::{Atom, AtomKind};
use crate::expr::{Expr, Id, Node, PrintRanks};
use crate::poly::{Monomial, Poly};
use crate::rational::Rational;

mod bracket;
mod constants;
mod fold;
mod gather;
mod known;
mod order;
mod sin_squares;
mod timed;
mod trig;
use bracket::group_node;
pub use fold::fold;
use order::{Ranks, leading_constant};
use sin_squares::merge_trig_squares;

/// A group (a bracket, or the whole sum) of more terms than this is
/// presented plainly: each term as the canonical form holds it (sin² θ as
/// 1 − cos² θ), no terms gathered under a shared bracket of constants. The
/// rules that choose sin² θ and shared brackets cost several times the
/// algebra per term; above this size (chain-7's Ḣ, 14,072 terms per
/// component) nobody reads the result term by term, and the display must
/// not cost more than the algebra that made it. Still exact: a plain form
/// expands to the same value.
pub const PLAIN_ABOVE: usize = 10_000;

/// How a result should be shown.
#[derive(Clone, Debug, Default)]
pub struct Presentation {
    /// Atoms to collect by, in the order the groups should appear.
    pub collect: Vec<Atom>,
    /// Abbreviations to fold back in: the abbreviation's atom and its definition.
    pub fold: Vec<(Atom, Poly)>,
    /// Known factors, such as `A − B` and `A − C`: a bracket that equals their
    /// product (or one of them) times a monomial is printed as that product.
    pub factors: Vec<Poly>,
    /// Each known factor as written in the file (`J s + (C − A) Ω`), in the
    /// order of `factors`: a bracket printed as a known factor is printed
    /// as written. Empty, or an entry that is not a plain formula (an
    /// empty tree), leaves that factor in the default presentation.
    pub factor_forms: Vec<Expr>,
    /// The file's order of constant factors (`[symbols] order`): the names
    /// listed come first, in this order, before the conventional one.
    pub constant_order: Vec<String>,
    /// Unknowns (what the file solves for): the terms of the sum that hold
    /// one come first, in their order otherwise, a (A_x − B_x) + … = 0.
    pub unknowns: Vec<Atom>,
}

/// What the parts of one presentation share: the request, and the ranks
/// of the result's atoms (found once, read by every bracket).
struct Context<'p> {
    pres: &'p Presentation,
    ranks: Ranks,
}

/// Presents `p` in textbook form (see the module doc).
pub fn present(p: &Poly, pres: &Presentation) -> Expr {
    // Folded only when there is something to fold: no copy of the result
    // otherwise.
    let mut folded: Option<Poly> = None;
    for (name, def) in &pres.fold {
        folded = Some(fold(folded.as_ref().unwrap_or(p), *name, def));
    }
    let p = folded.as_ref().unwrap_or(p);
    let rank = |a: Atom| pres.collect.iter().position(|k| *k == a);
    // Group by the collected part of each monomial. The rests of a group
    // are distinct (key · rest is the term's monomial), so a group is a
    // list of terms; `group_node` puts them in print order.
    let mut groups: Vec<(Monomial, Vec<(Monomial, Rational)>)> = if pres.collect.is_empty() {
        vec![(Monomial::one(), p.terms().to_vec())]
    } else {
        let mut map: BTreeMap<Monomial, Vec<(Monomial, Rational)>> = BTreeMap::new();
        for (m, c) in p.terms() {
            let (key, rest) = m.split(|a| rank(a).is_some());
            map.entry(key).or_default().push((rest, c.clone()));
        }
        map.into_iter().collect()
    };
    let group_key = |k: &Monomial| {
        let mut pos: Vec<(usize, Reverse<i32>)> = k
            .factors()
            .iter()
            .map(|&(a, e)| (rank(a).expect("collected"), Reverse(e)))
            .collect();
        pos.sort();
        (k.is_one(), pos)
    };
    groups.sort_by_key(|g| group_key(&g.0));

    for (_, ts) in &mut groups {
        if ts.len() <= PLAIN_ABOVE {
            merge_trig_squares(ts);
        }
    }
    groups.retain(|(_, ts)| !ts.is_empty());
    // Every bracket below is a quotient of these terms: its atoms are
    // among theirs.
    let monomials = groups
        .iter()
        .flat_map(|(k, ts)| std::iter::once(k).chain(ts.iter().map(|t| &t.0)));
    let cx = Context {
        pres,
        ranks: Ranks::of(monomials, &pres.constant_order),
    };
    // One rule for a constant ratio: when the result is a solved form whose
    // constant divisors go term by term (some terms divided by constants,
    // others not), every such term carries its ratio in front, whichever
    // group or bracket it is printed in.
    let ratios = bracket::distributes_over(p.terms().iter().map(|t| &t.0));
    let mut e = Expr::new();
    let several = groups.len() > 1;
    let mut ids: Vec<Id> = Vec::new();
    for (k, ts) in &groups {
        if several && k.is_one() {
            // What `collect` left over is not one bracket among the groups:
            // its terms are grouped by their rates (and sin, cos), each with
            // its own constants, A_3 ω̇_3 + ḣ − (I_1 − I_2) ω_1 ω_2.
            for (t, rest) in by_time_part(ts, &cx.ranks.print) {
                ids.push(group_node(&mut e, &t, &rest, &cx, ratios));
            }
        } else if let Some(classes) = split_by_content(ts) {
            // ½ (I′ θ̇² + …) − m g l cos θ: a fraction is pulled out only
            // over the terms that carry it; inside a collected group's
            // bracket too, ((J − I′) Ω² + (1/2) m g L) ε.
            let parts = content_parts(&mut e, &classes, &cx, ratios);
            if k.is_one() {
                ids.extend(parts);
            } else {
                let mut factors = vec![e.add(parts)];
                for (a, x) in cx.ranks.print.sorted(k) {
                    factors.push(e.atom_pow(a, x));
                }
                ids.push(e.mul(factors));
            }
        } else {
            ids.push(group_node(&mut e, k, ts, &cx, ratios));
        }
    }
    if ids.len() > 1 {
        ids = splice_sums(&mut e, ids);
        if !pres.unknowns.is_empty() {
            ids = unknowns_first(&e, ids, &pres.unknowns);
        }
    }
    e.add(ids);
    e.shrink_to_fit();
    crate::work::presented(e.len());
    e
}

/// The terms `ids` with those holding one of `unknowns` first, in their
/// own order, then the others from the lowest degree in the rates up
/// ([`order::knowns_by_degree`]).
fn unknowns_first(e: &Expr, ids: Vec<Id>, unknowns: &[Atom]) -> Vec<Id> {
    fn holds(e: &Expr, id: Id, unknowns: &[Atom]) -> bool {
        match e.node(id) {
            Node::Num(_) => false,
            Node::Atom(a) => unknowns.contains(a),
            Node::Add(ts) | Node::Mul(ts) => ts.iter().any(|&t| holds(e, t, unknowns)),
            Node::Neg(x) | Node::Pow(x, _) => holds(e, *x, unknowns),
        }
    }
    let (mut first, mut rest): (Vec<Id>, Vec<Id>) =
        ids.into_iter().partition(|&id| holds(e, id, unknowns));
    if !first.is_empty() {
        order::knowns_by_degree(e, &mut rest);
    }
    first.extend(rest);
    first
}

/// The terms grouped by their time-dependent part (rates, sin and cos of
/// time-dependent angles), each group as (that part, the terms divided by
/// it), in the order of terms inside a bracket: highest derivative first,
/// then the terms of constants only, then by name.
fn by_time_part(
    ts: &[(Monomial, Rational)],
    ranks: &PrintRanks,
) -> Vec<(Monomial, Vec<(Monomial, Rational)>)> {
    let mut map: BTreeMap<Monomial, Vec<(Monomial, Rational)>> = BTreeMap::new();
    for (m, c) in ts {
        let (t, rest) = m.split(|a| a.is_time_dependent());
        map.entry(t).or_default().push((rest, c.clone()));
    }
    let keys: Vec<(Monomial, Rational)> = map.keys().map(|k| (k.clone(), Rational::ONE)).collect();
    let mut sorted = ranks.sort(&keys, true);
    sorted.sort_by_key(|t| {
        let top = t.1.factors().iter().map(|f| f.0.order()).max();
        (Reverse(top.unwrap_or(0)), !t.1.is_one())
    });
    let order: Vec<Monomial> = sorted.into_iter().map(|t| t.1.clone()).collect();
    order
        .into_iter()
        .map(|k| {
            let v = map.remove(&k).expect("a key of the map");
            (k, v)
        })
        .collect()
}

/// A sum whose rational content is a fraction, split so that the fraction
/// is pulled out only over the terms that carry it: the terms are classed
/// by their degree in the rates (time-dependent symbols and constant rates
/// named by Greek letters; sin and cos do not count), the terms of degree
/// 0 also by whether their coefficient is whole, classes of the same
/// content are merged, highest degree first. So an energy keeps
/// ½ (I′ θ̇² + …) and its potential − m g l cos θ apart, and
/// I′ θ̈ − (I′ − J) Ω² sin θ cos θ + ½ m g L sin θ keeps its integer terms
/// whole. `None` when the content is an integer or one class remains.
fn split_by_content(ts: &[(Monomial, Rational)]) -> Option<Vec<Vec<(Monomial, Rational)>>> {
    let content = ts.iter().fold(Rational::ZERO, |g, t| g.gcd(&t.1));
    if content.is_zero() || content.is_integer() {
        return None;
    }
    let degree = |m: &Monomial| -> i32 {
        m.factors()
            .iter()
            .filter(|(a, _)| matches!(a.kind(), AtomKind::Var { .. }) && !leading_constant(*a))
            .map(|(_, e)| *e)
            .sum()
    };
    // Terms without rates are classed by whether their coefficient is
    // whole too: a half is never pulled over a bracket of doubles,
    // a (A_x − B_x) + (1/2) m g L sin β, not (1/2) (2 a (A_x − B_x) + …).
    type Class = (Reverse<i32>, bool);
    let mut by_degree: BTreeMap<Class, Vec<(Monomial, Rational)>> = BTreeMap::new();
    for t in ts {
        let d = degree(&t.0);
        by_degree
            .entry((Reverse(d), d == 0 && t.1.is_integer()))
            .or_default()
            .push(t.clone());
    }
    let mut classes: Vec<(Rational, Vec<(Monomial, Rational)>)> = Vec::new();
    for (_, class) in by_degree {
        let c = class.iter().fold(Rational::ZERO, |g, t| g.gcd(&t.1));
        match classes.iter_mut().find(|k| k.0 == c) {
            Some(k) => k.1.extend(class),
            None => classes.push((c, class)),
        }
    }
    (classes.len() > 1).then(|| classes.into_iter().map(|k| k.1).collect())
}

/// The classes of [`split_by_content`] as the terms of one sum, leading
/// with a positive part: g − (2/3) L Ω² cos θ.
fn content_parts(
    e: &mut Expr,
    classes: &[Vec<(Monomial, Rational)>],
    cx: &Context<'_>,
    ratios: bool,
) -> Vec<Id> {
    let parts: Vec<Id> = classes
        .iter()
        .map(|class| group_node(e, &Monomial::one(), class, cx, ratios))
        .collect();
    let mut parts = splice_sums(e, parts);
    let negative = |e: &Expr, id: Id| matches!(e.node(id), Node::Neg(_));
    if negative(e, parts[0])
        && let Some(p) = parts.iter().position(|&id| !negative(e, id))
    {
        let first = parts.remove(p);
        parts.insert(0, first);
    }
    parts
}

/// The terms of a sum with every bare bracket among them opened: a sum
/// inside a sum, or its negation, is written as its terms.
fn splice_sums(e: &mut Expr, ids: Vec<Id>) -> Vec<Id> {
    let mut out = Vec::with_capacity(ids.len());
    for id in ids {
        match e.node(id).clone() {
            Node::Add(ts) => out.extend(ts),
            Node::Neg(inner) => match e.node(inner).clone() {
                Node::Add(ts) => {
                    for t in ts {
                        let n = match e.node(t) {
                            Node::Neg(x) => *x,
                            _ => e.push(Node::Neg(t)),
                        };
                        out.push(n);
                    }
                }
                _ => out.push(id),
            },
            _ => out.push(id),
        }
    }
    out
}

/// Term order inside a sum: highest derivative first, then by names.
#[cfg(test)]
fn term_order(a: &[(Atom, i32)], b: &[(Atom, i32)]) -> std::cmp::Ordering {
    let top = |f: &[(Atom, i32)]| f.iter().map(|x| x.0.order()).max().unwrap_or(0);
    top(b)
        .cmp(&top(a))
        .then_with(|| crate::expr::print_order(a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The integer keys of `print_sorted` order the terms exactly as the
    /// name-based `term_order` (and, without the derivative key, as
    /// `print_order`), on chain-3's Ḣ (295 terms: rates of orders
    /// 1 and 2, sines and cosines, powers) and a hand-made mix with
    /// negative exponents.
    #[test]
    fn print_sorted_agrees_with_the_name_orders() {
        let d = crate::chain::derivation(3).expect("chain-3 derives");
        let mut polys: Vec<Poly> = d
            .steps
            .iter()
            .flat_map(|s| s.values().into_iter().cloned())
            .collect();
        let s = crate::Symbols::parse_decl(&["A", "B", "m"], &["theta", "phi", "psi"]);
        polys.push(
            s.poly("A*theta''*phi' - B^2*psi'/m + theta'^2*sin(phi)*cos(psi) - 3*cos(theta)^2/A")
                .unwrap(),
        );
        let mut checked = 0;
        for p in &polys {
            let fast: Vec<(Vec<(Atom, i32)>, Monomial)> =
                crate::expr::print_sorted(p.terms(), true)
                    .into_iter()
                    .map(|t| (t.0.to_vec(), t.1.clone()))
                    .collect();
            let mut slow: Vec<(Vec<(Atom, i32)>, Monomial)> = p
                .terms()
                .iter()
                .map(|(m, _)| (m.sorted_for_print(), m.clone()))
                .collect();
            let mut by_names = slow.clone();
            by_names.sort_by(|a, b| crate::expr::print_order(&a.0, &b.0));
            let fast_by_names: Vec<(Vec<(Atom, i32)>, Monomial)> =
                crate::expr::print_sorted(p.terms(), false)
                    .into_iter()
                    .map(|t| (t.0.to_vec(), t.1.clone()))
                    .collect();
            assert_eq!(fast_by_names, by_names);
            slow.sort_by(|a, b| term_order(&a.0, &b.0));
            assert_eq!(fast, slow);
            checked += p.len();
        }
        assert!(checked > 295, "only {checked} terms compared");
    }
}
