//! The inertia tensor, with its physical invariants in the type.
//!
//! An [`Inertia`] is a 3×3 tensor in the convention of `docs/equations.md` §0:
//! moments on the diagonal, products of inertia with a **minus** sign off
//! the diagonal,
//!
//! ```text
//!         |  I_x   -I_xy  -I_xz |
//!   [I] = | -I_yx   I_y   -I_yz |
//!         | -I_zx  -I_zy   I_z  |
//! ```
//!
//! **Invariant** (checked by [`Inertia::try_new`], assumed by
//! [`Inertia::new_unchecked`]): every entry finite, the matrix symmetric,
//! positive semi-definite, and its principal moments satisfy the triangle
//! inequalities `I_1 + I_2 ≥ I_3` (each way round) — all up to a tolerance
//! *relative* to the trace. Flat bodies, which sit exactly on the triangle
//! inequality, are accepted; `diag(1, 3, 5)` is rejected.
//!
//! The tensor does not know the point it is taken about nor its axes: that
//! is the job of [`crate::MassProperties`], which keeps the mass, the centre
//! and the tensor about the centre in world axes.

use nalgebra::{Matrix3, Rotation3, SymmetricEigen, Vector3};

/// Default relative tolerance of the invariant checks (relative to the
/// trace of the tensor). Loose enough for sums of 10⁸ particles, tight
/// enough to reject any tensor that is physically wrong.
pub const DEFAULT_RTOL: f64 = 1e-10;

/// Default relative tolerance under which two principal moments count as
/// equal (relative to the largest moment).
pub const DEFAULT_REPEAT_RTOL: f64 = 1e-9;

/// Why a matrix is not an inertia tensor.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InertiaError {
    /// An entry is NaN or infinite.
    #[error("inertia entry ({row}, {col}) is not finite: {value}")]
    NotFinite {
        /// Row index (0-based).
        row: usize,
        /// Column index (0-based).
        col: usize,
        /// The offending value.
        value: f64,
    },
    /// `I[row][col] ≠ I[col][row]` beyond the tolerance.
    #[error("inertia is not symmetric: entry ({row}, {col}) = {a} but ({col}, {row}) = {b}")]
    NotSymmetric {
        /// Row index (0-based).
        row: usize,
        /// Column index (0-based).
        col: usize,
        /// `I[row][col]`.
        a: f64,
        /// `I[col][row]`.
        b: f64,
    },
    /// A principal moment is negative beyond the tolerance.
    #[error("inertia is not positive semi-definite: principal moment {moment} < 0")]
    NotPositiveSemiDefinite {
        /// The most negative principal moment.
        moment: f64,
    },
    /// The principal moments break a triangle inequality.
    #[error(
        "principal moments {moments:?} break the triangle inequality: {a} + {b} < {c} (no body has this inertia)"
    )]
    Triangle {
        /// The principal moments, ascending.
        moments: [f64; 3],
        /// Smaller moment.
        a: f64,
        /// Middle moment.
        b: f64,
        /// Largest moment.
        c: f64,
    },
}

/// A physically valid inertia tensor (see the module docs for the
/// invariant and the sign convention).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia(Matrix3<f64>);

/// Principal moments and axes of an [`Inertia`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Principal {
    /// Principal moments, ascending.
    pub moments: Vector3<f64>,
    /// Principal axes: column `i` is the unit axis of `moments[i]`, in the
    /// axes of the tensor. Always a proper rotation (right-handed).
    pub axes: Rotation3<f64>,
    /// Multiplicity of each moment (1, 2 or 3), as decided by the
    /// repeat tolerance.
    pub multiplicity: [usize; 3],
}

/// # Construction
impl Inertia {
    /// Checks the invariant with [`DEFAULT_RTOL`].
    ///
    /// # Example
    /// ```
    /// use hdot_num::Inertia;
    /// use nalgebra::Matrix3;
    /// assert!(Inertia::try_new(Matrix3::from_diagonal(&[2.0, 3.0, 4.0].into())).is_ok());
    /// // flat body: I_z = I_x + I_y exactly
    /// assert!(Inertia::try_new(Matrix3::from_diagonal(&[1.0, 3.0, 4.0].into())).is_ok());
    /// // positive definite but impossible
    /// assert!(Inertia::try_new(Matrix3::from_diagonal(&[1.0, 3.0, 5.0].into())).is_err());
    /// ```
    pub fn try_new(m: Matrix3<f64>) -> Result<Self, InertiaError> {
        Self::try_new_with_tol(m, DEFAULT_RTOL)
    }

    /// Checks the invariant with a tolerance `rtol` relative to the trace.
    pub fn try_new_with_tol(m: Matrix3<f64>, rtol: f64) -> Result<Self, InertiaError> {
        for row in 0..3 {
            for col in 0..3 {
                let value = m[(row, col)];
                if !value.is_finite() {
                    return Err(InertiaError::NotFinite { row, col, value });
                }
            }
        }
        let scale = m.diagonal().abs().sum().max(f64::MIN_POSITIVE);
        let tol = rtol * scale;
        for (row, col) in [(0, 1), (1, 2), (0, 2)] {
            let (a, b) = (m[(row, col)], m[(col, row)]);
            if (a - b).abs() > tol {
                return Err(InertiaError::NotSymmetric { row, col, a, b });
            }
        }
        let sym = (m + m.transpose()) * 0.5;
        let mut ev: Vec<f64> = SymmetricEigen::new(sym)
            .eigenvalues
            .iter()
            .copied()
            .collect();
        ev.sort_by(f64::total_cmp);
        if ev[0] < -tol {
            return Err(InertiaError::NotPositiveSemiDefinite { moment: ev[0] });
        }
        if ev[0] + ev[1] < ev[2] - tol {
            return Err(InertiaError::Triangle {
                moments: [ev[0], ev[1], ev[2]],
                a: ev[0],
                b: ev[1],
                c: ev[2],
            });
        }
        Ok(Self(sym))
    }

    /// Wraps `m` without checking; the caller guarantees the invariant
    /// (e.g. a tensor computed from positive masses).
    pub fn new_unchecked(m: Matrix3<f64>) -> Self {
        Self(m)
    }

    /// The tensor from moments `I_x, I_y, I_z` and products
    /// `I_xy, I_yz, I_zx` (the integrals ∫xy dm…, entered with a minus
    /// sign), checked.
    ///
    /// # Example
    /// ```
    /// use hdot_num::Inertia;
    /// let i = Inertia::from_components(2.0, 2.0, 2.0, 0.5, 0.0, 0.0).unwrap();
    /// assert_eq!(i.matrix()[(0, 1)], -0.5);
    /// assert_eq!(i.products(), [0.5, 0.0, 0.0]);
    /// ```
    pub fn from_components(
        ix: f64,
        iy: f64,
        iz: f64,
        ixy: f64,
        iyz: f64,
        izx: f64,
    ) -> Result<Self, InertiaError> {
        Self::try_new(Matrix3::new(
            ix, -ixy, -izx, //
            -ixy, iy, -iyz, //
            -izx, -iyz, iz,
        ))
    }

    /// Diagonal tensor (principal axes along x, y, z), checked.
    pub fn diagonal(ix: f64, iy: f64, iz: f64) -> Result<Self, InertiaError> {
        Self::from_components(ix, iy, iz, 0.0, 0.0, 0.0)
    }

    /// The zero tensor (a point mass about its own position).
    pub fn zero() -> Self {
        Self(Matrix3::zeros())
    }
}

/// # Access
impl Inertia {
    /// The tensor as a matrix (products with a minus sign).
    pub fn matrix(&self) -> &Matrix3<f64> {
        &self.0
    }

    /// Moments `[I_x, I_y, I_z]`.
    pub fn moments(&self) -> [f64; 3] {
        [self.0[(0, 0)], self.0[(1, 1)], self.0[(2, 2)]]
    }

    /// Products `[I_xy, I_yz, I_zx]` as integrals (`∫xy dm`…), i.e. the
    /// negated off-diagonal entries.
    pub fn products(&self) -> [f64; 3] {
        [-self.0[(0, 1)], -self.0[(1, 2)], -self.0[(2, 0)]]
    }

    /// The trace (sum of the moments), a natural scale for tolerances.
    pub fn trace(&self) -> f64 {
        self.0.trace()
    }
}

/// # Operations
impl Inertia {
    /// The same body's tensor in axes whose unit vectors are the columns of
    /// `axes` (given in the current axes): `Rᵀ I R`.
    pub fn in_axes(&self, axes: &Rotation3<f64>) -> Self {
        let r = axes.matrix();
        Self(symmetrise(r.transpose() * self.0 * r))
    }

    /// The tensor of the body after it is rotated by `rot`, in the same
    /// axes: `R I Rᵀ`.
    pub fn rotated(&self, rot: &Rotation3<f64>) -> Self {
        let r = rot.matrix();
        Self(symmetrise(r * self.0 * r.transpose()))
    }

    /// Parallel-axis theorem: `self` is about the mass centre G; the
    /// result is about a point P with `d = G − P` (same axes):
    /// `I_P = I_G + m (|d|² E − d dᵀ)`.
    pub fn shifted_from_centre(&self, mass: f64, d: &Vector3<f64>) -> Self {
        Self(self.0 + point_mass_tensor(mass, d))
    }

    /// Inverse parallel-axis theorem: `self` is about P, the result about G
    /// with `d = G − P`. Checked, since subtraction can break the
    /// invariant when the input is inconsistent.
    pub fn to_centre(&self, mass: f64, d: &Vector3<f64>) -> Result<Self, InertiaError> {
        Self::try_new(self.0 - point_mass_tensor(mass, d))
    }

    /// Sum of two tensors about the same point in the same axes.
    pub fn add(&self, other: &Self) -> Self {
        Self(self.0 + other.0)
    }

    /// `I ω`: angular momentum for angular velocity `omega`.
    pub fn apply(&self, omega: &Vector3<f64>) -> Vector3<f64> {
        self.0 * omega
    }

    /// Principal moments (ascending) and a canonical right-handed basis of
    /// principal axes, with [`DEFAULT_REPEAT_RTOL`].
    pub fn principal(&self) -> Principal {
        self.principal_with_tol(DEFAULT_REPEAT_RTOL)
    }

    /// Principal moments and canonical axes; moments within `rtol` × the
    /// largest moment of each other count as repeated.
    ///
    /// The basis is canonical, i.e. the same for tensors that differ by
    /// round-off:
    /// - all three moments equal: the world axes x, y, z;
    /// - a distinct axis gets the sign that makes its largest component
    ///   positive (the first such on ties);
    /// - a repeated pair spans a plane: its first axis is the projection on
    ///   that plane of the first world axis (x, y, then z) that lies
    ///   furthest from the plane's normal; the second completes a
    ///   right-handed triad.
    ///
    /// # Example
    /// ```
    /// use hdot_num::Inertia;
    /// let disk = Inertia::diagonal(0.25, 0.25, 0.5).unwrap();
    /// let p = disk.principal();
    /// assert_eq!(p.multiplicity, [2, 2, 1]);
    /// assert_eq!(p.axes.matrix().column(2), nalgebra::Vector3::z());
    /// ```
    pub fn principal_with_tol(&self, rtol: f64) -> Principal {
        let eig = SymmetricEigen::new(self.0);
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let lam = Vector3::new(
            eig.eigenvalues[idx[0]],
            eig.eigenvalues[idx[1]],
            eig.eigenvalues[idx[2]],
        );
        let vec = |i: usize| -> Vector3<f64> { eig.eigenvectors.column(idx[i]).into_owned() };
        let scale = lam.abs().max().max(f64::MIN_POSITIVE);
        let tol = rtol * scale;
        let eq01 = (lam[1] - lam[0]).abs() <= tol;
        let eq12 = (lam[2] - lam[1]).abs() <= tol;
        let (axes, multiplicity) = if eq01 && eq12 {
            (Matrix3::identity(), [3, 3, 3])
        } else if eq01 {
            let n = canonical_sign(vec(2));
            let (a, b) = plane_basis(&n);
            (Matrix3::from_columns(&[a, b, n]), [2, 2, 1])
        } else if eq12 {
            let n = canonical_sign(vec(0));
            let (a, b) = plane_basis(&n);
            (Matrix3::from_columns(&[n, a, b]), [1, 2, 2])
        } else {
            let a = canonical_sign(vec(0));
            let b = canonical_sign(vec(1));
            let b = (b - a * a.dot(&b)).normalize();
            (Matrix3::from_columns(&[a, b, a.cross(&b)]), [1, 1, 1])
        };
        // Repeated moments are reported equal (their mean).
        let moments = match multiplicity {
            [3, 3, 3] => Vector3::repeat(lam.mean()),
            [2, 2, 1] => {
                let m = 0.5 * (lam[0] + lam[1]);
                Vector3::new(m, m, lam[2])
            }
            [1, 2, 2] => {
                let m = 0.5 * (lam[1] + lam[2]);
                Vector3::new(lam[0], m, m)
            }
            _ => lam,
        };
        Principal {
            moments,
            axes: Rotation3::from_matrix_unchecked(axes),
            multiplicity,
        }
    }
}

/// `m (|d|² E − d dᵀ)`: the tensor of a point mass `m` at `d`.
pub fn point_mass_tensor(mass: f64, d: &Vector3<f64>) -> Matrix3<f64> {
    (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * mass
}

fn symmetrise(m: Matrix3<f64>) -> Matrix3<f64> {
    (m + m.transpose()) * 0.5
}

/// Sign making the largest-magnitude component positive (first on ties
/// within round-off).
fn canonical_sign(v: Vector3<f64>) -> Vector3<f64> {
    let v = v.normalize();
    let big = v.abs().max();
    let first = (0..3)
        .find(|&i| v[i].abs() >= big * (1.0 - 1e-9))
        .unwrap_or(0);
    if v[first] < 0.0 { -v } else { v }
}

/// Canonical right-handed basis `(a, b)` of the plane normal to unit `n`,
/// with `a × b = n`.
fn plane_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let axes = [Vector3::x(), Vector3::y(), Vector3::z()];
    let least = axes
        .iter()
        .map(|e| e.dot(n).abs())
        .fold(f64::INFINITY, f64::min);
    let e = axes
        .iter()
        .find(|e| e.dot(n).abs() <= least + 1e-9)
        .copied()
        .unwrap_or(axes[0]);
    let a = (e - n * n.dot(&e)).normalize();
    (a, n.cross(&a))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_plate_on_the_inequality_is_accepted() {
        // plate a × b: I_x = b²/12, I_y = a²/12, I_z = I_x + I_y
        let (a, b) = (0.3_f64, 0.7_f64);
        let i = Inertia::diagonal(b * b / 12.0, a * a / 12.0, (a * a + b * b) / 12.0);
        assert!(i.is_ok());
    }

    #[test]
    fn impossible_and_negative_tensors_are_rejected() {
        assert!(matches!(
            Inertia::diagonal(1.0, 3.0, 5.0),
            Err(InertiaError::Triangle { .. })
        ));
        assert!(matches!(
            Inertia::diagonal(-1.0, 3.0, 3.0),
            Err(InertiaError::NotPositiveSemiDefinite { .. })
        ));
        let mut m = Matrix3::identity();
        m[(0, 1)] = 0.1;
        assert!(matches!(
            Inertia::try_new(m),
            Err(InertiaError::NotSymmetric { row: 0, col: 1, .. })
        ));
        m[(1, 0)] = f64::NAN;
        assert!(matches!(
            Inertia::try_new(m),
            Err(InertiaError::NotFinite { row: 1, col: 0, .. })
        ));
    }
}
