//! What a model of the motion is: the trait [`ModelEntry`] every entry of
//! the registry [`crate::models::MODELS`] implements (its name, the scenes
//! it applies to and why, what it covers exactly, how it integrates, runs
//! and sweeps), the handle [`Model`] a plan names one by, and the plain
//! data a model and the run exchange (the request, the plan, what a run
//! found). Nothing here knows any particular model.

use std::fmt;

use serde::Serialize;

use crate::record::Recorder;
use crate::scene::Scene;
use crate::{Method, SimError, Stats, Step};

/// One model of the motion, described by itself: its [`Descriptor`] says
/// what it is, the other methods how it behaves. Adding a model is one
/// file in `models/` implementing this trait and one line in
/// [`crate::models::MODELS`]: the `--model` help, the model choice, the
/// docs table and the refusals all come from the entries.
pub trait ModelEntry: Sync {
    /// What it says of itself (const data, one per entry).
    fn descriptor(&self) -> &'static Descriptor;
    /// Its command-line name (`--model`).
    fn name(&self) -> &'static str {
        self.descriptor().name
    }
    /// The scenes it applies to (for the docs and help).
    fn applies_to(&self) -> &'static str {
        self.descriptor().applies_to
    }
    /// Why it is the model chosen there.
    fn why(&self) -> &'static str {
        self.descriptor().why
    }
    /// Whether it integrates equations of motion when asked for by name
    /// (else a closed form).
    fn integrated(&self) -> bool {
        self.descriptor().integrated
    }
    /// Why it does not apply to a scene; `None` when it does.
    fn refusal(&self, scene: &Scene) -> Result<Option<&'static str>, SimError>;
    /// A closed form's test of a scene it applies to: whether it covers it
    /// exactly (and the reason it is chosen) or cannot be trusted there;
    /// `None` for a model that is not a closed form.
    fn covers(&self, _scene: &Scene, _t_end: f64) -> Option<Result<Cover, SimError>> {
        None
    }
    /// Whether it can integrate (with a method) at all.
    fn can_integrate(&self) -> bool {
        self.descriptor().can_integrate
    }
    /// How it integrates when no method is given: the scene, the request,
    /// the end time, and whether the model was chosen (not requested).
    fn integration(
        &self,
        _scene: &Scene,
        req: &Request,
        _t_end: f64,
        _chosen: bool,
    ) -> Result<Integration, SimError> {
        Ok(Integration::dop853(req))
    }
    /// Whether a request for `method` alone takes this model.
    fn takes(&self, method: Method) -> bool;
    /// Whether it is chosen to integrate a scene no closed form covers
    /// (the comparison model `euler-angles` is not).
    fn default_choice(&self) -> bool {
        false
    }
    /// CSV header of the rows it streams for a scene.
    fn stream_header(&self, scene: &Scene) -> String;
    /// Runs a planned scene, recording rows through `rec`.
    fn run(
        &self,
        scene: &Scene,
        plan: &Plan,
        rec: &mut Recorder<'_, '_>,
    ) -> Result<Outcome, SimError>;
    /// Whether `hdot work-precision` measures this model (closed forms and
    /// the comparison models of the same scenes are not measured).
    fn sweeps(&self) -> bool {
        false
    }
    /// One run of the work-precision sweep with `method` at `step`, timed
    /// over at least `min_time` seconds: `Ok(Err(message))` when the run
    /// itself failed (a row with that status), `Err` when the sweep cannot
    /// go on.
    fn sweep_run(
        &self,
        _scene: &Scene,
        _method: Method,
        _step: Step,
        _t_end: f64,
        _min_time: f64,
    ) -> Result<Result<Measured, String>, SimError> {
        Ok(Err("this model has no work-precision sweep".into()))
    }
    /// What the sweep's two drift columns measure on a scene.
    fn drift_columns(&self, _scene: &Scene) -> DriftColumns {
        let none = Err("this model has no work-precision sweep".to_string());
        DriftColumns {
            energy: none.clone(),
            momentum: none,
        }
    }
}

/// What a model says of itself, as const data: the part of an entry that
/// is the same kind of fact for every model (its behaviour is the trait's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Descriptor {
    /// Its command-line name (`--model`).
    pub name: &'static str,
    /// The scenes it applies to (for the docs and help).
    pub applies_to: &'static str,
    /// Why it is the model chosen there.
    pub why: &'static str,
    /// Whether it integrates equations of motion when asked for by name
    /// (else a closed form; `fixed-axis` has both and integrates when a
    /// method is given).
    pub integrated: bool,
    /// Whether it can integrate (with a method) at all.
    pub can_integrate: bool,
}

/// A model, by its registry entry: compared, printed and serialised by
/// its name.
#[derive(Clone, Copy)]
pub struct Model(pub &'static dyn ModelEntry);

impl Model {
    /// Command-line name (its entry's).
    pub fn name(self) -> &'static str {
        self.0.name()
    }

    /// The model's entry.
    pub fn entry(self) -> &'static dyn ModelEntry {
        self.0
    }
}

impl PartialEq for Model {
    fn eq(&self, other: &Model) -> bool {
        self.name() == other.name()
    }
}

impl Eq for Model {}

impl std::hash::Hash for Model {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        self.name().hash(h);
    }
}

impl fmt::Debug for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Model({})", self.name())
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
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

impl Plan {
    /// The method and step of an integrated plan.
    pub fn method_step(&self) -> Result<(Method, Step), SimError> {
        match (self.method, self.step) {
            (Some(m), Some(s)) => Ok((m, s)),
            _ => Err(SimError::MethodNotApplicable {
                method: "none".into(),
                model: self.model.name().into(),
                reason: "an integrated model needs a method and a step".into(),
            }),
        }
    }
}

pub(crate) fn ser_display<S: serde::Serializer, T: fmt::Display>(
    v: &T,
    s: S,
) -> Result<S::Ok, S::Error> {
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

/// The error of a model that does not apply to a scene.
pub fn not_applicable(model: Model, scene: &Scene, reason: &str) -> SimError {
    SimError::ModelNotApplicable {
        model: model.name().into(),
        scene: format!("{} ({})", scene.name, scene.file.display()),
        reason: reason.into(),
    }
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

impl Integration {
    /// DOP853 at the requested step or tolerance.
    pub fn dop853(req: &Request) -> Integration {
        let step = requested_step(req, Method::Dop853);
        Integration {
            method: Method::Dop853,
            step,
            fit_error: None,
            detail: format!("dop853 at {}", step_label(step)),
        }
    }
}

/// The requested step or tolerance, else the defaults.
pub fn requested_step(req: &Request, method: Method) -> Step {
    req.step.unwrap_or(if method.is_adaptive() {
        Step::Tolerance(DEFAULT_TOL)
    } else {
        Step::Fixed(DEFAULT_DT)
    })
}

/// Relative change of an invariant between start and end.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Drift {
    /// Which invariant (`energy`, `|H|`, `H_Z`, or a derived step's name).
    pub name: String,
    /// `|I(T) − I(0)| / |I(0)|`; for a derived scene's conserved step,
    /// `|I(T) − I(0)|` over the step's size along the run (the largest sum
    /// of its terms' magnitudes, docs/simulation.md, *Derived scenes*).
    pub relative: f64,
}

/// What a derived scene's configuration constraints f(q) = 0 met along
/// the run (`holonomic` in the scene's `[derivation]` table).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConstraintDrift {
    /// The steps holding f.
    pub steps: Vec<String>,
    /// The dependent coordinates solved for.
    pub dependent: Vec<String>,
    /// The largest |f_i(q)| over the accepted steps (after the
    /// projection, when there is one).
    pub max_residual: f64,
    /// Whether q_d was projected back onto f = 0 after every step.
    pub projected: bool,
    /// The largest correction the projection made to a dependent
    /// coordinate in one step (0 without projection).
    pub max_correction: f64,
}

/// What a multiplier form's velocity constraints A_c u = 0 met along the
/// run: the dependent speeds are solved from them after every step.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VelocityConstraintDrift {
    /// The dependent speeds solved for.
    pub dependent: Vec<String>,
    /// The largest |(A_c u)_i| over the start and the accepted steps
    /// (after the dependent speeds are solved).
    pub max_residual: f64,
    /// The largest change the solve made to a dependent speed in one step.
    pub max_correction: f64,
}

/// What the Euler parameters of a derived state met along the run: each
/// quaternion is divided by its norm after every step.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UnitNormDrift {
    /// The parameters of each quaternion, scalar part first.
    pub parameters: Vec<[String; 4]>,
    /// The largest | |e| − 1 | met before a normalization.
    pub max_drift: f64,
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

/// What one model's run found; the run's report is the plan and this.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outcome {
    /// The reference the error is measured against.
    pub reference: String,
    /// Error at T (see `error_basis`).
    pub error: Option<f64>,
    /// How `error` was obtained.
    pub error_basis: String,
    /// `--check`: distance of a closed-form run from a tight DOP853 run.
    pub check: Option<Check>,
    /// Invariant drifts at T.
    pub drifts: Vec<Drift>,
    /// Evaluations, steps and rejected steps.
    pub stats: Stats,
    /// Wall time of the run (without the reference), seconds.
    pub wall_s: f64,
    /// State at T.
    pub final_state: Vec<f64>,
    /// Heavy top in steady precession: §7 check.
    pub precession: Option<PrecessionCheck>,
    /// Shaft: bearing reactions and moments at T.
    pub reactions: Option<[f64; 7]>,
    /// Names of the components of `final_state` (empty for `[q, ω]`).
    pub state_names: Vec<String>,
    /// A derived scene's reported frame at T.
    pub frame: Option<FrameState>,
    /// A step or tolerance fitted on the scene during the run, and what
    /// was measured to fit it (appended to the plan's reason).
    pub fitted: Option<(Step, String)>,
    /// A derived scene's configuration constraints along the run.
    pub constraints: Option<ConstraintDrift>,
    /// A multiplier form's velocity constraints along the run.
    pub velocity_constraints: Option<VelocityConstraintDrift>,
    /// A derived state's Euler parameters along the run.
    pub unit_norms: Option<UnitNormDrift>,
}

/// What one timed run of the work-precision sweep measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Distance to the reference at T.
    pub error: f64,
    /// Mean wall time of one run, seconds.
    pub wall_s: f64,
    /// Evaluations and steps.
    pub stats: Stats,
    /// Relative energy drift at T (NaN when there is none to measure).
    pub energy_drift: f64,
    /// Relative momentum drift at T (NaN when there is none to measure).
    pub momentum_drift: f64,
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

/// `|a − b| / |b|`.
pub(crate) fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// Whether a method is not one of the splittings, which need the
/// quaternion body's exactly solved sub-flows.
pub(crate) fn not_a_splitting(m: Method) -> bool {
    !matches!(m, Method::Split2 | Method::Split4)
}
