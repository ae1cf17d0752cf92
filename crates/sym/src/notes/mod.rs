//! Lecture notes and slides: a [`Document`] (derivations arranged by a
//! [`Course`](crate::document::Course)) rendered as a LaTeX article ([`latex_document`]), as one
//! Markdown page ([`markdown_document`]), as LaTeX Beamer slides
//! ([`slides_document`]); one derivation as a LaTeX fragment to `\input`
//! in a lecturer's own document ([`latex_fragment`]) or as Markdown
//! ([`markdown_fragment`]) — the same sections `hdot derive` prints; and
//! as a static web site with MathML equations ([`html_site`]).
//!
//! Every format shows the same things for each derivation, in the same
//! order: its title, source and file; the summary; what is assumed
//! (assumptions, symbols, abbreviations, frames with their angular
//! velocity Ω); then every shown step with what it does, the formula as
//! written in the file, the result in textbook form and whether the
//! expectation holds. Prose goes through [`crate::prose`], so notation in
//! it (ΣM_x, (Ḣ_O)_Oxyz, `$…$`) is typeset as math.
//!
//! The LaTeX needs only packages of Debian's `texlive-latex-base`,
//! `texlive-latex-recommended` and `texlive-fonts-recommended` (amsmath,
//! amssymb, geometry, hyperref, lmodern, beamer) and compiles with
//! `pdflatex`; a fragment needs only amsmath and amssymb. The output holds
//! no character that pdflatex cannot typeset: apart from ASCII, only the
//! accented letters of Latin-1.
//!
//! [`coverage_document`] is a test document, not part of the notes: a
//! fixed list of expressions that together use every construct the LaTeX
//! printer can emit, so that compiling it proves each of them typesets.
//!
//! The output depends only on the derivations and the course (no date,
//! no paths other than the ones the derivations carry), so a committed
//! copy can be compared byte for byte with a fresh one.
//!
//! # Example
//! ```
//! let text = r#"
//! title = "Angular momentum of a sphere"
//! source = "example"
//! assumptions = ["The sphere is uniform: I_x = I_y = I_z = I."]
//! [symbols]
//! constants = ["I"]
//! time = ["w_x", "w_y", "w_z"]
//! [[frame]]
//! name = "B"
//! angular_velocity = "[w_x, w_y, w_z]"
//! [[step]]
//! name = "H"
//! value = "principal(I, I, I) * angvel(B)"
//! expect = ["I*w_x", "I*w_y", "I*w_z"]
//! "#;
//! let d = hdot_sym::derivation::load_str("sphere.toml", text).unwrap();
//! let doc = hdot_sym::document::Course::plain(&[d.clone()]).document(&[d.clone()]);
//! let tex = hdot_sym::notes::latex_document(&doc);
//! assert!(tex.contains(r"\section{Angular momentum of a sphere}"));
//! assert!(tex.contains(r"H_{x} &= I w_x"));
//! assert!(tex.contains(r"$I_{x} = I_{y} = I_{z} = I$"));
//! assert!(tex.contains(r"\end{document}"));
//! let md = hdot_sym::notes::markdown_document(&doc);
//! assert!(md.contains("$$\n\\begin{aligned}\nH_{x} &= I w_x"));
//! let slides = hdot_sym::notes::slides_document(&doc);
//! assert!(slides.contains(r"\documentclass") && slides.contains(r"\begin{frame}"));
//! let fragment = hdot_sym::notes::latex_fragment(&d);
//! assert!(!fragment.contains(r"\documentclass") && fragment.contains(r"\section{"));
//! ```
//!
//! Each format is a [`Backend`] of the document model, one file each
//! (`unicode.rs`, `latex.rs`, `markdown.rs`, `slides.rs`, `html.rs` with
//! its MathML in `mathml.rs`), listed once in
//! [`BACKENDS`]; what they share is in `layout.rs` (equations in LaTeX
//! math: widths, line breaks, matrices) and `words.rs` (titles and
//! sentences). A new output format is one new file and one line of
//! [`BACKENDS`].

mod coverage;
mod html;
mod latex;
mod layout;
mod markdown;
mod mathml;
mod slides;
mod unicode;
mod words;

use crate::document::{Backend, Document};

pub use coverage::{Coverage, coverage, coverage_document};
pub use html::{
    HTML_CSS_FILE, HTML_GENERATOR, HTML_INDEX, Html, SitePage, html_site, section_math_count,
};
pub use latex::{Latex, latex_document, latex_fragment};
pub use markdown::{Markdown, markdown_document, markdown_fragment};
pub use slides::{Slides, slides_document};
pub use unicode::{Unicode, unicode_section};

/// Every backend of the document, by name.
pub const BACKENDS: &[&dyn Backend] = &[&Unicode, &Latex, &Markdown, &Slides, &Html];

/// The backend called `name` (`unicode`, `latex`, `markdown`, `slides`, `html`).
pub fn backend(name: &str) -> Option<&'static dyn Backend> {
    BACKENDS.iter().copied().find(|b| b.name() == name)
}

/// The command that regenerates the committed notes in `docs/notes/`.
pub const REFRESH_COMMAND: &str = "cargo run -p hdot -- notes --slides";

/// File name of the LaTeX document.
pub const LATEX_FILE: &str = "hdot-notes.tex";

/// File name of the Markdown document.
pub const MARKDOWN_FILE: &str = "hdot-notes.md";

/// File name of the slides.
pub const SLIDES_FILE: &str = "hdot-slides.tex";

/// File name of the printer-coverage test document.
pub const COVERAGE_FILE: &str = "hdot-printer-coverage.tex";

/// Estimated width (in characters of math) beyond which an equation's
/// right-hand side is broken onto further lines (see [`equation_lines`]).
pub(crate) const LINE_BUDGET: f32 = 58.0;

/// The same for slides (a Beamer frame is narrower).
pub(crate) const SLIDE_BUDGET: f32 = 44.0;

/// Whether the document is divided into chapters.
fn has_chapters(doc: &Document) -> bool {
    doc.chapters.iter().any(|c| !c.title.is_empty())
}

#[cfg(test)]
mod tests {
    use super::layout::{equation_lines, math_width};
    use super::words::sentence;
    use super::*;
    use crate::{print, prose, symbols::Symbols};

    #[test]
    fn every_backend_has_its_own_name() {
        let mut names: Vec<&str> = BACKENDS.iter().map(|b| b.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), BACKENDS.len());
        for n in ["unicode", "latex", "markdown"] {
            assert!(
                backend(n).is_some(),
                "no backend {n} for `hdot derive --format {n}`"
            );
        }
    }

    #[test]
    fn long_sums_break_on_the_expression_tree() {
        let names: Vec<String> = (1..=30).map(|k| format!("v_{k}")).collect();
        let time: Vec<&str> = names.iter().map(String::as_str).collect();
        let s = Symbols::parse_decl(&["m", "I_x"], &time);
        // Top-level terms.
        let sum = names
            .iter()
            .map(|n| format!("I_x*{n}"))
            .collect::<Vec<_>>()
            .join(" - ");
        let lines = equation_lines("H_x", &s.expr(&sum).unwrap(), LINE_BUDGET);
        assert!(lines.len() > 1, "{lines:?}");
        assert!(
            lines[0].starts_with("H_x &= I_x v_1 - I_x v_2"),
            "{lines:?}"
        );
        assert!(lines[1].starts_with(r"&\quad {} - I_x v_"), "{lines:?}");
        // Inside the bracket of a product term that is too long alone.
        let bracket = format!(
            "1/2*m*({})*v_1",
            names
                .iter()
                .map(|n| format!("{n}^2"))
                .collect::<Vec<_>>()
                .join(" + ")
        );
        let lines = equation_lines("T", &s.expr(&bracket).unwrap(), LINE_BUDGET);
        assert!(lines.len() > 1, "{lines:?}");
        assert!(
            lines[0].starts_with(r"T &= \frac{1}{2} m \left(v_1^{2} + "),
            "{lines:?}"
        );
        assert!(lines[0].ends_with(r"\right."), "{lines:?}");
        assert!(lines[1].starts_with(r"&\quad \left. {} + v_"), "{lines:?}");
        assert!(
            lines.last().unwrap().ends_with(r"v_{30}^{2}\right) v_1"),
            "{lines:?}"
        );
        // Every line is balanced, and the lines hold the printed text.
        for l in &lines {
            assert_eq!(
                l.matches(r"\left").count(),
                l.matches(r"\right").count(),
                "{l}"
            );
        }
        let joined: String = lines
            .iter()
            .map(|l| {
                l.trim_start_matches("T &= ")
                    .trim_start_matches(r"&\quad ")
                    .trim_start_matches(r"\left. ")
                    .trim_start_matches("{} ")
                    .trim_end_matches(r" \right.")
            })
            .collect::<Vec<_>>()
            .join(" ");
        assert_eq!(joined, print::latex(&s.expr(&bracket).unwrap()));
        // Inside a bracket after a minus sign, −(a + b + …).
        let negated = format!(
            "-({})",
            names
                .iter()
                .map(|n| format!("m*{n}^2"))
                .collect::<Vec<_>>()
                .join(" + ")
        );
        let lines = equation_lines("T", &s.expr(&negated).unwrap(), SLIDE_BUDGET);
        assert!(lines.len() > 1, "{lines:?}");
        assert!(
            lines[0].starts_with(r"T &= -\left(m v_1^{2} + "),
            "{lines:?}"
        );
        assert!(lines[0].ends_with(r"\right."), "{lines:?}");
        assert!(lines.last().unwrap().ends_with(r"\right)"), "{lines:?}");
    }

    /// Every line of every bundled derivation's steps, in the notes and on
    /// slides, is within the printer's measure (the budget, plus the `&=`
    /// or `&\quad` that opens it and the `\left.`/`\right.` that balance
    /// it, which count nothing): long sums are broken between their terms,
    /// inside brackets and brackets in brackets. A matrix is measured by
    /// its columns ([`super::layout::matrix_groups`]), not here.
    #[test]
    fn no_line_of_a_bundled_derivation_is_wider_than_the_measure() {
        use crate::document::Section;
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../derivations");
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "toml") && !p.ends_with("notes.toml"))
            .collect();
        files.sort();
        assert!(files.iter().any(|p| p.ends_with("bicycle.toml")));
        let mut lines = 0;
        for path in &files {
            let d = crate::derivation::load(path).unwrap_or_else(|e| panic!("{e}"));
            let section = Section::of(&d, None);
            // The definitions of the results written by name are set at the
            // notes' measure (a slide only names them).
            let mut text = String::new();
            super::layout::write_coefficient_lines(&mut text, &section, LINE_BUDGET);
            let coefficients: Vec<String> = match text.is_empty() {
                true => Vec::new(),
                false => text.split(" \\\\\n").map(str::to_owned).collect(),
            };
            for st in section.steps.iter().filter(|s| !s.vanishes()) {
                for width in [LINE_BUDGET, SLIDE_BUDGET] {
                    let mut step = super::layout::step_groups(st, width).concat();
                    if width == LINE_BUDGET && st.has_named() {
                        step.extend(coefficients.iter().cloned());
                    }
                    for line in step {
                        if line.contains(r"\begin{bmatrix}") {
                            continue;
                        }
                        let w = math_width(&line);
                        assert!(
                            w <= width + 4.0,
                            "{}: step {}: a line {w} wide, beyond {width}: {line}",
                            path.display(),
                            st.name
                        );
                        lines += 1;
                    }
                }
            }
        }
        assert!(lines > 500, "only {lines} lines measured");
    }

    #[test]
    fn sentences_keep_a_leading_function_name() {
        assert_eq!(sentence("tan γ = −ω_x/ω_z"), "tan γ = −ω_x/ω_z.");
        assert!(prose::latex(&sentence("tan γ = 1")).starts_with(r"$\tan"));
        assert_eq!(sentence("tangent of γ"), "Tangent of γ.");
        assert_eq!(sentence("the rate"), "The rate.");
    }

    #[test]
    fn widths_ignore_decoration() {
        assert_eq!(math_width(r"\dot{\omega}"), 1.0);
        assert!(math_width(r"\left(a\right)") < 2.5);
    }

    #[test]
    fn coverage_builds() {
        let c = coverage();
        let all: String = c.iter().map(|c| print::latex(&c.expr)).collect();
        for construct in [
            r"\dot{",
            r"\ddot{",
            r"\dddot{",
            r"\ddddot{",
            "^{(5)}",
            r"\frac{",
            r"\left(",
            r"\right)",
            r"\sin^{2}",
            r"\cos^{3}",
            r"\mathrm{",
            "I'",
            "_{xy}",
            r"\,",
        ] {
            assert!(all.contains(construct), "coverage lacks {construct}: {all}");
        }
    }

    /// A result above the size (`document::NAMED_ABOVE` terms) is written
    /// by its name in its step and defined under *Coefficients* at the end
    /// of the section; one at the size prints as before (here a matrix
    /// entry too wide for its column: named and defined after the matrix).
    /// The slides name it and define nothing; the web page's count of
    /// equations follows.
    #[test]
    fn results_above_the_size_are_named_coefficients() {
        use crate::document::{NAMED_ABOVE, Section};
        let text = r#"
title = "Long results"
source = "a test"
[symbols]
constants = ["a", "b"]
time = ["q", "p"]
[[step]]
name = "E"
value = "(1 + a + q)^15"
[[step]]
name = "short"
value = "a*q + b"
[[step]]
name = "J"
label = "M"
value = "jacobian(list(q*(1 + a + b)^15 + p*(1 + a + b)^14, a*q + p*q), [q, p])"
"#;
        let d = crate::derivation::load_str("long.toml", text).unwrap();
        let section = Section::of(&d, None);
        // (1 + a + q)^15 has C(17, 2) = 136 terms, (1 + a + b)^14 has
        // C(16, 2) = 120: one above the size, one at it.
        assert_eq!(NAMED_ABOVE, 120);
        assert_eq!(section.steps[0].terms, vec![136]);
        assert_eq!(section.steps[2].terms, vec![136, 120, 2, 1]);
        let named: Vec<String> = section
            .coefficients()
            .iter()
            .map(|(e, terms)| format!("{} {terms}", e.lhs.latex()))
            .collect();
        assert_eq!(named, ["E 136", "M_{11} 136"]);
        let tex = latex_fragment(&d);
        let (steps, coefficients) = tex.split_once(r"\subsection*{Coefficients}").unwrap();
        assert!(!steps.contains("E &="), "{steps}");
        assert!(steps.contains("written by name"), "{steps}");
        assert!(
            steps.contains(r"M &= \begin{bmatrix} M_{11} & M_{12} \\ a + p & q \end{bmatrix}"),
            "{steps}"
        );
        assert!(steps.contains("M_{12} &= "), "{steps}");
        assert!(steps.contains("b + a q"), "{steps}");
        assert!(coefficients.contains("E &= "), "{coefficients}");
        assert!(coefficients.contains("M_{11} &= "), "{coefficients}");
        assert!(!coefficients.contains("M_{12} &="), "{coefficients}");
        let md = markdown_fragment(&d);
        let (steps, coefficients) = md.split_once("### Coefficients").unwrap();
        assert!(
            !steps.contains("E &=") && coefficients.contains("E &= "),
            "{md}"
        );
        let doc = crate::document::Course::plain(std::slice::from_ref(&d))
            .document(std::slice::from_ref(&d));
        let slides = slides_document(&doc);
        assert!(
            !slides.contains("E &=") && !slides.contains("M_{11} &="),
            "{slides}"
        );
        assert!(slides.contains("defined in the notes"), "{slides}");
        let site = html_site(&doc);
        let page = site.iter().find(|p| p.equations > 0).unwrap();
        assert_eq!(page.text.matches("<math").count(), page.equations);
        assert!(page.text.contains("Coefficients"));
    }
}
