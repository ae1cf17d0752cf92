//! The run budget: the steps one integration may take, a process-wide
//! setting (the command line's `--max-steps`) that every integration's
//! `Limits::default` takes and that `estimate` checks runs against before
//! they start. A leaf, so that the integrator and the estimates both read
//! it without importing each other.

use std::sync::atomic::{AtomicU64, Ordering};

/// The default run budget: steps (accepted and rejected) one integration
/// may take — 2^22, twice the finest fixed step of the work–precision
/// sweep. Documented in docs/cli.md; `--max-steps` raises it.
pub const DEFAULT_MAX_STEPS: u64 = 1 << 22;

static MAX_STEPS: AtomicU64 = AtomicU64::new(DEFAULT_MAX_STEPS);

/// The run budget in force: the steps one integration may take
/// ([`DEFAULT_MAX_STEPS`] unless [`set_max_steps`] changed it).
pub fn max_steps() -> u64 {
    MAX_STEPS.load(Ordering::Relaxed)
}

/// Sets the run budget for the rest of the process (the command line's
/// `--max-steps`); every integration's [`Limits::default`](crate::Limits::default) takes it.
pub fn set_max_steps(steps: u64) {
    MAX_STEPS.store(steps.max(1), Ordering::Relaxed);
}
