//! Typed errors of the simulation crate: each says where (file, field, time).

use std::path::PathBuf;

/// Everything that can go wrong while reading a scene or running it.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A step size that is zero, negative or not finite.
    #[error("step size must be positive and finite, got {0}")]
    NonPositiveStep(f64),
    /// A tolerance that is zero, negative or not finite.
    #[error("tolerance must be positive and finite, got {0}")]
    NonPositiveTolerance(f64),
    /// An end time that is negative or not finite.
    #[error("end time must be non-negative and finite, got {0}")]
    BadEndTime(f64),
    /// An attitude quaternion that is not of unit norm (or not finite).
    #[error("{field}: attitude quaternion must be finite and of unit norm, got norm {norm}")]
    NonUnitAttitude {
        /// Where the quaternion came from (scene field or argument name).
        field: String,
        /// Its norm (NaN if a component is NaN).
        norm: f64,
    },
    /// A field of a scene file with an invalid value.
    #[error("{file}: field `{field}`: {message}")]
    BadField {
        /// The scene file.
        file: PathBuf,
        /// Dotted path of the field.
        field: String,
        /// What is wrong with it.
        message: String,
    },
    /// A scene file that is not valid TOML or lacks a field.
    #[error("{file}: {message}")]
    Parse {
        /// The scene file.
        file: PathBuf,
        /// The parser's message (it names line and column).
        message: String,
    },
    /// What moves in a scene (`g`, `[[body]]`, `[[cloud]]`), read by the
    /// schema every scene shares: names file, line and field.
    #[error(transparent)]
    Bodies(#[from] hdot_num::scene::SceneError),
    /// A scene file that cannot be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Principal moments that no physical body has.
    #[error("principal moments {moments:?}: {message}")]
    BadInertia {
        /// The moments given.
        moments: [f64; 3],
        /// Which condition fails.
        message: String,
    },
    /// A model asked for (by `--model`) that the scene does not allow.
    #[error("model `{model}` cannot be honoured for scene `{scene}`: {reason}")]
    ModelNotApplicable {
        /// The model asked for.
        model: String,
        /// The scene name.
        scene: String,
        /// Why not.
        reason: String,
    },
    /// A step control the method does not have (a tolerance for a
    /// fixed-step method).
    #[error("method `{method}` {reason}")]
    StepControl {
        /// The method asked for.
        method: String,
        /// What it needs instead.
        reason: String,
    },
    /// A method that cannot integrate this model (e.g. a splitting of a non-splittable model).
    #[error("method `{method}` cannot integrate model `{model}`: {reason}")]
    MethodNotApplicable {
        /// The method asked for.
        method: String,
        /// The model.
        model: String,
        /// Why not.
        reason: String,
    },
    /// An unknown name on the command line or in a scene.
    #[error("unknown {what} `{name}` (expected one of: {expected})")]
    UnknownName {
        /// What kind of name (method, model, ...).
        what: &'static str,
        /// The name given.
        name: String,
        /// The names that are accepted.
        expected: String,
    },
    /// The Eulerian-angle kinematics are singular (θ at 0 or π).
    #[error(
        "Eulerian angles singular at t = {t}: nutation θ = {theta} (sin θ = {sin_theta:e}); \
         use the quaternion model"
    )]
    EulerAngleSingularity {
        /// Time of the failing step.
        t: f64,
        /// The nutation angle reached.
        theta: f64,
        /// Its sine.
        sin_theta: f64,
    },
    /// The state became NaN or infinite: the method is unstable at this step.
    #[error("state not finite at t = {t} (step {step}): the method is unstable at this step size")]
    NonFinite {
        /// Time reached.
        t: f64,
        /// Number of the step.
        step: u64,
    },
    /// An adaptive method's step became too small.
    #[error("step size underflow at t = {t} (h = {h:e})")]
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// The step size.
        h: f64,
    },
    /// An implicit method's iteration did not converge.
    #[error(
        "implicit iteration did not converge at t = {t} with h = {h}: step too large for fixed-point iteration"
    )]
    NotConverged {
        /// Time of the step.
        t: f64,
        /// The step size.
        h: f64,
    },
    /// A run needed more steps than the run budget allows: stopped there,
    /// naming which of the run's integrations spent the budget and how.
    #[error("{}", too_many_steps(run, *max_steps, *t, *t_end, *accepted, *rejected))]
    TooManySteps {
        /// The step limit.
        max_steps: u64,
        /// Time reached.
        t: f64,
        /// The end time the integration was to reach.
        t_end: f64,
        /// Steps accepted before it stopped.
        accepted: u64,
        /// Steps an adaptive method's error control rejected.
        rejected: u64,
        /// Which integration spent the budget, e.g. `the reference run
        /// (dop853 at tol=1e-14, …)`; empty until the caller names it
        /// ([`SimError::in_run`]).
        run: String,
    },
    /// Stored output would exceed the memory budget.
    #[error(
        "stored output would need {needed} bytes, more than the budget of {budget} bytes; \
         stream it to a file (--output FILE.csv) or sample less often"
    )]
    MemoryBudget {
        /// Bytes the output would need.
        needed: u64,
        /// The budget.
        budget: u64,
    },
    /// A derived model cannot be built from its derivation and scene.
    #[error("derived model: {message}")]
    Derived {
        /// What is wrong, naming the file, step or field.
        message: String,
    },
    /// A derived model cannot be built because of what one field of the
    /// scene says (the scene reader turns it into a [`SimError::BadField`]
    /// at that field's line).
    #[error("derived model: {field}: {message}")]
    DerivedField {
        /// The scene's field, e.g. `derivation.accelerations`, `constants`.
        field: String,
        /// What is wrong, naming the derivation and its step.
        message: String,
    },
    /// The coordinates of a derived model break down.
    #[error("coordinate singularity at t = {t}: {why}")]
    CoordinateSingularity {
        /// When.
        t: f64,
        /// What vanished.
        why: String,
    },
    /// A result (state, drift, reaction, error) that is NaN or infinite.
    #[error("{quantity} is not finite at t = {t}: the result is refused")]
    NonFiniteResult {
        /// Time of the result.
        t: f64,
        /// Which quantity, e.g. `state component ω_2`, `energy drift`.
        quantity: String,
    },
    /// An end time so long that f64 time no longer resolves the motion.
    #[error(
        "end time {t_end:e} is too long for this scene: the phase |ω| T = {phase:e} exceeds 2^52, \
         beyond the resolution of f64 time"
    )]
    EndTimeTooLong {
        /// The end time asked for.
        t_end: f64,
        /// `|ω| T`.
        phase: f64,
    },
    /// A run refused before it starts: its estimated steps exceed the
    /// run budget.
    #[error(
        "refused: a run to T = {t_end:e} needs at least {estimated:e} steps, more than the run \
         budget of {budget} steps (shorten --t-end, use a larger --dt, or raise the budget with \
         --max-steps)"
    )]
    OverBudget {
        /// The estimated steps (a lower bound).
        estimated: f64,
        /// The budget.
        budget: u64,
        /// The end time asked for.
        t_end: f64,
    },
    /// Writing streamed output failed.
    #[error("writing output: {0}")]
    Output(#[source] std::io::Error),
}

/// The message of [`SimError::TooManySteps`]: which integration stopped,
/// what it spent (accepted and rejected steps), how far it came, and what
/// to change.
fn too_many_steps(
    run: &str,
    max_steps: u64,
    t: f64,
    t_end: f64,
    accepted: u64,
    rejected: u64,
) -> String {
    let run = if run.is_empty() {
        "an integration of the run"
    } else {
        run
    };
    let spent = if accepted + rejected == 0 {
        // A fixed-step integration counts its steps before taking any.
        format!(
            "would need more than its {max_steps} steps to go from t = {t:e} to {t_end:e} in fixed steps"
        )
    } else {
        format!(
            "took its {max_steps} steps ({accepted} accepted, {rejected} rejected by the error control) \
             and reached only t = {t:e} of {t_end:e}"
        )
    };
    format!(
        "stopped on the run budget: {run} {spent}; the motion needs smaller steps than the budget \
         allows up to the end time (shorten --t-end, loosen --tol or --dt, or raise the budget with \
         --max-steps)"
    )
}

impl SimError {
    /// Names the integration an error of the run budget came from (`what`,
    /// e.g. `the reference run (dop853 at tol=1e-14)`), unless an inner
    /// caller named it already; any other error is returned as it is.
    pub fn in_run(self, what: impl FnOnce() -> String) -> SimError {
        match self {
            SimError::TooManySteps {
                max_steps,
                t,
                t_end,
                accepted,
                rejected,
                run,
            } if run.is_empty() => SimError::TooManySteps {
                max_steps,
                t,
                t_end,
                accepted,
                rejected,
                run: what(),
            },
            e => e,
        }
    }
}
