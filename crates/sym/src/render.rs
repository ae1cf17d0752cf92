//! Renders an evaluated [`Derivation`] as Unicode text, LaTeX, Markdown,
//! SymPy source or JSON.
//!
//! Each format shows the same things: the title and source, what is
//! assumed, the symbols and frames, then every shown step with its
//! components in textbook form and whether its expectation holds.

use std::fmt::Write;

use serde_json::json;

use crate::derivation::{Derivation, Step, Value};
use crate::expr::Expr;
use crate::print::{self, Latex, Sympy, Unicode, latex_symbol, unicode_symbol};
use crate::symbols::Decl;

/// The output formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Unicode text for a terminal.
    Unicode,
    /// LaTeX `align*` blocks for lecture notes.
    Latex,
    /// Markdown with `$$` math.
    Markdown,
    /// Python source that rebuilds every equation with sympy.
    Sympy,
    /// Machine-readable JSON.
    Json,
}

/// Renders `d` in `format`.
pub fn render(d: &Derivation, format: Format) -> String {
    match format {
        Format::Unicode => unicode(d),
        Format::Latex => latex(d),
        Format::Markdown => markdown(d),
        Format::Sympy => sympy(d),
        Format::Json => serde_json::to_string_pretty(&json(d)).expect("JSON of plain data") + "\n",
    }
}

/// A label word with trailing primes: `epsilon_2''` → (`epsilon_2`, 2).
fn label_word(w: &str) -> (&str, u32) {
    let base = w.trim_end_matches('\'');
    (base, (w.len() - base.len()) as u32)
}

/// A label such as `Sigma M` with component `x`, in LaTeX: `\Sigma M_{x}`.
pub fn latex_label(label: &str, component: &str) -> String {
    let words: Vec<String> = label
        .split_whitespace()
        .map(|w| {
            let (b, k) = label_word(w);
            latex_symbol(b, k)
        })
        .collect();
    let body = words.join(" ");
    match (
        component.is_empty(),
        label
            .split_whitespace()
            .last()
            .is_some_and(|w| w.contains('_')),
    ) {
        (true, _) => body,
        (false, false) => format!("{body}_{{{component}}}"),
        (false, true) => format!(r"\left({body}\right)_{{{component}}}"),
    }
}

/// A label with component in Unicode: `ΣM_x`.
pub fn unicode_label(label: &str, component: &str) -> String {
        let body: String = label
        .split_whitespace()
        .map(|w| {
            let (b, k) = label_word(w);
            unicode_symbol(b, k)
        })
        .collect();
    match (
        component.is_empty(),
        label
            .split_whitespace()
            .last()
            .is_some_and(|w| w.contains('_')),
    ) {
        (true, _) => body,
        (false, false) => format!("{body}_{component}"),
        (false, true) => format!("({body})_{component}"),
    }
}

fn unicode_names(d: &Derivation, want: fn(&Decl) -> bool) -> String {
    let names: Vec<String> = d
        .symbols
        .names()
        .iter()
        .filter(|n| d.symbols.get(n).is_some_and(want))
        .map(|n| unicode_symbol(n, 0))
        .collect();
    names.join(", ")
}

fn frame_omega_unicode(d: &Derivation, k: usize) -> String {
    let f = &d.frames[k];
    let c: Vec<String> = f
        .omega
        .0
        .iter()
        .map(|p| print::unicode(&Expr::from_poly(p)))
        .collect();
    format!("({})", c.join(", "))
}

fn unicode(d: &Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "{}", d.title);
    let _ = writeln!(o, "{}", "=".repeat(d.title.chars().count()));
    let _ = writeln!(o, "Source: {}", d.source);
    if !d.summary.is_empty() {
        let _ = writeln!(o, "\n{}", d.summary.trim());
    }
    if !d.assumptions.is_empty() {
        let _ = writeln!(o, "\nAssumptions:");
        for a in &d.assumptions {
            let _ = writeln!(o, "  • {a}");
        }
    }
    let consts = unicode_names(d, |x| matches!(x, Decl::Constant));
    let time = unicode_names(d, |x| matches!(x, Decl::Time));
    let _ = writeln!(o, "\nSymbols:");
    if !consts.is_empty() {
        let _ = writeln!(o, "  constants: {consts}");
    }
    if !time.is_empty() {
        let _ = writeln!(o, "  functions of time: {time}");
    }
    for a in &d.abbreviations {
        let e = print::unicode(&Expr::from_poly(&a.definition));
        let _ = writeln!(
            o,
            "  abbreviation: {} = {e}{}",
            unicode_symbol(&a.name, 0),
            doc_suffix(&a.doc)
        );
    }
    if d.frames.len() > 1 {
        let _ = writeln!(o, "\nFrames (Ω relative to N, in the frame's own axes):");
        for (k, f) in d.frames.iter().enumerate().skip(1) {
            let _ = writeln!(
                o,
                "  {}: Ω = {}{}",
                f.name,
                frame_omega_unicode(d, k),
                doc_suffix(&f.doc)
            );
        }
    }
    let mut n = 0;
    for s in d.steps.iter().filter(|s| s.show) {
        n += 1;
        let _ = writeln!(
            o,
            "\n{n}. {} = {}{}",
            unicode_label(&s.label, ""),
            s.formula,
            doc_suffix(&s.doc)
        );
        if let Value::Vector(_, f) = &s.value {
            let _ = writeln!(o, "   (components in frame {f})");
        }
        for (c, e) in &s.components {
            let _ = writeln!(
                o,
                "   {} = {}",
                unicode_label(&s.label, c),
                print::unicode(e)
            );
        }
        write_checks_unicode(&mut o, s);
    }
    o
}

fn doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!("  — {doc}")
    }
}

fn write_checks_unicode(o: &mut String, s: &Step) {
    if s.checks.is_empty() {
        return;
    }
    if s.checks.iter().all(|c| c.holds()) {
        let _ = writeln!(o, "   ✓ equals the expected (textbook) form");
        return;
    }
    for c in s.checks.iter().filter(|c| !c.holds()) {
        let _ = writeln!(
            o,
            "   ✗ {}: expected {}; derived − expected = {}",
            unicode_label(&s.label, &c.component),
            print::unicode(&c.expected),
            print::unicode(&Expr::from_poly(&c.difference))
        );
    }
}

/// LaTeX-escapes plain text (for titles and prose).
pub fn latex_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '\\' => out.push_str(r"\textbackslash{}"),
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(ch);
            }
            '~' => out.push_str(r"\textasciitilde{}"),
            '^' => out.push_str(r"\textasciicircum{}"),
            '§' => out.push_str(r"\S{}"),
            '—' => out.push_str("---"),
            '–' => out.push_str("--"),
            '−' => out.push('-'),
            '×' => out.push_str(r"$\times$"),
            '·' => out.push_str(r"$\cdot$"),
            '′' => out.push('\''),
            c if c.is_ascii() => out.push(c),
            c => match greek_latex(c) {
                Some(g) => {
                    let _ = write!(out, "${g}$");
                }
                None => out.push(c),
            },
        }
    }
    out
}

fn greek_latex(c: char) -> Option<&'static str> {
    const T: &[(char, &str)] = &[
        ('α', r"\alpha"),
        ('β', r"\beta"),
        ('γ', r"\gamma"),
        ('δ', r"\delta"),
        ('ε', r"\varepsilon"),
        ('θ', r"\theta"),
        ('λ', r"\lambda"),
        ('φ', r"\phi"),
        ('ψ', r"\psi"),
        ('ω', r"\omega"),
        ('Ω', r"\Omega"),
        ('Σ', r"\Sigma"),
        ('π', r"\pi"),
    ];
    T.iter().find(|t| t.0 == c).map(|t| t.1)
}

/// The `align*` block of one step.
pub fn latex_step(s: &Step) -> String {
    let mut o = String::from("\\begin{align*}\n");
    let lines: Vec<String> = s
        .components
        .iter()
        .map(|(c, e)| format!("  {} &= {}", latex_label(&s.label, c), print::latex(e)))
        .collect();
    o.push_str(&lines.join(" \\\\\n"));
    o.push_str("\n\\end{align*}\n");
    o
}

fn latex(d: &Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "% {} — generated by hdot from {}", d.title, d.path);
    for s in d.steps.iter().filter(|s| s.show) {
        if !s.doc.is_empty() {
            let _ = writeln!(o, "% {}", s.doc);
        }
        o.push_str(&latex_step(s));
    }
    o
}

fn markdown(d: &Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "## {}\n", d.title);
    let _ = writeln!(o, "*Source:* {}  ", d.source);
    let _ = writeln!(o, "*File:* `{}`\n", d.path);
    if !d.summary.is_empty() {
        let _ = writeln!(o, "{}\n", d.summary.trim());
    }
    if !d.assumptions.is_empty() {
        let _ = writeln!(o, "**Assumptions.**\n");
        for a in &d.assumptions {
            let _ = writeln!(o, "- {a}");
        }
        o.push('\n');
    }
    for s in d.steps.iter().filter(|s| s.show) {
        let _ = writeln!(
            o,
            "**{}** = `{}`{}\n",
            s.name,
            s.formula,
            if s.doc.is_empty() {
                String::new()
            } else {
                format!(" — {}", s.doc)
            }
        );
        let lines: Vec<String> = s
            .components
            .iter()
            .map(|(c, e)| format!("{} &= {}", latex_label(&s.label, c), print::latex(e)))
            .collect();
        let _ = writeln!(
            o,
            "$$\n\\begin{{aligned}}\n{}\n\\end{{aligned}}\n$$\n",
            lines.join(" \\\\\n")
        );
        if !s.checks.is_empty() {
            if s.checks.iter().all(|c| c.holds()) {
                let _ = writeln!(o, "✓ equals the expected (textbook) form.\n");
            } else {
                let _ = writeln!(o, "✗ does **not** equal the expected form.\n");
            }
        }
    }
    o
}

/// A Python identifier for a symbol name that cannot clash with the
/// names the export itself uses.
fn py_var(name: &str) -> String {
    const RESERVED: &[&str] = &[
        "t",
        "sin",
        "cos",
        "Eq",
        "Symbol",
        "Function",
        "Rational",
        "Integer",
        "equations",
        "expected",
        "abbreviations",
        "False",
        "None",
        "True",
        "and",
        "as",
        "assert",
        "async",
        "await",
        "break",
        "class",
        "continue",
        "def",
        "del",
        "elif",
        "else",
        "except",
        "finally",
        "for",
        "from",
        "global",
        "if",
        "import",
        "in",
        "is",
        "lambda",
        "nonlocal",
        "not",
        "or",
        "pass",
        "raise",
        "return",
        "try",
        "while",
        "with",
        "yield",
        "sympy",
        "labels",
    ];
    if RESERVED.contains(&name) {
        format!("{name}_")
    } else {
        name.to_owned()
    }
}

fn sympy(d: &Derivation) -> String {
    let var = |n: &str| py_var(n);
    let style = Sympy { var: &var };
    let mut o = String::new();
    let _ = writeln!(o, "# {} — generated by hdot from {}", d.title, d.path);
    let _ = writeln!(o, "# Source: {}", d.source);
    let _ = writeln!(
        o,
        "# Symbols are built by name with Symbol(...); functions of time are Function(...)(t)."
    );
    let _ = writeln!(
        o,
        "from sympy import Eq, Function, Integer, Rational, Symbol, cos, sin\n"
    );
    let _ = writeln!(o, "t = Symbol('t')");
    for n in d.symbols.names() {
        match d.symbols.get(n) {
            Some(Decl::Constant) => {
                let _ = writeln!(o, "{} = Symbol('{n}')", var(n));
            }
            Some(Decl::Time | Decl::Abbrev(_)) => {
                let _ = writeln!(o, "{} = Function('{n}')(t)", var(n));
            }
            None => {}
        }
    }
    let _ = writeln!(o, "\n# Abbreviations: name -> what it stands for.");
    let _ = writeln!(o, "abbreviations = {{");
    for a in &d.abbreviations {
        let _ = writeln!(
            o,
            "    {}: {},",
            var(&a.name),
            print::print(&Expr::from_poly(&a.definition), &style)
        );
    }
    let _ = writeln!(o, "}}\n");
    let mut eqs = Vec::new();
    let mut exps = Vec::new();
    let mut labels = Vec::new();
    for s in d.steps.iter().filter(|s| s.show) {
        let base: String = s.label.split_whitespace().collect();
        for (k, (c, e)) in s.components.iter().enumerate() {
            let lhs = if c.is_empty() {
                base.clone()
            } else {
                format!("{base}_{c}")
            };
            labels.push(format!("'{}.{}'", s.name, c));
            eqs.push(format!(
                "    Eq(Symbol('{lhs}'), {}),",
                print::print(e, &style)
            ));
            match s.checks.get(k) {
                Some(ch) => exps.push(format!(
                    "    Eq(Symbol('{lhs}'), {}),",
                    print::print(&ch.expected, &style)
                )),
                None => exps.push("    None,".into()),
            }
        }
    }
    let _ = writeln!(
        o,
        "# One equation per component of every shown step, in textbook form."
    );
    let _ = writeln!(o, "equations = [\n{}\n]\n", eqs.join("\n"));
    let _ = writeln!(
        o,
        "# The expected (textbook) form of each equation, or None."
    );
    let _ = writeln!(o, "expected = [\n{}\n]\n", exps.join("\n"));
    let _ = writeln!(o, "# step.component of each equation.");
    let _ = writeln!(o, "labels = [{}]", labels.join(", "));
    o
}

fn json(d: &Derivation) -> serde_json::Value {
    let steps: Vec<serde_json::Value> = d
        .steps
        .iter()
        .map(|s| {
            let kind = match &s.value {
                Value::Scalar(_) => json!({"kind": "scalar"}),
                Value::Vector(_, f) => json!({"kind": "vector", "frame": f}),
                Value::Matrix(_) => json!({"kind": "matrix"}),
            };
            let comps: Vec<serde_json::Value> = s
                .components
                .iter()
                .enumerate()
                .map(|(k, (c, e))| {
                    let check = s.checks.get(k).map(|ch| {
                        json!({
                            "expected": ch.expected_text,
                            "holds": ch.holds(),
                            "difference": ch.difference.to_source(),
                        })
                    });
                    json!({
                        "component": c,
                        "text": print::print(e, &Unicode),
                        "latex": print::print(e, &Latex),
                        "source": e.to_string(),
                        "canonical": e.to_poly().to_source(),
                        "terms": e.to_poly().len(),
                        "check": check,
                    })
                })
                .collect();
            json!({
                "name": s.name,
                "label": s.label,
                "doc": s.doc,
                "formula": s.formula,
                "show": s.show,
                "value": kind,
                "components": comps,
            })
        })
        .collect();
    json!({
        "name": d.name,
        "path": d.path,
        "title": d.title,
        "source": d.source,
        "summary": d.summary,
        "assumptions": d.assumptions,
        "all_hold": d.all_hold(),
        "checks": d.check_count(),
        "steps": steps,
    })
}
