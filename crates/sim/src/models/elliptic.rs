//! The `elliptic` model: the closed form of the asymmetric torque-free
//! body through Jacobi elliptic functions.

use super::body::{
    HEAVY_TOP_DOF, QUATERNION_HEADER, closed_form_meets_bound, free_body_is_elliptic,
    refuse_non_body, run_closed_form, untrusted_closed_form,
};
use crate::model::{Cover, Descriptor, ModelEntry, Outcome, Plan};
use crate::record::Recorder;
use crate::scene::Scene;
use crate::{Method, SimError};

/// The entry.
pub struct Elliptic;

/// The entry, as the registry lists it.
pub static ELLIPTIC: Elliptic = Elliptic;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: "elliptic",
    applies_to: "a free body with three distinct moments",
    why: "closed form through Jacobi elliptic functions, no integration",
    integrated: false,
    can_integrate: false,
};

impl ModelEntry for Elliptic {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        Ok(match free_body_is_elliptic(scene)? {
            Some(true) => None,
            Some(false) => Some(
                "the elliptic form needs three distinct moments and a motion that is not a permanent rotation; \
                 use steady-precession",
            ),
            None if scene.rigid_body().is_some() => Some(HEAVY_TOP_DOF),
            None => refuse_non_body(scene),
        })
    }
    fn covers(&self, scene: &Scene, t_end: f64) -> Option<Result<Cover, SimError>> {
        Some(closed_form_meets_bound(scene, t_end).map(|ok| {
            if ok {
                Cover::Covered(
                    "torque-free asymmetric body: exact solution by Jacobi elliptic functions, no integration",
                )
            } else {
                untrusted_closed_form()
            }
        }))
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
