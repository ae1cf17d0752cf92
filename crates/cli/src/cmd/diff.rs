//! `hdot diff OLD NEW` and `hdot diff --git REV [PATHS]`: what changed in
//! the mathematics of derivation files — for every step and component,
//! unchanged, the same mathematics in a new presentation, different
//! mathematics (with NEW − OLD in textbook form), added or removed — as
//! text, Markdown for a pull-request comment, or JSON.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::bail;
use clap::{Args, ValueEnum};

use crate::catalog::{self, FileKind};
use crate::review::compare::Change;
use crate::review::git::Repo;
use crate::review::report::{self, FileDiff, ReportFormat};
use crate::review::{self as rv, LoadFailure};

/// What makes `hdot diff` exit 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FailOn {
    /// A step or component whose mathematics differs, added or removed.
    Mathematics,
    /// That, or a change of presentation only.
    Presentation,
}

// Compare two versions of derivation files step by step by canonical
// equality: two files (`hdot diff OLD NEW`), or every derivation file of
// the working tree against a git revision (`hdot diff --git REV
// [PATHS]`). Scenes and notes manifests are skipped.
//
// Exit status: 0 when nothing differs mathematically (under
// `--fail-on presentation`: when nothing differs at all), 1 otherwise, 2
// on bad input (a version that does not load, a revision that does not
// exist, a path outside the repository).
#[derive(Debug, Args)]
pub struct DiffArgs {
    /// OLD and NEW derivation files; with `--git`, files or folders of the
    /// working tree to compare (default: the whole repository).
    #[arg(value_name = "OLD NEW | PATHS")]
    paths: Vec<PathBuf>,
    /// Compare the working tree with this git revision (commit, branch, tag).
    #[arg(long, value_name = "REV")]
    git: Option<String>,
    /// Output format.
    #[arg(long, short, value_enum, default_value = "text")]
    format: ReportFormat,
    /// Exit 1 on a change of the mathematics (default), or on any change.
    #[arg(long, value_enum, default_value = "mathematics")]
    fail_on: FailOn,
}

pub fn run(args: DiffArgs) -> anyhow::Result<ExitCode> {
    let files = match &args.git {
        Some(rev) => match git_files(rev, &args.paths)? {
            Ok(f) => f,
            Err(e) => return Ok(load_failure(&e)),
        },
        None => {
            let [old, new] = args.paths.as_slice() else {
                bail!(
                    "`hdot diff` takes two derivation files, OLD and NEW (or `--git REV [PATHS]`); {} given",
                    args.paths.len()
                );
            };
            let read = |which: &str, p: &PathBuf| -> anyhow::Result<String> {
                if p.is_dir() {
                    bail!("{which} {} is a folder, not a derivation file", p.display());
                }
                std::fs::read_to_string(p)
                    .map_err(|e| anyhow::anyhow!("cannot read {which} {}: {e}", p.display()))
            };
            let (ot, nt) = (read("OLD", old)?, read("NEW", new)?);
            let (on, nn) = (old.display().to_string(), new.display().to_string());
            match rv::compare_files(Some((&on, &ot)), Some((&nn, &nt))) {
                Ok(f) => vec![f],
                Err(e) => return Ok(load_failure(&e)),
            }
        }
    };
    crate::out!("{}", report::render(&files, args.format));
    Ok(exit_code(&files, args.fail_on))
}

/// Exit 1 when a file changed in a way `fail_on` counts.
pub fn exit_code(files: &[FileDiff], fail_on: FailOn) -> ExitCode {
    let fails = |c: Change| match fail_on {
        FailOn::Mathematics => c.is_mathematical(),
        FailOn::Presentation => c != Change::Unchanged,
    };
    if files.iter().any(|f| fails(f.change)) {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Reports a version that does not load (exit 2).
pub fn load_failure(e: &LoadFailure) -> ExitCode {
    crate::errln!("{}", e.diagnostic);
    crate::errln!(
        "error: the {} version {} does not load; nothing compared",
        e.which,
        e.name
    );
    ExitCode::from(2)
}

/// Every derivation file under `paths` (default: the whole repository)
/// that differs between `rev` and the working tree, compared.
fn git_files(rev: &str, paths: &[PathBuf]) -> anyhow::Result<Result<Vec<FileDiff>, LoadFailure>> {
    let repo = Repo::here()?;
    let commit = repo.commit(rev)?;
    let prefixes: Vec<String> = paths
        .iter()
        .map(|p| repo.relative(p))
        .collect::<anyhow::Result<_>>()?;
    let wanted = |f: &str| {
        f.ends_with(".toml")
            && (prefixes.is_empty()
                || prefixes.iter().any(|p| {
                    p.is_empty()
                        || f == p
                        || f.starts_with(&format!("{}/", p.trim_end_matches('/')))
                }))
    };
    let before: Vec<String> = repo
        .files_at(&commit)?
        .into_iter()
        .filter(|f| wanted(f))
        .collect();
    let mut all: Vec<String> = repo
        .files_now()?
        .into_iter()
        .filter(|f| wanted(f))
        .collect();
    all.extend(before.iter().cloned());
    all.sort();
    all.dedup();
    let mut out = Vec::new();
    for f in &all {
        let path = repo.top.join(f);
        let new_text = if path.is_file() {
            Some(
                std::fs::read_to_string(&path)
                    .map_err(|e| anyhow::anyhow!("cannot read {f}: {e}"))?,
            )
        } else {
            None
        };
        let old_text = if before.contains(f) {
            Some(repo.text_at(&commit, f)?)
        } else {
            None
        };
        let Some(sample) = new_text.as_deref().or(old_text.as_deref()) else {
            continue;
        };
        if catalog::kind_of(std::path::Path::new(f), sample) != FileKind::Derivation {
            continue;
        }
        let old_name = format!("{rev}:{f}");
        if old_text == new_text {
            out.push(rv::unchanged(&old_name, f));
            continue;
        }
        match rv::compare_files(
            old_text.as_deref().map(|t| (old_name.as_str(), t)),
            new_text.as_deref().map(|t| (f.as_str(), t)),
        ) {
            Ok(d) => out.push(d),
            Err(e) => return Ok(Err(e)),
        }
    }
    Ok(Ok(out))
}
