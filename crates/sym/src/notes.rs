//! Lecture notes: every derivation, step by step, as one LaTeX document
//! ([`latex_document`]) and as one Markdown page ([`markdown_document`]).
//!
//! Both show the same things for each derivation, in the same order: its
//! title, source and file; the summary; what is assumed (assumptions,
//! symbols, abbreviations, frames with their angular velocity Ω); then
//! every shown step with what it does, the formula as written in the file,
//! the result in textbook form and whether the expectation holds. An
//! appendix, *Printer coverage* ([`coverage`]), prints a fixed list of
//! expressions that together use every construct the LaTeX printer can
//! emit, so compiling the document proves that each of them typesets.
//!
//! The LaTeX document needs only packages of Debian's
//! `texlive-latex-base`, `texlive-latex-recommended` and
//! `texlive-fonts-recommended` (amsmath, amssymb, geometry, hyperref,
//! lmodern) and compiles with `pdflatex`. All prose goes through
//! [`latex_text`], so it holds no character that pdflatex cannot typeset:
//! apart from ASCII, only the accented letters of Latin-1 are left as they
//! are.
//!
//! The output depends only on the derivations (no date, no paths other
//! than the ones the derivations carry), so a committed copy can be
//! compared byte for byte with a fresh one.
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
//! let tex = hdot_sym::notes::latex_document(&[d.clone()]);
//! assert!(tex.contains(r"\section{Angular momentum of a sphere}"));
//! assert!(tex.contains(r"H_{x} &= I w_x"));
//! assert!(tex.contains(r"\end{document}"));
//! let md = hdot_sym::notes::markdown_document(&[d]);
//! assert!(md.contains("$$\n\\begin{aligned}\nH_{x} &= I w_x"));
//! ```

use std::fmt::Write;

use crate::derivation::{Check, Derivation, Step, Value};
use crate::expr::Expr;
use crate::print;
use crate::render::{latex_label, latex_text, unicode_math};
use crate::symbols::{Decl, Symbols};

/// The command that regenerates the committed notes in `docs/notes/`.
pub const REFRESH_COMMAND: &str = "cargo run -p hdot -- notes";

/// Title of the notes.
pub const TITLE: &str = "Three-dimensional rigid-body kinetics: the derivations of hdot";

/// File name of the LaTeX document.
pub const LATEX_FILE: &str = "hdot-notes.tex";

/// File name of the Markdown document.
pub const MARKDOWN_FILE: &str = "hdot-notes.md";

/// Estimated width (in characters of math) beyond which an equation's
/// right-hand side is broken before a `+` or `−` onto further lines.
const LINE_BUDGET: f32 = 58.0;

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
                let mut name = String::new();
                while let Some(&n) = chars.peek() {
                    if n.is_ascii_alphabetic() {
                        name.push(n);
                        chars.next();
                    } else {
                        break;
                    }
                }
                if name.is_empty() {
                    chars.next(); // `\,` and friends
                    w += 0.3;
                    continue;
                }
                w += scale(script)
                    * match name.as_str() {
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

/// Splits printed LaTeX math before every `+` or `-` between top-level
/// terms (outside braces and `\left( … \right)`); the sign stays with the
/// term that follows.
fn split_terms(s: &str) -> Vec<String> {
    let bytes = s.as_bytes();
    let mut depth = 0i32;
    let mut parts = Vec::new();
    let mut start = 0;
    let mut i = 0;
    while i < bytes.len() {
        let rest = &s[i..];
        if rest.starts_with(r"\left") {
            depth += 1;
            i += 5;
            continue;
        }
        if rest.starts_with(r"\right") {
            depth -= 1;
            i += 6;
            continue;
        }
        match bytes[i] {
            b'{' => depth += 1,
            b'}' => depth -= 1,
            b' ' if depth == 0 && (rest.starts_with(" + ") || rest.starts_with(" - ")) => {
                parts.push(s[start..i].to_owned());
                start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    parts.push(s[start..].to_owned());
    parts
}

/// The position of the first `\left(` outside braces and other
/// parentheses in `s`, and of its matching `\right)`.
fn outer_parens(s: &str) -> Option<(usize, usize)> {
    let mut depth = 0i32;
    let mut open = None;
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        if rest.starts_with(r"\left") {
            if depth == 0 && open.is_none() && rest.starts_with(r"\left(") {
                open = Some(i);
            }
            depth += 1;
            i += 5;
            continue;
        }
        if rest.starts_with(r"\right") {
            depth -= 1;
            if depth == 0
                && let Some(o) = open
            {
                return rest.starts_with(r"\right)").then_some((o, i));
            }
            i += 6;
            continue;
        }
        match s.as_bytes()[i] {
            b'{' => depth += 1,
            b'}' => depth -= 1,
            _ => {}
        }
        i += 1;
    }
    None
}

/// The pieces a long equation may be broken between: the top-level terms
/// of `rhs`, and inside a term that is itself too long, the terms of its
/// first parenthesised sum. Each piece says whether a break before it
/// falls inside that parenthesis.
fn pieces(rhs: &str, budget: f32) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    for term in split_terms(rhs) {
        if math_width(&term) > budget
            && let Some((l, r)) = outer_parens(&term)
        {
            let inner = split_terms(&term[l + 6..r]);
            if inner.len() > 1 {
                let last = inner.len() - 1;
                for (k, t) in inner.into_iter().enumerate() {
                    let mut piece = String::new();
                    if k == 0 {
                        piece.push_str(&term[..l]);
                        piece.push_str(r"\left(");
                    }
                    piece.push_str(&t);
                    if k == last {
                        piece.push_str(&term[r..]);
                    }
                    out.push((piece, k > 0));
                }
                continue;
            }
        }
        out.push((term, false));
    }
    out
}

/// The lines of one equation `lhs = rhs` for an `align*`/`aligned` block:
/// the first `lhs &= …`, continuation lines `&\quad + …`. A break inside
/// parentheses closes the line with `\right.` and opens the next with
/// `\left.`, so that every line is balanced.
fn equation_lines(lhs: &str, rhs: &str) -> Vec<String> {
    let budget = (LINE_BUDGET - math_width(lhs)).max(24.0);
    if math_width(rhs) <= budget {
        return vec![format!("{lhs} &= {rhs}")];
    }
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for (piece, inside) in pieces(rhs, budget) {
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

/// The body of an `align*` (or `aligned`) block for one step.
fn step_lines(s: &Step) -> String {
    let lines: Vec<String> = s
        .components
        .iter()
        .flat_map(|(c, e)| equation_lines(&crate::render::step_lhs_latex(s, c), &print::latex(e)))
        .collect();
    lines.join(" \\\\\n")
}

fn coverage_lines(c: &Coverage) -> String {
    equation_lines(&latex_label(c.label, c.component), &print::latex(&c.expr)).join(" \\\\\n")
}

// ------------------------------------------------------------- pieces --

fn symbol_list(d: &Derivation, want: fn(&Decl) -> bool) -> Vec<String> {
    d.symbols
        .names()
        .iter()
        .filter(|n| d.symbols.get(n).is_some_and(want))
        .map(|n| print::latex_symbol(n, 0))
        .collect()
}

fn frame_omega(d: &Derivation, k: usize) -> String {
    let c: Vec<String> = d.frames[k]
        .omega
        .0
        .iter()
        .map(|p| print::latex(&Expr::from_poly(p)))
        .collect();
    format!(r"\left({}\right)", c.join(",\\ "))
}

fn vector_frame(s: &Step) -> Option<&str> {
    match &s.value {
        Value::Vector(_, f) => Some(f),
        _ => None,
    }
}

fn failed_check_math(s: &Step, c: &Check) -> (String, String, String) {
    (
        crate::render::step_lhs_latex(s, &c.component),
        print::latex(&c.expected),
        print::latex(&Expr::from_poly(&c.difference)),
    )
}

/// Escapes code (a formula as written) for `\texttt`: every character is
/// kept as it is written, none becomes math, except non-ASCII symbols.
fn latex_code(s: &str) -> String {
    let mut o = String::new();
    for c in s.chars() {
        match c {
            '\\' => o.push_str(r"\textbackslash{}"),
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                o.push('\\');
                o.push(c);
            }
            '~' => o.push_str(r"\textasciitilde{}"),
            '^' => o.push_str(r"\textasciicircum{}"),
            // Straight quotes in typewriter type, and a break point after
            // commas so long formulas can wrap.
            '\'' => o.push_str(r"\textquotesingle{}"),
            '"' => o.push_str(r"\textquotedbl{}"),
            ',' => o.push_str(r",\allowbreak{}"),
            '<' => o.push_str(r"\textless{}"),
            '>' => o.push_str(r"\textgreater{}"),
            c if c.is_ascii() => o.push(c),
            c => o.push_str(&latex_text(&c.to_string())),
        }
    }
    o
}

/// Plain ASCII for PDF bookmarks: Greek letters by name, other symbols dropped.
fn bookmark_text(s: &str) -> String {
    let mut o = String::new();
    for c in s.chars() {
        match c {
            c if c.is_ascii_alphanumeric() || " .,:;()'-/+=".contains(c) => o.push(c),
            c => {
                if let Some(m) = unicode_math(c)
                    && let Some(name) = m.strip_prefix('\\')
                    && name.chars().all(|c| c.is_ascii_alphabetic())
                {
                    o.push_str(name.trim_start_matches("var"));
                }
            }
        }
    }
    o
}

fn latex_heading(cmd: &str, title: &str) -> String {
    let tex = latex_text(title);
    let plain = bookmark_text(title);
    if tex == plain {
        format!("\\{cmd}{{{tex}}}")
    } else {
        format!("\\{cmd}{{\\texorpdfstring{{{tex}}}{{{plain}}}}}")
    }
}

// --------------------------------------------------------------- LaTeX --

const LATEX_PREAMBLE: &str = r"\documentclass[11pt,a4paper]{article}
\usepackage[T1]{fontenc}
\usepackage[utf8]{inputenc}
\usepackage{lmodern}
\usepackage{amsmath}
\usepackage{amssymb}
\usepackage[margin=2.2cm]{geometry}
\usepackage[hidelinks]{hyperref}
\allowdisplaybreaks
\tracinglostchars=2
\setlength{\parindent}{0pt}
\setlength{\parskip}{0.5\baselineskip}
\newcommand{\hdotstep}[1]{\par\medskip\noindent\textbf{#1}\quad}
";

/// The lecture notes as a complete LaTeX document: a section per
/// derivation, in the order given, and the printer-coverage appendix.
pub fn latex_document(ds: &[Derivation]) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "% Generated by `hdot notes` from the derivation files; do not edit.\n\
         % Refresh with: {REFRESH_COMMAND}"
    );
    o.push_str(LATEX_PREAMBLE);
    let _ = writeln!(o, "\\title{{{}}}", latex_text(TITLE));
    let _ = writeln!(o, "\\author{{Generated by \\texttt{{hdot notes}}}}");
    let _ = writeln!(o, "\\date{{}}\n");
    let _ = writeln!(o, "\\begin{{document}}\n\\maketitle\n");
    let _ = writeln!(
        o,
        "{}\n",
        latex_text(
            "Every equation below is derived by hdot's exact engine from H = [I]ω, \
             the frames' angular velocities and the transport theorem, and checked \
             against the textbook form stated in the derivation file. Each section \
             says what is assumed, shows each step as written in the file and its \
             result in textbook form, and says whether the result equals the \
             expected form."
        )
    );
    o.push_str("\\tableofcontents\n");
    for d in ds {
        latex_section(&mut o, d);
    }
    latex_coverage(&mut o);
    o.push_str("\n\\end{document}\n");
    o
}

fn latex_section(o: &mut String, d: &Derivation) {
    let _ = writeln!(o, "\n\\clearpage\n{}", latex_heading("section", &d.title));
    let _ = writeln!(o, "\\label{{sec:{}}}\n", label_key(&d.name));
    let _ = writeln!(o, "\\textbf{{Source:}} {}\\\\", latex_text(&d.source));
    let _ = writeln!(o, "\\textbf{{File:}} \\texttt{{{}}}\n", latex_code(&d.path));
    if !d.summary.trim().is_empty() {
        let _ = writeln!(o, "{}\n", latex_text(d.summary.trim()));
    }
    let _ = writeln!(o, "\\subsection*{{What is assumed}}");
    if !d.assumptions.is_empty() {
        let _ = writeln!(o, "\\begin{{itemize}}");
        for a in &d.assumptions {
            let _ = writeln!(o, "  \\item{{}} {}", latex_text(a));
        }
        let _ = writeln!(o, "\\end{{itemize}}");
    }
    let consts = symbol_list(d, |x| matches!(x, Decl::Constant));
    let time = symbol_list(d, |x| matches!(x, Decl::Time));
    let mut items = Vec::new();
    if !consts.is_empty() {
        items.push(format!("Constants: ${}$.", consts.join(",\\ ")));
    }
    if !time.is_empty() {
        items.push(format!("Functions of time: ${}$.", time.join(",\\ ")));
    }
    for a in &d.abbreviations {
        items.push(format!(
            "Abbreviation: ${} = {}${}",
            print::latex_symbol(&a.name, 0),
            print::latex(&Expr::from_poly(&a.definition)),
            latex_doc_suffix(&a.doc)
        ));
    }
    if d.frames.len() > 1 {
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
        if d.frames.len() > 1 {
            let _ = writeln!(o, "  \\begin{{itemize}}");
            for (k, f) in d.frames.iter().enumerate().skip(1) {
                let parent = match &f.parent {
                    Some((p, _)) => format!(" (turned from ${}$)", print::latex_symbol(p, 0)),
                    None => String::new(),
                };
                let omega = frame_omega(d, k);
                let axes = f
                    .axes
                    .iter()
                    .map(|a| print::latex_symbol(a, 0))
                    .collect::<Vec<_>>()
                    .join(",\\ ");
                let doc = latex_doc_suffix(&f.doc);
                let name = print::latex_symbol(&f.name, 0);
                if math_width(&omega) <= 40.0 {
                    let _ = writeln!(
                        o,
                        "    \\item{{}} ${name}$, axes ${axes}${parent}: \
                         $\\boldsymbol{{\\Omega}} = {omega}${doc}"
                    );
                } else {
                    let lines: Vec<String> = f
                        .axes
                        .iter()
                        .zip(&f.omega.0)
                        .flat_map(|(a, p)| {
                            equation_lines(
                                &latex_label("Omega", a),
                                &print::latex(&Expr::from_poly(p)),
                            )
                        })
                        .collect();
                    let _ = writeln!(
                        o,
                        "    \\item{{}} ${name}$, axes ${axes}${parent}{doc}:\n\
                         \\begin{{align*}}\n{}\n\\end{{align*}}",
                        lines.join(" \\\\\n")
                    );
                }
            }
            let _ = writeln!(o, "  \\end{{itemize}}");
        }
        let _ = writeln!(o, "\\end{{itemize}}");
    }
    let _ = writeln!(o, "\\subsection*{{Steps}}");
    for (n, s) in d.steps.iter().filter(|s| s.show).enumerate() {
        let _ = writeln!(
            o,
            "\\hdotstep{{Step {}: ${}$.}}{}",
            n + 1,
            latex_label(&s.label, ""),
            latex_text(&sentence(&s.doc))
        );
        let frame = vector_frame(s)
            .map(|f| format!(", components in frame ${}$", print::latex_symbol(f, 0)))
            .unwrap_or_default();
        let _ = writeln!(
            o,
            "{{\\raggedright Written in the file as \\texttt{{{}}}{frame}.\\par}}",
            latex_code(&s.formula)
        );
        let _ = writeln!(o, "\\begin{{align*}}\n{}\n\\end{{align*}}", step_lines(s));
        if s.checks.is_empty() {
            let _ = writeln!(o, "\\emph{{No expectation is stated for this step.}}\n");
        } else if s.checks.iter().all(Check::holds) {
            let _ = writeln!(o, "$\\checkmark$ Equals the expected (textbook) form.\n");
        } else {
            let _ = writeln!(
                o,
                "\\textbf{{Does not equal the expected form}} (derived $-$ expected is shown):"
            );
            let _ = writeln!(o, "\\begin{{align*}}");
            let lines: Vec<String> = s
                .checks
                .iter()
                .filter(|c| !c.holds())
                .flat_map(|c| {
                    let (lhs, exp, diff) = failed_check_math(s, c);
                    let mut l = equation_lines(&format!("{lhs}^{{\\text{{expected}}}}"), &exp);
                    l.extend(equation_lines(r"\text{difference}", &diff));
                    l
                })
                .collect();
            let _ = writeln!(o, "{}\n\\end{{align*}}\n", lines.join(" \\\\\n"));
        }
    }
}

fn latex_coverage(o: &mut String) {
    let _ = writeln!(
        o,
        "\n\\clearpage\n\\appendix\n\\section{{Printer coverage}}"
    );
    let _ = writeln!(o, "\\label{{sec:printer-coverage}}\n");
    let _ = writeln!(
        o,
        "{}\n",
        latex_text(
            "These expressions are built in code, not derived: together they use every \
             construct the LaTeX printer can emit, so that compiling these notes proves \
             each of them typesets."
        )
    );
    for c in coverage() {
        let _ = writeln!(
            o,
            "\\hdotstep{{}}{}\n\\begin{{align*}}\n{}\n\\end{{align*}}",
            latex_text(&sentence(&capitalise(c.what))),
            coverage_lines(&c)
        );
    }
}

fn latex_doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!(" --- {}", latex_text(doc))
    }
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

fn capitalise(s: &str) -> String {
    let mut cs = s.chars();
    match cs.next() {
        Some(c) if c.is_ascii_lowercase() => c.to_ascii_uppercase().to_string() + cs.as_str(),
        _ => s.to_owned(),
    }
}

// ------------------------------------------------------------ Markdown --

/// Escapes Markdown prose so that `*`, `_`, `` ` ``, `$`, `[` and `<` show
/// as themselves.
fn md_text(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        if "\\*_`$[]<".contains(c) {
            o.push('\\');
        }
        o.push(c);
    }
    o
}

/// Inline code that may itself contain backticks.
fn md_code(s: &str) -> String {
    if s.contains('`') {
        format!("`` {s} ``")
    } else {
        format!("`{s}`")
    }
}

fn md_anchor(name: &str) -> String {
    label_key(name).to_ascii_lowercase()
}

/// The lecture notes as one Markdown page with `$$` math: the same
/// content as [`latex_document`], in the same order.
pub fn markdown_document(ds: &[Derivation]) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "# {}\n", md_text(TITLE));
    let _ = writeln!(
        o,
        "<!-- Generated by `hdot notes` from the derivation files; do not edit. \
         Refresh with: {REFRESH_COMMAND} -->\n"
    );
    let _ = writeln!(
        o,
        "{}\n",
        md_text(
            "Every equation below is derived by hdot's exact engine from H = [I]ω, \
             the frames' angular velocities and the transport theorem, and checked \
             against the textbook form stated in the derivation file. Each section \
             says what is assumed, shows each step as written in the file and its \
             result in textbook form, and says whether the result equals the \
             expected form."
        )
    );
    let _ = writeln!(o, "## Contents\n");
    for (k, d) in ds.iter().enumerate() {
        let _ = writeln!(
            o,
            "{}. [{}](#{})",
            k + 1,
            md_text(&d.title),
            md_anchor(&d.name)
        );
    }
    let _ = writeln!(
        o,
        "{}. [Appendix: Printer coverage](#printer-coverage)\n",
        ds.len() + 1
    );
    for (k, d) in ds.iter().enumerate() {
        markdown_section(&mut o, k + 1, d);
    }
    markdown_coverage(&mut o);
    o
}

fn md_math_block(o: &mut String, body: &str) {
    let _ = writeln!(o, "$$\n\\begin{{aligned}}\n{body}\n\\end{{aligned}}\n$$\n");
}

fn markdown_section(o: &mut String, n: usize, d: &Derivation) {
    let _ = writeln!(o, "<a id=\"{}\"></a>\n", md_anchor(&d.name));
    let _ = writeln!(o, "## {n}. {}\n", md_text(&d.title));
    let _ = writeln!(o, "**Source:** {}  ", md_text(&d.source));
    let _ = writeln!(o, "**File:** {}\n", md_code(&d.path));
    if !d.summary.trim().is_empty() {
        let _ = writeln!(o, "{}\n", md_text(d.summary.trim()));
    }
    let _ = writeln!(o, "### What is assumed\n");
    for a in &d.assumptions {
        let _ = writeln!(o, "- {}", md_text(a));
    }
    let consts = symbol_list(d, |x| matches!(x, Decl::Constant));
    let time = symbol_list(d, |x| matches!(x, Decl::Time));
    if !consts.is_empty() {
        let _ = writeln!(o, "- Constants: ${}$.", consts.join(",\\ "));
    }
    if !time.is_empty() {
        let _ = writeln!(o, "- Functions of time: ${}$.", time.join(",\\ "));
    }
    for a in &d.abbreviations {
        let _ = writeln!(
            o,
            "- Abbreviation: ${} = {}${}",
            print::latex_symbol(&a.name, 0),
            print::latex(&Expr::from_poly(&a.definition)),
            md_doc_suffix(&a.doc)
        );
    }
    if d.frames.len() > 1 {
        let _ = writeln!(
            o,
            "- Frames, each with its angular velocity $\\boldsymbol{{\\Omega}}$ relative to \
             the inertial frame $N$, in the frame's own axes:"
        );
        for (k, f) in d.frames.iter().enumerate().skip(1) {
            let parent = match &f.parent {
                Some((p, _)) => format!(" (turned from ${}$)", print::latex_symbol(p, 0)),
                None => String::new(),
            };
            let _ = writeln!(
                o,
                "  - ${}$, axes ${}${parent}: $\\boldsymbol{{\\Omega}} = {}${}",
                print::latex_symbol(&f.name, 0),
                f.axes
                    .iter()
                    .map(|a| print::latex_symbol(a, 0))
                    .collect::<Vec<_>>()
                    .join(",\\ "),
                frame_omega(d, k),
                md_doc_suffix(&f.doc)
            );
        }
    }
    let _ = writeln!(o, "\n### Steps\n");
    for (k, s) in d.steps.iter().filter(|s| s.show).enumerate() {
        let _ = writeln!(
            o,
            "**Step {}: ${}$.** {}\n",
            k + 1,
            latex_label(&s.label, ""),
            md_text(&sentence(&s.doc))
        );
        let frame = vector_frame(s)
            .map(|f| format!(", components in frame ${}$", print::latex_symbol(f, 0)))
            .unwrap_or_default();
        let _ = writeln!(
            o,
            "Written in the file as {}{frame}.\n",
            md_code(&s.formula)
        );
        md_math_block(o, &step_lines(s));
        if s.checks.is_empty() {
            let _ = writeln!(o, "*No expectation is stated for this step.*\n");
        } else if s.checks.iter().all(Check::holds) {
            let _ = writeln!(o, "✓ Equals the expected (textbook) form.\n");
        } else {
            let _ = writeln!(
                o,
                "✗ **Does not equal the expected form** (derived − expected is shown):\n"
            );
            let lines: Vec<String> = s
                .checks
                .iter()
                .filter(|c| !c.holds())
                .flat_map(|c| {
                    let (lhs, exp, diff) = failed_check_math(s, c);
                    let mut l = equation_lines(&format!("{lhs}^{{\\text{{expected}}}}"), &exp);
                    l.extend(equation_lines(r"\text{difference}", &diff));
                    l
                })
                .collect();
            md_math_block(o, &lines.join(" \\\\\n"));
        }
    }
}

fn markdown_coverage(o: &mut String) {
    let _ = writeln!(o, "<a id=\"printer-coverage\"></a>\n");
    let _ = writeln!(o, "## Appendix: Printer coverage\n");
    let _ = writeln!(
        o,
        "These expressions are built in code, not derived: together they use every \
         construct the LaTeX printer can emit, so that compiling these notes proves \
         each of them typesets.\n"
    );
    for c in coverage() {
        let _ = writeln!(o, "{}\n", md_text(&sentence(&capitalise(c.what))));
        md_math_block(o, &coverage_lines(&c));
    }
}

fn md_doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!(" — {}", md_text(doc))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_sums_break_before_top_level_signs() {
        let parts = split_terms(r"a + \left(b - c\right) d - \frac{1}{2} e^{x - y}");
        assert_eq!(
            parts,
            vec!["a", r"+ \left(b - c\right) d", r"- \frac{1}{2} e^{x - y}"]
        );
        let lines = equation_lines("H_x", &vec!["I_x \\omega_x"; 20].join(" + "));
        assert!(lines.len() > 1);
        assert!(lines[0].starts_with("H_x &= "));
        assert!(lines[1].starts_with(r"&\quad {} + "));
        let long = format!(
            r"\frac{{1}}{{2}} \left({}\right)",
            vec!["m v_x^{2}"; 30].join(" + ")
        );
        let lines = equation_lines("T", &long);
        assert!(lines.len() > 1);
        assert!(lines[0].starts_with(r"T &= \frac{1}{2} \left(m v_x^{2} + "));
        assert!(lines[0].ends_with(r"\right."));
        assert!(lines[1].starts_with(r"&\quad \left. {} + m v_x^{2}"));
        assert!(lines.last().unwrap().ends_with(r"m v_x^{2}\right)"));
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
