//! The work-precision study (`hdot work-precision`): every method the
//! swept model takes, over a ladder of steps and tolerances, each run
//! timed and measured against the reference; its CSV rows and chart.

use serde::Serialize;

use crate::model::{DriftColumns, Model, ModelEntry, not_applicable, ser_display};
use crate::models::MODELS;
use crate::scene::Scene;
use crate::{Method, SimError, Step};

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
    for method in Method::ALL.into_iter().filter(|m| entry.takes(*m)) {
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

/// The model whose sweep `hdot work-precision` measures on `scene`: the
/// first entry of [`MODELS`] with a sweep that applies to it.
pub fn sweep_model(scene: &Scene) -> Result<Model, SimError> {
    sweep_entry(scene).map(Model)
}

/// What `hdot work-precision` reports in its drift columns on `scene`.
pub fn drift_columns(scene: &Scene) -> Result<DriftColumns, SimError> {
    Ok(sweep_entry(scene)?.drift_columns(scene))
}

fn sweep_entry(scene: &Scene) -> Result<&'static dyn ModelEntry, SimError> {
    for &entry in MODELS {
        if entry.sweeps() && entry.refusal(scene)?.is_none() {
            return Ok(entry);
        }
    }
    Err(not_applicable(
        Model(&crate::models::rigid_body::RIGID_BODY),
        scene,
        "no integrated model of this scene has a work-precision sweep",
    ))
}

fn sweep_one(
    entry: &dyn ModelEntry,
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
    match entry.sweep_run(scene, method, step, t_end, min_time)? {
        Ok(m) => {
            row.error = m.error;
            row.wall_s = m.wall_s;
            row.evaluations = m.stats.evaluations;
            row.steps = m.stats.steps;
            row.energy_drift = m.energy_drift;
            row.momentum_drift = m.momentum_drift;
        }
        Err(status) => row.status = status,
    }
    // A run whose error is not finite diverged, as `hdot simulate` says of
    // it: a failed row, left out of the chart.
    if row.status == "ok" && !row.error.is_finite() {
        row.status = format!("diverged: the error at T = {t_end} is not finite");
    }
    Ok(row)
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
