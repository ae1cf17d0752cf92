//! `hdot convergence [--out DIR] [--tol T]`: error of the discretised
//! inertia of each bundled primitive against the analytic value, observed
//! orders, charts (error vs particles and vs time, one line per method),
//! and with `--tol` the cheapest discretisation meeting the tolerance.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_num::convergence::{
    METHODS, PrimitiveSweeps, bundled_primitives, cheapest_meeting, observed_orders, stage_charts,
    sweep,
};

use crate::output::{self, OutputError};

// Arguments of `hdot convergence`.
#[derive(Debug, Args)]
pub struct ConvergenceArgs {
    /// Directory for the charts (`<primitive>-error-vs-{particles,time}.{svg,png}`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Report, per primitive, the cheapest discretisation whose relative
    /// inertia error is at most T.
    #[arg(long, value_name = "T")]
    pub tol: Option<f64>,
    /// Largest number of particles tried per discretisation (1,000 to
    /// 20,000,000: fewer draws no chart, more holds gigabytes).
    #[arg(long, default_value_t = 2_000_000, value_parser = clap::value_parser!(u64).range(1_000..=MAX_PARTICLES))]
    pub max_particles: u64,
}

/// The largest `--max-particles` (see docs/cli.md's table of limits): a
/// discretisation of that many particles holds about a gigabyte.
pub const MAX_PARTICLES: u64 = 20_000_000;

/// Runs the sweeps. Exit 1 when some primitive cannot meet `--tol`
/// within `--max-particles`; 2 on a bad option.
pub fn run(args: ConvergenceArgs) -> anyhow::Result<ExitCode> {
    let max_particles = usize::try_from(args.max_particles).unwrap_or(usize::MAX);
    if let Some(t) = args.tol
        && (t.is_nan() || t <= 0.0 || t.is_infinite())
    {
        anyhow::bail!("--tol must be a positive number, got {t}");
    }
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir)
            .map_err(|e| OutputError::new(format!("cannot create {}", dir.display()), e))?;
    }
    let shapes = bundled_primitives();
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new((shapes.len() * METHODS.len()) as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}")
                .expect("valid template"),
        );
        bar
    });
    let mut code = ExitCode::SUCCESS;
    let mut batch = output::Batch::new();
    let mut written = Vec::new();
    for shape in &shapes {
        let mut sweeps = Vec::new();
        crate::outln!("{}", shape.name());
        for &method in &METHODS {
            if let Some(b) = &bar {
                b.set_message(format!("{} {method}", shape.name()));
            }
            let pts = sweep(shape, method, max_particles);
            let orders = observed_orders(&pts);
            let last = pts.last();
            let verdict = match (last, orders.iter().rev().flatten().next()) {
                (Some(p), _) if p.error < 1e-13 => "exact to round-off".to_string(),
                (_, Some(o)) => format!("observed order {o:.2}"),
                _ => "-".to_string(),
            };
            crate::outln!(
                "  {:<18} finest {:>9} particles  error {:>9}  {verdict}",
                method.to_string(),
                last.map_or(0, |p| p.particles),
                last.map_or("-".into(), |p| format!("{:.2e}", p.error)),
            );
            sweeps.push((method, pts));
            if let Some(b) = &bar {
                b.inc(1);
            }
        }
        if let Some(tol) = args.tol {
            match cheapest_meeting(shape, tol, &METHODS, max_particles) {
                Some(p) => crate::outln!(
                    "  cheapest for tol {tol:e}: {} with {} cells per parameter, {} particles, error {:.2e}",
                    p.disc.method,
                    p.disc.cells,
                    p.particles,
                    p.error
                ),
                None => {
                    crate::outln!(
                        "  no discretisation within {} particles meets tol {tol:e}",
                        args.max_particles
                    );
                    code = ExitCode::from(1);
                }
            }
        }
        if let Some(dir) = &args.out {
            let stems = stage_charts(
                &mut batch,
                dir,
                &PrimitiveSweeps {
                    shape: *shape,
                    sweeps,
                },
            )
            .map_err(|e| {
                OutputError::new(
                    "cannot write the charts",
                    std::io::Error::other(e.to_string()),
                )
            })?;
            written.extend(stems);
        }
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    // Every chart appears, or none does.
    batch
        .commit()
        .map_err(|e| OutputError::new("cannot write the charts", e))?;
    for s in written {
        crate::outln!("wrote {}.{{svg,png}}", s.display());
    }
    Ok(code)
}
