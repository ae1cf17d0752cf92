//! Numeric side of hdot: bodies, mass properties, particle sums, scenes.
//!
//! (Work in progress; see `docs/numerics.md`.)

pub mod body;
pub mod chart;
pub mod cloud;
pub mod convergence;
pub mod discretize;
pub mod error;
pub mod fsio;
pub mod inertia;
pub mod report;
pub mod scene;
pub mod solve;
pub mod sums;

pub use body::{Body, Composite, MassProperties, Part, Pose, Primitive};
pub use cloud::ParticleCloud;
pub use discretize::{Discretization, DiscretizedBody, DiscretizedComposite, Method};
pub use error::{BodyError, CsvError, CsvErrorKind};
pub use inertia::{Inertia, InertiaError, Principal};
pub use nalgebra;
pub use sums::{Kinetics, Motion, ParticleSource};
