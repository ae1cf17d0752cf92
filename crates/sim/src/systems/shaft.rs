//! Rotation about a fixed axis (§6): one degree of freedom, state
//! `y = [angle, ω]`, body axes Oxyz with z along the shaft.
//!
//! ```text
//! I_z α = M_motor(ω) = T_0 (1 − ω/ω_0) − c ω      (α = ω̇)
//! ΣM_x = −I_xz α + I_yz ω²,   ΣM_y = −I_yz α − I_xz ω²
//! ΣF   = m ā,  ā = α k × r̄ − ω² r̄                (r̄ = (x̄, ȳ, 0))
//! ```
//!
//! The motor law is linear in ω, so the motion has a closed form
//! ([`Shaft::exact`]); the bearing reactions at `z_A`, `z_B` follow from the
//! moment and force sums (weight and axial loads excluded: the dynamic part).

use crate::System;

/// A shaft turning about the fixed z axis under a motor torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shaft {
    /// Moment of inertia about the axis.
    pub i_z: f64,
    /// Products of inertia about O (`∫ xz dm`, `∫ yz dm`).
    pub i_xz: f64,
    /// See `i_xz`.
    pub i_yz: f64,
    /// Mass carried by the shaft.
    pub mass: f64,
    /// Mass centre offset from the axis, body x and y.
    pub xbar: f64,
    /// See `xbar`.
    pub ybar: f64,
    /// Stall torque `T_0` of the motor.
    pub stall_torque: f64,
    /// No-load speed `ω_0` of the motor (`f64::INFINITY` for constant torque).
    pub no_load_speed: f64,
    /// Viscous friction coefficient `c`.
    pub friction: f64,
    /// Axial positions of the two bearings A and B.
    pub bearings: [f64; 2],
}

/// Bearing reactions (body x, y components) at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reactions {
    /// Angular acceleration α.
    pub alpha: f64,
    /// ΣM_x about O (body axes).
    pub moment_x: f64,
    /// ΣM_y about O.
    pub moment_y: f64,
    /// ΣM_z about O (= I_z α).
    pub moment_z: f64,
    /// Reaction at bearing A, body x and y.
    pub bearing_a: [f64; 2],
    /// Reaction at bearing B, body x and y.
    pub bearing_b: [f64; 2],
}

impl Shaft {
    /// `α = a − b ω` with `a = T_0 / I_z`, `b = (T_0/ω_0 + c) / I_z`.
    fn coefficients(&self) -> (f64, f64) {
        let a = self.stall_torque / self.i_z;
        let b = (self.stall_torque / self.no_load_speed + self.friction) / self.i_z;
        (a, b)
    }

    /// Angular acceleration at speed ω.
    pub fn alpha(&self, w: f64) -> f64 {
        let (a, b) = self.coefficients();
        a - b * w
    }

    /// Kinetic energy `½ I_z ω²`.
    pub fn energy(&self, y: &[f64; 2]) -> f64 {
        0.5 * self.i_z * y[1] * y[1]
    }

    /// Closed-form state at time `t` from `y0` at time 0.
    pub fn exact(&self, y0: &[f64; 2], t: f64) -> [f64; 2] {
        let (a, b) = self.coefficients();
        if (b * t).abs() < 1e-300 {
            return [y0[0] + y0[1] * t + 0.5 * a * t * t, y0[1] + a * t];
        }
        let w_inf = a / b;
        let decay = -(-b * t).exp_m1(); // 1 − e^{−bt}
        let w = y0[1] + (w_inf - y0[1]) * decay;
        // ∫ω = ω_∞ t − (ω_∞ − ω_0)(1 − e^{−bt}) / b
        let angle = y0[0] + w_inf * t - (w_inf - y0[1]) * decay / b;
        [angle, w]
    }

    /// Moments of §6 and the bearing reactions at speed ω.
    pub fn reactions(&self, w: f64) -> Reactions {
        let alpha = self.alpha(w);
        let moment_x = -self.i_xz * alpha + self.i_yz * w * w;
        let moment_y = -self.i_yz * alpha - self.i_xz * w * w;
        let moment_z = self.i_z * alpha;
        // m ā in body axes.
        let fx = self.mass * (-alpha * self.ybar - w * w * self.xbar);
        let fy = self.mass * (alpha * self.xbar - w * w * self.ybar);
        // R_A + R_B = F;  Σ z e_3 × R = (−z R_y, z R_x):
        //   −(z_A R_Ay + z_B R_By) = M_x,  z_A R_Ax + z_B R_Bx = M_y.
        let [za, zb] = self.bearings;
        let span = zb - za;
        let rbx = (moment_y - za * fx) / span;
        let rax = fx - rbx;
        let rby = (-moment_x - za * fy) / span;
        let ray = fy - rby;
        Reactions {
            alpha,
            moment_x,
            moment_y,
            moment_z,
            bearing_a: [rax, ray],
            bearing_b: [rbx, rby],
        }
    }
}

impl System<2> for Shaft {
    fn name(&self) -> &str {
        "fixed-axis"
    }

    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; 2]) -> [f64; 2] {
        [y[1], self.alpha(y[1])]
    }

    /// Strang splitting into the drift `angle += ω h/2` and the exact motor
    /// flow of `ω̇ = a − b ω` over `h`.
    fn strang_step(&self, _t: f64, y: &[f64; 2], h: f64) -> Option<([f64; 2], u64)> {
        let (a, b) = self.coefficients();
        let mut angle = y[0] + 0.5 * h * y[1];
        let w = if b == 0.0 {
            y[1] + a * h
        } else {
            let w_inf = a / b;
            y[1] + (w_inf - y[1]) * (-(-b * h).exp_m1())
        };
        angle += 0.5 * h * w;
        Some(([angle, w], 3))
    }
}
