//! `hdot dynamics SCENE`: H_G, H_O, T, the resultant force and moment a
//! motion requires (checked against particle sums), and the unknown forces
//! and couples solved by a linear solve with a rank check.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_num::report::Report;
use hdot_num::scene::Scene;

use super::inertia::{NumFormat, print_report};

// Arguments of `hdot dynamics`.
#[derive(Debug, Args)]
pub struct DynamicsArgs {
    /// Scene file (TOML), e.g. docs/examples/rolling-disk.toml.
    pub scene: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value_t = NumFormat::Text)]
    pub format: NumFormat,
    /// Significant digits in text output (1 to 17: an f64 holds no more).
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u8).range(1..=17))]
    pub digits: u8,
}

/// Prints the report. Exit 1 when the unknowns are underdetermined or
/// inconsistent or the particle-sum check fails; 2 on a bad scene.
pub fn run(args: DynamicsArgs) -> anyhow::Result<ExitCode> {
    let scene = Scene::from_path(&args.scene)?;
    let report = Report::dynamics(&scene);
    if let Some(q) = report.non_finite() {
        crate::errln!(
            "error: {}: {q} is not a finite number (the scene's values are too large or too small for it)",
            args.scene.display()
        );
        return Ok(ExitCode::from(1));
    }
    print_report(&report, args.format, usize::from(args.digits))?;
    let check_failed = report
        .particle_check
        .is_some_and(|c| c.is_nan() || c > 1e-9);
    if report.unsolved.is_some() || check_failed {
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}
