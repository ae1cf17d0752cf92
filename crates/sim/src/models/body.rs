//! What the models of one rigid body (a free body or a heavy top) share:
//! the quaternion system and state of a scene, its exact or reference
//! state, its drifts, the closed forms' defect estimate and run, and the
//! refusals every body model gives a scene that is not a body.

use std::time::Instant;

use crate::estimate::{
    CHECK_TOL, CLOSED_FORM_BOUND, ESTIMATE_BASIS, ESTIMATE_SAMPLES, closed_form_estimate,
};
use crate::exact::{SteadyTop, TorqueFree};
use crate::model::{
    Check, Cover, Drift, Outcome, Plan, PrecessionCheck, REFERENCE_TOL, not_applicable, relative,
};
use crate::record::{Recorder, time_and_state};
use crate::scene::{Pivot, Rigid, Scene};
use crate::systems::free::{attitude, pack, state_distance};
use crate::systems::{FreeBody, Gravity};
use crate::{Limits, Method, SimError, Step, integrate};

/// Why only `derived` runs a derived scene (plan and run refuse alike).
pub(super) const ONLY_DERIVED: &str = "a derived scene is its derivation's equations of motion, which no built-in closed form is known to cover; only `derived` runs them";

/// Why a closed form of the free body is not the heavy top's.
pub(super) const HEAVY_TOP_DOF: &str =
    "a heavy top on a fixed point has three degrees of freedom and a gravity torque";

/// CSV header of the quaternion state.
pub(super) const QUATERNION_HEADER: &str = "t,q_w,q_x,q_y,q_z,omega_1,omega_2,omega_3";

/// Why a model of a rigid body (free or heavy top) does not apply.
pub(super) fn refuse_non_body(scene: &Scene) -> Option<&'static str> {
    if scene.rigid_body().is_some() {
        None
    } else if scene.derivation().is_some() {
        Some(ONLY_DERIVED)
    } else {
        Some(
            "the bearings constrain the body to one degree of freedom; only `fixed-axis` describes it",
        )
    }
}

/// Whether the scene's free rigid body (no pivot) moves by the elliptic
/// closed form (three distinct moments, not a permanent rotation) rather
/// than a steady precession: the one question `elliptic` and
/// `steady-precession` both ask of a free body. `None` when the scene is
/// not a free rigid body (a heavy top, a fixed axis, a derived scene).
pub(super) fn free_body_is_elliptic(scene: &Scene) -> Result<Option<bool>, SimError> {
    Ok(match scene.rigid_body() {
        Some(Rigid {
            moments,
            q0,
            w0,
            pivot: None,
        }) => Some(matches!(
            TorqueFree::new(moments.get(), *q0, *w0)?,
            TorqueFree::Elliptic(_)
        )),
        _ => None,
    })
}

/// The quaternion system and initial state of a free body or heavy top.
pub(super) fn free_body(scene: &Scene) -> Option<(FreeBody, [f64; 7])> {
    let b = scene.rigid_body()?;
    Some((
        FreeBody {
            moments: b.moments.get(),
            gravity: b.pivot.map(|p| Gravity {
                weight_arm: p.weight_arm,
            }),
        },
        pack(b.q0, b.w0),
    ))
}

/// [`free_body`], or the error of running `model` on a scene that is not a body.
pub(super) fn body_of(
    scene: &Scene,
    model: crate::model::Model,
) -> Result<(FreeBody, [f64; 7]), SimError> {
    free_body(scene).ok_or_else(|| {
        not_applicable(
            model,
            scene,
            "the scene is not of a kind this model describes",
        )
    })
}

/// The name of the `rigid-body` model (`models/rigid_body.rs`), kept here so
/// that the reference state's refusal can name it without importing the entry.
pub const RIGID_BODY_NAME: &str = "rigid-body";

/// The exact or reference state at `t` of a free body or heavy top, and its name.
pub fn reference_state(scene: &Scene, t: f64) -> Result<([f64; 7], String), SimError> {
    let refuse = |reason: &str| SimError::ModelNotApplicable {
        model: RIGID_BODY_NAME.into(),
        scene: scene.name.clone(),
        reason: reason.into(),
    };
    let Some(b) = scene.rigid_body() else {
        return Err(refuse(if scene.derivation().is_some() {
            "a derived scene's state is its derivation's coordinates and rates"
        } else {
            "a shaft has a one-degree-of-freedom state"
        }));
    };
    match b.pivot {
        None => {
            let exact = TorqueFree::new(b.moments.get(), *b.q0, *b.w0)?;
            Ok((exact.state(t), format!("closed form: {}", exact.form())))
        }
        Some(Pivot {
            steady: Some(top), ..
        }) => Ok((top.state(t), "closed form: steady precession (§7)".into())),
        Some(_) => {
            let (body, y0) = free_body(scene).expect("heavy top");
            let (y, _) = integrate(
                &body,
                Method::Dop853,
                Step::Tolerance(REFERENCE_TOL),
                0.0,
                y0,
                t,
                Limits::default(),
                |_, _| Ok(()),
            )
            .map_err(|e| {
                e.in_run(|| {
                    format!(
                        "the reference run (dop853 at tol={REFERENCE_TOL:e}, which the error at T is measured against)"
                    )
                })
            })?;
            Ok((y, format!("dop853 at tol={REFERENCE_TOL:e}")))
        }
    }
}

/// The drifts of the energy and of |H| (H_Z under gravity).
pub(super) fn free_drifts(body: &FreeBody, y0: &[f64; 7], y: &[f64; 7]) -> Vec<Drift> {
    vec![
        Drift {
            name: "energy".into(),
            relative: relative(body.energy(y), body.energy(y0)),
        },
        Drift {
            name: if body.gravity.is_some() { "H_Z" } else { "|H|" }.into(),
            relative: relative(body.momentum_invariant(y), body.momentum_invariant(y0)),
        },
    ]
}

fn precession_check(top: &SteadyTop, y: &[f64; 7], t: f64) -> PrecessionCheck {
    let (phi, theta, _) = crate::systems::euler_angles::angles_from_quaternion(&attitude(y));
    let predicted_phi = top.phi0 + top.phi_dot * t;
    let tau = std::f64::consts::TAU;
    let d = (phi - predicted_phi).rem_euclid(tau);
    let d = if d > std::f64::consts::PI { d - tau } else { d };
    let simulated = if t > 0.0 {
        top.phi_dot + d / t
    } else {
        top.phi_dot
    };
    PrecessionCheck {
        predicted: top.phi_dot,
        simulated,
        relative_difference: relative(simulated, top.phi_dot),
        nutation_change: (theta - top.theta).abs(),
    }
}

/// The outcome of an integrated body run ending in `y`: error against
/// the reference, drifts, and the §7 check of a steady top.
pub(super) fn finish_free(
    scene: &Scene,
    body: &FreeBody,
    y0: &[f64; 7],
    y: &[f64; 7],
    t_end: f64,
    out: &mut Outcome,
) -> Result<(), SimError> {
    let (reference, name) = reference_state(scene, t_end)?;
    out.error_basis = format!("measured against the reference ({name})");
    out.reference = name;
    out.error = Some(state_distance(y, &reference));
    out.drifts = free_drifts(body, y0, y);
    out.final_state = y.to_vec();
    if let Some(top) = scene
        .rigid_body()
        .and_then(|b| b.pivot)
        .and_then(|p| p.steady)
    {
        out.precession = Some(precession_check(top, y, t_end));
    }
    Ok(())
}

/// The defect estimate of a body scene's closed form (free or steady top).
pub(super) fn body_closed_form_estimate(
    scene: &Scene,
    t_end: f64,
    samples: usize,
) -> Result<f64, SimError> {
    let (body, y0) = free_body(scene).expect("free or heavy top");
    let scale = scene.rate_scale();
    let time_scale = if scale > 0.0 { 1.0 / scale } else { t_end };
    match scene.rigid_body() {
        Some(Rigid {
            moments,
            q0,
            w0,
            pivot: None,
        }) => {
            let exact = TorqueFree::new(moments.get(), *q0, *w0)?;
            closed_form_estimate(
                &body,
                &|t| exact.state(t),
                &y0,
                t_end,
                time_scale,
                samples,
                state_distance,
            )
        }
        Some(Rigid {
            pivot: Some(Pivot {
                steady: Some(top), ..
            }),
            ..
        }) => closed_form_estimate(
            &body,
            &|t| top.state(t),
            &y0,
            t_end,
            time_scale,
            samples,
            state_distance,
        ),
        _ => Ok(f64::NAN),
    }
}

/// Whether the torque-free closed form keeps its bound on this scene: its
/// defect estimate (four samples) within `CLOSED_FORM_BOUND · max(|ω|T, 1)`.
pub(super) fn closed_form_meets_bound(scene: &Scene, t_end: f64) -> Result<bool, SimError> {
    let est = body_closed_form_estimate(scene, t_end, 4)?;
    let w = scene.rate_scale();
    // Angle per unit of phase, and |Δω| relative to |ω|.
    let bound = CLOSED_FORM_BOUND * (w * t_end).max(1.0) * w.max(1.0);
    Ok(est.is_finite() && est <= bound)
}

/// Why a torque-free closed form is not trusted on a scene.
pub(super) fn untrusted_closed_form() -> Cover {
    Cover::Untrusted(format!(
        "torque-free, but the closed form's defect estimate on this scene exceeds its bound \
         ({CLOSED_FORM_BOUND:e} per unit of |ω| T) or is not finite, so it is not trusted"
    ))
}

/// Runs a body's closed form (steady precession or elliptic): the state at
/// T, recorded as one row, its defect estimate, and `--check`'s DOP853 run.
pub(super) fn run_closed_form(
    scene: &Scene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
) -> Result<Outcome, SimError> {
    let (body, y0) = body_of(scene, plan.model)?;
    let t_end = plan.t_end;
    let mut out = Outcome::default();
    let start = Instant::now();
    let (y, name) = reference_state(scene, t_end)?;
    out.wall_s = start.elapsed().as_secs_f64();
    if rec.active() {
        rec.record(time_and_state(t_end, &y))?;
    }
    out.reference = format!("none: this run is the {name}");
    out.error = Some(body_closed_form_estimate(scene, t_end, ESTIMATE_SAMPLES)?);
    out.error_basis = ESTIMATE_BASIS.into();
    if plan.check {
        let (yc, _) = integrate(
            &body,
            Method::Dop853,
            Step::Tolerance(CHECK_TOL),
            0.0,
            y0,
            t_end,
            Limits::default(),
            |_, _| Ok(()),
        )?;
        out.check = Some(Check {
            against: format!("dop853 at tol={CHECK_TOL:e}"),
            difference: state_distance(&y, &yc),
        });
    }
    out.drifts = free_drifts(&body, &y0, &y);
    out.final_state = y.to_vec();
    Ok(out)
}
