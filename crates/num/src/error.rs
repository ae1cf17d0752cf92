//! Typed errors of the numeric crate. Every error that comes from a file
//! names the file, the line and the field.

use std::path::PathBuf;

use crate::inertia::InertiaError;

/// A body, cloud or mass property that is not physical.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BodyError {
    /// A mass is zero or negative.
    #[error("{what}: mass must be positive, got {value}")]
    NonPositiveMass {
        /// What carries the mass (e.g. `particle 3`, `disk`).
        what: String,
        /// The value given.
        value: f64,
    },
    /// A mass below f64's normal range (a subnormal): its moments
    /// underflow, so the mass centre and inertia would be silently wrong.
    #[error(
        "{what}: mass {value:e} is below the normal range of f64 (about 2.2e-308): its moments underflow; rescale the units"
    )]
    TinyMass {
        /// What carries the mass.
        what: String,
        /// The value given.
        value: f64,
    },
    /// A dimension is negative, zero where it must not be, or
    /// inconsistent (inner radius above outer).
    #[error("{what}: invalid dimension {field} = {value} ({reason})")]
    BadDimension {
        /// The body.
        what: String,
        /// The dimension's name.
        field: &'static str,
        /// The value given.
        value: f64,
        /// Why it is invalid.
        reason: &'static str,
    },
    /// A value is NaN or infinite.
    #[error("{what}: {field} is not finite ({value})")]
    NotFinite {
        /// The body or particle.
        what: String,
        /// The field's name.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A cloud or composite without any mass.
    #[error("{what}: empty (no particles or parts)")]
    Empty {
        /// The cloud or composite.
        what: String,
    },
    /// The resulting inertia tensor is not physical.
    #[error("{what}: {source}")]
    Inertia {
        /// The body.
        what: String,
        /// The violated invariant.
        source: InertiaError,
    },
}

/// A line of a particle CSV file that cannot be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: field `{field}`: {kind}", at(file, *line))]
pub struct CsvError {
    /// The file (or the name given to a string source).
    pub file: PathBuf,
    /// 1-based line number (0 when the problem is the whole file).
    pub line: usize,
    /// The field: `x`, `y`, `z`, `m`, or `-` for the whole line/file.
    pub field: String,
    /// What is wrong.
    pub kind: CsvErrorKind,
}

/// What is wrong with a CSV field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CsvErrorKind {
    /// The file could not be read, or is not UTF-8 text (the message
    /// says which, and where).
    #[error("{0}")]
    Io(String),
    /// Fewer than four fields on the line.
    #[error("missing (expected 4 fields x,y,z,m)")]
    Missing,
    /// More than four fields on the line.
    #[error("too many fields ({0}; expected 4: x,y,z,m)")]
    TooMany(usize),
    /// Not a number.
    #[error("not a number: {0:?}")]
    NotANumber(String),
    /// NaN or infinite.
    #[error("not finite: {0}")]
    NotFinite(f64),
    /// Mass zero or negative.
    #[error("mass must be positive, got {0}")]
    NonPositiveMass(f64),
    /// A mass below f64's normal range: its products with the coordinates
    /// underflow, so the sums would be silently wrong.
    #[error(
        "mass {0:e} is below the normal range of f64 (about 2.2e-308): its moments underflow; rescale the units"
    )]
    TinyMass(f64),
    /// No particle in the file.
    #[error("no particles in file")]
    Empty,
    /// The particles' sums overflow (their total mass, first or second
    /// moments are not finite), named: `mass`, `mass centre`, `inertia`.
    #[error("the particles' {0} is not finite (the sums over the file overflow)")]
    Overflow(&'static str),
}

/// `file:line`, or just `file` when the line is not known (0): a message
/// never points at a line 0 that no editor shows.
pub fn at(file: &std::path::Path, line: usize) -> String {
    if line == 0 {
        file.display().to_string()
    } else {
        format!("{}:{line}", file.display())
    }
}
