//! Numeric side of hdot: bodies, mass properties, particle sums, scenes.
//!
//! (Work in progress; see `docs/numerics.md`.)

pub mod chart;
pub mod fsio;
