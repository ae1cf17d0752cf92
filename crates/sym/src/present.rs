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
//!    term with a bracket of constants, ((I_2 − A_3) ω_3 − h) ω_2/I_1; what
//!    the collect list leaves over is grouped the same way and written as
//!    terms of the sum, not as one more bracket.
//! 3. **Factor by known factors** (a step's `factor` list, such as A − B
//!    and A − C): a bracket equal to their product, or to one of them,
//!    times a monomial and a number is printed as that product; the
//!    product is checked by canonical equality, never assumed.
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

use std::borrow::Cow;
use std::cmp::Reverse;
use std::collections::BTreeMap;

use crate::atom::{Atom, AtomKind};
use crate::expr::{Expr, Id, Node, print_sorted};
use crate::poly::{Monomial, Poly};
use crate::rational::Rational;
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

mod sin_squares;
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
}

/// Folds the abbreviation `name := def` into `p`: of the atoms of `def`
/// that can be eliminated (h := J (v + β̇) may give β̇ := h/J − v or
/// v := h/J − β̇), the one that leaves the fewest terms. Returns `p`
/// unchanged when no atom can be eliminated or every fold would leave more
/// terms than `p` has: folding w := ψ̇ + a cos θ into a linearised
/// b (ψ̇ + a) θ would bring back cos θ (b (w − a cos θ + a) θ), which reads
/// as a term of higher order. Exact: the result equals `p` once `name` is
/// replaced by `def`.
pub fn fold(p: &Poly, name: Atom, def: &Poly) -> Poly {
    let mut best: Option<Poly> = None;
    for (v, coef, c) in eliminable(def) {
        // v = (name − (def − c coef v)) / (c coef)
        let rest = def - &Poly::term(coef.mul(&Monomial::atom(v, 1)), c.clone());
        let inv = Poly::term(
            Monomial::one().div(&coef),
            c.recip().expect("non-zero coefficient"),
        );
        let v_expr = &(&Poly::atom(name) - &rest) * &inv;
        let q = p.subst(&mut |a| match a.kind() {
            AtomKind::Var {
                time: true, order, ..
            } if a.base() == v.base() && order >= v.order() => Some(v_expr.dt_n(order - v.order())),
            _ => None,
        });
        if q.len() <= p.len() && best.as_ref().is_none_or(|b| q.len() < b.len()) {
            best = Some(q);
        }
    }
    best.unwrap_or_else(|| p.clone())
}

/// The atoms of `def` that occur in exactly one term, to the first power,
/// times constants only, and whose base symbol occurs nowhere else; the
/// highest derivative first.
fn eliminable(def: &Poly) -> Vec<(Atom, Monomial, Rational)> {
    let mut found = Vec::new();
    for (m, c) in def.terms() {
        let (timed, coef) = m.split(|a| a.is_time_dependent());
        let [(v, 1)] = timed.factors() else { continue };
        if !matches!(v.kind(), AtomKind::Var { time: true, .. }) {
            continue;
        }
        let others = def.terms().iter().filter(|(m2, _)| m2 != m);
        let clash = others
            .flat_map(|(m2, _)| m2.factors())
            .any(|(a, _)| match a.kind() {
                AtomKind::Var { .. } => a.base() == v.base(),
                AtomKind::Sin(q) | AtomKind::Cos(q) => q == v.base(),
            });
        if !clash {
            found.push((*v, coef, c.clone()));
        }
    }
    found.sort_by_key(|f| Reverse(f.0.order()));
    found
}

/// Presents `p` in textbook form (see the module doc).
pub fn present(p: &Poly, pres: &Presentation) -> Expr {
    let mut p = p.clone();
    for (name, def) in &pres.fold {
        p = fold(&p, *name, def);
    }
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
    let mut e = Expr::new();
    let several = groups.len() > 1;
    let mut ids: Vec<Id> = Vec::new();
    for (k, ts) in &groups {
        if several && k.is_one() {
            // What `collect` left over is not one bracket among the groups:
            // its terms are grouped by their rates (and sin, cos), each with
            // its own constants, A_3 ω̇_3 + ḣ − (I_1 − I_2) ω_1 ω_2.
            for (t, rest) in by_time_part(ts) {
                ids.push(group_node(&mut e, &t, &rest, pres));
            }
        } else if let Some(classes) = split_by_content(ts) {
            // ½ (I′ θ̇² + …) − m g l cos θ: a fraction is pulled out only
            // over the terms that carry it; inside a collected group's
            // bracket too, ((J − I′) Ω² + (1/2) m g L) ε.
            let parts = content_parts(&mut e, &classes, pres);
            if k.is_one() {
                ids.extend(parts);
            } else {
                let mut factors = vec![e.add(parts)];
                for (a, x) in k.sorted_for_print() {
                    factors.push(e.atom_pow(a, x));
                }
                ids.push(e.mul(factors));
            }
        } else {
            ids.push(group_node(&mut e, k, ts, pres));
        }
    }
    if ids.len() > 1 {
        ids = splice_sums(&mut e, ids);
    }
    e.add(ids);
    e.shrink_to_fit();
    crate::work::presented(e.len());
    e
}

/// The terms grouped by their time-dependent part (rates, sin and cos of
/// time-dependent angles), each group as (that part, the terms divided by
/// it), in the order of terms inside a bracket: highest derivative first,
/// then the terms of constants only, then by name.
fn by_time_part(ts: &[(Monomial, Rational)]) -> Vec<(Monomial, Vec<(Monomial, Rational)>)> {
    let mut map: BTreeMap<Monomial, Vec<(Monomial, Rational)>> = BTreeMap::new();
    for (m, c) in ts {
        let (t, rest) = m.split(|a| a.is_time_dependent());
        map.entry(t).or_default().push((rest, c.clone()));
    }
    let keys: Vec<(Monomial, Rational)> = map.keys().map(|k| (k.clone(), Rational::ONE)).collect();
    let mut sorted = print_sorted(&keys, true);
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
/// named by Greek letters; sin and cos do not count), classes of the same
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
    let mut by_degree: BTreeMap<Reverse<i32>, Vec<(Monomial, Rational)>> = BTreeMap::new();
    for t in ts {
        by_degree
            .entry(Reverse(degree(&t.0)))
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
    pres: &Presentation,
) -> Vec<Id> {
    let parts: Vec<Id> = classes
        .iter()
        .map(|class| group_node(e, &Monomial::one(), class, pres))
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

/// `key · Σ terms` with the sum factored.
fn group_node(
    e: &mut Expr,
    key: &Monomial,
    terms: &[(Monomial, Rational)],
    pres: &Presentation,
) -> Id {
    let known = &pres.factors[..];
    let order = &pres.constant_order[..];
    let mut terms = print_sorted(terms, true);
    let distribute = distributes(&terms);
    // Highest derivative first; then terms of constants only (J + I′ sin² θ);
    // in a distributed bracket the terms that were not divided before the
    // divided ones (θ̈ = φ̇² sin θ cos θ − (I/I′) …); then by name.
    // (What every term has, as x in (J s + (C − A) Ω) x, does not count.)
    let mut all = terms
        .first()
        .map(|t| t.1.clone())
        .unwrap_or_else(Monomial::one);
    for t in &terms {
        if all.is_one() {
            break;
        }
        all = all.gcd(t.1);
    }
    terms.sort_by_cached_key(|t| {
        let top = t.1.factors().iter().map(|f| f.0.order()).max();
        // Some factor of t / all that is not a leading constant (t / all
        // is not built: the exponents are compared).
        let timed =
            t.1.factors()
                .iter()
                .any(|&(a, e)| e != all.exponent(a) && !leading_constant(a))
                || all
                    .factors()
                    .iter()
                    .any(|&(a, _)| t.1.exponent(a) == 0 && !leading_constant(a));
        (
            Reverse(top.unwrap_or(0)),
            timed,
            distribute && has_divisor(t.1),
        )
    });
    // Content: rational gcd, with the minus sign pulled out only when that
    // leaves fewer negative terms inside the bracket and the bracket does
    // not mix kinds of terms of opposite signs; otherwise the bracket leads
    // with a positive term.
    let mut content = terms.iter().fold(Rational::ZERO, |g, t| g.gcd(t.2));
    if cyclic_pair_of_constants(&terms) {
        // Rule 3 decides the sign of a difference of one cyclic family:
        // −(A − C) ω_2 ω_3, as Euler's equations are written. Constants
        // with subscripts are put positive first, so that
        // `cyclic_difference` orders them by their subscripts or letters
        // whatever the sign (I_2 ω_3 − A_3 ω_3 is (I_2 − A_3) ω_3, and
        // C Ω − A Ω is (C − A) Ω, never −(A − C) Ω).
        if terms[0].2.is_negative() {
            terms.swap(0, 1);
        }
    } else if pull_sign(&terms) && lead_positive_inside(&mut terms) {
        content = -content;
    } else if terms[0].2.is_negative()
        && let Some(k) = terms.iter().position(|t| !t.2.is_negative())
    {
        let t = terms.remove(k);
        terms.insert(0, t);
    }
    let mut common = terms[0].1.clone();
    for t in &terms[1..] {
        if common.is_one() {
            break;
        }
        common = common.gcd(t.1);
    }
    if distribute {
        // Only common rates leave the bracket (½ (I′ + m L² + I L²/r²) φ̇²);
        // constants, sin and cos stay with each term.
        common = common
            .split(|a| a.is_time_dependent() && matches!(a.kind(), AtomKind::Var { .. }))
            .0;
    }
    let inv = content.recip().expect("non-zero content");
    let plain = common.is_one() && inv.is_one();

    let mut outer = key.mul(&common);
    let mut number = content.abs();
    let mut negative = content.is_negative();
    let rest = || Poly::from_terms(terms.iter().map(|(_, m, c)| (m.div(&common), *c * &inv)));
    let factored = if terms.len() > 1 && !known.is_empty() {
        factor_by(&rest(), known)
    } else {
        None
    };
    let bracket: Vec<Id> = if terms.len() == 1 {
        outer = outer.mul(&terms[0].1.div(&common));
        Vec::new()
    } else if let Some((a, b)) = cyclic_difference(&terms, &common) {
        // (a − b) with b before a in cyclic order: written −(b − a), as
        // Euler's equations are (− (I_z − I_x) ω_z ω_x).
        negative = !negative;
        let ta = e.term_node(&[(b, 1)], &Rational::ONE);
        let tb = e.term_node(&[(a, 1)], &-Rational::ONE);
        vec![e.add(vec![ta, tb])]
    } else if let Some((fs, m, c)) = factored {
        // rest = c · m · Π fs
        outer = outer.mul(&m);
        number = &number * &c.abs();
        negative ^= c.is_negative();
        fs.iter().map(|f| known_factor_node(e, f, pres)).collect()
    } else {
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
                    (Cow::Owned(m.div(&common)), *c * &inv)
                }
            })
            .collect();
        // The part that follows a bracket (rates, sin and cos, constant
        // rates named by Greek letters: J s + (C − A) Ω).
        let timed: Vec<Monomial> = if big {
            Vec::new()
        } else {
            parts
                .iter()
                .map(|(m, _)| m.split(|a| !leading_constant(a)).0)
                .collect()
        };
        let mut shared: FxHashMap<&Monomial, Vec<(Monomial, Rational)>> = FxHashMap::default();
        for ((m, c), t) in parts.iter().zip(&timed) {
            if !t.is_one() {
                shared.entry(t).or_default().push((m.div(t), c.clone()));
            }
        }
        shared.retain(|_, v| v.len() > 1);
        let mut atoms: FxHashMap<(Atom, i32), Id> = FxHashMap::default();
        // (node, negative, highest derivative order, has a part that
        // follows a bracket)
        let mut nodes: Vec<(Id, bool, u32, bool)> = Vec::with_capacity(terms.len());
        for (k, ((sorted, _, _), (m, c))) in terms.iter().zip(&parts).enumerate() {
            let top = m.factors().iter().map(|f| f.0.order()).max().unwrap_or(0);
            let follows = match timed.get(k) {
                None => m.factors().iter().any(|&(a, _)| !leading_constant(a)),
                Some(t) => {
                    if let Some(sub) = shared.get_mut(t) {
                        // The first term of the shared part stands for all of them.
                        if !sub.is_empty() {
                            let sub = std::mem::take(sub);
                            let id = group_node(e, t, &sub, pres);
                            nodes.push((id, matches!(e.node(id), Node::Neg(_)), top, true));
                        }
                        continue;
                    }
                    !t.is_one()
                }
            };
            let mut f: SmallVec<[(Atom, i32); 16]> = if plain {
                sorted.iter().copied().collect()
            } else {
                m.sorted_for_print().into_iter().collect()
            };
            conventional(&mut f, order);
            let id = if distribute {
                ratio_term(e, &f, c)
            } else if big {
                shared_term_node(e, &f, c, &mut atoms)
            } else {
                e.term_node(&f, c)
            };
            nodes.push((id, c.is_negative(), top, follows));
        }
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
            negative = !negative;
            nodes.sort_by_key(|n| (Reverse(n.2), n.3));
        }
        // The bracket leads with a positive term of its leading order.
        if nodes[0].1
            && let Some(k) = nodes.iter().position(|n| !n.1 && n.2 == nodes[0].2)
        {
            let n = nodes.remove(k);
            nodes.insert(0, n);
        }
        vec![e.add(nodes.into_iter().map(|n| n.0).collect())]
    };
    if terms.len() == 1 {
        number = terms[0].2.abs();
    }

    let factors = outer.sorted_for_print();
    let mut ids = Vec::new();
    if !number.is_one() || (factors.is_empty() && bracket.is_empty()) {
        ids.push(e.push(Node::Num(number)));
    }
    // Constant symbols lead, in conventional order (mass, inertia,
    // gravity, then by name: m g l, I′ θ̇); constants named by a Greek
    // letter (a constant rate Ω) and sin/cos (even of a constant angle)
    // follow the bracket with the rates.
    let leading = leading_constant;
    let mut lead: Vec<(Atom, i32)> = factors.iter().copied().filter(|f| leading(f.0)).collect();
    lead.sort_by_key(|f| constant_class(f.0, order));
    for (a, x) in lead {
        ids.push(e.atom_pow(a, x));
    }
    ids.extend(bracket);
    let mut trailing: Vec<(Atom, i32)> =
        factors.iter().copied().filter(|f| !leading(f.0)).collect();
    cyclic_pair(&mut trailing);
    for (a, x) in trailing {
        ids.push(e.atom_pow(a, x));
    }
    let m = e.mul(ids);
    if negative { e.push(Node::Neg(m)) } else { m }
}

/// A constant symbol that leads a product (`m g l`), as opposed to a rate,
/// sin or cos, or a constant named by a Greek letter (a constant rate Ω),
/// which follow the bracket.
fn leading_constant(a: Atom) -> bool {
    // Asked for every factor of every term: each atom's answer (a name
    // looked up in the Greek table) is found once.
    thread_local! {
        static KNOWN: std::cell::RefCell<FxHashMap<Atom, bool>> = Default::default();
    }
    KNOWN.with(|k| {
        *k.borrow_mut().entry(a).or_insert_with(|| {
            !a.is_time_dependent()
                && matches!(a.kind(), AtomKind::Var { .. })
                && crate::symbols::greek(a.name().split('_').next().unwrap_or("")).is_none()
        })
    })
}

/// Two terms, each a single constant of one cyclic family (I_x and I_z,
/// A and C), times a common factor.
fn cyclic_pair_of_constants(terms: &[crate::expr::PrintTerm<'_>]) -> bool {
    let [t0, t1] = terms else { return false };
    let common = t0.1.gcd(t1.1);
    let single = |m: &Monomial| match m.div(&common).factors() {
        [(a, 1)] if !a.is_time_dependent() => Some(*a),
        _ => None,
    };
    matches!((single(t0.1), single(t1.1)), (Some(a), Some(b)) if constants_of_one_family(a, b))
}

/// Whether a group's minus sign goes in front of its bracket: for a single
/// term, when it is negative; for a sum, when more of its terms are
/// negative than positive and it does not mix kinds of opposite signs —
/// terms of one kind (the same constant factors: `m` terms, `I′` terms, the
/// terms without constants) all positive and those of another all
/// negative. So −I′ (φ̈ sin θ + 2 φ̇ θ̇ cos θ), but m z ẍ − m x z̈ + ḣ_y
/// rather than −(m x z̈ − m z ẍ − ḣ_y), and I ω_z cos θ − I′ φ̇ − I′ φ̇ cos² θ
/// rather than −(I′ φ̇ + I′ φ̇ cos² θ − I ω_z cos θ).
fn pull_sign(terms: &[crate::expr::PrintTerm<'_>]) -> bool {
    let negative = terms.iter().filter(|t| t.2.is_negative()).count();
    if terms.len() == 1 {
        return negative == 1;
    }
    if 2 * negative <= terms.len() {
        return false;
    }
    // Per kind: (any positive, any negative).
    let mut kinds: BTreeMap<Monomial, (bool, bool)> = BTreeMap::new();
    for t in terms {
        let kind = t.1.split(leading_constant).0;
        let e = kinds.entry(kind).or_default();
        if t.2.is_negative() {
            e.1 = true;
        } else {
            e.0 = true;
        }
    }
    let all_positive = kinds.values().any(|&(p, n)| p && !n);
    let all_negative = kinds.values().any(|&(p, n)| n && !p);
    !(all_positive && all_negative)
}

/// With the sign pulled out, the bracket leads with a positive term: a
/// term of the leading one's derivative order that is negative (positive
/// once the sign is out) is moved to the front. When there is none —
/// the highest derivative would lead negative, −(−r θ̈ cos θ + b φ̇² + …) —
/// the sign is not pulled (false): r θ̈ cos θ − b φ̇² − ….
fn lead_positive_inside(terms: &mut Vec<crate::expr::PrintTerm<'_>>) -> bool {
    if terms[0].2.is_negative() {
        return true;
    }
    let top = |t: &crate::expr::PrintTerm<'_>| t.1.factors().iter().map(|f| f.0.order()).max();
    let first = top(&terms[0]);
    let Some(k) = terms
        .iter()
        .position(|t| top(t) == first && t.2.is_negative())
    else {
        return false;
    };
    let t = terms.remove(k);
    terms.insert(0, t);
    true
}

/// True when the monomial divides by something (a negative power).
fn has_divisor(m: &Monomial) -> bool {
    m.factors().iter().any(|f| f.1 < 0)
}

/// Whether a bracket's constant divisor is distributed over its terms
/// rather than written once under the whole bracket: when some terms are
/// divided by a constant and others not at all, as a solved form is after
/// the divisor cancelled in some terms, and nothing time-dependent divides
/// (a divisor such as sin θ keeps the bracket one fraction:
/// φ̈ = (I ω_z − 2 I′ φ̇ cos θ) θ̇/(I′ sin θ)). Terms that all share their
/// divisor keep it under the bracket, (F_z y_P − F_y z_P)/I_x, and terms
/// all divided by different constants go over their common denominator,
/// H_G (I′ − I) cos θ/(I I′).
fn distributes(terms: &[crate::expr::PrintTerm<'_>]) -> bool {
    if terms.len() < 2 {
        return false;
    }
    let divisor = |m: &Monomial| -> Option<Vec<(Atom, i32)>> {
        let d: Vec<(Atom, i32)> = m.factors().iter().copied().filter(|f| f.1 < 0).collect();
        d.iter().all(|f| leading_constant(f.0)).then_some(d)
    };
    let Some(first) = divisor(terms[0].1) else {
        return false;
    };
    let (mut differ, mut undivided) = (false, first.is_empty());
    for t in &terms[1..] {
        let Some(d) = divisor(t.1) else { return false };
        differ |= d != first;
        undivided |= d.is_empty();
    }
    differ && undivided
}

/// `c · factors` for a term of a distributed bracket: constant factors
/// over a constant divisor, followed by rates, sin and cos, are written
/// as a ratio in front, `(m g l/I′) sin θ`, as a textbook writes a solved
/// form; a term of constants only is one fraction (`I L²/r²`).
fn ratio_term(e: &mut Expr, factors: &[(Atom, i32)], c: &Rational) -> Id {
    type Factors = Vec<(Atom, i32)>;
    let (constants, rest): (Factors, Factors) =
        factors.iter().copied().partition(|f| leading_constant(f.0));
    let numerator = constants.iter().any(|f| f.1 > 0);
    let denominator = constants.iter().any(|f| f.1 < 0);
    if rest.is_empty() || !numerator || !denominator {
        return e.term_node(factors, c);
    }
    let mut ids = Vec::new();
    let mag = c.abs();
    if !mag.is_one() {
        ids.push(e.push(Node::Num(mag)));
    }
    let ratio: Vec<Id> = constants.iter().map(|&(a, x)| e.atom_pow(a, x)).collect();
    ids.push(e.mul(ratio));
    for &(a, x) in &rest {
        ids.push(e.atom_pow(a, x));
    }
    let m = e.mul(ids);
    if c.is_negative() {
        e.push(Node::Neg(m))
    } else {
        m
    }
}

/// `c · factors` as [`Expr::term_node`] writes it, with each atom power
/// stored once in the tree and shared by the terms that have it (`atoms`
/// remembers their nodes): a plain bracket of 40,000 terms costs three
/// nodes a term, not fifteen. Printing and expanding read a shared node as
/// they read a copy.
fn shared_term_node(
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

/// The place of a constant factor: the names of the file's own order
/// (`[symbols] order`) first, in that order; then the conventional one —
/// mass first, then inertia, then gravity, then the others (lengths),
/// `m g l`, `I′ θ̇` — each class by name.
fn constant_class(a: Atom, order: &[String]) -> (usize, u8, &'static str) {
    let name = a.name();
    let own = order.iter().position(|n| n == name).unwrap_or(order.len());
    let base = name.split('_').next().unwrap_or(name);
    let class = match base {
        "m" | "M" | "mass" => 0,
        "I" | "Ip" | "J" | "Jp" => 1,
        "g" => 2,
        _ => 3,
    };
    (own, class, name)
}

/// A place in a cyclic order: (family, position, which order).
type Place = (&'static str, usize, u8);

/// The position of a subscript or letter in a cyclic order (x → y → z,
/// 1 → 2 → 3, A → B → C, also with a common subscript: A_p → B_p → C_p),
/// the family (the name without the subscript, or the letters' common
/// subscript), and which of the three orders it is in.
fn cyclic_place(a: Atom) -> Option<Place> {
    // Each atom's place is found once (names compared as strings).
    thread_local! {
        static KNOWN: std::cell::RefCell<FxHashMap<Atom, Option<Place>>> = Default::default();
    }
    KNOWN.with(|k| *k.borrow_mut().entry(a).or_insert_with(|| place_of(a)))
}

fn place_of(a: Atom) -> Option<Place> {
    let name = a.name();
    if let Some((base, sub)) = name.rsplit_once('_') {
        if let Some(k) = ["x", "y", "z"].iter().position(|c| *c == sub) {
            return Some((base, k, 0));
        }
        if let Some(k) = ["1", "2", "3"].iter().position(|c| *c == sub) {
            return Some((base, k, 1));
        }
        // The letters A, B, C with one other subscript (a platform's A_p,
        // B_p, C_p): the family is the subscript.
        let k = ["A", "B", "C"].iter().position(|c| *c == base)?;
        return Some((sub, k, 2));
    }
    ["A", "B", "C"]
        .iter()
        .position(|c| *c == name)
        .map(|k| ("", k, 2))
}

/// Whether two constants are of one cyclic family as moments of inertia
/// about the three axes are: the same name with subscripts in one order,
/// or different names with subscripts in one order (a gyrostat's I_1, I_2
/// and A_3), or the letters A, B, C.
fn constants_of_one_family(a: Atom, b: Atom) -> bool {
    match (cyclic_place(a), cyclic_place(b)) {
        (Some((fa, _, oa)), Some((fb, _, ob))) => oa == ob && (fa == fb || oa != 2),
        _ => false,
    }
}

/// Whether constant `b` follows constant `a` in the cyclic order of their
/// subscripts ([`constants_of_one_family`]).
fn constant_next(a: Atom, b: Atom) -> bool {
    match (cyclic_place(a), cyclic_place(b)) {
        (Some((_, ka, _)), Some((_, kb, _))) => constants_of_one_family(a, b) && (ka + 1) % 3 == kb,
        _ => false,
    }
}

/// A bracket of two terms `a − b` (single constants of one cyclic family,
/// coefficients +1 and −1 after the common factor) in which `a` follows
/// `b` in cyclic order, so that it reads better as `−(b − a)`:
/// (I_x − I_z) → −(I_z − I_x), (A − C) → −(C − A).
fn cyclic_difference(
    terms: &[crate::expr::PrintTerm<'_>],
    common: &Monomial,
) -> Option<(Atom, Atom)> {
    let [t0, t1] = terms else { return None };
    let single = |m: &Monomial| match m.div(common).factors() {
        [(a, 1)] if !a.is_time_dependent() => Some(*a),
        _ => None,
    };
    let (a, b) = (single(t0.1)?, single(t1.1)?);
    if t0.2.is_negative() || !(t0.2 + t1.2).is_zero() {
        return None;
    }
    // a − b: reads cyclically when b follows a.
    (constant_next(b, a) && !constant_next(a, b)).then_some((a, b))
}

/// The factors of a term inside a bracket in conventional order: constants
/// first as [`constant_class`] orders them (`2 m g l cos θ`), the rest as
/// they were, two rates of one cyclic family in cyclic order.
fn conventional(fs: &mut [(Atom, i32)], order: &[String]) {
    let constant = leading_constant;
    let constants = fs.iter().filter(|f| constant(f.0)).count();
    if constants <= 1 {
        // The sort below would only move the one constant to the front.
        if let Some(k) = fs.iter().position(|f| constant(f.0)) {
            fs[..=k].rotate_right(1);
        }
        cyclic_pair(fs);
        return;
    }
    fs.sort_by_cached_key(|&(a, _)| {
        if constant(a) {
            (0, constant_class(a, order))
        } else {
            (1, (0, 0, ""))
        }
    });
    cyclic_pair(fs);
}

/// Two rates of one cyclic family in cyclic order: ω_x ω_z → ω_z ω_x
/// (the order Euler's equations write them in).
fn cyclic_pair(fs: &mut [(Atom, i32)]) {
    // Each factor's place is looked up once (names are compared as
    // strings), and a swap moves two factors of one family, so the places
    // move with them.
    let mut places: SmallVec<[Option<Place>; 8]> = fs.iter().map(|f| cyclic_place(f.0)).collect();
    let next = |a: Place, b: Place| a.0 == b.0 && a.2 == b.2 && (a.1 + 1) % 3 == b.1;
    for i in 0..fs.len() {
        let Some((family, _, _)) = places[i] else {
            continue;
        };
        let mut same = (0..fs.len()).filter(|&k| places[k].is_some_and(|(f, _, _)| f == family));
        let (Some(p), Some(q), None) = (same.next(), same.next(), same.next()) else {
            continue;
        };
        let (Some(pp), Some(pq)) = (places[p], places[q]) else {
            continue;
        };
        if p == i && fs[p].1 == 1 && fs[q].1 == 1 && next(pq, pp) && !next(pp, pq) {
            fs.swap(p, q);
            places.swap(p, q);
        }
    }
}

/// A known factor as the file writes it (`J s + (C − A) Ω`, the author's
/// grouping and order), when its written form expands to it; otherwise in
/// the default presentation.
fn known_factor_node(e: &mut Expr, f: &Poly, pres: &Presentation) -> Id {
    let written = pres
        .factors
        .iter()
        .position(|k| k == f)
        .and_then(|k| pres.factor_forms.get(k))
        .filter(|w| !w.is_empty() && w.to_poly() == *f);
    match written {
        Some(w) => graft(e, w, w.root()),
        None => e.poly_node(f),
    }
}

/// Copies the subtree of `src` at `id` into `e`; returns its new id.
fn graft(e: &mut Expr, src: &Expr, id: Id) -> Id {
    let node = match src.node(id) {
        Node::Add(ts) => Node::Add(ts.iter().map(|&t| graft(e, src, t)).collect()),
        Node::Mul(fs) => Node::Mul(fs.iter().map(|&f| graft(e, src, f)).collect()),
        Node::Neg(x) => Node::Neg(graft(e, src, *x)),
        Node::Pow(x, k) => Node::Pow(graft(e, src, *x), *k),
        leaf => leaf.clone(),
    };
    e.push(node)
}

/// Writes `p` as `c · m · Π fs` with `fs` all the known factors (or a single
/// one), `m` a monomial and `c` a number, when that is exact.
fn factor_by(p: &Poly, known: &[Poly]) -> Option<(Vec<Poly>, Monomial, Rational)> {
    if known.is_empty() {
        return None;
    }
    let mut candidates: Vec<Vec<Poly>> = vec![known.to_vec()];
    if known.len() > 1 {
        candidates.extend(known.iter().map(|f| vec![f.clone()]));
    }
    for fs in candidates {
        let product = fs.iter().fold(Poly::one(), |a, f| &a * f);
        if product.len() != p.len() || product.is_zero() {
            continue;
        }
        let (m0, c0) = &p.terms()[0];
        for (m1, c1) in product.terms() {
            let m = m0.div(m1);
            let c = c0 * &c1.recip().expect("non-zero coefficient");
            if &product * &Poly::term(m.clone(), c.clone()) == *p {
                return Some((fs, m, c));
            }
        }
    }
    None
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
            let fast: Vec<(Vec<(Atom, i32)>, Monomial)> = print_sorted(p.terms(), true)
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
            let fast_by_names: Vec<(Vec<(Atom, i32)>, Monomial)> = print_sorted(p.terms(), false)
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
