//! The `steady-precession` model: the closed forms of a torque-free
//! axisymmetric body or permanent rotation (§9) and of a heavy top started
//! in steady precession (§7).

use super::body::{
    QUATERNION_HEADER, closed_form_meets_bound, free_body_is_elliptic, refuse_non_body,
    run_closed_form, untrusted_closed_form,
};
use crate::exact::TorqueFree;
use crate::model::{Cover, Descriptor, ModelEntry, Outcome, Plan};
use crate::record::Recorder;
use crate::scene::{Pivot, Rigid, Scene};
use crate::{Method, SimError};

/// The entry.
pub struct SteadyPrecession;

/// The entry, as the registry lists it.
pub static STEADY_PRECESSION: SteadyPrecession = SteadyPrecession;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: "steady-precession",
    applies_to: "a free axisymmetric body or a permanent rotation; a heavy top started in steady precession",
    why: "closed form (§7, §9): θ, φ̇, ψ̇ constant, no integration",
    integrated: false,
    can_integrate: false,
};

impl ModelEntry for SteadyPrecession {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        Ok(match free_body_is_elliptic(scene)? {
            Some(true) => Some(
                "the body is not axisymmetric (three distinct moments): its motion is not a steady precession",
            ),
            Some(false) => None,
            None => match scene.rigid_body() {
                Some(Rigid {
                    pivot: Some(Pivot { steady: None, .. }),
                    ..
                }) => Some(
                    "the initial state does not satisfy §7's steady-precession relation (or θ̇ ≠ 0)",
                ),
                Some(_) => None,
                None => refuse_non_body(scene),
            },
        })
    }
    fn covers(&self, scene: &Scene, t_end: f64) -> Option<Result<Cover, SimError>> {
        Some(cover(scene, t_end))
    }
    fn takes(&self, _: Method) -> bool {
        false
    }
    fn stream_header(&self, _: &Scene) -> String {
        QUATERNION_HEADER.into()
    }
    fn run(
        &self,
        scene: &Scene,
        plan: &Plan,
        rec: &mut Recorder<'_, '_>,
    ) -> Result<Outcome, SimError> {
        run_closed_form(scene, plan, rec)
    }
}

fn cover(scene: &Scene, t_end: f64) -> Result<Cover, SimError> {
    let free = scene.rigid_body().filter(|b| b.pivot.is_none());
    Ok(match free {
        Some(_) if !closed_form_meets_bound(scene, t_end)? => untrusted_closed_form(),
        Some(Rigid {
            moments, q0, w0, ..
        }) => match TorqueFree::new(moments.get(), *q0, *w0)? {
            TorqueFree::Permanent { .. } => Cover::Covered(
                "torque-free spin about a principal axis: permanent rotation, ω constant, no integration",
            ),
            _ => Cover::Covered(
                "torque-free axisymmetric body: closed-form steady precession about H (§9), no integration",
            ),
        },
        _ => Cover::Covered(
            "heavy top started in steady precession (W l = (I ω_z − I' φ̇ cos θ) φ̇ holds, θ̇ = 0): \
             θ, φ̇, ψ̇ stay constant (§7), no integration",
        ),
    })
}
