//! # hdot-num: the numbers behind the equations
//!
//! A system of particles at fixed relative positions *is* a rigid body, so
//! every equation the symbolic side derives must hold for one, to
//! round-off. This crate makes such bodies and computes what the equations
//! talk about.
//!
//! ## What it owns
//!
//! - **Mass properties** ([`inertia`], [`body`], [`cloud`]): the
//!   [`Inertia`] tensor whose invariant (symmetric, positive
//!   semi-definite, triangle inequalities, relative tolerance) lives in the
//!   type; posed [`Primitive`]s with the analytic values of the reference
//!   table; [`Composite`]s; [`ParticleCloud`]s from code or CSV;
//!   [`MassProperties`] about G or any point, in any axes; principal
//!   moments with a canonical basis for repeated moments.
//! - **Particles and sums** ([`discretize`], [`sums`]): lazy midpoint and
//!   Gauss–Legendre discretisations (10⁸ particles in the memory of one
//!   block per thread), deterministic parallel pairwise sums, and the
//!   kinetic sums H_G, H_O, T, Σ m a, Ḣ_G, Σ m r × a next to the same
//!   quantities from the rigid-body formulas ([`sums::rigid_kinetics`]).
//! - **Worked problems** ([`scene`], [`solve`], [`report`]): TOML scenes,
//!   the loads a motion requires, impulse–momentum, unknown forces and
//!   couples solved by an SVD that refuses underdetermined and
//!   inconsistent sets.
//! - **Convergence and charts** ([`convergence`], [`chart`]): error against
//!   resolution, observed orders, the cheapest discretisation for a
//!   tolerance; log–log SVG/PNG charts (shared with `hdot-sim`).
//! - **Declared symbols bound to numbers** ([`bind`]): a derivation's
//!   `[[body]]` and `gravity` symbols solved from given bodies' mass
//!   properties — the one binding that `verify` and `hdot-sim`'s derived
//!   scenes both use.
//! - **Derived results as numbers** ([`eval`], [`verify`]): a derived
//!   polynomial compiled to a flat f64 tape; `hdot verify`'s checks, which
//!   bind a derivation's symbols from particle sums of random bodies and
//!   compare its results with direct sums over the same particles (never
//!   with the rigid-body formulas of [`sums::rigid_kinetics`], which are
//!   what is being checked).
//!
//! ## What it does not own, and why
//!
//! - No symbolic algebra: that is `hdot-sym`. This crate reads its
//!   results (canonical polynomials of a loaded derivation) only in
//!   [`eval`], [`bind`] and [`verify`]; the bodies, sums and scenes use no
//!   expression types, so either side can change without the other.
//! - No time integration: that is `hdot-sim` (which reuses [`chart`]).
//! - No printing policy beyond [`report::Report`]: the CLI decides formats,
//!   progress bars and exit codes; the library returns typed errors
//!   ([`BodyError`], [`CsvError`], [`scene::SceneError`],
//!   [`solve::SolveError`]) that name the file, line and field.
//!
//! ## Example
//!
//! ```
//! use hdot_num::{Body, Discretization, DiscretizedBody, Pose, Primitive, sums};
//! let disk = Body::try_new(Primitive::Disk { radius: 2.0 }, 3.0, Pose::identity()).unwrap();
//! let exact = disk.mass_properties();                 // I_z = m r²/2 = 6
//! let particles = DiscretizedBody::new(&disk, &Discretization::gauss(8, 2));
//! let summed = sums::mass_properties(&particles).unwrap();
//! let iz = summed.inertia_g.moments()[2];
//! assert!((iz - exact.inertia_g.moments()[2]).abs() < 1e-9 * iz);
//! ```

pub mod bind;
pub mod body;
pub mod chart;
pub mod cloud;
pub mod convergence;
pub mod discretize;
pub mod error;
pub mod eval;
pub mod fsio;
pub mod inertia;
pub mod mass;
pub mod report;
pub mod scene;
pub mod solve;
pub mod sums;
pub mod verify;

pub use body::{Body, Composite, MassProperties, Part, Pose, Primitive};
pub use cloud::ParticleCloud;
pub use discretize::{Discretization, DiscretizedBody, DiscretizedComposite, Method};
pub use error::{BodyError, CsvError, CsvErrorKind};
pub use inertia::{Inertia, InertiaError, Principal};
pub use nalgebra;
pub use sums::{Kinetics, Motion, ParticleSource};
