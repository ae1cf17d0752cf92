//! A group whose terms are products of sines and cosines only (the bracket
//! of like terms, `I′ φ̇ (1 + cos² θ)`: terms with the same constants and
//! rates that differ only in sin and cos), presented directly: such a
//! bracket has no constants, rates or divisors in it, so no kinds of
//! terms, shared parts, like terms, ratios or derivative orders to find.
//! chain-6 has 540 of them.
//!
//! The node is the one [`group_node`](super::bracket::group_node) builds
//! for the same terms (its rules specialised to such terms; a test
//! presents every bundled derivation and chain-1 … 5 both ways and
//! compares), only without the work those rules do for nothing here.

use crate::atom::{Atom, AtomKind};
use crate::expr::{Expr, Id};
use crate::poly::Monomial;
use crate::rational::Rational;

use super::Context;
use super::bracket::{group_product, reciprocal, scaled};
use super::gather::{direct_common, quotient_in_order, sum_of_nodes};
use super::order::{conventional, cyclic_difference, cyclic_pair_of_constants};

/// `key · Σ terms` as [`group_node`](super::bracket::group_node) writes
/// it, when the group is a bracket of sines and cosines: two terms or
/// more, each a product of sines and cosines to positive powers (or 1),
/// and no known factors to try. `None` (and `e` untouched) otherwise.
///
/// Why the general rules reduce to these steps for such terms: no term
/// is divided, so no ratio is written and the divisor is not distributed;
/// every factor is of derivative order 0 and none is a leading constant,
/// so the bracket order is the print order with the term equal to what
/// every term has (1 in 1 + cos² θ) first; every term is of one kind (no
/// constants), so the sign is pulled out when most terms are negative
/// and the bracket can lead with a negative one of its leading term's
/// order (a term 1 has none: no order), which it then does; a part is a product of sines and cosines, so
/// none shares a time-dependent part, a coefficient or what is left once
/// sin and cos are out; the bracket follows the rates. A pair the cyclic
/// rules would write otherwise is left to the general path.
pub(super) fn trig_group(
    e: &mut Expr,
    key: &Monomial,
    terms: &[(Monomial, Rational)],
    cx: &Context<'_>,
) -> Option<Id> {
    let common = direct_common(terms, cx, |a| cx.ranks.is_trig(a))?;
    let mut terms = cx.ranks.print.sort(terms, true);
    // Bracket order: the term that is `common` itself (at most one: the
    // terms are distinct) first, the others in print order.
    if let Some(k) = terms.iter().position(|t| *t.1 == common)
        && k > 0
    {
        let t = terms.remove(k);
        terms.insert(0, t);
    }
    if cyclic_pair_of_constants(&terms) {
        return None;
    }
    let mut content = terms.iter().fold(Rational::ZERO, |g, t| g.gcd(t.2));
    let negatives = terms.iter().filter(|t| t.2.is_negative()).count();
    // The sign goes in front when most terms are negative and the bracket
    // can then lead with a negative term (positive once the sign is out)
    // of the leading one's derivative order: not when 1 leads, positive
    // (1 − 2 cos² θ), as no other term is of its order (none).
    let pull = 2 * negatives > terms.len() && (terms[0].2.is_negative() || !terms[0].1.is_one());
    if pull {
        content = -content;
        if !terms[0].2.is_negative()
            && let Some(k) = terms.iter().position(|t| t.2.is_negative())
        {
            let t = terms.remove(k);
            terms.insert(0, t);
        }
    } else if terms[0].2.is_negative()
        && let Some(k) = terms.iter().position(|t| !t.2.is_negative())
    {
        let t = terms.remove(k);
        terms.insert(0, t);
    }
    if cyclic_difference(&terms, &common).is_some() {
        return None;
    }
    let inv = reciprocal(&content);
    let outer = key.mul(&common);
    let number = content.abs();
    let mut negative = content.is_negative();
    let plain = common.is_one() && inv.is_one();
    // Dividing by `common` keeps the print order unless it takes away a
    // sine, next to which its cosine was placed.
    let keeps_order = common
        .factors()
        .iter()
        .all(|f| !matches!(f.0.kind(), AtomKind::Sin(_)));
    let order = &cx.pres.constant_order[..];
    let mut nodes: Vec<(Id, bool, u32, bool)> = Vec::with_capacity(terms.len());
    for (sorted, m, c) in &terms {
        let mut f: smallvec::SmallVec<[(Atom, i32); 16]> = if plain {
            sorted.iter().copied().collect()
        } else if keeps_order {
            quotient_in_order(sorted, &common)
        } else {
            cx.ranks.print.sorted(&m.div(&common)).into_iter().collect()
        };
        conventional(&mut f, order, &cx.ranks);
        let c = if plain { (*c).clone() } else { scaled(c, &inv) };
        // A part other than 1 follows a bracket.
        let follows = !f.is_empty();
        let id = e.term_node(&f, &c);
        nodes.push((id, c.is_negative(), 0, follows));
    }
    let (sum, flip) = sum_of_nodes(e, nodes);
    negative ^= flip;
    Some(group_product(
        e,
        &outer,
        &number,
        negative,
        vec![sum],
        true,
        cx,
    ))
}
