//! Writing results: to standard output, or to files through the one
//! atomic-write helper of the workspace ([`hdot_num::fsio`]).
//!
//! A failure to write a result is an [`OutputError`]: `main` ends the
//! command quietly with exit 0 when standard output was closed by its
//! reader (`hdot list | head -1`), with exit 2 when the output is one of
//! the command's inputs (refused before anything is written), and with
//! exit 1 on any other write failure (a full disk, an unwritable `--out`).

use std::io::Write;
use std::path::Path;

pub use hdot_num::fsio::{AtomicFile, Batch};

/// A result could not be written (as opposed to bad input).
#[derive(Debug, thiserror::Error)]
#[error("{context}")]
pub struct OutputError {
    /// What was being written.
    pub context: String,
    /// The failure.
    #[source]
    pub source: std::io::Error,
}

impl OutputError {
    /// Wraps a write failure of `what`.
    pub fn new(what: impl std::fmt::Display, source: std::io::Error) -> OutputError {
        OutputError {
            context: what.to_string(),
            source,
        }
    }

    /// Whether the reader of standard output went away (not an error of
    /// the command).
    pub fn is_closed_stdout(&self) -> bool {
        self.context == STDOUT && self.source.kind() == std::io::ErrorKind::BrokenPipe
    }

    /// Whether the output is a file the command read (exit 2: the command
    /// line is wrong; nothing was written). Every write refuses one
    /// ([`hdot_num::fsio`]).
    pub fn is_input_refusal(&self) -> bool {
        hdot_num::fsio::is_input_refusal(&self.source)
    }
}

const STDOUT: &str = "writing to standard output";

/// Writes formatted text to standard output.
pub fn stdout_fmt(args: std::fmt::Arguments<'_>) -> Result<(), OutputError> {
    let mut so = std::io::stdout().lock();
    so.write_fmt(args)
        .and_then(|()| so.flush())
        .map_err(|e| OutputError::new(STDOUT, e))
}

/// `print!` that returns an [`OutputError`] instead of panicking.
#[macro_export]
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::output::stdout_fmt(format_args!($($arg)*))?
    };
}

/// `println!` that returns an [`OutputError`] instead of panicking.
#[macro_export]
macro_rules! outln {
    () => {
        $crate::output::stdout_fmt(format_args!("\n"))?
    };
    ($($arg:tt)*) => {
        $crate::output::stdout_fmt(format_args!("{}\n", format_args!($($arg)*)))?
    };
}

/// `eprintln!` that never panics: a message for a standard error whose
/// reader has gone is dropped, so the command still ends with the exit
/// code it documents (`eprintln!` would panic, exit 101).
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => {{
        use ::std::io::Write as _;
        let _ = ::std::writeln!(::std::io::stderr(), $($arg)*);
    }};
}

/// Writes `text` to `out` atomically, or to standard output when `out` is `None`.
pub fn emit(out: Option<&Path>, text: &str) -> Result<(), OutputError> {
    match out {
        None => stdout_fmt(format_args!("{text}")),
        Some(path) => write_atomic(path, text.as_bytes()),
    }
}

/// Writes `bytes` to `path` atomically (temp file + rename; links
/// followed, special files in place).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    hdot_num::fsio::write_atomic(path, bytes)
        .map_err(|e| OutputError::new(format!("cannot write {}", path.display()), e))
}
