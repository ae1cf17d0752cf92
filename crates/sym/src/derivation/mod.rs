//! Derivation files: load, run, check.
//!
//! A derivation file is TOML with expression strings (the format is
//! documented in `docs/derivation-format.md`). [`load`] parses it, declares
//! its symbols and frames, evaluates every step on canonical values and
//! checks every expectation. Any error — TOML syntax, an unknown symbol, a
//! vector where a scalar is expected, an unknown function — is a
//! [`Diagnostic`] at file:line:column; an expectation that does not hold is
//! not an error but a failed [`Check`] that names the component and carries
//! the difference.
//!
//! # Example
//! ```
//! let text = r#"
//! title = "Angular momentum of a sphere"
//! source = "example"
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
//! assert!(d.all_hold());
//! ```

mod error;
mod eval;
mod raw;

use std::collections::HashMap;
use std::path::Path;

pub use error::Diagnostic;
pub use eval::Value;

use crate::atom::Atom;
use crate::expr::Expr;
use crate::frame::Frame;
use crate::poly::Poly;
use crate::present::{Presentation, present};
use crate::symbols::{Decl, Symbols};

/// A loaded and evaluated derivation.
#[derive(Clone, Debug)]
pub struct Derivation {
    /// Short name (the file stem).
    pub name: String,
    /// The file path as given.
    pub path: String,
    /// Title.
    pub title: String,
    /// Where the equations come from.
    pub source: String,
    /// Free text shown before the steps.
    pub summary: String,
    /// What is assumed, one sentence each.
    pub assumptions: Vec<String>,
    /// The declared symbols.
    pub symbols: Symbols,
    /// Abbreviations, in declaration order: name, atom, definition, doc.
    pub abbreviations: Vec<Abbreviation>,
    /// Frames in declaration order (the inertial frame `N` first).
    pub frames: Vec<Frame>,
    /// The evaluated steps.
    pub steps: Vec<Step>,
}

/// A named abbreviation such as ω_z := ψ̇ + φ̇ cos θ.
#[derive(Clone, Debug)]
pub struct Abbreviation {
    /// The name.
    pub name: String,
    /// The atom that stands for it (a time-dependent symbol).
    pub atom: Atom,
    /// What it stands for.
    pub definition: Poly,
    /// One-line description.
    pub doc: String,
}

/// One evaluated step.
#[derive(Clone, Debug)]
pub struct Step {
    /// The name later steps refer to.
    pub name: String,
    /// Display label of the left-hand side (`Sigma M`, `H`), in source form.
    pub label: String,
    /// What the step does, in words.
    pub doc: String,
    /// The expression as written in the file.
    pub formula: String,
    /// Whether the step is printed.
    pub show: bool,
    /// The value.
    pub value: Value,
    /// How to present it.
    pub presentation: Presentation,
    /// Names of the axes its components refer to.
    pub axes: [String; 3],
    /// The presented components: (component label, textbook-form tree);
    /// empty for hidden steps (see [`Step::presented`]).
    pub components: Vec<(String, Expr)>,
    /// Expectation checks, one per component, when the file states one.
    pub checks: Vec<Check>,
}

impl Step {
    /// The canonical components, in the order of [`Step::presented`]
    /// (scalar; x, y, z; a matrix by rows).
    pub fn values(&self) -> Vec<&Poly> {
        match &self.value {
            Value::Scalar(p) => vec![p],
            Value::Vector(v, _) => v.0.iter().collect(),
            Value::Matrix(m) => m.0.iter().flatten().collect(),
        }
    }

    /// The presented components, computed now for a hidden step.
    pub fn presented(&self) -> Vec<(String, Expr)> {
        if !self.components.is_empty() {
            return self.components.clone();
        }
        present_components(&self.value, &self.axes, &self.presentation)
    }
}

/// Each component of `value` presented, with its label: empty for a
/// scalar, the axis name for a vector, two axis names for a matrix entry.
fn present_components(
    value: &Value,
    axes: &[String; 3],
    presentation: &Presentation,
) -> Vec<(String, Expr)> {
    match value {
        Value::Scalar(p) => vec![(String::new(), present(p, presentation))],
        Value::Vector(v, _) => (0..3)
            .map(|k| (axes[k].clone(), present(&v.0[k], presentation)))
            .collect(),
        Value::Matrix(m) => (0..3)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .map(|(i, j)| {
                (
                    format!("{}{}", axes[i], axes[j]),
                    present(&m.0[i][j], presentation),
                )
            })
            .collect(),
    }
}

/// The outcome of comparing one component with its expectation.
#[derive(Clone, Debug)]
pub struct Check {
    /// The component's label (`x`, `y`, `z`, or empty for a scalar).
    pub component: String,
    /// The expected form as written.
    pub expected_text: String,
    /// The expected form as written (or presented like the result when it
    /// refers to earlier steps).
    pub expected: Expr,
    /// `derived − expected`, with abbreviations expanded; zero when it holds.
    pub difference: Poly,
}

impl Check {
    /// True when the derived and expected forms are equal.
    pub fn holds(&self) -> bool {
        self.difference.is_zero()
    }
}

impl Derivation {
    /// True when every expectation holds.
    pub fn all_hold(&self) -> bool {
        self.steps.iter().flat_map(|s| &s.checks).all(Check::holds)
    }

    /// Number of expectations checked.
    pub fn check_count(&self) -> usize {
        self.steps.iter().map(|s| s.checks.len()).sum()
    }

    /// Failed checks as `(step name, check)`.
    pub fn failures(&self) -> Vec<(&str, &Check)> {
        self.steps
            .iter()
            .flat_map(|s| {
                s.checks
                    .iter()
                    .filter(|c| !c.holds())
                    .map(move |c| (s.name.as_str(), c))
            })
            .collect()
    }

    /// The frame called `name`.
    pub fn frame(&self, name: &str) -> Option<&Frame> {
        self.frames.iter().find(|f| f.name == name)
    }

    /// Replaces every abbreviation (and its derivatives) by its definition.
    pub fn unfold(&self, p: &Poly) -> Poly {
        unfold(&self.abbreviations, p)
    }
}

pub(crate) fn unfold(abbrevs: &[Abbreviation], p: &Poly) -> Poly {
    let mut p = p.clone();
    // Later abbreviations may use earlier ones: unfold in reverse order.
    for a in abbrevs.iter().rev() {
        p = p.subst(&mut |x| (x.base() == a.atom).then(|| a.definition.dt_n(x.order())));
    }
    p
}

/// Loads, runs and checks the derivation file at `path`.
pub fn load(path: &Path) -> Result<Derivation, Diagnostic> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| Diagnostic::file(&shown, format!("cannot read the file: {e}")))?;
    load_str(&shown, &text)
}

/// Loads, runs and checks a derivation given as text; `path` names it in messages.
pub fn load_str(path: &str, text: &str) -> Result<Derivation, Diagnostic> {
    let raw = raw::parse(path, text)?;
    let name = Path::new(path)
        .file_stem()
        .map_or_else(|| path.to_owned(), |s| s.to_string_lossy().into_owned());
    let mut cx = eval::Context::new(path, text);

    // Symbols.
    for (list, decl) in [
        (&raw.symbols.constants, Decl::Constant),
        (&raw.symbols.time, Decl::Time),
        (&raw.symbols.small, Decl::Time),
    ] {
        for s in list.iter() {
            cx.declare(s, decl.clone())?;
        }
    }
    for s in &raw.symbols.small {
        cx.small.push(Atom::time(s.get_ref(), 0));
    }
    for s in &raw.symbols.positive {
        cx.declare_positive(s)?;
    }
    // Abbreviations: time-dependent names standing for an expression.
    let mut abbreviations = Vec::new();
    for a in &raw.abbreviations {
        let def = cx.scalar_in(&a.value)?;
        cx.declare(&a.name, Decl::Abbrev(def.clone()))?;
        abbreviations.push(Abbreviation {
            name: a.name.get_ref().clone(),
            atom: Atom::time(a.name.get_ref(), 0),
            definition: def,
            doc: a.doc.clone(),
        });
    }
    // Frames.
    for f in &raw.frames {
        cx.add_frame(f)?;
    }
    // Steps.
    let mut steps = Vec::new();
    let mut seen: HashMap<String, ()> = HashMap::new();
    for s in &raw.steps {
        if seen.insert(s.name.get_ref().clone(), ()).is_some() {
            return Err(cx.diag_string(
                &s.name,
                0,
                s.name.get_ref().len(),
                "a step of this name is already defined",
            ));
        }
        let value = cx.eval_step(s)?;
        let presentation = cx.presentation(s, &abbreviations)?;
        let axes = cx.axes_of(&value);
        // Only shown steps are presented (hidden ones are printed nowhere
        // but JSON, which presents them on demand).
        let components = if s.show {
            present_components(&value, &axes, &presentation)
        } else {
            Vec::new()
        };
        let checks = cx.checks(s, &value, &abbreviations, &presentation, &axes)?;
        cx.bind(s.name.get_ref(), value.clone());
        steps.push(Step {
            name: s.name.get_ref().clone(),
            label: s.label.clone().unwrap_or_else(|| s.name.get_ref().clone()),
            doc: s.doc.clone(),
            formula: s.value.get_ref().clone(),
            show: s.show,
            value,
            presentation,
            axes,
            components,
            checks,
        });
    }
    Ok(Derivation {
        name,
        path: path.to_owned(),
        title: raw.title,
        source: raw.source,
        summary: raw.summary,
        assumptions: raw.assumptions,
        symbols: cx.symbols.clone(),
        abbreviations,
        frames: cx.frames.clone(),
        steps,
    })
}
