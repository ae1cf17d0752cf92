//! Kinematics without the transport theorem: an attitude given as a chain
//! of elementary rotations `R(t) = R₁(q₁(t)) R₂(q₂(t)) …` is differentiated
//! twice by the product rule (`d/dq R_k(q) = R_k(q) [e_k]×`), so `R`, `Ṙ`
//! and `R̈` at the instant are exact to round-off and independent of any
//! formula for ω. Angular velocities are read off as `Ṙ Rᵀ` (world) and
//! `Rᵀ Ṙ` (own axes); particles move as `p = c + R q`, so `p̈ = c̈ + R̈ q`
//! with no α × r or ω × (ω × r).

use nalgebra::{Matrix3, Vector3};

use crate::cloud::ParticleCloud;
use crate::sums::{self, Block, Kernel};

/// An attitude and its first two time derivatives at an instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attitude {
    /// R (columns: the moving axes in the reference axes).
    pub r: Matrix3<f64>,
    /// Ṙ.
    pub rd: Matrix3<f64>,
    /// R̈.
    pub rdd: Matrix3<f64>,
}

/// `[e]×` for the unit vector of axis `k`.
fn generator(k: usize) -> Matrix3<f64> {
    let mut e = Vector3::zeros();
    e[k] = 1.0;
    e.cross_matrix()
}

/// The axial vector of the skew part of `s`.
fn vee(s: &Matrix3<f64>) -> Vector3<f64> {
    0.5 * Vector3::new(
        s[(2, 1)] - s[(1, 2)],
        s[(0, 2)] - s[(2, 0)],
        s[(1, 0)] - s[(0, 1)],
    )
}

impl Attitude {
    /// The rotation about axis `k` (0 = x, 1 = y, 2 = z) by `q(t)` with
    /// `q, q̇, q̈` given.
    pub fn about(k: usize, q: f64, qd: f64, qdd: f64) -> Self {
        let mut axis = Vector3::zeros();
        axis[k] = 1.0;
        let r =
            *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(axis), q).matrix();
        let g = generator(k);
        let rg = r * g;
        Self {
            r,
            rd: rg * qd,
            rdd: rg * g * (qd * qd) + rg * qdd,
        }
    }

    /// `self` followed by `next` (`R = R_self R_next`), by the product rule.
    pub fn then(&self, next: &Attitude) -> Self {
        Self {
            r: self.r * next.r,
            rd: self.rd * next.r + self.r * next.rd,
            rdd: self.rdd * next.r + 2.0 * self.rd * next.rd + self.r * next.rdd,
        }
    }

    /// ω in the reference axes: the axial vector of `Ṙ Rᵀ`.
    pub fn omega_world(&self) -> Vector3<f64> {
        vee(&(self.rd * self.r.transpose()))
    }

    /// α in the reference axes: the axial vector of `d/dt (Ṙ Rᵀ)`.
    pub fn alpha_world(&self) -> Vector3<f64> {
        vee(&(self.rdd * self.r.transpose() + self.rd * self.rd.transpose()))
    }

    /// ω in the moving axes: the axial vector of `Rᵀ Ṙ`.
    pub fn omega_own(&self) -> Vector3<f64> {
        vee(&(self.r.transpose() * self.rd))
    }

    /// The time derivative of [`Attitude::omega_own`]'s components.
    pub fn omega_own_rate(&self) -> Vector3<f64> {
        vee(&(self.rd.transpose() * self.rd + self.r.transpose() * self.rdd))
    }

    /// `v` (reference axes) in the moving axes: `Rᵀ v`.
    pub fn to_own(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.r.transpose() * v
    }
}

/// Direct sums for particles moving as `p(t) = R(t) q` (the origin O fixed,
/// `q` the particle's position in the body).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PathSums {
    /// Σ m p × ṗ.
    pub h_o: Vector3<f64>,
    /// Σ m p × p̈.
    pub moment_o: Vector3<f64>,
}

struct PathKernel(Attitude);

impl Kernel for PathKernel {
    type Acc = PathSums;

    fn accumulate(&self, acc: &mut PathSums, b: Block<'_>) {
        let Attitude { r, rd, rdd } = self.0;
        for i in 0..b.m.len() {
            let q = Vector3::new(b.x[i], b.y[i], b.z[i]);
            let (p, v, a) = (r * q, rd * q, rdd * q);
            acc.h_o += p.cross(&v) * b.m[i];
            acc.moment_o += p.cross(&a) * b.m[i];
        }
    }

    fn combine(&self, l: PathSums, r: PathSums) -> PathSums {
        PathSums {
            h_o: l.h_o + r.h_o,
            moment_o: l.moment_o + r.moment_o,
        }
    }
}

/// Σ m p × ṗ and Σ m p × p̈ (reference axes) for the particles of `body`
/// (body coordinates about O) carried by `attitude`.
pub fn path_sums(body: &ParticleCloud, attitude: &Attitude) -> PathSums {
    sums::reduce(body, &PathKernel(*attitude))
}
