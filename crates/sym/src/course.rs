//! The notes manifest (`notes.toml` in a derivations folder): how a
//! lecturer's derivations become a course — title, author line, chapters
//! in teaching order, and which steps to show.
//!
//! ```toml
//! title = "Kinetics of rigid bodies in three dimensions"
//! author = "Dynamics II, lecture notes"
//! intro = "Optional prose before the first chapter."
//!
//! [[chapter]]
//! title = "Angular momentum"
//! intro = "Optional prose before the chapter's first derivation."
//! derivations = ["angular-momentum", "angular-momentum-about-point"]
//!
//! [steps]                       # optional: the steps to show, by file
//! heavy-top = ["SigmaM", "accelerations"]
//! ```
//!
//! Derivations are named by file stem. A name that is not among the
//! derivations, a step that is not in its file, or a derivation listed
//! twice is an error at its line and column; derivations the manifest does
//! not list follow in a last chapter, *Further derivations*.
//!
//! # Example
//! ```
//! let text = "title = \"T\"\nauthor = \"A\"\n[[chapter]]\ntitle = \"C\"\nderivations = [\"x\"]\n";
//! let err = hdot_sym::course::parse("notes.toml", text, &[]).unwrap_err();
//! assert_eq!((err.line, err.column), (5, 17));
//! assert!(err.message.contains("no derivation `x`"));
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::derivation::{Derivation, Diagnostic};
use crate::document::Course;

/// The file name of the manifest in a derivations folder.
pub const MANIFEST_FILE: &str = "notes.toml";

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    title: String,
    #[serde(default)]
    author: String,
    #[serde(default)]
    intro: String,
    #[serde(default)]
    chapter: Vec<RawChapter>,
    #[serde(default)]
    steps: BTreeMap<Spanned<String>, Vec<Spanned<String>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChapter {
    title: String,
    #[serde(default)]
    intro: String,
    derivations: Vec<Spanned<String>>,
}

/// Reads the manifest at `path` and checks it against `ds`.
pub fn load(path: &Path, ds: &[Derivation]) -> Result<Course, Diagnostic> {
    let shown = path.display().to_string();
    let text = crate::textfile::read(path).map_err(|e| Diagnostic::read(&shown, e))?;
    parse(&shown, &text, ds)
}

/// Parses a manifest given as text (`path` names it in messages) and
/// checks every name against `ds`.
pub fn parse(path: &str, text: &str, ds: &[Derivation]) -> Result<Course, Diagnostic> {
    let raw: Raw = toml::from_str(text).map_err(|e| {
        let span = e.span().unwrap_or(0..0);
        Diagnostic::at(
            path,
            text,
            span.start,
            span.end,
            format!("invalid notes manifest: {}", e.message().trim()),
        )
    })?;
    let at = |s: &Spanned<String>, msg: String| {
        let r = s.span();
        // The span covers the quotes; point at the name.
        Diagnostic::at(path, text, r.start + 1, r.end.saturating_sub(1), msg)
    };
    let find = |s: &Spanned<String>| -> Result<&Derivation, Diagnostic> {
        ds.iter().find(|d| d.name == *s.get_ref()).ok_or_else(|| {
            at(
                s,
                format!(
                    "no derivation `{}` among the files given (names are file stems, such as `{}`)",
                    s.get_ref(),
                    ds.first().map_or("euler-principal", |d| d.name.as_str())
                ),
            )
        })
    };
    let mut seen: Vec<&str> = Vec::new();
    let mut chapters = Vec::new();
    for c in &raw.chapter {
        let mut names = Vec::new();
        for n in &c.derivations {
            find(n)?;
            if seen.contains(&n.get_ref().as_str()) {
                return Err(at(
                    n,
                    format!("derivation `{}` is listed twice", n.get_ref()),
                ));
            }
            seen.push(n.get_ref());
            names.push(n.get_ref().clone());
        }
        chapters.push((c.title.clone(), c.intro.clone(), names));
    }
    let mut steps = BTreeMap::new();
    for (d, list) in &raw.steps {
        let deriv = find(d)?;
        for s in list {
            if !deriv.steps.iter().any(|x| x.name == *s.get_ref()) {
                let known: Vec<&str> = deriv.steps.iter().map(|x| x.name.as_str()).collect();
                return Err(at(
                    s,
                    format!(
                        "derivation `{}` has no step `{}` (its steps: {})",
                        d.get_ref(),
                        s.get_ref(),
                        known.join(", ")
                    ),
                ));
            }
        }
        steps.insert(
            d.get_ref().clone(),
            list.iter().map(|s| s.get_ref().clone()).collect(),
        );
    }
    Ok(Course {
        title: raw.title,
        author: raw.author,
        intro: raw.intro,
        chapters,
        steps,
    })
}
