//! Every derivation file in every output format, as insta snapshots
//! (`glob!` over `derivations/`): a changed derivation is a readable diff.

use hdot_sym::derivation::load_str;
use hdot_sym::render::{Format, render};

#[test]
fn every_derivation_in_every_format() {
    insta::glob!("../../derivations", "*.toml", |path| {
        let text = std::fs::read_to_string(path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        if name == hdot_sym::course::MANIFEST_FILE {
            return;
        }
        let shown = format!("derivations/{name}");
        let d = load_str(&shown, &text).unwrap_or_else(|e| panic!("{e}"));
        assert!(d.all_hold(), "{shown}: {:?}", d.failures());
        for (tag, format) in [
            ("unicode", Format::Unicode),
            ("latex", Format::Latex),
            ("markdown", Format::Markdown),
            ("sympy", Format::Sympy),
            ("json", Format::Json),
        ] {
            insta::assert_snapshot!(tag, digest(&render(&d, format)));
        }
    });
}

/// Above this many bytes a format's output is snapshot as a digest.
const FULL_UP_TO: usize = 256 * 1024;

/// The output itself up to [`FULL_UP_TO`] bytes; above it (the nonlinear
/// bicycle's equations run to thousands of terms, which no reviewer
/// reads), each line cut at 160 characters with its length: the structure
/// and the start of every result stay a readable diff, and a change of
/// any length shows. The notes' snapshot below holds such a file's
/// readable form (its long results as named coefficients).
fn digest(out: &str) -> String {
    if out.len() <= FULL_UP_TO {
        return out.to_string();
    }
    let mut d = format!(
        "digest of {} bytes: lines over 160 characters cut\n",
        out.len()
    );
    for line in out.lines() {
        let n = line.chars().count();
        if n > 160 {
            let cut: String = line.chars().take(160).collect();
            d.push_str(&format!("{cut} … ({n} characters)\n"));
        } else {
            d.push_str(line);
            d.push('\n');
        }
    }
    d
}

/// The lecture notes and the slides of the bundled derivations, arranged
/// by `derivations/notes.toml`, as LaTeX snapshots: a presentation change
/// shows up as a readable diff of what a lecturer compiles.
#[test]
fn notes_and_slides_latex() {
    let root = hdot_tests::repo_root().join("derivations");
    let mut files: Vec<_> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| p.file_name().unwrap() != hdot_sym::course::MANIFEST_FILE)
        .collect();
    files.sort();
    let ds: Vec<_> = files
        .iter()
        .map(|p| {
            let shown = format!("derivations/{}", p.file_name().unwrap().to_string_lossy());
            load_str(&shown, &std::fs::read_to_string(p).unwrap()).unwrap()
        })
        .collect();
    let manifest = std::fs::read_to_string(root.join(hdot_sym::course::MANIFEST_FILE)).unwrap();
    let doc = hdot_sym::course::parse("derivations/notes.toml", &manifest, &ds)
        .unwrap()
        .document(&ds);
    insta::assert_snapshot!("notes-latex", hdot_sym::notes::latex_document(&doc));
    insta::assert_snapshot!("slides-latex", hdot_sym::notes::slides_document(&doc));
}
