//! # A flat f64 instruction tape for the polynomials of `hdot-sym`
//!
//! [`Tape::compile`] turns one or several [`Poly`]s into a straight-line
//! program: each distinct atom is one input slot, each distinct power of an
//! atom is computed once, monomials that share a prefix of factors share
//! the partial product, and each output is accumulated with a compensated
//! (Neumaier) sum. Evaluating is then a loop over a few arrays with no
//! hashing and no allocation beyond one scratch buffer.
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
//! use hdot_sym::{atom::Atom, poly::{Monomial, Poly}, rational::Rational};
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

use hdot_sym::atom::Atom;
use hdot_sym::poly::Poly;

/// One instruction; operands and destination are slot indices.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    /// `slot[dst] = slot[src].powi(exp)`.
    Pow { dst: u32, src: u32, exp: i32 },
    /// `slot[dst] = slot[a] * slot[b]`.
    Mul { dst: u32, a: u32, b: u32 },
}

/// A term of an output: coefficient times a slot (`None` for the constant
/// monomial 1).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Term {
    slot: Option<u32>,
    coef: f64,
}

/// A compiled set of polynomials.
///
/// Invariant: slots `0..atoms.len()` are the inputs in [`Tape::atoms`]
/// order; every instruction writes a slot above every slot it reads; the
/// terms of output `k` are `terms[ends[k-1]..ends[k]]`.
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
        let mut atoms: Vec<Atom> = Vec::new();
        let mut atom_slot: HashMap<Atom, u32> = HashMap::new();
        for p in polys {
            for (m, _) in p.terms() {
                for &(a, _) in m.factors() {
                    atom_slot.entry(a).or_insert_with(|| {
                        atoms.push(a);
                        (atoms.len() - 1) as u32
                    });
                }
            }
        }
        let mut next = atoms.len() as u32;
        let mut ops = Vec::new();
        let mut powers: HashMap<(Atom, i32), u32> = HashMap::new();
        let mut prefixes: HashMap<Vec<(Atom, i32)>, u32> = HashMap::new();
        let mut terms = Vec::new();
        let mut ends = Vec::with_capacity(polys.len());
        for p in polys {
            for (m, c) in p.terms() {
                let factors = m.factors();
                let mut acc: Option<u32> = None;
                for (j, &(a, e)) in factors.iter().enumerate() {
                    let key = &factors[..=j];
                    if let Some(&s) = prefixes.get(key) {
                        acc = Some(s);
                        continue;
                    }
                    let pw = *powers.entry((a, e)).or_insert_with(|| {
                        let src = atom_slot[&a];
                        if e == 1 {
                            src
                        } else {
                            ops.push(Op::Pow {
                                dst: next,
                                src,
                                exp: e,
                            });
                            next += 1;
                            next - 1
                        }
                    });
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
                terms.push(Term {
                    slot: acc,
                    coef: c.to_f64(),
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
        assert_eq!(out.len(), self.ends.len(), "one output per polynomial");
        scratch.clear();
        scratch.extend_from_slice(inputs);
        scratch.resize(self.slots, 0.0);
        for op in &self.ops {
            match *op {
                Op::Pow { dst, src, exp } => {
                    scratch[dst as usize] = scratch[src as usize].powi(exp)
                }
                Op::Mul { dst, a, b } => {
                    scratch[dst as usize] = scratch[a as usize] * scratch[b as usize]
                }
            }
        }
        let mut start = 0;
        for (k, &end) in self.ends.iter().enumerate() {
            let (mut sum, mut comp) = (0.0f64, 0.0f64);
            for t in &self.terms[start..end] {
                let mut v = t.slot.map_or(t.coef, |s| t.coef * scratch[s as usize]);
                if abs {
                    v = v.abs();
                }
                let s = sum + v;
                comp += if sum.abs() >= v.abs() {
                    (sum - s) + v
                } else {
                    (v - s) + sum
                };
                sum = s;
            }
            out[k] = sum + comp;
            start = end;
        }
    }
}
