//! The `precession-angle` model: a torque-free body integrated as ω and
//! the angle turned about the invariable H (4 components, projected onto
//! the conserved energy and |H|).

use super::body::{QUATERNION_HEADER, body_of, finish_free, refuse_non_body};
use crate::model::{
    Descriptor, Integration, Model, ModelEntry, Outcome, Plan, Request, not_a_splitting,
    not_applicable,
};
use crate::record::{Recorder, integrate_recorded, time_and_state};
use crate::scene::{Rigid, Scene};
use crate::systems::PrecessionAngle as System;
use crate::{Method, SimError, Step};

/// The entry.
pub struct PrecessionAngle;

/// The entry, as the registry lists it.
pub static PRECESSION_ANGLE: PrecessionAngle = PrecessionAngle;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: "precession-angle",
    applies_to: "a free body that turns (H ≠ 0)",
    why: "torque-free, H is fixed in space: the attitude is fixed by body H and one angle φ about H, so [ω, φ] is integrated (4 components, ω projected back onto the conserved energy and |H| after every step) instead of the quaternion form",
    integrated: true,
    can_integrate: true,
};

/// Why the model does not apply to a body at rest.
const AT_REST: &str = "the body is at rest: H = 0 defines no invariable axis";

impl ModelEntry for PrecessionAngle {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        Ok(match scene.rigid_body() {
            Some(b) if b.pivot.is_some() => Some(
                "gravity turns H in space, so the attitude is not fixed by body H and one angle about it",
            ),
            Some(b) if b.w0.norm() == 0.0 => Some(AT_REST),
            Some(_) => None,
            None => refuse_non_body(scene),
        })
    }
    /// Chosen over a closed form that is not trusted: DOP853 at tol 1e-13.
    fn integration(
        &self,
        _: &Scene,
        req: &Request,
        _: f64,
        chosen: bool,
    ) -> Result<Integration, SimError> {
        if !chosen {
            return Ok(Integration::dop853(req));
        }
        let step = Step::Tolerance(1e-13);
        Ok(Integration {
            method: Method::Dop853,
            step,
            fit_error: None,
            detail: format!("dop853 at {}", crate::model::step_label(step)),
        })
    }
    fn takes(&self, method: Method) -> bool {
        not_a_splitting(method)
    }
    fn default_choice(&self) -> bool {
        true
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
        let (body, y0) = body_of(scene, plan.model)?;
        let Some(Rigid {
            moments,
            q0,
            w0,
            pivot: None,
        }) = scene.rigid_body()
        else {
            return Err(not_applicable(
                plan.model,
                scene,
                "the scene is not of a kind this model describes",
            ));
        };
        let (sys, z0) = System::new(moments.get(), q0, w0)
            .ok_or_else(|| not_applicable(Model(&PRECESSION_ANGLE), scene, AT_REST))?;
        let (z, stats, wall) =
            integrate_recorded(&sys, plan.method_step()?, z0, plan.t_end, rec, |t, z| {
                time_and_state(t, &sys.full_state(z))
            })?;
        let mut out = Outcome {
            wall_s: wall,
            stats,
            ..Outcome::default()
        };
        let y = sys.full_state(&z);
        finish_free(scene, &body, &y0, &y, plan.t_end, &mut out)?;
        Ok(out)
    }
}
