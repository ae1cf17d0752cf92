//! Evaluating a [`Tape`](super::Tape): the inputs gathered from a state
//! vector, the instructions, then each output's compensated sum, in a
//! buffer on the stack sized for the tape (or one kept per thread).

use std::mem::MaybeUninit;
use std::ops::{Add, Sub};

use super::lanes::Lanes;
use super::{Tape, Term, Trig, WIDTH};

/// A buffer of slots an evaluation reads and writes: an array on the
/// stack left uninitialised, or a slice. Read and written unchecked: the
/// operands and destinations of a tape are below its `slots` (checked once
/// when it is compiled, [`Tape::indices_in_bounds`]) and [`Tape::run`]
/// checks once per evaluation that the buffer has that many. A check or
/// mask per operand was about 45 of the heavy top's 366 instructions in
/// the tape.
trait Slots {
    fn len(&self) -> usize;
    /// # Safety
    /// `i < self.len()`, and slot `i` written in this evaluation (every
    /// slot a tape reads is: an input by the gathering, the slot of 1 by
    /// [`Tape::run`], the others by an earlier instruction — checked once
    /// when the tape is compiled, `Tape::writes_before_reads`).
    unsafe fn get(&self, i: u32) -> f64;
    /// # Safety
    /// `i < self.len()`.
    unsafe fn set(&mut self, i: u32, v: f64);
    /// Slots `i` and `i + 1` (one 16-byte store).
    ///
    /// # Safety
    /// `i + 1 < self.len()`.
    unsafe fn set_pair(&mut self, i: u32, v: [f64; 2]);
}

/// The buffer on the stack, not cleared: clearing 16 slots was 9 of the
/// heavy top's instructions per evaluation, and every slot a tape reads
/// is written first.
impl<const N: usize> Slots for [MaybeUninit<f64>; N] {
    #[inline(always)]
    fn len(&self) -> usize {
        N
    }
    #[inline(always)]
    unsafe fn get(&self, i: u32) -> f64 {
        debug_assert!((i as usize) < N);
        // SAFETY: the caller's contract: in bounds, and written.
        unsafe { self.get_unchecked(i as usize).assume_init() }
    }
    #[inline(always)]
    unsafe fn set(&mut self, i: u32, v: f64) {
        debug_assert!((i as usize) < N);
        // SAFETY: the caller's contract.
        unsafe {
            self.get_unchecked_mut(i as usize).write(v);
        }
    }
    #[inline(always)]
    unsafe fn set_pair(&mut self, i: u32, v: [f64; 2]) {
        debug_assert!((i as usize) + 1 < N);
        // SAFETY: the caller's contract; `[f64; 2]` has the layout of two
        // slots, written unaligned.
        unsafe {
            self.as_mut_ptr()
                .add(i as usize)
                .cast::<[f64; 2]>()
                .write_unaligned(v)
        }
    }
}

impl Slots for [f64] {
    #[inline(always)]
    fn len(&self) -> usize {
        <[f64]>::len(self)
    }
    #[inline(always)]
    unsafe fn get(&self, i: u32) -> f64 {
        debug_assert!((i as usize) < self.len());
        // SAFETY: the caller's contract.
        unsafe { *self.get_unchecked(i as usize) }
    }
    #[inline(always)]
    unsafe fn set(&mut self, i: u32, v: f64) {
        debug_assert!((i as usize) < self.len());
        // SAFETY: the caller's contract.
        unsafe { *self.get_unchecked_mut(i as usize) = v }
    }
    #[inline(always)]
    unsafe fn set_pair(&mut self, i: u32, v: [f64; 2]) {
        debug_assert!((i as usize) + 1 < self.len());
        // SAFETY: the caller's contract; `[f64; 2]` has the layout of two
        // slots, written unaligned.
        unsafe {
            self.as_mut_ptr()
                .add(i as usize)
                .cast::<[f64; 2]>()
                .write_unaligned(v)
        }
    }
}

/// Marks a loop of a tape's evaluation as one LLVM must not unroll: an
/// empty optimisation barrier (`black_box` of `()`, no instruction) in its
/// body. The loops of a small tape (the state's copies, the reciprocals,
/// the products, the outputs of one term) run one to three times, and
/// unrolled by two or four they paid a set-up and a remainder test of ~12
/// instructions each per evaluation.
#[inline(always)]
fn once_per_iteration() {
    std::hint::black_box(());
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
            self.run::<true, false, [f64]>(scratch, out);
        } else {
            self.run::<false, false, [f64]>(scratch, out);
        }
    }

    /// Evaluates every output at the state vector `x`: the inputs planned
    /// by [`Tape::plan_inputs`] gathered from it, then the [`Input::Given`]
    /// ones written by `given` into the slice it is given
    /// (`atoms().len()` slots, input i at index i; the given ones are 0
    /// until it writes them). The gathering and the evaluation are one
    /// call, in a buffer on the stack sized for this tape and not cleared
    /// (no allocation, no shared scratch buffer, no bounds check per
    /// operand); a tape of more than 4096 slots uses a buffer kept per
    /// thread instead.
    ///
    /// # Panics
    /// When `out.len() != outputs()`, or `x` is shorter than a planned
    /// component.
    #[inline(always)]
    pub fn eval_at(&self, x: &[f64], given: impl FnOnce(&mut [f64]), out: &mut [f64]) {
        self.eval_at_with::<false>(x, given, out);
    }

    /// [`Tape::eval_at`] into an `out` the caller has cleared: the
    /// structurally zero outputs (no terms) are left as they are, not
    /// written. A mass matrix's buffer is cleared when it is made, and
    /// writing its zeros again was ~23 of the heavy top's instructions.
    ///
    /// # Panics
    /// As [`Tape::eval_at`].
    #[inline(always)]
    pub fn eval_at_cleared(&self, x: &[f64], given: impl FnOnce(&mut [f64]), out: &mut [f64]) {
        self.eval_at_with::<true>(x, given, out);
    }

    /// [`Tape::eval_at`], the zero outputs written unless `CLEARED`.
    #[inline(always)]
    fn eval_at_with<const CLEARED: bool>(
        &self,
        x: &[f64],
        given: impl FnOnce(&mut [f64]),
        out: &mut [f64],
    ) {
        match self.slots {
            0..=16 => self.eval_in::<16, CLEARED>(x, given, out),
            17..=32 => self.eval_on_stack::<32, CLEARED>(x, given, out),
            33..=64 => self.eval_on_stack::<64, CLEARED>(x, given, out),
            65..=128 => self.eval_on_stack::<128, CLEARED>(x, given, out),
            129..=256 => self.eval_on_stack::<256, CLEARED>(x, given, out),
            257..=1024 => self.eval_on_stack::<1024, CLEARED>(x, given, out),
            1025..=STACK_SLOTS => self.eval_on_stack::<STACK_SLOTS, CLEARED>(x, given, out),
            _ => self.eval_on_heap::<CLEARED>(x, given, out),
        }
    }

    #[cold]
    #[inline(never)]
    fn eval_on_heap<const CLEARED: bool>(
        &self,
        x: &[f64],
        given: impl FnOnce(&mut [f64]),
        out: &mut [f64],
    ) {
        // Taken out of the thread's cell while in use: a `given` that
        // evaluates another tape gets a buffer of its own.
        let mut buf = SCRATCH.take();
        buf.clear();
        buf.resize(self.slots, 0.0);
        self.gather_into::<[f64]>(&mut buf, x);
        given(&mut buf[..self.atoms.len()]);
        self.run::<false, CLEARED, [f64]>(&mut buf, out);
        SCRATCH.set(buf);
    }

    // Not inlined: each size keeps a stack frame of its own (one frame
    // holding every size's buffer would probe 40 KB of stack per call);
    // the smallest (16 slots, 128 bytes) is inlined into its caller
    // (`eval_in`): its call, frame and saved registers were ~25 of the
    // heavy top's instructions per evaluation.
    #[inline(never)]
    fn eval_on_stack<const N: usize, const CLEARED: bool>(
        &self,
        x: &[f64],
        given: impl FnOnce(&mut [f64]),
        out: &mut [f64],
    ) {
        self.eval_in::<N, CLEARED>(x, given, out);
    }

    /// The evaluation in a buffer of `N` slots on the stack, not cleared
    /// (every slot read is written first).
    #[inline(always)]
    fn eval_in<const N: usize, const CLEARED: bool>(
        &self,
        x: &[f64],
        given: impl FnOnce(&mut [f64]),
        out: &mut [f64],
    ) {
        debug_assert!(self.slots <= N && N.is_power_of_two());
        let mut buf = [MaybeUninit::<f64>::uninit(); N];
        self.gather_into(&mut buf, x);
        // SAFETY: the inputs are below the slot of 1, which is below the
        // tape's slots (`indices_in_bounds`), and `buf` has those (checked
        // by `gather_into`); every input is written by `gather_into` (a
        // planned one gathered, the others set to 0), so the slice is of
        // initialised `f64`s.
        let inputs = unsafe {
            std::slice::from_raw_parts_mut(buf.as_mut_ptr().cast::<f64>(), self.atoms.len())
        };
        given(inputs);
        self.run::<false, CLEARED, [MaybeUninit<f64>; N]>(&mut buf, out);
    }

    /// The planned inputs from `x`.
    ///
    /// # Panics
    /// When `s` has fewer than the tape's slots, or `x` is shorter than a
    /// planned component.
    #[inline(always)]
    fn gather_into<S: Slots + ?Sized>(&self, s: &mut S, x: &[f64]) {
        let g = &self.gather;
        assert!(s.len() >= self.slots, "a buffer of the tape's slots");
        assert!(
            x.len() >= g.components,
            "a state of every planned component"
        );
        // SAFETY: a planned slot is an input's, below the tape's slots, and
        // `s` has them; a planned component is below `g.components`, and
        // `x` has them (both checked above); so are a run's, and a pair of
        // a run is within it.
        unsafe {
            let pair = |i: u32| {
                x.as_ptr()
                    .add(i as usize)
                    .cast::<[f64; 2]>()
                    .read_unaligned()
            };
            let x = |i: u32| *x.get_unchecked(i as usize);
            // Two at a time (a 16-byte load and store), the last pair
            // ending the run (overlapping the one before when the run is
            // odd): the heavy top's three rates in two moves. A run of up
            // to four is its first pair and its last, with no loop.
            for r in &g.runs {
                let last = r.len.wrapping_sub(2);
                match r.len {
                    1 => s.set(r.slot, x(r.i)),
                    2..=4 => {
                        s.set_pair(r.slot, pair(r.i));
                        s.set_pair(r.slot + last, pair(r.i + last));
                    }
                    _ => {
                        let mut k = 0;
                        while k < last {
                            s.set_pair(r.slot + k, pair(r.i + k));
                            k += 2;
                            once_per_iteration();
                        }
                        s.set_pair(r.slot + last, pair(r.i + last));
                    }
                }
                once_per_iteration();
            }
            for t in &g.trig {
                match *t {
                    Trig::Both { i, sin, cos } => {
                        let (a, b) = x(i).sin_cos();
                        s.set(sin, a);
                        s.set(cos, b);
                    }
                    Trig::Sin { i, slot } => s.set(slot, x(i).sin()),
                    Trig::Cos { i, slot } => s.set(slot, x(i).cos()),
                }
            }
            // Every input written: the buffer on the stack is not cleared.
            for &slot in &g.given {
                s.set(slot, 0.0);
                once_per_iteration();
            }
        }
    }

    /// The instructions, then each output's sum, on `s` (inputs filled);
    /// the zero outputs are written unless `CLEARED`.
    ///
    /// # Panics
    /// When `s` has fewer than the tape's slots, or `out.len() != outputs()`.
    #[inline(always)]
    fn run<const ABS: bool, const CLEARED: bool, S: Slots + ?Sized>(
        &self,
        s: &mut S,
        out: &mut [f64],
    ) {
        assert_eq!(out.len(), self.outputs, "one output per polynomial");
        assert!(s.len() >= self.slots, "a buffer of the tape's slots");
        // SAFETY: every operand and destination of an instruction, and the
        // slot of 1, is below the tape's slots (`indices_in_bounds`, checked
        // when compiled), and `s` has them (checked above); so are the
        // term's and scale's slots and the output indices `sum_terms` reads
        // and writes, and `out` has the tape's outputs.
        unsafe {
            s.set(self.atoms.len() as u32, 1.0);
            for &(dst, src) in &self.ops.recips {
                s.set(dst, 1.0 / s.get(src));
                once_per_iteration();
            }
            for &[dst, a, b] in &self.ops.muls {
                s.set(dst, s.get(a) * s.get(b));
                once_per_iteration();
            }
            match self.width {
                1 => self.sum_terms::<ABS, CLEARED, 1, S>(s, out),
                2 => self.sum_terms::<ABS, CLEARED, 2, S>(s, out),
                3 => self.sum_terms::<ABS, CLEARED, 3, S>(s, out),
                _ => self.sum_terms::<ABS, CLEARED, WIDTH, S>(s, out),
            }
        }
        for &(k, j) in &self.aliases {
            // SAFETY: an alias's indices are below the tape's outputs
            // (`indices_in_bounds`), and `out` has them (checked above).
            unsafe { *out.get_unchecked_mut(k) = *out.get_unchecked(j) };
            once_per_iteration();
        }
    }

    /// Each output's terms (`W` factors each: the tape's width), summed
    /// with an exact error term (Knuth's TwoSum: no branch; the same error
    /// Neumaier's comparison finds), from the first term on, then
    /// multiplied by the output's common factors. A sum of one or two terms
    /// is added plainly: `x + e` of TwoSum rounds back to `x`, so the bits
    /// are the same.
    ///
    /// # Safety
    /// `s` has at least the tape's slots, and `out` its outputs.
    #[inline(always)]
    unsafe fn sum_terms<const ABS: bool, const CLEARED: bool, const W: usize, S: Slots + ?Sized>(
        &self,
        s: &S,
        out: &mut [f64],
    ) {
        // SAFETY: the slots of a term's factors and of a scale are below the
        // tape's slots, and an output's index below its outputs
        // (`indices_in_bounds`); `s` and `out` have them (the contract).
        let get = |i: u32| unsafe { s.get(i) };
        let mut put = |k: u32, v: f64| unsafe { *out.get_unchecked_mut(k as usize) = v };
        // The outputs of a class one at a time (functions, not closures:
        // LLVM called a closure used twice out of line, ~24 instructions).
        let r = Read::<ABS, W, S> { s };
        // Two at a time, one in each lane (the same operations: the same
        // bits); the magnitudes of `eval_abs` one at a time.
        let lanes = |k: u32, l: u32| Lanes::new(get(k), get(l));
        let term2 = |t: &Term, u: &Term| {
            let mut v = Lanes::new(t.coef, u.coef);
            for j in 0..W {
                v = v * lanes(t.factors[j], u.factors[j]);
            }
            v
        };
        let o = &self.sums;
        if !CLEARED {
            for &k in &o.zeros {
                put(k, 0.0);
                once_per_iteration();
            }
        }
        // `+ 0.0` as the compensated sum's last step adds it: −0 → +0.
        for [a, b] in &o.ones.pairs {
            if ABS {
                put(a.0, unsafe { r.one(a) });
                put(b.0, unsafe { r.one(b) });
            } else {
                let v = Lanes::new(a.1, b.1) * lanes(a.2, b.2) + Lanes::splat(0.0);
                put(a.0, v.lo());
                put(b.0, v.hi());
            }
            once_per_iteration();
        }
        for [a, b] in &o.twos.pairs {
            if ABS {
                put(a.0, unsafe { r.two(a) });
                put(b.0, unsafe { r.two(b) });
            } else {
                let ([t, u], [t1, u1]) = (a.2, b.2);
                let v = (term2(&t, &t1) + term2(&u, &u1)) * lanes(a.1, b.1) + Lanes::splat(0.0);
                put(a.0, v.lo());
                put(b.0, v.hi());
            }
        }
        for [a, b] in &o.threes.pairs {
            if ABS {
                put(a.0, unsafe { r.three(a) });
                put(b.0, unsafe { r.three(b) });
            } else {
                let ([t, u, v], [t1, u1, v1]) = (a.2, b.2);
                let first = (term2(&t, &t1), Lanes::splat(-0.0));
                let (sum, comp) = two_sum(two_sum(first, term2(&u, &u1)), term2(&v, &v1));
                let v = (sum + comp) * lanes(a.1, b.1) + Lanes::splat(0.0);
                put(a.0, v.lo());
                put(b.0, v.hi());
            }
        }
        if let Some(a) = &o.ones.odd {
            put(a.0, unsafe { r.one(a) });
        }
        if let Some(a) = &o.twos.odd {
            put(a.0, unsafe { r.two(a) });
        }
        if let Some(a) = &o.threes.odd {
            put(a.0, unsafe { r.three(a) });
        }
        for l in &o.longer {
            let terms = &self.terms[l.start as usize..l.end as usize];
            if let [t, rest @ ..] = terms {
                // SAFETY: as above.
                unsafe {
                    let first = (r.term(t), -0.0);
                    let (sum, comp) = rest.iter().fold(first, |acc, u| two_sum(acc, r.term(u)));
                    put(l.out, (sum + comp) * r.scale(l.scale) + 0.0);
                }
            }
        }
    }
}

/// The outputs of one to three terms, one at a time, read from `s`
/// unchecked: what [`Tape::sum_terms`] sums (the magnitudes of the terms
/// with `ABS`; `W` factors per term). Every method is inlined.
struct Read<'a, const ABS: bool, const W: usize, S: Slots + ?Sized> {
    s: &'a S,
}

// SAFETY (each method): the caller's contract is [`Tape::sum_terms`]'s —
// `s` has the tape's slots, every slot a term or a scale reads is in bounds
// and written, and the items are the tape's.
impl<const ABS: bool, const W: usize, S: Slots + ?Sized> Read<'_, ABS, W, S> {
    /// # Safety
    /// As [`Tape::sum_terms`], `t` a term of the tape.
    #[inline(always)]
    unsafe fn term(&self, t: &Term) -> f64 {
        let mut v = t.coef;
        for &f in &t.factors[..W] {
            v *= unsafe { self.s.get(f) };
        }
        if ABS { v.abs() } else { v }
    }

    /// # Safety
    /// As [`Tape::sum_terms`], `k` a scale of the tape.
    #[inline(always)]
    unsafe fn scale(&self, k: u32) -> f64 {
        let v = unsafe { self.s.get(k) };
        if ABS { v.abs() } else { v }
    }

    /// # Safety
    /// As [`Tape::sum_terms`], `a` an output of one term of the tape.
    #[inline(always)]
    unsafe fn one(&self, &(_, c, f): &(u32, f64, u32)) -> f64 {
        let c = if ABS { c.abs() } else { c };
        c * unsafe { self.scale(f) } + 0.0
    }

    /// # Safety
    /// As [`Tape::sum_terms`], `a` an output of two terms of the tape.
    #[inline(always)]
    unsafe fn two(&self, (_, c, [t, u]): &(u32, u32, [Term; 2])) -> f64 {
        unsafe { (self.term(t) + self.term(u)) * self.scale(*c) + 0.0 }
    }

    /// # Safety
    /// As [`Tape::sum_terms`], `a` an output of three terms of the tape.
    #[inline(always)]
    unsafe fn three(&self, (_, c, [t, u, v]): &(u32, u32, [Term; 3])) -> f64 {
        unsafe {
            let (sum, comp) = two_sum(two_sum((self.term(t), -0.0), self.term(u)), self.term(v));
            (sum + comp) * self.scale(*c) + 0.0
        }
    }
}

/// TwoSum (Knuth): `sum + v` and its exact error added to `comp`. The
/// error of the first addition is added to a `comp` of −0, which LLVM
/// folds away (`−0 + e = e` for every `e`, where `+0 + e` turns a −0 to
/// +0: only the sign of a zero differs, and the `+ 0.0` every output ends
/// with makes it +0 either way).
#[inline(always)]
fn two_sum<T: Copy + Add<Output = T> + Sub<Output = T>>((sum, comp): (T, T), v: T) -> (T, T) {
    let x = sum + v;
    let bv = x - sum;
    (x, comp + ((sum - (x - bv)) + (v - bv)))
}
