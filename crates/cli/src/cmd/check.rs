//! `hdot check`: run derivations and their expectations, print a table.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;

use crate::catalog;

// Run derivations and check every expectation; print a table.
//
// Exit status: 0 when every expectation of every derivation holds, 1 when
// one does not, 2 when a file cannot be loaded.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Derivation names, paths, or folders of derivation files (default:
    /// every bundled derivation).
    #[arg(value_name = "NAME|PATH")]
    targets: Vec<String>,
    /// Folder of derivation files (default: ./derivations).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
}

pub fn run(args: CheckArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let paths = catalog::select(&dir, &args.targets)?;
    crate::outln!(
        "{:<30} {:>7} {:>10}  result",
        "derivation",
        "checks",
        "time"
    );
    let (mut failed, mut broken) = (0, 0);
    for p in &paths {
        let t0 = Instant::now();
        // A file that crashes the loader (a bug: its message is on stderr)
        // is one row of the table; the others are still checked.
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| p.load()));
        let dt = t0.elapsed();
        let time = format!("{:.2} ms", dt.as_secs_f64() * 1e3);
        match r {
            Err(_) => {
                crate::outln!(
                    "{:<30} {:>7} {:>10}  CRASHED (internal error; please report)",
                    p.name(),
                    "-",
                    time
                );
                broken += 1;
            }
            Ok(Ok(d)) => {
                let fails = d.failures();
                let status = if fails.is_empty() {
                    "ok".to_owned()
                } else {
                    format!("FAILED ({} of {})", fails.len(), d.check_count())
                };
                crate::outln!(
                    "{:<30} {:>7} {:>10}  {}",
                    d.name,
                    d.check_count(),
                    time,
                    status
                );
                for (step, c) in fails {
                    crate::outln!(
                        "    {step}{}{}: derived − expected = {}",
                        if c.component.is_empty() { "" } else { "." },
                        c.component,
                        c.difference
                    );
                    failed += 1;
                }
            }
            Ok(Err(diag)) => {
                crate::outln!("{:<30} {:>7} {:>10}  ERROR", p.name(), "-", time);
                crate::errln!("{diag}");
                broken += 1;
            }
        }
    }
    crate::outln!(
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
