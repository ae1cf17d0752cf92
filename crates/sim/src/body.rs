//! Mass properties the simulation needs: principal moments, checked by
//! the one inertia invariant of `hdot_num::Inertia`. Bodies themselves
//! (primitives, composites, clouds) are `hdot-num`'s, read from a scene's
//! `[[body]]` tables (`docs/scenes.md`).

use crate::SimError;

/// Principal moments of inertia `(I_1, I_2, I_3)` about the mass centre or a
/// fixed point.
///
/// Invariant: each moment is finite and positive and the diagonal tensor
/// satisfies `hdot_num::Inertia`'s invariant (triangle inequalities
/// `I_i + I_j ≥ I_k` to its relative tolerance); only
/// [`PrincipalMoments::new`] builds one.
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
        let diagonal = hdot_num::nalgebra::Matrix3::from_diagonal(&moments.into());
        hdot_num::Inertia::try_new(diagonal).map_err(|e| bad(&e.to_string()))?;
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
