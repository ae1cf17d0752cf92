//! File output that never leaves a half-written file: the one helper every
//! command writes its files through.
//!
//! - A file is written to a temporary file beside its destination and
//!   renamed into place, so the destination is either complete or
//!   untouched ([`AtomicFile`], [`write_atomic`]).
//! - The files of one command are staged together and renamed only when
//!   all of them are written ([`Batch`]): a failure on the second leaves
//!   the first untouched too.
//! - Symbolic links are followed: the file the link points at is replaced,
//!   not the link.
//! - Special files (`/dev/stdout`, `/dev/null`, a named pipe, anything
//!   under `/dev` or `/proc`) are written in place: they cannot be renamed
//!   over, and they hold no earlier content to protect.
//! - New files get the permissions `0o666` less the process umask, as
//!   `File::create` would; a replaced file keeps its permissions.
//! - An output that is an input of the same command is refused before
//!   anything is written: every file the process read through
//!   [`hdot_sym::textfile::read`] (derivations, the ones scenes name,
//!   notes manifests, scenes, CSV clouds) is such an input, and
//!   [`AtomicFile::create`] checks each destination against them
//!   ([`refuse_overwriting_inputs`]; [`is_input_refusal`] tells the
//!   refusal from a failure to write).

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Symbolic links followed before giving up (as the kernel's `ELOOP`).
const MAX_LINKS: usize = 40;

/// Where writing to `path` really writes: `path` with every symbolic link
/// (of the file itself) followed. A dangling link resolves to the path it
/// points at, which is then created.
pub fn resolve(path: &Path) -> io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let t = std::fs::read_link(&p)?;
                p = if t.is_absolute() {
                    t
                } else {
                    p.parent().unwrap_or(Path::new("")).join(t)
                };
            }
            _ => return Ok(p),
        }
    }
    Err(io::Error::other(format!(
        "{}: too many levels of symbolic links",
        path.display()
    )))
}

/// Whether `path` is a special file written in place: a device, a pipe or
/// a socket, or anything under `/dev` or `/proc` (`/dev/stdout` is a link
/// to `/proc/self/fd/1`, which may be a pipe or the terminal).
fn is_special(path: &Path) -> bool {
    if path.starts_with("/dev") || path.starts_with("/proc") {
        return true;
    }
    match std::fs::metadata(path) {
        Ok(m) => !m.is_file() && !m.is_dir(),
        Err(_) => false,
    }
}

enum Inner {
    /// A temporary file beside the destination, renamed over it on commit.
    Temp(tempfile::NamedTempFile),
    /// A special file written in place.
    InPlace(File),
}

/// A file being written: complete at its destination after
/// [`commit`](AtomicFile::commit), absent (or unchanged) if dropped before.
pub struct AtomicFile {
    dest: PathBuf,
    inner: Inner,
}

impl AtomicFile {
    /// Starts writing `path` (see the module documentation); refuses a
    /// file this process has read as an input.
    pub fn create(path: &Path) -> io::Result<AtomicFile> {
        refuse_overwriting_inputs(path, &hdot_sym::textfile::inputs())?;
        if is_special(path) {
            let f = OpenOptions::new().append(true).open(path)?;
            return Ok(AtomicFile {
                dest: path.to_path_buf(),
                inner: Inner::InPlace(f),
            });
        }
        let dest = resolve(path)?;
        if is_special(&dest) {
            let f = OpenOptions::new().append(true).open(&dest)?;
            return Ok(AtomicFile {
                dest,
                inner: Inner::InPlace(f),
            });
        }
        if dest.is_dir() {
            return Err(io::Error::other(format!(
                "{} is a directory",
                path.display()
            )));
        }
        let dir = match dest.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let mut builder = tempfile::Builder::new();
        builder.prefix(".hdot-tmp");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // A replaced file keeps its permissions; a new one gets what
            // File::create would give it (0o666 less the umask).
            let mode = std::fs::metadata(&dest).map_or(0o666, |m| m.permissions().mode() & 0o7777);
            builder.permissions(std::fs::Permissions::from_mode(mode));
        }
        let tmp = builder.tempfile_in(dir)?;
        Ok(AtomicFile {
            dest,
            inner: Inner::Temp(tmp),
        })
    }

    /// The file this writes (links followed).
    pub fn destination(&self) -> &Path {
        &self.dest
    }

    /// Finishes the file: flushes it and renames it into place.
    pub fn commit(self) -> io::Result<()> {
        match self.inner {
            Inner::Temp(mut t) => {
                t.flush()?;
                t.persist(&self.dest).map_err(|e| e.error)?;
                Ok(())
            }
            Inner::InPlace(mut f) => f.flush(),
        }
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.inner {
            Inner::Temp(t) => t.write(buf),
            Inner::InPlace(f) => f.write(buf),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match &mut self.inner {
            Inner::Temp(t) => t.flush(),
            Inner::InPlace(f) => f.flush(),
        }
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename, so
/// `path` is either complete or untouched (see the module documentation).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut f = AtomicFile::create(path)?;
    f.write_all(bytes)?;
    f.commit()
}

/// The files of one command, staged and then renamed into place together:
/// nothing appears unless every file was written.
#[derive(Default)]
pub struct Batch {
    files: Vec<AtomicFile>,
}

impl Batch {
    /// An empty batch.
    pub fn new() -> Batch {
        Batch::default()
    }

    /// Stages `bytes` for `path`.
    pub fn write(&mut self, path: &Path, bytes: &[u8]) -> io::Result<()> {
        let mut f = AtomicFile::create(path)?;
        f.write_all(bytes)?;
        self.files.push(f);
        Ok(())
    }

    /// Renames every staged file into place.
    pub fn commit(self) -> io::Result<()> {
        for f in self.files {
            f.commit()?;
        }
        Ok(())
    }
}

/// Whether `a` and `b` name the same existing file (links followed).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
        false
    }
    #[cfg(not(unix))]
    {
        match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
    }
}

/// An output that is an input of the same command (the error inside the
/// [`io::Error`] of [`refuse_overwriting_inputs`]).
#[derive(Debug)]
pub struct OverwritesInput {
    /// The output asked for.
    pub output: PathBuf,
    /// The input it is (links followed).
    pub input: PathBuf,
}

impl std::fmt::Display for OverwritesInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the output {} is an input of this command ({}); choose another path",
            self.output.display(),
            self.input.display()
        )
    }
}

impl std::error::Error for OverwritesInput {}

/// Whether `e` is the refusal of [`refuse_overwriting_inputs`] (a mistake
/// of the command line, not a failure to write).
pub fn is_input_refusal(e: &io::Error) -> bool {
    e.get_ref().is_some_and(|x| x.is::<OverwritesInput>())
}

/// Refuses to write `output` when it is one of `inputs` (links followed):
/// `hdot derive F --out F` would destroy its own input.
pub fn refuse_overwriting_inputs(output: &Path, inputs: &[impl AsRef<Path>]) -> io::Result<()> {
    if is_special(output) || !output.exists() {
        return Ok(());
    }
    for input in inputs {
        if same_file(output, input.as_ref()) {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                OverwritesInput {
                    output: output.to_path_buf(),
                    input: input.as_ref().to_path_buf(),
                },
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_batch_dropped_before_commit_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let mut b = Batch::new();
        b.write(&dir.path().join("a.txt"), b"a").unwrap();
        assert!(
            b.write(&dir.path().join("no/such/dir/b.txt"), b"b")
                .is_err()
        );
        drop(b);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[cfg(unix)]
    #[test]
    fn links_are_followed_and_special_files_written_in_place() {
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real.txt");
        std::fs::write(&real, "old").unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink("real.txt", &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
        write_atomic(Path::new("/dev/null"), b"x").unwrap();
        assert!(refuse_overwriting_inputs(&link, &[&real]).is_err_and(|e| is_input_refusal(&e)));
        assert!(refuse_overwriting_inputs(&dir.path().join("other"), &[&real]).is_ok());
        // A file read through the one reader is refused as an output.
        let input = dir.path().join("input.toml");
        std::fs::write(&input, "x = 1").unwrap();
        write_atomic(&input, b"x = 2").unwrap();
        hdot_sym::textfile::read(&input).unwrap();
        let e = write_atomic(&link_to(&input, dir.path()), b"x = 3").unwrap_err();
        assert!(is_input_refusal(&e), "{e}");
        assert_eq!(std::fs::read_to_string(&input).unwrap(), "x = 2");
    }

    #[cfg(unix)]
    fn link_to(target: &Path, dir: &Path) -> PathBuf {
        let link = dir.join("input-link.toml");
        std::os::unix::fs::symlink(target, &link).unwrap();
        link
    }
}
