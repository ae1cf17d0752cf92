//! Linear stability of a steady motion as a parameter varies: the
//! linearised equations M q̈ + C q̇ + K q = 0 a derivation derived, swept
//! over one of its constants (`hdot stability`, docs/stability.md).
//!
//! A stability scene (`kind = "stability"`, [`StabilityScene`]) names the
//! derivation, the steps whose values are M, C and K (square arrays in
//! the coordinates' order), values for the other constants and the sweep
//! (`parameter`, `from`, `to`, `count`). The matrices' entries are
//! compiled once to one `hdot-num` tape in the parameter alone
//! ([`LinearMatrices`]); at each value the state matrix
//! A = [[0, I], [−M⁻¹K, −M⁻¹C]] is formed and its eigenvalues computed
//! from the real Schur form ([`spectrum`]), ordered along the sweep
//! so that each column follows one eigenvalue ([`sweep()`]); the intervals
//! in which every real part is negative — and those in which none is
//! positive, for conservative systems such as a sleeping top — are found
//! on the grid and their ends refined by bisection ([`Interval`]).
//!
//! `scene.rs` reads the file; `grid.rs` spaces the values; `sweep.rs`
//! holds the numerics.

mod grid;
mod scene;
mod sweep;

pub use scene::{LinearMatrices, StabilityScene};
pub use sweep::{
    BISECTION_REL, Edge, Interval, MARGIN, STRICT_MARGIN, Sweep, csv, max_real_part, spectrum,
    state_matrix, sweep,
};
