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

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::poly::Poly;
// The compiler's maps are looked up, never iterated: Fx (an atom is a
// small integer; SipHash was half of compiling the bicycle's steps).
use rustc_hash::FxHashMap;

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
/// sums of four terms or more keep their terms in [`Tape`]'s `terms`.
#[derive(Clone, Debug, Default, PartialEq)]
struct Outputs {
    /// No terms: structurally zero.
    zeros: Vec<u32>,
    /// `(out, term)`: a single term has no common factor taken out.
    ones: Vec<(u32, Term)>,
    /// `(out, scale, terms)`, as in [`Sum`].
    twos: Vec<(u32, u32, [Term; 2])>,
    threes: Vec<(u32, u32, [Term; 3])>,
    longer: Vec<Sum>,
}

impl Outputs {
    fn of(sums: &[Sum], terms: &[Term], zeros: Vec<u32>) -> Outputs {
        let mut o = Outputs {
            zeros,
            ..Outputs::default()
        };
        for s in sums {
            let t = &terms[s.start as usize..s.end as usize];
            match *t {
                [a] => o.ones.push((s.out, a)),
                [a, b] => o.twos.push((s.out, s.scale, [a, b])),
                [a, b, c] => o.threes.push((s.out, s.scale, [a, b, c])),
                _ => o.longer.push(*s),
            }
        }
        o
    }
}

/// A monomial's factors left after folding the known atoms, and its
/// coefficient.
type FoldedTerm = (Vec<(Atom, i32)>, f64);

/// Takes out of `terms` (the terms of one output) the factors common to
/// all of them, and returns those: each atom every term has with an
/// exponent of the same sign, to the smallest such power (`x²y + x³/z` →
/// `x²`; `θ̇/sin θ` out of `a ψ̇ θ̇/sin θ + b φ̇ θ̇ cos θ/sin θ`). Nothing
/// is taken out of fewer than two terms. The output is then the product
/// of the common factors times the sum of what is left: fewer products
/// per term, and other bits than multiplying every term out, within the
/// same bound (a few ulps of `Σ |terms|`).
fn take_common(terms: &mut [FoldedTerm]) -> Vec<(Atom, i32)> {
    let [(first, _), rest @ ..] = &*terms else {
        return Vec::new();
    };
    let mut common = first.clone();
    if rest.is_empty() {
        return Vec::new();
    }
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

/// A compiled set of polynomials.
///
/// Invariant: slots `0..atoms.len()` are the inputs in [`Tape::atoms`]
/// order, slot `atoms.len()` holds 1 during an evaluation; every
/// instruction writes a slot above every slot it reads; every term
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
/// slots copied from it, and one `sin_cos` per component whose sine and
/// cosine are both read (one libm call instead of two). No match on each
/// input's source per evaluation.
#[derive(Clone, Debug, Default)]
struct Gather {
    /// `(slot, i)`: slot ← x[i].
    copies: Vec<(u32, u32)>,
    trig: Vec<Trig>,
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
        Tape {
            atoms,
            ops,
            sums: Outputs::of(&sums, &terms, zeros),
            terms,
            width,
            outputs: polys.len(),
            aliases,
            slots: next as usize,
            gather: Gather::default(),
        }
    }
}

/// # Planning the inputs
impl Tape {
    /// Plans how [`Tape::eval_at`] fills each input slot: `input(a)` for
    /// each atom `a` of [`Tape::atoms`]. Until planned, every input is
    /// [`Input::Given`].
    pub fn plan_inputs(&mut self, mut input: impl FnMut(Atom) -> Input) {
        let mut g = Gather::default();
        let mut trig: Vec<(usize, Option<u32>, Option<u32>)> = Vec::new();
        for (slot, &a) in self.atoms.iter().enumerate() {
            let slot = slot as u32;
            let source = input(a);
            match source {
                Input::Component(i) => g.copies.push((slot, i as u32)),
                Input::Sin(i) | Input::Cos(i) => {
                    let k = match trig.iter().position(|t| t.0 == i) {
                        Some(k) => k,
                        None => {
                            trig.push((i, None, None));
                            trig.len() - 1
                        }
                    };
                    if matches!(source, Input::Sin(_)) {
                        trig[k].1 = Some(slot);
                    } else {
                        trig[k].2 = Some(slot);
                    }
                }
                Input::Given => {}
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

/// A buffer of slots an evaluation reads and writes: a fixed array of
/// `N` (a power of two ≥ the tape's slots) indexed by masking, so the
/// compiler needs no bounds check per operand, or a slice (checked).
trait Slots {
    fn get(&self, i: u32) -> f64;
    fn set(&mut self, i: u32, v: f64);
}

impl<const N: usize> Slots for [f64; N] {
    #[inline(always)]
    fn get(&self, i: u32) -> f64 {
        self[i as usize & (N - 1)]
    }
    #[inline(always)]
    fn set(&mut self, i: u32, v: f64) {
        self[i as usize & (N - 1)] = v;
    }
}

impl Slots for [f64] {
    #[inline(always)]
    fn get(&self, i: u32) -> f64 {
        self[i as usize]
    }
    #[inline(always)]
    fn set(&mut self, i: u32, v: f64) {
        self[i as usize] = v;
    }
}

/// The largest tape [`Tape::eval_at`] evaluates in a buffer on the
/// stack (32 KB); a larger one uses a buffer kept per thread.
const STACK_SLOTS: usize = 4096;

thread_local! {
    /// The slots of tapes larger than [`STACK_SLOTS`], reused.
    static SCRATCH: std::cell::Cell<Vec<f64>> = const { std::cell::Cell::new(Vec::new()) };
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
        let scratch = &mut slots[..self.slots];
        if abs {
            self.run::<true, [f64]>(scratch, out);
        } else {
            self.run::<false, [f64]>(scratch, out);
        }
    }

    /// Evaluates every output at the state vector `x`: the inputs planned
    /// by [`Tape::plan_inputs`] gathered from it, then the [`Input::Given`]
    /// ones written by `given` into the slice it is given
    /// (`atoms().len()` slots, input i at index i). The gathering and the
    /// evaluation are one call, in a buffer on the stack sized for this
    /// tape (no allocation, no shared scratch buffer, no bounds check per
    /// operand); a tape of more than 4096 slots uses a buffer kept per
    /// thread instead.
    ///
    /// # Panics
    /// When `out.len() != outputs()`, or `x` is shorter than a planned
    /// component.
    #[inline]
    pub fn eval_at(&self, x: &[f64], given: impl FnOnce(&mut [f64]), out: &mut [f64]) {
        match self.slots {
            0..=16 => self.eval_on_stack::<16>(x, given, out),
            17..=32 => self.eval_on_stack::<32>(x, given, out),
            33..=64 => self.eval_on_stack::<64>(x, given, out),
            65..=128 => self.eval_on_stack::<128>(x, given, out),
            129..=256 => self.eval_on_stack::<256>(x, given, out),
            257..=1024 => self.eval_on_stack::<1024>(x, given, out),
            1025..=STACK_SLOTS => self.eval_on_stack::<STACK_SLOTS>(x, given, out),
            _ => self.eval_on_heap(x, given, out),
        }
    }

    #[cold]
    #[inline(never)]
    fn eval_on_heap(&self, x: &[f64], given: impl FnOnce(&mut [f64]), out: &mut [f64]) {
        // Taken out of the thread's cell while in use: a `given` that
        // evaluates another tape gets a buffer of its own.
        let mut buf = SCRATCH.take();
        buf.clear();
        buf.resize(self.slots, 0.0);
        self.gather_into::<[f64]>(&mut buf, x);
        given(&mut buf[..self.atoms.len()]);
        self.run::<false, [f64]>(&mut buf, out);
        SCRATCH.set(buf);
    }

    // Not inlined: each size keeps a stack frame of its own (one frame
    // holding every size's buffer would probe 40 KB of stack per call).
    #[inline(never)]
    fn eval_on_stack<const N: usize>(
        &self,
        x: &[f64],
        given: impl FnOnce(&mut [f64]),
        out: &mut [f64],
    ) {
        debug_assert!(self.slots <= N && N.is_power_of_two());
        let mut buf = [0.0; N];
        self.gather_into(&mut buf, x);
        given(&mut buf[..self.atoms.len()]);
        self.run::<false, [f64; N]>(&mut buf, out);
    }

    /// The planned inputs from `x`.
    #[inline(always)]
    fn gather_into<S: Slots + ?Sized>(&self, s: &mut S, x: &[f64]) {
        for &(slot, i) in &self.gather.copies {
            s.set(slot, x[i as usize]);
        }
        for t in &self.gather.trig {
            match *t {
                Trig::Both { i, sin, cos } => {
                    let (a, b) = x[i as usize].sin_cos();
                    s.set(sin, a);
                    s.set(cos, b);
                }
                Trig::Sin { i, slot } => s.set(slot, x[i as usize].sin()),
                Trig::Cos { i, slot } => s.set(slot, x[i as usize].cos()),
            }
        }
    }

    /// The instructions, then each output's sum, on `s` (inputs filled).
    #[inline(always)]
    fn run<const ABS: bool, S: Slots + ?Sized>(&self, s: &mut S, out: &mut [f64]) {
        assert_eq!(out.len(), self.outputs, "one output per polynomial");
        s.set(self.atoms.len() as u32, 1.0);
        for &(dst, src) in &self.ops.recips {
            s.set(dst, 1.0 / s.get(src));
        }
        for &[dst, a, b] in &self.ops.muls {
            s.set(dst, s.get(a) * s.get(b));
        }
        match self.width {
            1 => self.sum_terms::<ABS, 1, S>(s, out),
            2 => self.sum_terms::<ABS, 2, S>(s, out),
            3 => self.sum_terms::<ABS, 3, S>(s, out),
            _ => self.sum_terms::<ABS, WIDTH, S>(s, out),
        }
        for &(k, j) in &self.aliases {
            out[k] = out[j];
        }
    }

    /// Each output's terms (`W` factors each: the tape's width), summed
    /// with an exact error term (Knuth's TwoSum: no branch; the same error
    /// Neumaier's comparison finds), from the first term on, then
    /// multiplied by the output's common factors. A sum of one or two terms
    /// is added plainly: `x + e` of TwoSum rounds back to `x`, so the bits
    /// are the same.
    #[inline(always)]
    fn sum_terms<const ABS: bool, const W: usize, S: Slots + ?Sized>(
        &self,
        s: &S,
        out: &mut [f64],
    ) {
        let term = |t: &Term| {
            let mut v = t.coef;
            for &f in &t.factors[..W] {
                v *= s.get(f);
            }
            if ABS { v.abs() } else { v }
        };
        let scale = |k: u32| if ABS { s.get(k).abs() } else { s.get(k) };
        // TwoSum: `sum + v` and its exact error added to `comp`.
        let add = |(sum, comp): (f64, f64), v: f64| {
            let x = sum + v;
            let bv = x - sum;
            (x, comp + ((sum - (x - bv)) + (v - bv)))
        };
        let o = &self.sums;
        for &k in &o.zeros {
            out[k as usize] = 0.0;
        }
        // `+ 0.0` as the compensated sum's last step adds it: −0 → +0.
        for (k, t) in &o.ones {
            out[*k as usize] = term(t) + 0.0;
        }
        for (k, c, [t, u]) in &o.twos {
            out[*k as usize] = (term(t) + term(u)) * scale(*c) + 0.0;
        }
        for (k, c, [t, u, v]) in &o.threes {
            let (sum, comp) = add(add((term(t), 0.0), term(u)), term(v));
            out[*k as usize] = (sum + comp) * scale(*c) + 0.0;
        }
        for r in &o.longer {
            let terms = &self.terms[r.start as usize..r.end as usize];
            if let [t, rest @ ..] = terms {
                let (sum, comp) = rest.iter().fold((term(t), 0.0), |acc, u| add(acc, term(u)));
                out[r.out as usize] = (sum + comp) * scale(r.scale) + 0.0;
            }
        }
    }
}
