//! Estimates of a run before it is made: the error of a closed-form run,
//! not assuming the closed form is right (its defect against the equations
//! of motion it claims to solve), and the run budget — the steps one
//! integration may take, checked against an estimate of the steps a run
//! needs before it starts and enforced while it runs.

pub use crate::budget::{DEFAULT_MAX_STEPS, max_steps, set_max_steps};
use crate::{Limits, Method, SimError, Step, integrate};

/// The most phase `|ω| h` (radians of the scene's rate scale) one step of
/// any method is taken to cover when the steps of an adaptive run are
/// estimated: a generous bound (an eighth-order step at the loosest
/// tolerance swept covers about one radian), so the estimate is a lower
/// bound and a run it refuses could not finish within the budget.
pub const MAX_PHASE_PER_STEP: f64 = 4.0;

/// The budget of the work–precision study's timing: `--min-time` (the
/// least wall time spent repeating one run) times the number of runs of
/// the sweep may not exceed this many seconds.
pub const MAX_TIMING_SECONDS: f64 = 600.0;

/// Refuses a `min_time` per run that, over `runs` runs, exceeds
/// [`MAX_TIMING_SECONDS`] (or is negative or not finite).
pub fn check_timing_budget(runs: usize, min_time: f64) -> Result<(), String> {
    if !(min_time.is_finite() && min_time >= 0.0) {
        return Err(format!(
            "--min-time must be non-negative and finite, got {min_time}"
        ));
    }
    let total = runs as f64 * min_time;
    if total > MAX_TIMING_SECONDS {
        return Err(format!(
            "refused: --min-time {min_time:e} s for each of the {runs} runs of the sweep would \
             take at least {total:e} s, more than the timing budget of {MAX_TIMING_SECONDS} s; \
             choose --min-time {:.3} or less",
            MAX_TIMING_SECONDS / runs.max(1) as f64
        ));
    }
    Ok(())
}

/// A lower estimate of the steps a run over `[0, t_end]` takes: `t_end/h`
/// for a fixed step; for an adaptive one (or a step still to be chosen),
/// the phase `rate_scale · t_end` over [`MAX_PHASE_PER_STEP`].
pub fn estimated_steps(rate_scale: f64, t_end: f64, step: Option<Step>) -> f64 {
    match step {
        Some(Step::Fixed(h)) => (t_end / h).ceil(),
        _ => (rate_scale * t_end / MAX_PHASE_PER_STEP).ceil(),
    }
}

/// Refuses, before any work, a run whose estimated steps
/// ([`estimated_steps`]) exceed the run budget ([`max_steps`]).
pub fn check_run_budget(rate_scale: f64, t_end: f64, step: Option<Step>) -> Result<(), SimError> {
    let estimated = estimated_steps(rate_scale, t_end, step);
    let budget = max_steps();
    if estimated.is_nan() || estimated > budget as f64 {
        return Err(SimError::OverBudget {
            estimated,
            budget,
            t_end,
        });
    }
    Ok(())
}

/// The error a closed form must stay within, per unit of phase `|ω| T`
/// (the bound the exact torque-free solution is tested to).
pub const CLOSED_FORM_BOUND: f64 = 1e-13;
/// Tolerance of the DOP853 run that `--check` compares a closed form with.
pub const CHECK_TOL: f64 = 1e-13;
/// Number of points along a closed-form run where its defect is sampled.
pub const ESTIMATE_SAMPLES: usize = 16;
/// What a closed-form run's error is.
pub const ESTIMATE_BASIS: &str = "estimated: distance from the initial state plus the defect of the \
     equations of motion (and attitude kinematics) sampled at 16 points along the run, times T";

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

/// The Euclidean distance of two states.
pub fn euclid<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}
