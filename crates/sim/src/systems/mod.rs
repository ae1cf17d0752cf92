//! The equations of motion as [`crate::System`]s, one per file: the
//! right-hand sides the models of [`crate::models`] integrate (a model
//! entry says when and how; a system only says what moves).
//!
//! * [`free`]: a body about its mass centre (torque-free) or about a fixed
//!   point under gravity (heavy top): unit quaternion + body angular velocity.
//! * [`euler_angles`]: the same body with Eulerian angles (φ, θ, ψ), for
//!   comparison; singular at θ = 0 and θ = π.
//! * [`derived`]: the equations of motion a derivation file derived
//!   (solved accelerations or mass-matrix form), compiled and integrated in
//!   its own coordinates.
//! * [`shaft`]: rotation about a fixed axis, one degree of freedom, with the
//!   bearing reactions of §6.

pub mod derived;
pub mod euler_angles;
pub mod free;
pub mod precession;
pub mod shaft;
pub mod time_function;

pub use euler_angles::EulerAngleBody;
pub use free::{FreeBody, Gravity};
pub use precession::PrecessionAngle;
pub use shaft::Shaft;
