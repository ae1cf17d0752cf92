//! Running a scene: choosing the least model that is exact for it, running
//! it, comparing with the exact or reference solution, and sweeping every
//! method for the work-precision study.
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
//! | heavy top otherwise | `rigid-body` with the method and setting cheapest for the requested error | no closed form covers it; measured on this scene by pilots ([`pilot_choice`]) |
//! | derived (a derivation's equations of motion) | `derived`, integrated with DOP853 at a tolerance fitted on the scene | no built-in closed form is known to cover it: nothing less will do |
//!
//! `--model` and `--method` override: a method alone means "integrate with
//! it the first model of the registry that takes the method and applies".
//!
//! # The registry
//!
//! Each model is one [`ModelEntry`] of [`MODELS`]: what it applies to, why
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
//! `integrate_recorded`. The `derived` model is the entry whose run is
//! [`derived`]'s.

use std::fmt;
use std::io::Write;
use std::str::FromStr;
use std::time::Instant;

use serde::Serialize;

use crate::exact::{SteadyTop, TorqueFree};
use crate::models::euler_angles::to_quaternion_state;
use crate::models::free::{attitude, pack, state_distance};
use crate::models::{EulerAngleBody, FreeBody, Gravity, PrecessionAngle, Shaft};
use crate::scene::{Scene, SceneKind};
use crate::{Limits, Method, SimError, Stats, Step, integrate};

pub mod derived;

/// A model of the motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Model {
    /// One degree of freedom about a fixed axis (§6).
    FixedAxis,
    /// Closed-form steady precession (§7, §9) or permanent rotation.
    SteadyPrecession,
    /// Closed form of the asymmetric torque-free body (Jacobi elliptic functions).
    Elliptic,
    /// Torque-free body: Euler's equations plus the angle turned about the
    /// invariable `H` (4 components), integrated; see [`PrecessionAngle`].
    PrecessionAngle,
    /// Euler's equations with a unit-quaternion attitude, integrated.
    RigidBody,
    /// Euler's equations with Eulerian angles, integrated.
    EulerAngles,
    /// The equations of motion of a derivation file, integrated in its
    /// coordinates (see [`crate::models::derived`]).
    Derived,
}

impl Model {
    /// Every model, least first.
    pub const ALL: [Model; 7] = [
        Model::FixedAxis,
        Model::SteadyPrecession,
        Model::Elliptic,
        Model::PrecessionAngle,
        Model::RigidBody,
        Model::EulerAngles,
        Model::Derived,
    ];

    /// Command-line name (its entry's).
    pub fn name(self) -> &'static str {
        self.entry().name
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Model {
    type Err = SimError;
    fn from_str(s: &str) -> Result<Self, SimError> {
        Model::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| SimError::UnknownName {
                what: "model",
                name: s.to_string(),
                expected: Model::ALL.map(Model::name).join(", "),
            })
    }
}

/// What the user asked for (all optional).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Request {
    /// `--model`.
    pub model: Option<Model>,
    /// `--method`.
    pub method: Option<Method>,
    /// `--dt` or `--tol`.
    pub step: Option<Step>,
    /// `--t-end` (else the scene's).
    pub t_end: Option<f64>,
    /// `--check`: also compare a closed-form run with a tight DOP853 run.
    pub check: bool,
}

/// Default tolerance of adaptive runs and of the heavy-top method choice.
pub const DEFAULT_TOL: f64 = 1e-8;
/// Default fixed step.
pub const DEFAULT_DT: f64 = 1e-3;
/// Tolerance of the DOP853 reference run where there is no closed form.
pub const REFERENCE_TOL: f64 = 1e-14;

/// The model and method a run will use, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Plan {
    /// Model name.
    #[serde(serialize_with = "ser_display")]
    pub model: Model,
    /// Method, if the model is integrated.
    #[serde(serialize_with = "ser_opt_display")]
    pub method: Option<Method>,
    /// Step or tolerance, if integrated.
    #[serde(serialize_with = "ser_step")]
    pub step: Option<Step>,
    /// End time.
    pub t_end: f64,
    /// Why this model (and method).
    pub reason: String,
    /// `--check` asked for.
    #[serde(skip)]
    pub check: bool,
    /// The error the run must reach, when the tolerance is to be fitted on
    /// the scene before the run (derived scenes without `--method`).
    #[serde(skip)]
    pub fit_error: Option<f64>,
}

fn ser_display<S: serde::Serializer, T: fmt::Display>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&v.to_string())
}

fn ser_opt_display<S: serde::Serializer, T: fmt::Display>(
    v: &Option<T>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match v {
        Some(v) => s.serialize_str(&v.to_string()),
        None => s.serialize_none(),
    }
}

fn ser_step<S: serde::Serializer>(v: &Option<Step>, s: S) -> Result<S::Ok, S::Error> {
    match v {
        Some(st) => s.serialize_str(&step_label(*st)),
        None => s.serialize_none(),
    }
}

/// `dt=…` or `tol=…`.
pub fn step_label(step: Step) -> String {
    match step {
        Step::Fixed(h) => format!("dt={h:e}"),
        Step::Tolerance(t) => format!("tol={t:e}"),
    }
}

fn not_applicable(model: Model, scene: &Scene, reason: &str) -> SimError {
    SimError::ModelNotApplicable {
        model: model.name().into(),
        scene: format!("{} ({})", scene.name, scene.file.display()),
        reason: reason.into(),
    }
}

/// Why only `derived` runs a derived scene (plan and run refuse alike).
const ONLY_DERIVED: &str = "a derived scene is its derivation's equations of motion, which no built-in closed form is known to cover; only `derived` runs them";
/// Why `derived` runs only a derived scene.
const NOT_DERIVED: &str =
    "only a scene of kind \"derived\" names a derivation's equations of motion";

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
    let make = |e: &ModelEntry, how: Option<Integration>, reason: String| Plan {
        model: e.model,
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
    let applies = |e: &ModelEntry| -> Result<bool, SimError> { Ok((e.refusal)(scene)?.is_none()) };
    if let Some(m) = req.model {
        // Whether a requested model applies is its registry entry's to say.
        check_applies(m, scene)?;
        let e = m.entry();
        let Some(default) = e
            .integration
            .filter(|_| e.integrated || req.method.is_some())
        else {
            return Ok(make(e, None, format!("{} as requested: {}", e.name, e.why)));
        };
        return Ok(match req.method {
            Some(method) => make(
                e,
                Some(with_method(method)),
                format!(
                    "{} integrated with {method} as requested: {}",
                    e.name, e.why
                ),
            ),
            None => {
                let how = default(scene, req, t_end, false)?;
                let reason = format!("{} as requested: {}; {}", e.name, e.why, how.detail);
                make(e, Some(how), reason)
            }
        });
    }
    if let Some(method) = req.method {
        for e in MODELS.iter() {
            if e.integration.is_some() && (e.takes)(method) && applies(e)? {
                return Ok(make(
                    e,
                    Some(with_method(method)),
                    format!(
                        "integration with {method} as requested, in the `{}` model: {}",
                        e.name, e.why
                    ),
                ));
            }
        }
        // Name the model that would integrate the scene, and why the
        // method is not one of its.
        for e in MODELS.iter() {
            if e.integration.is_some() && e.default_choice && applies(e)? {
                return Err(SimError::MethodNotApplicable {
                    method: method.name().into(),
                    model: e.name.into(),
                    reason: "it has no splitting into exactly solved sub-flows, which the \
                             splitting methods need"
                        .into(),
                });
            }
        }
        return Err(not_applicable(
            Model::RigidBody,
            scene,
            "no model of this scene integrates with the requested method",
        ));
    }
    // A closed form the scene is covered by wins.
    let mut refusals: Vec<String> = Vec::new();
    let mut untrusted: Option<String> = None;
    for e in MODELS.iter() {
        let Some(covers) = e.covers else { continue };
        match (e.refusal)(scene)? {
            Some(why) => refusals.push(why.to_string()),
            None => match covers(scene, t_end)? {
                Cover::Covered(reason) => return Ok(make(e, None, reason.to_string())),
                Cover::Untrusted(why) => untrusted = Some(why),
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
    for e in MODELS.iter() {
        let Some(default) = e.integration else {
            continue;
        };
        if !e.default_choice || !applies(e)? {
            continue;
        }
        let how = default(scene, req, t_end, true)?;
        let reason = format!(
            "{why_not}; nothing less will do, so the `{}` model is integrated: {}; {}",
            e.name, e.why, how.detail
        );
        return Ok(make(e, Some(how), reason));
    }
    Err(not_applicable(
        Model::RigidBody,
        scene,
        "no closed form covers this scene and no model integrates it",
    ))
}

/// What a closed form's entry says of a scene it applies to.
pub enum Cover {
    /// The closed form covers the scene: the reason it is chosen.
    Covered(&'static str),
    /// It applies but cannot be trusted on this scene (why).
    Untrusted(String),
}

/// How an integrated model runs by default: method, step, the error to fit
/// the tolerance to (derived scenes) and what was measured to choose them.
pub struct Integration {
    /// The method.
    pub method: Method,
    /// Its step or tolerance.
    pub step: Step,
    /// The error the run must reach, when the tolerance is fitted on the
    /// scene before the run.
    pub fit_error: Option<f64>,
    /// How the method and step were chosen.
    pub detail: String,
}

/// A closed form's test of a scene (and end time) it applies to.
type CoverFn = fn(&Scene, f64) -> Result<Cover, SimError>;

/// An entry's default integration: the scene, the request, the end time,
/// and whether the model was chosen (not requested).
type IntegrationFn = fn(&Scene, &Request, f64, bool) -> Result<Integration, SimError>;

/// The requested step or tolerance, else the defaults.
fn requested_step(req: &Request, method: Method) -> Step {
    req.step.unwrap_or(if method.is_adaptive() {
        Step::Tolerance(DEFAULT_TOL)
    } else {
        Step::Fixed(DEFAULT_DT)
    })
}

/// DOP853 at the requested step or tolerance.
fn integrate_dop853(_: &Scene, req: &Request, _: f64, _: bool) -> Result<Integration, SimError> {
    let step = requested_step(req, Method::Dop853);
    Ok(Integration {
        method: Method::Dop853,
        step,
        fit_error: None,
        detail: format!("dop853 at {}", step_label(step)),
    })
}

/// The precession-angle state chosen over a closed form that is not
/// trusted: DOP853 at tol 1e-13.
fn integrate_precession_angle(
    scene: &Scene,
    req: &Request,
    t_end: f64,
    chosen: bool,
) -> Result<Integration, SimError> {
    if !chosen {
        return integrate_dop853(scene, req, t_end, chosen);
    }
    let step = Step::Tolerance(1e-13);
    Ok(Integration {
        method: Method::Dop853,
        step,
        fit_error: None,
        detail: format!("dop853 at {}", step_label(step)),
    })
}

/// A heavy top: method and step measured on the scene ([`pilot_choice`]);
/// a free body: DOP853.
fn integrate_rigid_body(
    scene: &Scene,
    req: &Request,
    t_end: f64,
    chosen: bool,
) -> Result<Integration, SimError> {
    if !matches!(scene.kind, SceneKind::HeavyTop { .. }) {
        return integrate_dop853(scene, req, t_end, chosen);
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

/// A derived scene: DOP853, its tolerance fitted on the scene to the
/// requested error unless a fixed step is asked for (run/derived.rs).
fn integrate_derived(
    scene: &Scene,
    req: &Request,
    t_end: f64,
    chosen: bool,
) -> Result<Integration, SimError> {
    let target = match req.step {
        Some(Step::Fixed(_)) => return integrate_dop853(scene, req, t_end, chosen),
        Some(Step::Tolerance(t)) => t,
        None => DEFAULT_TOL,
    };
    Ok(Integration {
        method: Method::Dop853,
        step: Step::Tolerance(target),
        fit_error: Some(target),
        detail: "dop853, its tolerance fitted to the requested error by two pilot runs".to_string(),
    })
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

/// The error a closed form must stay within, per unit of phase `|ω| T`
/// (the bound the exact torque-free solution is tested to).
pub const CLOSED_FORM_BOUND: f64 = 1e-13;
/// Tolerance of the DOP853 run that `--check` compares a closed form with.
pub const CHECK_TOL: f64 = 1e-13;

/// The largest rate of the scene's motion, `|ω₀|` (`|ω|` of a shaft).
fn rate_scale(scene: &Scene) -> f64 {
    match &scene.kind {
        SceneKind::Free { w0, .. } | SceneKind::HeavyTop { w0, .. } => w0.norm(),
        SceneKind::FixedAxis { y0, .. } => y0[1].abs(),
        SceneKind::Derived(ds) => {
            let n = ds.y0.len() / 2;
            ds.y0[n..].iter().fold(0.0, |m: f64, v| m.max(v.abs()))
        }
    }
}

/// Refuses an end time that is negative, not finite, or so long that the
/// phase `|ω| T` exceeds 2^52 (f64 time no longer resolves one turn).
pub fn check_end_time(scene: &Scene, t_end: f64) -> Result<(), SimError> {
    if !(t_end.is_finite() && t_end >= 0.0) {
        return Err(SimError::BadEndTime(t_end));
    }
    let phase = rate_scale(scene) * t_end;
    if phase.is_nan() || phase > 2f64.powi(52) {
        return Err(SimError::EndTimeTooLong { t_end, phase });
    }
    Ok(())
}

/// An estimate of the error at `t_end` of a closed form `exact` of the
/// system `sys` from `y0`, not assuming the closed form is right: its
/// distance from `y0` at t = 0, plus its *defect* — starting from
/// `exact(t_k)` at `samples` points along the run, the equations
/// (`sys`: Euler's equations and the attitude kinematics for a body) are
/// integrated by DOP853 in fixed steps of `1/(64|ω|)` over `Δ` (16 time
/// scales `1/|ω|`, at most `T/samples`) and compared with `exact(t_k + Δ)`;
/// the largest defect, plus the largest defect rate times T. The estimate
/// includes DOP853's own round-off over Δ: it is an upper estimate at
/// round-off level, not a proof.
pub fn closed_form_estimate<const N: usize, S: crate::System<N>>(
    sys: &S,
    exact: &dyn Fn(f64) -> [f64; N],
    y0: &[f64; N],
    t_end: f64,
    time_scale: f64,
    samples: usize,
    dist: fn(&[f64; N], &[f64; N]) -> f64,
) -> Result<f64, SimError> {
    let start = exact(0.0);
    // Fixed DOP853 steps of 1/64 of the time scale: truncation (1/64)^8 per
    // step, far below round-off, and no tolerance floor. Δ spans up to 16
    // time scales so that the evaluation's own jitter (ε u in the elliptic
    // argument) is not mistaken for a drift.
    let delta_max = (t_end / samples as f64).min(16.0 * time_scale);
    let step = Step::Fixed(delta_max.min(time_scale) / 64.0);
    let initial = dist(&start, y0);
    if t_end <= 0.0 || samples == 0 {
        return Ok(initial);
    }
    let delta = delta_max;
    let mut rate: f64 = 0.0;
    let mut jitter: f64 = 0.0;
    for k in 0..samples {
        let t = if samples == 1 {
            0.0
        } else {
            (t_end - delta) * k as f64 / (samples - 1) as f64
        };
        let ya = exact(t);
        if ya.iter().any(|v| !v.is_finite()) {
            return Ok(f64::INFINITY);
        }
        let (yi, _) = integrate(
            sys,
            Method::Dop853,
            step,
            t,
            ya,
            t + delta,
            Limits::default(),
            |_, _| Ok(()),
        )?;
        let d = dist(&yi, &exact(t + delta));
        jitter = jitter.max(d);
        rate = rate.max(d / delta);
    }
    Ok(initial + jitter + rate * t_end)
}

fn euclid<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The defect estimate of a body scene's closed form (free or steady top).
fn body_closed_form_estimate(scene: &Scene, t_end: f64, samples: usize) -> Result<f64, SimError> {
    let (body, y0) = free_body(scene).expect("free or heavy top");
    let scale = rate_scale(scene);
    let time_scale = if scale > 0.0 { 1.0 / scale } else { t_end };
    match &scene.kind {
        SceneKind::Free { moments, q0, w0 } => {
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
        SceneKind::HeavyTop {
            steady: Some(top), ..
        } => closed_form_estimate(
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
fn closed_form_meets_bound(scene: &Scene, t_end: f64) -> Result<bool, SimError> {
    let est = body_closed_form_estimate(scene, t_end, 4)?;
    let w = rate_scale(scene);
    // Angle per unit of phase, and |Δω| relative to |ω|.
    let bound = CLOSED_FORM_BOUND * (w * t_end).max(1.0) * w.max(1.0);
    Ok(est.is_finite() && est <= bound)
}

/// Relative change of an invariant between start and end.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Drift {
    /// Which invariant (`energy`, `|H|`, `H_Z`, or a derived step's name).
    pub name: String,
    /// `|I(T) − I(0)| / |I(0)|`.
    pub relative: f64,
}

/// §7 check of a simulated steady precession.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PrecessionCheck {
    /// φ̇ from §7's relation.
    pub predicted: f64,
    /// φ̇ measured from the simulated attitude over [0, T].
    pub simulated: f64,
    /// `|simulated − predicted| / |predicted|`.
    pub relative_difference: f64,
    /// Largest |θ(T) − θ(0)|.
    pub nutation_change: f64,
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
}

/// The attitude and angular velocity of a frame at T.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameState {
    /// The frame's name in the derivation.
    pub frame: String,
    /// Rotation matrix: columns are the frame's axes in the fixed frame N.
    pub attitude: [[f64; 3]; 3],
    /// Angular velocity relative to N, in the frame's own axes.
    pub angular_velocity: [f64; 3],
}

/// Comparison of a closed-form run with an independent integration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// What it was compared with.
    pub against: String,
    /// Distance at T.
    pub difference: f64,
}

/// Output options of a run.
pub struct Output<'a> {
    /// Stream every accepted step as a CSV row to this writer.
    pub stream: Option<&'a mut dyn Write>,
    /// Keep the trajectory in the report.
    pub store: bool,
    /// Budget in bytes for the stored trajectory.
    pub memory_budget: u64,
    /// Called with the current time after every step.
    pub progress: Option<&'a mut dyn FnMut(f64)>,
}

impl Default for Output<'_> {
    fn default() -> Self {
        Output {
            stream: None,
            store: false,
            memory_budget: 64 << 20,
            progress: None,
        }
    }
}

/// Bytes one stored row of `len` numbers takes (values and vector header).
fn row_bytes(len: usize) -> u64 {
    (len * 8 + 24) as u64
}

/// Records streamed/stored rows and progress inside the integrator's observer.
struct Recorder<'a, 'b> {
    out: &'b mut Output<'a>,
    rows: Vec<Vec<f64>>,
    bytes: u64,
}

impl Recorder<'_, '_> {
    fn record(&mut self, row: Vec<f64>) -> Result<(), SimError> {
        if let Some(p) = self.out.progress.as_mut() {
            p(row[0]);
        }
        if let Some(w) = self.out.stream.as_mut() {
            // `+ 0.0` turns −0 into 0: a streamed row never reads `-0e0`.
            let line: Vec<String> = row.iter().map(|v| format!("{:e}", v + 0.0)).collect();
            writeln!(w, "{}", line.join(",")).map_err(SimError::Output)?;
        }
        if self.out.store {
            self.bytes += row_bytes(row.len());
            if self.bytes > self.out.memory_budget {
                return Err(SimError::MemoryBudget {
                    needed: self.bytes,
                    budget: self.out.memory_budget,
                });
            }
            self.rows.push(row);
        }
        Ok(())
    }

    fn active(&self) -> bool {
        self.out.stream.is_some() || self.out.store || self.out.progress.is_some()
    }
}

/// Checks the budget of stored output before a fixed-step run.
fn check_budget(out: &Output<'_>, plan: &Plan, row_len: usize) -> Result<(), SimError> {
    if !out.store {
        return Ok(());
    }
    let rows = match plan.step {
        Some(Step::Fixed(h)) => crate::fixed_step_count(plan.t_end, h) + 1,
        _ => 1,
    };
    let needed = rows.saturating_mul(row_bytes(row_len));
    if needed > out.memory_budget {
        return Err(SimError::MemoryBudget {
            needed,
            budget: out.memory_budget,
        });
    }
    Ok(())
}

/// CSV header of the streamed rows for a scene.
pub fn stream_header(scene: &Scene, model: Model) -> String {
    match (&scene.kind, model) {
        (SceneKind::Derived(ds), _) => format!("t,{}", ds.state_names().join(",")),
        (SceneKind::FixedAxis { .. }, _) => "t,angle,omega,A_x,A_y,B_x,B_y".into(),
        (_, Model::EulerAngles) => "t,phi,theta,psi,omega_1,omega_2,omega_3".into(),
        _ => "t,q_w,q_x,q_y,q_z,omega_1,omega_2,omega_3".into(),
    }
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

fn free_body(scene: &Scene) -> Option<(FreeBody, [f64; 7])> {
    match &scene.kind {
        SceneKind::Free { moments, q0, w0 } => Some((
            FreeBody {
                moments: moments.get(),
                gravity: None,
            },
            pack(q0, w0),
        )),
        SceneKind::HeavyTop {
            moments,
            weight_arm,
            q0,
            w0,
            ..
        } => Some((
            FreeBody {
                moments: moments.get(),
                gravity: Some(Gravity {
                    weight_arm: *weight_arm,
                }),
            },
            pack(q0, w0),
        )),
        SceneKind::FixedAxis { .. } | SceneKind::Derived(_) => None,
    }
}

/// The exact or reference state at `t` of a free body or heavy top, and its name.
pub fn reference_state(scene: &Scene, t: f64) -> Result<([f64; 7], String), SimError> {
    match &scene.kind {
        SceneKind::Free { moments, q0, w0 } => {
            let exact = TorqueFree::new(moments.get(), *q0, *w0)?;
            Ok((exact.state(t), format!("closed form: {}", exact.form())))
        }
        SceneKind::HeavyTop {
            steady: Some(top), ..
        } => Ok((top.state(t), "closed form: steady precession (§7)".into())),
        SceneKind::HeavyTop { .. } => {
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
            )?;
            Ok((y, format!("dop853 at tol={REFERENCE_TOL:e}")))
        }
        SceneKind::FixedAxis { .. } => Err(SimError::ModelNotApplicable {
            model: Model::RigidBody.name().into(),
            scene: scene.name.clone(),
            reason: "a shaft has a one-degree-of-freedom state".into(),
        }),
        SceneKind::Derived(_) => Err(SimError::ModelNotApplicable {
            model: Model::RigidBody.name().into(),
            scene: scene.name.clone(),
            reason: "a derived scene's state is its derivation's coordinates and rates".into(),
        }),
    }
}

fn free_drifts(body: &FreeBody, y0: &[f64; 7], y: &[f64; 7]) -> Vec<Drift> {
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
    let (phi, theta, _) = crate::models::euler_angles::angles_from_quaternion(&attitude(y));
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

/// One model of the motion: what it applies to, why it is chosen, and how
/// it runs. [`plan`] asks the entry whether a requested model applies and
/// [`run`] runs the planned model through it; adding a model is adding an
/// entry to [`MODELS`] (the `derived` one is `run/derived.rs`).
pub struct ModelEntry {
    /// The model.
    pub model: Model,
    /// Its command-line name (`--model`).
    pub name: &'static str,
    /// The scenes it applies to.
    pub applies_to: &'static str,
    /// Why it is the model chosen there (the rule of the module docs).
    pub why: &'static str,
    /// Whether it integrates equations of motion (else a closed form;
    /// `fixed-axis` has both and integrates when a method is given).
    pub integrated: bool,
    /// Why it does not apply to a scene; `None` when it does.
    refusal: fn(&Scene) -> Result<Option<&'static str>, SimError>,
    /// A closed form's test of a scene it applies to: whether it covers
    /// it (and the reason it is chosen) or cannot be trusted there.
    covers: Option<CoverFn>,
    /// How the model integrates when no method is given; `None` for the
    /// closed forms that never integrate.
    integration: Option<IntegrationFn>,
    /// The methods with which a request for a method alone takes this
    /// model.
    takes: fn(Method) -> bool,
    /// Whether the model is chosen to integrate a scene no closed form
    /// covers (the comparison model `euler-angles` is not).
    default_choice: bool,
    /// Runs a planned scene, filling the report.
    run: RunFn,
    /// One run of the work-precision sweep (`hdot work-precision`) on the
    /// integrated system of the scenes this model applies to; `None` for
    /// models the sweep does not measure (closed forms, and the
    /// comparison models of the same scenes).
    sweep: Option<Sweep>,
}

/// How the work-precision sweep measures a model.
#[derive(Clone, Copy)]
struct Sweep {
    /// One run.
    run: SweepFn,
    /// What its drift columns measure on a scene.
    columns: fn(&Scene) -> DriftColumns,
}

/// How a model runs: the scene, its plan, the recorder of streamed or
/// stored rows, and the report to fill.
type RunFn = fn(&Scene, &Plan, &mut Recorder<'_, '_>, &mut Report) -> Result<(), SimError>;

/// One sweep run: the scene, the row to fill (its method and step set), the
/// end time and the least wall time spent repeating the run to time it.
type SweepFn = fn(&Scene, &mut Row, f64, f64) -> Result<(), SimError>;

/// Every model, in the order of [`Model::ALL`].
pub const MODELS: [ModelEntry; 7] = [
    ModelEntry {
        model: Model::FixedAxis,
        name: "fixed-axis",
        applies_to: "a shaft in two bearings (kind fixed-axis)",
        why: "one degree of freedom, linear motor law: a closed form, or integrated with --method; bearing reactions from §6",
        integrated: false,
        refusal: refuse_fixed_axis,
        covers: Some(cover_fixed_axis),
        integration: Some(integrate_dop853),
        takes: any_method,
        default_choice: true,
        run: run_fixed_axis,
        sweep: Some(Sweep {
            run: sweep_fixed_axis,
            columns: columns_fixed_axis,
        }),
    },
    ModelEntry {
        model: Model::SteadyPrecession,
        name: "steady-precession",
        applies_to: "a free axisymmetric body or a permanent rotation; a heavy top started in steady precession",
        why: "closed form (§7, §9): θ, φ̇, ψ̇ constant, no integration",
        integrated: false,
        refusal: refuse_steady_precession,
        covers: Some(cover_steady_precession),
        integration: None,
        takes: no_method,
        default_choice: false,
        run: run_closed_form,
        sweep: None,
    },
    ModelEntry {
        model: Model::Elliptic,
        name: "elliptic",
        applies_to: "a free body with three distinct moments",
        why: "closed form through Jacobi elliptic functions, no integration",
        integrated: false,
        refusal: refuse_elliptic,
        covers: Some(cover_elliptic),
        integration: None,
        takes: no_method,
        default_choice: false,
        run: run_closed_form,
        sweep: None,
    },
    ModelEntry {
        model: Model::PrecessionAngle,
        name: "precession-angle",
        applies_to: "a free body that turns (H ≠ 0)",
        why: "torque-free, H is fixed in space: the attitude is fixed by body H and one angle φ about H, so [ω, φ] is integrated (4 components, ω projected back onto the conserved energy and |H| after every step) instead of the quaternion form",
        integrated: true,
        refusal: refuse_precession_angle,
        covers: None,
        integration: Some(integrate_precession_angle),
        takes: not_a_splitting,
        default_choice: true,
        run: run_precession_angle,
        sweep: None,
    },
    ModelEntry {
        model: Model::RigidBody,
        name: "rigid-body",
        applies_to: "a free body or a heavy top",
        why: "Euler's equations with a unit-quaternion attitude (no singular attitude)",
        integrated: true,
        refusal: refuse_body_model,
        covers: None,
        integration: Some(integrate_rigid_body),
        takes: any_method,
        default_choice: true,
        run: run_rigid_body,
        sweep: Some(Sweep {
            run: sweep_rigid_body,
            columns: columns_rigid_body,
        }),
    },
    ModelEntry {
        model: Model::EulerAngles,
        name: "euler-angles",
        applies_to: "a free body or a heavy top (away from θ = 0, π)",
        why: "Euler's equations with Eulerian angles, for comparison: singular at sin θ = 0",
        integrated: true,
        refusal: refuse_euler_angles,
        covers: None,
        integration: Some(integrate_dop853),
        takes: no_method,
        default_choice: false,
        run: run_euler_angles,
        sweep: None,
    },
    ModelEntry {
        model: Model::Derived,
        name: "derived",
        applies_to: "a scene of kind derived (a derivation's equations of motion)",
        why: "exactly the equations the file derived, integrated in its coordinates",
        integrated: true,
        refusal: refuse_derived,
        covers: None,
        integration: Some(integrate_derived),
        takes: not_a_splitting,
        default_choice: true,
        run: derived::run,
        sweep: Some(Sweep {
            run: derived::sweep_one,
            columns: derived::drift_columns,
        }),
    },
];

fn any_method(_: Method) -> bool {
    true
}

fn no_method(_: Method) -> bool {
    false
}

/// The splittings need the quaternion body's exact sub-flows.
fn not_a_splitting(m: Method) -> bool {
    !matches!(m, Method::Split2 | Method::Split4)
}

fn cover_fixed_axis(_: &Scene, _: f64) -> Result<Cover, SimError> {
    Ok(Cover::Covered(
        "the bearings fix the axis: one degree of freedom, I_z α = T_0 (1 − ω/ω_0) − c ω, \
         linear in ω, so its closed form needs no integration; bearing reactions from §6",
    ))
}

/// Why a torque-free closed form is not trusted on a scene.
fn untrusted_closed_form() -> Cover {
    Cover::Untrusted(format!(
        "torque-free, but the closed form's defect estimate on this scene exceeds its bound \
         ({CLOSED_FORM_BOUND:e} per unit of |ω| T) or is not finite, so it is not trusted"
    ))
}

fn cover_steady_precession(scene: &Scene, t_end: f64) -> Result<Cover, SimError> {
    Ok(match &scene.kind {
        SceneKind::Free { .. } if !closed_form_meets_bound(scene, t_end)? => {
            untrusted_closed_form()
        }
        SceneKind::Free { moments, q0, w0 } => match TorqueFree::new(moments.get(), *q0, *w0)? {
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

fn cover_elliptic(scene: &Scene, t_end: f64) -> Result<Cover, SimError> {
    Ok(if closed_form_meets_bound(scene, t_end)? {
        Cover::Covered(
            "torque-free asymmetric body: exact solution by Jacobi elliptic functions, no integration",
        )
    } else {
        untrusted_closed_form()
    })
}

impl Model {
    /// The model's entry in [`MODELS`].
    pub fn entry(self) -> &'static ModelEntry {
        MODELS
            .iter()
            .find(|e| e.model == self)
            .expect("every model has an entry")
    }
}

/// Refuses `model` on `scene` when its entry says it does not apply.
fn check_applies(model: Model, scene: &Scene) -> Result<(), SimError> {
    match (model.entry().refusal)(scene)? {
        Some(why) => Err(not_applicable(model, scene, why)),
        None => Ok(()),
    }
}

/// Why a model of a rigid body (free or heavy top) does not apply.
fn refuse_non_body(scene: &Scene) -> Option<&'static str> {
    match &scene.kind {
        SceneKind::Derived(_) => Some(ONLY_DERIVED),
        SceneKind::FixedAxis { .. } => Some(
            "the bearings constrain the body to one degree of freedom; only `fixed-axis` describes it",
        ),
        SceneKind::Free { .. } | SceneKind::HeavyTop { .. } => None,
    }
}

fn refuse_body_model(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    Ok(refuse_non_body(scene))
}

fn refuse_euler_angles(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    if let Some(why) = refuse_non_body(scene) {
        return Ok(Some(why));
    }
    let (_, y0) = free_body(scene).expect("a free body or heavy top");
    let (_, theta, _) = crate::models::euler_angles::angles_from_quaternion(&attitude(&y0));
    Ok(
        (theta.sin() < crate::models::euler_angles::SIN_THETA_MIN).then_some(
            "the initial attitude has nutation θ = 0 or π, where Eulerian angles are singular; \
         use rigid-body (quaternion attitude)",
        ),
    )
}

fn refuse_derived(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    Ok((!matches!(scene.kind, SceneKind::Derived(_))).then_some(NOT_DERIVED))
}

fn refuse_fixed_axis(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    Ok(match &scene.kind {
        SceneKind::FixedAxis { .. } => None,
        SceneKind::Derived(_) => Some(ONLY_DERIVED),
        SceneKind::Free { .. } => Some(
            "the body is free: no bearing fixes its axis (a spin about a principal axis is \
             found by the closed form as a permanent rotation)",
        ),
        SceneKind::HeavyTop { .. } => Some(HEAVY_TOP_DOF),
    })
}

/// Why a closed form of the free body is not the heavy top's.
const HEAVY_TOP_DOF: &str =
    "a heavy top on a fixed point has three degrees of freedom and a gravity torque";

fn refuse_steady_precession(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    Ok(match &scene.kind {
        SceneKind::Free { moments, q0, w0 } => match TorqueFree::new(moments.get(), *q0, *w0)? {
            TorqueFree::Elliptic(_) => Some(
                "the body is not axisymmetric (three distinct moments): its motion is not a steady precession",
            ),
            _ => None,
        },
        SceneKind::HeavyTop { steady: None, .. } => {
            Some("the initial state does not satisfy §7's steady-precession relation (or θ̇ ≠ 0)")
        }
        SceneKind::HeavyTop { .. } => None,
        _ => refuse_non_body(scene),
    })
}

fn refuse_elliptic(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    Ok(match &scene.kind {
        SceneKind::Free { moments, q0, w0 } => match TorqueFree::new(moments.get(), *q0, *w0)? {
            TorqueFree::Elliptic(_) => None,
            _ => Some(
                "the elliptic form needs three distinct moments and a motion that is not a permanent rotation; \
                     use steady-precession",
            ),
        },
        SceneKind::HeavyTop { .. } => Some(HEAVY_TOP_DOF),
        _ => refuse_non_body(scene),
    })
}

fn refuse_precession_angle(scene: &Scene) -> Result<Option<&'static str>, SimError> {
    Ok(match &scene.kind {
        SceneKind::Free { w0, .. } if w0.norm() == 0.0 => {
            Some("the body is at rest: H = 0 defines no invariable axis")
        }
        SceneKind::Free { .. } => None,
        SceneKind::HeavyTop { .. } => Some(
            "gravity turns H in space, so the attitude is not fixed by body H and one angle about it",
        ),
        _ => refuse_non_body(scene),
    })
}

/// Integrates `sys` from `y0` over `[0, t_end]`, recording the row
/// `row(t, y)` of every accepted step when output is asked for: the one
/// integrate-and-record block of every integrated model. Returns the state
/// at `t_end`, the counts and the wall time.
fn integrate_recorded<const N: usize, S: crate::System<N>>(
    sys: &S,
    (method, step): (Method, Step),
    y0: [f64; N],
    t_end: f64,
    rec: &mut Recorder<'_, '_>,
    row: impl Fn(f64, &[f64; N]) -> Vec<f64>,
) -> Result<([f64; N], Stats, f64), SimError> {
    let active = rec.active();
    let start = Instant::now();
    let (y, stats) = integrate(
        sys,
        method,
        step,
        0.0,
        y0,
        t_end,
        Limits::default(),
        |t, y| {
            if active {
                rec.record(row(t, y))?;
            }
            Ok(())
        },
    )?;
    Ok((y, stats, start.elapsed().as_secs_f64()))
}

/// A row `[t, y…]`.
fn time_and_state<const N: usize>(t: f64, y: &[f64; N]) -> Vec<f64> {
    let mut row = Vec::with_capacity(N + 1);
    row.push(t);
    row.extend_from_slice(y);
    row
}

/// Runs a scene as planned.
pub fn run(scene: &Scene, plan: &Plan, out: &mut Output<'_>) -> Result<Report, SimError> {
    check_applies(plan.model, scene)?;
    let mut report = Report {
        scene: scene.name.clone(),
        kind: scene.kind.name(),
        plan: plan.clone(),
        reference: String::new(),
        error: None,
        error_basis: String::new(),
        check: None,
        drifts: vec![],
        evaluations: 0,
        steps: 0,
        rejected: 0,
        wall_s: 0.0,
        final_state: vec![],
        precession: None,
        reactions: None,
        trajectory: None,
        state_names: vec![],
        frame: None,
    };
    let row_len = match &scene.kind {
        SceneKind::FixedAxis { .. } => 7,
        SceneKind::Derived(ds) => ds.y0.len() + 1,
        _ => 8,
    };
    check_budget(out, plan, row_len)?;
    let mut rec = Recorder {
        out,
        rows: vec![],
        bytes: 0,
    };
    (plan.model.entry().run)(scene, plan, &mut rec, &mut report)?;
    if rec.out.store {
        report.trajectory = Some(std::mem::take(&mut rec.rows));
    }
    refuse_non_finite(&report)?;
    Ok(report)
}

/// The error of running `model` on a scene its entry should have refused.
fn wrong_kind(model: Model, scene: &Scene) -> SimError {
    not_applicable(
        model,
        scene,
        "the scene is not of a kind this model describes",
    )
}

fn run_fixed_axis(
    scene: &Scene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
    report: &mut Report,
) -> Result<(), SimError> {
    let SceneKind::FixedAxis { shaft, y0 } = &scene.kind else {
        return Err(wrong_kind(plan.model, scene));
    };
    let t_end = plan.t_end;
    let row = |t: f64, y: &[f64; 2]| {
        let mut row = vec![t, y[0], y[1]];
        row.extend_from_slice(&shaft_reactions(shaft, y[1])[..4]);
        row
    };
    let (y, stats) = match (plan.method, plan.step) {
        (Some(method), Some(step)) => {
            let (y, stats, wall) = integrate_recorded(shaft, (method, step), *y0, t_end, rec, row)?;
            report.wall_s = wall;
            (y, stats)
        }
        _ => {
            let start = Instant::now();
            let y = shaft.exact(y0, t_end);
            report.wall_s = start.elapsed().as_secs_f64();
            if rec.active() {
                rec.record(row(t_end, &y))?;
            }
            (y, Stats::default())
        }
    };
    let exact = shaft.exact(y0, t_end);
    report.reference = "closed form of the one-degree-of-freedom equation".into();
    if plan.method.is_some() {
        report.error = Some(((y[0] - exact[0]).powi(2) + (y[1] - exact[1]).powi(2)).sqrt());
        report.error_basis = "measured against the closed form".into();
    } else {
        let w = y0[1].abs();
        let time_scale = if w > 0.0 { 1.0 / w } else { t_end };
        report.error = Some(closed_form_estimate(
            shaft,
            &|t| shaft.exact(y0, t),
            y0,
            t_end,
            time_scale,
            ESTIMATE_SAMPLES,
            euclid,
        )?);
        report.error_basis = ESTIMATE_BASIS.into();
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
            report.check = Some(Check {
                against: format!("dop853 at tol={CHECK_TOL:e}"),
                difference: euclid(&y, &yc),
            });
        }
    }
    report.reactions = Some(shaft_reactions(shaft, y[1]));
    report.final_state = y.to_vec();
    set_stats(report, stats);
    Ok(())
}

fn run_closed_form(
    scene: &Scene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
    report: &mut Report,
) -> Result<(), SimError> {
    let (body, y0) = free_body(scene).ok_or_else(|| wrong_kind(plan.model, scene))?;
    let t_end = plan.t_end;
    let start = Instant::now();
    let (y, name) = reference_state(scene, t_end)?;
    report.wall_s = start.elapsed().as_secs_f64();
    if rec.active() {
        rec.record(time_and_state(t_end, &y))?;
    }
    report.reference = format!("none: this run is the {name}");
    report.error = Some(body_closed_form_estimate(scene, t_end, ESTIMATE_SAMPLES)?);
    report.error_basis = ESTIMATE_BASIS.into();
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
        report.check = Some(Check {
            against: format!("dop853 at tol={CHECK_TOL:e}"),
            difference: state_distance(&y, &yc),
        });
    }
    report.drifts = free_drifts(&body, &y0, &y);
    report.final_state = y.to_vec();
    Ok(())
}

fn run_precession_angle(
    scene: &Scene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
    report: &mut Report,
) -> Result<(), SimError> {
    let SceneKind::Free { moments, q0, w0 } = &scene.kind else {
        return Err(wrong_kind(plan.model, scene));
    };
    let (body, y0) = free_body(scene).ok_or_else(|| wrong_kind(plan.model, scene))?;
    let (sys, z0) = PrecessionAngle::new(moments.get(), q0, w0).ok_or_else(|| {
        not_applicable(
            Model::PrecessionAngle,
            scene,
            "the body is at rest: H = 0 defines no invariable axis",
        )
    })?;
    let (z, stats, wall) =
        integrate_recorded(&sys, method_step(plan)?, z0, plan.t_end, rec, |t, z| {
            time_and_state(t, &sys.full_state(z))
        })?;
    report.wall_s = wall;
    let y = sys.full_state(&z);
    finish_free(scene, &body, &y0, &y, plan.t_end, report)?;
    set_stats(report, stats);
    Ok(())
}

fn run_rigid_body(
    scene: &Scene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
    report: &mut Report,
) -> Result<(), SimError> {
    let (body, y0) = free_body(scene).ok_or_else(|| wrong_kind(plan.model, scene))?;
    let (y, stats, wall) = integrate_recorded(
        &body,
        method_step(plan)?,
        y0,
        plan.t_end,
        rec,
        time_and_state,
    )?;
    report.wall_s = wall;
    finish_free(scene, &body, &y0, &y, plan.t_end, report)?;
    set_stats(report, stats);
    Ok(())
}

fn run_euler_angles(
    scene: &Scene,
    plan: &Plan,
    rec: &mut Recorder<'_, '_>,
    report: &mut Report,
) -> Result<(), SimError> {
    let (body, y0) = free_body(scene).ok_or_else(|| wrong_kind(plan.model, scene))?;
    let (phi, theta, psi) = crate::models::euler_angles::angles_from_quaternion(&attitude(&y0));
    let e0 = [phi, theta, psi, y0[4], y0[5], y0[6]];
    let sys = EulerAngleBody {
        moments: body.moments,
        weight_arm: body.gravity.map_or(0.0, |g| g.weight_arm),
    };
    let (e, stats, wall) = integrate_recorded(
        &sys,
        method_step(plan)?,
        e0,
        plan.t_end,
        rec,
        time_and_state,
    )?;
    report.wall_s = wall;
    let y = to_quaternion_state(&e);
    finish_free(scene, &body, &y0, &y, plan.t_end, report)?;
    set_stats(report, stats);
    Ok(())
}

/// Number of points along a closed-form run where its defect is sampled.
const ESTIMATE_SAMPLES: usize = 16;
const ESTIMATE_BASIS: &str = "estimated: distance from the initial state plus the defect of the \
     equations of motion (and attitude kinematics) sampled at 16 points along the run, times T";

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
    Ok(())
}

fn method_step(plan: &Plan) -> Result<(Method, Step), SimError> {
    match (plan.method, plan.step) {
        (Some(m), Some(s)) => Ok((m, s)),
        _ => Err(SimError::MethodNotApplicable {
            method: "none".into(),
            model: plan.model.name().into(),
            reason: "an integrated model needs a method and a step".into(),
        }),
    }
}

fn set_stats(report: &mut Report, stats: Stats) {
    report.evaluations = stats.evaluations;
    report.steps = stats.steps;
    report.rejected = stats.rejected;
}

fn finish_free(
    scene: &Scene,
    body: &FreeBody,
    y0: &[f64; 7],
    y: &[f64; 7],
    t_end: f64,
    report: &mut Report,
) -> Result<(), SimError> {
    let (reference, name) = reference_state(scene, t_end)?;
    report.error_basis = format!("measured against the reference ({name})");
    report.reference = name;
    report.error = Some(state_distance(y, &reference));
    report.drifts = free_drifts(body, y0, y);
    report.final_state = y.to_vec();
    if let SceneKind::HeavyTop {
        steady: Some(top), ..
    } = &scene.kind
    {
        report.precession = Some(precession_check(top, y, t_end));
    }
    Ok(())
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.plan;
        writeln!(f, "scene:       {} ({})", self.scene, self.kind)?;
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
        for d in &self.drifts {
            writeln!(
                f,
                "drift {:<6} {:.3e} (relative)",
                format!("{}:", d.name),
                d.relative
            )?;
        }
        writeln!(
            f,
            "evaluations: {} ({} steps, {} rejected)",
            self.evaluations, self.steps, self.rejected
        )?;
        writeln!(f, "wall time:   {:.3e} s", self.wall_s)?;
        if let Some(pc) = &self.precession {
            writeln!(
                f,
                "precession:  simulated φ̇ = {}, §7 predicts {} (relative difference {:.2e}, |Δθ| = {:.2e})",
                fixed(pc.simulated, 9),
                fixed(pc.predicted, 9),
                pc.relative_difference,
                pc.nutation_change
            )?;
        }
        if let Some(r) = &self.reactions {
            let r: Vec<String> = r.iter().map(|v| fixed(*v, 6)).collect();
            writeln!(
                f,
                "reactions:   A = ({}, {}), B = ({}, {}) N; ΣM_O = ({}, {}, {}) N·m",
                r[0], r[1], r[2], r[3], r[4], r[5], r[6]
            )?;
        }
        if let Some(fs) = &self.frame {
            let row = |v: &[f64]| {
                v.iter()
                    .map(|x| fixed(*x, 9))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let r = &fs.attitude;
            writeln!(
                f,
                "frame {}:     attitude [[{}], [{}], [{}]], ω = ({}) rad/s",
                fs.frame,
                row(&r[0]),
                row(&r[1]),
                row(&r[2]),
                row(&fs.angular_velocity)
            )?;
        }
        let state: Vec<String> = if self.state_names.len() == self.final_state.len() {
            self.state_names
                .iter()
                .zip(&self.final_state)
                .map(|(n, v)| format!("{n} = {}", fixed(*v, 12)))
                .collect()
        } else {
            self.final_state.iter().map(|v| fixed(*v, 12)).collect()
        };
        writeln!(f, "state at T:  [{}]", state.join(", "))
    }
}

/// `v` with `decimals` decimals, and no sign when it rounds to zero
/// (`-1e-17` and `-0.0` print as `0.000000000`, never `-0.000000000`):
/// the one formatter of the report's fixed-point numbers.
pub fn fixed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => s,
    }
}

// ---------------------------------------------------------------- work-precision

/// One run of the work-precision sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Method.
    #[serde(serialize_with = "ser_display")]
    pub method: Method,
    /// Step or tolerance.
    #[serde(skip)]
    pub step: Step,
    /// Distance to the reference at T (NaN if the run failed).
    pub error: f64,
    /// Mean wall time of one run, seconds.
    pub wall_s: f64,
    /// Evaluations.
    pub evaluations: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Relative energy drift at T; NaN when the run failed or the scene
    /// has no energy to measure (see [`drift_columns`]).
    pub energy_drift: f64,
    /// Relative drift of |H| (free) or H_Z (heavy top) at T, or the
    /// largest of a derived scene's other conserved steps; NaN for a shaft
    /// (see [`drift_columns`]).
    pub momentum_drift: f64,
    /// `ok` or the error message.
    pub status: String,
}

/// CSV header of [`Row::csv`].
pub const CSV_HEADER: &str =
    "method,step,value,error,wall_s,evaluations,steps,energy_drift,momentum_drift,status";

impl Row {
    /// One CSV line (no newline).
    pub fn csv(&self) -> String {
        let (kind, value) = match self.step {
            Step::Fixed(h) => ("dt", h),
            Step::Tolerance(t) => ("tol", t),
        };
        // A value that is not available (a failed run's error and time, a
        // drift the scene has no quantity for) is an empty cell, never `NaN`.
        let cell = |v: f64| {
            if v.is_nan() {
                String::new()
            } else {
                format!("{v:e}")
            }
        };
        format!(
            "{},{kind},{value:e},{},{},{},{},{},{},{}",
            self.method,
            cell(self.error),
            cell(self.wall_s),
            self.evaluations,
            self.steps,
            cell(self.energy_drift),
            cell(self.momentum_drift),
            self.status.replace(',', ";")
        )
    }
}

/// Steps and tolerances the sweep tries for a method over `[0, t_end]`.
pub fn sweep_steps(method: Method, t_end: f64) -> Vec<Step> {
    if method.is_adaptive() {
        return (3..=13).map(|k| Step::Tolerance(10f64.powi(-k))).collect();
    }
    // Steps from t_end/8 down by factors of 2 until the cost cap.
    let max_steps: u64 = match method {
        Method::Euler => 1 << 21,
        _ => 1 << 17,
    };
    let mut out = vec![];
    let mut n: u64 = 8;
    while n <= max_steps {
        out.push(Step::Fixed(t_end / n as f64));
        n *= 2;
    }
    out
}

/// Runs every method over its steps on a scene; `min_time` is the least
/// total wall time spent repeating one run to time it.
pub fn work_precision(
    scene: &Scene,
    t_end: f64,
    min_time: f64,
    mut progress: impl FnMut(&Row),
) -> Result<Vec<Row>, SimError> {
    let entry = sweep_entry(scene)?;
    let mut rows = vec![];
    // The methods that apply to the model (no splittings without exactly
    // solved sub-flows).
    for method in Method::ALL.into_iter().filter(|m| (entry.takes)(*m)) {
        let mut previous_error = f64::INFINITY;
        for step in sweep_steps(method, t_end) {
            let row = sweep_one(entry, scene, method, step, t_end, min_time)?;
            let err = row.error;
            progress(&row);
            rows.push(row);
            // Stop refining once round-off dominates.
            if err.is_finite() && err < 1e-13 && previous_error < 1e-12 {
                break;
            }
            if err.is_finite() {
                previous_error = err;
            }
        }
    }
    Ok(rows)
}

fn timed<T>(
    min_time: f64,
    mut f: impl FnMut() -> Result<T, SimError>,
) -> Result<(T, f64), SimError> {
    let start = Instant::now();
    let mut out = f()?;
    let first = start.elapsed().as_secs_f64();
    if first >= min_time {
        return Ok((out, first));
    }
    let reps = ((min_time / first.max(1e-7)).ceil() as u32).clamp(1, 1000);
    let start = Instant::now();
    for _ in 0..reps {
        out = f()?;
    }
    Ok((out, start.elapsed().as_secs_f64() / reps as f64))
}

/// The model whose sweep `hdot work-precision` measures on `scene`: the
/// first entry of [`MODELS`] with a sweep that applies to it.
pub fn sweep_model(scene: &Scene) -> Result<Model, SimError> {
    sweep_entry(scene).map(|e| e.model)
}

/// What the two drift columns of the sweep measure on a scene: for each,
/// the quantity, or why the column is not available (its cells are then
/// empty).
#[derive(Debug, Clone, PartialEq)]
pub struct DriftColumns {
    /// The `energy_drift` column.
    pub energy: Result<String, String>,
    /// The `momentum_drift` column.
    pub momentum: Result<String, String>,
}

/// What `hdot work-precision` reports in its drift columns on `scene`.
pub fn drift_columns(scene: &Scene) -> Result<DriftColumns, SimError> {
    let entry = sweep_entry(scene)?;
    Ok((entry.sweep.expect("chosen by sweep_entry").columns)(scene))
}

fn columns_fixed_axis(_: &Scene) -> DriftColumns {
    DriftColumns {
        energy: Ok("the shaft's kinetic energy at T against the closed form's".into()),
        momentum: Err(
            "a shaft has one degree of freedom and no momentum the motion conserves".into(),
        ),
    }
}

fn columns_rigid_body(scene: &Scene) -> DriftColumns {
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

fn sweep_entry(scene: &Scene) -> Result<&'static ModelEntry, SimError> {
    for entry in &MODELS {
        if entry.sweep.is_some() && (entry.refusal)(scene)?.is_none() {
            return Ok(entry);
        }
    }
    Err(not_applicable(
        Model::RigidBody,
        scene,
        "no integrated model of this scene has a work-precision sweep",
    ))
}

fn sweep_one(
    entry: &ModelEntry,
    scene: &Scene,
    method: Method,
    step: Step,
    t_end: f64,
    min_time: f64,
) -> Result<Row, SimError> {
    let mut row = Row {
        method,
        step,
        error: f64::NAN,
        wall_s: f64::NAN,
        evaluations: 0,
        steps: 0,
        energy_drift: f64::NAN,
        momentum_drift: f64::NAN,
        status: "ok".into(),
    };
    let sweep = entry.sweep.expect("chosen by sweep_entry");
    (sweep.run)(scene, &mut row, t_end, min_time)?;
    // A run whose error is not finite diverged, as `hdot simulate` says of
    // it: a failed row, left out of the chart.
    if row.status == "ok" && !row.error.is_finite() {
        row.status = format!("diverged: the error at T = {t_end} is not finite");
    }
    Ok(row)
}

/// One sweep run of a shaft, measured against its closed form.
fn sweep_fixed_axis(
    scene: &Scene,
    row: &mut Row,
    t_end: f64,
    min_time: f64,
) -> Result<(), SimError> {
    let SceneKind::FixedAxis { shaft, y0 } = &scene.kind else {
        return Err(wrong_kind(Model::FixedAxis, scene));
    };
    let run = || {
        integrate(
            shaft,
            row.method,
            row.step,
            0.0,
            *y0,
            t_end,
            Limits::default(),
            |_, _| Ok(()),
        )
    };
    match timed(min_time, run) {
        Ok(((y, stats), wall)) => {
            let e = shaft.exact(y0, t_end);
            row.error = ((y[0] - e[0]).powi(2) + (y[1] - e[1]).powi(2)).sqrt();
            row.wall_s = wall;
            row.evaluations = stats.evaluations;
            row.steps = stats.steps;
            row.energy_drift = relative(shaft.energy(&y), shaft.energy(&e));
        }
        Err(e) => row.status = e.to_string(),
    }
    Ok(())
}

/// One sweep run of a free body or heavy top in the quaternion model,
/// measured against the reference state.
fn sweep_rigid_body(
    scene: &Scene,
    row: &mut Row,
    t_end: f64,
    min_time: f64,
) -> Result<(), SimError> {
    let (body, y0) = free_body(scene).ok_or_else(|| wrong_kind(Model::RigidBody, scene))?;
    let (reference, _) = reference_state(scene, t_end)?;
    let run = || {
        integrate(
            &body,
            row.method,
            row.step,
            0.0,
            y0,
            t_end,
            Limits::default(),
            |_, _| Ok(()),
        )
    };
    match timed(min_time, run) {
        Ok(((y, stats), wall)) => {
            row.error = state_distance(&y, &reference);
            row.wall_s = wall;
            row.evaluations = stats.evaluations;
            row.steps = stats.steps;
            let d = free_drifts(&body, &y0, &y);
            row.energy_drift = d[0].relative;
            row.momentum_drift = d[1].relative;
        }
        Err(e) => row.status = e.to_string(),
    }
    Ok(())
}

/// Writes the work-precision chart (error against wall time, log–log, one
/// line per method) to `<stem>.svg` and `<stem>.png` with the shared helper.
pub fn write_chart(
    rows: &[Row],
    stem: &std::path::Path,
    title: &str,
) -> Result<(), hdot_num::chart::ChartError> {
    let mut batch = hdot_num::fsio::Batch::new();
    stage_chart(&mut batch, rows, stem, title)?;
    batch
        .commit()
        .map_err(|source| hdot_num::chart::ChartError::Io {
            path: stem.to_path_buf(),
            source,
        })
}

/// As [`write_chart`], staged in `batch` with the other files of the command.
pub fn stage_chart(
    batch: &mut hdot_num::fsio::Batch,
    rows: &[Row],
    stem: &std::path::Path,
    title: &str,
) -> Result<(), hdot_num::chart::ChartError> {
    let series: Vec<hdot_num::chart::Series> = Method::ALL
        .into_iter()
        .filter_map(|m| {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.method == m && r.status == "ok")
                .map(|r| (r.wall_s, r.error))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            (!pts.is_empty()).then(|| hdot_num::chart::Series::new(m.name(), pts))
        })
        .collect();
    hdot_num::chart::loglog_chart_into(
        batch,
        stem,
        title,
        "wall time per run (s)",
        "error at T",
        &series,
    )
}
