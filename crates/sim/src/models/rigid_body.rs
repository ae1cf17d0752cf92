//! The `rigid-body` model: Euler's equations with a unit-quaternion
//! attitude, for a free body or a heavy top; a heavy top's method and step
//! are measured on the scene by pilot runs ([`pilot_choice`]).

use super::body::{
    QUATERNION_HEADER, RIGID_BODY_NAME, body_of, finish_free, free_body, free_drifts,
    reference_state, refuse_non_body,
};
use crate::model::{
    DEFAULT_TOL, Descriptor, DriftColumns, Integration, Measured, Model, ModelEntry, Outcome, Plan,
    REFERENCE_TOL, Request, step_label,
};
use crate::record::{Recorder, integrate_recorded, time_and_state, timed};
use crate::scene::Scene;
use crate::systems::free::state_distance;
use crate::{Limits, Method, SimError, Step, integrate};

/// The entry.
pub struct RigidBody;

/// The entry, as the registry lists it.
pub static RIGID_BODY: RigidBody = RigidBody;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: RIGID_BODY_NAME,
    applies_to: "a free body or a heavy top",
    why: "Euler's equations with a unit-quaternion attitude (no singular attitude)",
    integrated: true,
    can_integrate: true,
};

impl ModelEntry for RigidBody {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        Ok(refuse_non_body(scene))
    }
    /// A heavy top: method and step measured on the scene
    /// ([`pilot_choice`]); a free body: DOP853.
    fn integration(
        &self,
        scene: &Scene,
        req: &Request,
        t_end: f64,
        _: bool,
    ) -> Result<Integration, SimError> {
        if scene.rigid_body().and_then(|b| b.pivot).is_none() {
            return Ok(Integration::dop853(req));
        }
        let tol = match req.step {
            Some(Step::Tolerance(t)) => t,
            Some(Step::Fixed(_)) | None => DEFAULT_TOL,
        };
        let (method, step, detail) = pilot_choice(scene, t_end, tol)?;
        Ok(Integration {
            method,
            step,
            fit_error: None,
            detail,
        })
    }
    fn takes(&self, _: Method) -> bool {
        true
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
        let (y, stats, wall) = integrate_recorded(
            &body,
            plan.method_step()?,
            y0,
            plan.t_end,
            rec,
            time_and_state,
        )?;
        let mut out = Outcome {
            wall_s: wall,
            stats,
            ..Outcome::default()
        };
        finish_free(scene, &body, &y0, &y, plan.t_end, &mut out)?;
        Ok(out)
    }
    fn sweeps(&self) -> bool {
        true
    }
    /// One sweep run in the quaternion model, measured against the
    /// reference state.
    fn sweep_run(
        &self,
        scene: &Scene,
        method: Method,
        step: Step,
        t_end: f64,
        min_time: f64,
    ) -> Result<Result<Measured, String>, SimError> {
        let (body, y0) = body_of(scene, Model(&RIGID_BODY))?;
        let (reference, _) = reference_state(scene, t_end)?;
        let run = || {
            integrate(
                &body,
                method,
                step,
                0.0,
                y0,
                t_end,
                Limits::default(),
                |_, _| Ok(()),
            )
        };
        Ok(match timed(min_time, run) {
            Ok(((y, stats), wall_s)) => {
                let d = free_drifts(&body, &y0, &y);
                Ok(Measured {
                    error: state_distance(&y, &reference),
                    wall_s,
                    stats,
                    energy_drift: d[0].relative,
                    momentum_drift: d[1].relative,
                })
            }
            Err(e) => Err(e.to_string()),
        })
    }
    fn drift_columns(&self, scene: &Scene) -> DriftColumns {
        let gravity = free_body(scene).is_some_and(|(b, _)| b.gravity.is_some());
        DriftColumns {
            energy: Ok(if gravity {
                "the energy T + V".into()
            } else {
                "the kinetic energy T".into()
            }),
            momentum: Ok(if gravity {
                "H_Z, the angular momentum about the vertical".into()
            } else {
                "|H|".into()
            }),
        }
    }
}

/// Safety factor of the pilot-based choice: the predicted error must be
/// at most the requested one divided by this.
pub const PILOT_SAFETY: f64 = 3.0;

/// Chooses method and step for a heavy top by measuring on this scene:
/// pilots over the whole run at two loose settings (dop853 and dopri5 at
/// tol 1e-5 and 1e-7, rk4 at `dt = T/4000` and `T/8000`) against DOP853 at
/// tol 1e-14, fits `error ∝ setting^p` and `evaluations ∝ setting^(−q)`,
/// and picks the candidate whose setting predicted to reach
/// `requested / PILOT_SAFETY` needs the fewest predicted evaluations (all
/// candidates evaluate the same right-hand side). Loose settings cost little; the
/// reference is the one the report measures against.
pub fn pilot_choice(
    scene: &Scene,
    t_end: f64,
    requested: f64,
) -> Result<(Method, Step, String), SimError> {
    let (body, y0) = free_body(scene).expect("heavy top");
    let fallback = |why: &str| {
        (
            Method::Dop853,
            Step::Tolerance(requested.clamp(1e-13, 1e-3)),
            format!("{why}, so dop853 at tol = the requested error {requested:e}"),
        )
    };
    if t_end <= 0.0 {
        return Ok(fallback("T = 0 leaves nothing to measure"));
    }
    let (reference, _) = reference_state(scene, t_end)?;
    let pilot = |method: Method, step: Step| -> Option<(f64, u64)> {
        let (y, stats) = integrate(
            &body,
            method,
            step,
            0.0,
            y0,
            t_end,
            Limits::default(),
            |_, _| Ok(()),
        )
        .ok()?;
        let e = state_distance(&y, &reference);
        (e.is_finite() && e > 0.0 && e < 1.0).then_some((e, stats.evaluations.max(1)))
    };
    let target = requested / PILOT_SAFETY;
    let mut best: Option<(f64, Method, Step, String)> = None;
    for method in [Method::Dop853, Method::Dopri5, Method::Rk4] {
        let adaptive = method.is_adaptive();
        let (xa, xb) = if adaptive {
            (1e-5, 1e-7)
        } else {
            (t_end / 4000.0, t_end / 8000.0)
        };
        let mk = |x: f64| {
            if adaptive {
                Step::Tolerance(x)
            } else {
                Step::Fixed(x)
            }
        };
        let (Some((ea, na)), Some((eb, nb))) = (pilot(method, mk(xa)), pilot(method, mk(xb)))
        else {
            continue;
        };
        let lx = (xa / xb).ln();
        let p = (ea / eb).ln() / lx;
        // A fixed-step method's error cannot fall faster than its order
        // (a steeper pilot slope is pre-asymptotic): rk4 is of order 4.
        let p = if adaptive { p } else { p.min(4.0) };
        let q = (nb as f64 / na as f64).ln() / lx;
        if !(p > 0.5 && p < 12.0 && q.is_finite()) {
            continue;
        }
        let x = xb * (target / eb).powf(1.0 / p);
        let x = if adaptive {
            x.clamp(1e-13, 1e-3)
        } else {
            x.clamp(t_end / 1e7, t_end / 10.0)
        };
        // Three significant digits, never above the fitted setting: one a
        // person can read and repeat.
        let x: f64 = format!("{:.2e}", x * 0.995).parse().unwrap_or(x);
        let predicted_error = eb * (x / xb).powf(p);
        if predicted_error > target * 1.0001 {
            continue;
        }
        let evals = nb as f64 * (x / xb).powf(-q);
        // The candidates evaluate the same right-hand side: evaluations are
        // the cost (deterministic, unlike wall time).
        let cost = evals;
        let step = if adaptive {
            Step::Tolerance(x)
        } else {
            Step::Fixed(t_end / (t_end / x).ceil())
        };
        let why = format!(
            "{method}: error ∝ {v}^{p:.2}, evaluations ∝ {v}^-{q:.2} (pilot errors {ea:.2e} at {}, {eb:.2e} at {}); \
             predicted error {predicted_error:.2e} with {evals:.0} evaluations",
            step_label(mk(xa)),
            step_label(mk(xb)),
            v = if adaptive { "tol" } else { "dt" },
        );
        if best.as_ref().is_none_or(|b| cost < b.0) {
            best = Some((cost, method, step, why));
        }
    }
    Ok(match best {
        Some((_, method, step, why)) => (
            method,
            step,
            format!(
                "measured on this scene by pilots over [0, T] at two \
                 loose settings per method against dop853 at tol={REFERENCE_TOL:e}: the cheapest setting predicted \
                 to reach {requested:e}/{PILOT_SAFETY} is {method} at {} — {why}",
                step_label(step)
            ),
        ),
        None => fallback("no pilot gave a usable fit"),
    })
}
