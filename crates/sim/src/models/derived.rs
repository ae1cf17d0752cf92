//! The `derived` model: the equations of motion a derivation file
//! derived, integrated in its coordinates `y = (q, q̇)`
//! ([`DerivedSystem`]), with the same recording, reference run and drift
//! report as the built-in models; its tolerance is fitted on the scene.
//!
//! The state has `2 × dof` components (or the coordinates and speeds of a
//! first-order model), a number known only when the scene is read, while
//! the integrators take fixed-size arrays; `with_len` dispatches on it
//! once, up to [`MAX_STATE`] components.

use nalgebra::Matrix3;

use crate::model::{
    ConstraintDrift, DEFAULT_TOL, Descriptor, Drift, DriftColumns, FrameState, Integration,
    Measured, Model, ModelEntry, Outcome, Plan, REFERENCE_TOL, Request, UnitNormDrift,
    VelocityConstraintDrift, not_a_splitting, not_applicable,
};
use crate::record::{Recorder, integrate_recorded, time_and_state, timed};
use crate::scene::{DerivedScene, Scene};
use crate::systems::derived::{Conserved, DerivedModel, DerivedSystem, MAX_STATE};
use crate::{Limits, Method, SimError, Stats, Step, integrate};

/// Calls `$f::<N>(args)` for the state length `$len` (2 to MAX_STATE).
macro_rules! with_len {
    ($len:expr, $f:ident ( $($arg:expr),* )) => {
        match $len {
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            7 => $f::<7>($($arg),*),
            8 => $f::<8>($($arg),*),
            9 => $f::<9>($($arg),*),
            10 => $f::<10>($($arg),*),
            11 => $f::<11>($($arg),*),
            12 => $f::<12>($($arg),*),
            13 => $f::<13>($($arg),*),
            14 => $f::<14>($($arg),*),
            15 => $f::<15>($($arg),*),
            16 => $f::<16>($($arg),*),
            17 => $f::<17>($($arg),*),
            18 => $f::<18>($($arg),*),
            n => Err(SimError::Derived {
                message: format!(
                    "a state of {n} components; derived models have 2 to {MAX_STATE} components"
                ),
            }),
        }
    };
}

/// The entry.
pub struct Derived;

/// The entry, as the registry lists it.
pub static DERIVED: Derived = Derived;

/// What the entry says of itself.
const DESCRIPTOR: Descriptor = Descriptor {
    name: "derived",
    applies_to: "a scene of kind derived (a derivation's equations of motion)",
    why: "exactly the equations the file derived, integrated in its coordinates",
    integrated: true,
    can_integrate: true,
};

/// Why `derived` runs only a derived scene.
const NOT_DERIVED: &str =
    "only a scene of kind \"derived\" names a derivation's equations of motion";

fn derived_of(scene: &Scene) -> Result<&DerivedScene, SimError> {
    scene.derivation().ok_or_else(|| {
        not_applicable(
            Model(&DERIVED),
            scene,
            "the scene is not of a kind this model describes",
        )
    })
}

impl ModelEntry for Derived {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError> {
        Ok(scene.derivation().is_none().then_some(NOT_DERIVED))
    }
    /// DOP853, its tolerance fitted on the scene to the requested error
    /// unless a fixed step is asked for.
    fn integration(
        &self,
        _: &Scene,
        req: &Request,
        _: f64,
        _: bool,
    ) -> Result<Integration, SimError> {
        let target = match req.step {
            Some(Step::Fixed(_)) => return Ok(Integration::dop853(req)),
            Some(Step::Tolerance(t)) => t,
            None => DEFAULT_TOL,
        };
        Ok(Integration {
            method: Method::Dop853,
            step: Step::Tolerance(target),
            fit_error: Some(target),
            detail: "dop853, its tolerance fitted to the requested error by two pilot runs"
                .to_string(),
        })
    }
    fn takes(&self, method: Method) -> bool {
        not_a_splitting(method)
    }
    fn default_choice(&self) -> bool {
        true
    }
    fn stream_header(&self, scene: &Scene) -> String {
        match scene.derivation() {
            Some(ds) => format!("t,{}", ds.state_names().join(",")),
            None => "t".into(),
        }
    }
    fn run(
        &self,
        scene: &Scene,
        plan: &Plan,
        rec: &mut Recorder<'_, '_>,
    ) -> Result<Outcome, SimError> {
        let ds = derived_of(scene)?;
        with_len!(ds.y0.len(), run_n(ds, plan, rec))
    }
    fn sweeps(&self) -> bool {
        true
    }
    fn sweep_run(
        &self,
        scene: &Scene,
        method: Method,
        step: Step,
        t_end: f64,
        min_time: f64,
    ) -> Result<Result<Measured, String>, SimError> {
        let ds = derived_of(scene)?;
        with_len!(ds.y0.len(), sweep_n(ds, method, step, t_end, min_time))
    }
    fn drift_columns(&self, scene: &Scene) -> DriftColumns {
        drift_columns(scene)
    }
}

fn start<const N: usize>(ds: &DerivedScene) -> [f64; N] {
    let mut y = [0.0; N];
    y.copy_from_slice(&ds.y0);
    y
}

fn integrate_n<const N: usize>(
    model: &DerivedModel,
    method: Method,
    step: Step,
    y0: [f64; N],
    t_end: f64,
    observe: impl FnMut(f64, &[f64; N]) -> Result<(), SimError>,
) -> Result<([f64; N], Stats), SimError> {
    integrate(
        &DerivedSystem::<N>(model),
        method,
        step,
        0.0,
        y0,
        t_end,
        Limits::default(),
        observe,
    )
}

/// The state at `t_end` of the reference run (DOP853 at [`REFERENCE_TOL`]),
/// its progress reported to `observe`; a stop on the run budget names it.
fn reference_n<const N: usize>(
    ds: &DerivedScene,
    t_end: f64,
    observe: impl FnMut(f64, &[f64; N]) -> Result<(), SimError>,
) -> Result<[f64; N], SimError> {
    integrate_n(
        &ds.model,
        Method::Dop853,
        Step::Tolerance(REFERENCE_TOL),
        start::<N>(ds),
        t_end,
        observe,
    )
    .map(|(y, _)| y)
    .map_err(|e| {
        e.in_run(|| {
            format!(
                "the reference run (dop853 at tol={REFERENCE_TOL:e}, which the error at T is measured against)"
            )
        })
    })
}

/// How many times a fitted tolerance that misses its target is tightened
/// (each time confirmed by one more pilot run).
const MAX_REFITS: usize = 2;

/// The DOP853 tolerance at which the error at `t_end` (against
/// `reference`) should be `target`, measured on this scene by two pilot
/// runs at `target` and `target/100`:
/// - the first pilot already within `target/3`: its tolerance;
/// - the error shrinking with the tolerance: fit `error ≈ C tol^p` and take
///   the tolerance predicted for `target/3` (a factor 3 of safety);
/// - otherwise (the error does not shrink: the motion is so sensitive that
///   the reference itself is in doubt) no fit: the smaller pilot
///   tolerance, and the reason says so.
///
/// A tolerance whose error is not measured yet is then confirmed by a
/// pilot run at it, and while its error misses `target` tightened (to the
/// fit's prediction from that error, at least tenfold) and confirmed
/// again — at most [`MAX_REFITS`] times, never below `1e-13`.
/// Whether the run then meets `target` is for its caller to check (a run
/// at the tolerance returned reaches the error its last pilot measured).
/// Returns the tolerance and what was measured.
fn fit_tolerance<const N: usize>(
    ds: &DerivedScene,
    t_end: f64,
    target: f64,
    reference: &[f64; N],
    rec: &mut Recorder<'_, '_>,
) -> Result<(f64, String), SimError> {
    let mut error_at = |tol: f64| -> Result<(f64, u64), SimError> {
        let (y, stats) = integrate_n(
            &ds.model,
            Method::Dop853,
            Step::Tolerance(tol),
            start::<N>(ds),
            t_end,
            rec.observer::<N>("pilot run"),
        )
        .map_err(|e| {
            e.in_run(|| format!("a pilot run (dop853 at tol={tol:e}, fitting the tolerance)"))
        })?;
        Ok((distance(ds, t_end, &y, reference), stats.evaluations))
    };
    let (lo, hi) = (1e-13, 1e-2);
    let ta = target.clamp(lo, hi);
    let tb = (ta * 1e-2).max(lo);
    let (ea, na) = error_at(ta)?;
    let (eb, nb) = error_at(tb)?;
    let pilots = format!(
        "tolerance fitted on this scene: dop853 reached {ea:.2e} at tol={ta:.0e} and {eb:.2e} at tol={tb:.0e} ({} evaluations)",
        na + nb
    );
    let safe = target / 3.0;
    if ea <= safe {
        return Ok((
            ta,
            format!("{pilots}; the first already within {target:e}/3, so tol={ta:.1e}"),
        ));
    }
    let shrinks = ea > eb && eb > 0.0 && ta > tb;
    let p = if shrinks {
        (ea / eb).ln() / (ta / tb).ln()
    } else {
        1.0
    };
    let (mut tol, mut why) = if shrinks {
        // Never looser than the loosest pilot: beyond it the fit is an
        // extrapolation (an error ∝ tol^0.5 fitted where both pilots
        // already meet the request predicts tolerances that miss it).
        let tol = (ta * (safe / ea).powf(1.0 / p)).clamp(lo, ta);
        (
            tol,
            format!(
                "{pilots}, error ∝ tol^{p:.2}, so tol={tol:.1e} for an error ≤ {target:e}/3{}",
                if tol == lo {
                    " (the smallest tolerance tried)"
                } else {
                    ""
                }
            ),
        )
    } else {
        (
            tb,
            format!(
                "{pilots}: the error did not shrink with the tolerance, so no fit (the motion is sensitive to \
                 small changes and the reference at tol={REFERENCE_TOL:e} may be as far off); tol={tb:.1e}"
            ),
        )
    };
    // Confirm the tolerance, tightening it while it misses the target.
    let mut known = (tol == tb).then_some(eb).or((tol == ta).then_some(ea));
    for round in 0..=MAX_REFITS {
        let e = match known.take() {
            Some(e) => e,
            None => {
                let (e, _) = error_at(tol)?;
                why.push_str(&format!("; a pilot at tol={tol:.1e} reached {e:.2e}"));
                e
            }
        };
        if e <= target || tol <= lo || round == MAX_REFITS {
            break;
        }
        let tighter = if e > 0.0 && e.is_finite() {
            (tol * (safe / e).powf(1.0 / p.max(0.5))).min(tol / 10.0)
        } else {
            tol / 10.0
        };
        tol = tighter.max(lo);
        why.push_str(&format!(
            ", more than {target:e}: tightened to tol={tol:.1e}"
        ));
    }
    Ok((tol, why))
}

/// What the error of a derived run measures.
pub fn error_measure(ds: &DerivedScene) -> String {
    match &ds.frame {
        Some(f) => format!(
            "√(angle² + |Δω|²) of frame {f} at T, as for the built-in models (the angle of the rotation \
             between the two attitudes, ω in the frame's axes)"
        ),
        None if ds.model.is_first_order() => {
            "largest |Δq| plus largest |Δu| over the largest |u| at T (no frame named)".into()
        }
        None => "largest |Δq| plus largest |Δq̇| over the largest |q̇| at T (no frame named)".into(),
    }
}

/// Distance of `y` from the reference `r`: see [`error_measure`].
pub fn distance(ds: &DerivedScene, t: f64, y: &[f64], r: &[f64]) -> f64 {
    let m = &ds.model;
    if let Some(f) = &ds.frame
        && let (Ok(a), Ok(b), Ok(wa), Ok(wb)) = (
            m.attitude(f, t, y),
            m.attitude(f, t, r),
            m.angular_velocity(f, t, y),
            m.angular_velocity(f, t, r),
        )
    {
        return rotation_angle(&(a.transpose() * b)).hypot((wa - wb).norm());
    }
    // The carried angles follow from the rest: not counted.
    let (n, base) = (m.dof(), m.carried_base());
    let dq = (0..n).map(|i| (y[i] - r[i]).abs()).fold(0.0, f64::max);
    let scale = r[n..base].iter().map(|v| v.abs()).fold(0.0, f64::max);
    let dv = (n..base).map(|i| (y[i] - r[i]).abs()).fold(0.0, f64::max);
    dq + dv / scale.max(f64::MIN_POSITIVE)
}

/// The angle of a rotation matrix, accurate for small angles as well.
fn rotation_angle(r: &Matrix3<f64>) -> f64 {
    let axis = nalgebra::Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    );
    let cos = (r.trace() - 1.0) / 2.0;
    (axis.norm() / 2.0).atan2(cos)
}

/// The size of each conserved quantity along a run: the largest norm,
/// over the states seen, of its components' term sizes
/// ([`DerivedModel::conserved_size`]) — what its drift is relative to.
struct Sizes<'a> {
    ds: &'a DerivedScene,
    largest: Vec<f64>,
}

impl<'a> Sizes<'a> {
    fn new(ds: &'a DerivedScene) -> Self {
        Sizes {
            ds,
            largest: vec![0.0; ds.model.conserved().len()],
        }
    }

    /// Takes the state `(t, y)` into account.
    fn see(&mut self, t: f64, y: &[f64]) {
        let m = &self.ds.model;
        for (q, s) in m.conserved().iter().zip(&mut self.largest) {
            *s = s.max(norm(&m.conserved_size(q, t, y)));
        }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The drift of each conserved quantity between `y0` and `y` at `t`,
/// relative to its size along the run (`sizes`, [`Sizes`]; never less
/// than its value at either end): an energy that is zero at the start —
/// an arm released from rest where its potential is zero — drifts
/// relative to the kinetic and potential energies it exchanges, not to 0.
fn drifts(ds: &DerivedScene, y0: &[f64], t: f64, y: &[f64], sizes: &Sizes<'_>) -> Vec<Drift> {
    let m = &ds.model;
    m.conserved()
        .iter()
        .zip(&sizes.largest)
        .map(|(q, &size)| {
            let a = m.conserved_value(q, 0.0, y0);
            let b = m.conserved_value(q, t, y);
            let diff: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x - y).collect();
            let scale = size
                .max(norm(&m.conserved_size(q, 0.0, y0)))
                .max(norm(&m.conserved_size(q, t, y)));
            Drift {
                name: q.name.clone(),
                relative: norm(&diff) / scale.max(f64::MIN_POSITIVE),
            }
        })
        .collect()
}

fn run_n<const N: usize>(
    ds: &DerivedScene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
) -> Result<Outcome, SimError> {
    let (method, mut step) = plan.method_step()?;
    let y0 = start::<N>(ds);
    let mut sizes = Sizes::new(ds);
    sizes.see(0.0, &y0);
    let reference = {
        let mut observe = rec.observer::<N>("reference run");
        reference_n::<N>(ds, plan.t_end, |t, y| {
            sizes.see(t, y);
            observe(t, y)
        })?
    };
    let mut report = Outcome::default();
    if let (Some(target), Method::Dop853) = (plan.fit_error, method) {
        let (tol, why) = fit_tolerance::<N>(ds, plan.t_end, target, &reference, rec)?;
        step = Step::Tolerance(tol);
        report.fitted = Some((step, why));
    }
    ds.model.reset_constraint_monitor();
    ds.model.reset_velocity_monitor(&y0);
    ds.model.reset_unit_norm_monitor();
    let (y, stats, wall) = integrate_recorded(
        &DerivedSystem::<N>(&ds.model),
        (method, step),
        y0,
        plan.t_end,
        rec,
        time_and_state,
    )?;
    report.wall_s = wall;
    report.reference = format!("dop853 at tol={REFERENCE_TOL:e} on the same derived equations");
    report.error_basis = format!("measured against the reference: {}", error_measure(ds));
    report.error = Some(distance(ds, plan.t_end, &y, &reference));
    report.drifts = drifts(ds, &y0, plan.t_end, &y, &sizes);
    report.final_state = y.to_vec();
    report.state_names = ds.state_names();
    report.frame = frame_state(ds, plan.t_end, &y);
    report.constraints = constraint_drift(ds, &y0);
    report.velocity_constraints = ds
        .model
        .velocity_monitor()
        .map(|v| VelocityConstraintDrift {
            dependent: ds.model.dependent_speeds(),
            max_residual: v.max_residual,
            max_correction: v.max_correction,
        });
    report.unit_norms = ds.model.unit_norm_drift().map(|max_drift| UnitNormDrift {
        parameters: ds.model.unit_norms(),
        max_drift,
    });
    report.stats = stats;
    Ok(report)
}

/// What the configuration constraints met along the run just made (the
/// model's monitor), with the residual at the start counted.
fn constraint_drift(ds: &DerivedScene, y0: &[f64]) -> Option<ConstraintDrift> {
    let m = &ds.model;
    let (steps, dependent) = m.holonomic()?;
    let rec = m.constraint_monitor()?;
    let r0 = m
        .constraint_residual(0.0, y0)
        .iter()
        .fold(0.0_f64, |a, v| a.max(v.abs()));
    Some(ConstraintDrift {
        steps,
        dependent,
        max_residual: rec.max_residual.max(r0),
        projected: m.projects(),
        max_correction: rec.max_correction,
    })
}

/// The reported frame's attitude and angular velocity at `(t, y)`.
pub fn frame_state(ds: &DerivedScene, t: f64, y: &[f64]) -> Option<FrameState> {
    let f = ds.frame.as_ref()?;
    let r = ds.model.attitude(f, t, y).ok()?;
    let w = ds.model.angular_velocity(f, t, y).ok()?;
    Some(FrameState {
        frame: f.clone(),
        attitude: [
            [r[(0, 0)], r[(0, 1)], r[(0, 2)]],
            [r[(1, 0)], r[(1, 1)], r[(1, 2)]],
            [r[(2, 0)], r[(2, 1)], r[(2, 2)]],
        ],
        angular_velocity: [w.x, w.y, w.z],
    })
}

/// One run of the work-precision sweep on a derived scene.
fn sweep_n<const N: usize>(
    ds: &DerivedScene,
    method: Method,
    step: Step,
    t_end: f64,
    min_time: f64,
) -> Result<Result<Measured, String>, SimError> {
    let y0 = start::<N>(ds);
    let mut sizes = Sizes::new(ds);
    sizes.see(0.0, &y0);
    let reference = reference_n::<N>(ds, t_end, |t, y| {
        sizes.see(t, y);
        Ok(())
    })?;
    let run = || integrate_n(&ds.model, method, step, y0, t_end, |_, _| Ok(()));
    Ok(match timed(min_time, run) {
        Ok(((y, stats), wall_s)) => {
            // The work-precision table has two drift columns: the first
            // conserved step that is an energy goes in the first, the
            // largest drift of the others (momenta) in the second (see
            // [`drift_columns`]).
            let energy = ds.model.conserved().iter().map(|q| q.energy.is_some());
            let (energy, others): (Vec<_>, Vec<_>) = energy
                .zip(drifts(ds, &y0, t_end, &y, &sizes))
                .partition(|(e, _)| *e);
            Ok(Measured {
                error: distance(ds, t_end, &y, &reference),
                wall_s,
                stats,
                energy_drift: energy.first().map_or(f64::NAN, |(_, d)| d.relative),
                momentum_drift: others
                    .iter()
                    .map(|(_, d)| d.relative)
                    .reduce(f64::max)
                    .unwrap_or(f64::NAN),
            })
        }
        Err(e) => Err(e.to_string()),
    })
}

/// What the work-precision drift columns measure on a derived scene: the
/// first conserved step that is an energy, and the largest drift of the
/// other conserved steps; or why there is none.
fn drift_columns(scene: &Scene) -> DriftColumns {
    let Some(ds) = scene.derivation() else {
        let none = Err("not a derived scene".to_string());
        return DriftColumns {
            energy: none.clone(),
            momentum: none,
        };
    };
    let conserved = ds.model.conserved();
    let (energy, others): (Vec<_>, Vec<_>) = conserved.iter().partition(|q| q.energy.is_some());
    let names = |qs: &[&Conserved]| {
        qs.iter()
            .map(|q| format!("`{}`", q.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let energy = match energy.first() {
        Some(q) => Ok(format!(
            "step `{}` ({})",
            q.name,
            q.energy.as_deref().unwrap_or_default()
        )),
        None if conserved.is_empty() => Err(
            "the derivation marks no step `conserved = true` (and the scene lists none under `conserved`)"
                .to_string(),
        ),
        None => Err(format!(
            "no conserved step is an energy (its `means` a kinetic or potential energy, or `energy` in its name, label or doc); conserved: {}",
            names(&others)
        )),
    };
    let momentum = if others.is_empty() {
        Err("no conserved step other than an energy".to_string())
    } else {
        Ok(format!("the largest drift of step(s) {}", names(&others)))
    };
    DriftColumns { energy, momentum }
}
