//! The `fixed-axis` model: a shaft in two bearings, one degree of freedom
//! (§6), by its closed form or integrated with a method, with the bearing
//! reactions.

use std::time::Instant;

use super::body::{HEAVY_TOP_DOF, ONLY_DERIVED};
use crate::estimate::{CHECK_TOL, ESTIMATE_BASIS, ESTIMATE_SAMPLES, closed_form_estimate, euclid};
use crate::model::{
    Check, Cover, Descriptor, DriftColumns, Measured, Model, ModelEntry, Outcome, Plan,
    not_applicable, relative,
};
use crate::record::{Recorder, integrate_recorded, timed};
use crate::scene::Scene;
use crate::systems::Shaft;
use crate::{Limits, Method, SimError, Stats, Step, integrate};

/// The entry.
pub struct FixedAxis;

/// The entry, as the registry lists it.
pub static FIXED_AXIS: FixedAxis = FixedAxis;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: "fixed-axis",
    applies_to: "a shaft in two bearings (kind fixed-axis)",
    why: "one degree of freedom, linear motor law: a closed form, or integrated with --method; bearing reactions from §6",
    integrated: false,
    can_integrate: true,
};

fn shaft_of(scene: &Scene) -> Result<(&Shaft, &[f64; 2]), SimError> {
    scene.shaft().ok_or_else(|| {
        not_applicable(
            Model(&FIXED_AXIS),
            scene,
            "the scene is not of a kind this model describes",
        )
    })
}

fn shaft_reactions(shaft: &Shaft, w: f64) -> [f64; 7] {
    let r = shaft.reactions(w);
    [
        r.bearing_a[0],
        r.bearing_a[1],
        r.bearing_b[0],
        r.bearing_b[1],
        r.moment_x,
        r.moment_y,
        r.moment_z,
    ]
}

impl ModelEntry for FixedAxis {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        Ok(if scene.shaft().is_some() {
            None
        } else if scene.derivation().is_some() {
            Some(ONLY_DERIVED)
        } else if scene.rigid_body().is_some_and(|b| b.pivot.is_some()) {
            Some(HEAVY_TOP_DOF)
        } else {
            Some(
                "the body is free: no bearing fixes its axis (a spin about a principal axis is \
                 found by the closed form as a permanent rotation)",
            )
        })
    }
    fn covers(&self, _: &Scene, _: f64) -> Option<Result<Cover, SimError>> {
        Some(Ok(Cover::Covered(
            "the bearings fix the axis: one degree of freedom, I_z α = T_0 (1 − ω/ω_0) − c ω, \
             linear in ω, so its closed form needs no integration; bearing reactions from §6",
        )))
    }
    fn takes(&self, _: Method) -> bool {
        true
    }
    fn default_choice(&self) -> bool {
        true
    }
    fn stream_header(&self, _: &Scene) -> String {
        "t,angle,omega,A_x,A_y,B_x,B_y".into()
    }

    fn run(
        &self,
        scene: &Scene,
        plan: &Plan,
        rec: &mut Recorder<'_, '_>,
    ) -> Result<Outcome, SimError> {
        let (shaft, y0) = shaft_of(scene)?;
        let t_end = plan.t_end;
        let mut out = Outcome::default();
        let row = |t: f64, y: &[f64; 2]| {
            let mut row = vec![t, y[0], y[1]];
            row.extend_from_slice(&shaft_reactions(shaft, y[1])[..4]);
            row
        };
        let (y, stats) = match (plan.method, plan.step) {
            (Some(method), Some(step)) => {
                let (y, stats, wall) =
                    integrate_recorded(shaft, (method, step), *y0, t_end, rec, row)?;
                out.wall_s = wall;
                (y, stats)
            }
            _ => {
                let start = Instant::now();
                let y = shaft.exact(y0, t_end);
                out.wall_s = start.elapsed().as_secs_f64();
                if rec.active() {
                    rec.record(row(t_end, &y))?;
                }
                (y, Stats::default())
            }
        };
        let exact = shaft.exact(y0, t_end);
        out.reference = "closed form of the one-degree-of-freedom equation".into();
        if plan.method.is_some() {
            out.error = Some(euclid(&y, &exact));
            out.error_basis = "measured against the closed form".into();
        } else {
            // The shorter of a turn's time and the motion's own time
            // constant I_z/|T_0/ω_0 + c| (a stiff friction decays in
            // milliseconds: steps of a turn's time would be unstable).
            let w = y0[1].abs();
            let damping = (shaft.stall_torque / shaft.no_load_speed + shaft.friction).abs();
            let relax = if damping > 0.0 {
                shaft.i_z / damping
            } else {
                f64::INFINITY
            };
            let time_scale = if w > 0.0 { 1.0 / w } else { t_end }.min(relax);
            out.error = Some(closed_form_estimate(
                shaft,
                &|t| shaft.exact(y0, t),
                y0,
                t_end,
                time_scale,
                ESTIMATE_SAMPLES,
                euclid,
            )?);
            out.error_basis = ESTIMATE_BASIS.into();
            if plan.check {
                let (yc, _) = integrate(
                    shaft,
                    Method::Dop853,
                    Step::Tolerance(CHECK_TOL),
                    0.0,
                    *y0,
                    t_end,
                    Limits::default(),
                    |_, _| Ok(()),
                )?;
                out.check = Some(Check {
                    against: format!("dop853 at tol={CHECK_TOL:e}"),
                    difference: euclid(&y, &yc),
                });
            }
        }
        out.reactions = Some(shaft_reactions(shaft, y[1]));
        out.final_state = y.to_vec();
        out.stats = stats;
        Ok(out)
    }

    fn sweeps(&self) -> bool {
        true
    }

    /// One sweep run of a shaft, measured against its closed form.
    fn sweep_run(
        &self,
        scene: &Scene,
        method: Method,
        step: Step,
        t_end: f64,
        min_time: f64,
    ) -> Result<Result<Measured, String>, SimError> {
        let (shaft, y0) = shaft_of(scene)?;
        let run = || {
            integrate(
                shaft,
                method,
                step,
                0.0,
                *y0,
                t_end,
                Limits::default(),
                |_, _| Ok(()),
            )
        };
        Ok(match timed(min_time, run) {
            Ok(((y, stats), wall_s)) => {
                let e = shaft.exact(y0, t_end);
                Ok(Measured {
                    error: euclid(&y, &e),
                    wall_s,
                    stats,
                    energy_drift: relative(shaft.energy(&y), shaft.energy(&e)),
                    momentum_drift: f64::NAN,
                })
            }
            Err(e) => Err(e.to_string()),
        })
    }

    fn drift_columns(&self, _: &Scene) -> DriftColumns {
        DriftColumns {
            energy: Ok("the shaft's kinetic energy at T against the closed form's".into()),
            momentum: Err(
                "a shaft has one degree of freedom and no momentum the motion conserves".into(),
            ),
        }
    }
}
