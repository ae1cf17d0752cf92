//! `hdot work-precision SCENE`: sweep every method over step sizes and
//! tolerances; write the CSV and the chart (error against wall time), and
//! with `--html` a page of both (`crate::html::work_precision_page`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_sim::run;

use crate::output::{self, OutputError};

// Arguments of `hdot work-precision`.
#[derive(Debug, Args)]
pub struct WorkPrecisionArgs {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Directory for `<scene>-work-precision.{csv,svg,png}`.
    #[arg(long, default_value = ".")]
    pub out: PathBuf,
    /// End time (default: the scene's).
    #[arg(long, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Least wall time spent repeating one run to time it, seconds.
    #[arg(long, default_value_t = 0.02, allow_negative_numbers = true)]
    pub min_time: f64,
    /// Run budget: steps one integration may take (see docs/cli.md).
    #[arg(long, default_value_t = hdot_sim::estimate::DEFAULT_MAX_STEPS, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: u64,
    /// Also write the report, the chart and the table of every run as one
    /// self-contained web page.
    #[arg(long, value_name = "FILE")]
    pub html: Option<PathBuf>,
}

/// Runs `hdot work-precision`.
pub fn run(args: WorkPrecisionArgs) -> anyhow::Result<ExitCode> {
    let scene = crate::catalog::scene(&args.scene)?;
    let t_end = args.t_end.unwrap_or(scene.t_end);
    if !(t_end.is_finite() && t_end > 0.0) {
        anyhow::bail!("--t-end must be positive and finite, got {t_end}");
    }
    run::check_end_time(&scene, t_end)?;
    // The budgets, before any run: the steps of the adaptive runs (the
    // fixed steps of the sweep stay within it), and the time spent timing.
    hdot_sim::estimate::set_max_steps(args.max_steps);
    hdot_sim::estimate::check_run_budget(scene.rate_scale(), t_end, None)?;
    let runs: usize = hdot_sim::Method::ALL
        .into_iter()
        .map(|m| run::sweep_steps(m, t_end).len())
        .sum();
    hdot_sim::estimate::check_timing_budget(runs, args.min_time).map_err(anyhow::Error::msg)?;
    let stem_name = format!(
        "{}-work-precision",
        args.scene
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scene")
    );
    let stem = args.out.join(&stem_name);
    let csv = stem.with_extension("csv");
    let (svg, png) = (stem.with_extension("svg"), stem.with_extension("png"));
    if let Some(page) = &args.html {
        let mut inputs = vec![args.scene.as_path()];
        if let Some(ds) = scene.derivation() {
            inputs.push(ds.derivation.as_path());
        }
        crate::html::refuse_page_path(
            page,
            &inputs,
            &[("the CSV", &csv), ("the chart", &svg), ("the chart", &png)],
        )?;
    }
    // The CSV and charts, before the sweep: none may be a file the scene
    // read (the scene, its derivation, a CSV cloud).
    for out in [&csv, &svg, &png] {
        hdot_num::fsio::refuse_overwriting_inputs(out, &hdot_sym::textfile::inputs())?;
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| OutputError::new(format!("cannot create {}", args.out.display()), e))?;
    // The rows as they come, under the CSV's header line (stderr: the
    // progress of a sweep that may take minutes).
    crate::errln!("{}", run::CSV_HEADER);
    // A spinner on a terminal (the reference run, made first, can take
    // seconds before the first row), counting the rows as they come.
    let spinner = std::io::IsTerminal::is_terminal(&std::io::stderr()).then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.set_message(format!("reference run and {runs} runs of the sweep"));
        b.enable_steady_tick(std::time::Duration::from_millis(200));
        b
    });
    let mut done = 0usize;
    let result = run::work_precision(&scene, t_end, args.min_time, |r| {
        done += 1;
        match &spinner {
            Some(b) => {
                b.println(r.csv());
                b.set_message(format!("{done} of at most {runs} runs"));
            }
            None => crate::errln!("{}", r.csv()),
        }
    });
    if let Some(b) = &spinner {
        b.finish_and_clear();
    }
    // A run that fails (the run budget spent, a motion that explodes) is a
    // failure of the run, exit 1, as in `hdot simulate`; a scene it cannot
    // take is an error of the input, exit 2.
    let rows = match result {
        Ok(rows) => rows,
        Err(e) if crate::cmd::simulate::is_input_error(&e) => return Err(e.into()),
        Err(e) => {
            crate::errln!("error: {e}");
            return Ok(ExitCode::from(1));
        }
    };
    // The CSV and the chart appear together or not at all.
    let mut text = format!("{}\n", run::CSV_HEADER);
    for r in &rows {
        text.push_str(&r.csv());
        text.push('\n');
    }
    // A log–log chart needs a positive error: a scene every method computes
    // exactly (a body at rest) has none, and gets its CSV alone.
    let drawable = rows
        .iter()
        .any(|r| r.status == "ok" && r.error.is_finite() && r.error > 0.0);
    let mut batch = output::Batch::new();
    batch
        .write(&csv, text.as_bytes())
        .map_err(|e| OutputError::new(format!("cannot write {}", csv.display()), e))?;
    if drawable {
        run::stage_chart(
            &mut batch,
            &rows,
            &stem,
            &format!("{} (T = {t_end})", scene.name),
        )
        .map_err(|e| {
            OutputError::new(
                "cannot write the chart",
                std::io::Error::other(e.to_string()),
            )
        })?;
    }
    batch
        .commit()
        .map_err(|e| OutputError::new(format!("cannot write {}", stem.display()), e))?;
    if drawable {
        crate::outln!(
            "wrote {}, {}.svg, {}.png",
            csv.display(),
            stem.display(),
            stem.display()
        );
    } else {
        crate::outln!(
            "wrote {}; no chart: no run has a positive error at T to draw on a log scale \
             (every method computes this motion exactly, e.g. a body at rest)",
            csv.display()
        );
    }
    // What the drift columns hold, or why a column is empty.
    let columns = run::drift_columns(&scene)?;
    let drifts = [
        ("energy_drift", &columns.energy),
        ("momentum_drift", &columns.momentum),
    ];
    for (name, column) in drifts {
        match column {
            Ok(what) => crate::outln!("{name}: {what}"),
            Err(why) => crate::outln!("{name}: not available: {why}"),
        }
    }
    if let Some(page) = &args.html {
        let chart = if drawable {
            Some(
                std::fs::read_to_string(&svg)
                    .map_err(|e| OutputError::new("cannot read the chart back", e))?,
            )
        } else {
            None
        };
        let model = run::sweep_model(&scene)?;
        let study = crate::html::Study {
            scene: &scene,
            t_end,
            model: model.name(),
            rows: &rows,
            drifts,
        };
        output::write_atomic(
            page,
            crate::html::work_precision_page(&study, chart.as_deref()).as_bytes(),
        )?;
        crate::outln!("wrote {}", page.display());
    }
    Ok(ExitCode::SUCCESS)
}
