//! The torque-free body reduced to Euler's equations plus **one angle**.
//!
//! Without torque the angular momentum `H` is constant in space, so the
//! attitude is fixed by the body components of `H` (two angles: the
//! direction of the invariable axis in the body) and the angle `φ` the body
//! has turned about `H` (Landau & Lifshitz, *Mechanics* §37). In a right-handed
//! cyclic relabelling `(p, q, c)` of the principal axes, with 3-1-3 angles
//! from the invariable frame (space `Z` along `H`) to the body:
//!
//! ```text
//! I ω̇ = (I ω) × ω                                   (§5, no torque)
//! φ̇ = L (ω_p H_p + ω_q H_q) / (H_p² + H_q²)          (L = |H|, H = I ω)
//! cos θ = H_c / L,   tan ψ = H_p / H_q
//! R(t) = C R_Z(φ) R_X(θ) R_Z(ψ) Pᵀ,   C = R₀ P R_zf(0)ᵀ
//! ```
//!
//! `φ̇` follows from `ω = φ̇ H/L + θ̇ n + ψ̇ e_c` dotted with
//! `(H_p, H_q, 0)`, which is orthogonal to the line of nodes `n` and to
//! `e_c`. The state is `[ω_1, ω_2, ω_3, φ]` (4 components instead of 7):
//! the attitude error then follows the error of ω and of a single smooth
//! angle, instead of four quaternion components that an integrator must
//! resolve separately. The exact solution in [`crate::exact`] uses the same
//! frame with ω in closed form and `φ` by quadrature; this model integrates
//! both.
//!
//! **Projection.** The exact flow keeps the energy `E` and `|H|`; an
//! integrator's local errors change them, and with them the period of ω
//! and the mean precession rate, so the phase error at T grows with T²
//! instead of T. After every accepted step ω is moved back onto both
//! invariants ([`project_invariants`]; Hairer, Lubich & Wanner, *Geometric
//! Numerical Integration* §IV.4). The direction of `H` in space is kept by
//! construction (it is `C e_Z` for every state). Together they remove every
//! drift of a first integral, and what remains is the phase error along the
//! invariant torus. On the body of issue 5 this is worth a factor 10–20 in
//! the error at T = 100 for the same cost (docs/performance.md).
//!
//! The axis `c` is chosen so that `H` stays away from it over the whole
//! motion (the formula for `φ̇` is singular only where `H ∥ e_c`): among
//! the three axes, the one maximising the least value of `H_p² + H_q²` on the
//! orbit `|H| = L`, `Σ H_i²/I_i = 2E` (extremes of `H_c²` there lie where a
//! second component vanishes).
//!
//! Valid for torque-free motion only (a heavy top's `H` turns in space).

use nalgebra::{UnitQuaternion, Vector3};

use crate::System;
use crate::exact::{cyclic_perm, invariable_frame};
use crate::systems::free::pack;

/// Euler's equations plus the angle turned about the invariable `H`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrecessionAngle {
    /// Principal moments about G.
    pub moments: [f64; 3],
    /// The axis `c` of the 3-1-3 angles (0, 1 or 2).
    axis: usize,
    /// `C = R₀ P R_zf(0)ᵀ`.
    c_rot: UnitQuaternion<f64>,
    /// The cyclic relabelling `P` (coordinates in `(p, q, c)` → body).
    perm: UnitQuaternion<f64>,
    /// Initial `|H|²` and `2E`.
    invariants: [f64; 2],
    /// Project ω back onto `|H|² = L²`, `Σ I ω² = 2E` after every step
    /// (on by default; off only to compare with integrators that cannot).
    pub projection: bool,
}

impl PrecessionAngle {
    /// The model for principal moments `moments` started at attitude `q0`
    /// with body angular velocity `w0`, and its initial state
    /// `[ω_1, ω_2, ω_3, 0]`. `None` when `ω = 0` (no invariable axis).
    pub fn new(
        moments: [f64; 3],
        q0: &UnitQuaternion<f64>,
        w0: &Vector3<f64>,
    ) -> Option<(Self, [f64; 4])> {
        let i = moments;
        let h = Vector3::new(i[0] * w0.x, i[1] * w0.y, i[2] * w0.z);
        let l2 = h.norm_squared();
        if !(l2 > 0.0 && l2.is_finite()) {
            return None;
        }
        let two_e = h.x * w0.x + h.y * w0.y + h.z * w0.z;
        let axis = (0..3)
            .max_by(|&a, &b| {
                let fa = l2 - max_sq_on_orbit(i, a, l2, two_e, h[a] * h[a]);
                let fb = l2 - max_sq_on_orbit(i, b, l2, two_e, h[b] * h[b]);
                fa.total_cmp(&fb)
            })
            .expect("three axes");
        let mut s = PrecessionAngle {
            moments,
            axis,
            c_rot: UnitQuaternion::identity(),
            perm: cyclic_perm(axis),
            invariants: [l2, two_e],
            projection: true,
        };
        s.c_rot = q0 * s.perm * s.frame(&h, 0.0).inverse();
        Some((s, [w0.x, w0.y, w0.z, 0.0]))
    }

    /// The axis `c` the 3-1-3 angles use.
    pub fn axis(&self) -> usize {
        self.axis
    }

    /// `R_Z(φ) R_X(θ) R_Z(ψ)` from body `H` and `φ`.
    fn frame(&self, h: &Vector3<f64>, phi: f64) -> UnitQuaternion<f64> {
        let c = self.axis;
        let hp = Vector3::new(h[(c + 1) % 3], h[(c + 2) % 3], h[c]);
        invariable_frame(&hp, phi)
    }

    /// The attitude (body → space) of a state.
    pub fn attitude(&self, y: &[f64; 4]) -> UnitQuaternion<f64> {
        let i = self.moments;
        let h = Vector3::new(i[0] * y[0], i[1] * y[1], i[2] * y[2]);
        self.c_rot * self.frame(&h, y[3]) * self.perm.inverse()
    }

    /// The full state `[q, ω]` of a reduced state.
    pub fn full_state(&self, y: &[f64; 4]) -> [f64; 7] {
        pack(&self.attitude(y), &Vector3::new(y[0], y[1], y[2]))
    }
}

/// Largest `H_c²` on the orbit `|H|² = l2`, `Σ H_i²/I_i = two_e`: where a
/// second component vanishes (or the current value, for equal moments).
fn max_sq_on_orbit(i: [f64; 3], c: usize, l2: f64, two_e: f64, current: f64) -> f64 {
    let mut best = current;
    for o in (0..3).filter(|&o| o != c) {
        let den = 1.0 / i[c] - 1.0 / i[o];
        if den != 0.0 {
            let x = (two_e - l2 / i[o]) / den;
            if (0.0..=l2).contains(&x) {
                best = best.max(x);
            }
        }
    }
    best
}

impl System<4> for PrecessionAngle {
    fn name(&self) -> &str {
        "precession-angle"
    }

    /// Moves ω back onto the initial `|H|` and energy (see
    /// [`project_invariants`]) when [`PrecessionAngle::projection`] is set.
    fn project(&self, y: &mut [f64; 4]) -> bool {
        if !self.projection {
            return false;
        }
        let mut w = [y[0], y[1], y[2]];
        project_invariants(self.moments, self.invariants, &mut w);
        y[..3].copy_from_slice(&w);
        true
    }

    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; 4]) -> [f64; 4] {
        let i = self.moments;
        let (a, b, c) = (y[0], y[1], y[2]);
        let h = [i[0] * a, i[1] * b, i[2] * c];
        let k = self.axis;
        let (p, q) = ((k + 1) % 3, (k + 2) % 3);
        let l = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
        let phi_dot = l * (y[p] * h[p] + y[q] * h[q]) / (h[p] * h[p] + h[q] * h[q]);
        [
            (i[1] - i[2]) * b * c / i[0],
            (i[2] - i[0]) * c * a / i[1],
            (i[0] - i[1]) * a * b / i[2],
            phi_dot,
        ]
    }
}

/// Projects a body angular velocity `w` onto `|I w|² = inv[0]`,
/// `Σ I_i w_i² = inv[1]` along the gradients of the two invariants at `w`
/// (`w + 2 I² w λ₁ + 2 I w λ₂`, simplified Newton on λ; after an
/// integration step the residual is near the tolerance, so one iteration
/// reaches round-off and the second only confirms it). Left unchanged where
/// the gradients are parallel (`w` along a principal axis or equal
/// moments), where the 2×2 system is singular.
#[inline]
pub fn project_invariants(i: [f64; 3], inv: [f64; 2], w: &mut [f64; 3]) {
    let g1: [f64; 3] = std::array::from_fn(|k| 2.0 * i[k] * i[k] * w[k]);
    let g2: [f64; 3] = std::array::from_fn(|k| 2.0 * i[k] * w[k]);
    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (a11, a12, a22) = (dot(&g1, &g1), dot(&g1, &g2), dot(&g2, &g2));
    let det = a11 * a22 - a12 * a12;
    // Also catches NaN.
    if det.is_nan() || det <= 1e-12 * a11 * a22 {
        return;
    }
    let (mut l1, mut l2) = (0.0, 0.0);
    let mut x = *w;
    for _ in 0..3 {
        let h: [f64; 3] = std::array::from_fn(|k| i[k] * x[k]);
        let r1 = dot(&h, &h) - inv[0];
        let r2 = dot(&h, &x) - inv[1];
        if r1.abs() <= 8.0 * f64::EPSILON * inv[0] && r2.abs() <= 8.0 * f64::EPSILON * inv[1] {
            break;
        }
        l1 -= (a22 * r1 - a12 * r2) / det;
        l2 -= (a11 * r2 - a12 * r1) / det;
        x = std::array::from_fn(|k| w[k] + l1 * g1[k] + l2 * g2[k]);
    }
    *w = x;
}
