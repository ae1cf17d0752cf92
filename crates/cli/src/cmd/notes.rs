//! `hdot notes`: every derivation, step by step, as lecture notes in
//! LaTeX and Markdown.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_sym::notes;

use crate::{catalog, output};

/// Write the lecture notes: every derivation step by step, as a LaTeX
/// document (`hdot-notes.tex`) and as Markdown with $$ math (`hdot-notes.md`).
///
/// Exit status: 0 when written; 2 when a derivation file cannot be read or
/// has an error (then nothing is written). A derivation whose expectation
/// does not hold is still written, marked as such, and named on stderr.
#[derive(Debug, Args)]
pub struct NotesArgs {
    /// Folder to write hdot-notes.tex and hdot-notes.md into.
    #[arg(long, short, value_name = "DIR", default_value = "docs/notes")]
    out: PathBuf,
    /// Folder of derivation files (default: ./derivations).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
}

pub fn run(args: NotesArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let mut ds = Vec::new();
    for path in catalog::all(&dir)? {
        match hdot_sym::derivation::load(&path) {
            Ok(d) => ds.push(d),
            Err(diag) => {
                eprintln!("{diag}");
                eprintln!("error: no notes written");
                return Ok(ExitCode::from(2));
            }
        }
    }
    let tex = notes::latex_document(&ds);
    let md = notes::markdown_document(&ds);
    let tex_path = args.out.join(notes::LATEX_FILE);
    let md_path = args.out.join(notes::MARKDOWN_FILE);
    output::write_atomic(&tex_path, tex.as_bytes())?;
    output::write_atomic(&md_path, md.as_bytes())?;
    for d in &ds {
        for (step, c) in d.failures() {
            eprintln!(
                "warning: {}: expectation does not hold: {}{}{}",
                d.path,
                step,
                if c.component.is_empty() { "" } else { "." },
                c.component
            );
        }
    }
    println!(
        "wrote {} and {} ({} derivations)",
        tex_path.display(),
        md_path.display(),
        ds.len()
    );
    Ok(ExitCode::SUCCESS)
}
