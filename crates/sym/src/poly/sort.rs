//! Sorting a list of terms by monomial, the order of a [`Poly`](super::Poly)'s
//! terms, through one integer key per term.
//!
//! Comparing two monomials walks their factors pair by pair, and a term
//! (monomial and coefficient) is over a hundred bytes to move: sorting the
//! terms themselves (chain-8's Ḣ, 42,000 terms per component) spent most
//! of its time in those comparisons and moves. Here each term gets a
//! `u128` key that orders as its monomial does over the leading factors,
//! with the term's index in its low bits; the keys are sorted as plain
//! integers, a run of keys with the same leading factors is put in order
//! by comparing the monomials (only when some monomial is longer than a
//! key holds), and the terms are then moved once along the permutation's
//! cycles.
//!
//! The key of a monomial packs its first factors, each as (the atom's rank
//! among the atoms of the list, the exponent less the list's smallest):
//! ranks are in atom order and start at 1, so an absent factor (0) sorts
//! before any present one, as a shorter monomial sorts before a longer one
//! with the same leading factors. The field widths are the fewest bits
//! that hold the list's ranks and exponent range, so the key is exact for
//! a monomial of up to `(128 − index bits) / width` factors.

use super::Monomial;
use crate::rational::Rational;

/// Below this many terms the comparison sort is cheaper than the keys.
const KEYED_FROM: usize = 64;

/// Sorts `terms` by monomial (the monomials distinct or not: equal ones
/// end up adjacent, in no particular order).
pub(super) fn sort_terms(terms: &mut [(Monomial, Rational)]) {
    let Some(code) = (terms.len() >= KEYED_FROM)
        .then(|| Code::of(terms))
        .flatten()
    else {
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        return;
    };
    let mut keys: Vec<u128> = terms
        .iter()
        .enumerate()
        .map(|(i, t)| code.key(&t.0) | i as u128)
        .collect();
    keys.sort_unstable();
    let index = |k: u128| (k & code.index_mask) as usize;
    if code.longer {
        // Keys equal but for the index: the same leading factors, in
        // index order; the rest of the monomials decides.
        let mut run = 0;
        for k in 1..=keys.len() {
            if k == keys.len() || keys[k] >> code.index_bits != keys[run] >> code.index_bits {
                if k - run > 1 {
                    keys[run..k]
                        .sort_unstable_by(|a, b| terms[index(*a)].0.cmp(&terms[index(*b)].0));
                }
                run = k;
            }
        }
    }
    let mut from: Vec<u32> = keys.into_iter().map(|k| index(k) as u32).collect();
    permute(terms, &mut from);
}

/// Puts `terms[from[k]]` at place `k` for every `k`, moving each term
/// along its cycle of the permutation; `from` is used up (each place is
/// marked done by pointing at itself).
fn permute<T>(terms: &mut [T], from: &mut [u32]) {
    for start in 0..from.len() {
        let mut k = start;
        // Place k holds the term that belongs further along the cycle
        // (the one first at `start`); the one from `from[k]` comes in.
        loop {
            let src = from[k] as usize;
            from[k] = k as u32;
            if src == start || src == k {
                break;
            }
            terms.swap(k, src);
            k = src;
        }
    }
}

/// The packing of one term list's monomials into keys: the leading
/// factors' fields above the term's index.
struct Code {
    /// The rank (from 1, in atom order) of each atom id of the list.
    rank: Vec<u32>,
    /// Bits of a factor's exponent field, and its smallest exponent.
    exp_bits: u32,
    min_exp: i64,
    /// Bits of one factor, and how many factors a key holds.
    width: u32,
    factors: usize,
    /// Bits of the index (the low bits of a key), and their mask.
    index_bits: u32,
    index_mask: u128,
    /// Whether some monomial has more factors than a key holds.
    longer: bool,
}

impl Code {
    /// The code of a list's monomials; `None` when its atom ids are too
    /// sparse for a table indexed by id, or a factor's field too wide (the
    /// comparison sort is used).
    fn of(terms: &[(Monomial, Rational)]) -> Option<Code> {
        let (mut max_id, mut min_exp, mut max_exp) = (0u32, i64::MAX, i64::MIN);
        let (mut count, mut max_len) = (0usize, 0usize);
        for (m, _) in terms {
            let fs = m.factors();
            max_len = max_len.max(fs.len());
            count += fs.len();
            for &(a, e) in fs {
                max_id = max_id.max(a.id());
                min_exp = min_exp.min(i64::from(e));
                max_exp = max_exp.max(i64::from(e));
            }
        }
        if count == 0 || max_id as usize > 4 * count + 4096 {
            return None;
        }
        let mut rank = vec![0u32; max_id as usize + 1];
        for (m, _) in terms {
            for &(a, _) in m.factors() {
                rank[a.id() as usize] = 1;
            }
        }
        let mut atoms = 0;
        for r in rank.iter_mut().filter(|r| **r != 0) {
            atoms += 1;
            *r = atoms;
        }
        let bits = |n: u64| 64 - n.leading_zeros();
        let exp_bits = bits((max_exp - min_exp) as u64);
        let width = bits(u64::from(atoms)) + exp_bits;
        let index_bits = bits(terms.len() as u64 - 1);
        let factors = ((128 - index_bits) / width) as usize;
        (factors > 0).then(|| Code {
            rank,
            exp_bits,
            min_exp,
            width,
            factors,
            index_bits,
            index_mask: (1u128 << index_bits) - 1,
            longer: max_len > factors,
        })
    }

    /// The key of `m` with index 0: its first factors' (rank, exponent)
    /// fields, then zeros for the absent ones, then the index's bits.
    fn key(&self, m: &Monomial) -> u128 {
        let fs = m.factors();
        let n = fs.len().min(self.factors);
        let mut k: u128 = 0;
        for &(a, e) in &fs[..n] {
            let field = (u128::from(self.rank[a.id() as usize]) << self.exp_bits)
                | (i64::from(e) - self.min_exp) as u128;
            k = (k << self.width) | field;
        }
        // The shift reaches 128 only for the monomial 1, whose key is 0.
        k.checked_shl((self.factors - n) as u32 * self.width + self.index_bits)
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atom::Atom;
    use crate::poly::Exp;

    /// A deterministic stream of numbers (a fixed-seed LCG).
    struct Lcg(u64);
    impl Lcg {
        fn below(&mut self, n: u64) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 33) % n
        }
    }

    /// Random monomials over `atoms` with up to `max_len` factors and
    /// exponents in `lo..=hi`, sorted by key and by comparison alike.
    fn agrees(seed: u64, n: usize, atoms: &[Atom], max_len: u64, lo: Exp, hi: Exp) {
        let mut r = Lcg(seed);
        let terms: Vec<(Monomial, Rational)> = (0..n)
            .map(|i| {
                let len = r.below(max_len + 1);
                let m = Monomial::from_factors((0..len).map(|_| {
                    let a = atoms[r.below(atoms.len() as u64) as usize];
                    (a, lo + r.below((hi - lo) as u64 + 1) as Exp)
                }));
                (m, Rational::int(i as i64))
            })
            .collect();
        let mut keyed = terms.clone();
        sort_terms(&mut keyed);
        let mut plain = terms.clone();
        plain.sort_by(|a, b| a.0.cmp(&b.0));
        let monomials =
            |v: &[(Monomial, Rational)]| v.iter().map(|t| t.0.clone()).collect::<Vec<_>>();
        assert_eq!(monomials(&keyed), monomials(&plain), "seed {seed}");
        // Every term is kept, with its own coefficient.
        let mut coefs: Vec<i64> = keyed
            .iter()
            .map(|t| match t.1 {
                Rational::Small(n, 1) => n,
                _ => unreachable!(),
            })
            .collect();
        coefs.sort_unstable();
        assert!(coefs.iter().copied().eq(0..n as i64), "seed {seed}");
    }

    #[test]
    fn the_key_sorts_as_the_monomials_compare() {
        let few: Vec<Atom> = (0..5)
            .map(|i| Atom::constant(&format!("sort_a{i}")))
            .collect();
        let many: Vec<Atom> = (0..200)
            .map(|i| Atom::constant(&format!("sort_b{i}")))
            .collect();
        for seed in 0..20 {
            // Short monomials (exact keys), many repeats.
            agrees(seed, 500, &few, 3, 1, 2);
            // Long monomials over many atoms: keys hold only a prefix.
            agrees(seed, 400, &many, 14, -3, 3);
            // A wide exponent range: few factors per key, many ties.
            agrees(seed, 300, &few, 9, -1_000_000, 1_000_000);
            agrees(seed, 300, &few, 5, 1, 1);
        }
    }

    #[test]
    fn a_permutation_moves_every_term_once_to_its_place() {
        let mut r = Lcg(7);
        for n in [0usize, 1, 2, 3, 10, 100] {
            let mut from: Vec<u32> = (0..n as u32).collect();
            for i in (1..n).rev() {
                from.swap(i, r.below(i as u64 + 1) as usize);
            }
            let want: Vec<u32> = from.iter().map(|&i| i * 10).collect();
            let mut terms: Vec<u32> = (0..n as u32).map(|i| i * 10).collect();
            permute(&mut terms, &mut from.clone());
            assert_eq!(terms, want, "n = {n}");
        }
    }
}
