//! # Derived equations against particle sums
//!
//! A system of particles at fixed relative positions is a rigid body, so a
//! derived result must agree with the direct particle sum to round-off.
//! Verification reads what a derivation file *declares* — its bodies,
//! points, conditions on the motion and what each step means — never its
//! name: [`check`] draws random bodies with the declared symmetry (clouds,
//! coarsely discretised posed primitives and composites, coaxial stacks;
//! exact symmetry by copying particles), binds the file's symbols from the
//! particle sums of *the same particles* (moments and products of inertia
//! as integrals, `I_xy = ∫xy dm`: the tensor holds them with a minus
//! sign), draws a motion, evaluates every step with a meaning with a
//! compiled [`Tape`](crate::eval::Tape) and compares it with the quantity
//! measured on the particles ([`quantities`], [`world`]): a particle sum
//! (Σ m r × a, Σ m r × v, Σ ½ m v², the inertia about P), point kinematics
//! from rotation matrices differentiated by the product rule (never
//! through ω or the transport theorem), or numerics on those sums (the
//! first-order part in the small symbols by central differences, the rates
//! of the linearised motion by a solve, a solve for the velocities after
//! an impulse). The path is described in [`declared`].
//!
//! (The rotation chains of [`motion`] are shared with the simulation's
//! tests.)
//!
//! The error of a comparison is `|derived − direct| / scale`, where the
//! scale is the sum of the magnitudes of the derived terms with every
//! symbol replaced by a bound on its size plus the magnitude of the direct
//! value and of the terms its computation sums (or cancels); it passes
//! below [`TOLERANCE_ULPS`] units of round-off.

mod bodies;
mod claims;
mod configuration;
mod declared;
mod draw;
mod expressed;
pub mod jet;
mod knowns;
mod linear;
mod linearized;
pub mod means;
pub mod motion;
mod partials;
mod placed;
mod power;
mod prepared;
pub mod quantities;
mod quaternion;
mod reactions;
mod speeds;
#[cfg(feature = "proptest")]
pub mod strategy;
pub mod world;

use hdot_sym::atom::Atom;
use hdot_sym::derivation::Derivation;

pub use bodies::{random_body, random_cloud};
pub use declared::{Options, Report, check, check_bodies, check_with};
pub use draw::{Draw, symmetric};

use crate::bind::BindError;
pub use crate::bind::Values;
use crate::error::BodyError;

/// Pass threshold, in units of `f64::EPSILON` relative to the scale.
pub const TOLERANCE_ULPS: f64 = 256.0;

/// Why a check could not run.
#[derive(Debug, thiserror::Error)]
pub enum VerifyError {
    /// The derived result uses a symbol the check does not bind.
    #[error("{derivation}: step {step} uses {symbol}, which the check does not bind")]
    Unbound {
        /// Derivation name.
        derivation: String,
        /// Step name.
        step: String,
        /// The symbol as printed.
        symbol: String,
    },
    /// A numeric solve failed (singular particle inertia).
    #[error("{derivation}: {what} is singular")]
    Singular {
        /// Derivation name.
        derivation: String,
        /// What could not be solved.
        what: &'static str,
    },
    /// A random body was invalid (a bug in the sampler).
    #[error(transparent)]
    Body(#[from] BodyError),
    /// The declarations cannot be met by the drawn bodies and motions.
    #[error("{derivation}: {message}")]
    Declaration {
        /// Derivation name.
        derivation: String,
        /// What is wrong.
        message: String,
    },
}

/// A declaration the drawn bodies and motions cannot meet.
pub(crate) fn declaration(d: &Derivation, message: String) -> VerifyError {
    VerifyError::Declaration {
        derivation: d.name.clone(),
        message,
    }
}

impl From<BindError> for VerifyError {
    /// An unbound symbol is attributed to its step later
    /// ([`VerifyError::in_step`]).
    fn from(e: BindError) -> Self {
        match e {
            BindError::Unbound(symbol) => VerifyError::Unbound {
                derivation: String::new(),
                step: String::new(),
                symbol,
            },
            BindError::Declaration {
                derivation,
                message,
            } => VerifyError::Declaration {
                derivation,
                message,
            },
        }
    }
}

impl VerifyError {
    pub(crate) fn unbound(d: &Derivation, step: &str, a: Atom) -> VerifyError {
        VerifyError::Unbound {
            derivation: d.name.clone(),
            step: step.into(),
            symbol: a.to_string(),
        }
    }

    /// The same error, attributed to `step` of `d`.
    pub(crate) fn in_step(self, d: &Derivation, step: &str) -> VerifyError {
        match self {
            VerifyError::Unbound { symbol, .. } => VerifyError::Unbound {
                derivation: d.name.clone(),
                step: step.into(),
                symbol,
            },
            e => e,
        }
    }
}

/// One derived value against its direct value.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// `step[component]`.
    pub quantity: String,
    /// The derived result, evaluated.
    pub derived: f64,
    /// The direct value (particle sum or independent numerics).
    pub direct: f64,
    /// The magnitudes involved.
    pub scale: f64,
}

impl Comparison {
    /// `|derived − direct| / scale` (0 when both vanish).
    pub fn relative_error(&self) -> f64 {
        let d = (self.derived - self.direct).abs();
        if d == 0.0 { 0.0 } else { d / self.scale }
    }

    /// Whether the error is within [`TOLERANCE_ULPS`].
    pub fn passes(&self) -> bool {
        self.relative_error() <= TOLERANCE_ULPS * f64::EPSILON
    }
}

/// One compared step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepCheck {
    /// The step's name.
    pub step: String,
    /// Its meaning as written.
    pub means: String,
    /// Its conditions as written (`given = [...]`, `symmetry = {...}`),
    /// empty without.
    pub conditions: String,
    /// What the meaning was measured as.
    pub against: String,
    /// The largest relative error over the draws.
    pub max_error: f64,
    /// The comparison with the largest error.
    pub worst: Option<Comparison>,
    /// Whether every comparison passed.
    pub passed: bool,
}
