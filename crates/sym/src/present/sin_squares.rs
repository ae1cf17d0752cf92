//! Presentation rule 1: `sin² θ` or `1 − cos² θ`, whichever leaves a
//! group of terms the fewest terms.
//!
//! The work is linear in the terms (hash grouping, one pass per angle
//! over the terms, and only the terms with a power of `cos θ` are keyed):
//! a result of 100,000 terms must not make its display slower than the
//! algebra that made it.

use std::collections::BTreeMap;

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::atom::{Atom, AtomKind};
use crate::poly::Monomial;
use crate::rational::Rational;

type Terms = Vec<(Monomial, Rational)>;

/// One chain: the terms `X cosᵉ θ` of one rest `X`, as (exponent, index
/// into the terms), ascending by exponent.
type Chain = (Monomial, SmallVec<[(i32, usize); 4]>);

/// Chooses between `sin² θ` and `1 − cos² θ` so that the group has the
/// fewest terms. The canonical form holds sin² θ as 1 − cos² θ, so for each
/// angle the terms that differ only in their power of cos θ (the same
/// other factors X, whatever power of cos θ divides them) form a
/// polynomial P(cos θ); when P = (1 − cos² θ)ᵏ Q with Q of fewer terms than
/// P, the terms are written X sin²ᵏ θ Q(cos θ). So φ̇² − φ̇² cos² θ prints
/// φ̇² sin² θ, I′ − I′ cos² θ + J prints J + I′ sin² θ, a cone's
/// (cos² γ − 1) φ̇/cos γ prints −sin² γ φ̇/cos γ and
/// I cos⁴ γ − 2 I cos² γ + I prints I sin⁴ γ. What remains, a pair
/// X cosⁿ θ − X cosⁿ⁺² θ, becomes X cosⁿ θ sin² θ, the pairs of one X
/// taken from the lowest power of cos θ up. Exact: every term expands back
/// to the terms it replaces. The order of the terms afterwards is not
/// meaningful (the printer sorts them).
pub(super) fn merge_trig_squares(ts: &mut Terms) {
    let mut angles: Vec<Atom> = ts
        .iter()
        .flat_map(|(m, _)| m.factors().iter())
        .filter_map(|&(a, _)| match a.kind() {
            AtomKind::Cos(q) => Some(q),
            _ => None,
        })
        .collect();
    angles.sort_unstable();
    angles.dedup();
    angles.sort_by_cached_key(|a| a.sort_key());
    let mut changed = false;
    // Each term's hash, a sum over its factors, from which the hash of
    // the term without its power of cos θ is one subtraction; kept beside
    // the terms as the rules rewrite them.
    let mut hashes: Vec<u64> = ts.iter().map(|t| monomial_hash(&t.0)).collect();
    for q in angles {
        if let (Some(cos), Some(sin)) = (Atom::cos(q), Atom::sin(q)) {
            let mut found = chains(ts, &hashes, cos, None);
            if let Some(rewrite) = factor_sin_squares(ts, &mut hashes, &found, cos, sin) {
                changed = true;
                found = patched(ts, &hashes, found, &rewrite, cos, sin);
                #[cfg(debug_assertions)]
                {
                    let mut again = chains(&mut ts.clone(), &hashes, cos, None);
                    again.retain(|(_, c)| c.iter().any(|&(_, i)| !ts[i].1.is_zero()));
                    debug_assert_eq!(found, again, "chains patched after a rewrite");
                }
            }
            // Unchanged terms have the same chains: they are found once.
            changed |= merge_pairs(ts, &mut hashes, &found, cos, sin);
        }
    }
    debug_assert!(
        ts.iter()
            .zip(&hashes)
            .all(|(t, &h)| monomial_hash(&t.0) == h)
    );
    if changed {
        // Two rewritten terms may meet on one monomial: add them.
        add_equal_monomials(ts);
    }
}

/// The chains of `cos` in `ts` that have two terms or more: the terms with
/// a power of `cos` keyed by what is left without it, and the term without
/// `cos` of the same rest joined to its chain. Equal exponents in a chain
/// (two equal monomials left by an earlier angle) are added into the first.
///
/// The terms are keyed by a hash of the rest (`hashes[i]` is the
/// [`monomial_hash`] of term i; no rest is built until a chain is found),
/// and a bucket is split by comparing the rests factor by factor, so hash
/// collisions cost time, never correctness.
///
/// `among`: only these terms (ascending indices) are looked at, as
/// [`patched`] asks; `None`, all of them.
fn chains(ts: &mut Terms, hashes: &[u64], cos: Atom, among: Option<&[usize]>) -> Vec<Chain> {
    // The j-th term looked at.
    let at = |j: usize| among.map_or(j, |m| m[j]);
    let n = among.map_or(ts.len(), <[usize]>::len);
    // Each term's exponent of cos, read once (by bisection: the factors
    // are sorted by atom).
    let exps: Vec<i32> = (0..n).map(|j| exponent(&ts[at(j)].0, cos)).collect();
    let with_cos = exps.iter().filter(|&&e| e != 0).count();
    if with_cos == 0 {
        return Vec::new();
    }
    let mut buckets = Buckets::with_room(with_cos, n);
    for (j, &e) in exps.iter().enumerate() {
        if e != 0 {
            buckets.insert(hashes[at(j)].wrapping_sub(factor_hash(cos, e)), j);
        }
    }
    for (j, &e) in exps.iter().enumerate() {
        if e == 0 {
            buckets.join(hashes[at(j)], j);
        }
    }
    let mut out: Vec<Chain> = Vec::new();
    for mut bucket in buckets.shared() {
        while bucket.len() > 1 {
            let first = at(bucket[0]);
            let (same, other): (SmallVec<[usize; 4]>, SmallVec<[usize; 4]>) = bucket
                .into_iter()
                .partition(|&j| same_rest(&ts[at(j)].0, &ts[first].0, cos));
            if same.len() > 1 {
                let m = &ts[first].0;
                let rest = m.without(cos, m.exponent(cos));
                let chain = same.iter().map(|&j| (exps[j], at(j))).collect();
                out.push((rest, chain));
            }
            bucket = other;
        }
    }
    for (_, c) in &mut out {
        c.sort_unstable();
        // Equal monomials: one term (a zero sum keeps a zero coefficient,
        // removed with the other zeros by `add_equal_monomials`).
        let mut k = 1;
        while k < c.len() {
            if c[k].0 == c[k - 1].0 {
                let extra = std::mem::replace(&mut ts[c[k].1].1, Rational::ZERO);
                let first = &mut ts[c[k - 1].1].1;
                *first = &*first + &extra;
                c.remove(k);
            } else {
                k += 1;
            }
        }
    }
    by_first_term(out)
}

/// Chains in the order of their first terms (distinct: a term is in one
/// chain at most), found by sorting those indices, not by moving the
/// chains at every step of a sort.
fn by_first_term(out: Vec<Chain>) -> Vec<Chain> {
    let mut order: Vec<(usize, usize)> = out
        .iter()
        .enumerate()
        .map(|(k, (_, c))| (c[0].1, k))
        .collect();
    order.sort_unstable();
    let mut slots: Vec<Option<Chain>> = out.into_iter().map(Some).collect();
    order
        .into_iter()
        .map(|(_, k)| slots[k].take().expect("each chain once"))
        .collect()
}

/// The exponent of `a` in `m` (0 when absent), by bisection: the factors
/// are sorted by atom.
fn exponent(m: &Monomial, a: Atom) -> i32 {
    let fs = m.factors();
    fs.binary_search_by(|f| f.0.cmp(&a)).map_or(0, |k| fs[k].1)
}

/// What [`factor_sin_squares`] rewrote: for each term before it, its
/// index after (`None`: removed); the terms it added are the last
/// `added` of the terms.
struct Rewrite {
    moved: Vec<Option<usize>>,
    added: usize,
}

/// The chains of `cos` after [`factor_sin_squares`] rewrote some of
/// `before` (the chains it was given), found without searching every term
/// again. A rewritten chain's terms are gone; each new term is `X sin²ᵏ θ
/// cosᵉ θ`, so a chain it belongs to has a rest whose power of sin θ is
/// one of the new terms'. The terms with such a power of sin θ are chained
/// again ([`chains`] among them); every other chain has the terms it had
/// (none of them was removed or added), under their new indices. The same
/// chains, in the same order, as [`chains`] of all the terms, but for a
/// chain of zero coefficients only (terms added into an equal one by
/// [`chains`] before the rewrite, with nothing left to merge or rewrite;
/// debug builds check).
fn patched(
    ts: &mut Terms,
    hashes: &[u64],
    before: Vec<Chain>,
    rewrite: &Rewrite,
    cos: Atom,
    sin: Atom,
) -> Vec<Chain> {
    let mut powers: SmallVec<[i32; 4]> = ts[ts.len() - rewrite.added..]
        .iter()
        .map(|t| exponent(&t.0, sin))
        .collect();
    powers.sort_unstable();
    powers.dedup();
    let again: Vec<usize> = (0..ts.len())
        .filter(|&i| powers.contains(&exponent(&ts[i].0, sin)))
        .collect();
    let mut out = chains(ts, hashes, cos, Some(&again));
    for (rest, mut chain) in before {
        if powers.contains(&exponent(&rest, sin)) {
            continue;
        }
        // A chain rewritten is gone (all its terms were removed); any
        // other has all its terms still.
        let mut kept = true;
        for c in &mut chain {
            match rewrite.moved[c.1] {
                Some(i) => c.1 = i,
                None => kept = false,
            }
        }
        if kept {
            out.push((rest, chain));
        }
    }
    by_first_term(out)
}

/// An empty slot of [`Buckets`], the end of a term list.
const NONE: u32 = u32::MAX;

/// Terms grouped by a 64-bit key (the hash of each term's rest): an
/// open-addressed table of the keys, each slot with the list of its terms
/// threaded through `next`. Flat arrays and no allocation per key:
/// [`chains`] groups every term of a result once or twice per angle.
struct Buckets {
    /// Per slot: its key.
    keys: Vec<u64>,
    /// Per slot: the term added last (`NONE`: an empty slot).
    heads: Vec<u32>,
    /// Per slot: how many terms it has.
    counts: Vec<u32>,
    /// Per term: the term added to its slot before it (`NONE`: the first).
    next: Vec<u32>,
}

impl Buckets {
    /// Room for up to `keys` distinct keys over the terms `0..terms`, the
    /// table at most half full (a probe always ends on an empty slot).
    fn with_room(keys: usize, terms: usize) -> Buckets {
        let slots = (2 * keys).next_power_of_two().max(16);
        Buckets {
            keys: vec![0; slots],
            heads: vec![NONE; slots],
            counts: vec![0; slots],
            next: vec![NONE; terms],
        }
    }

    /// The slot of `key`: where it is, or the empty slot where it goes.
    fn slot(&self, key: u64) -> usize {
        let mask = self.heads.len() - 1;
        let mut s = (key ^ (key >> 32)) as usize & mask;
        while self.heads[s] != NONE && self.keys[s] != key {
            s = (s + 1) & mask;
        }
        s
    }

    /// Adds term `i` under `key`.
    fn insert(&mut self, key: u64, i: usize) {
        let s = self.slot(key);
        self.keys[s] = key;
        self.push(s, i);
    }

    /// Adds term `i` under `key` when some term is there already.
    fn join(&mut self, key: u64, i: usize) {
        let s = self.slot(key);
        if self.heads[s] != NONE {
            self.push(s, i);
        }
    }

    fn push(&mut self, s: usize, i: usize) {
        self.next[i] = self.heads[s];
        self.heads[s] = i as u32;
        self.counts[s] += 1;
    }

    /// The terms of each key that has two or more.
    fn shared(&self) -> impl Iterator<Item = SmallVec<[usize; 4]>> + '_ {
        (0..self.heads.len())
            .filter(|&s| self.counts[s] > 1)
            .map(|s| {
                let mut terms = SmallVec::new();
                let mut i = self.heads[s];
                while i != NONE {
                    terms.push(i as usize);
                    i = self.next[i as usize];
                }
                terms
            })
    }
}

/// A hash of `m`: the sum of its factors' hashes, so that the hash of `m`
/// without one factor is the difference (`chains` keys every term by its
/// rest without cos θ, for each angle in turn).
fn monomial_hash(m: &Monomial) -> u64 {
    m.factors()
        .iter()
        .fold(0u64, |h, &(a, e)| h.wrapping_add(factor_hash(a, e)))
}

/// A hash of one factor `a^e` (splitmix64 of the atom's id and exponent).
fn factor_hash(a: Atom, e: i32) -> u64 {
    let mut z =
        ((u64::from(a.id()) << 32) | u64::from(e as u32)).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Whether `a` and `b` agree but for their powers of `cos`.
fn same_rest(a: &Monomial, b: &Monomial, cos: Atom) -> bool {
    let x = a.factors().iter().filter(|f| f.0 != cos);
    let y = b.factors().iter().filter(|f| f.0 != cos);
    x.eq(y)
}

/// Each chain as a polynomial P(cos) (exponent → coefficient), divided by
/// (1 − cos²) as often as that leaves the fewest terms (fewer than
/// before). What was rewritten, when a chain was.
fn factor_sin_squares(
    ts: &mut Terms,
    hashes: &mut Vec<u64>,
    chains: &[Chain],
    cos: Atom,
    sin: Atom,
) -> Option<Rewrite> {
    let mut removed: Vec<usize> = Vec::new();
    let mut added: Terms = Vec::new();
    for (rest, chain) in chains {
        // (1 − cos²) divides P only where P(1) = P(−1) = 0: two sums tell
        // most chains apart without the division.
        let (mut at_one, mut at_minus_one) = (Rational::ZERO, Rational::ZERO);
        for &(e, i) in chain {
            let c = &ts[i].1;
            at_one = &at_one + c;
            at_minus_one = if e.rem_euclid(2) == 0 {
                &at_minus_one + c
            } else {
                &at_minus_one - c
            };
        }
        if !at_one.is_zero() || !at_minus_one.is_zero() {
            continue;
        }
        let p: BTreeMap<i32, Rational> = chain
            .iter()
            .filter(|&&(_, i)| !ts[i].1.is_zero())
            .map(|&(e, i)| (e, ts[i].1.clone()))
            .collect();
        let mut best = (0, None);
        let mut q = p.clone();
        let mut k = 0;
        let mut fewest = p.len();
        while let Some(next) = divide_one_minus_square(&q) {
            k += 1;
            if next.len() < fewest {
                fewest = next.len();
                best = (k, Some(next.clone()));
            }
            q = next;
        }
        let (k, Some(q)) = best else { continue };
        removed.extend(chain.iter().map(|&(_, i)| i));
        let rest = rest.mul(&Monomial::atom(sin, 2 * k));
        added.extend(
            q.into_iter()
                .map(|(e, c)| (rest.mul(&Monomial::atom(cos, e)), c)),
        );
    }
    if removed.is_empty() {
        return None;
    }
    let moved = remove_indices(ts, hashes, &removed);
    hashes.extend(added.iter().map(|t| monomial_hash(&t.0)));
    let added_len = added.len();
    ts.extend(added);
    Some(Rewrite {
        moved,
        added: added_len,
    })
}

/// `p / (1 − x²)` when it divides exactly (Laurent exponents allowed).
fn divide_one_minus_square(p: &BTreeMap<i32, Rational>) -> Option<BTreeMap<i32, Rational>> {
    let low = *p.keys().next()?;
    let mut r = p.clone();
    let mut q = BTreeMap::new();
    // Long division from the top: a xⁿ = (1 − x²)(−a xⁿ⁻²) + a xⁿ⁻².
    while let Some((&n, a)) = r.iter().next_back() {
        if n < low + 2 {
            return None;
        }
        let a = a.clone();
        r.remove(&n);
        q.insert(n - 2, -&a);
        let s = &r.get(&(n - 2)).cloned().unwrap_or(Rational::ZERO) + &a;
        if s.is_zero() {
            r.remove(&(n - 2));
        } else {
            r.insert(n - 2, s);
        }
    }
    Some(q)
}

/// A pair `X cosⁿ θ − X cosⁿ⁺² θ` becomes the single term
/// `X cosⁿ θ sin² θ` (n of any sign); in a chain of one X the pairs are
/// taken from the lowest power up, each term in one pair at most. True
/// when a pair was merged.
fn merge_pairs(
    ts: &mut Terms,
    hashes: &mut Vec<u64>,
    chains: &[Chain],
    cos: Atom,
    sin: Atom,
) -> bool {
    let mut removed: Vec<usize> = Vec::new();
    for (rest, chain) in chains {
        let mut used: SmallVec<[bool; 4]> = SmallVec::from_elem(false, chain.len());
        for b in 0..chain.len() {
            let (e, k) = chain[b];
            if e == 0 || used[b] {
                continue;
            }
            let Some(a) = chain[..b].iter().rposition(|&(x, _)| x == e - 2) else {
                continue;
            };
            let j = chain[a].1;
            if used[a] || ts[k].1.is_zero() || !(&ts[j].1 + &ts[k].1).is_zero() {
                continue;
            }
            ts[j].0 = rest.mul(&Monomial::from_factors([(cos, e - 2), (sin, 2)]));
            hashes[j] = monomial_hash(&ts[j].0);
            used[a] = true;
            used[b] = true;
            removed.push(k);
        }
    }
    if removed.is_empty() {
        return false;
    }
    remove_indices(ts, hashes, &removed);
    true
}

/// Removes the terms at `indices` (any order, no repeats), and their
/// hashes: for each term before, its index after (`None`: removed).
fn remove_indices(ts: &mut Terms, hashes: &mut Vec<u64>, indices: &[usize]) -> Vec<Option<usize>> {
    let mut moved: Vec<Option<usize>> = vec![Some(0); ts.len()];
    for &i in indices {
        moved[i] = None;
    }
    let mut kept = 0;
    for m in &mut moved {
        if m.is_some() {
            *m = Some(kept);
            kept += 1;
        }
    }
    let mut k = 0;
    ts.retain(|_| {
        k += 1;
        moved[k - 1].is_some()
    });
    let mut k = 0;
    hashes.retain(|_| {
        k += 1;
        moved[k - 1].is_some()
    });
    moved
}

/// Adds the coefficients of equal monomials into the first of them and
/// drops zero coefficients, keeping the order of first appearance.
fn add_equal_monomials(ts: &mut Terms) {
    let mut first: FxHashMap<&Monomial, usize> =
        FxHashMap::with_capacity_and_hasher(ts.len(), Default::default());
    let mut moves: Vec<(usize, usize)> = Vec::new();
    for (i, (m, _)) in ts.iter().enumerate() {
        match first.get(m) {
            Some(&j) => moves.push((i, j)),
            None => {
                first.insert(m, i);
            }
        }
    }
    drop(first);
    for (i, j) in moves {
        let extra = std::mem::replace(&mut ts[i].1, Rational::ZERO);
        ts[j].1 = &ts[j].1 + &extra;
    }
    ts.retain(|(_, c)| !c.is_zero());
}
