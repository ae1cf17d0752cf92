//! `hdot work-precision --html`: the page of the study — what was swept,
//! the chart of error against wall time inline, and the tables of the
//! runs (method, step or tolerance, error, time, cost, drifts; the failed
//! ones with the reason).

use std::fmt::Write;

use hdot_sim::Step;
use hdot_sim::run::Row;
use hdot_sim::scene::Scene;

use super::escape;
use super::shell::{Shell, chart, report_table};

/// What the study swept, beside its rows.
#[derive(Debug, Clone)]
pub struct Study<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The end time of every run.
    pub t_end: f64,
    /// The model the methods integrate.
    pub model: &'a str,
    /// Every run, in the order of the sweep.
    pub rows: &'a [Row],
    /// What the two drift columns hold, or why one is empty: `(column, Ok(what) | Err(why))`.
    pub drifts: [(&'a str, &'a Result<String, String>); 2],
}

/// The page of `study`; `svg` is its chart, `None` when no run has a
/// positive error to draw on log axes (the page says so).
pub fn work_precision_page(study: &Study<'_>, svg: Option<&str>) -> String {
    let scene = study.scene;
    let ok = study.rows.iter().filter(|r| r.status == "ok").count();
    let mut report = format!(
        "model: {}\nend time: T = {}\nruns: {} ({ok} reached T, {} failed), each timed over repeats\n",
        study.model,
        study.t_end,
        study.rows.len(),
        study.rows.len() - ok
    );
    for (name, column) in study.drifts {
        // The CSV's column name, in words (`energy_drift`: energy drift).
        let name = name.replace('_', " ");
        let _ = match column {
            Ok(what) => writeln!(report, "{name}: {what}"),
            Err(why) => writeln!(report, "{name}: not available: {why}"),
        };
    }
    let mut s = String::from("<section class=\"report\">\n<h2>Report</h2>\n");
    s.push_str(&report_table(&report));
    s.push_str("</section>\n<section class=\"charts\">\n<h2>Error against wall time</h2>\n");
    match svg {
        Some(svg) => s.push_str(&chart(
            svg,
            "Error at T against the wall time of one run, one line per method (lower left is better).",
        )),
        None => s.push_str(
            "<p class=\"note\">No chart: no run has a positive error at T to draw on a log scale \
             (every method computes this motion exactly, e.g. a body at rest).</p>\n",
        ),
    }
    s.push_str("</section>\n<section class=\"runs\">\n<h2>Every run</h2>\n");
    s.push_str(&runs_tables(study.rows));
    s.push_str("</section>\n");
    Shell {
        title: &scene.name,
        command: "hdot work-precision",
        description: &scene.description,
        detail: format!("{} · kind {}", scene.file.display(), scene.kind.name()),
    }
    .page(&s, "")
}

/// A value of the table: three significant digits, `—` when not available.
fn cell(v: f64) -> String {
    if v.is_nan() {
        "—".into()
    } else {
        format!("{v:.2e}")
    }
}

/// A run's step or tolerance.
fn step(r: &Row) -> String {
    match r.step {
        Step::Fixed(h) => format!("dt = {h:.3e}"),
        Step::Tolerance(t) => format!("tol = {t:.0e}"),
    }
}

/// The tables of the runs: those that reached T with their numbers (the
/// table scrolls sideways inside its box on a narrow screen, the page does
/// not), then those that failed with the reason.
fn runs_tables(rows: &[Row]) -> String {
    let (ok, failed): (Vec<&Row>, Vec<&Row>) = rows.iter().partition(|r| r.status == "ok");
    let mut s = String::from(
        "<div class=\"scroll\" tabindex=\"0\" role=\"region\" aria-label=\"runs that reached T\">\n\
         <table class=\"data\">\n<thead><tr><th>method</th><th>step or tolerance</th><th>error at T</th>\
         <th>wall time (s)</th><th>evaluations</th><th>steps</th><th>energy drift</th><th>momentum drift</th>\
         </tr></thead>\n<tbody>\n",
    );
    for r in &ok {
        let _ = writeln!(
            s,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            r.method,
            step(r),
            cell(r.error),
            cell(r.wall_s),
            r.evaluations,
            r.steps,
            cell(r.energy_drift),
            cell(r.momentum_drift),
        );
    }
    s.push_str("</tbody>\n</table>\n</div>\n");
    if failed.is_empty() {
        return s;
    }
    let _ = write!(
        s,
        "<h3>Runs that failed ({})</h3>\n<table class=\"failed\">\n<thead><tr><th>method</th>\
         <th>step or tolerance</th><th>why</th></tr></thead>\n<tbody>\n",
        failed.len()
    );
    for r in &failed {
        let _ = writeln!(
            s,
            "<tr><td>{}</td><td>{}</td><td>{}</td></tr>",
            r.method,
            step(r),
            escape(&r.status)
        );
    }
    s.push_str("</tbody>\n</table>\n");
    s
}
