//! `hdot notes`: derivations as lecture notes (LaTeX and Markdown), slides
//! (LaTeX Beamer), per-derivation LaTeX fragments, or a static web site
//! with MathML equations (`--html DIR`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use hdot_sym::course;
use hdot_sym::derivation::Derivation;
use hdot_sym::document::Course;
use hdot_sym::notes;

use crate::output::OutputError;
use crate::{catalog, output};

// Write lecture notes: derivations step by step, as a LaTeX document
// (`hdot-notes.tex`) and as Markdown with $$ math (`hdot-notes.md`);
// with `--slides` also LaTeX Beamer slides (`hdot-slides.tex`), with
// `--fragments` one LaTeX fragment per derivation (`fragments/NAME.tex`,
// to \input in your own document). With `--html DIR`, instead, a web
// site: DIR/index.html with the contents and one page per derivation,
// every equation as MathML (no script, nothing fetched from the network).
//
// The derivations are the files and folders given (default: the
// derivations folder). Chapters, their order, the title and author line
// and the steps shown come from a notes manifest: `--manifest FILE`, or
// `notes.toml` in the one folder given (see docs/notes/README.md);
// without one, the derivations follow in file-name order.
//
// Exit status: 0 when written; 2 when a derivation file or the manifest
// cannot be read or has an error (then nothing is written). A derivation
// whose expectation does not hold is still written, marked as such, and
// named on stderr.
#[derive(Debug, Args)]
pub struct NotesArgs {
    /// Derivation files or folders of them (default: the derivations folder).
    #[arg(value_name = "FILE|DIR")]
    paths: Vec<PathBuf>,
    /// Folder to write the notes into.
    #[arg(long, short, value_name = "DIR", default_value = "docs/notes")]
    out: PathBuf,
    /// Folder of derivation files when no FILE|DIR is given (default: ./derivations).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
    /// The notes manifest (title, author, chapters, steps shown).
    #[arg(long, value_name = "FILE", conflicts_with = "no_manifest")]
    manifest: Option<PathBuf>,
    /// Ignore any notes.toml: file-name order, no chapters.
    #[arg(long)]
    no_manifest: bool,
    /// Also write LaTeX Beamer slides (hdot-slides.tex).
    #[arg(long)]
    slides: bool,
    /// Also write one standalone LaTeX fragment per derivation (fragments/NAME.tex).
    #[arg(long)]
    fragments: bool,
    /// Write the notes as a web site into DIR instead (index.html, one page
    /// per derivation, the stylesheet); DIR must be new, empty, or an
    /// earlier site of hdot notes.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["slides", "fragments", "printer_coverage", "out"])]
    html: Option<PathBuf>,
    /// Also write the printer-coverage test document (for scripts/build_notes).
    #[arg(long, hide = true)]
    printer_coverage: bool,
}

fn load_all(files: &[catalog::Entry]) -> Result<Vec<Derivation>, ExitCode> {
    let mut ds = Vec::new();
    for entry in files {
        match entry.load() {
            Ok(d) => ds.push(d),
            Err(diag) => {
                crate::errln!("{diag}");
                crate::errln!("error: no notes written");
                return Err(ExitCode::from(2));
            }
        }
    }
    Ok(ds)
}

/// Whether the site may be written into `dir`: a folder that does not
/// exist yet, an empty one, or one whose `index.html` hdot notes wrote
/// (it names [`notes::HTML_GENERATOR`]). Anything else is refused, so a
/// folder of other files is never written into.
fn site_folder_ok(dir: &Path) -> Result<(), String> {
    if !dir.exists() {
        return Ok(());
    }
    if !dir.is_dir() {
        return Err(format!(
            "--html {}: exists and is not a folder",
            dir.display()
        ));
    }
    let mut entries = std::fs::read_dir(dir)
        .map_err(|e| format!("--html {}: cannot read the folder: {e}", dir.display()))?;
    if entries.next().is_none() {
        return Ok(());
    }
    let index = dir.join(notes::HTML_INDEX);
    let ours = std::fs::read_to_string(&index).is_ok_and(|t| {
        t.contains(&format!(
            "<meta name=\"generator\" content=\"{}\">",
            notes::HTML_GENERATOR
        ))
    });
    if ours {
        Ok(())
    } else {
        Err(format!(
            "--html {}: the folder holds files that are not a site written by hdot notes \
             (no {} naming it); give a new or empty folder",
            dir.display(),
            notes::HTML_INDEX
        ))
    }
}

pub fn run(args: NotesArgs) -> anyhow::Result<ExitCode> {
    // The files, and the folder whose notes.toml applies.
    let mut files = Vec::new();
    let mut folders: Vec<catalog::Dir> = Vec::new();
    if args.paths.is_empty() {
        let dir = catalog::derivations_dir(args.dir.as_deref());
        files = catalog::all(&dir)?;
        folders.push(dir);
    }
    for p in &args.paths {
        if p.is_dir() {
            let dir = catalog::Dir::Folder(p.clone());
            files.extend(catalog::all(&dir)?);
            folders.push(dir);
        } else if p.is_file() {
            files.push(catalog::Entry::File(p.clone()));
        } else {
            anyhow::bail!("no such derivation file or folder: {}", p.display());
        }
    }
    let ds = match load_all(&files) {
        Ok(ds) => ds,
        Err(code) => return Ok(code),
    };
    let manifest: Option<(PathBuf, String)> = if args.no_manifest {
        None
    } else if let Some(m) = &args.manifest {
        let text = hdot_sym::textfile::read(m)
            .map_err(|e| anyhow::anyhow!("cannot read the notes manifest: {e}"))?;
        Some((m.clone(), text))
    } else if let [dir] = folders.as_slice() {
        catalog::manifest(dir)?
    } else {
        None
    };
    let course = match &manifest {
        Some((m, text)) => match course::parse(&m.display().to_string(), text, &ds) {
            Ok(c) => c,
            Err(diag) => {
                crate::errln!("{diag}");
                crate::errln!("error: no notes written");
                return Ok(ExitCode::from(2));
            }
        },
        None => Course::plain(&ds),
    };
    let doc = course.document(&ds);
    if let Some(dir) = &args.html
        && let Err(why) = site_folder_ok(dir)
    {
        crate::errln!("error: {why}");
        crate::errln!("error: no notes written");
        return Ok(ExitCode::from(2));
    }
    // Every file appears, or none does.
    let mut written: Vec<PathBuf> = Vec::new();
    let mut batch = output::Batch::new();
    let mut write = |path: PathBuf, text: &str| -> anyhow::Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|e| OutputError::new(format!("cannot create {}", dir.display()), e))?;
        }
        batch
            .write(&path, text.as_bytes())
            .map_err(|e| OutputError::new(format!("cannot write {}", path.display()), e))?;
        written.push(path);
        Ok(())
    };
    if let Some(dir) = &args.html {
        for page in notes::html_site(&doc) {
            write(dir.join(&page.file), &page.text)?;
        }
    } else {
        write(
            args.out.join(notes::LATEX_FILE),
            &notes::latex_document(&doc),
        )?;
        write(
            args.out.join(notes::MARKDOWN_FILE),
            &notes::markdown_document(&doc),
        )?;
    }
    if args.slides {
        write(
            args.out.join(notes::SLIDES_FILE),
            &notes::slides_document(&doc),
        )?;
    }
    if args.fragments {
        let dir: &Path = &args.out.join("fragments");
        for d in &ds {
            write(
                dir.join(format!("{}.tex", d.name)),
                &notes::latex_fragment(d),
            )?;
        }
    }
    if args.printer_coverage {
        write(
            args.out.join(notes::COVERAGE_FILE),
            &notes::coverage_document(),
        )?;
    }
    let folder = args.html.as_ref().unwrap_or(&args.out);
    batch
        .commit()
        .map_err(|e| OutputError::new(format!("cannot write {}", folder.display()), e))?;
    for d in &ds {
        for (step, c) in d.failures() {
            crate::errln!(
                "warning: {}: expectation does not hold: {}{}{}",
                d.path,
                step,
                if c.component.is_empty() { "" } else { "." },
                c.component
            );
        }
    }
    let shown: Vec<String> = written
        .iter()
        .take(3)
        .map(|p| p.display().to_string())
        .collect();
    crate::outln!(
        "wrote {}{} ({} derivations{})",
        shown.join(", "),
        if written.len() > 3 {
            format!(" and {} more", written.len() - 3)
        } else {
            String::new()
        },
        ds.len(),
        match &manifest {
            Some((m, _)) => format!(", arranged by {}", m.display()),
            None => String::new(),
        }
    );
    Ok(ExitCode::SUCCESS)
}
