//! Finding derivation files: by name in the derivations folder, or by path.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};

/// The folder of bundled derivations: `--dir`, then `$HDOT_DERIVATIONS`,
/// then `./derivations`, then the folder this binary was built from.
pub fn derivations_dir(explicit: Option<&Path>) -> PathBuf {
    if let Some(d) = explicit {
        return d.to_owned();
    }
    if let Some(d) = std::env::var_os("HDOT_DERIVATIONS") {
        return PathBuf::from(d);
    }
    let here = PathBuf::from("derivations");
    if here.is_dir() {
        return here;
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../derivations")
}

/// Every `*.toml` in `dir` but the notes manifest (`notes.toml`), sorted by name.
pub fn all(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read the derivations folder {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| {
            p.file_name()
                .is_none_or(|n| n != hdot_sym::course::MANIFEST_FILE)
        })
        .collect();
    v.sort();
    Ok(v)
}

/// The short name of a derivation file (its stem).
pub fn name_of(p: &Path) -> String {
    p.file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
}

/// What a command-line argument names: a derivation file, or the generated
/// scaling family `chain-K`.
pub enum Target {
    /// A file.
    File(PathBuf),
    /// `chain-K`.
    Chain(usize),
}

/// Resolves a file or `chain-K` (see [`resolve`]).
pub fn target(dir: &Path, arg: &str) -> anyhow::Result<Target> {
    if let Some(k) = hdot_sym::chain::parse_name(arg)
        && !dir.join(format!("{arg}.toml")).is_file()
    {
        return Ok(Target::Chain(k));
    }
    resolve(dir, arg).map(Target::File)
}

/// Loads what `arg` names.
pub fn load(
    dir: &Path,
    arg: &str,
) -> anyhow::Result<Result<hdot_sym::derivation::Derivation, hdot_sym::derivation::Diagnostic>> {
    Ok(match target(dir, arg)? {
        Target::File(p) => hdot_sym::derivation::load(&p),
        Target::Chain(k) => hdot_sym::chain::derivation(k),
    })
}

/// Resolves `NAME` (a file in `dir`) or `PATH` (an existing file, or
/// anything containing a path separator or ending in `.toml`).
pub fn resolve(dir: &Path, arg: &str) -> anyhow::Result<PathBuf> {
    let p = Path::new(arg);
    if p.is_file() || arg.contains('/') || arg.ends_with(".toml") {
        if !p.is_file() {
            bail!("no such derivation file: {arg}");
        }
        return Ok(p.to_owned());
    }
    let candidate = dir.join(format!("{arg}.toml"));
    if candidate.is_file() {
        return Ok(candidate);
    }
    let names: Vec<String> = all(dir)
        .unwrap_or_default()
        .iter()
        .map(|p| name_of(p))
        .collect();
    bail!(
        "unknown derivation `{arg}`; known: {}, chain-1 … chain-{} (or give a path to a .toml file)",
        names.join(", "),
        hdot_sym::chain::MAX_K
    )
}
