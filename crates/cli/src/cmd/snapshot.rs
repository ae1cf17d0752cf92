//! `hdot snapshot [FILES|DIRS] --dir snapshots/ --check|--accept`: one
//! review file per derivation (see `review::snapshot`); `--check` exits 1
//! and prints the semantic diff when one would change, `--accept` writes
//! them. New and removed snapshot files are reported; scenes and notes
//! manifests among the derivations are skipped.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::bail;
use clap::Args;

use hdot_sym::derivation::Derivation;

use crate::catalog::{self, Entry, FileKind};
use crate::cmd::diff::FailOn;
use crate::output::{self, OutputError};
use crate::review::compare::{self, Change, Version};
use crate::review::report::{self, FileDiff, ReportFormat};
use crate::review::snapshot as snap;

// Record what each derivation derives in a review file
// (`DIR/NAME.hdot.txt`): the verdicts of check and verify, every step's
// equations in textbook form with their canonical forms. Commit the
// folder; `--check` in CI fails when a derivation's results change, and
// says how.
//
// Exit status: 0 when every snapshot is up to date, or differs only in
// presentation (`--check`), or was written (`--accept`); 1 when the
// mathematics or a verdict of one would change, or one is new or no
// longer needed (`--check`; `--fail-on presentation`: any change); 2 on
// bad input (a derivation that does not load, a
// snapshot folder that is a file): then nothing is written.
#[derive(Debug, Args)]
#[command(group(clap::ArgGroup::new("mode").required(true).args(["check", "accept"])))]
pub struct SnapshotArgs {
    /// Derivation files or folders of them (default: the derivations folder).
    #[arg(value_name = "FILE|DIR")]
    paths: Vec<String>,
    /// The folder of snapshot files.
    #[arg(long, value_name = "DIR", default_value = "snapshots")]
    dir: PathBuf,
    /// Exit 1 and print the semantic diff when a snapshot would change.
    #[arg(long)]
    check: bool,
    /// Write the snapshots (and remove those of derivations that are gone).
    #[arg(long)]
    accept: bool,
    /// Random bodies for the verify verdict (seed 0).
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..))]
    bodies: u64,
    /// Output format of the semantic diff.
    #[arg(long, short, value_enum, default_value = "text")]
    format: ReportFormat,
    /// `--check` exits 1 on a change of the mathematics or a verdict
    /// (default), or on any change.
    #[arg(long, value_enum, default_value = "mathematics")]
    fail_on: FailOn,
}

/// `p` as a snapshot shows it: relative to the current folder when it is
/// inside it, else its file name (never an absolute path).
fn shown(p: &Path) -> String {
    let rel = std::env::current_dir().ok().and_then(|cwd| {
        p.canonicalize()
            .ok()?
            .strip_prefix(cwd.canonicalize().ok()?)
            .ok()
            .map(Path::to_path_buf)
    });
    match rel {
        Some(r) => r.display().to_string(),
        None if p.is_relative() => p.display().to_string(),
        None => p
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
    }
}

/// The derivations named (scenes and manifests skipped, said on stderr).
fn derivations(paths: &[String]) -> anyhow::Result<Vec<Entry>> {
    let dir = catalog::derivations_dir(None);
    let mut out = Vec::new();
    for e in catalog::select(&dir, paths)? {
        if let Entry::File(p) = &e
            && let Ok(text) = std::fs::read_to_string(p)
        {
            match catalog::kind_of(p, &text) {
                FileKind::Derivation => {}
                FileKind::Scene => {
                    crate::errln!("skipped {}: a scene, not a derivation", p.display());
                    continue;
                }
                FileKind::Manifest => {
                    crate::errln!("skipped {}: the notes manifest", p.display());
                    continue;
                }
            }
        }
        out.push(e);
    }
    Ok(out)
}

/// The derivations to snapshot, loaded, by snapshot file name: (shown
/// path, derivation); `Err(code)` when one does not load.
type Wanted = BTreeMap<String, (String, Derivation)>;

fn load_wanted(paths: &[String]) -> anyhow::Result<Result<Wanted, ExitCode>> {
    let mut wanted = Wanted::new();
    for e in derivations(paths)? {
        let d = match e.load() {
            Ok(d) => d,
            Err(diag) => {
                crate::errln!("{diag}");
                crate::errln!("error: no snapshots written or checked");
                return Ok(Err(ExitCode::from(2)));
            }
        };
        let file = format!("{}{}", d.name, snap::EXTENSION);
        let path = match &e {
            Entry::File(p) => shown(p),
            Entry::Bundled(n, _) => format!("derivations/{n}.toml"),
            Entry::Chain(k) => format!("chain-{k}"),
        };
        if let Some((other, _)) = wanted.get(&file) {
            bail!("{path} and {other} would both be snapshot {file}: rename one");
        }
        wanted.insert(file, (path, d));
    }
    Ok(Ok(wanted))
}

/// The snapshot files in `dir` (by file name), if it exists.
fn existing(dir: &Path) -> anyhow::Result<BTreeMap<String, String>> {
    let mut out = BTreeMap::new();
    if !dir.is_dir() {
        return Ok(out);
    }
    for entry in
        std::fs::read_dir(dir).map_err(|e| anyhow::anyhow!("cannot read {}: {e}", dir.display()))?
    {
        let p = entry?.path();
        let Some(name) = p.file_name().map(|n| n.to_string_lossy().into_owned()) else {
            continue;
        };
        if name.ends_with(snap::EXTENSION)
            && let Ok(text) = std::fs::read_to_string(&p)
            && snap::is_snapshot(&text)
        {
            out.insert(name, text);
        }
    }
    Ok(out)
}

/// What would change: each derivation's snapshot compared with the one
/// there, the header lines that changed (and whether a verdict of check
/// or verify is among them), and the files to write.
#[derive(Default)]
struct Plan {
    diffs: Vec<FileDiff>,
    verdicts: Vec<String>,
    verdict_changed: bool,
    writes: Vec<(PathBuf, String)>,
}

fn plan(args: &SnapshotArgs, wanted: &Wanted, existing: &BTreeMap<String, String>) -> Plan {
    let mut plan = Plan::default();
    for (file, (path, d)) in wanted {
        let text = snap::render(d, path, &snap::verify_line(d, args.bodies as usize));
        let target = args.dir.join(file);
        let old = existing.get(file);
        if old == Some(&text) {
            plan.diffs.push(crate::review::unchanged(
                &target.display().to_string(),
                path,
            ));
            continue;
        }
        let before = old.map(|o| snap::read(o, &d.symbols)).unwrap_or_default();
        let steps = compare::compare(&before, &Version::of(d), Some(d));
        let mut change = compare::file_change(old.is_some(), true, &steps);
        if let Some(old) = old {
            for (a, b) in head_changes(old, &text) {
                let verdict = [&a, &b]
                    .iter()
                    .any(|l| l.starts_with("check:") || l.starts_with("verify:"));
                plan.verdict_changed |= verdict;
                plan.verdicts.push(format!("{path}: {a}  →  {b}"));
            }
            // A retitled or moved file is a change of presentation.
            change = change.max(Change::Presentation);
        }
        plan.diffs.push(FileDiff {
            old: old.map(|_| target.display().to_string()),
            new: Some(path.clone()),
            change,
            steps,
        });
        plan.writes.push((target, text));
    }
    plan
}

pub fn run(args: SnapshotArgs) -> anyhow::Result<ExitCode> {
    if args.dir.exists() && !args.dir.is_dir() {
        bail!(
            "the snapshot folder {} is a file; name a folder with --dir",
            args.dir.display()
        );
    }
    // Load everything first: a derivation that does not load writes nothing.
    let wanted = match load_wanted(&args.paths)? {
        Ok(w) => w,
        Err(code) => return Ok(code),
    };
    let existing = existing(&args.dir)?;
    let plan = plan(&args, &wanted, &existing);
    let removed: Vec<&String> = existing
        .keys()
        .filter(|f| !wanted.contains_key(*f))
        .collect();
    if args.accept {
        accept(&args.dir, &plan.writes, &removed)?;
        let new = plan
            .diffs
            .iter()
            .filter(|f| f.change == Change::Added)
            .count();
        crate::outln!(
            "{} snapshots in {}: {} written ({new} new), {} removed, {} unchanged",
            wanted.len(),
            args.dir.display(),
            plan.writes.len(),
            removed.len(),
            wanted.len() - plan.writes.len()
        );
        return Ok(ExitCode::SUCCESS);
    }
    if plan.writes.is_empty() && removed.is_empty() {
        crate::outln!(
            "{} snapshots in {} are up to date",
            wanted.len(),
            args.dir.display()
        );
        return Ok(ExitCode::SUCCESS);
    }
    let changed: Vec<FileDiff> = plan
        .diffs
        .into_iter()
        .filter(|f| f.change != Change::Unchanged)
        .collect();
    crate::out!("{}", report::render(&changed, args.format));
    for v in &plan.verdicts {
        crate::outln!("changed: {v}");
    }
    for f in &removed {
        crate::outln!(
            "removed: {} (its derivation is no longer among those snapshotted)",
            args.dir.join(f).display()
        );
    }
    let failed = plan.verdict_changed
        || !removed.is_empty()
        || crate::cmd::diff::exit_code(&changed, args.fail_on) != ExitCode::SUCCESS;
    crate::outln!(
        "snapshots {}: {} to write, {} to remove; run `hdot snapshot --accept` and commit {}",
        if failed {
            "out of date"
        } else {
            "differ in presentation only"
        },
        plan.writes.len(),
        removed.len(),
        args.dir.display()
    );
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// The header lines (title, verdicts) that differ, old and new.
fn head_changes(old: &str, new: &str) -> Vec<(String, String)> {
    let (a, b) = (snap::head(old), snap::head(new));
    let n = a.len().max(b.len());
    (0..n)
        .filter_map(|k| {
            let (x, y) = (
                a.get(k).copied().unwrap_or(""),
                b.get(k).copied().unwrap_or(""),
            );
            (x != y).then(|| (x.to_owned(), y.to_owned()))
        })
        .collect()
}

/// Writes the changed snapshots together (all or none) and removes those
/// no longer wanted.
fn accept(dir: &Path, writes: &[(PathBuf, String)], removed: &[&String]) -> anyhow::Result<()> {
    if !writes.is_empty() {
        std::fs::create_dir_all(dir)
            .map_err(|e| OutputError::new(format!("cannot create {}", dir.display()), e))?;
    }
    let mut batch = output::Batch::new();
    for (p, text) in writes {
        batch
            .write(p, text.as_bytes())
            .map_err(|e| OutputError::new(format!("cannot write {}", p.display()), e))?;
    }
    batch
        .commit()
        .map_err(|e| OutputError::new(format!("cannot write {}", dir.display()), e))?;
    for f in removed {
        let p = dir.join(f);
        std::fs::remove_file(&p)
            .map_err(|e| OutputError::new(format!("cannot remove {}", p.display()), e))?;
    }
    Ok(())
}
