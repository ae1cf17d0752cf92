//! What a scene holds, asked of it: a rigid body (free, or on a pivot
//! under gravity) with its initial state, a shaft in bearings, or the
//! equations of a derivation. A model decides whether it applies from
//! these answers, not by matching the kind of file the scene came from.

use nalgebra::{UnitQuaternion, Vector3};

use super::{DerivedScene, Scene, SceneKind};
use crate::PrincipalMoments;
use crate::exact::SteadyTop;
use crate::systems::Shaft;

/// A rigid body turning about its mass centre or about a fixed point, in
/// its principal (body) axes.
#[derive(Debug, Clone, Copy)]
pub struct Rigid<'a> {
    /// Principal moments, about G (free) or about the pivot O.
    pub moments: &'a PrincipalMoments,
    /// Initial attitude.
    pub q0: &'a UnitQuaternion<f64>,
    /// Initial body angular velocity.
    pub w0: &'a Vector3<f64>,
    /// The fixed point it turns about under gravity, if any (a heavy top).
    pub pivot: Option<Pivot<'a>>,
}

/// A fixed point O under gravity, with G on body axis 3.
#[derive(Debug, Clone, Copy)]
pub struct Pivot<'a> {
    /// Weight × distance O→G.
    pub weight_arm: f64,
    /// The steady precession the body starts in, if it does (§7).
    pub steady: Option<&'a SteadyTop>,
}

/// # What it holds
impl Scene {
    /// The rigid body it holds, free or on a pivot; `None` when what moves
    /// is a shaft or a derivation's coordinates.
    pub fn rigid_body(&self) -> Option<Rigid<'_>> {
        match &self.kind {
            SceneKind::Free { moments, q0, w0 } => Some(Rigid {
                moments,
                q0,
                w0,
                pivot: None,
            }),
            SceneKind::HeavyTop {
                moments,
                weight_arm,
                q0,
                w0,
                steady,
            } => Some(Rigid {
                moments,
                q0,
                w0,
                pivot: Some(Pivot {
                    weight_arm: *weight_arm,
                    steady: steady.as_ref(),
                }),
            }),
            SceneKind::FixedAxis { .. } | SceneKind::Derived(_) => None,
        }
    }

    /// The shaft in two bearings it holds, and its initial angle and rate.
    pub fn shaft(&self) -> Option<(&Shaft, &[f64; 2])> {
        match &self.kind {
            SceneKind::FixedAxis { shaft, y0 } => Some((shaft, y0)),
            _ => None,
        }
    }

    /// The derivation whose equations of motion it integrates.
    pub fn derivation(&self) -> Option<&DerivedScene> {
        match &self.kind {
            SceneKind::Derived(ds) => Some(ds),
            _ => None,
        }
    }
}
