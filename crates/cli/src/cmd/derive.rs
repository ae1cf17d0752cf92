//! `hdot derive`: run one derivation and print it.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, ValueEnum};
use hdot_sym::render::{Format, render};

use crate::{catalog, output};

/// Output formats of `hdot derive`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum FormatArg {
    /// Unicode text for a terminal.
    Unicode,
    /// LaTeX align* blocks for lecture notes.
    Latex,
    /// Markdown with $$ math.
    Markdown,
    /// Python source that rebuilds the equations with sympy.
    Sympy,
    /// Machine-readable JSON.
    Json,
}

// Derive the equations of one derivation and print them in textbook form.
//
// Exit status: 0 when every expectation holds, 1 when one does not (the
// output is still printed and the failing components are named on
// stderr), 2 when the file cannot be read or has an error.
#[derive(Debug, Args)]
pub struct DeriveArgs {
    /// A bundled derivation's name (see `hdot list`), `chain-K` (K = 1…8), or a path to a .toml file.
    #[arg(value_name = "NAME|PATH")]
    target: String,
    /// Output format.
    #[arg(long, short, value_enum, default_value = "unicode")]
    format: FormatArg,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long, short, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Folder of derivation files (default: ./derivations).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
}

pub fn run(args: DeriveArgs) -> anyhow::Result<ExitCode> {
    let dir = catalog::derivations_dir(args.dir.as_deref());
    let d = match catalog::load(&dir, &args.target)? {
        Ok(d) => d,
        Err(diag) => {
            crate::errln!("{diag}");
            return Ok(ExitCode::from(2));
        }
    };
    let format = match args.format {
        FormatArg::Unicode => Format::Unicode,
        FormatArg::Latex => Format::Latex,
        FormatArg::Markdown => Format::Markdown,
        FormatArg::Sympy => Format::Sympy,
        FormatArg::Json => Format::Json,
    };
    let text = render(&d, format);
    output::emit(args.out.as_deref(), &text)?;
    let failures = d.failures();
    for (step, c) in &failures {
        crate::errln!(
            "expectation failed: {}{}{}: derived − expected = {}",
            step,
            if c.component.is_empty() { "" } else { "." },
            c.component,
            c.difference
        );
    }
    let code = if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    };
    drop(failures);
    // The command ends with the process: freeing a large derivation piece
    // by piece (chain-8: a million allocations, 2 % of the run) would only
    // hand memory back to a process about to exit.
    std::mem::forget(d);
    Ok(code)
}
