//! `hdot inertia SCENE`: mass, centre, inertia about G and O, principal
//! moments and axes of a scene's body.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Args, ValueEnum};
use hdot_num::report::Report;
use hdot_num::scene::Scene;

/// Output format of the numeric commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum NumFormat {
    /// Aligned text for reading.
    Text,
    /// JSON with the keys documented in docs/cli-numeric.md.
    Json,
}

// Arguments of `hdot inertia`.
#[derive(Debug, Args)]
pub struct InertiaArgs {
    /// Scene file (TOML), e.g. docs/examples/rod-on-axle.toml.
    pub scene: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value_t = NumFormat::Text)]
    pub format: NumFormat,
    /// Significant digits in text output (1 to 17: an f64 holds no more).
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u8).range(1..=17))]
    pub digits: u8,
}

/// Prints the mass properties. Exit 2 on a bad scene.
pub fn run(args: InertiaArgs) -> anyhow::Result<ExitCode> {
    let scene = Scene::from_path(&args.scene)?;
    let report = Report::inertia(&scene);
    if let Some(q) = report.non_finite() {
        crate::errln!(
            "error: {}: {q} is not a finite number (the scene's values are too large or too small for it)",
            args.scene.display()
        );
        return Ok(ExitCode::from(1));
    }
    print_report(&report, args.format, usize::from(args.digits))?;
    Ok(ExitCode::SUCCESS)
}

/// Prints a report in the chosen format.
pub fn print_report(report: &Report, format: NumFormat, digits: usize) -> anyhow::Result<()> {
    match format {
        NumFormat::Text => crate::out!("{}", report.text(digits)),
        NumFormat::Json => crate::outln!(
            "{}",
            serde_json::to_string_pretty(report).context("serialising the report")?
        ),
    }
    Ok(())
}
