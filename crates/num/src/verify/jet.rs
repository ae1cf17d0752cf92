//! Jets: a function of time with its first three derivatives (the value,
//! rate, acceleration and jerk), and the product rule on them — the
//! arithmetic the instant's motion ([`super::world`]) and a draw's free
//! points ([`super::draw`]) are built from.

use nalgebra::{Matrix3, Vector3};

/// Orders kept in a jet: the value and three time derivatives.
pub const ORDERS: usize = 4;

pub(crate) const BINOMIAL: [[f64; ORDERS]; ORDERS] = [
    [1.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 0.0, 0.0],
    [1.0, 2.0, 1.0, 0.0],
    [1.0, 3.0, 3.0, 1.0],
];

/// A matrix function of time and its derivatives.
pub type MatJet = [Matrix3<f64>; ORDERS];
/// A vector function of time and its derivatives.
pub type VecJet = [Vector3<f64>; ORDERS];

/// `(a b)⁽ⁿ⁾ = Σ C(n, k) a⁽ᵏ⁾ b⁽ⁿ⁻ᵏ⁾`.
pub fn mat_mat(a: &MatJet, b: &MatJet) -> MatJet {
    std::array::from_fn(|n| (0..=n).map(|k| BINOMIAL[n][k] * a[k] * b[n - k]).sum())
}

/// `(A v)⁽ⁿ⁾` by the product rule.
pub fn mat_vec(a: &MatJet, v: &VecJet) -> VecJet {
    std::array::from_fn(|n| (0..=n).map(|k| BINOMIAL[n][k] * a[k] * v[n - k]).sum())
}

/// `(Aᵀ v)⁽ⁿ⁾` by the product rule.
pub fn mat_t_vec(a: &MatJet, v: &VecJet) -> VecJet {
    std::array::from_fn(|n| {
        (0..=n)
            .map(|k| BINOMIAL[n][k] * a[k].transpose() * v[n - k])
            .sum()
    })
}

/// `[e_k]×`.
pub(crate) fn generator(k: usize) -> Matrix3<f64> {
    Vector3::ith(k, 1.0).cross_matrix()
}

/// The axial vector of the skew part of `s`.
pub fn vee(s: &Matrix3<f64>) -> Vector3<f64> {
    0.5 * Vector3::new(
        s[(2, 1)] - s[(1, 2)],
        s[(0, 2)] - s[(2, 0)],
        s[(1, 0)] - s[(0, 1)],
    )
}

/// The rotation about axis `k` by `q(t)` and its derivatives, from
/// `q, q̇, q̈, q⃛`: `Ṙ = R G q̇`, `R̈ = R (G² q̇² + G q̈)`,
/// `R⃛ = R (G³ q̇³ + 3 G² q̇ q̈ + G q⃛)`.
pub fn rotation_jet(k: usize, q: [f64; ORDERS]) -> MatJet {
    let axis = nalgebra::Unit::new_unchecked(Vector3::ith(k, 1.0));
    let r = *nalgebra::Rotation3::from_axis_angle(&axis, q[0]).matrix();
    let g = generator(k);
    let (g2, g3) = (g * g, g * g * g);
    [
        r,
        r * g * q[1],
        r * (g2 * (q[1] * q[1]) + g * q[2]),
        r * (g3 * q[1].powi(3) + g2 * (3.0 * q[1] * q[2]) + g * q[3]),
    ]
}

/// The rotation about the unit axis `k` by `q(t)` and its derivatives
/// (a hinge), as [`rotation_jet`] with the generator `[k]×`.
pub fn hinge_jet(k: Vector3<f64>, q: [f64; ORDERS]) -> MatJet {
    let axis = nalgebra::Unit::new_normalize(k);
    let r = *nalgebra::Rotation3::from_axis_angle(&axis, q[0]).matrix();
    let g = axis.into_inner().cross_matrix();
    let (g2, g3) = (g * g, g * g * g);
    [
        r,
        r * g * q[1],
        r * (g2 * (q[1] * q[1]) + g * q[2]),
        r * (g3 * q[1].powi(3) + g2 * (3.0 * q[1] * q[2]) + g * q[3]),
    ]
}

/// Frobenius norm.
pub(crate) fn fro(m: &Matrix3<f64>) -> f64 {
    m.norm()
}

/// A point's motion: the jet (world axes) and the magnitudes of the terms
/// each order is computed from (for the round-off scale).
#[derive(Clone, Copy, Debug)]
pub struct PointJet {
    /// r, ṙ, r̈, r⃛ in N's axes.
    pub r: VecJet,
    /// Magnitudes of the terms summed into each order.
    pub mag: [f64; ORDERS],
}
