//! The sum inside a group's bracket (the group itself is `bracket.rs`'s):
//! terms that share their time-dependent part gathered over a bracket of
//! constants, a coefficient shared by constants (`a (A_x − B_x)`), like
//! terms over a bracket of sines and cosines, and every other term's node,
//! in bracket order with the sign in front when every term is negative.

use std::borrow::Cow;
use std::cmp::Reverse;
use std::collections::BTreeMap;

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::bracket::{group_node, ratio_term, scaled};
use super::order::{conventional, leading_constant};
use super::timed::{self, Classes};
use super::{Context, PLAIN_ABOVE};
use crate::atom::{Atom, AtomKind};
use crate::expr::{Expr, Id, Node, PrintTerm};
use crate::poly::Monomial;
use crate::rational::Rational;

/// The bracket of a group with more than one term (`terms` divided by
/// `common` and times `inv`, the reciprocal of the content): terms that
/// share their time-dependent part (the same rates, sin and cos) and
/// differ in constants are one term of that part with a bracket of
/// constants, ((I_2 − A_3) ω_3 − h) ω_2/I_1; the others each a term. The
/// node of the sum, and whether its sign went in front of the bracket.
pub(super) fn bracket_sum(
    e: &mut Expr,
    terms: &[PrintTerm<'_>],
    common: &Monomial,
    inv: &Rational,
    distribute: bool,
    cx: &Context<'_>,
    ratios: bool,
) -> (Id, bool) {
    let order = &cx.pres.constant_order[..];
    let plain = common.is_one() && inv.is_one();
    // Terms that share their time-dependent part (the same rates, sin
    // and cos) and differ in constants are one term of that part with
    // a bracket of constants: ((I_2 − A_3) ω_3 − h) ω_2/I_1.
    // (A large bracket is plain, see PLAIN_ABOVE: no shared parts,
    // and its atom powers are stored once in the tree.)
    let big = terms.len() > PLAIN_ABOVE;
    let parts: Vec<(Cow<'_, Monomial>, Rational)> = terms
        .iter()
        .map(|(_, m, c)| {
            if plain {
                (Cow::Borrowed(*m), (*c).clone())
            } else {
                (Cow::Owned(m.div(common)), scaled(c, inv))
            }
        })
        .collect();
    // Parts that are products of sines and cosines only (the bracket of
    // like terms, I′ φ̇ (1 + cos² θ)) are each their own time-dependent
    // part: distinct, so none is shared; none is a term of constants, so
    // none shares a coefficient; nothing is left once sin and cos are
    // out, so none is a like term. No maps are built for them.
    let simple = big
        || parts
            .iter()
            .all(|(m, _)| m.factors().iter().all(|f| cx.ranks.is_trig(f.0)));
    // The part that follows a bracket (rates, sin and cos, constant
    // rates named by Greek letters: J s + (C − A) Ω), as a class of the
    // parts that share it (present/timed.rs; none when `simple`).
    let lead = |a: Atom| cx.ranks.leads(a);
    let classes = if simple {
        Classes::none()
    } else {
        Classes::of(&parts, &lead)
    };
    // Most parts share with none: only the parts of a time-dependent part
    // shared by two or more are divided and kept, under that part (built
    // once, from the first of them).
    let mut slot: Vec<u32> = vec![timed::NONE; classes.size.len()];
    let mut shared: Vec<(Monomial, Vec<(Monomial, Rational)>)> = Vec::new();
    for (k, (m, c)) in parts.iter().enumerate() {
        if k < classes.of.len() && classes.shared(k) {
            let class = classes.of[k] as usize;
            let (t, rest) = timed::split(m, &lead);
            if slot[class] == timed::NONE {
                slot[class] = shared.len() as u32;
                shared.push((t, Vec::new()));
            }
            shared[slot[class] as usize].1.push((rest, c.clone()));
        }
    }
    // A coefficient shared by constants (a A_x − a B_x): one term,
    // a (A_x − B_x); the first of them stands for all.
    let linear = if simple {
        Vec::new()
    } else {
        let unknowns = &cx.pres.unknowns[..];
        // Whether each part is a term of constants, or of unknowns to the
        // first power that no other part shares.
        let constants_and_unknowns: Vec<bool> = parts
            .iter()
            .enumerate()
            .map(|(k, (m, _))| {
                classes.of[k] == timed::NONE
                    || (!unknowns.is_empty()
                        && !classes.shared(k)
                        && m.factors()
                            .iter()
                            .filter(|f| !lead(f.0))
                            .all(|&(a, x)| x == 1 && unknowns.contains(&a)))
            })
            .collect();
        linear_groups(&parts, &constants_and_unknowns, unknowns)
    };
    let mut linear_of: Vec<Option<(usize, bool)>> = vec![None; classes.of.len()];
    for (g, (_, members)) in linear.iter().enumerate() {
        for (j, f) in members.iter().enumerate() {
            linear_of[f.0] = Some((g, j == 0));
        }
    }
    // Like terms: terms with the same constants and rates that differ
    // only in sin and cos are one term with a bracket of those,
    // I′ φ̇ (1 + cos² θ), not I′ φ̇ + I′ φ̇ cos² θ.
    // (Parts are distinct, so without a sine or cosine in any of them no
    // two share what is left once sin and cos are taken out.)
    // (Each part is split once; only the rests of two parts or more are
    // kept, with the sin and cos of each.)
    let mut alike: FxHashMap<Monomial, Vec<(Monomial, Rational)>> = FxHashMap::default();
    let mut alike_of: Vec<Option<Monomial>> = vec![None; classes.of.len()];
    let any_trig = !simple
        && parts
            .iter()
            .any(|(m, _)| m.factors().iter().any(|f| cx.ranks.is_trig(f.0)));
    if any_trig {
        let mut splits: Vec<Option<(Monomial, Monomial)>> = Vec::with_capacity(parts.len());
        for (k, (m, _)) in parts.iter().enumerate() {
            let split = if classes.shared(k) || linear_of[k].is_some() {
                None
            } else {
                Some(m.split(|a| cx.ranks.is_trig(a))).filter(|(_, rest)| !rest.is_one())
            };
            splits.push(split);
        }
        let mut count: FxHashMap<&Monomial, u32> = FxHashMap::default();
        for (_, rest) in splits.iter().flatten() {
            *count.entry(rest).or_default() += 1;
        }
        let several: Vec<bool> = splits
            .iter()
            .map(|s| s.as_ref().is_some_and(|(_, rest)| count[rest] > 1))
            .collect();
        drop(count);
        for (k, (split, (_, c))) in splits.into_iter().zip(&parts).enumerate() {
            if let (true, Some((trig, rest))) = (several[k], split) {
                alike
                    .entry(rest.clone())
                    .or_default()
                    .push((trig, c.clone()));
                alike_of[k] = Some(rest);
            }
        }
    }
    // Dividing by `common` keeps the print order of a term's other factors
    // unless it takes away a sine, next to which its cosine was placed (a
    // positive power of `common` is in every term; a negative one, a
    // divisor of some terms only, would add a factor to the others).
    let common_keeps_order = common
        .factors()
        .iter()
        .all(|f| f.1 > 0 && !matches!(f.0.kind(), AtomKind::Sin(_)));
    let mut atoms: FxHashMap<(Atom, i32), Id> = FxHashMap::default();
    // (node, negative, highest derivative order, has a part that
    // follows a bracket)
    let mut nodes: Vec<(Id, bool, u32, bool)> = Vec::with_capacity(terms.len());
    for (k, ((factors, term, _), (m, c))) in terms.iter().zip(&parts).enumerate() {
        // (Found only for a term that is written: most parts of a large
        // bracket stand in a shared one.)
        let top = || cx.ranks.top(m);
        let follows = match classes.of.get(k) {
            None => m.factors().iter().any(|&(a, _)| !leading_constant(a)),
            Some(&class) => {
                if let Some((g, first)) = linear_of[k] {
                    if first {
                        let (x, members) = &linear[g];
                        let sub: Vec<(Monomial, Rational)> = members
                            .iter()
                            .map(|(_, u, c)| (u.clone(), c.clone()))
                            .collect();
                        let id = group_node(e, x, &sub, cx, ratios);
                        nodes.push((id, matches!(e.node(id), Node::Neg(_)), top(), false));
                    }
                    continue;
                }
                if let Some(rest) = &alike_of[k]
                    && let Some(sub) = alike.get_mut(rest)
                {
                    // The first of the like terms stands for all of them.
                    if !sub.is_empty() {
                        let sub = std::mem::take(sub);
                        let id = group_node(e, rest, &sub, cx, ratios);
                        let follows = rest.factors().iter().any(|&(a, _)| !leading_constant(a));
                        nodes.push((id, matches!(e.node(id), Node::Neg(_)), top(), follows));
                    }
                    continue;
                }
                if classes.shared(k) {
                    // The first term of the shared part stands for all of them.
                    let (t, sub) = &mut shared[slot[class as usize] as usize];
                    if !sub.is_empty() {
                        let sub = std::mem::take(sub);
                        let id = group_node(e, t, &sub, cx, ratios);
                        nodes.push((id, matches!(e.node(id), Node::Neg(_)), top(), true));
                    }
                    continue;
                }
                class != timed::NONE
            }
        };
        // The term's factors in print order: sorted with the order when the
        // bracket is plain (PLAIN_ABOVE), found here otherwise.
        let in_order = || -> SmallVec<[(Atom, i32); 16]> {
            if factors.is_empty() {
                cx.ranks.print.sorted(term).into_iter().collect()
            } else {
                factors.iter().copied().collect()
            }
        };
        let mut f: SmallVec<[(Atom, i32); 16]> = if plain {
            in_order()
        } else if common_keeps_order {
            quotient_in_order(&in_order(), common)
        } else {
            cx.ranks.print.sorted(m).into_iter().collect()
        };
        debug_assert!(f.iter().eq(cx.ranks.print.sorted(m).iter()));
        conventional(&mut f, order, &cx.ranks);
        let id = if distribute {
            ratio_term(e, &f, c)
        } else if big {
            shared_term_node(e, &f, c, &mut atoms)
        } else {
            e.term_node(&f, c)
        };
        nodes.push((id, c.is_negative(), top(), follows));
    }
    sum_of_nodes(e, nodes)
}

/// The sum of a bracket's term nodes, each as (node, negative, highest
/// derivative order, has a part that follows a bracket), in bracket
/// order; and whether its sign went in front of the bracket.
pub(super) fn sum_of_nodes(e: &mut Expr, mut nodes: Vec<(Id, bool, u32, bool)>) -> (Id, bool) {
    let mut negative = false;
    // Grouping may leave every term negative (−J s − (C − A) Ω): the
    // sign goes in front of the bracket, −(J s + (C − A) Ω) (rule 4),
    // the terms in bracket order.
    if nodes.iter().all(|n| n.1) {
        for n in &mut nodes {
            if let Node::Neg(x) = e.node(n.0) {
                n.0 = *x;
                n.1 = false;
            }
        }
        negative = true;
        nodes.sort_by_key(|n| (Reverse(n.2), n.3));
    }
    // The bracket leads with a positive term of its leading order.
    if nodes[0].1
        && let Some(k) = nodes.iter().position(|n| !n.1 && n.2 == nodes[0].2)
    {
        let n = nodes.remove(k);
        nodes.insert(0, n);
    }
    (e.add(nodes.into_iter().map(|n| n.0).collect()), negative)
}

/// Terms of constants only that differ in one constant, to the first
/// power, and share the rest (`a A_x − a B_x`, a coefficient and the
/// unknowns it multiplies): each group as (what they share, [(term's
/// index, its constant, its coefficient)]), so that the group prints as
/// one term, a (A_x − B_x). The unknowns the file solves for count as
/// constants here whether it declares them constants or functions of time
/// (a shaft's reactions A_x(t), B_x(t)): a term whose time-dependent part
/// is unknowns to the first power, and no other term's (`shared`, a
/// bracket of constants over that part), is grouped as a term of
/// constants is. A term can be split in several ways; the largest groups
/// are taken first, each term in one group at most, ties broken by the
/// shared part's order (the result depends only on the terms). Linear in
/// the terms times their factors, and a sort of the candidate groups.
#[allow(clippy::type_complexity)]
fn linear_groups(
    parts: &[(Cow<'_, Monomial>, Rational)],
    constants_and_unknowns: &[bool],
    unknowns: &[Atom],
) -> Vec<(Monomial, Vec<(usize, Monomial, Rational)>)> {
    let unknown = |a: Atom| unknowns.contains(&a);
    let mut by_rest: BTreeMap<Monomial, Vec<(usize, Monomial, Rational)>> = BTreeMap::new();
    for (k, ((m, c), &candidate)) in parts.iter().zip(constants_and_unknowns).enumerate() {
        if !candidate || m.factors().len() < 2 {
            continue;
        }
        for &(u, x) in m.factors() {
            if x == 1 && (leading_constant(u) || unknown(u)) {
                let u = Monomial::atom(u, 1);
                by_rest
                    .entry(m.div(&u))
                    .or_default()
                    .push((k, u, c.clone()));
            }
        }
    }
    let mut candidates: Vec<(Monomial, Vec<(usize, Monomial, Rational)>)> =
        by_rest.into_iter().filter(|g| g.1.len() > 1).collect();
    // Ties by the shared part's factors in print order (names, never the
    // atoms' ids, which depend on what was interned first).
    candidates.sort_by_cached_key(|g| {
        let shared: Vec<_> =
            g.0.sorted_for_print()
                .into_iter()
                .map(|(a, x)| (a.sort_key(), x))
                .collect();
        (Reverse(g.1.len()), shared)
    });
    let mut taken = vec![false; parts.len()];
    let mut groups = Vec::new();
    for (rest, members) in candidates {
        let free: Vec<_> = members.into_iter().filter(|f| !taken[f.0]).collect();
        if free.len() > 1 {
            for f in &free {
                taken[f.0] = true;
            }
            groups.push((rest, free));
        }
    }
    groups
}

/// The factors of `term / common` in print order, given the term's
/// factors in print order (`sorted`) and a `common` divisor of it of
/// positive powers and without a sine: the same factors with `common`'s exponents taken off, those left
/// at zero dropped (print order is by atom, and a cosine follows the sine
/// of its angle, neither of which a division without a sine changes).
pub(super) fn quotient_in_order(
    sorted: &[(Atom, i32)],
    common: &Monomial,
) -> SmallVec<[(Atom, i32); 16]> {
    sorted
        .iter()
        .filter_map(|&(a, x)| {
            let y = x - common.exponent(a);
            (y != 0).then_some((a, y))
        })
        .collect()
}

/// A sine or a cosine.
pub(super) fn is_trig(a: Atom) -> bool {
    matches!(a.kind(), AtomKind::Sin(_) | AtomKind::Cos(_))
}

/// `c · factors` as [`Expr::term_node`] writes it, with each atom power
/// stored once in the tree and shared by the terms that have it (`atoms`
/// remembers their nodes): a plain bracket of 40,000 terms costs three
/// nodes a term, not fifteen. Printing and expanding read a shared node as
/// they read a copy.
pub(super) fn shared_term_node(
    e: &mut Expr,
    factors: &[(Atom, i32)],
    c: &Rational,
    atoms: &mut FxHashMap<(Atom, i32), Id>,
) -> Id {
    let mut ids = Vec::with_capacity(factors.len() + 1);
    let mag = c.abs();
    if !mag.is_one() || factors.is_empty() {
        ids.push(e.push(Node::Num(mag)));
    }
    for &(a, x) in factors {
        ids.push(*atoms.entry((a, x)).or_insert_with(|| e.atom_pow(a, x)));
    }
    let m = e.mul(ids);
    if c.is_negative() {
        e.push(Node::Neg(m))
    } else {
        m
    }
}

/// What every term of a bracket has ([`common_factor`]) when the bracket
/// may take a direct path (`constants.rs`, `trig.rs`): 2 to
/// [`PLAIN_ABOVE`] terms, no known factors asked for, and every factor of
/// every term a positive power of an atom `of_kind` accepts; `None`
/// otherwise.
pub(super) fn direct_common(
    terms: &[(Monomial, Rational)],
    cx: &Context<'_>,
    of_kind: impl Fn(Atom) -> bool,
) -> Option<Monomial> {
    if terms.len() < 2 || terms.len() > PLAIN_ABOVE || !cx.pres.factors.is_empty() {
        return None;
    }
    let all = terms
        .iter()
        .all(|(m, _)| m.factors().iter().all(|&(a, x)| x > 0 && of_kind(a)));
    all.then(|| common_factor(terms))
}

/// What every term of a bracket has: the gcd of its monomials (`terms` not
/// empty), stopping once it is 1.
pub(super) fn common_factor(terms: &[(Monomial, Rational)]) -> Monomial {
    let mut common = terms[0].0.clone();
    for t in &terms[1..] {
        if common.is_one() {
            break;
        }
        common = common.gcd(&t.0);
    }
    common
}
