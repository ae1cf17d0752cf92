//! Deterministic counts of symbolic work, a clock that load cannot move.
//!
//! Wall time depends on the machine and on whoever else is using it; the
//! number of monomials multiplied, of terms put into sums and of
//! nodes in the presented trees does not. [`measure`] runs a computation and
//! returns what it did, so a test can hold a workload (a chain, the
//! gyroscope, the heavy top) to a committed budget and a change that makes
//! a pass cost several times more is caught where it is made
//! (`tests/sym/work_budget.toml` and its test).
//!
//! The counters are thread-local (a test thread sees only its own work)
//! and cost one add on a thread-local cell per counted operation, not per
//! factor.

use std::cell::Cell;

/// What a computation did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    /// Monomials multiplied (or divided): every product of two monomials,
    /// in arithmetic, derivatives, substitution and presentation alike.
    pub monomial_products: u64,
    /// Terms added into a sum being accumulated (before like terms
    /// cancel), and the terms of every sum formed by merging two: the
    /// size of every general sum and product formed.
    pub terms_accumulated: u64,
    /// Nodes of the presented (textbook-form) expression trees.
    pub presented_nodes: u64,
}

impl std::ops::Sub for Work {
    type Output = Work;
    fn sub(self, rhs: Work) -> Work {
        Work {
            monomial_products: self.monomial_products - rhs.monomial_products,
            terms_accumulated: self.terms_accumulated - rhs.terms_accumulated,
            presented_nodes: self.presented_nodes - rhs.presented_nodes,
        }
    }
}

thread_local! {
    static COUNTS: Cell<Work> = const {
        Cell::new(Work {
            monomial_products: 0,
            terms_accumulated: 0,
            presented_nodes: 0,
        })
    };
}

/// The work done so far on this thread.
pub fn so_far() -> Work {
    COUNTS.with(Cell::get)
}

/// Runs `f` and returns its value with the work it did on this thread.
///
/// # Example
/// ```
/// use hdot_sym::{work, Symbols};
/// let s = Symbols::parse_decl(&["a", "b"], &[]);
/// let (p, w) = work::measure(|| {
///     let x = s.poly("a + b").unwrap();
///     &x * &x
/// });
/// assert_eq!(p, s.poly("a^2 + 2*a*b + b^2").unwrap());
/// assert!(w.monomial_products >= 4);
/// ```
pub fn measure<T>(f: impl FnOnce() -> T) -> (T, Work) {
    let before = so_far();
    let value = f();
    (value, so_far() - before)
}

#[inline]
fn bump(f: impl FnOnce(&mut Work)) {
    COUNTS.with(|c| {
        let mut w = c.get();
        f(&mut w);
        c.set(w);
    });
}

/// Counts one monomial product.
#[inline]
pub(crate) fn monomial_product() {
    bump(|w| w.monomial_products += 1);
}

/// Counts one term put into an accumulating sum.
#[inline]
pub(crate) fn term_accumulated() {
    bump(|w| w.terms_accumulated += 1);
}

/// Counts the terms of a sum formed by merging two (one add for the
/// whole merge): a sum built by adding terms one at a time shows here as
/// the quadratic work it is.
#[inline]
pub(crate) fn terms_merged(n: usize) {
    bump(|w| w.terms_accumulated += n as u64);
}

/// Counts the nodes of a presented tree.
#[inline]
pub(crate) fn presented(nodes: usize) {
    bump(|w| w.presented_nodes += nodes as u64);
}
