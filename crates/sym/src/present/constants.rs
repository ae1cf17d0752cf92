//! A group whose terms are products of constants only (the bracket of
//! constants that terms sharing their rates, sin and cos are gathered
//! over: `(I_1yz − I_2yz) q̈_1 sin q_1`), presented directly: such a
//! bracket has no time-dependent part, so no shared parts, like terms,
//! ratios or derivative order to find. chain-6 has 2,764 of them.
//!
//! The node is the one [`group_node`](super::bracket::group_node) builds
//! for the same terms (its rules specialised to terms of constants; a test
//! presents every bundled derivation and chain-1 … 5 both ways and
//! compares), only without the work those rules do for nothing here.

use crate::expr::{Expr, Id};
use crate::poly::Monomial;
use crate::rational::Rational;

use super::Context;
use super::bracket::{group_product, reciprocal, scaled};
use super::gather::{direct_common, quotient_in_order, sum_of_nodes};
use super::order::{conventional, cyclic_difference, cyclic_pair_of_constants};

/// `key · Σ terms` as [`group_node`](super::bracket::group_node) writes
/// it, when the group is a bracket of constants: two terms or more, each
/// a product of leading constants to positive powers, and no known
/// factors to try. `None` (and `e` untouched) otherwise.
///
/// Why the general rules reduce to these steps for such terms: no term
/// is divided, so no ratio is written and the divisor is not distributed;
/// every term has derivative order 0 and nothing time-dependent, so the
/// bracket order is the print order; each term is a kind of its own (its
/// constants), so kinds of both signs are mixed unless all terms have one
/// sign, and the sign is pulled out exactly when every term is negative;
/// every term of the bracket is of constants, so none
/// shares a time-dependent part or differs only in sin and cos; and a
/// term of one factor (what is left once the common factor is out) is in
/// no group of a shared coefficient (the groups with one are left to the
/// general path).
pub(super) fn constants_group(
    e: &mut Expr,
    key: &Monomial,
    terms: &[(Monomial, Rational)],
    cx: &Context<'_>,
) -> Option<Id> {
    let common = direct_common(terms, cx, |a| cx.ranks.is_leading_constant(a))?;
    // A term of two constants or more once `common` is out may share a
    // coefficient with another (a A_x − a B_x): the general path.
    let single = terms.iter().all(|(m, _)| {
        m.factors()
            .iter()
            .filter(|&&(a, x)| x != common.exponent(a))
            .count()
            < 2
    });
    if !single {
        return None;
    }
    let mut terms = cx.ranks.print.sort(terms, true);
    let mut content = terms.iter().fold(Rational::ZERO, |g, t| g.gcd(t.2));
    let negatives = terms.iter().filter(|t| t.2.is_negative()).count();
    if cyclic_pair_of_constants(&terms) {
        if terms[0].2.is_negative() {
            terms.swap(0, 1);
        }
    } else if negatives == terms.len() {
        content = -content;
    } else if terms[0].2.is_negative()
        && let Some(k) = terms.iter().position(|t| !t.2.is_negative())
    {
        let t = terms.remove(k);
        terms.insert(0, t);
    }
    let inv = reciprocal(&content);
    let outer = key.mul(&common);
    let number = content.abs();
    let mut negative = content.is_negative();
    let bracket = if let Some((a, b)) = cyclic_difference(&terms, &common) {
        negative = !negative;
        let ta = e.term_node(&[(b, 1)], &Rational::ONE);
        let tb = e.term_node(&[(a, 1)], &-Rational::ONE);
        e.add(vec![ta, tb])
    } else {
        let plain = common.is_one() && inv.is_one();
        let order = &cx.pres.constant_order[..];
        let mut nodes: Vec<(Id, bool, u32, bool)> = Vec::with_capacity(terms.len());
        for (sorted, _, c) in &terms {
            let mut f = quotient_in_order(sorted, &common);
            conventional(&mut f, order, &cx.ranks);
            let id = if plain {
                e.term_node(&f, c)
            } else {
                e.term_node(&f, &scaled(c, &inv))
            };
            nodes.push((id, c.is_negative() != inv.is_negative(), 0, false));
        }
        let (sum, flip) = sum_of_nodes(e, nodes);
        negative ^= flip;
        sum
    };
    Some(group_product(
        e,
        &outer,
        &number,
        negative,
        vec![bracket],
        false,
        cx,
    ))
}
