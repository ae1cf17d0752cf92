//! The unit norm of Euler parameters in a first-order state: the
//! kinematic equations ė = ½ E(e)ᵀ ω keep e·e constant exactly, but an
//! integrator's steps do not, so after every accepted step each
//! quaternion of the state is divided by its norm. The largest departure
//! | |e| − 1 | met before a normalization is recorded and reported as the
//! run's drift of the norm.

use std::cell::Cell;

use hdot_sym::atom::Atom;
use hdot_sym::derivation::Derivation;

use super::DerivedModel;

/// The quaternions of a state and what their normalization met.
#[derive(Debug, Default)]
pub(super) struct UnitNorms {
    /// The state indices of each quaternion's four parameters, and their
    /// names (scalar part first).
    quaternions: Vec<([usize; 4], [String; 4])>,
    /// The largest | |e| − 1 | before a normalization since the last reset.
    max_drift: Cell<f64>,
}

impl UnitNorms {
    /// The quaternions of `d` whose four parameters are coordinates of
    /// the state (`coordinates`, in state order).
    pub(super) fn of(d: &Derivation, coordinates: &[Atom]) -> UnitNorms {
        let index = |e: &Atom| coordinates.iter().position(|q| q == e);
        let quaternions = d
            .speeds
            .unit_norms
            .iter()
            .filter_map(|e| {
                let i = [index(&e[0])?, index(&e[1])?, index(&e[2])?, index(&e[3])?];
                Some((i, e.map(|x| x.to_string())))
            })
            .collect();
        UnitNorms {
            quaternions,
            max_drift: Cell::new(0.0),
        }
    }
}

/// # The norm of Euler parameters along a run
impl DerivedModel {
    /// The names of the parameters of each quaternion the state carries
    /// (scalar part first).
    pub fn unit_norms(&self) -> Vec<[String; 4]> {
        self.unit_norms
            .quaternions
            .iter()
            .map(|(_, n)| n.clone())
            .collect()
    }

    /// Starts a new record of the norms' drift.
    pub fn reset_unit_norm_monitor(&self) {
        self.unit_norms.max_drift.set(0.0);
    }

    /// The largest | |e| − 1 | met before a normalization since the last
    /// reset (`None` when the state carries no quaternion).
    pub fn unit_norm_drift(&self) -> Option<f64> {
        (!self.unit_norms.quaternions.is_empty()).then(|| self.unit_norms.max_drift.get())
    }

    /// Why the state `y` cannot start a run: a quaternion whose norm is
    /// not 1 (to 1e-9, what a value typed to ten digits gives).
    pub fn unit_norm_refusal(&self, y: &[f64]) -> Option<String> {
        self.unit_norms.quaternions.iter().find_map(|(i, names)| {
            let norm = i.iter().map(|&k| y[k] * y[k]).sum::<f64>().sqrt();
            let on_sphere = (norm - 1.0).abs() <= 1e-9;
            (!on_sphere).then(|| {
                format!(
                    "the Euler parameters {} have norm {norm}: they must have unit norm ({}² = 1)",
                    names.join(", "),
                    names.join("² + ")
                )
            })
        })
    }

    /// After an accepted step: divides each quaternion of `y` by its norm
    /// and records how far the norm had drifted. Returns whether `y`
    /// changed.
    pub(super) fn keep_unit_norms(&self, y: &mut [f64]) -> bool {
        let mut changed = false;
        for (i, _) in &self.unit_norms.quaternions {
            let norm = i.iter().map(|&k| y[k] * y[k]).sum::<f64>().sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                continue;
            }
            let drift = (norm - 1.0).abs();
            let m = &self.unit_norms.max_drift;
            m.set(m.get().max(drift));
            if drift > 0.0 {
                for &k in i {
                    y[k] /= norm;
                }
                changed = true;
            }
        }
        changed
    }
}
