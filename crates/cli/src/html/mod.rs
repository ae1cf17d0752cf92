//! The web pages of a run or a sweep, each one self-contained file
//! (nothing is loaded from the network) in one shell and stylesheet
//! ([`shell`]): `hdot simulate --html` ([`simulation_page`]: the report,
//! plots against time and the body moving in 3D), `hdot stability --html`
//! ([`stability_page`]) and `hdot work-precision --html`
//! ([`work_precision_page`]): their reports, charts and tables.

use std::path::{Path, PathBuf};

mod motion;
mod place;
mod plot;
mod shapes;
mod shell;
mod simulation;
mod stability;
mod work_precision;

pub use simulation::simulation_page;
pub use stability::stability_page;
pub use work_precision::{Study, work_precision_page};

/// Why a page cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum PageError {
    /// A sample of the trajectory (or a quantity computed from it) is not finite.
    #[error(
        "the trajectory has a non-finite sample: {quantity} = {value} at t = {t} (sample {sample}); \
         the page is not written"
    )]
    NonFinite {
        /// Index of the sample.
        sample: usize,
        /// Its time.
        t: f64,
        /// Which quantity.
        quantity: String,
        /// The value.
        value: f64,
    },
    /// The scene's bodies cannot be read or the run cannot be sampled.
    #[error("{0}")]
    Run(String),
}

/// Escapes text for HTML content and attribute values (the one escaper of
/// every page hdot writes).
pub use hdot_sym::escape::html as escape;

/// Refuses, before anything is computed, a page path that is a directory,
/// an input of the command (the scene, its derivation: also through a
/// link) or another file it writes (`outputs`: the option or file that
/// names it, and its path). A refusal is a mistake of the command line
/// (exit 2): nothing is written.
pub fn refuse_page_path(
    page: &Path,
    inputs: &[&Path],
    outputs: &[(&str, &Path)],
) -> anyhow::Result<()> {
    if page.is_dir() {
        anyhow::bail!(
            "--html {} is a directory; a page is one file (name it, e.g. {})",
            page.display(),
            page.join("page.html").display()
        );
    }
    hdot_num::fsio::refuse_overwriting_inputs(page, inputs)?;
    // Every file the command has read so far (a scene's CSV clouds too).
    hdot_num::fsio::refuse_overwriting_inputs(page, &hdot_sym::textfile::inputs())?;
    for (what, other) in outputs {
        if hdot_num::fsio::same_file(page, other) || lexical(page) == lexical(other) {
            anyhow::bail!(
                "--html and {what} name the same file {}; choose another path",
                page.display()
            );
        }
    }
    Ok(())
}

/// A path made absolute by its directory (resolved when it exists), for
/// comparing files that need not exist yet.
fn lexical(p: &Path) -> PathBuf {
    let dir = match p.parent() {
        Some(d) if d.as_os_str().is_empty() => Path::new("."),
        Some(d) => d,
        None => return p.to_path_buf(),
    };
    match (std::fs::canonicalize(dir), p.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()),
    }
}
