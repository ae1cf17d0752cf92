//! The body of [`FreeBody`](super::FreeBody) with Eulerian angles: precession
//! φ about space Z, nutation θ, spin ψ (`R = R_Z(φ) R_y(θ) R_z(ψ)`, the
//! z-y-z convention of §7), state `y = [φ, θ, ψ, ω_1, ω_2, ω_3]`.
//!
//! With `ω' = R_z(ψ) ω` (components in the §7 frame, which does not spin):
//!
//! ```text
//! φ̇ = −ω'_x / sin θ,   θ̇ = ω'_y,   ψ̇ = ω_3 + ω'_x cos θ / sin θ
//! ```
//!
//! The kinematics divide by `sin θ`: at θ = 0 or π the angles are singular
//! and [`System::check`] reports [`SimError::EulerAngleSingularity`].

use nalgebra::{UnitQuaternion, Vector3};

use crate::{SimError, System};

/// Smallest `sin θ` accepted: below it one step of `φ̇` would lose more than
/// half of the digits of the state.
pub const SIN_THETA_MIN: f64 = 1e-8;

/// A torque-free body or heavy top in Eulerian angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerAngleBody {
    /// Principal moments (about G, or O under gravity).
    pub moments: [f64; 3],
    /// `W l` under gravity (G at `l e_3` from O), 0 without.
    pub weight_arm: f64,
}

/// Attitude quaternion `R_Z(φ) R_y(θ) R_z(ψ)`.
/// The one convention of every scene: [`hdot_num::body::eulerian_rotation`].
pub fn quaternion_from_angles(phi: f64, theta: f64, psi: f64) -> UnitQuaternion<f64> {
    hdot_num::body::eulerian_rotation(phi, theta, psi)
}

/// Eulerian angles `(φ, θ, ψ)` of an attitude, θ ∈ [0, π].
pub fn angles_from_quaternion(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    let r = q.to_rotation_matrix();
    let m = r.matrix();
    // Third column = R e_z = (sinθ cosφ, sinθ sinφ, cosθ); third row = (−sinθ cosψ, sinθ sinψ, cosθ).
    let theta = m[(2, 2)].clamp(-1.0, 1.0).acos();
    let phi = m[(1, 2)].atan2(m[(0, 2)]);
    let psi = m[(2, 1)].atan2(-m[(2, 0)]);
    (phi, theta, psi)
}

/// Converts an Eulerian-angle state to the 7-component quaternion state.
pub fn to_quaternion_state(y: &[f64; 6]) -> [f64; 7] {
    let q = quaternion_from_angles(y[0], y[1], y[2]);
    super::free::pack(&q, &Vector3::new(y[3], y[4], y[5]))
}

impl System<6> for EulerAngleBody {
    fn name(&self) -> &str {
        "euler-angles"
    }

    fn rhs(&self, _t: f64, y: &[f64; 6]) -> [f64; 6] {
        let (st, ct) = y[1].sin_cos();
        let (sp, cp) = y[2].sin_cos();
        let (w1, w2, w3) = (y[3], y[4], y[5]);
        let wx = cp * w1 - sp * w2;
        let wy = sp * w1 + cp * w2;
        let i = self.moments;
        // Rᵀ e_Z = (−sinθ cosψ, sinθ sinψ, cosθ); τ = W l (v_2, −v_1, 0).
        let tau = [self.weight_arm * st * sp, self.weight_arm * st * cp, 0.0];
        [
            -wx / st,
            wy,
            w3 + wx * ct / st,
            ((i[1] - i[2]) * w2 * w3 + tau[0]) / i[0],
            ((i[2] - i[0]) * w3 * w1 + tau[1]) / i[1],
            ((i[0] - i[1]) * w1 * w2 + tau[2]) / i[2],
        ]
    }

    fn check(&self, t: f64, y: &[f64; 6]) -> Result<(), SimError> {
        let s = y[1].sin();
        if s.is_nan() || s < SIN_THETA_MIN {
            return Err(SimError::EulerAngleSingularity {
                t,
                theta: y[1],
                sin_theta: s,
            });
        }
        Ok(())
    }
}
