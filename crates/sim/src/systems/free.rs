//! A rigid body with principal moments `I = (I_1, I_2, I_3)`, attitude as a
//! unit quaternion `q` (body → space) and body angular velocity `ω`.
//!
//! State `y = [q_w, q_x, q_y, q_z, ω_1, ω_2, ω_3]`:
//!
//! ```text
//! q̇ = ½ q ⊗ (0, ω)
//! I_1 ω̇_1 = (I_2 − I_3) ω_2 ω_3 + τ_1      (§5, cyclic)
//! τ = W l e_3 × (−Rᵀ e_Z)                     (heavy top: G at l e_3 from O)
//! ```
//!
//! Without gravity the moments are about G and `τ = 0`; with gravity they
//! are about the fixed point O.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::System;

/// Gravity on a body with a fixed point O: weight `W` times the distance
/// `l` from O to G along body axis 3 (space Z is up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// `W l` (weight × distance O→G).
    pub weight_arm: f64,
}

/// Torque-free body or heavy top, quaternion attitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeBody {
    /// Principal moments (about G, or about O when there is gravity).
    pub moments: [f64; 3],
    /// Gravity torque, if the body turns about a fixed point under gravity.
    pub gravity: Option<Gravity>,
}

/// Packs attitude and body angular velocity into the 7-component state.
pub fn pack(q: &UnitQuaternion<f64>, w: &Vector3<f64>) -> [f64; 7] {
    let q = q.quaternion();
    [q.w, q.i, q.j, q.k, w.x, w.y, w.z]
}

/// The attitude of a state, renormalised (the raw components may drift off
/// the unit sphere under a method that does not preserve `|q|`).
pub fn attitude(y: &[f64; 7]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(y[0], y[1], y[2], y[3]))
}

/// The body angular velocity of a state.
pub fn omega(y: &[f64; 7]) -> Vector3<f64> {
    Vector3::new(y[4], y[5], y[6])
}

/// Body coordinates of the space vertical `Rᵀ e_Z` for a unit quaternion.
pub fn vertical_in_body(y: &[f64; 7]) -> [f64; 3] {
    let (w, x, yy, z) = (y[0], y[1], y[2], y[3]);
    [
        2.0 * (x * z - w * yy),
        2.0 * (yy * z + w * x),
        1.0 - 2.0 * (x * x + yy * yy),
    ]
}

/// The error of a state against a reference: the attitude as the angle of
/// the rotation taking one attitude to the other (radians; each quaternion
/// renormalised, q and −q are one attitude), the angular velocity as the
/// Euclidean norm of the difference (rad/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateError {
    /// Rotation angle between the attitudes, in [0, π].
    pub attitude: f64,
    /// `|ω − ω_ref|`.
    pub omega: f64,
}

impl StateError {
    /// `√(attitude² + omega²)`: the one number the targets and the reports use.
    pub fn combined(&self) -> f64 {
        self.attitude.hypot(self.omega)
    }
}

/// Attitude angle and ω error of `a` against `b`; NaN if either is not finite.
///
/// # Example
/// ```
/// use hdot_sim::systems::free::{pack, state_error};
/// use hdot_sim::nalgebra::{UnitQuaternion, Vector3};
/// let w = Vector3::new(1.0, 2.0, 3.0);
/// let a = pack(&UnitQuaternion::identity(), &w);
/// let b = pack(&UnitQuaternion::from_euler_angles(1e-9, 0.0, 0.0), &w);
/// assert!((state_error(&a, &b).attitude - 1e-9).abs() < 1e-22);
/// ```
pub fn state_error(a: &[f64; 7], b: &[f64; 7]) -> StateError {
    if a.iter().chain(b.iter()).any(|v| !v.is_finite()) {
        return StateError {
            attitude: f64::NAN,
            omega: f64::NAN,
        };
    }
    let omega = ((a[4] - b[4]).powi(2) + (a[5] - b[5]).powi(2) + (a[6] - b[6]).powi(2)).sqrt();
    StateError {
        // 2 atan2(|v|, |w|) of the relative rotation: `angle_to` goes through
        // acos, which cannot tell angles below ~2e-8 from 0.
        attitude: {
            let d = attitude(a).rotation_to(&attitude(b));
            2.0 * d.imag().norm().atan2(d.scalar().abs())
        },
        omega,
    }
}

/// Distance between two states: [`StateError::combined`] of
/// [`state_error`], `√(angle² + |Δω|²)`.
pub fn state_distance(a: &[f64; 7], b: &[f64; 7]) -> f64 {
    state_error(a, b).combined()
}

/// # Invariants
impl FreeBody {
    /// Body angular momentum `H = I ω` (body components).
    pub fn momentum(&self, y: &[f64; 7]) -> [f64; 3] {
        let i = self.moments;
        [i[0] * y[4], i[1] * y[5], i[2] * y[6]]
    }

    /// Total energy: kinetic `½ Σ I_i ω_i²` plus `W l cos θ` under gravity.
    pub fn energy(&self, y: &[f64; 7]) -> f64 {
        let i = self.moments;
        let kinetic = 0.5 * (i[0] * y[4] * y[4] + i[1] * y[5] * y[5] + i[2] * y[6] * y[6]);
        match self.gravity {
            None => kinetic,
            Some(g) => kinetic + g.weight_arm * vertical_in_body(y)[2],
        }
    }

    /// `|H|` (conserved without torque).
    pub fn momentum_norm(&self, y: &[f64; 7]) -> f64 {
        let h = self.momentum(y);
        (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt()
    }

    /// Vertical component `H_Z = (Rᵀ e_Z) · H` (conserved under gravity).
    pub fn momentum_vertical(&self, y: &[f64; 7]) -> f64 {
        let h = self.momentum(y);
        let v = vertical_in_body(y);
        v[0] * h[0] + v[1] * h[1] + v[2] * h[2]
    }

    /// The conserved momentum measure: `|H|` without gravity, `H_Z` with it.
    pub fn momentum_invariant(&self, y: &[f64; 7]) -> f64 {
        match self.gravity {
            None => self.momentum_norm(y),
            Some(_) => self.momentum_vertical(y),
        }
    }

    /// Torque on the body in body components.
    pub fn torque(&self, y: &[f64; 7]) -> [f64; 3] {
        match self.gravity {
            None => [0.0; 3],
            Some(g) => {
                let v = vertical_in_body(y);
                // W l e_3 × (−v) = W l (v_2, −v_1, 0)
                [g.weight_arm * v[1], -g.weight_arm * v[0], 0.0]
            }
        }
    }
}

/// Quaternion kinematics `q̇ = ½ q ⊗ (0, ω)`.
#[inline]
pub(crate) fn quat_rate(y: &[f64; 7]) -> [f64; 4] {
    let (w, x, yy, z) = (y[0], y[1], y[2], y[3]);
    let (a, b, c) = (y[4], y[5], y[6]);
    [
        0.5 * (-x * a - yy * b - z * c),
        0.5 * (w * a + yy * c - z * b),
        0.5 * (w * b + z * a - x * c),
        0.5 * (w * c + x * b - yy * a),
    ]
}

/// Right-multiplies `q` (in `y[0..4]`) by a rotation of angle `angle`
/// about body axis `axis`.
#[inline]
fn rotate_attitude(y: &mut [f64; 7], axis: usize, angle: f64) {
    let (s, c) = (0.5 * angle).sin_cos();
    let (w, x, yy, z) = (y[0], y[1], y[2], y[3]);
    // q ⊗ (c, s e_axis)
    let r = match axis {
        0 => [w * c - x * s, x * c + w * s, yy * c + z * s, z * c - yy * s],
        1 => [w * c - yy * s, x * c - z * s, yy * c + w * s, z * c + x * s],
        _ => [w * c - z * s, x * c + yy * s, yy * c - x * s, z * c + w * s],
    };
    y[..4].copy_from_slice(&r);
}

/// # Splitting
impl FreeBody {
    /// Exact flow of `T_k = H_k² / (2 I_k)` for time `h`: the body turns
    /// about its axis `k` by `h ω_k`, so `H` (body) turns by `−h ω_k`.
    #[inline]
    fn free_rotation(&self, y: &mut [f64; 7], axis: usize, h: f64) {
        let angle = h * y[4 + axis];
        rotate_attitude(y, axis, angle);
        let i = self.moments;
        let mut m = [i[0] * y[4], i[1] * y[5], i[2] * y[6]];
        let (s, c) = angle.sin_cos();
        let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
        // Rot(e_k, −angle) on (m_p, m_q)
        let (mp, mq) = (m[p], m[q]);
        m[p] = c * mp + s * mq;
        m[q] = -s * mp + c * mq;
        y[4 + p] = m[p] / i[p];
        y[4 + q] = m[q] / i[q];
    }

    /// Exact flow of the potential: a kick `H ← H + h τ(q)` at fixed attitude.
    #[inline]
    fn gravity_kick(&self, y: &mut [f64; 7], h: f64) {
        let tau = self.torque(y);
        for k in 0..3 {
            y[4 + k] += h * tau[k] / self.moments[k];
        }
    }
}

impl System<7> for FreeBody {
    fn name(&self) -> &str {
        "rigid-body"
    }

    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; 7]) -> [f64; 7] {
        let i = self.moments;
        let tau = self.torque(y);
        let qd = quat_rate(y);
        let (a, b, c) = (y[4], y[5], y[6]);
        [
            qd[0],
            qd[1],
            qd[2],
            qd[3],
            ((i[1] - i[2]) * b * c + tau[0]) / i[0],
            ((i[2] - i[0]) * c * a + tau[1]) / i[1],
            ((i[0] - i[1]) * a * b + tau[2]) / i[2],
        ]
    }

    /// Strang splitting `T = T_1 + T_2 + T_3` (+ V under gravity):
    /// `V(h/2) ∘ T_1(h/2) ∘ T_2(h/2) ∘ T_3(h) ∘ T_2(h/2) ∘ T_1(h/2) ∘ V(h/2)`.
    fn strang_step(&self, _t: f64, y: &[f64; 7], h: f64) -> Option<([f64; 7], u64)> {
        let mut z = *y;
        let mut flows = 5;
        if self.gravity.is_some() {
            self.gravity_kick(&mut z, 0.5 * h);
            flows += 2;
        }
        self.free_rotation(&mut z, 0, 0.5 * h);
        self.free_rotation(&mut z, 1, 0.5 * h);
        self.free_rotation(&mut z, 2, h);
        self.free_rotation(&mut z, 1, 0.5 * h);
        self.free_rotation(&mut z, 0, 0.5 * h);
        if self.gravity.is_some() {
            self.gravity_kick(&mut z, 0.5 * h);
        }
        Some((z, flows))
    }
}

/// Euler's equations alone (§5, no torque): state `ω`, 3 components. The
/// angular velocity of a torque-free body does not depend on the attitude,
/// so this is the least system for ω(t); it is what the DOP853 cost target
/// and the comparison with `ode_solvers` integrate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerEquations {
    /// Principal moments about G.
    pub moments: [f64; 3],
}

impl System<3> for EulerEquations {
    fn name(&self) -> &str {
        "Euler's equations (ω only)"
    }

    #[inline]
    fn rhs(&self, _t: f64, w: &[f64; 3]) -> [f64; 3] {
        let i = self.moments;
        [
            (i[1] - i[2]) * w[1] * w[2] / i[0],
            (i[2] - i[0]) * w[2] * w[0] / i[1],
            (i[0] - i[1]) * w[0] * w[1] / i[2],
        ]
    }
}
