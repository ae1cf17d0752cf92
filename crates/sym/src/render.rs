//! Renders an evaluated [`Derivation`] as Unicode text, LaTeX, Markdown,
//! SymPy source or JSON.
//!
//! Each format shows the same things: the title and source, what is
//! assumed, the symbols and frames, then every shown step with its
//! components in textbook form and whether its expectation holds. The
//! Unicode, LaTeX and Markdown formats are backends over the derivation's
//! [`Section`] of the document model ([`crate::document`]), one file each
//! in [`crate::notes`] (the same section the lecture notes print). SymPy
//! and JSON export the steps.

use std::fmt::Write;

use crate::derivation::{Derivation, Value};
use crate::document::Section;
use crate::escape;
use crate::expr::Expr;
use crate::poly::Poly;
use crate::print::{self, Latex, Sympy, Unicode};
use crate::symbols::Decl;

/// The output formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Unicode text for a terminal.
    Unicode,
    /// The derivation's section of the lecture notes, as a LaTeX fragment
    /// to `\input` (needs amsmath and amssymb).
    Latex,
    /// The derivation's section of the notes in Markdown with `$$` math.
    Markdown,
    /// Python source that rebuilds every equation with sympy.
    Sympy,
    /// Machine-readable JSON.
    Json,
}

/// Renders `d` in `format`: the derivation's [`Section`] by the backend
/// of that name ([`crate::notes::BACKENDS`]), or an export of the steps.
pub fn render(d: &Derivation, format: Format) -> String {
    let section = |name: &str| {
        crate::notes::backend(name)
            .expect("every section format has a backend")
            .section(&Section::of(d, None))
    };
    match format {
        Format::Unicode => section("unicode"),
        Format::Latex => section("latex"),
        Format::Markdown => section("markdown"),
        Format::Sympy => sympy(d),
        Format::Json => serde_json::to_string_pretty(&json(d)).expect("JSON of plain data") + "\n",
    }
}

/// Step labels are part of the document model ([`crate::label`]).
pub use crate::document::{latex_label, unicode_label};

pub use crate::document::VANISHES;
pub use crate::notes::unicode_section;

/// Prose (titles, summaries, docs) as LaTeX text with its notation set
/// as math; see [`crate::prose`].
///
/// # Example
/// ```
/// use hdot_sym::render::latex_text;
/// assert_eq!(latex_text("ΣM = Ḣ, 50% & ω̇_x"), r"$\Sigma M = \dot{H}$, 50\% \& $\dot{\omega}_{x}$");
/// ```
pub fn latex_text(s: &str) -> String {
    crate::prose::latex(s)
}

pub use crate::prose::unicode_math;

/// Names the SymPy export itself uses, and Python's keywords: no
/// variable of a file is given one of them.
const PY_RESERVED: &[&str] = &[
    "t",
    "sin",
    "cos",
    "Eq",
    "Symbol",
    "Function",
    "Matrix",
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

/// The Python variables of a SymPy export: one distinct identifier per
/// name (symbols first, then the steps kept as values), spelled by
/// [`escape::python_name`], never a reserved name, never one given out
/// before (a `_` is appended until it is new).
#[derive(Default)]
struct PyNames {
    given: std::collections::HashMap<String, String>,
    used: std::collections::HashSet<String>,
}

impl PyNames {
    /// The variable of symbol `name`, given out once.
    fn add(&mut self, name: &str) -> String {
        if let Some(v) = self.given.get(name) {
            return v.clone();
        }
        let v = self.fresh(name);
        self.given.insert(name.to_owned(), v.clone());
        v
    }

    /// A new variable spelling `name`, distinct from every one before.
    fn fresh(&mut self, name: &str) -> String {
        let mut v = escape::python_name(name);
        while PY_RESERVED.contains(&v.as_str()) || self.used.contains(&v) {
            v.push('_');
        }
        self.used.insert(v.clone());
        v
    }

    fn get(&self, name: &str) -> String {
        self.given
            .get(name)
            .cloned()
            .unwrap_or_else(|| escape::python_name(name))
    }
}

fn sympy(d: &Derivation) -> String {
    let mut names = PyNames::default();
    for n in d.symbols.names() {
        names.add(n);
    }
    // Steps kept as values (solved unknowns, arrays, lists) are variables
    // too, named after the step.
    let steps: std::collections::HashMap<&str, String> = d
        .steps
        .iter()
        .filter(|s| s.show && matches!(s.value, Value::List { .. } | Value::Array(_)))
        .map(|s| (s.name.as_str(), names.fresh(&s.name)))
        .collect();
    let var = |n: &str| names.get(n);
    let style = Sympy { var: &var };
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# {} — generated by hdot from {}",
        escape::python_comment(&d.title),
        escape::python_comment(&d.path)
    );
    let _ = writeln!(o, "# Source: {}", escape::python_comment(&d.source));
    let _ = writeln!(
        o,
        "# Symbols are built by name with Symbol(...); functions of time are Function(...)(t)."
    );
    let _ = writeln!(
        o,
        "from sympy import Eq, Function, Integer, Matrix, Rational, Symbol, cos, sin\n"
    );
    let _ = writeln!(o, "t = Symbol('t')");
    for n in d.symbols.names() {
        match d.symbols.get(n) {
            Some(Decl::Constant) => {
                let _ = writeln!(o, "{} = Symbol({})", var(n), escape::python_str(n));
            }
            Some(Decl::Time | Decl::Abbrev(_)) => {
                let _ = writeln!(o, "{} = Function({})(t)", var(n), escape::python_str(n));
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
    let mut motion = Vec::new();
    for s in d.steps.iter().filter(|s| s.show) {
        // Values to continue with in SymPy: solved unknowns as a dict
        // {q'': …}, arrays (a mass matrix) and unlabelled lists (a forcing,
        // Lagrange's equations) as Matrix objects.
        let printed: Vec<String> = s
            .components()
            .iter()
            .map(|(_, e)| print::print(e, &style))
            .collect();
        match &s.value {
            Value::List { labels, .. } if labels.len() == printed.len() && !labels.is_empty() => {
                let items: Vec<String> = labels
                    .iter()
                    .zip(&printed)
                    .map(|(&a, p)| {
                        let mut x = Expr::new();
                        x.push(crate::expr::Node::Atom(a));
                        format!("    {}: {p},", print::print(&x, &style))
                    })
                    .collect();
                motion.push(format!(
                    "{} = {{\n{}\n}}",
                    steps[s.name.as_str()],
                    items.join("\n")
                ));
            }
            Value::Array(rows) => {
                let mut k = 0;
                let rows: Vec<String> = rows
                    .iter()
                    .map(|r| {
                        let row = printed[k..k + r.len()].join(", ");
                        k += r.len();
                        format!("    [{row}],")
                    })
                    .collect();
                motion.push(format!(
                    "{} = Matrix([\n{}\n])",
                    steps[s.name.as_str()],
                    rows.join("\n")
                ));
            }
            Value::List { .. } => {
                motion.push(format!(
                    "{} = Matrix([{}])",
                    steps[s.name.as_str()],
                    printed.join(", ")
                ));
            }
            _ => {}
        }
        // A Python string: primes (time derivatives) become `dot`.
        let base: String = s
            .label
            .split_whitespace()
            .collect::<String>()
            .replace('\'', "dot");
        // Solved values are equations for their unknowns: θ̈ = … has the
        // left side theta.diff(t, 2).
        let unknowns = match &s.value {
            Value::List { labels, .. } if !labels.is_empty() => labels.clone(),
            _ => Vec::new(),
        };
        for (k, (c, e)) in s.components().iter().enumerate() {
            let lhs = match unknowns.get(k) {
                Some(&a) => {
                    let mut x = Expr::new();
                    x.push(crate::expr::Node::Atom(a));
                    print::print(&x, &style)
                }
                // An equation "= 0": the number 0, not a symbol named 0.
                None if s.label.trim() == "0" => "Integer(0)".to_owned(),
                None if c.is_empty() => format!("Symbol({})", escape::python_str(&base)),
                None => format!(
                    "Symbol({})",
                    escape::python_str(&format!("{base}_{}", c.replace('\'', "dot")))
                ),
            };
            labels.push(escape::python_str(&format!("{}.{c}", s.name)));
            // Eq(0, 0) would evaluate to True and lose its sides.
            let keep = if lhs == "Integer(0)" {
                ", evaluate=False"
            } else {
                ""
            };
            eqs.push(format!("    Eq({lhs}, {}{keep}),", print::print(e, &style)));
            match s.checks.get(k) {
                Some(ch) => exps.push(format!(
                    "    Eq({lhs}, {}{keep}),",
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
    if !motion.is_empty() {
        let _ = writeln!(
            o,
            "\n# Solved values as {{unknown: value}}; arrays and lists as Matrix objects (for equations\n\
             # of motion in the form M q'' = f, M.LUsolve(f) gives q'' where M can be inverted)."
        );
        for m in &motion {
            let _ = writeln!(o, "{m}");
        }
    }
    o
}

/// The JSON document of a derivation, serialised straight from borrowed
/// data (a chain-6 document is 5 MB: building a `serde_json::Value` first
/// would copy all of it). Fields are declared in alphabetical order, the
/// order the documented output has always had.
#[derive(serde::Serialize)]
struct JsonDerivation<'a> {
    all_hold: bool,
    assumptions: &'a [String],
    checks: usize,
    name: &'a str,
    path: &'a str,
    source: &'a str,
    steps: Vec<JsonStep<'a>>,
    summary: &'a str,
    title: &'a str,
}

#[derive(serde::Serialize)]
struct JsonStep<'a> {
    components: Vec<JsonComponent<'a>>,
    doc: &'a str,
    formula: &'a str,
    label: &'a str,
    name: &'a str,
    show: bool,
    value: JsonKind<'a>,
}

#[derive(serde::Serialize)]
struct JsonKind<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    frame: Option<&'a str>,
    kind: &'static str,
    /// A matrix, array or list as an array of rows (a list is a column:
    /// rows of one), each entry the value in source syntax (abbreviations
    /// expanded).
    #[serde(skip_serializing_if = "Option::is_none")]
    rows: Option<Vec<Vec<String>>>,
}

#[derive(serde::Serialize)]
struct JsonComponent<'a> {
    canonical: String,
    check: Option<JsonCheck<'a>>,
    component: String,
    latex: String,
    source: String,
    terms: usize,
    text: String,
}

#[derive(serde::Serialize)]
struct JsonCheck<'a> {
    difference: String,
    expected: &'a str,
    holds: bool,
}

fn json(d: &Derivation) -> JsonDerivation<'_> {
    let steps = d
        .steps
        .iter()
        .map(|s| {
            let rows = |rows: Vec<Vec<&Poly>>| {
                Some(
                    rows.into_iter()
                        .map(|r| r.into_iter().map(Poly::to_source).collect())
                        .collect(),
                )
            };
            let (frame, kind, rows) = match &s.value {
                Value::Scalar(_) => (None, "scalar", None),
                Value::Vector(_, f) => (Some(f.as_str()), "vector", None),
                Value::Matrix(m) => (
                    None,
                    "matrix",
                    rows(m.0.iter().map(|r| r.iter().collect()).collect()),
                ),
                Value::List { items, .. } => {
                    (None, "list", rows(items.iter().map(|p| vec![p]).collect()))
                }
                Value::Array(a) => (
                    None,
                    "array",
                    rows(a.iter().map(|r| r.iter().collect()).collect()),
                ),
            };
            let value = JsonKind { frame, kind, rows };
            let values = s.values();
            let components = s
                .presented()
                .into_iter()
                .enumerate()
                .map(|(k, (component, e))| {
                    let check = s.checks.get(k).map(|ch| JsonCheck {
                        difference: ch.difference.to_source(),
                        expected: &ch.expected_text,
                        holds: ch.holds(),
                    });
                    // The presented form expanded. Presentation is exact, so
                    // without folded abbreviations that is the value itself
                    // (tests/sym/presentation.rs checks it for every file).
                    let (canonical, terms) = if s.presentation.fold.is_empty() {
                        (values[k].to_source(), values[k].len())
                    } else {
                        let p = e.to_poly();
                        (p.to_source(), p.len())
                    };
                    JsonComponent {
                        canonical,
                        check,
                        component,
                        latex: print::print(&e, &Latex),
                        source: e.to_string(),
                        terms,
                        text: print::print(&e, &Unicode),
                    }
                })
                .collect();
            JsonStep {
                components,
                doc: &s.doc,
                formula: &s.formula,
                label: &s.label,
                name: &s.name,
                show: s.show,
                value,
            }
        })
        .collect();
    JsonDerivation {
        all_hold: d.all_hold(),
        assumptions: &d.assumptions,
        checks: d.check_count(),
        name: &d.name,
        path: &d.path,
        source: &d.source,
        steps,
        summary: &d.summary,
        title: &d.title,
    }
}
