//! Renders an evaluated [`Derivation`] as Unicode text, LaTeX, Markdown,
//! SymPy source or JSON.
//!
//! Each format shows the same things: the title and source, what is
//! assumed, the symbols and frames, then every shown step with its
//! components in textbook form and whether its expectation holds. The
//! Unicode, LaTeX and Markdown formats are backends over the derivation's
//! [`Section`] of the document model ([`crate::document`]): Unicode here
//! ([`unicode_section`]), LaTeX and Markdown in [`crate::notes`] (the same
//! section the lecture notes print). SymPy and JSON export the steps.

use std::fmt::Write;

use crate::derivation::{Derivation, Value};
use crate::document::{Equation, Section, Verdict};
use crate::expr::Expr;
use crate::print::{self, Latex, Sympy, Unicode, unicode_symbol};
use crate::prose;
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

/// Renders `d` in `format`.
pub fn render(d: &Derivation, format: Format) -> String {
    match format {
        Format::Unicode => unicode_section(&Section::of(d, None)),
        Format::Latex => crate::notes::latex_fragment(d),
        Format::Markdown => crate::notes::markdown_fragment(d),
        Format::Sympy => sympy(d),
        Format::Json => serde_json::to_string_pretty(&json(d)).expect("JSON of plain data") + "\n",
    }
}

/// Step labels are part of the document model ([`crate::document`]).
pub use crate::document::{latex_label, unicode_label};

/// One derivation's section as Unicode text for a terminal (`hdot
/// derive`): the backend of [`Section`] that [`crate::notes`] renders as
/// LaTeX and Markdown, showing the same things in the same order.
pub fn unicode_section(s: &Section) -> String {
    let mut o = String::new();
    let title = prose::unicode(&s.title);
    let _ = writeln!(o, "{title}");
    let _ = writeln!(o, "{}", "=".repeat(title.chars().count()));
    let _ = writeln!(o, "Source: {}", prose::unicode(&s.source));
    if !s.summary.is_empty() {
        let _ = writeln!(o, "\n{}", prose::unicode(&s.summary));
    }
    if !s.assumptions.is_empty() {
        let _ = writeln!(o, "\nAssumptions:");
        for a in &s.assumptions {
            let _ = writeln!(o, "  • {}", prose::unicode(a));
        }
    }
    let names = |ns: &[String]| {
        ns.iter()
            .map(|n| unicode_symbol(n, 0))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let _ = writeln!(o, "\nSymbols:");
    if !s.constants.is_empty() {
        let _ = writeln!(o, "  constants: {}", names(&s.constants));
    }
    if !s.time.is_empty() {
        let _ = writeln!(o, "  functions of time: {}", names(&s.time));
    }
    for (name, def, doc) in &s.abbreviations {
        let _ = writeln!(
            o,
            "  abbreviation: {} = {}{}",
            unicode_symbol(name, 0),
            print::unicode(def),
            doc_suffix(doc)
        );
    }
    if !s.frames.is_empty() {
        let _ = writeln!(o, "\nFrames (Ω relative to N, in the frame's own axes):");
        for f in &s.frames {
            let c: Vec<String> = f.omega.iter().map(|e| print::unicode(&e.rhs)).collect();
            let _ = writeln!(
                o,
                "  {}: Ω = ({}){}",
                f.name,
                c.join(", "),
                doc_suffix(&f.doc)
            );
        }
    }
    for (n, st) in s.steps.iter().enumerate() {
        // The heading: what the step defines, = the formula as written; a
        // step labelled 0 states that its formula is zero.
        let heading = if st.heading.is_zero() {
            format!("{} = 0", st.formula)
        } else {
            format!("{} = {}", st.heading.unicode(), st.formula)
        };
        let _ = writeln!(o, "\n{}. {heading}{}", n + 1, doc_suffix(&st.doc));
        if let Some(f) = &st.frame {
            let _ = writeln!(o, "   (components in frame {f})");
        }
        if st.vanishes() {
            let _ = writeln!(o, "   {VANISHES}");
        } else {
            for e in &st.equations {
                let _ = writeln!(o, "   {}", equation_unicode(e));
            }
        }
        match &st.verdict {
            Verdict::NoExpectation => {}
            Verdict::Holds => {
                let _ = writeln!(o, "   ✓ equals the expected (textbook) form");
            }
            Verdict::Fails(f) => {
                for (expected, difference) in f {
                    let _ = writeln!(
                        o,
                        "   ✗ {}: expected {}; derived − expected = {}",
                        expected.lhs.unicode(),
                        print::unicode(&expected.rhs),
                        print::unicode(&difference.rhs)
                    );
                }
            }
        }
    }
    o
}

/// What a step labelled `0` whose result is identically zero shows
/// instead of `0 = 0` (see [`crate::document::StepBlock::vanishes`]).
pub const VANISHES: &str = "the formula reduces to 0: the relation holds identically";

/// `lhs = rhs` in Unicode; `rhs = 0` for a left side `0`.
fn equation_unicode(e: &Equation) -> String {
    if e.lhs.is_zero() {
        format!("{} = 0", print::unicode(&e.rhs))
    } else {
        format!("{} = {}", e.lhs.unicode(), print::unicode(&e.rhs))
    }
}

fn doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!("  — {}", prose::unicode(doc))
    }
}

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
        "from sympy import Eq, Function, Integer, Matrix, Rational, Symbol, cos, sin\n"
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
                motion.push(format!("{} = {{\n{}\n}}", var(&s.name), items.join("\n")));
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
                    var(&s.name),
                    rows.join("\n")
                ));
            }
            Value::List { .. } => {
                motion.push(format!(
                    "{} = Matrix([{}])",
                    var(&s.name),
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
                None if c.is_empty() => format!("Symbol('{base}')"),
                None => format!("Symbol('{base}_{}')", c.replace('\'', "dot")),
            };
            labels.push(format!("'{}.{}'", s.name, c.replace('\'', "\\'")));
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
            let value = match &s.value {
                Value::Scalar(_) => JsonKind {
                    frame: None,
                    kind: "scalar",
                },
                Value::Vector(_, f) => JsonKind {
                    frame: Some(f.as_str()),
                    kind: "vector",
                },
                Value::Matrix(_) => JsonKind {
                    frame: None,
                    kind: "matrix",
                },
                Value::List { .. } => JsonKind {
                    frame: None,
                    kind: "list",
                },
                Value::Array(_) => JsonKind {
                    frame: None,
                    kind: "array",
                },
            };
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
