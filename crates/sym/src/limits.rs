//! Resource limits of symbolic work: terms in one polynomial, the work of
//! one product, the size of an exponent, the digits of a coefficient.
//!
//! A derivation is user input, and polynomial arithmetic can explode:
//! `(a + b + c + d + e + f)^60` has millions of terms, `a^2147483648 *
//! a^2147483648` overflows an exponent, a chain of thirty rotations doubles
//! its terms thirty times. Every such operation checks its budget **before**
//! the work that would break it (a product's pair count is known before it
//! is expanded), so an absurd input fails in well under a second.
//!
//! The arithmetic operators of [`Poly`](crate::Poly) are infallible (they
//! are used everywhere, nested deeply in vector and matrix code), so the
//! budget is carried in a thread-local *scope* rather than through every
//! signature: [`scope`] runs a computation under [`Limits`]; the first
//! operation that would exceed one records a [`LimitError`] and every later
//! operation in the scope returns zero at once, and [`scope`] returns the
//! error instead of the (meaningless) value. Outside any scope the limits
//! are not enforced, but an exponent that would overflow still panics
//! rather than wrap: exact arithmetic never silently wraps.

use std::cell::{Cell, RefCell};
use std::fmt;

/// The budget of one computation (one derivation step, by default).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Terms in one polynomial.
    pub max_terms: usize,
    /// Term products formed by one multiplication (`len(a) · len(b)`).
    pub max_work: u64,
    /// Absolute value of any exponent.
    pub max_exponent: u32,
    /// Bits in the numerator or denominator of any coefficient.
    pub max_bits: u64,
}

impl Limits {
    /// The defaults: generous enough for `chain-8` (the largest generated
    /// family: its biggest polynomial has 41,969 terms, its largest product
    /// forms 4,251 term products), small enough that reaching one takes
    /// well under a second of an optimised build even when a file grows a
    /// polynomial step by step up to the term limit (a million-term limit
    /// took seconds and gigabytes to reach that way).
    pub const DEFAULT: Limits = Limits {
        max_terms: 200_000,
        max_work: 5_000_000,
        max_exponent: 10_000,
        max_bits: 100_000,
    };
}

impl Default for Limits {
    fn default() -> Self {
        Limits::DEFAULT
    }
}

/// Which limit was exceeded, and by how much.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LimitError {
    /// A polynomial would have more terms than allowed.
    Terms {
        /// Terms the result would have (at least).
        needed: u64,
        /// The limit.
        limit: usize,
    },
    /// A product would form more term products than allowed.
    Work {
        /// Term products the multiplication needs.
        needed: u64,
        /// The limit.
        limit: u64,
    },
    /// An exponent would exceed the limit (or overflow).
    Exponent {
        /// The limit.
        limit: u32,
    },
    /// A coefficient would have more bits than allowed.
    Bits {
        /// Bits the coefficient would have (at least).
        needed: u64,
        /// The limit.
        limit: u64,
    },
}

impl LimitError {
    /// The name of the setting that raises this limit.
    pub fn setting(&self) -> &'static str {
        match self {
            LimitError::Terms { .. } => "max_terms",
            LimitError::Work { .. } => "max_work",
            LimitError::Exponent { .. } => "max_exponent",
            LimitError::Bits { .. } => "max_bits",
        }
    }
}

impl fmt::Display for LimitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LimitError::Terms { needed, limit } => write!(
                f,
                "the result would have at least {needed} terms, more than the limit of {limit}"
            ),
            LimitError::Work { needed, limit } => write!(
                f,
                "a product would form {needed} term products, more than the limit of {limit}"
            ),
            LimitError::Exponent { limit } => {
                write!(f, "an exponent would exceed the limit of {limit}")
            }
            LimitError::Bits { needed, limit } => write!(
                f,
                "a coefficient would have {needed} bits, more than the limit of {limit}"
            ),
        }
    }
}

impl std::error::Error for LimitError {}

struct Active {
    limits: Limits,
    error: Option<LimitError>,
}

thread_local! {
    static ACTIVE: RefCell<Vec<Active>> = const { RefCell::new(Vec::new()) };
    /// The innermost scope's `max_exponent` (`u32::MAX` outside any scope),
    /// kept apart because it is read on every exponent addition.
    static MAX_EXPONENT: Cell<u32> = const { Cell::new(u32::MAX) };
}

fn sync_max_exponent() {
    let m = ACTIVE.with(|a| {
        a.borrow()
            .last()
            .map_or(u32::MAX, |s| s.limits.max_exponent)
    });
    MAX_EXPONENT.with(|c| c.set(m));
}

/// Runs `f` under `limits`; the first limit exceeded is returned as the
/// error (the value `f` computed after it is discarded). Scopes nest: an
/// inner scope has its own budget.
pub fn scope<T>(limits: Limits, f: impl FnOnce() -> T) -> Result<T, LimitError> {
    ACTIVE.with(|a| {
        a.borrow_mut().push(Active {
            limits,
            error: None,
        })
    });
    sync_max_exponent();
    // Pop the scope even if `f` unwinds.
    struct Pop;
    impl Drop for Pop {
        fn drop(&mut self) {
            ACTIVE.with(|a| a.borrow_mut().pop());
            sync_max_exponent();
        }
    }
    let pop = Pop;
    let value = f();
    let error = ACTIVE.with(|a| a.borrow_mut().last_mut().and_then(|s| s.error.take()));
    drop(pop);
    match error {
        Some(e) => Err(e),
        None => Ok(value),
    }
}

/// True when the innermost scope has already exceeded a limit: operations
/// then return zero without working.
pub(crate) fn tripped() -> bool {
    ACTIVE.with(|a| a.borrow().last().is_some_and(|s| s.error.is_some()))
}

/// Records `e` in the innermost scope (the first error wins). Returns
/// false outside any scope.
fn trip(e: LimitError) -> bool {
    ACTIVE.with(|a| match a.borrow_mut().last_mut() {
        Some(s) => {
            s.error.get_or_insert(e);
            true
        }
        None => false,
    })
}

fn limits() -> Option<Limits> {
    ACTIVE.with(|a| a.borrow().last().map(|s| s.limits))
}

/// Checks a product of `n` by `m` terms before it is formed, each term
/// product weighing `weight` (more for long coefficients); false (and the
/// scope tripped) when it is over budget.
pub(crate) fn allow_product(n: usize, m: usize, weight: u64) -> bool {
    let Some(l) = limits() else { return true };
    let needed = (n as u64)
        .saturating_mul(m as u64)
        .saturating_mul(weight.max(1));
    if needed > l.max_work {
        trip(LimitError::Work {
            needed,
            limit: l.max_work,
        });
        return false;
    }
    true
}

/// Checks the term count of a result; false (and the scope tripped) when
/// it is over budget.
pub(crate) fn allow_terms(n: usize) -> bool {
    let Some(l) = limits() else { return true };
    if n > l.max_terms {
        trip(LimitError::Terms {
            needed: n as u64,
            limit: l.max_terms,
        });
        return false;
    }
    true
}

/// The sum of two exponents, checked: within the scope's limit, and never
/// wrapping. Outside a scope an overflow panics (it would otherwise give a
/// wrong answer); inside one it trips the scope and saturates.
#[inline]
pub(crate) fn add_exponents(a: i32, b: i32) -> i32 {
    match a.checked_add(b) {
        Some(s) if s.unsigned_abs() <= MAX_EXPONENT.with(Cell::get) => s,
        sum => exponent_over(a, b, sum),
    }
}

#[cold]
fn exponent_over(a: i32, b: i32, sum: Option<i32>) -> i32 {
    match limits() {
        None => panic!("exponent overflow: {a} + {b} does not fit in 32 bits"),
        Some(l) => {
            trip(LimitError::Exponent {
                limit: l.max_exponent,
            });
            sum.unwrap_or(if a > 0 { i32::MAX } else { i32::MIN })
        }
    }
}

/// Checks an exponent given directly (`x^n`); false (and the scope
/// tripped) when it is over the limit.
pub(crate) fn allow_exponent(n: u64) -> bool {
    let Some(l) = limits() else {
        return n <= i32::MAX as u64;
    };
    if n > u64::from(l.max_exponent) {
        trip(LimitError::Exponent {
            limit: l.max_exponent,
        });
        return false;
    }
    true
}

/// Checks the size of a coefficient that would have `bits` bits.
pub(crate) fn allow_bits(bits: u64) -> bool {
    let Some(l) = limits() else { return true };
    if bits > l.max_bits {
        trip(LimitError::Bits {
            needed: bits,
            limit: l.max_bits,
        });
        return false;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scope_reports_the_first_error_and_pops() {
        let r = scope(
            Limits {
                max_terms: 3,
                ..Limits::DEFAULT
            },
            || {
                assert!(allow_terms(3));
                assert!(!allow_terms(4));
                assert!(tripped());
                assert!(!allow_product(10, 10_000_000_000, 1));
                7
            },
        );
        assert_eq!(
            r,
            Err(LimitError::Terms {
                needed: 4,
                limit: 3
            })
        );
        assert!(!tripped());
        assert!(allow_terms(usize::MAX));
    }

    #[test]
    fn exponents_never_wrap() {
        let r = scope(Limits::DEFAULT, || add_exponents(i32::MAX, 1));
        assert!(matches!(r, Err(LimitError::Exponent { .. })));
        let r = scope(Limits::DEFAULT, || add_exponents(6_000, 6_000));
        assert!(matches!(r, Err(LimitError::Exponent { limit: 10_000 })));
        assert_eq!(add_exponents(2, 3), 5);
        assert!(std::panic::catch_unwind(|| add_exponents(i32::MIN, -1)).is_err());
    }
}
