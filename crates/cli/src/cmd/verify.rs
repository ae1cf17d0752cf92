//! `hdot verify [NAME…] [--bodies N] [--seed S] [--require]`: every step
//! that declares a meaning (`means`, docs/derivation-format.md), evaluated
//! on random bodies and motions drawn from the file's declarations with its
//! symbols bound from particle sums, against the measured quantity. Prints
//! the draws and the largest relative error per derivation, the steps
//! compared (with `--steps`: each with what it was compared with) and the
//! steps not compared; exit 1 when one fails, or under `--require` when a
//! file compares nothing. Nothing depends on the file's name.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_num::verify::{Options, TOLERANCE_ULPS, check_with};

use crate::catalog;

/// The largest `--bodies` (see docs/cli.md's table of limits).
pub const MAX_BODIES: u64 = 100_000;

// Arguments of `hdot verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Derivations to verify (names in the derivations folder, paths, or
    /// folders of derivation files); all bundled ones when omitted.
    pub names: Vec<String>,
    /// Random bodies per derivation (1 to 100,000: zero would pass without
    /// checking anything, and each body is a full particle sum).
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..=MAX_BODIES))]
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
    /// Fail (exit 1) when a file has no step that is compared.
    #[arg(long)]
    pub require: bool,
}

/// Runs the checks. Exit 1 when a derivation fails; 2 on bad input.
pub fn run(args: VerifyArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let paths = catalog::select(&dir, &args.names)?;
    let checked = paths.len();
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
            // The diagnostic carries its own `error:` (as `derive` prints it).
            Err(diag) => {
                if let Some(b) = &bar {
                    b.finish_and_clear();
                }
                crate::errln!("{diag}");
                return Ok(ExitCode::from(2));
            }
        };
        if let Some(b) = &bar {
            b.set_message(name.clone());
        }
        let mut tick = || {
            if let Some(b) = &bar {
                b.inc(1);
            }
        };
        let options = Options {
            draws: args.bodies as usize,
            seed: args.seed,
        };
        match check_with(&d, &options, &mut tick) {
            Err(e) => {
                crate::outln!("{name:<36} {:>7} {:>12}  error: {e}", "-", "-");
                code = ExitCode::FAILURE;
            }
            Ok(r) if r.steps.is_empty() => {
                if args.require {
                    code = ExitCode::FAILURE;
                }
                crate::outln!("{name:<36} {:>7} {:>12}  nothing compared", "-", "-");
                if let Some(h) = r.hint(&d) {
                    crate::outln!("    {h}");
                }
            }
            Ok(r) => {
                let verdict = if r.passed() {
                    "pass".to_string()
                } else {
                    code = ExitCode::FAILURE;
                    match r.worst() {
                        Some(w) => format!(
                            "FAIL at {}: derived {:e}, measured {:e}",
                            w.quantity, w.derived, w.direct
                        ),
                        // A failed step without a comparison (a claim
                        // with nothing to check it against): named, its
                        // line below says why.
                        None => r
                            .first_failure()
                            .map_or_else(|| "FAIL".into(), |s| format!("FAIL at {}", s.step)),
                    }
                };
                crate::outln!(
                    "{name:<36} {:>7} {:>12.3e}  {verdict}",
                    r.draws,
                    r.max_error()
                );
                for s in &r.steps {
                    if args.steps || !s.passed {
                        let conditions = if s.conditions.is_empty() {
                            String::new()
                        } else {
                            format!(" [{}]", s.conditions)
                        };
                        crate::outln!(
                            "    {}: {}{conditions} ({}), max rel err {:.3e}{}",
                            s.step,
                            s.means,
                            s.against,
                            s.max_error,
                            if s.passed { "" } else { "  FAIL" }
                        );
                    }
                }
                if !r.not_compared.is_empty() {
                    crate::outln!(
                        "    not compared (no meaning): {}",
                        r.not_compared.join(", ")
                    );
                }
            }
        }
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(code)
}
