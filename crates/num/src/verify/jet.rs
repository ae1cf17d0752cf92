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
    mat_mat_to(a, b, ORDERS)
}

/// [`mat_mat`] to the first `orders` orders (the others zero).
pub(crate) fn mat_mat_to(a: &MatJet, b: &MatJet, orders: usize) -> MatJet {
    std::array::from_fn(|n| {
        if n < orders {
            (0..=n).map(|k| BINOMIAL[n][k] * a[k] * b[n - k]).sum()
        } else {
            Matrix3::zeros()
        }
    })
}

/// `(A v)⁽ⁿ⁾` by the product rule.
pub fn mat_vec(a: &MatJet, v: &VecJet) -> VecJet {
    mat_vec_to(a, v, ORDERS)
}

/// [`mat_vec`] to the first `orders` orders (the others zero).
pub(crate) fn mat_vec_to(a: &MatJet, v: &VecJet, orders: usize) -> VecJet {
    std::array::from_fn(|n| {
        if n < orders {
            (0..=n).map(|k| BINOMIAL[n][k] * a[k] * v[n - k]).sum()
        } else {
            Vector3::zeros()
        }
    })
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
    rotation_jet_to(k, q, ORDERS)
}

/// [`rotation_jet`] to the first `orders` orders (the others zero).
pub(crate) fn rotation_jet_to(k: usize, q: [f64; ORDERS], orders: usize) -> MatJet {
    let axis = nalgebra::Unit::new_unchecked(Vector3::ith(k, 1.0));
    let r = *nalgebra::Rotation3::from_axis_angle(&axis, q[0]).matrix();
    turn_jet(r, generator(k), q, orders)
}

/// `R, Ṙ, R̈, R⃛` of a turn `R` about the axis of generator `g` by `q(t)`,
/// to the first `orders` orders (the others zero).
fn turn_jet(r: Matrix3<f64>, g: Matrix3<f64>, q: [f64; ORDERS], orders: usize) -> MatJet {
    let mut jet = [r, Matrix3::zeros(), Matrix3::zeros(), Matrix3::zeros()];
    if orders > 1 {
        jet[1] = r * g * q[1];
    }
    if orders > 2 {
        let g2 = g * g;
        jet[2] = r * (g2 * (q[1] * q[1]) + g * q[2]);
        if orders > 3 {
            let g3 = g * g * g;
            jet[3] = r * (g3 * q[1].powi(3) + g2 * (3.0 * q[1] * q[2]) + g * q[3]);
        }
    }
    jet
}

/// The rotation about the unit axis `k` by `q(t)` and its derivatives
/// (a hinge), as [`rotation_jet`] with the generator `[k]×`.
pub fn hinge_jet(k: Vector3<f64>, q: [f64; ORDERS]) -> MatJet {
    hinge_jet_to(k, q, ORDERS)
}

/// [`hinge_jet`] to the first `orders` orders (the others zero).
pub(crate) fn hinge_jet_to(k: Vector3<f64>, q: [f64; ORDERS], orders: usize) -> MatJet {
    let axis = nalgebra::Unit::new_normalize(k);
    let r = *nalgebra::Rotation3::from_axis_angle(&axis, q[0]).matrix();
    turn_jet(r, axis.into_inner().cross_matrix(), q, orders)
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
