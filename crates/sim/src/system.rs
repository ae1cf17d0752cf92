//! The one interface every integrator drives: a right-hand side on a
//! fixed-size state, an optional validity check, and (for the splitting
//! methods) an optional symmetric step into exactly solved sub-flows.

use crate::SimError;

/// An ordinary differential equation `ẏ = f(t, y)` on `[f64; N]`.
pub trait System<const N: usize> {
    /// The model's name, for errors (`rigid-body`, `derived`): the names
    /// of the registry [`crate::models::MODELS`] where the system is one of its models.
    fn name(&self) -> &str;

    /// The right-hand side `f(t, y)`.
    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N];

    /// Called after every accepted step: reject states where the model's
    /// coordinates break down (e.g. Eulerian angles at θ = 0).
    fn check(&self, _t: f64, _y: &[f64; N]) -> Result<(), SimError> {
        Ok(())
    }

    /// Called after every accepted step, before `check`: a model with
    /// invariants it keeps exactly may move the state back onto them
    /// (projection, Hairer–Lubich–Wanner *Geometric Numerical Integration*
    /// §IV.4). Returns whether it changed the state. Default: no projection.
    fn project(&self, _y: &mut [f64; N]) -> bool {
        false
    }

    /// One step of a symmetric second-order (Strang) splitting into exactly
    /// solved sub-flows, and the number of sub-flows it applied; `None` if
    /// the model has no such splitting.
    fn strang_step(&self, _t: f64, _y: &[f64; N], _h: f64) -> Option<([f64; N], u64)> {
        None
    }
}
