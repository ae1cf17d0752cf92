//! Mass properties as a value: [`MassProperties`] (mass, centre G and
//! inertia about G in world axes), how parts combine, and the check of a
//! mass. Bodies, clouds and particle sums all produce it, so it sits
//! below them (none of them imports another for it).

use nalgebra::{Rotation3, Vector3};

use crate::error::BodyError;
use crate::inertia::{Inertia, Principal, point_mass_tensor};

/// A mass checked finite and positive (`what` names what carries it).
pub(crate) fn check_mass(what: &str, mass: f64) -> Result<(), BodyError> {
    if !mass.is_finite() {
        return Err(BodyError::NotFinite {
            what: what.to_string(),
            field: "mass",
            value: mass,
        });
    }
    if mass <= 0.0 {
        return Err(BodyError::NonPositiveMass {
            what: what.to_string(),
            value: mass,
        });
    }
    if mass < f64::MIN_POSITIVE {
        return Err(BodyError::TinyMass {
            what: what.to_string(),
            value: mass,
        });
    }
    Ok(())
}

/// Mass, centre G and inertia about G, all in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Total mass.
    pub mass: f64,
    /// Mass centre G in world coordinates.
    pub center: Vector3<f64>,
    /// Inertia about G in world axes.
    pub inertia_g: Inertia,
}

impl MassProperties {
    /// A point mass.
    pub fn point(mass: f64, at: Vector3<f64>) -> Self {
        Self {
            mass,
            center: at,
            inertia_g: Inertia::zero(),
        }
    }

    /// Inertia about `point` in world axes (parallel-axis theorem).
    pub fn inertia_about(&self, point: &Vector3<f64>) -> Inertia {
        self.inertia_g
            .shifted_from_centre(self.mass, &(self.center - point))
    }

    /// Inertia about `point` in the axes whose unit vectors (in world
    /// coordinates) are the columns of `axes`.
    pub fn inertia_about_in(&self, point: &Vector3<f64>, axes: &Rotation3<f64>) -> Inertia {
        self.inertia_about(point).in_axes(axes)
    }

    /// Principal moments and canonical axes about G (world axes).
    pub fn principal(&self) -> Principal {
        self.inertia_g.principal()
    }

    /// Combines parts into one body: total mass, mass-weighted centre,
    /// inertia about the common centre.
    pub fn combine(parts: &[MassProperties]) -> Result<Self, BodyError> {
        if parts.is_empty() {
            return Err(BodyError::Empty {
                what: "composite".into(),
            });
        }
        let mass: f64 = parts.iter().map(|p| p.mass).sum();
        check_mass("composite", mass)?;
        let center = parts
            .iter()
            .fold(Vector3::zeros(), |acc, p| acc + p.center * p.mass)
            / mass;
        let m = parts.iter().fold(nalgebra::Matrix3::zeros(), |acc, p| {
            acc + p.inertia_g.matrix() + point_mass_tensor(p.mass, &(p.center - center))
        });
        Ok(Self {
            mass,
            center,
            inertia_g: Inertia::new_unchecked((m + m.transpose()) * 0.5),
        })
    }
}
