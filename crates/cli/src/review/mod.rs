//! Review of changes to derivation files (`hdot diff`, `hdot snapshot`):
//! two versions of a derivation compared step by step by canonical
//! equality ([`compare`]), reported as text, Markdown or JSON
//! ([`report`]); the versions come from files, from a git revision
//! ([`git`]), or from a snapshot file ([`snapshot`]).

pub mod compare;
pub mod git;
pub mod report;
pub mod snapshot;

use hdot_sym::derivation::{Derivation, Diagnostic};

use compare::{Change, Version};
use report::FileDiff;

/// A version of a derivation that does not load.
#[derive(Debug)]
pub struct LoadFailure {
    /// `old` or `new`.
    pub which: &'static str,
    /// How that version is named (a path, or `REV:path`).
    pub name: String,
    /// Where and why.
    pub diagnostic: Box<Diagnostic>,
}

/// Loads the text `text` of the version named `name`.
fn load(which: &'static str, name: &str, text: &str) -> Result<Derivation, LoadFailure> {
    hdot_sym::derivation::load_str(name, text).map_err(|diagnostic| LoadFailure {
        diagnostic: Box::new(diagnostic),
        which,
        name: name.to_owned(),
    })
}

/// Compares two versions of a derivation file, each `(name, text)` or
/// `None` for a file that is not there on that side.
pub fn compare_files(
    old: Option<(&str, &str)>,
    new: Option<(&str, &str)>,
) -> Result<FileDiff, LoadFailure> {
    let old_d = old.map(|(n, t)| load("old", n, t)).transpose()?;
    let new_d = new.map(|(n, t)| load("new", n, t)).transpose()?;
    let old_v = old_d.as_ref().map(Version::of).unwrap_or_default();
    let new_v = new_d.as_ref().map(Version::of).unwrap_or_default();
    let steps = compare::compare(&old_v, &new_v, new_d.as_ref());
    Ok(FileDiff {
        old: old.map(|(n, _)| n.to_owned()),
        new: new.map(|(n, _)| n.to_owned()),
        change: compare::file_change(old.is_some(), new.is_some(), &steps),
        steps,
    })
}

/// An unchanged file (same text on both sides): nothing to load.
pub fn unchanged(old: &str, new: &str) -> FileDiff {
    FileDiff {
        old: Some(old.to_owned()),
        new: Some(new.to_owned()),
        change: Change::Unchanged,
        steps: Vec::new(),
    }
}
