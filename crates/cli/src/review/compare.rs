//! The semantic comparison of two versions of one derivation: steps matched
//! by name, components by label, each classified by canonical equality
//! (abbreviations unfolded, as `check` compares a result with its
//! expectation) and by the printed textbook form.
//!
//! Nothing here does algebra of its own: the values, the unfolding, the
//! subtraction and the textbook form of a difference are hdot-sym's.

use hdot_sym::derivation::{Derivation, Step};
use hdot_sym::document::step_lhs;
use hdot_sym::present::present;
use hdot_sym::{Expr, Poly, print};

/// One component of a step as a reviewer reads it.
#[derive(Clone, Debug)]
pub struct Component {
    /// The component's label (`x`, `theta''`, empty for a scalar).
    pub label: String,
    /// The equation in textbook form, Unicode: `ΣM_x = I_x ω̇_x − …`.
    pub text: String,
    /// The equation in LaTeX; `None` for a version read back from a
    /// snapshot file, which keeps only the Unicode form.
    pub latex: Option<String>,
    /// The value in canonical form with abbreviations unfolded; `None` when
    /// a snapshot's canonical line no longer reads (a symbol it names is
    /// not declared any more).
    pub canonical: Option<Poly>,
    /// The canonical form in source syntax (what a snapshot stores).
    pub canonical_text: String,
}

/// One step of a version.
#[derive(Clone, Debug)]
pub struct StepView {
    /// The step's name (steps are matched by it).
    pub name: String,
    /// The formula as written in the file, on one line.
    pub formula: String,
    /// Whether the step is printed (`show`).
    pub shown: bool,
    /// Its components in order.
    pub components: Vec<Component>,
}

/// The steps of one version of a derivation.
#[derive(Clone, Debug, Default)]
pub struct Version {
    /// Every step, hidden ones too (a change there is a change of what
    /// later steps are built from).
    pub steps: Vec<StepView>,
}

impl Version {
    /// The version a loaded derivation is.
    pub fn of(d: &Derivation) -> Version {
        Version {
            steps: d.steps.iter().map(|s| step_view(d, s)).collect(),
        }
    }
}

fn step_view(d: &Derivation, s: &Step) -> StepView {
    let values = s.values();
    let components = s
        .presented()
        .into_iter()
        .zip(values)
        .map(|((label, rhs), value)| {
            let lhs = step_lhs(s, &label);
            let (text, latex) = if lhs.is_zero() {
                (
                    format!("{} = 0", print::unicode(&rhs)),
                    format!("{} = 0", print::latex(&rhs)),
                )
            } else {
                (
                    format!("{} = {}", lhs.unicode(), print::unicode(&rhs)),
                    format!("{} = {}", lhs.latex(), print::latex(&rhs)),
                )
            };
            let canonical = d.unfold(value);
            Component {
                label,
                text,
                latex: Some(latex),
                canonical_text: canonical.to_source(),
                canonical: Some(canonical),
            }
        })
        .collect();
    StepView {
        name: s.name.clone(),
        formula: one_line(&s.formula),
        shown: s.show,
        components,
    }
}

/// Whitespace as one space: a formula may span lines in the file, and
/// re-wrapping it changes nothing.
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// What happened to a step or component between two versions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Change {
    /// Printed the same and canonically equal.
    Unchanged,
    /// Canonically equal, printed (or written) differently.
    Presentation,
    /// Canonically different.
    Mathematics,
    /// Only in the new version.
    Added,
    /// Only in the old version.
    Removed,
}

impl Change {
    /// Whether the mathematics differs (a new or removed step or
    /// component counts: what the file derives has changed).
    pub fn is_mathematical(self) -> bool {
        !matches!(self, Change::Unchanged | Change::Presentation)
    }

    /// A short phrase for reports.
    pub fn phrase(self) -> &'static str {
        match self {
            Change::Unchanged => "unchanged",
            Change::Presentation => "same mathematics, new presentation",
            Change::Mathematics => "different mathematics",
            Change::Added => "added",
            Change::Removed => "removed",
        }
    }

    /// The key used in JSON.
    pub fn key(self) -> &'static str {
        match self {
            Change::Unchanged => "unchanged",
            Change::Presentation => "presentation",
            Change::Mathematics => "mathematics",
            Change::Added => "added",
            Change::Removed => "removed",
        }
    }
}

/// `new − old` of a component whose mathematics changed, in textbook form.
#[derive(Clone, Debug)]
pub struct Difference {
    /// Unicode.
    pub text: String,
    /// LaTeX.
    pub latex: String,
    /// Canonical form in source syntax.
    pub canonical: String,
}

/// One component compared.
#[derive(Clone, Debug)]
pub struct ComponentDiff {
    /// The component's label.
    pub label: String,
    /// What happened to it.
    pub change: Change,
    /// The old version's component.
    pub old: Option<Component>,
    /// The new version's component.
    pub new: Option<Component>,
    /// `new − old` when the mathematics changed and both read.
    pub difference: Option<Difference>,
}

/// One step compared.
#[derive(Clone, Debug)]
pub struct StepDiff {
    /// The step's name.
    pub name: String,
    /// What happened to it: the weightiest change of its components, or a
    /// presentation change when only its written formula or `show` changed.
    pub change: Change,
    /// The formula, old and new, when it was rewritten.
    pub formula: Option<(String, String)>,
    /// `show`, old and new, when it changed.
    pub shown: Option<(bool, bool)>,
    /// Its components.
    pub components: Vec<ComponentDiff>,
}

/// Compares two versions; `new_d` is the new version's derivation, when
/// there is one (its steps' presentations put a difference in textbook
/// form). Steps come in
/// the new version's order, a removed step where it stood in the old one.
pub fn compare(old: &Version, new: &Version, new_d: Option<&Derivation>) -> Vec<StepDiff> {
    merge(&old.steps, &new.steps, |s| &s.name)
        .into_iter()
        .map(|(o, n)| match (o, n) {
            (Some(o), Some(n)) => compare_step(o, n, new_d),
            (Some(o), None) => whole_step(o, Change::Removed),
            (None, Some(n)) => whole_step(n, Change::Added),
            (None, None) => unreachable!("merge pairs at least one side"),
        })
        .collect()
}

/// Pairs the items of `old` and `new` by key: in `new`'s order, an item
/// only in `old` just after the old item before it.
fn merge<'a, T>(
    old: &'a [T],
    new: &'a [T],
    key: impl Fn(&T) -> &str,
) -> Vec<(Option<&'a T>, Option<&'a T>)> {
    let in_new = |k: &str| new.iter().any(|n| key(n) == k);
    let mut out = Vec::new();
    let mut next_old = 0;
    let flush_to = |end: usize, next_old: &mut usize, out: &mut Vec<_>| {
        while *next_old < end {
            let o = &old[*next_old];
            if !in_new(key(o)) {
                out.push((Some(o), None));
            }
            *next_old += 1;
        }
    };
    for n in new {
        match old.iter().position(|o| key(o) == key(n)) {
            Some(j) => {
                flush_to(j, &mut next_old, &mut out);
                next_old = next_old.max(j + 1);
                out.push((Some(&old[j]), Some(n)));
            }
            None => out.push((None, Some(n))),
        }
    }
    flush_to(old.len(), &mut next_old, &mut out);
    out
}

fn whole_step(s: &StepView, change: Change) -> StepDiff {
    let side = |c: &Component| {
        if change == Change::Added {
            (None, Some(c.clone()))
        } else {
            (Some(c.clone()), None)
        }
    };
    StepDiff {
        name: s.name.clone(),
        change,
        formula: None,
        shown: None,
        components: s
            .components
            .iter()
            .map(|c| {
                let (old, new) = side(c);
                ComponentDiff {
                    label: c.label.clone(),
                    change,
                    old,
                    new,
                    difference: None,
                }
            })
            .collect(),
    }
}

fn compare_step(o: &StepView, n: &StepView, new_d: Option<&Derivation>) -> StepDiff {
    let step = new_d.and_then(|d| d.steps.iter().find(|s| s.name == n.name));
    let components: Vec<ComponentDiff> = merge(&o.components, &n.components, |c| &c.label)
        .into_iter()
        .map(|pair| match pair {
            (Some(a), Some(b)) => compare_component(a, b, step),
            (Some(a), None) => ComponentDiff {
                label: a.label.clone(),
                change: Change::Removed,
                old: Some(a.clone()),
                new: None,
                difference: None,
            },
            (None, Some(b)) => ComponentDiff {
                label: b.label.clone(),
                change: Change::Added,
                old: None,
                new: Some(b.clone()),
                difference: None,
            },
            (None, None) => unreachable!("merge pairs at least one side"),
        })
        .collect();
    let formula = (o.formula != n.formula).then(|| (o.formula.clone(), n.formula.clone()));
    let shown = (o.shown != n.shown).then_some((o.shown, n.shown));
    let worst = components
        .iter()
        .map(|c| c.change)
        .max()
        .unwrap_or(Change::Unchanged);
    let change = if worst.is_mathematical() {
        Change::Mathematics
    } else if worst == Change::Presentation || formula.is_some() || shown.is_some() {
        Change::Presentation
    } else {
        Change::Unchanged
    };
    StepDiff {
        name: n.name.clone(),
        change,
        formula,
        shown,
        components,
    }
}

fn compare_component(a: &Component, b: &Component, step: Option<&Step>) -> ComponentDiff {
    let (same, difference) = match (&a.canonical, &b.canonical) {
        (Some(pa), Some(pb)) => {
            let d = pb - pa;
            if d.is_zero() {
                (true, None)
            } else {
                (false, Some(difference(&d, step)))
            }
        }
        _ => (a.canonical_text == b.canonical_text, None),
    };
    let change = if !same {
        Change::Mathematics
    } else if a.text != b.text {
        Change::Presentation
    } else {
        Change::Unchanged
    };
    ComponentDiff {
        label: b.label.clone(),
        change,
        old: Some(a.clone()),
        new: Some(b.clone()),
        difference,
    }
}

/// `d` in the textbook form of the new step (its abbreviations folded
/// back, its collect and factor lists).
fn difference(d: &Poly, step: Option<&Step>) -> Difference {
    let e: Expr = match step {
        Some(s) => present(d, &s.presentation),
        None => Expr::from_poly(d),
    };
    Difference {
        text: print::unicode(&e),
        latex: print::latex(&e),
        canonical: d.to_source(),
    }
}

/// What happened to a whole file: added, removed, or the weightiest change
/// of its steps.
pub fn file_change(old: bool, new: bool, steps: &[StepDiff]) -> Change {
    match (old, new) {
        (false, _) => Change::Added,
        (_, false) => Change::Removed,
        _ => {
            let worst = steps
                .iter()
                .map(|s| s.change)
                .max()
                .unwrap_or(Change::Unchanged);
            if worst.is_mathematical() {
                Change::Mathematics
            } else {
                worst
            }
        }
    }
}
