//! Compiling polynomials to a [`Tape`](super::Tape): atoms to input
//! slots, known atoms folded into the coefficients, equal outputs
//! aliased, common factors taken out, powers and shared prefixes to
//! instructions, and the outputs classed by their number of terms.

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::poly::Poly;
// The compiler's maps are looked up, never iterated: Fx (an atom is a
// small integer; SipHash was half of compiling the bicycle's steps).
use rustc_hash::FxHashMap;

use super::{Gather, Input, Ops, Outputs, Paired, Sum, Tape, Term, WIDTH};

/// The slot of `a^e` (`e ≠ 0`), emitting the products (and reciprocal)
/// it needs once: `x⁵ = (x²)² · x`, `x⁻² = (1/x)²`.
fn power_slot(
    a: Atom,
    e: i32,
    atom_slot: &FxHashMap<Atom, u32>,
    powers: &mut FxHashMap<(Atom, i32), u32>,
    ops: &mut Ops,
    next: &mut u32,
) -> u32 {
    if e == 1 {
        return atom_slot[&a];
    }
    if let Some(&s) = powers.get(&(a, e)) {
        return s;
    }
    let s = if e == -1 {
        ops.recips.push((*next, atom_slot[&a]));
        *next += 1;
        *next - 1
    } else if e % 2 == 0 {
        let h = power_slot(a, e / 2, atom_slot, powers, ops, next);
        emit_mul(ops, next, h, h)
    } else {
        let unit = e.signum();
        let p = power_slot(a, e - unit, atom_slot, powers, ops, next);
        let one = power_slot(a, unit, atom_slot, powers, ops, next);
        emit_mul(ops, next, p, one)
    };
    powers.insert((a, e), s);
    s
}

/// The value `known` gives `a`; for a sum of constants, its terms'
/// sum when `known` gives every atom of it.
fn known_value(a: Atom, known: &mut dyn FnMut(Atom) -> Option<f64>) -> Option<f64> {
    match a.kind() {
        AtomKind::Sum { sum, .. } => {
            let mut all = true;
            let v = sum.eval(&mut |b| {
                known(b).unwrap_or_else(|| {
                    all = false;
                    f64::NAN
                })
            });
            all.then_some(v)
        }
        _ => known(a),
    }
}

fn emit_mul(ops: &mut Ops, next: &mut u32, a: u32, b: u32) -> u32 {
    ops.muls.push([*next, a, b]);
    *next += 1;
    *next - 1
}

impl Outputs {
    fn of(sums: &[Sum], terms: &[Term], zeros: Vec<u32>) -> Outputs {
        let (mut ones, mut twos, mut threes, mut longer) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for s in sums {
            let t = &terms[s.start as usize..s.end as usize];
            match *t {
                [a] => ones.push((s.out, a.coef, s.scale)),
                [a, b] => twos.push((s.out, s.scale, [a, b])),
                [a, b, c] => threes.push((s.out, s.scale, [a, b, c])),
                _ => longer.push(*s),
            }
        }
        Outputs {
            zeros,
            ones: Paired::of(&ones),
            twos: Paired::of(&twos),
            threes: Paired::of(&threes),
            longer,
        }
    }
}

/// A monomial's factors left after folding the known atoms, and its
/// coefficient.
type FoldedTerm = (Vec<(Atom, i32)>, f64);

/// Takes out of `terms` (the terms of one output) the factors common to
/// all of them, and returns those: each atom every term has with an
/// exponent of the same sign, to the smallest such power (`x²y + x³/z` →
/// `x²`; `θ̇/sin θ` out of `a ψ̇ θ̇/sin θ + b φ̇ θ̇ cos θ/sin θ`). A
/// single term gives all its factors (what is left is its coefficient):
/// its product is a slot, shared with equal prefixes, and the term sets
/// no width for the others (`I φ̇ θ̇ sin θ` made the heavy top's mass
/// matrix three factors wide). The output is then the product
/// of the common factors times the sum of what is left: fewer products
/// per term, and other bits than multiplying every term out, within the
/// same bound (a few ulps of `Σ |terms|`).
fn take_common(terms: &mut [FoldedTerm]) -> Vec<(Atom, i32)> {
    let [(first, _), rest @ ..] = terms else {
        return Vec::new();
    };
    if rest.is_empty() {
        return std::mem::take(first);
    }
    let mut common = first.clone();
    for (m, _) in rest {
        common.retain_mut(|(a, e)| match m.iter().find(|(b, _)| b == a) {
            Some(&(_, f)) if f.signum() == e.signum() => {
                *e = if *e > 0 { (*e).min(f) } else { (*e).max(f) };
                true
            }
            _ => false,
        });
        if common.is_empty() {
            return common;
        }
    }
    for (m, _) in terms.iter_mut() {
        m.retain_mut(|(a, e)| match common.iter().find(|(b, _)| b == a) {
            Some(&(_, c)) => {
                *e -= c;
                *e != 0
            }
            None => true,
        });
    }
    common
}

/// # Construction
impl Tape {
    /// Compiles `polys`; output `k` of [`Tape::eval`] is `polys[k]`.
    pub fn compile(polys: &[Poly]) -> Tape {
        Tape::compile_with(polys, &mut |_| None)
    }

    /// Compiles `polys` with the atoms that `known` gives a value fixed for
    /// good (the constants of a model): their powers are multiplied into
    /// the coefficients now, they are no inputs, and terms left with the
    /// same monomial are merged. `m g l / I′ · sin θ` costs one product per
    /// evaluation, not a reciprocal power and three products.
    ///
    /// An output equal to an earlier one (a symmetric mass matrix's
    /// M_ji = M_ij) is computed once and copied. The factors common to all
    /// the terms of an output are multiplied once, after its sum (see
    /// `take_common`).
    pub fn compile_with(polys: &[Poly], known: &mut dyn FnMut(Atom) -> Option<f64>) -> Tape {
        let mut value: FxHashMap<Atom, Option<f64>> = FxHashMap::default();
        let mut first: FxHashMap<&Poly, usize> = FxHashMap::default();
        let mut aliases = Vec::new();
        for (k, p) in polys.iter().enumerate() {
            match first.get(p) {
                Some(&j) if !p.is_zero() => aliases.push((k, j)),
                Some(_) => {}
                None => {
                    first.insert(p, k);
                }
            }
        }
        let mut aliased = vec![false; polys.len()];
        for &(k, _) in &aliases {
            aliased[k] = true;
        }
        let mut folded: Vec<Vec<FoldedTerm>> = polys
            .iter()
            .enumerate()
            .map(|(k, p)| {
                if aliased[k] {
                    return Vec::new();
                }
                let mut out: Vec<FoldedTerm> = Vec::new();
                let mut index: FxHashMap<Vec<(Atom, i32)>, usize> = FxHashMap::default();
                for (m, c) in p.terms() {
                    let mut coef = c.to_f64();
                    let mut rest = Vec::new();
                    for &(a, e) in m.factors() {
                        match *value.entry(a).or_insert_with(|| known_value(a, known)) {
                            Some(v) => coef *= v.powi(e),
                            None => rest.push((a, e)),
                        }
                    }
                    match index.get(&rest) {
                        Some(&k) => out[k].1 += coef,
                        None => {
                            index.insert(rest.clone(), out.len());
                            out.push((rest, coef));
                        }
                    }
                }
                out
            })
            .collect();
        let commons: Vec<Vec<(Atom, i32)>> = folded.iter_mut().map(|p| take_common(p)).collect();
        let mut atoms: Vec<Atom> = Vec::new();
        let mut atom_slot: FxHashMap<Atom, u32> = FxHashMap::default();
        for (p, common) in folded.iter().zip(&commons) {
            for m in std::iter::once(common).chain(p.iter().map(|(m, _)| m)) {
                for &(a, _) in m {
                    atom_slot.entry(a).or_insert_with(|| {
                        atoms.push(a);
                        (atoms.len() - 1) as u32
                    });
                }
            }
        }
        let one = atoms.len() as u32;
        let mut next = one + 1;
        let mut ops = Ops::default();
        let mut powers: FxHashMap<(Atom, i32), u32> = FxHashMap::default();
        let mut prefixes: FxHashMap<Vec<(Atom, i32)>, u32> = FxHashMap::default();
        // How many terms share each prefix: only a shared one is stored in
        // a slot; a term's own factors are multiplied in a register (a
        // chain of stored products is a chain of store-to-load latencies).
        let mut uses: FxHashMap<&[(Atom, i32)], usize> = FxHashMap::default();
        for p in &folded {
            for (factors, _) in p {
                for j in 0..factors.len() {
                    *uses.entry(&factors[..=j]).or_insert(0) += 1;
                }
            }
        }
        let mut terms = Vec::new();
        let mut width = 1;
        let (mut sums, mut zeros) = (Vec::new(), Vec::new());
        for (k, (p, common)) in folded.iter().zip(&commons).enumerate() {
            // The product of the common factors, a slot (shared with an
            // equal prefix or common product elsewhere).
            let mut scale = one;
            for j in 0..common.len() {
                let key = &common[..=j];
                if let Some(&s) = prefixes.get(key) {
                    scale = s;
                    continue;
                }
                let (a, e) = common[j];
                let pw = power_slot(a, e, &atom_slot, &mut powers, &mut ops, &mut next);
                let s = if j == 0 {
                    pw
                } else {
                    emit_mul(&mut ops, &mut next, scale, pw)
                };
                prefixes.insert(key.to_vec(), s);
                scale = s;
            }
            let start = terms.len() as u32;
            for (factors, c) in p {
                let mut shared = (0..factors.len())
                    .rev()
                    .find(|&j| j > 0 && uses[&factors[..=j]] > 1)
                    .map_or(0, |j| j + 1);
                // A term longer than the register width stores a prefix
                // (a slot and at most WIDTH − 1 factors are left).
                if factors.len() > WIDTH && factors.len() - shared + usize::from(shared > 0) > WIDTH
                {
                    shared = factors.len() - (WIDTH - 1);
                }
                let mut acc: Option<u32> = None;
                for (j, &(a, e)) in factors[..shared].iter().enumerate() {
                    let key = &factors[..=j];
                    if let Some(&s) = prefixes.get(key) {
                        acc = Some(s);
                        continue;
                    }
                    let pw = power_slot(a, e, &atom_slot, &mut powers, &mut ops, &mut next);
                    let s = match acc {
                        None => pw,
                        Some(prev) => emit_mul(&mut ops, &mut next, prev, pw),
                    };
                    prefixes.insert(key.to_vec(), s);
                    acc = Some(s);
                }
                let mut slots = [one; WIDTH];
                let own = factors[shared..]
                    .iter()
                    .map(|&(a, e)| power_slot(a, e, &atom_slot, &mut powers, &mut ops, &mut next));
                for (k, s) in acc.into_iter().chain(own).enumerate() {
                    slots[k] = s;
                    width = width.max(k + 1);
                }
                terms.push(Term {
                    coef: *c,
                    factors: slots,
                });
            }
            let end = terms.len() as u32;
            if end > start {
                sums.push(Sum {
                    out: k as u32,
                    scale,
                    start,
                    end,
                });
            } else if !aliased[k] {
                zeros.push(k as u32);
            }
        }
        let mut tape = Tape {
            atoms,
            ops,
            sums: Outputs::of(&sums, &terms, zeros),
            terms,
            width,
            outputs: polys.len(),
            aliases,
            slots: next as usize,
            gather: Gather::default(),
        };
        tape.plan_inputs(|_| Input::Given);
        // The evaluation reads and writes slots and outputs unchecked, in
        // a buffer on the stack it does not clear.
        assert!(tape.indices_in_bounds(), "a tape's indices are in bounds");
        assert!(
            tape.writes_before_reads(),
            "a tape writes each slot before reading it"
        );
        tape
    }

    /// Every slot index of the instructions, terms and scales `i`
    /// replaced by `f(i)` (a permutation of the inputs, in
    /// [`Tape::plan_inputs`]).
    pub(super) fn renumber(&mut self, f: impl Fn(u32) -> u32) {
        for (dst, src) in &mut self.ops.recips {
            (*dst, *src) = (f(*dst), f(*src));
        }
        for i in self.ops.muls.iter_mut().flatten() {
            *i = f(*i);
        }
        let term = |t: &mut Term| t.factors.iter_mut().for_each(|i| *i = f(*i));
        self.terms.iter_mut().for_each(term);
        let o = &mut self.sums;
        for (_, _, scale) in o.ones.iter_mut() {
            *scale = f(*scale);
        }
        for (_, scale, t) in o.twos.iter_mut() {
            *scale = f(*scale);
            t.iter_mut().for_each(term);
        }
        for (_, scale, t) in o.threes.iter_mut() {
            *scale = f(*scale);
            t.iter_mut().for_each(term);
        }
        for r in &mut o.longer {
            r.scale = f(r.scale);
        }
    }

    /// Whether every slot an instruction, a term or a scale reads is an
    /// input (each written by the gathering, [`Tape::plan_inputs`]), the
    /// slot of 1, or the destination of an instruction run before the
    /// read (the reciprocals, then the products in order; the terms
    /// after them all): what lets [`Tape::eval_at`] leave its buffer on
    /// the stack uninitialised. Its indices are in bounds
    /// ([`Tape::indices_in_bounds`]).
    fn writes_before_reads(&self) -> bool {
        let mut written = vec![false; self.slots];
        written[..=self.atoms.len()].fill(true);
        for &(dst, src) in &self.ops.recips {
            if !written[src as usize] {
                return false;
            }
            written[dst as usize] = true;
        }
        for &[dst, a, b] in &self.ops.muls {
            if !(written[a as usize] && written[b as usize]) {
                return false;
            }
            written[dst as usize] = true;
        }
        let read = |i: &u32| written[*i as usize];
        let term = |t: &Term| t.factors.iter().all(read);
        let o = &self.sums;
        o.ones.iter().all(|(_, _, f)| read(f))
            && o.twos.iter().all(|(_, f, t)| read(f) && t.iter().all(term))
            && o.threes
                .iter()
                .all(|(_, f, t)| read(f) && t.iter().all(term))
            && o.longer.iter().all(|r| read(&r.scale))
            && self.terms.iter().all(term)
    }

    /// Whether every slot an instruction, a term or a scale reads or
    /// writes is below `slots`, and every output index (an alias's too)
    /// below `outputs`:
    /// what lets the evaluation index its buffers unchecked.
    fn indices_in_bounds(&self) -> bool {
        let slot = |i: u32| (i as usize) < self.slots;
        let output = |k: u32| (k as usize) < self.outputs;
        let term = |t: &Term| t.factors.iter().all(|&i| slot(i));
        let o = &self.sums;
        slot(self.atoms.len() as u32)
            && self.ops.recips.iter().all(|&(d, s)| slot(d) && slot(s))
            && self.ops.muls.iter().flatten().all(|&i| slot(i))
            && self
                .aliases
                .iter()
                .all(|&(k, j)| k < self.outputs && j < self.outputs)
            && o.zeros.iter().all(|&k| output(k))
            && o.ones.iter().all(|&(k, _, f)| output(k) && slot(f))
            && o.twos
                .iter()
                .all(|(k, f, t)| output(*k) && slot(*f) && t.iter().all(term))
            && o.threes
                .iter()
                .all(|(k, f, t)| output(*k) && slot(*f) && t.iter().all(term))
            && o.longer.iter().all(|r| {
                output(r.out)
                    && slot(r.scale)
                    && r.start <= r.end
                    && (r.end as usize) <= self.terms.len()
                    && self.terms[r.start as usize..r.end as usize]
                        .iter()
                        .all(term)
            })
    }
}
