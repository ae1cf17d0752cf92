//! # A flat f64 instruction tape for the polynomials of `hdot-sym`
//!
//! [`Tape::compile`] turns one or several [`Poly`]s into a straight-line
//! program: each distinct atom is one input slot, each distinct power of an
//! atom is computed once (by products and at most one reciprocal), a prefix
//! of factors shared by several monomials is computed once into a slot
//! (the rest of a monomial is multiplied in a register), the factors common
//! to every term of an output are multiplied once after its sum, and each
//! output is accumulated with a compensated (Neumaier) sum. Atoms whose
//! values are fixed at compile time (a model's constants,
//! [`Tape::compile_with`]) are folded into the coefficients. Evaluating is
//! then a loop over a few arrays with no hashing and no allocation beyond
//! one scratch buffer.
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

use hdot_sym::atom::Atom;

mod compile;
mod evaluate;
mod lanes;

/// The instructions of a tape; operands and destinations are slot
/// indices. Powers are products (by squaring) of the atom or of its
/// reciprocal: no call to `powi` per evaluation. A reciprocal is only ever
/// of an input (one division per distinct denominator), so every
/// reciprocal is taken first and the products follow in one loop with no
/// dispatch per instruction.
#[derive(Clone, Debug, Default, PartialEq)]
struct Ops {
    /// `(dst, src)`: `slot[dst] = 1 / slot[src]`, `src` an input.
    recips: Vec<(u32, u32)>,
    /// `[dst, a, b]`: `slot[dst] = slot[a] * slot[b]`, in order.
    muls: Vec<[u32; 3]>,
}

/// The most factors of a term multiplied in a register. Every term of a
/// tape has the same number, the tape's width (at most this; padded with
/// the slot holding 1, an exact product), so evaluating a term is a fixed,
/// branch-free product.
const WIDTH: usize = 4;

/// A term of an output: `coef · slot[f₀] · slot[f₁] · …`, the factors
/// being a prefix product shared with other terms (if any) and then the
/// powers of the term's own atoms, padded with [`Tape`]'s slot of 1.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Term {
    coef: f64,
    factors: [u32; WIDTH],
}

/// Output `out` is `slot[scale]` (the factors common to its terms) times
/// the sum of `terms[start..end]` (at least one term).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sum {
    out: u32,
    scale: u32,
    start: u32,
    end: u32,
}

/// The outputs of a tape by their number of terms, known when compiled:
/// each class is summed by a loop of its own with no dispatch or slice
/// per output (a mass matrix has many outputs of one or two terms). The
/// outputs of one, two and three terms are taken two at a time, one in
/// each lane of a vector register ([`Paired`]). The sums of four terms or
/// more keep their terms in [`Tape`]'s `terms`.
#[derive(Clone, Debug, Default, PartialEq)]
struct Outputs {
    /// No terms: structurally zero.
    zeros: Vec<u32>,
    /// `(out, coef, scale)`: a single term, `coef · slot[scale]` (all its
    /// factors taken out).
    ones: Paired<(u32, f64, u32)>,
    /// `(out, scale, terms)`, as in [`Sum`].
    twos: Paired<(u32, u32, [Term; 2])>,
    threes: Paired<(u32, u32, [Term; 3])>,
    longer: Vec<Sum>,
}

/// The outputs of one class in pairs, evaluated together in the two lanes
/// of a vector register (`eval/lanes.rs`: the same operations on each
/// lane as on a scalar, so the same bits), and the last one alone when
/// their number is odd.
#[derive(Clone, Debug, PartialEq)]
struct Paired<T> {
    pairs: Vec<[T; 2]>,
    odd: Option<T>,
}

impl<T> Default for Paired<T> {
    fn default() -> Self {
        Paired {
            pairs: Vec::new(),
            odd: None,
        }
    }
}

impl<T: Copy> Paired<T> {
    /// `items` in pairs, in order.
    fn of(items: &[T]) -> Paired<T> {
        let mut chunks = items.chunks_exact(2);
        let pairs = chunks.by_ref().map(|c| [c[0], c[1]]).collect();
        Paired {
            pairs,
            odd: chunks.remainder().first().copied(),
        }
    }

    /// Every output of the class, in order.
    fn iter(&self) -> impl Iterator<Item = &T> {
        self.pairs.iter().flatten().chain(&self.odd)
    }

    fn iter_mut(&mut self) -> impl Iterator<Item = &mut T> {
        self.pairs.iter_mut().flatten().chain(&mut self.odd)
    }
}

/// A compiled set of polynomials.
///
/// Invariant: slots `0..atoms.len()` are the inputs in [`Tape::atoms`]
/// order, slot `atoms.len()` holds 1 during an evaluation; every
/// instruction writes a slot above every slot it reads, and every slot an
/// instruction, a term or a scale reads is an input, the slot of 1 or
/// written by an earlier instruction; the plan of the inputs writes each
/// input once; every term
/// multiplies `width` factors (its own, padded with the slot of 1); each
/// output is
/// either one of `outputs`' classes (a sum of four terms or more has its
/// terms in `terms[start..end]`), or in its `zeros` (no terms:
/// structurally zero), or in `aliases` as `(k, j)` (j < k): the same
/// polynomial as output j, copied from it.
#[derive(Clone, Debug)]
pub struct Tape {
    atoms: Vec<Atom>,
    ops: Ops,
    terms: Vec<Term>,
    width: usize,
    sums: Outputs,
    outputs: usize,
    aliases: Vec<(usize, usize)>,
    slots: usize,
    gather: Gather,
}

/// Where an input of a tape gets its value in [`Tape::eval_at`] (see
/// [`Tape::plan_inputs`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// Component `i` of the state vector.
    Component(usize),
    /// The sine of component `i`.
    Sin(usize),
    /// The cosine of component `i`.
    Cos(usize),
    /// Written by the caller's closure.
    Given,
}

/// How [`Tape::eval_at`] fills the inputs from a state vector, planned once:
/// runs of slots copied from runs of its components, and one `sin_cos` per
/// component whose sine and cosine are both read (one libm call instead of
/// two). No match on each input's source per evaluation.
#[derive(Clone, Debug, Default)]
struct Gather {
    runs: Vec<Run>,
    trig: Vec<Trig>,
    /// The [`Input::Given`] slots, set to 0 before the caller's closure
    /// writes them: with the runs and `trig`, every input is written
    /// once (the buffer on the stack is not cleared).
    given: Vec<u32>,
    /// One more than the largest component read: the shortest state.
    components: usize,
}

/// Slots `slot..slot + len` ← `x[i..i + len]`, copied two at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Run {
    slot: u32,
    i: u32,
    len: u32,
}

#[derive(Clone, Copy, Debug)]
enum Trig {
    /// `(sin slot, cos slot) ← sin_cos x[i]`.
    Both {
        i: u32,
        sin: u32,
        cos: u32,
    },
    Sin {
        i: u32,
        slot: u32,
    },
    Cos {
        i: u32,
        slot: u32,
    },
}

/// # Planning the inputs
impl Tape {
    /// Plans how [`Tape::eval_at`] fills each input slot: `input(a)` for
    /// each atom `a` of [`Tape::atoms`], called once per atom in that
    /// order. Until planned, every input is [`Input::Given`].
    ///
    /// The inputs are put in the order they are gathered in — the state's
    /// components by component, then the sines and cosines, then the given
    /// ones (each kind in the order it had) — so that components next to
    /// each other in the state are copied as a run: [`Tape::atoms`] is to
    /// be read after planning. The outputs are the same, to the bit.
    pub fn plan_inputs(&mut self, mut input: impl FnMut(Atom) -> Input) {
        let sources: Vec<Input> = self.atoms.iter().map(|&a| input(a)).collect();
        let rank = |s: Input| match s {
            Input::Component(i) => (0, i, false),
            Input::Sin(i) => (1, i, false),
            Input::Cos(i) => (1, i, true),
            Input::Given => (2, 0, false),
        };
        // `order[new] = old`; the sort is stable.
        let mut order: Vec<usize> = (0..sources.len()).collect();
        order.sort_by_key(|&k| rank(sources[k]));
        let mut slot_of = vec![0; order.len()];
        for (new, &old) in order.iter().enumerate() {
            slot_of[old] = new as u32;
        }
        let inputs = order.len() as u32;
        self.renumber(|i| if i < inputs { slot_of[i as usize] } else { i });
        self.atoms = order.iter().map(|&k| self.atoms[k]).collect();
        let mut input = order.iter().map(|&k| sources[k]);
        let mut g = Gather::default();
        let mut trig: Vec<(usize, Option<u32>, Option<u32>)> = Vec::new();
        // A second atom of the same sine or cosine (no caller plans one):
        // gathered alone, so that every input is written.
        let mut again = Vec::new();
        for slot in 0..inputs {
            let source = input.next().expect("one source per input");
            if let Input::Component(i) | Input::Sin(i) | Input::Cos(i) = source {
                g.components = g.components.max(i + 1);
            }
            match source {
                Input::Component(i) => {
                    let i = i as u32;
                    match g.runs.last_mut() {
                        Some(r) if r.slot + r.len == slot && r.i + r.len == i => r.len += 1,
                        _ => g.runs.push(Run { slot, i, len: 1 }),
                    }
                }
                Input::Sin(i) | Input::Cos(i) => {
                    let k = match trig.iter().position(|t| t.0 == i) {
                        Some(k) => k,
                        None => {
                            trig.push((i, None, None));
                            trig.len() - 1
                        }
                    };
                    let i = i as u32;
                    match (source, &mut trig[k]) {
                        (Input::Sin(_), (_, s @ None, _)) => *s = Some(slot),
                        (Input::Sin(_), _) => again.push(Trig::Sin { i, slot }),
                        (_, (_, _, c @ None)) => *c = Some(slot),
                        _ => again.push(Trig::Cos { i, slot }),
                    }
                }
                Input::Given => g.given.push(slot),
            }
        }
        g.trig = trig
            .into_iter()
            .map(|(i, sin, cos)| {
                let i = i as u32;
                match (sin, cos) {
                    (Some(sin), Some(cos)) => Trig::Both { i, sin, cos },
                    (Some(slot), None) => Trig::Sin { i, slot },
                    (None, Some(slot)) => Trig::Cos { i, slot },
                    (None, None) => unreachable!("a trigonometric input has a slot"),
                }
            })
            .chain(again)
            .collect();
        self.gather = g;
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
        self.outputs
    }

    /// The number of instructions (powers and products).
    pub fn len(&self) -> usize {
        self.ops.recips.len() + self.ops.muls.len()
    }

    /// True when the tape has no instructions.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
