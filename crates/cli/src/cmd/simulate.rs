//! `hdot simulate SCENE`: run a scene with the least exact model (or the one
//! asked for) and report error, invariant drift, cost and wall time;
//! `--html FILE` also writes the run's page (`crate::html`).

use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_sim::run::{self, Output, Request};
use hdot_sim::{Method, SimError, Step};

use crate::output::{self, OutputError};

// Arguments of `hdot simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Scene file (TOML), e.g. docs/examples/sim-heavy-top.toml.
    pub scene: PathBuf,
    /// Integration method: euler, rk4, dopri5, dop853, midpoint, split2, split4.
    #[arg(long)]
    pub method: Option<String>,
    /// The models of the registry (`hdot_sim::models::MODELS`).
    #[arg(long, help = hdot_sim::models::help())]
    pub model: Option<String>,
    /// Fixed step size.
    #[arg(long, conflicts_with = "tol", allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Tolerance of an adaptive method (rtol = atol); for a heavy top without
    /// --method, the error the chosen method must reach.
    #[arg(long, allow_negative_numbers = true)]
    pub tol: Option<f64>,
    /// End time (default: the scene's).
    #[arg(long, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Output format.
    #[arg(long, default_value = "text", value_parser = ["text", "json"])]
    pub format: String,
    /// Stream every step to this CSV file as it is computed.
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Include the trajectory in the report (bounded by --memory-budget).
    #[arg(long)]
    pub trajectory: bool,
    /// Budget in bytes for the stored trajectory.
    #[arg(long, default_value_t = 64 << 20)]
    pub memory_budget: u64,
    /// Also compare a closed-form run with a tight DOP853 run (tol 1e-13).
    #[arg(long)]
    pub check: bool,
    /// Write a self-contained web page of the run: report, plots against
    /// time and a 3D view of the body moving (keeps the trajectory in
    /// memory, bounded by --memory-budget).
    #[arg(long, value_name = "FILE")]
    pub html: Option<PathBuf>,
    /// Run budget: steps one integration may take (see docs/cli.md); a
    /// run estimated to need more is refused, one that needs more stops.
    #[arg(long, default_value_t = hdot_sim::estimate::DEFAULT_MAX_STEPS, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: u64,
}

/// Errors of the input (exit 2) as opposed to failures of a run (exit 1).
pub(crate) fn is_input_error(e: &SimError) -> bool {
    !matches!(
        e,
        SimError::EulerAngleSingularity { .. }
            | SimError::CoordinateSingularity { .. }
            | SimError::NonFinite { .. }
            | SimError::StepSizeUnderflow { .. }
            | SimError::NotConverged { .. }
            | SimError::TooManySteps { .. }
            | SimError::NonFiniteResult { .. }
            | SimError::Output(_)
    )
}

/// Runs `hdot simulate`.
pub fn run(args: SimulateArgs) -> anyhow::Result<ExitCode> {
    hdot_sim::estimate::set_max_steps(args.max_steps);
    let scene = crate::catalog::scene(&args.scene)?;
    let method = args
        .method
        .as_deref()
        .map(str::parse::<Method>)
        .transpose()?;
    let model = args
        .model
        .as_deref()
        .map(str::parse::<run::Model>)
        .transpose()?;
    let step = match (args.dt, args.tol) {
        (Some(h), _) => Some(Step::Fixed(h).validate()?),
        (_, Some(t)) => Some(Step::Tolerance(t).validate()?),
        _ => None,
    };
    let request = Request {
        model,
        method,
        step,
        t_end: args.t_end,
        check: args.check,
    };
    let plan = run::plan(&scene, &request)?;
    if let Some(page) = &args.html {
        let mut inputs = vec![args.scene.as_path()];
        if let Some(ds) = scene.derivation() {
            inputs.push(ds.derivation.as_path());
        }
        let outputs: Vec<(&str, &std::path::Path)> = args
            .output
            .iter()
            .map(|o| ("--output", o.as_path()))
            .collect();
        crate::html::refuse_page_path(page, &inputs, &outputs)?;
    }

    let mut file = match &args.output {
        // Streamed to a temporary file, renamed into place when the run
        // succeeds: a failed run leaves nothing behind. A file the scene
        // read (the scene, its derivation, a CSV cloud) is refused.
        Some(path) => {
            let cannot = |e| OutputError::new(format!("cannot write {}", path.display()), e);
            let f = output::AtomicFile::create(path).map_err(cannot)?;
            let mut w = BufWriter::new(f);
            writeln!(w, "{}", run::csv_header(&scene, plan.model)).map_err(cannot)?;
            Some(w)
        }
        None => None,
    };
    // A progress bar on a terminal for any run that lasts over a second:
    // made when the first second has passed, moved as each integration of
    // the run (its reference and pilot runs too) advances, and labelled
    // with the one under way.
    let t_end = plan.t_end;
    let started = std::time::Instant::now();
    let terminal = std::io::stderr().is_terminal();
    let mut bar: Option<indicatif::ProgressBar> = None;
    let mut calls = 0u64;
    let mut last: (String, u64) = (String::new(), u64::MAX);
    let mut tick = |what: &str, t: f64| {
        calls += 1;
        if bar.is_none() && calls.is_multiple_of(256) && started.elapsed().as_secs_f64() > 1.0 {
            let b = indicatif::ProgressBar::new(1000);
            b.set_style(
                indicatif::ProgressStyle::with_template("{bar:40} {percent}% {msg} eta {eta}")
                    .expect("valid template"),
            );
            bar = Some(b);
        }
        if let Some(b) = &bar {
            let pos = if t_end > 0.0 {
                (1000.0 * t / t_end) as u64
            } else {
                1000
            };
            if pos != last.1 || what != last.0 {
                if what != last.0 {
                    // A new integration starts again from t = 0.
                    b.reset_eta();
                    last.0 = what.to_string();
                }
                last.1 = pos;
                b.set_position(pos);
                b.set_message(format!("{what}: t={t:.3e} of {t_end:e}"));
            }
        }
    };
    let mut out = Output {
        stream: file.as_mut().map(|w| w as &mut dyn Write),
        store: args.trajectory || args.html.is_some(),
        memory_budget: args.memory_budget,
        progress: terminal.then_some(&mut tick as &mut dyn FnMut(&str, f64)),
    };
    let result = run::run(&scene, &plan, &mut out);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    if let (Some(w), Ok(_)) = (file, &result) {
        let path = args.output.as_deref().unwrap_or(std::path::Path::new("-"));
        let cannot = |e| OutputError::new(format!("cannot write {}", path.display()), e);
        w.into_inner()
            .map_err(|e| cannot(e.into_error()))?
            .commit()
            .map_err(cannot)?;
    }
    let report = match result {
        Ok(r) => r,
        Err(e) if is_input_error(&e) => return Err(e.into()),
        Err(e) => {
            crate::errln!("error: {e}");
            return Ok(ExitCode::from(1));
        }
    };
    if let Some(path) = &args.html {
        // A non-finite sample is a failure of the run (exit 1), as when
        // the run itself ends on one.
        let page = match crate::html::simulation_page(&scene, &report) {
            Ok(page) => page,
            Err(e @ crate::html::PageError::NonFinite { .. }) => {
                crate::errln!("error: {e}");
                return Ok(ExitCode::from(1));
            }
            Err(e) => return Err(e.into()),
        };
        output::write_atomic(path, page.as_bytes())?;
    }
    // The trajectory kept for the page is not printed unless asked for.
    let mut report = report;
    if !args.trajectory {
        report.trajectory = None;
    }
    let text = if args.format == "json" {
        serde_json::to_string_pretty(&report)? + "\n"
    } else {
        report.to_string()
    };
    // A closed pipe (`hdot simulate … | head`) is not an error of the run.
    if let Err(e) = std::io::stdout().lock().write_all(text.as_bytes())
        && e.kind() != std::io::ErrorKind::BrokenPipe
    {
        return Err(e.into());
    }
    // A conserved step that drifts far above the run's error is a false
    // claim (or an unconverged run): a failure, not a number.
    if let Some(d) = report.failed_drifts().first() {
        crate::errln!(
            "error: step `{}` is declared conserved, but it drifts by {:.3e} (relative), more than {}× the error \
             at T ({:.3e})",
            d.name,
            d.relative,
            run::DRIFT_FACTOR,
            report.error.unwrap_or(f64::NAN)
        );
        return Ok(ExitCode::from(1));
    }
    // Without --method, --tol is the error the run must reach. A derived
    // scene given no --tol fits (and tightens) its tolerance to the
    // default; a run that still misses the default is reported, not
    // failed: the user asked for no error.
    let missed = |tol: f64| report.error.is_some_and(|e| e.is_nan() || e > tol);
    match (args.tol, &args.method) {
        (Some(tol), None) if missed(tol) => {
            crate::errln!(
                "error: the requested error {tol:e} is not met: error at T is {:e} ({})",
                report.error.unwrap_or(f64::NAN),
                report.error_basis
            );
            return Ok(ExitCode::from(1));
        }
        (None, None) => {
            if let Some(tol) = report.plan.fit_error.filter(|&t| missed(t)) {
                crate::errln!(
                    "note: the default error {tol:e} (no --tol given) is not reached: error at T is {:e} \
                     ({}); the tolerance was tightened as far as its pilot runs allowed (the report's `why`). \
                     Give --tol to require an error.",
                    report.error.unwrap_or(f64::NAN),
                    report.error_basis
                );
            }
        }
        _ => {}
    }
    Ok(ExitCode::SUCCESS)
}
