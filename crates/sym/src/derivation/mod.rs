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

mod attitude;
mod attitude_quaternion;
mod checks;
mod contact;
mod context;
mod error;
mod eval;
mod frames;
mod joints;
mod labels;
mod loads;
mod multibody;
mod operating;
pub mod ops;
pub mod physics;
mod presentation;
mod quaternion;
mod raw;
mod speeds;
mod value;

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

pub use error::Diagnostic;
pub use multibody::{Load, Speeds};
pub use value::Value;

use crate::atom::Atom;
use crate::expr::Expr;
use crate::frame::Frame;
pub use crate::limits::Limits;
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
    /// Title, on one line: the file's line breaks and runs of white space
    /// are single spaces (a heading cannot hold a paragraph break: a blank
    /// line in a LaTeX `\section{…}` ends it with an error).
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
    /// The physical model the file declares (empty without declarations).
    pub physics: physics::Physics,
    /// The generalized speeds and kinematic equations (empty without
    /// `[symbols] speeds`).
    pub speeds: Speeds,
    /// The applied forces and torques (`[[load]]`): verification takes them
    /// from the resultant a body's supports carry.
    pub loads: Vec<Load>,
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
    /// What it means physically (`means`), verified like a step's.
    pub meaning: Option<physics::StepMeaning>,
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
    /// The label when it is mathematics rather than a name (see
    /// [`crate::label::LabelMath`]): `phi''*sin(theta)`,
    /// `partial(T, theta')`, `0`.
    pub label_math: Option<crate::label::LabelMath>,
    /// The value.
    pub value: Value,
    /// How to present it.
    pub presentation: Presentation,
    /// Names of the axes its components refer to.
    pub axes: [String; 3],
    /// The presented components, computed on first use (see
    /// [`Step::components`]): a derivation that fails at a later step, or
    /// whose output is never printed, pays nothing for presenting it.
    presented: std::sync::OnceLock<Vec<(String, Arc<Expr>)>>,
    /// Expectation checks, one per component, when the file states one.
    pub checks: Vec<Check>,
    /// What the step means physically (`means`), when the file says.
    pub meaning: Option<physics::StepMeaning>,
    /// Whether the file marks the value as constant along the motion
    /// (`conserved = true`): simulations of the file's equations report
    /// its drift.
    pub conserved: bool,
}

impl Step {
    /// The canonical components, in the order of [`Step::presented`]
    /// (scalar; x, y, z; a matrix or array by rows; a list in order).
    pub fn values(&self) -> Vec<&Poly> {
        self.value.components()
    }

    /// The presented components of a shown step: (component label,
    /// textbook-form tree); empty for hidden steps (see
    /// [`Step::presented`]).
    pub fn components(&self) -> &[(String, Arc<Expr>)] {
        if self.show { self.presented_ref() } else { &[] }
    }

    /// The presented components, hidden steps included.
    pub fn presented(&self) -> Vec<(String, Expr)> {
        self.presented_ref()
            .iter()
            .map(|(c, e)| (c.clone(), Expr::clone(e)))
            .collect()
    }

    fn presented_ref(&self) -> &[(String, Arc<Expr>)] {
        self.presented
            .get_or_init(|| present_components(&self.value, &self.axes, &self.presentation))
    }
}

/// The label of each component of `value`: empty for a scalar, the axis
/// name for a vector, two axis names for a matrix entry, the unknown's
/// source name for a solved list (`theta''`), the position (1, 2, …) for an
/// unlabelled list and `ij` for an array entry.
pub(crate) fn component_labels(value: &Value, axes: &[String; 3]) -> Vec<String> {
    match value {
        Value::Scalar(_) => vec![String::new()],
        Value::Vector(..) => axes.to_vec(),
        Value::Matrix(_) => (0..9)
            .map(|k| format!("{}{}", axes[k / 3], axes[k % 3]))
            .collect(),
        Value::List { items, labels } if labels.len() == items.len() => {
            labels.iter().map(|a| a.to_string()).collect()
        }
        Value::List { items, .. } => (1..=items.len()).map(|k| k.to_string()).collect(),
        Value::Array(rows) => rows
            .iter()
            .enumerate()
            .flat_map(|(i, r)| (0..r.len()).map(move |j| format!("{}{}", i + 1, j + 1)))
            .collect(),
    }
}

/// Each component of `value` presented, with its label (see
/// [`component_labels`]).
fn present_components(
    value: &Value,
    axes: &[String; 3],
    presentation: &Presentation,
) -> Vec<(String, Arc<Expr>)> {
    component_labels(value, axes)
        .into_iter()
        .zip(value.components())
        .map(|(l, p)| (l, Arc::new(present(p, presentation))))
        .collect()
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

    /// The generalized speeds u, in declaration order.
    pub fn speeds(&self) -> &[Atom] {
        &self.speeds.speeds
    }

    /// The kinematic equations q̇ = f(q, u): each coordinate with its rate,
    /// in the file's order.
    pub fn kinematic_equations(&self) -> &[(Atom, Poly)] {
        &self.speeds.kinematics
    }

    /// The values of step `step`, solved for the speeds' rates, in the
    /// order of [`Derivation::speeds`] (abbreviations unfolded); an error
    /// message when the step is not such a list.
    pub fn speed_rates(&self, step: &str) -> Result<Vec<Poly>, String> {
        speeds::speed_rates(self, step)
    }
}

pub(crate) fn unfold(abbrevs: &[Abbreviation], p: &Poly) -> Poly {
    // Most values name no abbreviation (nor a sum of constants, whose
    // terms `subst` visits): nothing to replace, so no pass per
    // abbreviation.
    let named = |x: Atom| {
        matches!(x.kind(), crate::atom::AtomKind::Sum { .. })
            || abbrevs.iter().any(|a| x.base() == a.atom)
    };
    if abbrevs.is_empty() || !p.atoms().into_iter().any(named) {
        return p.clone();
    }
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
    let text = crate::textfile::read(path).map_err(|e| Diagnostic::read(&shown, e))?;
    load_str(&shown, &text)
}

/// Loads, runs and checks a derivation given as text; `path` names it in
/// messages. Runs under the default [`Limits`] (a file's `[limits]` table
/// overrides them).
pub fn load_str(path: &str, text: &str) -> Result<Derivation, Diagnostic> {
    load_str_with(path, text, Limits::DEFAULT)
}

/// [`load_str`] under `limits` (a file's `[limits]` table overrides them).
pub fn load_str_with(path: &str, text: &str, limits: Limits) -> Result<Derivation, Diagnostic> {
    let raw = raw::parse(path, text)?;
    let limits = raw.limits.as_ref().map_or(limits, |l| l.over(limits));
    // Runs `f` under the limits; a limit exceeded becomes an error at `at`.
    let limited = |cx: &context::Context<'_>,
                   at: &toml::Spanned<String>,
                   what: &str,
                   f: &mut dyn FnMut() -> Result<(), Diagnostic>| {
        match crate::limits::scope(limits, f) {
            Ok(r) => r,
            Err(e) => Err(cx.diag_string(
                at,
                0,
                at.get_ref().len(),
                format!(
                    "{what}: {e}; raise the limit with `{} = …` under [limits] in the file",
                    e.setting(),
                ),
            )),
        }
    };
    let name = Path::new(path)
        .file_stem()
        .map_or_else(|| path.to_owned(), |s| s.to_string_lossy().into_owned());
    let mut cx = context::Context::new(path, text);

    cx.declare_symbols(&raw.symbols)?;
    // Abbreviations: time-dependent names standing for an expression.
    let mut abbreviations = Vec::new();
    for a in &raw.abbreviations {
        let mut def = Poly::zero();
        limited(&cx, &a.name, "this abbreviation", &mut || {
            def = cx.scalar_in(&a.value)?;
            Ok(())
        })?;
        cx.declare(&a.name, Decl::Abbrev(def.clone()))?;
        let abbreviation = Abbreviation {
            name: a.name.get_ref().clone(),
            atom: Atom::time(a.name.get_ref(), 0),
            definition: def,
            doc: a.doc.clone(),
            meaning: None,
        };
        cx.abbrevs.push(abbreviation.clone());
        abbreviations.push(abbreviation);
    }
    // Frames.
    for f in &raw.frames {
        let mut cx_frame = None;
        limited(&cx, &f.name, "this frame", &mut || {
            cx_frame = Some(cx.frame_of(f)?);
            Ok(())
        })?;
        cx.push_frame(cx_frame.expect("built"));
    }
    speeds::declare(&mut cx, &raw)?;
    // Bodies, points, gravity, knowns, conditions.
    let mut physics = physics::declarations(&cx, &raw)?;
    // Rolling contacts declare their contact points.
    cx.physics = physics.clone();
    let (contacts, contact_points) = contact::declare(&cx, &raw.contacts)?;
    physics.points.extend(contact_points);
    cx.contacts = contacts;
    for (a, r) in abbreviations.iter_mut().zip(&raw.abbreviations) {
        let value = Value::Scalar(a.definition.clone());
        a.meaning = physics::abbreviation_meaning(&cx, &physics, r, &value)?;
    }
    cx.physics = physics.clone();
    cx.loads = loads::declare(&cx, &raw)?;
    // Steps, each printing the terms of what the file solves for first.
    cx.unknowns = cx.solve_targets(&raw.steps);
    let mut steps = Vec::new();
    let mut seen: HashMap<String, ()> = HashMap::new();
    // Per step, the angles its value is written in the deviation of.
    let mut shifted: HashMap<String, Vec<(String, i64)>> = HashMap::new();
    for (k, s) in raw.steps.iter().enumerate() {
        if seen.insert(s.name.get_ref().clone(), ()).is_some() {
            return Err(cx.diag_string(
                &s.name,
                0,
                s.name.get_ref().len(),
                "a step of this name is already defined",
            ));
        }
        let n = s.name.get_ref();
        cx.valid_name(&s.name, "step")?;
        if cx.frame_index(n) == Some(0) {
            return Err(cx.diag_string(
                &s.name,
                0,
                n.len(),
                format!(
                    "a step may not be named `{n}`: {n} is the inertial frame, which every derivation has; choose another name"
                ),
            ));
        }
        if cx.symbols.get(n).is_some() || cx.frame_index(n).is_some() {
            return Err(cx.diag_string(
                &s.name,
                0,
                n.len(),
                "a step may not be named like a declared symbol or frame: it would shadow it in later steps and expectations",
            ));
        }
        let mut out = None;
        limited(
            &cx,
            &s.name,
            &format!("step `{}`", s.name.get_ref()),
            &mut || {
                let value = cx.eval_step(s)?;
                let value = match cx.speeds.unit_norms.as_slice() {
                    [] => value,
                    norms => value.map(&mut |p| quaternion::reduce_all(p, norms)),
                };
                let presentation = cx.presentation(s, &abbreviations)?;
                let axes = cx.axes_of(&value);
                let checks = cx.checks(s, &value, &abbreviations, &presentation, &axes)?;
                let meaning = physics::step_meaning(&cx, &physics, s, &value)?;
                out = Some((value, presentation, axes, checks, meaning));
                Ok(())
            },
        )?;
        let (value, presentation, axes, checks, meaning) = out.expect("evaluated");
        let label_math = match &s.label {
            Some(l) => crate::label::LabelMath::parse(l.get_ref(), &cx.symbols, &|w| {
                cx.is_step(w) || w == s.name.get_ref()
            })
            .map_err(|m| {
                let n = s.name.get_ref();
                cx.diag_string(
                    l,
                    0,
                    l.get_ref().len(),
                    format!("step `{n}`, field `label`: {m}"),
                )
            })?,
            None => None,
        };
        cx.check_label(s, &value, label_math.as_ref())?;
        let doc = deviations_said(&mut shifted, s, &value);
        // A step's value is bound for the steps after it to name; the last
        // has none after it, and its copy (chain-8's Ḣ: 126,000 terms) would
        // only be made to be dropped.
        if k + 1 < raw.steps.len() {
            cx.bind(s.name.get_ref(), value.clone());
        }
        steps.push(Step {
            name: s.name.get_ref().clone(),
            label: s
                .label
                .as_ref()
                .map_or_else(|| s.name.get_ref().clone(), |l| l.get_ref().clone()),
            doc,
            formula: s.value.get_ref().clone(),
            show: s.show,
            label_math,
            value,
            presentation,
            axes,
            presented: std::sync::OnceLock::new(),
            checks,
            meaning,
            conserved: s.conserved,
        });
    }
    Ok(Derivation {
        name,
        path: path.to_owned(),
        title: crate::prose::one_line(&raw.title),
        source: raw.source,
        summary: raw.summary,
        assumptions: raw.assumptions,
        symbols: cx.symbols.clone(),
        abbreviations,
        frames: cx.frames.clone(),
        steps,
        physics,
        speeds: cx.speeds.clone(),
        loads: cx.loads.clone(),
    })
}

/// The step's doc, with what its printed angles stand for when its value
/// is written in the deviation of some from an operating point at a
/// multiple of π/2 (`kane(…, q = pi)`: q stands for q − π) — the value's
/// own or an earlier step's it names — recorded in `shifted` for later
/// steps. Only angles the value still holds are named.
fn deviations_said(
    shifted: &mut HashMap<String, Vec<(String, i64)>>,
    s: &raw::RawStep,
    value: &Value,
) -> String {
    let text = s.value.get_ref();
    if !text.contains("pi") && shifted.is_empty() {
        return s.doc.clone();
    }
    let Ok(ast) = crate::parse::parse(text) else {
        return s.doc.clone();
    };
    let mut angles = operating::shifted_angles(&ast, shifted);
    let held: std::collections::BTreeSet<&str> = value
        .components()
        .into_iter()
        .flat_map(|p| p.atoms())
        .map(|a| match a.kind() {
            crate::atom::AtomKind::Sin(x) | crate::atom::AtomKind::Cos(x) => x.name(),
            _ => a.name(),
        })
        .collect();
    angles.retain(|(q, _)| held.contains(q.as_str()));
    if angles.is_empty() {
        return s.doc.clone();
    }
    let note = operating::deviation_note(&angles);
    shifted.insert(s.name.get_ref().clone(), angles);
    if s.doc.is_empty() {
        note
    } else {
        format!("{}; {note}", s.doc)
    }
}
