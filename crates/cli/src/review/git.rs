//! The git repository a review runs in, through the `git` command: its
//! top folder, whether a revision exists, the files of a revision and of
//! the working tree, and a file's text at a revision.

use std::path::{Component, Path, PathBuf};
use std::process::Command;

use anyhow::{Context, bail};

/// A git repository found from the current folder.
#[derive(Debug)]
pub struct Repo {
    /// Its top folder (as git reports it: links resolved).
    pub top: PathBuf,
}

/// Runs `git ARGS` in `dir`; its standard output, or an error with git's
/// own message.
fn git(dir: &Path, args: &[&str]) -> anyhow::Result<Vec<u8>> {
    let out = Command::new("git")
        .args(args)
        .current_dir(dir)
        .output()
        .context("cannot run `git` (is it installed and on PATH?)")?;
    if !out.status.success() {
        bail!("{}", String::from_utf8_lossy(&out.stderr).trim());
    }
    Ok(out.stdout)
}

/// NUL-separated file names.
fn names(bytes: &[u8]) -> Vec<String> {
    bytes
        .split(|b| *b == 0)
        .filter(|s| !s.is_empty())
        .map(|s| String::from_utf8_lossy(s).into_owned())
        .collect()
}

impl Repo {
    /// The repository the current folder is in.
    pub fn here() -> anyhow::Result<Repo> {
        let cwd = std::env::current_dir().context("cannot read the current folder")?;
        let top = git(&cwd, &["rev-parse", "--show-toplevel"])
            .map_err(|e| anyhow::anyhow!("`--git` needs a git repository: {e}"))?;
        let top = String::from_utf8_lossy(&top).trim().to_owned();
        Ok(Repo {
            top: PathBuf::from(top),
        })
    }

    /// The commit `rev` names, or an error saying it does not exist.
    pub fn commit(&self, rev: &str) -> anyhow::Result<String> {
        if rev.starts_with('-') {
            bail!(
                "no such revision `{rev}` in the repository at {}",
                self.top.display()
            );
        }
        let spec = format!("{rev}^{{commit}}");
        match git(&self.top, &["rev-parse", "--verify", "--quiet", &spec]) {
            Ok(out) => Ok(String::from_utf8_lossy(&out).trim().to_owned()),
            Err(_) => bail!(
                "no such revision `{rev}` in the repository at {} (a commit, branch or tag; fetch it first in a shallow clone)",
                self.top.display()
            ),
        }
    }

    /// The path of `p` (relative to the current folder, or absolute)
    /// relative to the top folder, `/`-separated; an error for a path
    /// outside the repository.
    pub fn relative(&self, p: &Path) -> anyhow::Result<String> {
        let abs = resolve(&std::env::current_dir()?.join(p));
        let top = resolve(&self.top);
        let Ok(rel) = abs.strip_prefix(&top) else {
            bail!(
                "{} is outside the repository at {}",
                p.display(),
                self.top.display()
            );
        };
        Ok(rel
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect::<Vec<_>>()
            .join("/"))
    }

    /// Every file of commit `rev` (paths from the top folder).
    pub fn files_at(&self, rev: &str) -> anyhow::Result<Vec<String>> {
        Ok(names(&git(
            &self.top,
            &["ls-tree", "-r", "-z", "--name-only", "--full-tree", rev],
        )?))
    }

    /// Every file of the working tree: tracked, and new files git does not
    /// ignore.
    pub fn files_now(&self) -> anyhow::Result<Vec<String>> {
        Ok(names(&git(
            &self.top,
            &[
                "ls-files",
                "-z",
                "--cached",
                "--others",
                "--exclude-standard",
            ],
        )?))
    }

    /// The text of `path` at commit `rev`.
    pub fn text_at(&self, rev: &str, path: &str) -> anyhow::Result<String> {
        let bytes = git(&self.top, &["cat-file", "blob", &format!("{rev}:{path}")])?;
        String::from_utf8(bytes).with_context(|| format!("{rev}:{path} is not UTF-8 text"))
    }
}

/// `p` (absolute) with `.` and `..` resolved, then links followed as far
/// as it exists (a deleted file is still placed where it was).
fn resolve(p: &Path) -> PathBuf {
    let mut lexical = PathBuf::new();
    for c in p.components() {
        match c {
            Component::ParentDir => {
                lexical.pop();
            }
            Component::CurDir => {}
            other => lexical.push(other.as_os_str()),
        }
    }
    let mut existing = lexical.clone();
    let mut rest = Vec::new();
    while !existing.exists() {
        match (existing.file_name(), existing.parent()) {
            (Some(n), Some(parent)) => {
                rest.push(n.to_owned());
                existing = parent.to_path_buf();
            }
            _ => break,
        }
    }
    let mut out = existing.canonicalize().unwrap_or(existing);
    for n in rest.into_iter().rev() {
        out.push(n);
    }
    out
}
