//! Interned atoms: the indivisible building blocks of every expression.
//!
//! An [`Atom`] is a `u32` handle into a process-wide interner, so that
//! comparing, hashing and copying atoms in the polynomial hot loops costs
//! one integer operation (STYLE.md item 1). Three kinds exist:
//!
//! * a *constant* symbol (`I_x`, `m`, `L`);
//! * a *time-dependent* symbol together with its derivative order
//!   (`theta` is order 0, θ̇ is `theta'` of order 1, θ̈ order 2, …). Each
//!   derivative is an atom of its own: there is no unevaluated derivative
//!   node anywhere in the core;
//! * `sin` or `cos` of an angle symbol (order 0, constant or time-dependent);
//! * a *sum of constants* `s` standing as one factor, so that a division
//!   by it is the factor's power −1 (`M_a/(I′ + I L²/r²)`): see
//!   `poly/sums.rs` for its normal form and the reduction that keeps the
//!   canonical form unique.
//!
//! Atom ids depend on the order of interning, so nothing that is printed
//! or compared across processes may depend on them: printers sort by
//! [`Atom::sort_key`], which depends only on names.

use std::fmt;
use std::sync::{OnceLock, RwLock};

use rustc_hash::FxHashMap;

/// What an atom is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AtomKind {
    /// A symbol; `time` says whether it is a function of time, `order` is
    /// the order of its time derivative (always 0 for constants).
    Var {
        /// The symbol's name as written in a derivation file.
        name: &'static str,
        /// Whether the symbol is a function of time.
        time: bool,
        /// How many times it has been differentiated.
        order: u32,
    },
    /// `sin` of an angle (an order-0 [`AtomKind::Var`] atom).
    Sin(Atom),
    /// `cos` of an angle (an order-0 [`AtomKind::Var`] atom).
    Cos(Atom),
    /// A sum of constant symbols in its normal form (`poly/sums.rs`),
    /// which occurs only to negative powers: `1/(m r² + I)`. `text` is
    /// the sum in source syntax, its name for sorting and messages.
    Sum {
        /// The sum.
        sum: &'static crate::poly::Poly,
        /// The sum in source syntax (`I + m*r^2`).
        text: &'static str,
    },
}

/// A handle to an interned atom. Copy, compare and hash in O(1).
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Atom(u32);

#[derive(Default)]
/// Its maps are looked up, never iterated, so their hash (Fx, not the
/// std's SipHash, which was 5 % of a small run's instructions) changes no
/// order.
struct Interner {
    kinds: Vec<AtomKind>,
    ids: FxHashMap<AtomKind, Atom>,
    names: FxHashMap<String, &'static str>,
    /// Sum atoms by their text, so that a sum is leaked once.
    sums: FxHashMap<&'static str, Atom>,
}

fn interner() -> &'static RwLock<Interner> {
    static INTERNER: OnceLock<RwLock<Interner>> = OnceLock::new();
    INTERNER.get_or_init(Default::default)
}

fn intern(kind: AtomKind) -> Atom {
    if let Some(a) = interner()
        .read()
        .expect("atom interner poisoned")
        .ids
        .get(&kind)
    {
        return *a;
    }
    let mut w = interner().write().expect("atom interner poisoned");
    if let Some(a) = w.ids.get(&kind) {
        return *a;
    }
    let n = w.kinds.len();
    assert!(
        n < CHUNK * CHUNKS,
        "more than {} distinct atoms",
        CHUNK * CHUNKS
    );
    let id = Atom(n as u32);
    publish(n, kind);
    w.kinds.push(kind);
    w.ids.insert(kind, id);
    id
}

fn intern_name(name: &str) -> &'static str {
    if let Some(s) = interner()
        .read()
        .expect("atom interner poisoned")
        .names
        .get(name)
    {
        return s;
    }
    let mut w = interner().write().expect("atom interner poisoned");
    if let Some(s) = w.names.get(name) {
        return s;
    }
    let s: &'static str = Box::leak(name.to_owned().into_boxed_str());
    w.names.insert(name.to_owned(), s);
    s
}

/// # Construction
impl Atom {
    /// The interned index (stable within a process only: never printed or
    /// used for order that a user sees).
    pub(crate) fn id(self) -> u32 {
        self.0
    }

    /// A constant symbol.
    pub fn constant(name: &str) -> Atom {
        intern(AtomKind::Var {
            name: intern_name(name),
            time: false,
            order: 0,
        })
    }

    /// A time-dependent symbol, differentiated `order` times.
    pub fn time(name: &str, order: u32) -> Atom {
        intern(AtomKind::Var {
            name: intern_name(name),
            time: true,
            order,
        })
    }

    /// `sin(angle)`. Returns `None` unless `angle` is an undifferentiated symbol.
    pub fn sin(angle: Atom) -> Option<Atom> {
        angle.is_angle().then(|| intern(AtomKind::Sin(angle)))
    }

    /// `cos(angle)`. Returns `None` unless `angle` is an undifferentiated symbol.
    pub fn cos(angle: Atom) -> Option<Atom> {
        angle.is_angle().then(|| intern(AtomKind::Cos(angle)))
    }

    /// The sum `s` as one factor; `s` must be in the normal form of
    /// `poly/sums.rs` (the caller's duty: [`crate::poly::Poly::recip_sum`]).
    pub(crate) fn sum(s: &crate::poly::Poly) -> Atom {
        let text = intern_name(&s.to_string());
        if let Some(a) = interner()
            .read()
            .expect("atom interner poisoned")
            .sums
            .get(text)
        {
            return *a;
        }
        let sum: &'static crate::poly::Poly = Box::leak(Box::new(s.clone()));
        let a = intern(AtomKind::Sum { sum, text });
        interner()
            .write()
            .expect("atom interner poisoned")
            .sums
            .insert(text, a);
        a
    }
}

/// Atom kinds in chunks that never move once written, so that reading a
/// kind takes two atomic loads and no lock: this is the hottest call of the
/// polynomial loops. Capacity: `CHUNKS × CHUNK` atoms.
const CHUNK: usize = 1024;
const CHUNKS: usize = 4096;
type Chunk = [OnceLock<AtomKind>; CHUNK];
static KINDS: [OnceLock<Box<Chunk>>; CHUNKS] = [const { OnceLock::new() }; CHUNKS];

fn publish(id: usize, kind: AtomKind) {
    let chunk = KINDS[id / CHUNK].get_or_init(|| Box::new([const { OnceLock::new() }; CHUNK]));
    let _ = chunk[id % CHUNK].set(kind);
}

/// A property of atoms worked out once per atom and thread and then read
/// by the atom's id (an index, no hashing): the presentation asks such
/// questions (is it a leading constant, what is its cyclic place) of
/// every factor of every term. `f` must not read the same memo.
pub(crate) struct AtomMemo<T: Copy>(std::cell::RefCell<Vec<Option<T>>>);

impl<T: Copy> AtomMemo<T> {
    /// An empty memo (for a `thread_local!` with `const` initialisation).
    pub(crate) const fn new() -> Self {
        AtomMemo(std::cell::RefCell::new(Vec::new()))
    }

    /// The value for `a`, computed by `f` the first time.
    pub(crate) fn get(&self, a: Atom, f: impl FnOnce(Atom) -> T) -> T {
        let i = a.0 as usize;
        if let Some(Some(v)) = self.0.borrow().get(i) {
            return *v;
        }
        let v = f(a);
        let mut table = self.0.borrow_mut();
        if table.len() <= i {
            table.resize(i + 1, None);
        }
        table[i] = Some(v);
        v
    }
}

/// # Queries
impl Atom {
    /// What this atom is.
    pub fn kind(self) -> AtomKind {
        let i = self.0 as usize;
        *KINDS[i / CHUNK]
            .get()
            .and_then(|c| c[i % CHUNK].get())
            .expect("atoms are published before their id escapes")
    }

    /// The symbol's name (for `sin`/`cos`, the angle's name).
    pub fn name(self) -> &'static str {
        match self.kind() {
            AtomKind::Var { name, .. } => name,
            AtomKind::Sin(a) | AtomKind::Cos(a) => a.name(),
            AtomKind::Sum { text, .. } => text,
        }
    }

    /// True for an undifferentiated symbol, which may stand inside sin/cos.
    pub fn is_angle(self) -> bool {
        matches!(self.kind(), AtomKind::Var { order: 0, .. })
    }

    /// True when the atom varies with time.
    pub fn is_time_dependent(self) -> bool {
        match self.kind() {
            AtomKind::Var { time, .. } => time,
            AtomKind::Sin(a) | AtomKind::Cos(a) => a.is_time_dependent(),
            AtomKind::Sum { .. } => false,
        }
    }

    /// The derivative order of a symbol (0 for constants, sin and cos).
    pub fn order(self) -> u32 {
        match self.kind() {
            AtomKind::Var { order, .. } => order,
            _ => 0,
        }
    }

    /// The same symbol differentiated once more; `None` for constants and trig atoms.
    pub fn derivative(self) -> Option<Atom> {
        match self.kind() {
            AtomKind::Var {
                name,
                time: true,
                order,
            } => Some(Atom::time(name, order + 1)),
            _ => None,
        }
    }

    /// The undifferentiated symbol this atom derives from (itself for order 0).
    pub fn base(self) -> Atom {
        match self.kind() {
            AtomKind::Var {
                name,
                time: true,
                order,
            } if order > 0 => Atom::time(name, 0),
            _ => self,
        }
    }

    /// An order that depends only on names, for stable printing:
    /// constants first, then sums of constants, then time-dependent
    /// symbols by derivative order and name, then `sin`, then `cos`.
    pub fn sort_key(self) -> (u8, u32, &'static str) {
        match self.kind() {
            AtomKind::Var {
                name, time: false, ..
            } => (0, 0, name),
            AtomKind::Sum { text, .. } => (0, 1, text),
            AtomKind::Var {
                name,
                time: true,
                order,
            } => (1, order, name),
            AtomKind::Sin(a) => (2, 0, a.name()),
            AtomKind::Cos(a) => (3, 0, a.name()),
        }
    }
}

/// Source syntax: `I_x`, `theta''`, `sin(theta)`.
impl fmt::Display for Atom {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind() {
            AtomKind::Var { name, order, .. } => {
                f.write_str(name)?;
                for _ in 0..order {
                    f.write_str("'")?;
                }
                Ok(())
            }
            AtomKind::Sin(a) => write!(f, "sin({a})"),
            AtomKind::Cos(a) => write!(f, "cos({a})"),
            AtomKind::Sum { text, .. } => write!(f, "({text})"),
        }
    }
}

impl fmt::Debug for Atom {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interning_is_idempotent_and_kinds_differ() {
        assert_eq!(Atom::time("theta", 2), Atom::time("theta", 2));
        assert_ne!(Atom::time("m", 0), Atom::constant("m"));
        let th = Atom::time("theta", 0);
        assert_eq!(
            th.derivative().unwrap().derivative(),
            Some(Atom::time("theta", 2))
        );
        assert_eq!(Atom::sin(Atom::time("theta", 1)), None);
        assert_eq!(Atom::cos(th).unwrap().to_string(), "cos(theta)");
        assert_eq!(Atom::time("phi", 2).to_string(), "phi''");
    }
}
