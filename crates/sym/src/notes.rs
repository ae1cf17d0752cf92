//! Lecture notes and slides: a [`Document`] (derivations arranged by a
//! [`Course`](crate::document::Course)) rendered as a LaTeX article ([`latex_document`]), as one
//! Markdown page ([`markdown_document`]), as LaTeX Beamer slides
//! ([`slides_document`]); one derivation as a LaTeX fragment to `\input`
//! in a lecturer's own document ([`latex_fragment`]) or as Markdown
//! ([`markdown_fragment`]) — the same sections `hdot derive` prints.
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

use std::fmt::Write;

use crate::document::{Chapter, Document, Equation, Section, StepBlock, Verdict};
use crate::escape;
use crate::expr::Expr;
use crate::label::{latex_label, latex_name};
use crate::print;
use crate::prose;
use crate::symbols::Symbols;

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
const LINE_BUDGET: f32 = 58.0;

/// The same for slides (a Beamer frame is narrower).
const SLIDE_BUDGET: f32 = 44.0;

// ------------------------------------------------------------- coverage --

/// One entry of the printer-coverage appendix.
#[derive(Clone, Debug)]
pub struct Coverage {
    /// What the entry exercises, in words.
    pub what: &'static str,
    /// Left-hand side as a step label (`Sigma M`, `H_G`).
    pub label: &'static str,
    /// Component of the label (`x`) or empty.
    pub component: &'static str,
    /// The expression as parsed (its written shape is kept).
    pub expr: Expr,
}

/// Expressions that together use every construct the LaTeX printer emits:
/// time derivatives of order 1 to 5 (`\dot` … `\ddddot`, `^{(5)}`), rational
/// coefficients (`\frac`), quotients by constants, parentheses
/// (`\left( \right)`), powers of sin and cos (`\sin^{2}`), the thin space
/// after a trigonometric factor, multi-letter names (`\mathrm`), primed
/// names (`I'`), braced and Greek subscripts, labels with and without a
/// component, and every Greek name of the printer.
pub fn coverage() -> Vec<Coverage> {
    let constants = [
        "I_x", "I_y", "I_z", "I_xy", "Ip", "Ip_x", "m", "mass", "a", "b", "r_G", "I_theta",
    ];
    let mut time: Vec<&str> = vec!["x", "omega_x", "omega_y", "omega_z", "omega_1_2"];
    time.extend(crate::print::greek_names());
    let s = Symbols::parse_decl(&constants, &time);
    let (upper, lower): (Vec<&str>, Vec<&str>) =
        crate::print::greek_names().partition(|g| g.starts_with(|c: char| c.is_ascii_uppercase()));
    let greek_lower = lower.join(" + ");
    let greek_upper = upper.join(" + ");
    let greek_dotted = format!("{}'' + {}'", lower.join("' + "), upper.join("' + "));
    let entries: Vec<(&'static str, &'static str, &'static str, String)> = vec![
        (
            "time derivatives of order one to five",
            "q",
            "",
            "theta' + theta'' + theta''' + theta'''' + theta'''''".into(),
        ),
        (
            "subscripted derivatives, a label with a component",
            "Sigma M",
            "x",
            "I_x*omega_x' - (I_y - I_z)*omega_y*omega_z".into(),
        ),
        (
            "rational coefficients and a label whose name has a subscript",
            "H_G",
            "x",
            "1/2*m*x'^2 - 3/4*I_xy*omega_x*omega_y + 5*a".into(),
        ),
        (
            "powers of sin and cos, a thin space after a trigonometric factor",
            "T",
            "",
            "sin(theta)^2*cos(phi)^3 + sin(theta)*phi' - cos(x)^2 + sin(x)*cos(theta)".into(),
        ),
        (
            "quotients by constants",
            "f",
            "",
            "m/I_x - 2*a*b/(I_y*I_z^2) + 1/mass".into(),
        ),
        (
            "parentheses, nested and under a power, and negations",
            "g",
            "",
            "-(a - b)*(a + b)^2 - (x*(a + b))^3 + (-(a))".into(),
        ),
        (
            "primed and multi-letter names, braced and Greek subscripts",
            "h",
            "",
            "Ip*omega_x + Ip_x*omega_1_2' + mass*r_G + I_theta*omega_z".into(),
        ),
        ("every lower-case Greek name", "Sigma", "", greek_lower),
        ("every capital Greek name", "Omega", "", greek_upper),
        ("Greek names with dots", "Phi", "", greek_dotted),
    ];
    entries
        .into_iter()
        .map(|(what, label, component, text)| Coverage {
            what,
            label,
            component,
            expr: s
                .expr(&text)
                .unwrap_or_else(|e| panic!("coverage expression `{text}`: {}", e.message)),
        })
        .collect()
}

// -------------------------------------------------------- line breaking --

/// A rough width of LaTeX math in characters: commands that only decorate
/// count nothing, a Greek letter or a digit counts one, scripts count less.
fn math_width(s: &str) -> f32 {
    let mut w = 0.0;
    let mut script = 0usize; // brace depth inside ^{…} / _{…}
    let mut depth = 0usize;
    let mut chars = s.chars().peekable();
    let mut pending_script = false;
    let scale = |script: usize| if script > 0 { 0.7 } else { 1.0 };
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                // The command's name, without allocating (the names that
                // matter are short; a longer one counts as any other).
                let (mut name, mut len) = ([0u8; 8], 0);
                while let Some(&n) = chars.peek().filter(|n| n.is_ascii_alphabetic()) {
                    name[len.min(7)] = n as u8;
                    len += 1;
                    chars.next();
                }
                let name = if len <= 7 {
                    std::str::from_utf8(&name[..len]).unwrap_or("")
                } else {
                    "long"
                };
                if name.is_empty() {
                    chars.next(); // `\,` and friends
                    w += 0.3;
                    continue;
                }
                w += scale(script)
                    * match name {
                        "left" | "right" => 0.0,
                        "dot" | "ddot" | "dddot" | "ddddot" | "mathrm" | "frac" => 0.0,
                        "sin" | "cos" => 3.0,
                        _ => 1.0,
                    };
            }
            '^' | '_' => pending_script = true,
            '{' => {
                depth += 1;
                if pending_script || script > 0 {
                    script += 1;
                }
                pending_script = false;
            }
            '}' => {
                depth = depth.saturating_sub(1);
                script = script.saturating_sub(1);
            }
            ' ' => {}
            '+' | '-' | '=' => w += 2.0,
            '(' | ')' | ',' => w += 0.6 * scale(script),
            _ => {
                w += if pending_script { 0.7 } else { scale(script) };
                pending_script = false;
            }
        }
    }
    let _ = depth;
    w
}

/// The lines of one equation `lhs = rhs` for an `align*`/`aligned` block
/// no wider than `width` (estimated characters of math):
/// the first `lhs &= …`, continuation lines `&\quad + …`. The right side
/// is broken on its expression tree ([`print::break_pieces`]): between its
/// top-level terms, and inside the bracket of a product term that is
/// itself too long; each piece is printed by the printer and its width
/// estimated on its own. A break inside the bracket closes the line with
/// `\right.` and opens the next with `\left.`, so that every line is
/// balanced.
fn equation_lines(lhs: &str, rhs: &Expr, width: f32) -> Vec<String> {
    let budget = (width - math_width(lhs)).max(24.0);
    let printed = print::latex(rhs);
    if math_width(&printed) <= budget {
        return vec![format!("{lhs} &= {printed}")];
    }
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for (piece, inside) in print::break_pieces(rhs, &print::Latex, &|t| math_width(t) > budget) {
        if !current.is_empty() && math_width(&current) + math_width(&piece) > budget {
            let mut line = std::mem::take(&mut current);
            if inside {
                line.push_str(r" \right.");
                // `{}` keeps the sign that follows binary.
                current.push_str(r"\left. {} ");
            }
            lines.push(line);
        }
        if !current.is_empty() && !current.ends_with(' ') {
            current.push(' ');
        }
        current.push_str(&piece);
    }
    lines.push(current);
    lines
        .iter()
        .enumerate()
        .map(|(k, l)| {
            if k == 0 {
                format!("{lhs} &= {l}")
            } else {
                let sign = if l.starts_with("+ ") || l.starts_with("- ") {
                    "{} "
                } else {
                    ""
                };
                format!(r"&\quad {sign}{l}")
            }
        })
        .collect()
}

// ------------------------------------------------------------- pieces --

fn symbol_list(names: &[String]) -> String {
    names
        .iter()
        .map(|n| latex_name(n, 0))
        .collect::<Vec<_>>()
        // A permitted break after each comma: a long list wraps instead of
        // running into the margin.
        .join(",\\ \\allowbreak ")
}

/// The lines of equations in one `align*` block, one group per equation.
/// An equation labelled 0
/// always reads `… = 0`: when every such equation of the block fits on a
/// line they are aligned at `=` (`result &= 0`); when one must be broken,
/// each is set from the left edge of the block (`& result = 0`, the
/// continuation lines indented under it), so that a long equation never
/// turns into `0 = …` beside a short one that reads `… = 0`.
fn equations_groups(eqs: &[Equation], width: f32) -> Vec<Vec<String>> {
    let zero_fits = |e: &Equation| math_width(&print::latex(&e.rhs)) + 4.0 <= width;
    let aligned_at_equals = eqs.iter().filter(|e| e.lhs.is_zero()).all(zero_fits);
    eqs.iter()
        .map(|e| {
            if !e.lhs.is_zero() {
                equation_lines(&e.lhs.latex(), &e.rhs, width)
            } else if aligned_at_equals {
                vec![format!("{} &= 0", print::latex(&e.rhs))]
            } else {
                zero_lines(&e.rhs, width)
            }
        })
        .collect()
}

fn equations_lines(eqs: &[Equation], width: f32) -> Vec<String> {
    equations_groups(eqs, width).concat()
}

/// A matrix result (an inertia tensor, a mass matrix) as a matrix,
/// `M = [ … ]`, when it can be set within `width`: an entry too long for
/// its column is written by its name (M_{11}) and defined by an equation
/// after the matrix, the longest first, until the matrix fits; in a
/// symmetric matrix both entries of a pair carry the name of the one above
/// the diagonal, which alone is defined. The groups are the matrix, then
/// each definition. `None` for a result that is not a matrix, or one whose
/// columns do not fit even with every entry named.
fn matrix_groups(s: &StepBlock, width: f32) -> Option<Vec<Vec<String>>> {
    let (n, m) = s.shape?;
    if n * m < 2
        || !matches!(s.heading, crate::document::Lhs::Label(..))
        || n * m != s.equations.len()
    {
        return None;
    }
    let lhs = s.heading.latex();
    let entries: Vec<String> = s.equations.iter().map(|e| print::latex(&e.rhs)).collect();
    let names: Vec<String> = s.equations.iter().map(|e| e.lhs.latex()).collect();
    let at = |i: usize, j: usize| i * m + j;
    let symmetric =
        n == m && (0..n).all(|i| (0..i).all(|j| entries[at(i, j)] == entries[at(j, i)]));
    // The entry that stands at position k: the one above the diagonal of a
    // symmetric pair.
    let owner = |k: usize| {
        let (i, j) = (k / m, k % m);
        if symmetric && i > j { at(j, i) } else { k }
    };
    let budget = width - math_width(&lhs) - 3.0;
    let mut named = vec![false; n * m];
    loop {
        let cells: Vec<&str> = (0..n * m)
            .map(|k| {
                let o = owner(k);
                if named[o] { &names[o] } else { &entries[o] }
            })
            .map(String::as_str)
            .collect();
        let widths: Vec<f32> = cells.iter().map(|c| math_width(c)).collect();
        let total: f32 = (0..m)
            .map(|j| (0..n).map(|i| widths[at(i, j)]).fold(0.0, f32::max))
            .sum::<f32>()
            + 2.0 * m as f32;
        if total <= budget {
            let rows: Vec<String> = (0..n)
                .map(|i| cells[i * m..(i + 1) * m].join(" & "))
                .collect();
            let mut groups = vec![vec![format!(
                "{lhs} &= \\begin{{bmatrix}} {} \\end{{bmatrix}}",
                rows.join(r" \\ ")
            )]];
            for k in (0..n * m).filter(|&k| named[k]) {
                groups.push(equation_lines(&names[k], &s.equations[k].rhs, width));
            }
            return Some(groups);
        }
        let widest = (0..n * m)
            .filter(|&k| owner(k) == k && !named[k] && widths[k] > math_width(&names[k]))
            .max_by(|&a, &b| widths[a].total_cmp(&widths[b]))?;
        named[widest] = true;
    }
}

/// The equations of one step as groups of lines of an `align*` block:
/// a matrix as a matrix ([`matrix_groups`]), else one group per equation.
fn step_groups(s: &StepBlock, width: f32) -> Vec<Vec<String>> {
    matrix_groups(s, width).unwrap_or_else(|| equations_groups(&s.equations, width))
}

/// `rhs = 0` broken like [`equation_lines`], set from the left edge of the
/// block: `& a + b`, `&\quad {} + c = 0`.
fn zero_lines(rhs: &Expr, width: f32) -> Vec<String> {
    let mut lines = equation_lines("", rhs, width - 4.0);
    if let Some(last) = lines.last_mut() {
        last.push_str(" = 0");
    }
    lines
        .into_iter()
        .map(|l| match l.strip_prefix(" &= ") {
            Some(first) => format!("& {first}"),
            None => l,
        })
        .collect()
}

/// A step's title in LaTeX (also Markdown's math): `Step 3: $\\Sigma M$`,
/// the label as mathematics; only `Step 3` for a step labelled `0` (its
/// equations read `… = 0`). Number 0 gives the title of a slide without
/// a doc: the label alone.
fn step_title(n: usize, st: &StepBlock) -> String {
    if st.heading.is_zero() {
        if n == 0 {
            "Equation".to_owned()
        } else {
            format!("Step {n}")
        }
    } else if n == 0 {
        format!("${}$", st.heading.latex())
    } else {
        format!("Step {n}: ${}$", st.heading.latex())
    }
}

/// The sentence that replaces `0 = 0` for a step whose result vanishes
/// identically, as prose of the backend.
fn vanishes_text(markdown: bool) -> String {
    let text = capitalise(crate::render::VANISHES);
    if markdown {
        format!("*{}.*", prose::markdown(&text))
    } else {
        format!("\\emph{{{}.}}", prose::latex(&text))
    }
}

/// The body of an `align*` (or `aligned`) block for one step.
fn step_lines(s: &StepBlock, width: f32) -> String {
    step_groups(s, width).concat().join(" \\\\\n")
}

fn failure_lines(fails: &[(Equation, Equation)], width: f32) -> String {
    let lines: Vec<String> = fails
        .iter()
        .flat_map(|(exp, diff)| {
            let mut l = equation_lines(
                &format!("{}^{{\\text{{expected}}}}", exp.lhs.latex()),
                &exp.rhs,
                width,
            );
            l.extend(equation_lines(r"\text{difference}", &diff.rhs, width));
            l
        })
        .collect();
    lines.join(" \\\\\n")
}

/// Ω of a frame inside a line of text: plain parentheses and a permitted
/// break after each comma, so that a long Ω wraps instead of running into
/// the margin (a `\left(…\right)` group cannot be broken).
fn omega_inline(f: &crate::document::FrameItem) -> String {
    let c: Vec<String> = f.omega.iter().map(|e| print::latex(&e.rhs)).collect();
    format!("({})", c.join(",\\ \\allowbreak "))
}

/// Code (a formula as written, a file name) for `\texttt`: every
/// character is kept as it is written, none becomes math.
fn latex_code(s: &str) -> String {
    escape::latex(s, escape::Latex::Code)
}

fn label_key(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}

/// The text with a capital first letter and a final full stop.
fn sentence(s: &str) -> String {
    let s = capitalise(s.trim());
    if s.is_empty() || s.ends_with(['.', '!', '?', ':']) {
        s
    } else {
        format!("{s}.")
    }
}

/// The text with a capital first letter, unless it begins with notation
/// that a capital would change: a function name before its argument
/// (`tan γ = …` stays `tan γ`).
fn capitalise(s: &str) -> String {
    let first = s
        .split(|c: char| !c.is_ascii_alphabetic())
        .next()
        .unwrap_or("");
    if prose::FUNCTIONS.contains(&first) && s[first.len()..].starts_with(' ') {
        return s.to_owned();
    }
    let mut cs = s.chars();
    match cs.next() {
        Some(c) if c.is_ascii_lowercase() => c.to_ascii_uppercase().to_string() + cs.as_str(),
        _ => s.to_owned(),
    }
}

// --------------------------------------------------------------- LaTeX --

/// Where LaTeX is going: the article (with hyperref), or a fragment to
/// `\input` in a document we know nothing about.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Target {
    Article,
    Fragment,
}

/// A heading; in the article, with a plain-text PDF bookmark when the
/// title has math.
fn latex_heading(cmd: &str, title: &str, target: Target) -> String {
    let tex = prose::latex(title);
    let plain = prose::ascii(title);
    if target == Target::Fragment || tex == plain {
        format!("\\{cmd}{{{tex}}}")
    } else {
        format!("\\{cmd}{{\\texorpdfstring{{{tex}}}{{{plain}}}}}")
    }
}

const LATEX_PREAMBLE: &str = r"\documentclass[11pt,a4paper]{article}
\usepackage[T1]{fontenc}
\usepackage[utf8]{inputenc}
\usepackage{lmodern}
\usepackage{amsmath}
\usepackage{amssymb}
\usepackage[margin=2.2cm]{geometry}
\usepackage[hidelinks]{hyperref}
\allowdisplaybreaks
\setlength{\emergencystretch}{2em}
\tracinglostchars=2
\setlength{\parindent}{0pt}
\setlength{\parskip}{0.5\baselineskip}
";

fn generated_comment(o: &mut String) {
    let _ = writeln!(
        o,
        "% Generated by `hdot notes` from the derivation files; do not edit.\n\
         % Refresh with: {REFRESH_COMMAND}"
    );
}

/// Whether the document is divided into chapters.
fn has_chapters(doc: &Document) -> bool {
    doc.chapters.iter().any(|c| !c.title.is_empty())
}

/// The lecture notes as a complete LaTeX article: a section per chapter
/// and a subsection per derivation (a section per derivation when there
/// are no chapters).
pub fn latex_document(doc: &Document) -> String {
    let mut o = String::new();
    generated_comment(&mut o);
    o.push_str(LATEX_PREAMBLE);
    let _ = writeln!(o, "\\title{{{}}}", prose::latex(&doc.title));
    let _ = writeln!(o, "\\author{{{}}}", prose::latex(&doc.author));
    let _ = writeln!(o, "\\date{{}}\n");
    let _ = writeln!(o, "\\begin{{document}}\n\\maketitle\n");
    if !doc.intro.trim().is_empty() {
        let _ = writeln!(o, "{}\n", prose::latex(doc.intro.trim()));
    }
    o.push_str("\\tableofcontents\n");
    let chapters = has_chapters(doc);
    for c in &doc.chapters {
        if chapters {
            let _ = writeln!(
                o,
                "\n\\clearpage\n{}",
                latex_heading("section", &c.title, Target::Article)
            );
            if !c.intro.trim().is_empty() {
                let _ = writeln!(o, "{}\n", prose::latex(c.intro.trim()));
            }
        }
        for (k, s) in c.sections.iter().enumerate() {
            if !chapters || k > 0 {
                o.push_str("\n\\clearpage");
            }
            o.push('\n');
            latex_section(&mut o, s, if chapters { 1 } else { 0 }, Target::Article);
        }
    }
    o.push_str("\n\\end{document}\n");
    o
}

/// One derivation as a LaTeX fragment to `\input` in an existing
/// document: a `\section` with its steps, needing only the packages
/// amsmath and amssymb (no preamble, no macros of hdot's own). It is the
/// same section the notes print.
pub fn latex_fragment(d: &crate::derivation::Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "% {} --- generated by hdot from {}; \\input this file in a document\n\
         % that loads amsmath and amssymb.",
        prose::ascii(&d.title),
        escape::latex(&d.path, escape::Latex::Comment)
    );
    latex_section(&mut o, &Section::of(d, None), 0, Target::Fragment);
    o
}

const LEVELS: [&str; 3] = ["section", "subsection", "subsubsection"];

fn latex_section(o: &mut String, s: &Section, level: usize, target: Target) {
    let _ = writeln!(o, "{}", latex_heading(LEVELS[level], &s.title, target));
    let _ = writeln!(o, "\\label{{sec:{}}}\n", label_key(&s.name));
    let _ = writeln!(o, "\\textbf{{Source:}} {}\\\\", prose::latex(&s.source));
    let _ = writeln!(o, "\\textbf{{File:}} \\texttt{{{}}}\n", latex_code(&s.path));
    if !s.summary.is_empty() {
        let _ = writeln!(o, "{}\n", prose::latex(&s.summary));
    }
    let sub = LEVELS[level + 1];
    let _ = writeln!(o, "\\{sub}*{{What is assumed}}");
    let mut items: Vec<String> = s.assumptions.iter().map(|a| prose::latex(a)).collect();
    if !s.constants.is_empty() {
        items.push(format!("Constants: ${}$.", symbol_list(&s.constants)));
    }
    if !s.time.is_empty() {
        items.push(format!("Functions of time: ${}$.", symbol_list(&s.time)));
    }
    for (name, def, doc) in &s.abbreviations {
        items.push(format!(
            "Abbreviation: ${} = {}${}",
            latex_name(name, 0),
            print::latex(def),
            latex_doc_suffix(doc)
        ));
    }
    if !s.frames.is_empty() {
        items.push(
            "Frames, each with its angular velocity $\\boldsymbol{\\Omega}$ relative to the \
             inertial frame $N$, in the frame's own axes:"
                .to_owned(),
        );
    }
    if !items.is_empty() {
        let _ = writeln!(o, "\\begin{{itemize}}");
        for it in &items {
            let _ = writeln!(o, "  \\item{{}} {it}");
        }
        if !s.frames.is_empty() {
            let _ = writeln!(o, "  \\begin{{itemize}}");
            for f in &s.frames {
                let parent = match &f.parent {
                    Some(p) => format!(" (turned from ${}$)", latex_name(p, 0)),
                    None => String::new(),
                };
                let omega = omega_inline(f);
                let axes = symbol_list(&f.axes);
                let doc = latex_doc_suffix(&f.doc);
                let name = latex_name(&f.name, 0);
                if math_width(&omega) <= 40.0 {
                    let _ = writeln!(
                        o,
                        "    \\item{{}} ${name}$, axes ${axes}${parent}: \
                         $\\boldsymbol{{\\Omega}} = {omega}${doc}"
                    );
                } else {
                    let _ = writeln!(
                        o,
                        "    \\item{{}} ${name}$, axes ${axes}${parent}{doc}:\n\
                         \\begin{{align*}}\n{}\n\\end{{align*}}",
                        equations_lines(&f.omega, LINE_BUDGET).join(" \\\\\n")
                    );
                }
            }
            let _ = writeln!(o, "  \\end{{itemize}}");
        }
        let _ = writeln!(o, "\\end{{itemize}}");
    }
    let _ = writeln!(o, "\\{sub}*{{Steps}}");
    for (n, st) in s.steps.iter().enumerate() {
        let _ = writeln!(
            o,
            "\\par\\medskip\\noindent\\textbf{{{}.}}\\quad {}",
            step_title(n + 1, st),
            prose::latex(&sentence(&st.doc))
        );
        let frame = st
            .frame
            .as_ref()
            .map(|f| format!(", components in frame ${}$", latex_name(f, 0)))
            .unwrap_or_default();
        let _ = writeln!(
            o,
            "{{\\raggedright Written in the file as \\texttt{{{}}}{frame}.\\par}}",
            latex_code(&st.formula)
        );
        if st.vanishes() {
            let _ = writeln!(o, "{}\n", vanishes_text(false));
        } else {
            let _ = writeln!(
                o,
                "\\begin{{align*}}\n{}\n\\end{{align*}}",
                step_lines(st, LINE_BUDGET)
            );
        }
        match &st.verdict {
            Verdict::NoExpectation => {
                let _ = writeln!(o, "\\emph{{No expectation is stated for this step.}}\n");
            }
            Verdict::Holds => {
                let _ = writeln!(o, "$\\checkmark$ Equals the expected (textbook) form.\n");
            }
            Verdict::Fails(f) => {
                let _ = writeln!(
                    o,
                    "\\textbf{{Does not equal the expected form}} (derived $-$ expected is shown):"
                );
                let _ = writeln!(
                    o,
                    "\\begin{{align*}}\n{}\n\\end{{align*}}\n",
                    failure_lines(f, LINE_BUDGET)
                );
            }
        }
    }
}

fn latex_doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!(" --- {}", prose::latex(doc))
    }
}

// -------------------------------------------------------------- slides --

const SLIDES_PREAMBLE: &str = r"\documentclass[11pt]{beamer}
\usepackage[T1]{fontenc}
\usepackage[utf8]{inputenc}
\usepackage{lmodern}
\usepackage{amsmath}
\usepackage{amssymb}
\usetheme{default}
\setbeamertemplate{navigation symbols}{}
\setbeamertemplate{footline}[frame number]
\tracinglostchars=2
";

/// Options of every frame: top-aligned, and shrunk only as far as needed
/// when its content is taller than the slide, with a warning that
/// `scripts/build_notes` turns into a failure: a safety net, since a
/// frame that would not fit is split ([`slides_step`], [`slides_intro`]);
/// a frame that fits is set as it is.
const FRAME_OPTIONS: &str = "t,shrink=0";

/// The notes as LaTeX Beamer slides: a title frame, a frame of contents,
/// then for each derivation a frame with its summary and what is assumed,
/// and one frame per shown step with its result in textbook form; a
/// frame that would be taller than the slide (estimated from the printed
/// lines) continues on further frames.
pub fn slides_document(doc: &Document) -> String {
    let mut o = String::new();
    generated_comment(&mut o);
    o.push_str(SLIDES_PREAMBLE);
    let _ = writeln!(o, "\\title{{{}}}", prose::latex(&doc.title));
    let _ = writeln!(o, "\\author{{{}}}", prose::latex(&doc.author));
    let _ = writeln!(o, "\\date{{}}\n");
    let _ = writeln!(
        o,
        "\\begin{{document}}\n\\begin{{frame}}\n\\titlepage\n\\end{{frame}}\n"
    );
    if has_chapters(doc) {
        let _ = writeln!(
            o,
            "\\begin{{frame}}{{Contents}}\n\\tableofcontents\n\\end{{frame}}\n"
        );
    }
    for c in &doc.chapters {
        slides_chapter(&mut o, c);
    }
    o.push_str("\\end{document}\n");
    o
}

fn frame_title(title: &str) -> String {
    prose::latex(title)
}

fn slides_chapter(o: &mut String, c: &Chapter) {
    if !c.title.is_empty() {
        let _ = writeln!(o, "\\section{{{}}}", latex_heading_plain(&c.title));
    }
    for s in &c.sections {
        if c.title.is_empty() {
            let _ = writeln!(o, "\\section{{{}}}", latex_heading_plain(&s.title));
        }
        slides_intro(o, s);
        for st in &s.steps {
            slides_step(o, &s.title, st);
        }
    }
}

// The height of a frame, estimated from the expression trees' printed
// lines (an 11pt Beamer frame, 128 mm × 96 mm), in units of one line of
// plain math in an `align*` block (about 18pt).

/// The text height of a frame below a one-line title.
const FRAME_HEIGHT: f32 = 11.6;
/// What a step's frame holds besides its equations: the line saying what
/// the step does, the verdict, the space around the `align*` block, and
/// a margin for the estimate.
const FRAME_FIXED: f32 = 2.9;
/// Characters of a frame title per line (it wraps beyond).
const TITLE_CHARS: usize = 48;
/// Characters of small prose per line.
const NOTE_CHARS: usize = 85;
/// The height of a line of small prose.
const NOTE_HEIGHT: f32 = 0.55;

/// Characters of a summary or assumption (`\\small`) per line.
const SMALL_CHARS: usize = 72;
/// The height of a line of a summary or assumption.
const SMALL_HEIGHT: f32 = 0.62;

/// The frame that opens a derivation: its source, summary and
/// assumptions; assumptions that do not fit below the summary continue on
/// a further frame.
fn slides_intro(o: &mut String, s: &Section) {
    let title = frame_title(&s.title);
    let room =
        FRAME_HEIGHT - (text_lines(prose::ascii(&s.title).chars().count(), TITLE_CHARS) - 1.0);
    let small = |t: &str, chars: usize| text_lines(t.chars().count(), chars) * SMALL_HEIGHT;
    let mut used = text_lines(s.source.chars().count(), NOTE_CHARS) * NOTE_HEIGHT + 0.4;
    let _ = writeln!(
        o,
        "\\begin{{frame}}[{FRAME_OPTIONS}]{{{title}}}\n{{\\footnotesize {}\\par}}\\medskip",
        prose::latex(&s.source)
    );
    if !s.summary.is_empty() {
        let _ = writeln!(o, "{{\\small {}\\par}}", prose::latex(&s.summary));
        used += small(&s.summary, SMALL_CHARS);
    }
    let heights: Vec<f32> = s
        .assumptions
        .iter()
        .map(|a| small(a, SMALL_CHARS - 6) + 0.15)
        .collect();
    let next_frame = |o: &mut String, what: &str| {
        let _ = writeln!(
            o,
            "\\end{{frame}}\n\n\\begin{{frame}}[{FRAME_OPTIONS}]{{{title}}}\n\
             {{\\footnotesize {what}\\par}}"
        );
    };
    if !s.assumptions.is_empty() {
        // The list stays below the summary when it fits there whole.
        if used + 0.5 + heights.iter().sum::<f32>() > room && !s.summary.is_empty() {
            next_frame(o, "What is assumed");
            used = NOTE_HEIGHT;
        }
        let _ = writeln!(o, "\\begin{{itemize}}\\small");
        used += 0.5;
        let mut on_frame = 0;
        for (a, h) in s.assumptions.iter().zip(&heights) {
            if used + h > room && on_frame > 0 {
                let _ = writeln!(o, "\\end{{itemize}}");
                next_frame(o, "What is assumed (continued)");
                let _ = writeln!(o, "\\begin{{itemize}}\\small");
                used = NOTE_HEIGHT + 0.5;
                on_frame = 0;
            }
            let _ = writeln!(o, "  \\item {}", prose::latex(a));
            used += h;
            on_frame += 1;
        }
        let _ = writeln!(o, "\\end{{itemize}}");
    }
    let _ = writeln!(o, "\\end{{frame}}\n");
}

/// The estimated height of one line of an `align*` block: a line with a
/// fraction is taller (display style), a matrix counts its rows.
fn line_height(l: &str) -> f32 {
    let frac = |t: &str| t.contains(r"\frac");
    if let Some(k) = l.find(r"\begin{bmatrix}") {
        let body = &l[k..];
        return 0.3
            + body
                .split(r"\\")
                .map(|row| if frac(row) { 1.25 } else { 0.75 })
                .sum::<f32>();
    }
    if frac(l) { 1.6 } else { 1.0 }
}

/// Lines of `chars` characters a text of `n` characters takes.
fn text_lines(n: usize, chars: usize) -> f32 {
    n.div_ceil(chars).max(1) as f32
}

/// The groups of lines of a step split into frames: as few frames as the
/// room on one allows, filled evenly, an equation kept on one frame
/// unless it is taller than a frame alone (then its lines continue on the
/// next).
fn frames_of(groups: Vec<Vec<String>>, room: f32) -> Vec<Vec<String>> {
    let mut pieces: Vec<(Vec<String>, f32)> = Vec::new();
    for g in groups {
        let mut piece: (Vec<String>, f32) = (Vec::new(), 0.0);
        for l in g {
            let h = line_height(&l);
            if !piece.0.is_empty() && piece.1 + h > room {
                pieces.push(std::mem::take(&mut piece));
            }
            piece.0.push(l);
            piece.1 += h;
        }
        pieces.push(piece);
    }
    let total: f32 = pieces.iter().map(|p| p.1).sum();
    let target = total / (total / room).ceil().max(1.0);
    let mut frames: Vec<(Vec<String>, f32)> = Vec::new();
    for (lines, h) in pieces {
        match frames.last_mut() {
            Some(f) if f.1 + h <= room && f.1 + h / 2.0 <= target => {
                f.0.extend(lines);
                f.1 += h;
            }
            _ => frames.push((lines, h)),
        }
    }
    frames.into_iter().map(|f| f.0).collect()
}

/// The frames of one step: its equations in textbook form, split into
/// continuation frames (the step's line marked *continued*) when they are
/// taller than a frame; the verdict on the last.
fn slides_step(o: &mut String, section_title: &str, st: &StepBlock) {
    let title = frame_title(section_title);
    let note = if st.doc.trim().is_empty() {
        step_title(0, st)
    } else {
        prose::latex(&sentence(&st.doc))
    };
    let note_chars = if st.doc.trim().is_empty() {
        8
    } else {
        st.doc.chars().count()
    };
    let room = FRAME_HEIGHT
        - FRAME_FIXED
        - (text_lines(prose::ascii(section_title).chars().count(), TITLE_CHARS) - 1.0)
        - (text_lines(note_chars + 12, NOTE_CHARS) - 1.0) * NOTE_HEIGHT;
    let frames = if st.vanishes() {
        vec![Vec::new()]
    } else {
        frames_of(step_groups(st, SLIDE_BUDGET), room)
    };
    let last = frames.len() - 1;
    for (k, lines) in frames.iter().enumerate() {
        let cont = if k > 0 { " (continued)" } else { "" };
        let _ = writeln!(
            o,
            "\\begin{{frame}}[{FRAME_OPTIONS}]{{{title}}}\n{{\\footnotesize {note}{cont}\\par}}"
        );
        if st.vanishes() {
            let _ = writeln!(o, "{}\\par", vanishes_text(false));
        } else {
            let _ = writeln!(
                o,
                "\\begin{{align*}}\n{}\n\\end{{align*}}",
                lines.join(" \\\\\n")
            );
        }
        if k == last {
            match &st.verdict {
                Verdict::NoExpectation => {}
                Verdict::Holds => {
                    let _ = writeln!(o, "{{\\footnotesize $\\checkmark$ the textbook form\\par}}");
                }
                Verdict::Fails(_) => {
                    let _ = writeln!(
                        o,
                        "{{\\footnotesize\\textbf{{Does not equal the expected form.}}\\par}}"
                    );
                }
            }
        }
        let _ = writeln!(o, "\\end{{frame}}\n");
    }
}

/// A heading for Beamer's outline (which cannot hold every construct): the
/// prose as LaTeX, protected.
fn latex_heading_plain(title: &str) -> String {
    let tex = prose::latex(title);
    let plain = prose::ascii(title);
    if tex == plain {
        tex
    } else {
        format!("\\texorpdfstring{{{tex}}}{{{plain}}}")
    }
}

// ------------------------------------------------------------ coverage --

/// The printer-coverage test document: every entry of [`coverage`] in an
/// `align*` block, as a complete LaTeX article. It is not part of the
/// notes; `scripts/build_notes` compiles it to prove each construct the
/// printer can emit typesets.
pub fn coverage_document() -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "% Generated by `hdot notes --printer-coverage`; a test document."
    );
    o.push_str(LATEX_PREAMBLE);
    let _ = writeln!(o, "\\begin{{document}}\n\\section*{{Printer coverage}}\n");
    let _ = writeln!(
        o,
        "{}\n",
        prose::latex(
            "These expressions are built in code, not derived: together they use every \
             construct the LaTeX printer can emit, so that compiling this document proves \
             each of them typesets."
        )
    );
    for c in coverage() {
        let _ = writeln!(
            o,
            "\\par\\medskip\\noindent {}\n\\begin{{align*}}\n{}\n\\end{{align*}}",
            prose::latex(&sentence(&capitalise(c.what))),
            equation_lines(&latex_label(c.label, c.component), &c.expr, LINE_BUDGET)
                .join(" \\\\\n")
        );
    }
    o.push_str("\n\\end{document}\n");
    o
}

// ------------------------------------------------------------ Markdown --

/// Inline code that may itself contain backticks.
fn md_code(s: &str) -> String {
    escape::markdown_code(s)
}

fn md_anchor(name: &str) -> String {
    label_key(name).to_ascii_lowercase()
}

/// The lecture notes as one Markdown page with `$$` math: the same
/// content as [`latex_document`], in the same order.
pub fn markdown_document(doc: &Document) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "# {}\n", prose::markdown(&doc.title));
    let _ = writeln!(
        o,
        "<!-- Generated by `hdot notes` from the derivation files; do not edit. \
         Refresh with: {REFRESH_COMMAND} -->\n"
    );
    if !doc.author.is_empty() {
        let _ = writeln!(o, "*{}*\n", prose::markdown(&doc.author));
    }
    if !doc.intro.trim().is_empty() {
        let _ = writeln!(o, "{}\n", prose::markdown(doc.intro.trim()));
    }
    let chapters = has_chapters(doc);
    let _ = writeln!(o, "## Contents\n");
    for (i, c) in doc.chapters.iter().enumerate() {
        if chapters {
            let _ = writeln!(o, "{}. {}", i + 1, prose::markdown(&c.title));
        }
        for (k, s) in c.sections.iter().enumerate() {
            let indent = if chapters { "   " } else { "" };
            let _ = writeln!(
                o,
                "{indent}{}. [{}](#{})",
                k + 1,
                prose::markdown(&s.title),
                md_anchor(&s.name)
            );
        }
    }
    o.push('\n');
    for (i, c) in doc.chapters.iter().enumerate() {
        if chapters {
            let _ = writeln!(o, "## {}. {}\n", i + 1, prose::markdown(&c.title));
            if !c.intro.trim().is_empty() {
                let _ = writeln!(o, "{}\n", prose::markdown(c.intro.trim()));
            }
        }
        for (k, s) in c.sections.iter().enumerate() {
            let number = if chapters {
                format!("{}.{}", i + 1, k + 1)
            } else {
                format!("{}.", k + 1)
            };
            markdown_section(&mut o, &number, s, if chapters { 3 } else { 2 });
        }
    }
    o
}

/// One derivation as Markdown: the section the notes print.
pub fn markdown_fragment(d: &crate::derivation::Derivation) -> String {
    let mut o = String::new();
    markdown_section(&mut o, "", &Section::of(d, None), 2);
    o
}

fn md_math_block(o: &mut String, body: &str) {
    let body = escape::markdown_math(body);
    let _ = writeln!(o, "$$\n\\begin{{aligned}}\n{body}\n\\end{{aligned}}\n$$\n");
}

/// Names as Markdown math (see [`escape::markdown_math`]).
fn md_name(name: &str, order: u32) -> String {
    escape::markdown_math(&latex_name(name, order))
}

fn md_symbols(names: &[String]) -> String {
    escape::markdown_math(&symbol_list(names))
}

fn markdown_section(o: &mut String, number: &str, s: &Section, level: usize) {
    let h = "#".repeat(level);
    let sub = "#".repeat(level + 1);
    let _ = writeln!(o, "<a id=\"{}\"></a>\n", md_anchor(&s.name));
    let number = if number.is_empty() {
        String::new()
    } else {
        format!("{number} ")
    };
    let _ = writeln!(o, "{h} {number}{}\n", prose::markdown(&s.title));
    let _ = writeln!(o, "**Source:** {}  ", prose::markdown(&s.source));
    let _ = writeln!(o, "**File:** {}\n", md_code(&s.path));
    if !s.summary.is_empty() {
        let _ = writeln!(o, "{}\n", prose::markdown(&s.summary));
    }
    let _ = writeln!(o, "{sub} What is assumed\n");
    for a in &s.assumptions {
        let _ = writeln!(o, "- {}", prose::markdown(a));
    }
    if !s.constants.is_empty() {
        let _ = writeln!(o, "- Constants: ${}$.", md_symbols(&s.constants));
    }
    if !s.time.is_empty() {
        let _ = writeln!(o, "- Functions of time: ${}$.", md_symbols(&s.time));
    }
    for (name, def, doc) in &s.abbreviations {
        let _ = writeln!(
            o,
            "- Abbreviation: ${} = {}${}",
            md_name(name, 0),
            print::latex(def),
            md_doc_suffix(doc)
        );
    }
    if !s.frames.is_empty() {
        let _ = writeln!(
            o,
            "- Frames, each with its angular velocity $\\boldsymbol{{\\Omega}}$ relative to \
             the inertial frame $N$, in the frame's own axes:"
        );
        for f in &s.frames {
            let parent = match &f.parent {
                Some(p) => format!(" (turned from ${}$)", md_name(p, 0)),
                None => String::new(),
            };
            let _ = writeln!(
                o,
                "  - ${}$, axes ${}${parent}: $\\boldsymbol{{\\Omega}} = {}${}",
                md_name(&f.name, 0),
                md_symbols(&f.axes),
                omega_inline(f),
                md_doc_suffix(&f.doc)
            );
        }
    }
    let _ = writeln!(o, "\n{sub} Steps\n");
    for (k, st) in s.steps.iter().enumerate() {
        let _ = writeln!(
            o,
            "**{}.** {}\n",
            escape::markdown_math(&step_title(k + 1, st)),
            prose::markdown(&sentence(&st.doc))
        );
        let frame = st
            .frame
            .as_ref()
            .map(|f| format!(", components in frame ${}$", md_name(f, 0)))
            .unwrap_or_default();
        let _ = writeln!(
            o,
            "Written in the file as {}{frame}.\n",
            md_code(&st.formula)
        );
        if st.vanishes() {
            let _ = writeln!(o, "{}\n", vanishes_text(true));
        } else {
            md_math_block(o, &step_lines(st, LINE_BUDGET));
        }
        match &st.verdict {
            Verdict::NoExpectation => {
                let _ = writeln!(o, "*No expectation is stated for this step.*\n");
            }
            Verdict::Holds => {
                let _ = writeln!(o, "✓ Equals the expected (textbook) form.\n");
            }
            Verdict::Fails(f) => {
                let _ = writeln!(
                    o,
                    "✗ **Does not equal the expected form** (derived − expected is shown):\n"
                );
                md_math_block(o, &failure_lines(f, LINE_BUDGET));
            }
        }
    }
}

fn md_doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!(" — {}", prose::markdown(doc))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
