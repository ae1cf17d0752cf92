//! # hdot-sim: the motion of rigid bodies, integrated or exact
//!
//! **Owns**: the equations of motion as ODE right-hand sides
//! ([`systems`]: torque-free body and heavy top with a unit-quaternion
//! attitude, the same in Eulerian angles, a shaft about a fixed axis, a
//! derivation's compiled equations), the integrators ([`integrate()`]:
//! explicit Euler, RK4, Dormand–Prince 5(4) and 8(5,3), implicit midpoint,
//! symplectic splittings of order 2 and 4), the closed-form motions
//! ([`exact`], with Jacobi elliptic functions of our own in [`elliptic`]),
//! scenes ([`scene`]), the models of the motion as self-describing
//! registry entries ([`model`] says what an entry is, [`models`] lists
//! them, one file each), the choice of the least exact model for a scene,
//! the run and its report ([`run`], recording through [`record`]) and the
//! work-precision sweep ([`sweep`]).
//!
//! **A simulation's path**: [`scene::Scene`] reads the file; [`run::plan`]
//! asks each entry of [`models::MODELS`] whether it applies and covers the
//! scene and picks the least; [`run::run`] runs the planned entry, whose
//! integrated systems record through [`record::integrate_recorded`], and
//! builds the [`run::Report`] from the entry's [`model::Outcome`].
//!
//! **Does not own**: deriving the equations (that is `hdot-sym`: this crate
//! codes the *results* of §5–§10 of `docs/equations.md`, which the symbolic
//! crate derives and checks), general numerics (`hdot-num`), the command
//! line (`hdot`).
//!
//! **Why cut this way**: a simulation wants a fixed-size state and a
//! right-hand side that costs a few dozen flops; evaluating derived
//! expressions at run time would dominate every comparison of methods. The
//! equations here are short, stated once in each model's docs, and tested
//! against the invariants they must conserve, the closed forms, and the
//! derived equations themselves: `tests/sim/derived.rs` compiles
//! `derivations/euler-principal.toml`'s moment equations with
//! `hdot_num::eval::Tape`, solves them for ω̇ and checks the hand-written
//! right-hand sides at random seeded states to round-off, and the heavy
//! top's against `derivations/gyroscope.toml`'s moment equations in
//! Eulerian angles (the angle accelerations that produce its ω̇ give the
//! derived ΣM_O equal to its gravity torque). The hand-written form stays
//! for speed (a few dozen flops, no tape, no allocation).
//!
//! ## Conventions
//! State `[q_w, q_x, q_y, q_z, ω_1, ω_2, ω_3]`: `q` turns body axes into
//! space axes, `ω` is in body principal axes. Space Z is up.

pub mod body;
mod budget;
pub mod dd;
pub mod elliptic;
mod error;
pub mod estimate;
pub mod exact;
mod integrate;
pub mod model;
pub mod models;
pub mod record;
pub mod run;
pub mod scene;
pub mod stability;
pub mod sweep;
mod system;
pub mod systems;
mod tableau;

pub use body::PrincipalMoments;
pub use error::SimError;
pub use integrate::{Limits, Method, Stats, Step, fixed_step_count, integrate};
/// Re-exported so that users (and the tests) name the same nalgebra version.
pub use nalgebra;
pub use system::System;
