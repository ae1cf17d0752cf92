//! `hdot list`: the bundled derivations with title and source.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use crate::catalog;

// List the bundled derivations with their titles and sources.
#[derive(Debug, Args)]
pub struct ListArgs {
    /// Folder of derivation files (default: ./derivations).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
}

pub fn run(args: ListArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let mut failed = false;
    for p in catalog::all(&dir)? {
        match p.load() {
            Ok(d) => crate::outln!(
                "{:<28} {}\n{:<28} source: {}",
                d.name,
                d.title,
                "",
                d.source
            ),
            Err(e) => {
                failed = true;
                crate::outln!("{:<28} (does not load: {})", p.name(), e.message);
            }
        }
    }
    crate::outln!(
        "{:<28} Chain of K bodies: Ḣ in the inertial frame (generated scaling family)\n{:<28} source: hdot_sym::chain (K = 1…{})",
        "chain-K",
        "",
        hdot_sym::chain::MAX_K
    );
    Ok(if failed {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
