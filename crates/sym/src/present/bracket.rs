//! One group of a presented result as `[number] [constants] (bracket)
//! [rates, sin, cos]`: its terms in bracket order, the rational content and
//! the sign pulled out or not, the common monomial, a bracket that is a
//! known factor or a cyclic difference, and a solved form's ratios. The sum
//! inside the bracket is `gather.rs`'s.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;
use std::cmp::Reverse;

use super::constants::constants_group;
use super::gather::bracket_sum;
use super::known::{factor_by, known_factor_node};
use super::order::{
    Ranks, conventional, cyclic_difference, cyclic_pair_of_constants, leading_constant,
};
use super::trig::trig_group;
use super::{Context, PLAIN_ABOVE};
use crate::atom::{Atom, AtomKind};
use crate::expr::{Expr, Id, Node, PrintTerm};
use crate::poly::{Monomial, Poly};
use crate::rational::Rational;

/// `key · Σ terms` with the sum factored. `ratios`: the whole result is a
/// solved form whose constant divisors are written term by term
/// ([`distributes`] of all its terms), so every term of this group that
/// is divided by constants carries its ratio in front, `(m g l/I′) sin θ`,
/// whether it stands alone or in a bracket (one rule for a constant ratio).
pub(super) fn group_node(
    e: &mut Expr,
    key: &Monomial,
    terms: &[(Monomial, Rational)],
    cx: &Context<'_>,
    ratios: bool,
) -> Id {
    // A bracket of constants (chain-6 has thousands) or of sines and
    // cosines (hundreds) takes a direct path.
    #[cfg(test)]
    if GENERAL_ONLY.with(std::cell::Cell::get) {
        return general_group(e, key, terms, cx, ratios);
    }
    if let Some(id) = constants_group(e, key, terms, cx) {
        return id;
    }
    if let Some(id) = trig_group(e, key, terms, cx) {
        return id;
    }
    general_group(e, key, terms, cx, ratios)
}

/// [`group_node`] by the general rules.
fn general_group(
    e: &mut Expr,
    key: &Monomial,
    terms: &[(Monomial, Rational)],
    cx: &Context<'_>,
    ratios: bool,
) -> Id {
    let known = &cx.pres.factors[..];
    let order = &cx.pres.constant_order[..];
    // The order only: most terms of a bracket are written inside a shared
    // bracket of constants, which sorts its own (`bracket_sum` finds the
    // factors of the terms it writes). A plain bracket (above
    // PLAIN_ABOVE) writes every term: its factors come with the order.
    let mut terms = if terms.len() > PLAIN_ABOVE {
        cx.ranks.print.sort(terms, true)
    } else {
        cx.ranks.print.sort_unfactored(terms, true)
    };
    if ratios && terms.len() == 1 {
        let m = key.mul(terms[0].1);
        let mut f: SmallVec<[(Atom, i32); 16]> = cx.ranks.print.sorted(&m).into_iter().collect();
        conventional(&mut f, order, &cx.ranks);
        if let Some(id) = ratio_node(e, &f, terms[0].2) {
            return id;
        }
    }
    let distribute = distributes(&terms)
        || (ratios && terms.len() > 1 && terms.iter().any(|t| has_constant_divisor(t.1)));
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
    let bracket_order = |t: &PrintTerm<'_>| {
        let top = cx.ranks.top(t.1);
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
        (Reverse(top), timed, distribute && has_divisor(t.1))
    };
    // A stable sort of terms already in print order: often nothing moves,
    // and the keys tell it without a sort.
    if !terms.iter().map(bracket_order).is_sorted() {
        terms.sort_by_cached_key(bracket_order);
    }
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
    } else if pull_sign(&terms, &cx.ranks) && lead_positive_inside(&mut terms) {
        content = -content;
    } else if terms[0].2.is_negative()
        && let Some(k) = terms.iter().position(|t| !t.2.is_negative())
    {
        let t = terms.remove(k);
        terms.insert(0, t);
    }
    // What every term has (`all`: the same terms, in another order).
    let mut common = all;
    if distribute {
        // Only common rates leave the bracket (½ (I′ + m L² + I L²/r²) φ̇²);
        // constants, sin and cos stay with each term.
        common = common
            .split(|a| a.is_time_dependent() && matches!(a.kind(), AtomKind::Var { .. }))
            .0;
    }
    let inv = reciprocal(&content);

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
        fs.iter()
            .map(|f| known_factor_node(e, f, cx.pres))
            .collect()
    } else {
        let (sum, flip) = bracket_sum(e, &terms, &common, &inv, distribute, cx, ratios);
        negative ^= flip;
        vec![sum]
    };
    if terms.len() == 1 {
        number = terms[0].2.abs();
    }
    // A bracket of sines and cosines only follows the rates, as the
    // bracket of like terms does: I′ φ̇ (1 + cos² θ).
    let trig_only = terms.len() > 1
        && terms.iter().all(|t| {
            t.1.factors()
                .iter()
                .all(|&(a, x)| cx.ranks.is_trig(a) || x == common.exponent(a))
                && common
                    .factors()
                    .iter()
                    .all(|&(a, x)| cx.ranks.is_trig(a) || x == t.1.exponent(a))
        });
    group_product(e, &outer, &number, negative, bracket, trig_only, cx)
}

/// A group's node from its parts: `[number] [constants] (bracket) [rates,
/// sin, cos]` (the bracket after the rates when `trig_only`), negated
/// when `negative`. `outer` is what multiplies the bracket.
pub(super) fn group_product(
    e: &mut Expr,
    outer: &Monomial,
    number: &Rational,
    negative: bool,
    bracket: Vec<Id>,
    trig_only: bool,
    cx: &Context<'_>,
) -> Id {
    let order = &cx.pres.constant_order[..];
    let factors = cx.ranks.print.sorted(outer);
    let mut ids = Vec::with_capacity(factors.len() + bracket.len() + 1);
    if !number.is_one() || (factors.is_empty() && bracket.is_empty()) {
        ids.push(e.push(Node::Num(number.clone())));
    }
    // Constant symbols lead, in conventional order (mass, inertia,
    // gravity, then by name: m g l, I′ θ̇); constants named by a Greek
    // letter (a constant rate Ω) and sin/cos (even of a constant angle)
    // follow the bracket with the rates.
    type Factors = SmallVec<[(Atom, i32); 16]>;
    let (mut lead, mut trailing): (Factors, Factors) =
        factors.iter().copied().partition(|f| cx.ranks.leads(f.0));
    cx.ranks.sort_constants(&mut lead, order);
    for (a, x) in lead {
        ids.push(e.atom_pow(a, x));
    }
    if !trig_only {
        ids.extend(bracket.iter().copied());
    }
    cx.ranks.cyclic_pair(&mut trailing);
    for (a, x) in trailing {
        ids.push(e.atom_pow(a, x));
    }
    if trig_only {
        ids.extend(bracket);
    }
    let m = e.mul(ids);
    if negative { e.push(Node::Neg(m)) } else { m }
}

/// Whether a group's minus sign goes in front of its bracket: for a single
/// term, when it is negative; for a sum, when more of its terms are
/// negative than positive and it does not mix kinds of opposite signs —
/// terms of one kind (the same constant factors: `m` terms, `I′` terms, the
/// terms without constants) all positive and those of another all
/// negative. So −I′ (φ̈ sin θ + 2 φ̇ θ̇ cos θ), but m z ẍ − m x z̈ + ḣ_y
/// rather than −(m x z̈ − m z ẍ − ḣ_y), and I ω_z cos θ − I′ φ̇ − I′ φ̇ cos² θ
/// rather than −(I′ φ̇ + I′ φ̇ cos² θ − I ω_z cos θ).
pub(super) fn pull_sign(terms: &[PrintTerm<'_>], ranks: &Ranks) -> bool {
    let negative = terms.iter().filter(|t| t.2.is_negative()).count();
    if terms.len() == 1 {
        return negative == 1;
    }
    if 2 * negative <= terms.len() {
        return false;
    }
    // Per kind: (a term of it, any positive, any negative). A term's kind
    // is found by a hash of its constant factors, then compared factor by
    // factor with the kinds of that hash (nothing built per term).
    fn constants<'m>(m: &'m Monomial, ranks: &'m Ranks) -> impl Iterator<Item = &'m (Atom, i32)> {
        m.factors().iter().filter(|f| ranks.leads(f.0))
    }
    let mut kinds: Vec<(usize, bool, bool)> = Vec::new();
    let mut by_hash: FxHashMap<u64, SmallVec<[u32; 1]>> = FxHashMap::default();
    for (i, t) in terms.iter().enumerate() {
        let mut h: u64 = 0x243F_6A88_85A3_08D3;
        for &(a, x) in t.1.factors() {
            if ranks.leads(a) {
                let w = (u64::from(a.id()) << 32) | u64::from(x as u32);
                h = (h ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                h ^= h >> 29;
            }
        }
        let slot = by_hash.entry(h).or_default();
        let found = slot
            .iter()
            .copied()
            .find(|&k| constants(terms[kinds[k as usize].0].1, ranks).eq(constants(t.1, ranks)));
        let k = found.unwrap_or_else(|| {
            kinds.push((i, false, false));
            slot.push((kinds.len() - 1) as u32);
            (kinds.len() - 1) as u32
        }) as usize;
        if t.2.is_negative() {
            kinds[k].2 = true;
        } else {
            kinds[k].1 = true;
        }
    }
    let all_positive = kinds.iter().any(|&(_, p, n)| p && !n);
    let all_negative = kinds.iter().any(|&(_, p, n)| n && !p);
    !(all_positive && all_negative)
}

/// With the sign pulled out, the bracket leads with a positive term: a
/// term of the leading one's derivative order that is negative (positive
/// once the sign is out) is moved to the front. When there is none —
/// the highest derivative would lead negative, −(−r θ̈ cos θ + b φ̇² + …) —
/// the sign is not pulled (false): r θ̈ cos θ − b φ̇² − ….
pub(super) fn lead_positive_inside(terms: &mut Vec<PrintTerm<'_>>) -> bool {
    if terms[0].2.is_negative() {
        return true;
    }
    let top = |t: &PrintTerm<'_>| t.1.factors().iter().map(|f| f.0.order()).max();
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
pub(super) fn has_divisor(m: &Monomial) -> bool {
    m.factors().iter().any(|f| f.1 < 0)
}

/// True when the monomial divides by constants, and by nothing else.
fn has_constant_divisor(m: &Monomial) -> bool {
    has_divisor(m) && m.factors().iter().all(|f| f.1 > 0 || leading_constant(f.0))
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
pub(super) fn distributes(terms: &[PrintTerm<'_>]) -> bool {
    distributes_over(terms.iter().map(|t| t.1))
}

/// [`distributes`] of the terms' monomials.
pub(super) fn distributes_over<'a>(terms: impl ExactSizeIterator<Item = &'a Monomial>) -> bool {
    if terms.len() < 2 {
        return false;
    }
    let divisor = |m: &Monomial| -> Option<Vec<(Atom, i32)>> {
        let d: Vec<(Atom, i32)> = m.factors().iter().copied().filter(|f| f.1 < 0).collect();
        d.iter().all(|f| leading_constant(f.0)).then_some(d)
    };
    let mut terms = terms;
    let Some(first) = terms.next().and_then(divisor) else {
        return false;
    };
    let (mut differ, mut undivided) = (false, first.is_empty());
    for t in terms {
        let Some(d) = divisor(t) else { return false };
        differ |= d != first;
        undivided |= d.is_empty();
    }
    differ && undivided
}

/// `c · factors` for a term of a distributed bracket: constant factors
/// over a constant divisor, followed by rates, sin and cos, are written
/// as a ratio in front, `(m g l/I′) sin θ`, as a textbook writes a solved
/// form, the number in the ratio (`(m g L/(4 a)) sin β`, `(2 m L²/a) φ̇²`,
/// as presentation rule 10 writes a fraction); a term of constants only
/// is one fraction (`I L²/r²`).
pub(super) fn ratio_term(e: &mut Expr, factors: &[(Atom, i32)], c: &Rational) -> Id {
    ratio_node(e, factors, c).unwrap_or_else(|| e.term_node(factors, c))
}

/// [`ratio_term`] when the term is a ratio of constants times something
/// else; `None` otherwise.
fn ratio_node(e: &mut Expr, factors: &[(Atom, i32)], c: &Rational) -> Option<Id> {
    type Factors = Vec<(Atom, i32)>;
    let (constants, rest): (Factors, Factors) =
        factors.iter().copied().partition(|f| leading_constant(f.0));
    let numerator = constants.iter().any(|f| f.1 > 0);
    let denominator = constants.iter().any(|f| f.1 < 0);
    if rest.is_empty() || !numerator || !denominator {
        return None;
    }
    let mut ids = Vec::new();
    let mag = c.abs();
    let mut ratio: Vec<Id> = Vec::with_capacity(constants.len() + 1);
    if !mag.is_one() {
        ratio.push(e.push(Node::Num(mag)));
    }
    ratio.extend(constants.iter().map(|&(a, x)| e.atom_pow(a, x)));
    ids.push(e.mul(ratio));
    for &(a, x) in &rest {
        ids.push(e.atom_pow(a, x));
    }
    let m = e.mul(ids);
    Some(if c.is_negative() {
        e.push(Node::Neg(m))
    } else {
        m
    })
}

/// `1/content` for a non-zero content; an integer's without the gcd a
/// general reciprocal takes.
pub(super) fn reciprocal(content: &Rational) -> Rational {
    match *content {
        Rational::Small(n, 1) if n > 0 => Rational::Small(1, n),
        Rational::Small(n, 1) if n < 0 && n != i64::MIN => Rational::Small(-1, -n),
        _ => content.recip().expect("non-zero content"),
    }
}

/// `c · inv` with `inv` the [`reciprocal`] of a content of `c`: an integer
/// over an integer content is an exact division, without the gcd of a
/// product of fractions.
pub(super) fn scaled(c: &Rational, inv: &Rational) -> Rational {
    if let (Rational::Small(k, 1), Rational::Small(s @ (1 | -1), n)) = (c, inv)
        && k % n == 0
        && let Some(q) = (k / n).checked_mul(*s)
    {
        return Rational::Small(q, 1);
    }
    c * inv
}

#[cfg(test)]
thread_local! {
    /// Tests: every group by the general rules (no direct path).
    static GENERAL_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cfg(test)]
mod tests {
    use super::GENERAL_ONLY;
    use crate::derivation::Derivation;

    /// Every presented result of `d` printed (Unicode), under the
    /// general rules alone or with the direct path.
    fn printed(load: &dyn Fn() -> Derivation, general_only: bool) -> Vec<String> {
        GENERAL_ONLY.with(|g| g.set(general_only));
        let d = load();
        let out = d
            .steps
            .iter()
            .flat_map(|s| s.presented())
            .map(|(label, e)| format!("{label}: {}", crate::print::unicode(&e)))
            .collect();
        GENERAL_ONLY.with(|g| g.set(false));
        out
    }

    /// The direct paths write every bracket of constants and every bracket
    /// of sines and cosines as the general rules do: every bundled
    /// derivation and chain-1 … 5 (chain-5 alone has hundreds of such
    /// brackets) print the same both ways.
    #[test]
    fn direct_paths_write_brackets_as_the_general_rules_do() {
        // The bundled derivations and the files written for the tests
        // (textbook, lecturer and newcomer problems; the verify tests').
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let dirs = [
            "derivations",
            "tests/sym/textbook",
            "tests/sym/lecturer",
            "tests/sym/newcomer",
            "tests/num/derivations",
        ];
        let mut files: Vec<_> = dirs
            .iter()
            .flat_map(|d| std::fs::read_dir(root.join(d)).expect("a folder of derivations"))
            .map(|f| f.expect("a directory entry").path())
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        files.sort();
        let mut loads: Vec<Box<dyn Fn() -> Option<Derivation>>> = Vec::new();
        for f in files {
            loads.push(Box::new(move || crate::derivation::load(&f).ok()));
        }
        for k in 1..=5 {
            loads.push(Box::new(move || crate::chain::derivation(k).ok()));
        }
        let mut compared = 0;
        for load in &loads {
            // Scenes and the notes manifest are not derivations.
            if load().is_none() {
                continue;
            }
            let load = || load().expect("loaded once");
            let general = printed(&load, true);
            let direct = printed(&load, false);
            assert_eq!(direct, general);
            compared += general.len();
        }
        assert!(compared > 100, "only {compared} results compared");
    }
}
