//! `hdot verify [NAME…] [--bodies N] [--seed S]`: each derivation with a
//! numeric meaning, evaluated on random bodies and states with its symbols
//! bound from particle sums, against the direct particle sums of the same
//! particles. Prints the bodies tried and the largest relative error per
//! derivation, and under it the steps compared with kinematics rather than
//! particle sums and the steps not compared (all steps with `--steps`);
//! exit 1 when one fails.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_num::verify::{TOLERANCE_ULPS, coverage, is_supported, verify};

use crate::catalog;

/// Arguments of `hdot verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Derivations to verify (names in the derivations folder, or paths);
    /// all bundled ones when omitted.
    pub names: Vec<String>,
    /// Random bodies per derivation (at least 1: zero would pass without
    /// checking anything).
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..))]
    pub bodies: u64,
    /// Seed of the ChaCha generator.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// The derivations folder (default: `$HDOT_DERIVATIONS`, then `./derivations`).
    #[arg(long)]
    pub dir: Option<PathBuf>,
    /// Also list the steps compared with particle sums, and what with.
    #[arg(long)]
    pub steps: bool,
}

/// Runs the checks. Exit 1 when a derivation fails; 2 on bad input.
pub fn run(args: VerifyArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let paths = if args.names.is_empty() {
        catalog::all(&dir)?
    } else {
        args.names
            .iter()
            .map(|n| catalog::resolve(&dir, n))
            .collect::<anyhow::Result<Vec<_>>>()?
    };
    let checked = paths.iter().filter(|p| is_supported(&p.name())).count();
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(checked as u64 * args.bodies);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}")
                .expect("valid template"),
        );
        bar
    });
    crate::outln!(
        "{:<36} {:>7} {:>12}  result (tolerance {TOLERANCE_ULPS} ulps of the magnitudes)",
        "derivation",
        "bodies",
        "max rel err"
    );
    let mut code = ExitCode::SUCCESS;
    for p in &paths {
        let name = p.name();
        let d = match p.load() {
            Ok(d) => d,
            Err(e) => anyhow::bail!("{e}"),
        };
        if let Some(b) = &bar {
            b.set_message(name.clone());
        }
        let mut tick = || {
            if let Some(b) = &bar {
                b.inc(1);
            }
        };
        match verify(&d, args.bodies as usize, args.seed, &mut tick) {
            None => crate::outln!("{name:<36} {:>7} {:>12}  skipped: no binding", "-", "-"),
            Some(Err(e)) => {
                crate::outln!("{name:<36} {:>7} {:>12}  error: {e}", "-", "-");
                code = ExitCode::FAILURE;
            }
            Some(Ok(o)) => {
                let verdict = if o.passed {
                    "pass".to_string()
                } else {
                    code = ExitCode::FAILURE;
                    match &o.worst {
                        Some(w) => format!(
                            "FAIL at {}: derived {:e}, direct {:e}",
                            w.quantity, w.derived, w.direct
                        ),
                        None => "FAIL".into(),
                    }
                };
                crate::outln!(
                    "{name:<36} {:>7} {:>12.3e}  {verdict}",
                    o.bodies,
                    o.max_error
                );
            }
        }
        if let Some(c) = coverage(&name) {
            if args.steps {
                for (steps, against) in c.compared {
                    crate::outln!("    {steps}: against {against}");
                }
            }
            for (steps, against) in c.kinematic {
                crate::outln!("    {steps}: kinematics, against {against} (no particle sum)");
            }
            for (steps, why) in c.not_compared {
                crate::outln!("    {steps}: not compared, {why}");
            }
        }
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(code)
}
