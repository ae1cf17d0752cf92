//! The `euler-angles` model: Euler's equations with Eulerian angles, for
//! comparison with the quaternion form; singular at sin θ = 0.

use super::body::{body_of, finish_free, refuse_non_body};
use crate::model::{Descriptor, ModelEntry, Outcome, Plan};
use crate::record::{Recorder, integrate_recorded, time_and_state};
use crate::scene::Scene;
use crate::systems::EulerAngleBody;
use crate::systems::euler_angles::{SIN_THETA_MIN, angles_from_quaternion, to_quaternion_state};
use crate::systems::free::attitude;
use crate::{Method, SimError};

/// The entry.
pub struct EulerAngles;

/// The entry, as the registry lists it.
pub static EULER_ANGLES: EulerAngles = EulerAngles;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: "euler-angles",
    applies_to: "a free body or a heavy top (away from θ = 0, π)",
    why: "Euler's equations with Eulerian angles, for comparison: singular at sin θ = 0",
    integrated: true,
    can_integrate: true,
};

impl ModelEntry for EulerAngles {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        if let Some(why) = refuse_non_body(scene) {
            return Ok(Some(why));
        }
        let (_, y0) = body_of(scene, crate::model::Model(&EULER_ANGLES))?;
        let (_, theta, _) = angles_from_quaternion(&attitude(&y0));
        Ok((theta.sin() < SIN_THETA_MIN).then_some(
            "the initial attitude has nutation θ = 0 or π, where Eulerian angles are singular; \
             use rigid-body (quaternion attitude)",
        ))
    }
    fn takes(&self, _: Method) -> bool {
        false
    }
    fn stream_header(&self, _: &Scene) -> String {
        "t,phi,theta,psi,omega_1,omega_2,omega_3".into()
    }
    fn run(
        &self,
        scene: &Scene,
        plan: &Plan,
        rec: &mut Recorder<'_, '_>,
    ) -> Result<Outcome, SimError> {
        let (body, y0) = body_of(scene, plan.model)?;
        let (phi, theta, psi) = angles_from_quaternion(&attitude(&y0));
        let e0 = [phi, theta, psi, y0[4], y0[5], y0[6]];
        let sys = EulerAngleBody {
            moments: body.moments,
            weight_arm: body.gravity.map_or(0.0, |g| g.weight_arm),
        };
        let (e, stats, wall) = integrate_recorded(
            &sys,
            plan.method_step()?,
            e0,
            plan.t_end,
            rec,
            time_and_state,
        )?;
        let mut out = Outcome {
            wall_s: wall,
            stats,
            ..Outcome::default()
        };
        let y = to_quaternion_state(&e);
        finish_free(scene, &body, &y0, &y, plan.t_end, &mut out)?;
        Ok(out)
    }
}
