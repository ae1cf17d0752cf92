//! Finding derivation files: by name in the derivations folder, or by path;
//! and the bundled derivations and example scenes, embedded in the binary
//! (by `build.rs`) so that an installed `hdot` needs no source tree.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use hdot_sym::derivation::{Derivation, Diagnostic};

/// The embedded files: `DERIVATIONS` and `SCENES`, (stem, text) pairs.
mod bundled {
    include!(concat!(env!("OUT_DIR"), "/bundled.rs"));
}

/// Where derivations are looked up.
#[derive(Debug, Clone)]
pub enum Dir {
    /// A folder of `*.toml` files.
    Folder(PathBuf),
    /// The derivations embedded in the binary.
    Bundled,
}

/// The folder of derivations: `--dir`, then `$HDOT_DERIVATIONS`, then
/// `./derivations`, then the bundled derivations embedded in the binary.
pub fn derivations_dir(explicit: Option<&Path>) -> Dir {
    if let Some(d) = explicit {
        return Dir::Folder(d.to_owned());
    }
    if let Some(d) = std::env::var_os("HDOT_DERIVATIONS") {
        return Dir::Folder(PathBuf::from(d));
    }
    let here = PathBuf::from("derivations");
    if here.is_dir() {
        return Dir::Folder(here);
    }
    Dir::Bundled
}

/// One derivation: a file, or one embedded in the binary.
#[derive(Debug, Clone)]
pub enum Entry {
    /// A file.
    File(PathBuf),
    /// An embedded derivation: its name and text.
    Bundled(&'static str, &'static str),
    /// The generated scaling family `chain-K`.
    Chain(usize),
}

impl Entry {
    /// The short name (the file's stem).
    pub fn name(&self) -> String {
        match self {
            Entry::File(p) => name_of(p),
            Entry::Bundled(n, _) => (*n).to_owned(),
            Entry::Chain(k) => format!("chain-{k}"),
        }
    }

    /// Loads and derives it.
    pub fn load(&self) -> Result<Derivation, Diagnostic> {
        match self {
            Entry::File(p) => hdot_sym::derivation::load(p),
            Entry::Bundled(n, text) => {
                hdot_sym::derivation::load_str(&format!("derivations/{n}.toml"), text)
            }
            Entry::Chain(k) => hdot_sym::chain::derivation(*k),
        }
    }
}

/// Whether `p` is the notes manifest (`notes.toml`), not a derivation.
fn is_manifest(p: &Path) -> bool {
    p.file_name()
        .is_some_and(|n| n == hdot_sym::course::MANIFEST_FILE)
}

/// What a `*.toml` file in a lecturer's folder is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A derivation (also a file that does not parse: its loader says where).
    Derivation,
    /// A scene (`hdot inertia|dynamics|simulate`), recognised by its tables.
    Scene,
    /// The notes manifest (`notes.toml`, or a file of `[[chapter]]`s).
    Manifest,
}

/// Top-level keys that only scenes have (docs/scenes.md, docs/simulation.md).
const SCENE_KEYS: &[&str] = &[
    "kind",
    "initial",
    "t_end",
    "force",
    "couple",
    "constraint",
    "impulse",
    "derivation",
    "top",
    "shaft",
    "motor",
];

/// Classifies the file at `p` with text `text`: a file with `[[step]]`s is
/// a derivation; without, `notes.toml` or a file of `[[chapter]]`s is the
/// manifest and a file with a scene's tables is a scene. Anything else is
/// read as a derivation, so that a broken one is reported, not skipped.
pub fn kind_of(p: &Path, text: &str) -> FileKind {
    let Ok(table) = text.parse::<toml::Table>() else {
        return if is_manifest(p) {
            FileKind::Manifest
        } else {
            FileKind::Derivation
        };
    };
    if table.contains_key("step") {
        FileKind::Derivation
    } else if is_manifest(p) || table.contains_key("chapter") {
        FileKind::Manifest
    } else if SCENE_KEYS.iter().any(|k| table.contains_key(*k)) {
        FileKind::Scene
    } else {
        FileKind::Derivation
    }
}

/// Whether the file at `p` is a derivation (see [`kind_of`]); an
/// unreadable file counts as one, so that the loader reports it.
pub fn is_derivation_file(p: &Path) -> bool {
    std::fs::read_to_string(p).map_or(true, |t| kind_of(p, &t) == FileKind::Derivation)
}

/// The notes manifest of `dir`, if it has one: its path (as shown) and
/// text; an error when it is there but cannot be read.
pub fn manifest(dir: &Dir) -> anyhow::Result<Option<(PathBuf, String)>> {
    Ok(match dir {
        Dir::Folder(d) => {
            let m = d.join(hdot_sym::course::MANIFEST_FILE);
            if !m.exists() {
                return Ok(None);
            }
            let text = hdot_sym::textfile::read(&m)?;
            Some((m, text))
        }
        Dir::Bundled => bundled::DERIVATIONS
            .iter()
            .find(|(n, _)| is_manifest(Path::new(&format!("{n}.toml"))))
            .map(|(n, t)| {
                (
                    PathBuf::from(format!("derivations/{n}.toml")),
                    (*t).to_owned(),
                )
            }),
    })
}

/// Every derivation of `dir` (not the notes manifest, not a scene beside
/// them: see [`kind_of`]), sorted by name; an error when there is none
/// (checking nothing must not pass).
pub fn all(dir: &Dir) -> anyhow::Result<Vec<Entry>> {
    let dir = match dir {
        Dir::Bundled => {
            return Ok(bundled::DERIVATIONS
                .iter()
                .filter(|(n, _)| !is_manifest(Path::new(&format!("{n}.toml"))))
                .map(|(n, t)| Entry::Bundled(n, t))
                .collect());
        }
        Dir::Folder(d) => d,
    };
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read the derivations folder {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|x| x == "toml") && !is_manifest(p) && is_derivation_file(p)
        })
        .collect();
    v.sort();
    if v.is_empty() {
        bail!("no derivation files (*.toml) in {}", dir.display());
    }
    Ok(v.into_iter().map(Entry::File).collect())
}

/// The derivations a command's arguments name: every derivation of `dir`
/// when there are none; otherwise each argument resolved (see
/// [`target`]: `chain-K` too, as `derive` takes it), a folder standing
/// for every derivation file in it.
pub fn select(dir: &Dir, args: &[String]) -> anyhow::Result<Vec<Entry>> {
    if args.is_empty() {
        return all(dir);
    }
    let mut v = Vec::new();
    for a in args {
        let p = Path::new(a);
        if p.is_dir() {
            v.extend(all(&Dir::Folder(p.to_owned()))?);
        } else {
            v.push(target(dir, a)?);
        }
    }
    Ok(v)
}

/// The short name of a derivation file (its stem).
pub fn name_of(p: &Path) -> String {
    p.file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
}

/// Resolves a derivation (see [`resolve`]) or, when no derivation has
/// that name, the generated scaling family `chain-K`.
pub fn target(dir: &Dir, arg: &str) -> anyhow::Result<Entry> {
    if let Some(k) = hdot_sym::chain::parse_name(arg)
        && !matches!(find(dir, arg), Ok(Some(_)))
    {
        return Ok(Entry::Chain(k));
    }
    resolve(dir, arg)
}

/// Loads what `arg` names.
pub fn load(dir: &Dir, arg: &str) -> anyhow::Result<Result<Derivation, Diagnostic>> {
    Ok(target(dir, arg)?.load())
}

/// Resolves `NAME` (a derivation of `dir`) or `PATH` (an existing file, or
/// anything containing a path separator or ending in `.toml`).
pub fn resolve(dir: &Dir, arg: &str) -> anyhow::Result<Entry> {
    if let Some(entry) = find(dir, arg)? {
        return Ok(entry);
    }
    // Only the error lists the known names: reading every file of the
    // folder to classify it costs more than deriving chain-4, which
    // `target` tries here first.
    let names: Vec<String> = all(dir)
        .unwrap_or_default()
        .iter()
        .map(Entry::name)
        .collect();
    bail!(
        "unknown derivation `{arg}`; known: {}, chain-1 … chain-{} (or give a path to a .toml file)",
        names.join(", "),
        hdot_sym::chain::MAX_K
    )
}

/// [`resolve`] without the error of a name that is not there: `None` when
/// `dir` has no derivation called `arg` (an error for a folder, a missing
/// path or a file that is not a derivation).
fn find(dir: &Dir, arg: &str) -> anyhow::Result<Option<Entry>> {
    let p = Path::new(arg);
    if p.is_dir() {
        bail!(
            "`{arg}` is a folder: name one derivation file in it (`hdot check` and `hdot verify` take folders)"
        );
    }
    if p.is_file() || arg.contains('/') || arg.ends_with(".toml") {
        if !p.is_file() {
            bail!("no such derivation file: {arg}");
        }
        not_a_derivation(p, arg)?;
        return Ok(Some(Entry::File(p.to_owned())));
    }
    Ok(match dir {
        Dir::Folder(d) => {
            let candidate = d.join(format!("{arg}.toml"));
            candidate.is_file().then_some(Entry::File(candidate))
        }
        Dir::Bundled => bundled::DERIVATIONS
            .iter()
            .find(|(n, _)| *n == arg)
            .map(|(n, t)| Entry::Bundled(n, t)),
    })
}

/// Refuses a notes manifest or a scene given where a derivation is
/// expected (see [`kind_of`]), saying what it is and which command takes
/// it; a derivation, or a file that cannot be read, passes (the loader
/// reports it).
fn not_a_derivation(p: &Path, arg: &str) -> anyhow::Result<()> {
    let Ok(text) = std::fs::read_to_string(p) else {
        return Ok(());
    };
    match kind_of(p, &text) {
        FileKind::Derivation => Ok(()),
        FileKind::Manifest => {
            let folder = p
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .map_or_else(|| ".".to_owned(), |d| d.display().to_string());
            bail!(
                "`{arg}` is a notes manifest (the course's title, author and chapters, docs/notes/README.md), \
                 not a derivation: `hdot notes {folder}` (or `hdot notes --manifest {arg}`) reads it with the \
                 derivations it names; give this command a derivation file (one with [[step]]s) or its folder"
            )
        }
        FileKind::Scene => bail!(
            "`{arg}` is a scene (docs/scenes.md), not a derivation: `hdot simulate`, `hdot dynamics` and \
             `hdot inertia` take it; give this command a derivation file (one with [[step]]s)"
        ),
    }
}

/// A bundled example scene named by `arg` when no such file exists: its
/// stem (`sim-heavy-top`) or its path in the source tree
/// (`docs/examples/sim-heavy-top.toml`). Returns the name to show and the
/// text.
pub fn bundled_scene(arg: &Path) -> Option<(String, &'static str)> {
    if arg.exists() {
        return None;
    }
    let (n, t) = bundled::SCENES
        .iter()
        .find(|(n, _)| arg == Path::new(n) || arg.ends_with(format!("docs/examples/{n}.toml")))?;
    Some((format!("docs/examples/{n}.toml"), t))
}

/// The finder of a scene's derivation (`derivation.file`): looked up
/// next to the scene first, then among the derivations of
/// [`derivations_dir`] (the bundled ones when there is no folder).
pub fn derivation_finder(path: &Path) -> impl Fn(&str) -> Result<(PathBuf, String), String> + '_ {
    move |name: &str| {
        hdot_sim::scene::resolve_near(path, name).or_else(|near| {
            let Ok(Some(entry)) = find(&derivations_dir(None), name) else {
                return Err(near);
            };
            match entry {
                Entry::File(file) => {
                    let text = hdot_sym::textfile::read(&file).map_err(|e| e.to_string())?;
                    Ok((file, text))
                }
                Entry::Bundled(n, text) => Ok((
                    PathBuf::from(format!("derivations/{n}.toml")),
                    text.to_owned(),
                )),
                // `resolve` names files and bundled derivations only.
                Entry::Chain(_) => Err(near),
            }
        })
    }
}

/// Reads a simulation scene: a file, or a bundled example named as in
/// [`bundled_scene`]; its derivation is found by [`derivation_finder`].
pub fn scene(path: &Path) -> anyhow::Result<hdot_sim::scene::Scene> {
    let find = derivation_finder(path);
    let text = match bundled_scene(path) {
        Some((_, text)) => Some(text.to_owned()),
        None => std::fs::read_to_string(path).ok(),
    };
    if let Some(table) = text.and_then(|t| t.parse::<toml::Table>().ok())
        && table.get("kind").and_then(|k| k.as_str()) == Some("stability")
    {
        bail!(
            "{}: a stability scene (kind = \"stability\"): run `hdot stability {}`",
            path.display(),
            path.display()
        );
    }
    Ok(match bundled_scene(path) {
        Some((name, text)) => hdot_sim::scene::Scene::parse_with(text, Path::new(&name), &find)?,
        None => hdot_sim::scene::Scene::from_file_with(path, &find)?,
    })
}

/// Reads a stability scene (`hdot stability`): a file, or a bundled
/// example named as in [`bundled_scene`]; its derivation is found by
/// [`derivation_finder`].
pub fn stability_scene(path: &Path) -> anyhow::Result<hdot_sim::stability::StabilityScene> {
    use hdot_sim::stability::StabilityScene;
    let find = derivation_finder(path);
    Ok(match bundled_scene(path) {
        Some((name, text)) => StabilityScene::parse_with(text, Path::new(&name), &find)?,
        None => {
            let text = hdot_sym::textfile::read(path)?;
            StabilityScene::parse_with(&text, path, &find)?
        }
    })
}
