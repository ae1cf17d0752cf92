//! # A flat f64 instruction tape for the polynomials of `hdot-sym`
//!
//! [`Tape::compile`] turns one or several [`Poly`]s into a straight-line
//! program: each distinct atom is one input slot, each distinct power of an
//! atom is computed once (by products and at most one reciprocal), a prefix
//! of factors shared by several monomials is computed once into a slot
//! (the rest of a monomial is multiplied in a register), and each output is
//! accumulated with a compensated (Neumaier) sum. Atoms whose values are
//! fixed at compile time (a model's constants, [`Tape::compile_with`]) are
//! folded into the coefficients. Evaluating is then a loop over a few arrays
//! with no hashing and no allocation beyond one scratch buffer.
//!
//! ## Why hand-written
//!
//! The polynomials are `hdot-sym`'s own canonical form (interned atoms,
//! Laurent monomials in constants, exact rationals); no published crate
//! compiles *this* representation, and a general expression JIT would need
//! a translation layer larger than this module. [`Poly::eval`] stays the
//! slow reference the tests compare against.
//!
//! ## Example
//!
//! ```
//! use hdot_num::eval::Tape;
//! use hdot_sym::{Rational, atom::Atom, poly::{Monomial, Poly}};
//! let (x, y) = (Atom::constant("x"), Atom::constant("y"));
//! // 3 x² y − ½ y
//! let p = Poly::from_terms([
//!     (Monomial::from_factors([(x, 2), (y, 1)]), Rational::int(3)),
//!     (Monomial::atom(y, 1), Rational::new(-1, 2).unwrap()),
//! ]);
//! let tape = Tape::compile(&[p]);
//! let inputs: Vec<f64> = tape.atoms().iter().map(|&a| if a == x { 2.0 } else { 4.0 }).collect();
//! let mut out = [0.0];
//! tape.eval(&inputs, &mut out);
//! assert_eq!(out[0], 3.0 * 4.0 * 4.0 - 2.0);
//! ```

use std::collections::HashMap;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::poly::Poly;

/// One instruction; operands and destination are slot indices. Powers
/// are products (by squaring) of the atom or of its reciprocal: no call
/// to `powi` per evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    /// `slot[dst] = 1 / slot[src]`.
    Recip { dst: u32, src: u32 },
    /// `slot[dst] = slot[a] * slot[b]`.
    Mul { dst: u32, a: u32, b: u32 },
}

/// The slot of `a^e` (`e ≠ 0`), emitting the products (and reciprocal)
/// it needs once: `x⁵ = (x²)² · x`, `x⁻² = (1/x)²`.
fn power_slot(
    a: Atom,
    e: i32,
    atom_slot: &HashMap<Atom, u32>,
    powers: &mut HashMap<(Atom, i32), u32>,
    ops: &mut Vec<Op>,
    next: &mut u32,
) -> u32 {
    if e == 1 {
        return atom_slot[&a];
    }
    if let Some(&s) = powers.get(&(a, e)) {
        return s;
    }
    let s = if e == -1 {
        ops.push(Op::Recip {
            dst: *next,
            src: atom_slot[&a],
        });
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

fn emit_mul(ops: &mut Vec<Op>, next: &mut u32, a: u32, b: u32) -> u32 {
    ops.push(Op::Mul { dst: *next, a, b });
    *next += 1;
    *next - 1
}

/// The number of factors of a term multiplied in a register: every term
/// has exactly this many (padded with the slot holding 1, an exact
/// product), so evaluating a term is a fixed, branch-free product.
const WIDTH: usize = 4;

/// A term of an output: `coef · slot[f₀] · slot[f₁] · …`, the factors
/// being a prefix product shared with other terms (if any) and then the
/// powers of the term's own atoms, padded with [`Tape`]'s slot of 1.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Term {
    coef: f64,
    factors: [u32; WIDTH],
}

/// A monomial's factors left after folding the known atoms, and its
/// coefficient.
type FoldedTerm = (Vec<(Atom, i32)>, f64);

/// A compiled set of polynomials.
///
/// Invariant: slots `0..atoms.len()` are the inputs in [`Tape::atoms`]
/// order, slot `atoms.len()` holds 1 during an evaluation; every
/// instruction writes a slot above every slot it reads; the terms of
/// output `k` are `terms[ends[k-1]..ends[k]]`.
#[derive(Clone, Debug)]
pub struct Tape {
    atoms: Vec<Atom>,
    ops: Vec<Op>,
    terms: Vec<Term>,
    ends: Vec<usize>,
    slots: usize,
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
    pub fn compile_with(polys: &[Poly], known: &mut dyn FnMut(Atom) -> Option<f64>) -> Tape {
        let mut value: HashMap<Atom, Option<f64>> = HashMap::new();
        let folded: Vec<Vec<FoldedTerm>> = polys
            .iter()
            .map(|p| {
                let mut out: Vec<FoldedTerm> = Vec::new();
                let mut index: HashMap<Vec<(Atom, i32)>, usize> = HashMap::new();
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
        let mut atoms: Vec<Atom> = Vec::new();
        let mut atom_slot: HashMap<Atom, u32> = HashMap::new();
        for p in &folded {
            for (m, _) in p {
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
        let mut ops = Vec::new();
        let mut powers: HashMap<(Atom, i32), u32> = HashMap::new();
        let mut prefixes: HashMap<Vec<(Atom, i32)>, u32> = HashMap::new();
        // How many terms share each prefix: only a shared one is stored in
        // a slot; a term's own factors are multiplied in a register (a
        // chain of stored products is a chain of store-to-load latencies).
        let mut uses: HashMap<&[(Atom, i32)], usize> = HashMap::new();
        for p in &folded {
            for (factors, _) in p {
                for j in 0..factors.len() {
                    *uses.entry(&factors[..=j]).or_insert(0) += 1;
                }
            }
        }
        let mut terms = Vec::new();
        let mut ends = Vec::with_capacity(polys.len());
        for p in &folded {
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
                        Some(prev) => {
                            ops.push(Op::Mul {
                                dst: next,
                                a: prev,
                                b: pw,
                            });
                            next += 1;
                            next - 1
                        }
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
                }
                terms.push(Term {
                    coef: *c,
                    factors: slots,
                });
            }
            ends.push(terms.len());
        }
        Tape {
            atoms,
            ops,
            terms,
            ends,
            slots: next as usize,
        }
    }
}

/// # Access
impl Tape {
    /// The inputs the tape reads, in slot order.
    pub fn atoms(&self) -> &[Atom] {
        &self.atoms
    }

    /// The number of outputs.
    pub fn outputs(&self) -> usize {
        self.ends.len()
    }

    /// The number of instructions (powers and products).
    pub fn len(&self) -> usize {
        self.ops.len()
    }

    /// True when the tape has no instructions.
    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }
}

/// # Evaluation
impl Tape {
    /// Evaluates every output. `inputs[i]` is the value of `atoms()[i]`.
    ///
    /// # Panics
    /// When `inputs.len() != atoms().len()` or `out.len() != outputs()`.
    pub fn eval(&self, inputs: &[f64], out: &mut [f64]) {
        let mut scratch = Vec::new();
        self.eval_with(inputs, &mut scratch, out, false);
    }

    /// The sum of the magnitudes of the terms, `Σ |c · monomial|`, per
    /// output: the natural scale of the round-off in [`Tape::eval`].
    pub fn eval_abs(&self, inputs: &[f64], out: &mut [f64]) {
        let mut scratch = Vec::new();
        self.eval_with(inputs, &mut scratch, out, true);
    }

    /// [`Tape::eval`] (or, with `abs`, [`Tape::eval_abs`]) reusing `scratch`.
    pub fn eval_with(&self, inputs: &[f64], scratch: &mut Vec<f64>, out: &mut [f64], abs: bool) {
        assert_eq!(inputs.len(), self.atoms.len(), "one input per atom");
        scratch.clear();
        scratch.extend_from_slice(inputs);
        scratch.resize(self.slots, 0.0);
        self.eval_slots(scratch, out, abs);
    }

    /// The number of slots [`Tape::eval_slots`] needs.
    pub fn slots(&self) -> usize {
        self.slots
    }

    /// [`Tape::eval_with`] on a buffer the caller provides (on the stack,
    /// say) whose first `atoms().len()` entries hold the inputs; the rest
    /// is overwritten.
    ///
    /// # Panics
    /// When `slots.len() < self.slots()` or `out.len() != outputs()`.
    pub fn eval_slots(&self, slots: &mut [f64], out: &mut [f64], abs: bool) {
        assert_eq!(out.len(), self.ends.len(), "one output per polynomial");
        let scratch = &mut slots[..self.slots];
        scratch[self.atoms.len()] = 1.0;
        for op in &self.ops {
            match *op {
                Op::Recip { dst, src } => scratch[dst as usize] = 1.0 / scratch[src as usize],
                Op::Mul { dst, a, b } => {
                    scratch[dst as usize] = scratch[a as usize] * scratch[b as usize]
                }
            }
        }
        if abs {
            self.sum_terms::<true>(scratch, out);
        } else {
            self.sum_terms::<false>(scratch, out);
        }
    }

    /// Each output's terms, summed with an exact error term (Knuth's
    /// TwoSum: no branch; the same error Neumaier's comparison finds).
    fn sum_terms<const ABS: bool>(&self, s: &[f64], out: &mut [f64]) {
        let mut start = 0;
        for (k, &end) in self.ends.iter().enumerate() {
            let (mut sum, mut comp) = (0.0f64, 0.0f64);
            for t in &self.terms[start..end] {
                let [a, b, c, d] = t.factors;
                let mut v = t.coef * s[a as usize] * s[b as usize] * s[c as usize] * s[d as usize];
                if ABS {
                    v = v.abs();
                }
                let x = sum + v;
                let bv = x - sum;
                comp += (sum - (x - bv)) + (v - bv);
                sum = x;
            }
            out[k] = sum + comp;
            start = end;
        }
    }
}
