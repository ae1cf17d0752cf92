//! Running a scene: the plan (choosing the least model that is exact for
//! it from the registry), the run through the chosen entry, and the
//! report. The models are entries of [`crate::models::MODELS`]; the one
//! integrate-and-record loop is [`crate::record`]; the work-precision
//! sweep is [`crate::sweep`].
//!
//! # The model-selection rule
//!
//! | scene | model chosen | why |
//! |---|---|---|
//! | fixed axis | `fixed-axis` | one degree of freedom; the motor law is linear in ω, so the closed form needs no integration; reactions from §6 |
//! | free, spin about a principal axis | `steady-precession` (permanent rotation) | ω is constant |
//! | free, axisymmetric | `steady-precession` | §9: closed form, θ constant, no integration |
//! | free, asymmetric | `elliptic` | closed form through Jacobi elliptic functions |
//! | free, integrated (`--method`, not a splitting) | `precession-angle` | H is fixed in space: ω and one angle about H, ω projected onto E and \|H\| |
//! | heavy top in steady precession | `steady-precession` | §7's relation holds: θ, φ̇, ψ̇ constant |
//! | heavy top otherwise | `rigid-body` with the method and setting cheapest for the requested error | no closed form covers it; measured on this scene by pilots ([`crate::models::rigid_body::pilot_choice`]) |
//! | derived (a derivation's equations of motion) | `derived`, integrated with DOP853 at a tolerance fitted on the scene | no built-in closed form is known to cover it: nothing less will do |
//!
//! `--model` and `--method` override: a method alone means "integrate with
//! it the first model of the registry that takes the method and applies".
//!
//! # The registry
//!
//! Each model is one [`ModelEntry`] of [`MODELS`], in its own file of
//! `models/`: what it applies to, why
//! it is chosen, whether it integrates, when it is refused, whether (as a
//! closed form) it covers a scene it applies to, how it integrates by
//! default, which methods a request for a method alone gives it, and how
//! it runs. [`plan`] makes the table above from the entries alone, with no
//! match on scene kind × model: a requested model through its entry's
//! refusal; otherwise the first closed form that applies and covers the
//! scene wins (its reason is the entry's), and when none does, the first
//! entry chosen to integrate that applies is integrated — the reason gives
//! the closed forms' refusals (or why the one that applies is not trusted),
//! says that nothing less will do, the entry's `why`, and how its method
//! and step were chosen. [`run`] runs the planned model through its entry,
//! and every integrated model records its rows through the one
//! [`crate::record::integrate_recorded`]. The `derived` model is the
//! entry of `models/derived.rs`.

use std::fmt;

use serde::Serialize;

pub use crate::estimate::{CHECK_TOL, CLOSED_FORM_BOUND, closed_form_estimate};
pub use crate::model::{
    Check, ConstraintDrift, Cover, DEFAULT_DT, DEFAULT_TOL, Drift, DriftColumns, FrameState,
    Integration, Model, ModelEntry, Plan, PrecessionCheck, REFERENCE_TOL, Request, UnitNormDrift,
    VelocityConstraintDrift, step_label,
};
use crate::model::{not_applicable, requested_step};
pub use crate::models::rigid_body::{PILOT_SAFETY, pilot_choice};
pub use crate::models::{MODELS, reference_state};
pub use crate::record::Output;
use crate::record::{Recorder, check_budget};
use crate::scene::Scene;
pub use crate::sweep::{
    CSV_HEADER, Row, drift_columns, stage_chart, sweep_model, sweep_steps, work_precision,
    write_chart,
};
use crate::{Method, SimError};

/// Chooses the model (and method) for a scene: see the module docs. The
/// choice and its reason come from the registry [`MODELS`]: a requested
/// model is checked by its entry's refusal; without one, the first closed
/// form whose entry covers the scene wins; otherwise the first entry that
/// integrates the scene by default is integrated, and the reason says that
/// nothing less will do and why the closed forms did not apply.
pub fn plan(scene: &Scene, req: &Request) -> Result<Plan, SimError> {
    let t_end = req.t_end.unwrap_or(scene.t_end);
    check_end_time(scene, t_end)?;
    if let Some(step) = req.step {
        step.validate()?;
    }
    let make = |e: &'static dyn ModelEntry, how: Option<Integration>, reason: String| Plan {
        model: Model(e),
        method: how.as_ref().map(|h| h.method),
        step: how.as_ref().map(|h| h.step),
        t_end,
        reason,
        check: req.check,
        fit_error: how.and_then(|h| h.fit_error),
    };
    let with_method = |method: Method| Integration {
        method,
        step: requested_step(req, method),
        fit_error: None,
        detail: String::new(),
    };
    let applies =
        |e: &dyn ModelEntry| -> Result<bool, SimError> { Ok(e.refusal(scene)?.is_none()) };
    // The run budget, before any pilot or reference run: a request's own
    // step, or (for a step still to be chosen) the scene's phase.
    let budget = |step: Option<crate::Step>| {
        crate::estimate::check_run_budget(scene.rate_scale(), t_end, step)
    };
    if let Some(m) = req.model {
        // Whether a requested model applies is its registry entry's to say.
        check_applies(m, scene)?;
        let e = m.entry();
        if !(e.can_integrate() && (e.integrated() || req.method.is_some())) {
            return Ok(make(
                e,
                None,
                format!("{} as requested: {}", e.name(), e.why()),
            ));
        }
        budget(req.method.map(|m| requested_step(req, m)).or(req.step))?;
        return Ok(match req.method {
            Some(method) => make(
                e,
                Some(with_method(method)),
                format!(
                    "{} integrated with {method} as requested: {}",
                    e.name(),
                    e.why()
                ),
            ),
            None => {
                let how = e.integration(scene, req, t_end, false)?;
                let reason = format!("{} as requested: {}; {}", e.name(), e.why(), how.detail);
                make(e, Some(how), reason)
            }
        });
    }
    if let Some(method) = req.method {
        budget(Some(requested_step(req, method)))?;
        for &e in MODELS {
            if e.can_integrate() && e.takes(method) && applies(e)? {
                return Ok(make(
                    e,
                    Some(with_method(method)),
                    format!(
                        "integration with {method} as requested, in the `{}` model: {}",
                        e.name(),
                        e.why()
                    ),
                ));
            }
        }
        // Name the model that would integrate the scene, and why the
        // method is not one of its.
        for &e in MODELS {
            if e.can_integrate() && e.default_choice() && applies(e)? {
                return Err(SimError::MethodNotApplicable {
                    method: method.name().into(),
                    model: e.name().into(),
                    reason: "it has no splitting into exactly solved sub-flows, which the \
                             splitting methods need"
                        .into(),
                });
            }
        }
        return Err(not_applicable(
            Model(&crate::models::rigid_body::RIGID_BODY),
            scene,
            "no model of this scene integrates with the requested method",
        ));
    }
    // A closed form the scene is covered by wins.
    let mut refusals: Vec<String> = Vec::new();
    let mut untrusted: Option<String> = None;
    for &e in MODELS {
        if e.integrated() {
            continue;
        }
        match e.refusal(scene)? {
            Some(why) => refusals.push(why.to_string()),
            None => match e.covers(scene, t_end).transpose()? {
                None => {}
                Some(Cover::Covered(reason)) => return Ok(make(e, None, reason.to_string())),
                Some(Cover::Untrusted(why)) => untrusted = Some(why),
            },
        }
    }
    // Nothing less will do: the first entry that integrates the scene.
    let why_not = untrusted.unwrap_or_else(|| {
        refusals.dedup();
        let mut unique: Vec<String> = Vec::new();
        for r in refusals {
            if !unique.contains(&r) {
                unique.push(r);
            }
        }
        format!("no closed form covers this scene ({})", unique.join("; "))
    });
    for &e in MODELS {
        if !e.can_integrate() || !e.default_choice() || !applies(e)? {
            continue;
        }
        budget(req.step)?;
        let how = e.integration(scene, req, t_end, true)?;
        let reason = format!(
            "{why_not}; nothing less will do, so the `{}` model is integrated: {}; {}",
            e.name(),
            e.why(),
            how.detail
        );
        return Ok(make(e, Some(how), reason));
    }
    Err(not_applicable(
        Model(&crate::models::rigid_body::RIGID_BODY),
        scene,
        "no closed form covers this scene and no model integrates it",
    ))
}

/// Refuses an end time that is negative, not finite, or so long that the
/// phase `|ω| T` exceeds 2^52 (f64 time no longer resolves one turn).
pub fn check_end_time(scene: &Scene, t_end: f64) -> Result<(), SimError> {
    if !(t_end.is_finite() && t_end >= 0.0) {
        return Err(SimError::BadEndTime(t_end));
    }
    let phase = scene.rate_scale() * t_end;
    if phase.is_nan() || phase > 2f64.powi(52) {
        return Err(SimError::EndTimeTooLong { t_end, phase });
    }
    Ok(())
}

/// What a run reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Scene name.
    pub scene: String,
    /// Scene kind.
    pub kind: &'static str,
    /// Model, method and why.
    pub plan: Plan,
    /// The reference the error is measured against.
    pub reference: String,
    /// Error at T: distance to the reference for an integrated run, an
    /// estimate (see `error_basis`) for a closed-form run.
    pub error: Option<f64>,
    /// How `error` was obtained (`measured against …` or `estimated: …`).
    pub error_basis: String,
    /// `--check`: distance of a closed-form run from a tight DOP853 run.
    pub check: Option<Check>,
    /// Invariant drifts at T.
    pub drifts: Vec<Drift>,
    /// Right-hand-side evaluations (sub-flows for the splittings).
    pub evaluations: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Wall time of the run (without the reference), seconds.
    pub wall_s: f64,
    /// State at T (`[q, ω]`, `[angle, ω]` for a shaft).
    pub final_state: Vec<f64>,
    /// Heavy top in steady precession: §7 check.
    pub precession: Option<PrecessionCheck>,
    /// Shaft: bearing reactions at T (`[A_x, A_y, B_x, B_y]`) and moments `[M_x, M_y, M_z]`.
    pub reactions: Option<[f64; 7]>,
    /// Stored trajectory rows (time first), when asked for.
    pub trajectory: Option<Vec<Vec<f64>>>,
    /// Names of the components of `final_state` (a derived scene's
    /// coordinates and rates; empty for the built-in models, whose state
    /// is `[q, ω]`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub state_names: Vec<String>,
    /// A derived scene's reported frame at T.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frame: Option<FrameState>,
    /// A derived scene's configuration constraints along the run: the
    /// largest |f(q)| and the projection's largest correction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub constraints: Option<ConstraintDrift>,
    /// A multiplier form's velocity constraints along the run: the
    /// largest |A_c u| and the largest correction of a dependent speed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity_constraints: Option<VelocityConstraintDrift>,
    /// A derived state's Euler parameters: normalized after each step,
    /// the largest | |e| − 1 | met before it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit_norms: Option<UnitNormDrift>,
    /// Where a derived scene's declared bodies are at T, in the order of
    /// their declarations (empty for the built-in models).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub positions: Vec<BodyPosition>,
}

/// Where one of a derivation's declared bodies is at T: its reference
/// point (its `point`) from N's origin, in N's axes; or why that is not
/// known (a point that moves freely, a frame whose attitude is not a
/// function of the state).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodyPosition {
    /// The body's name in the derivation.
    pub body: String,
    /// `[x, y, z]` in N, when the body is placed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 3]>,
    /// Why the body has no position, when it has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unknown: Option<String>,
}

/// The positions of a derived scene's declared bodies at `(t, y)` (none
/// for a built-in model's scene).
fn positions_at(scene: &Scene, t: f64, y: &[f64]) -> Vec<BodyPosition> {
    let Some(ds) = scene.derivation() else {
        return Vec::new();
    };
    ds.model
        .bodies()
        .map(|b| {
            let (at, unknown) = match ds.model.position(b, t, y) {
                Ok(r) => (Some([r.x, r.y, r.z]), None),
                Err(why) => (None, Some(why)),
            };
            BodyPosition {
                body: b.to_owned(),
                at,
                unknown,
            }
        })
        .collect()
}

/// The bodies whose positions the `--output` stream carries: those of a
/// derived scene placed at its initial state, in declaration order.
fn placed_bodies(scene: &Scene) -> Vec<String> {
    let Some(ds) = scene.derivation() else {
        return Vec::new();
    };
    positions_at(scene, 0.0, &ds.y0)
        .into_iter()
        .filter(|p| p.at.is_some())
        .map(|p| p.body)
        .collect()
}

/// Refuses `model` on `scene` when its entry says it does not apply.
fn check_applies(model: Model, scene: &Scene) -> Result<(), SimError> {
    match model.entry().refusal(scene)? {
        Some(why) => Err(not_applicable(model, scene, why)),
        None => Ok(()),
    }
}

/// Runs a scene as planned, through the planned model's entry.
pub fn run(scene: &Scene, plan: &Plan, out: &mut Output<'_>) -> Result<Report, SimError> {
    check_applies(plan.model, scene)?;
    let entry = plan.model.entry();
    let row_len = entry.stream_header(scene).split(',').count();
    check_budget(out, plan.step, plan.t_end, row_len)?;
    // The streamed rows carry the placed bodies' positions after the state.
    let placed = placed_bodies(scene);
    let columns = |row: &[f64]| -> Vec<f64> {
        let Some(ds) = scene.derivation() else {
            return Vec::new();
        };
        placed
            .iter()
            .flat_map(|b| {
                let r = ds
                    .model
                    .position(b, row[0], &row[1..])
                    .unwrap_or_else(|_| nalgebra::Vector3::repeat(f64::NAN));
                [r.x, r.y, r.z]
            })
            .collect()
    };
    let mut rec = Recorder::new(out);
    if !placed.is_empty() {
        rec = rec.with_columns(&columns);
    }
    let o = entry.run(scene, plan, &mut rec)?;
    let mut plan = plan.clone();
    if let Some((step, why)) = o.fitted {
        plan.step = Some(step);
        plan.reason = format!("{}; {why}", plan.reason);
    }
    let positions = positions_at(scene, plan.t_end, &o.final_state);
    let report = Report {
        scene: scene.name.clone(),
        kind: scene.kind.name(),
        plan,
        reference: o.reference,
        error: o.error,
        error_basis: o.error_basis,
        check: o.check,
        drifts: o.drifts,
        evaluations: o.stats.evaluations,
        steps: o.stats.steps,
        rejected: o.stats.rejected,
        wall_s: o.wall_s,
        final_state: o.final_state,
        precession: o.precession,
        reactions: o.reactions,
        trajectory: rec.take_rows(),
        state_names: o.state_names,
        frame: o.frame,
        constraints: o.constraints,
        velocity_constraints: o.velocity_constraints,
        unit_norms: o.unit_norms,
        positions,
    };
    refuse_non_finite(&report)?;
    Ok(report)
}

/// How far above the run's error a derived scene's conserved step may
/// drift: more is a failure (the step is not conserved by the equations
/// integrated, or the run is not converged), not a number to print.
pub const DRIFT_FACTOR: f64 = 100.0;

/// The error below which a drift is round-off however small the run's
/// error (relative).
pub const DRIFT_FLOOR: f64 = 1e-12;

impl Report {
    /// The drifts of a derived scene's conserved steps more than
    /// [`DRIFT_FACTOR`] times the error at T (at least [`DRIFT_FLOOR`]):
    /// each a claim `conserved` the integrated equations contradict.
    pub fn failed_drifts(&self) -> Vec<&Drift> {
        let Some(error) = self.error.filter(|_| self.kind == "derived") else {
            return Vec::new();
        };
        let bound = DRIFT_FACTOR * error.max(DRIFT_FLOOR);
        self.drifts.iter().filter(|d| d.relative > bound).collect()
    }
}

/// The columns of the rows `model` records on a scene (the stored
/// trajectory): `t` and the state.
pub fn stream_header(scene: &Scene, model: Model) -> String {
    model.entry().stream_header(scene)
}

/// The CSV header of the `--output` stream: the recorded row's columns
/// ([`stream_header`]), then, for a derived scene, the position of each
/// declared body placed at the start, `<body>.x,<body>.y,<body>.z` (in
/// N, from its origin).
pub fn csv_header(scene: &Scene, model: Model) -> String {
    let mut header = stream_header(scene, model);
    for b in placed_bodies(scene) {
        for c in ["x", "y", "z"] {
            header.push_str(&format!(",{b}.{c}"));
        }
    }
    header
}

/// A NaN or infinity anywhere in a report is an error naming it.
fn refuse_non_finite(r: &Report) -> Result<(), SimError> {
    let t = r.plan.t_end;
    let bad = |quantity: String| Err(SimError::NonFiniteResult { t, quantity });
    let names: &[&str] = if r.final_state.len() == 7 {
        &["q_w", "q_x", "q_y", "q_z", "ω_1", "ω_2", "ω_3"]
    } else {
        &["angle", "ω"]
    };
    for (k, v) in r.final_state.iter().enumerate() {
        if !v.is_finite() {
            return bad(format!(
                "state component {}",
                names.get(k).copied().unwrap_or("?")
            ));
        }
    }
    for d in &r.drifts {
        if !d.relative.is_finite() {
            return bad(format!("drift of {}", d.name));
        }
    }
    if let Some(c) = &r.constraints
        && !(c.max_residual.is_finite() && c.max_correction.is_finite())
    {
        return bad(format!(
            "residual of the constraint(s) {}",
            c.steps.join(", ")
        ));
    }
    if let Some(c) = &r.velocity_constraints
        && !(c.max_residual.is_finite() && c.max_correction.is_finite())
    {
        return bad("residual of the velocity constraints A_c u".into());
    }
    if let Some(n) = &r.unit_norms
        && !n.max_drift.is_finite()
    {
        return bad("drift of the Euler parameters' norm".into());
    }
    if let Some(re) = &r.reactions {
        const RN: [&str; 7] = ["A_x", "A_y", "B_x", "B_y", "M_x", "M_y", "M_z"];
        if let Some(k) = re.iter().position(|v| !v.is_finite()) {
            return bad(format!("reaction {}", RN[k]));
        }
    }
    if let Some(e) = r.error
        && !e.is_finite()
    {
        return bad("error at T".into());
    }
    for p in &r.positions {
        if p.at.is_some_and(|a| !a.iter().all(|c| c.is_finite())) {
            return bad(format!("position of body `{}`", p.body));
        }
    }
    Ok(())
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.plan;
        // The scene's name as a terminal shows it, never obeyed.
        let scene = hdot_sym::escape::terminal(&self.scene);
        writeln!(f, "scene:       {scene} ({})", self.kind)?;
        writeln!(f, "model:       {}", p.model)?;
        writeln!(f, "why:         {}", p.reason)?;
        match (p.method, p.step) {
            (Some(m), Some(s)) => writeln!(f, "method:      {m} ({})", step_label(s))?,
            _ => writeln!(f, "method:      none (closed form)")?,
        }
        writeln!(f, "t_end:       {}", p.t_end)?;
        writeln!(f, "reference:   {}", self.reference)?;
        match self.error {
            Some(e) => writeln!(f, "error at T:  {e:.3e} ({})", self.error_basis)?,
            None => writeln!(f, "error at T:  not estimated")?,
        }
        if let Some(c) = &self.check {
            writeln!(
                f,
                "check:       {:.3e} from {} (--check)",
                c.difference, c.against
            )?;
        }
        let failed = self.failed_drifts();
        for d in &self.drifts {
            writeln!(
                f,
                "drift {:<6} {:.3e} (relative){}",
                format!("{}:", d.name),
                d.relative,
                if failed.iter().any(|x| x.name == d.name) {
                    format!(
                        "  FAIL: more than {DRIFT_FACTOR}× the error at T: not conserved by these equations"
                    )
                } else {
                    String::new()
                }
            )?;
        }
        if let Some(c) = &self.constraints {
            let steps = c
                .steps
                .iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", ");
            let kept = if c.projected {
                format!(
                    "{} projected onto f = 0 after each step by Newton's method (largest correction {:.3e})",
                    c.dependent.join(", "),
                    c.max_correction
                )
            } else {
                format!(
                    "not projected (project = false): {} integrated from the constraints' rates",
                    c.dependent.join(", ")
                )
            };
            writeln!(
                f,
                "constraint:  max |f(q)| = {:.3e} over the run (step(s) {steps}); {kept}",
                c.max_residual
            )?;
        }
        if let Some(c) = &self.velocity_constraints {
            writeln!(
                f,
                "velocity:    max |A_c u| = {:.3e} over the run; {} solved from A_c u = 0 after each \
                 step (largest correction {:.3e})",
                c.max_residual,
                c.dependent.join(", "),
                c.max_correction
            )?;
        }
        if let Some(n) = &self.unit_norms {
            let names: Vec<String> = n.parameters.iter().map(|e| e.join(", ")).collect();
            writeln!(
                f,
                "unit norm:   {} divided by the norm after each step (largest | |e| - 1 | before it {:.3e})",
                names.join("; "),
                n.max_drift
            )?;
        }
        writeln!(
            f,
            "evaluations: {} ({} steps, {} rejected)",
            self.evaluations, self.steps, self.rejected
        )?;
        writeln!(f, "wall time:   {:.3e} s", self.wall_s)?;
        if let Some(pc) = &self.precession {
            let rates = significant(&[pc.simulated, pc.predicted], 9);
            writeln!(
                f,
                "precession:  simulated φ̇ = {}, §7 predicts {} (relative difference {:.2e}, |Δθ| = {:.2e})",
                rates[0], rates[1], pc.relative_difference, pc.nutation_change
            )?;
        }
        if let Some(r) = &self.reactions {
            // Forces and moments each on their own scale.
            let forces = significant(&r[..4], 6);
            let moments = significant(&r[4..], 6);
            writeln!(
                f,
                "reactions:   A = ({}, {}), B = ({}, {}) N; ΣM_O = ({}, {}, {}) N·m",
                forces[0], forces[1], forces[2], forces[3], moments[0], moments[1], moments[2]
            )?;
        }
        if let Some(fs) = &self.frame {
            let r = &fs.attitude;
            let attitude = significant(&r.concat(), 9);
            let row = |k: usize| attitude[3 * k..3 * k + 3].join(", ");
            writeln!(
                f,
                "frame {}:     attitude [[{}], [{}], [{}]], ω = ({}) rad/s",
                fs.frame,
                row(0),
                row(1),
                row(2),
                significant(&fs.angular_velocity, 9).join(", ")
            )?;
        }
        for p in &self.positions {
            let body = hdot_sym::escape::terminal(&p.body);
            match (&p.at, &p.unknown) {
                (Some(a), _) => writeln!(
                    f,
                    "position:    {body} at ({}) in N (its reference point at T)",
                    significant(a, 9).join(", ")
                )?,
                (None, why) => writeln!(
                    f,
                    "position:    {body} not known: {}",
                    why.as_deref().unwrap_or("no place declared")
                )?,
            }
        }
        writeln!(f, "state at T:  [{}]", self.state_text().join(", "))
    }
}

impl Report {
    /// The state at T as printed: 12 significant digits; a built-in
    /// model's quaternion's scalar part, its vector part and the rates (or
    /// a shaft's angle and rate) each on their own scale, a derived scene's components each named and on
    /// its own.
    fn state_text(&self) -> Vec<String> {
        let y = &self.final_state;
        if self.state_names.len() == y.len() {
            return self
                .state_names
                .iter()
                .zip(y)
                .map(|(n, v)| format!("{n} = {}", significant(&[*v], 12)[0]))
                .collect();
        }
        // A quaternion's scalar part, its vector part (small for a small
        // rotation, however close the scalar part is to 1) and the rates;
        // or an angle and its rates.
        let groups: &[usize] = if y.len() == 7 { &[1, 4] } else { &[1] };
        let mut out = Vec::with_capacity(y.len());
        let mut from = 0;
        for &to in groups.iter().chain([&y.len()]) {
            let to = to.clamp(from, y.len());
            out.extend(significant(&y[from..to], 12));
            from = to;
        }
        out
    }
}

/// The values of one quantity (a vector, a matrix, a group of forces) with
/// `digits` significant digits, however small they all are: a value below
/// 10⁻¹² of the group's largest — round-off of an exact zero — prints as
/// `0`, unsigned. The numeric commands' formatter
/// ([`hdot_num::report::fmt_num_at`]), the one formatter of the report's
/// numbers.
pub fn significant(xs: &[f64], digits: usize) -> Vec<String> {
    let scale = xs.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    xs.iter()
        .map(|x| hdot_num::report::fmt_num_at(*x, scale, digits))
        .collect()
}
