//! Mass properties the simulation needs: principal moments (checked), and
//! the simple bodies of the reference table that produce them.

use serde::Deserialize;

use crate::SimError;

/// Principal moments of inertia `(I_1, I_2, I_3)` about the mass centre or a
/// fixed point.
///
/// Invariant: each moment is finite and positive and the triangle
/// inequalities `I_i + I_j ≥ I_k` hold (with a relative tolerance of
/// `8 ε (I_1 + I_2 + I_3)`); only [`PrincipalMoments::new`] builds one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipalMoments([f64; 3]);

/// # Construction
impl PrincipalMoments {
    /// Checks positivity and the triangle inequalities.
    ///
    /// # Example
    /// ```
    /// use hdot_sim::PrincipalMoments;
    /// assert!(PrincipalMoments::new([0.6, 0.8, 1.0]).is_ok());
    /// assert!(PrincipalMoments::new([0.1, 0.2, 1.0]).is_err()); // 0.1 + 0.2 < 1
    /// ```
    pub fn new(moments: [f64; 3]) -> Result<Self, SimError> {
        let bad = |message: &str| SimError::BadInertia {
            moments,
            message: message.to_string(),
        };
        if moments.iter().any(|i| !(i.is_finite() && *i > 0.0)) {
            return Err(bad("every principal moment must be positive and finite"));
        }
        let sum: f64 = moments.iter().sum();
        let tol = 8.0 * f64::EPSILON * sum;
        for k in 0..3 {
            if moments[(k + 1) % 3] + moments[(k + 2) % 3] + tol < moments[k] {
                return Err(bad("triangle inequality I_i + I_j ≥ I_k fails"));
            }
        }
        Ok(Self(moments))
    }
}

/// # Operations
impl PrincipalMoments {
    /// The three moments.
    pub fn get(&self) -> [f64; 3] {
        self.0
    }

    /// The index of the symmetry axis if exactly two moments agree to a
    /// relative `tol`, `None` if all differ; a sphere (all equal) reports axis 2.
    pub fn symmetry_axis(&self, tol: f64) -> Option<usize> {
        let i = self.0;
        let close = |a: f64, b: f64| (a - b).abs() <= tol * a.max(b);
        match (close(i[0], i[1]), close(i[1], i[2]), close(i[0], i[2])) {
            (true, true, _) => Some(2),
            (true, _, _) => Some(2),
            (_, true, _) => Some(0),
            (_, _, true) => Some(1),
            _ => None,
        }
    }
}

/// A simple body of the reference table, principal axes along x, y, z
/// (the symmetry axis is z where there is one). Moments about G.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Shape {
    /// Rectangular prism with edges a (x), b (y), c (z).
    Prism {
        /// Mass.
        mass: f64,
        /// Edge along x.
        a: f64,
        /// Edge along y.
        b: f64,
        /// Edge along z.
        c: f64,
    },
    /// Solid circular cylinder, axis z.
    Cylinder {
        /// Mass.
        mass: f64,
        /// Radius.
        radius: f64,
        /// Length along z.
        length: f64,
    },
    /// Thin disk, axis z.
    Disk {
        /// Mass.
        mass: f64,
        /// Radius.
        radius: f64,
    },
    /// Solid right circular cone, axis z (moments about its mass centre).
    Cone {
        /// Mass.
        mass: f64,
        /// Base radius.
        radius: f64,
        /// Height.
        height: f64,
    },
    /// Solid sphere.
    Sphere {
        /// Mass.
        mass: f64,
        /// Radius.
        radius: f64,
    },
}

impl Shape {
    /// Mass of the body.
    pub fn mass(&self) -> f64 {
        match *self {
            Shape::Prism { mass, .. }
            | Shape::Cylinder { mass, .. }
            | Shape::Disk { mass, .. }
            | Shape::Cone { mass, .. }
            | Shape::Sphere { mass, .. } => mass,
        }
    }

    /// Principal moments about the mass centre (reference table).
    pub fn moments(&self) -> [f64; 3] {
        match *self {
            Shape::Prism { mass, a, b, c } => [
                mass * (b * b + c * c) / 12.0,
                mass * (c * c + a * a) / 12.0,
                mass * (a * a + b * b) / 12.0,
            ],
            Shape::Cylinder {
                mass,
                radius,
                length,
            } => {
                let t = mass * (3.0 * radius * radius + length * length) / 12.0;
                [t, t, mass * radius * radius / 2.0]
            }
            Shape::Disk { mass, radius } => {
                let t = mass * radius * radius / 4.0;
                [t, t, 2.0 * t]
            }
            Shape::Cone {
                mass,
                radius,
                height,
            } => {
                let t = 3.0 * mass * radius * radius / 20.0 + 3.0 * mass * height * height / 80.0;
                [t, t, 3.0 * mass * radius * radius / 10.0]
            }
            Shape::Sphere { mass, radius } => [2.0 * mass * radius * radius / 5.0; 3],
        }
    }

    /// Every dimension and the mass must be positive and finite.
    pub fn validate(&self) -> Result<(), String> {
        let values: Vec<f64> = match *self {
            Shape::Prism { mass, a, b, c } => vec![mass, a, b, c],
            Shape::Cylinder {
                mass,
                radius,
                length,
            } => vec![mass, radius, length],
            Shape::Disk { mass, radius } | Shape::Sphere { mass, radius } => vec![mass, radius],
            Shape::Cone {
                mass,
                radius,
                height,
            } => vec![mass, radius, height],
        };
        if values.iter().all(|v| v.is_finite() && *v > 0.0) {
            Ok(())
        } else {
            Err("mass and dimensions must be positive and finite".into())
        }
    }
}
