//! `hdot check`: run derivations and their expectations, print a table.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;

use crate::catalog;

/// Run derivations and check every expectation; print a table.
///
/// Exit status: 0 when every expectation of every derivation holds, 1 when
/// one does not, 2 when a file cannot be loaded.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Derivation names or paths (default: every bundled derivation).
    #[arg(value_name = "NAME|PATH")]
    targets: Vec<String>,
    /// Folder of derivation files (default: ./derivations).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
}

pub fn run(args: CheckArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let paths = if args.targets.is_empty() {
        catalog::all(&dir)?
    } else {
        args.targets
            .iter()
            .map(|t| catalog::resolve(&dir, t))
            .collect::<anyhow::Result<_>>()?
    };
    println!(
        "{:<30} {:>7} {:>10}  result",
        "derivation", "checks", "time"
    );
    let (mut failed, mut broken) = (0, 0);
    for p in &paths {
        let t0 = Instant::now();
        let r = hdot_sym::derivation::load(p);
        let dt = t0.elapsed();
        let time = format!("{:.2} ms", dt.as_secs_f64() * 1e3);
        match r {
            Ok(d) => {
                let fails = d.failures();
                let status = if fails.is_empty() {
                    "ok".to_owned()
                } else {
                    format!("FAILED ({} of {})", fails.len(), d.check_count())
                };
                println!(
                    "{:<30} {:>7} {:>10}  {}",
                    d.name,
                    d.check_count(),
                    time,
                    status
                );
                for (step, c) in fails {
                    println!(
                        "    {step}{}{}: derived − expected = {}",
                        if c.component.is_empty() { "" } else { "." },
                        c.component,
                        c.difference
                    );
                    failed += 1;
                }
            }
            Err(diag) => {
                println!("{:<30} {:>7} {:>10}  ERROR", catalog::name_of(p), "-", time);
                eprintln!("{diag}");
                broken += 1;
            }
        }
    }
    println!(
        "{} derivations, {} failed expectations, {} files with errors",
        paths.len(),
        failed,
        broken
    );
    Ok(if broken > 0 {
        ExitCode::from(2)
    } else if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
