//! The document hdot writes about derivations, built once and rendered by
//! each output format: `hdot derive` (one [`Section`]) and `hdot notes`
//! (a [`Document`] of chapters of sections, arranged by a [`Course`]).
//!
//! A section holds prose (titles, summaries, docs, assumptions — written
//! in hdot's notation and typeset by [`crate::prose`]), lists of symbols,
//! and equations as expression trees with their left sides; it never holds
//! printed LaTeX, so every backend prints the same content its own way.
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
//! let s = hdot_sym::document::Section::of(&d, None);
//! assert_eq!(s.steps.len(), 1);
//! assert_eq!(s.steps[0].equations.len(), 3);
//! assert!(matches!(s.steps[0].verdict, hdot_sym::document::Verdict::Holds));
//! ```

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::derivation::{Check, Derivation, Step, Value};
use crate::escape;
use crate::expr::Expr;
use crate::print;
use crate::symbols::Decl;

pub use crate::label::{LabelMath, latex_label, unicode_label};

// ------------------------------------------------------------- document --

/// A whole document: lecture notes or slides.
#[derive(Clone, Debug)]
pub struct Document {
    /// Title.
    pub title: String,
    /// Author line.
    pub author: String,
    /// Prose before the first chapter.
    pub intro: String,
    /// Chapters in order; a single chapter without a title means the
    /// document is not divided into chapters.
    pub chapters: Vec<Chapter>,
}

/// A chapter: a group of derivations under one heading.
#[derive(Clone, Debug)]
pub struct Chapter {
    /// Heading; empty for a document without chapters.
    pub title: String,
    /// Prose before its first section.
    pub intro: String,
    /// Its derivations, in order.
    pub sections: Vec<Section>,
}

/// One derivation.
#[derive(Clone, Debug)]
pub struct Section {
    /// Short name (the file stem), for labels and anchors.
    pub name: String,
    /// Title (prose).
    pub title: String,
    /// Textbook source (prose).
    pub source: String,
    /// The file, as given.
    pub path: String,
    /// Summary (prose).
    pub summary: String,
    /// Assumptions (prose).
    pub assumptions: Vec<String>,
    /// Symbol names of the constants.
    pub constants: Vec<String>,
    /// Symbol names of the functions of time.
    pub time: Vec<String>,
    /// Abbreviations: name, definition, doc.
    pub abbreviations: Vec<(String, Expr, String)>,
    /// Frames other than the inertial one.
    pub frames: Vec<FrameItem>,
    /// The steps shown.
    pub steps: Vec<StepBlock>,
}

impl Section {
    /// The equations printed by name in their steps ([`StepBlock::named`]),
    /// in the order of the steps: what the section lists at its end under
    /// *Coefficients*, each with its number of terms.
    pub fn coefficients(&self) -> Vec<(&Equation, usize)> {
        self.steps
            .iter()
            .flat_map(|st| {
                st.equations
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| st.named(*k))
                    .map(|(k, e)| (e, st.terms[k]))
            })
            .collect()
    }
}

/// A frame with its angular velocity.
#[derive(Clone, Debug)]
pub struct FrameItem {
    /// Frame name.
    pub name: String,
    /// Axis names.
    pub axes: Vec<String>,
    /// The frame it is turned from, if declared so.
    pub parent: Option<String>,
    /// Ω in the frame's own axes, one equation per axis (`Ω_x = …`).
    pub omega: Vec<Equation>,
    /// Description.
    pub doc: String,
}

/// The left side of an equation.
#[derive(Clone, Debug)]
pub enum Lhs {
    /// A step label with a component: `Sigma M` and `x` (ΣM_x).
    Label(String, String),
    /// An expression: the unknown of a solved list (θ̈).
    Expr(Expr),
    /// A label that is mathematics, with a component (empty for a scalar):
    /// (φ̈ sin θ)_x, ∂T/∂θ̇.
    Math(LabelMath, String),
}

impl Lhs {
    /// LaTeX.
    pub fn latex(&self) -> String {
        match self {
            Lhs::Label(l, c) => latex_label(l, c),
            Lhs::Expr(e) => print::latex(e),
            Lhs::Math(LabelMath::Zero, _) => "0".to_owned(),
            Lhs::Math(m, c) if c.is_empty() => m.latex(),
            Lhs::Math(m, c) if m.compound() => {
                format!(r"\left({}\right)_{{{}}}", m.latex(), escape::latex_math(c))
            }
            Lhs::Math(m, c) => format!("{}_{{{}}}", m.latex(), escape::latex_math(c)),
        }
    }

    /// Unicode.
    pub fn unicode(&self) -> String {
        match self {
            Lhs::Label(l, c) => unicode_label(l, c),
            Lhs::Expr(e) => print::unicode(e),
            Lhs::Math(LabelMath::Zero, _) => "0".to_owned(),
            Lhs::Math(m, c) if c.is_empty() => m.unicode(),
            Lhs::Math(m, c) if m.compound() => format!("({})_{c}", m.unicode()),
            Lhs::Math(m, c) => format!("{}_{c}", m.unicode()),
        }
    }

    /// True for `0`: the equation is printed `result = 0`.
    pub fn is_zero(&self) -> bool {
        matches!(self, Lhs::Math(LabelMath::Zero, _))
    }
}

/// An equation `lhs = rhs` with the right side as an expression tree.
#[derive(Clone, Debug)]
pub struct Equation {
    /// Left side.
    pub lhs: Lhs,
    /// Right side, shared with the step it shows (a large result is not
    /// copied into the document).
    pub rhs: Arc<Expr>,
}

/// Whether a step's result equals its expectation.
#[derive(Clone, Debug)]
pub enum Verdict {
    /// No expectation is stated.
    NoExpectation,
    /// Every expectation holds.
    Holds,
    /// Some do not: for each, the expected form and derived − expected.
    Fails(Vec<(Equation, Equation)>),
}

impl Verdict {
    /// The words every backend shows for a step without an expectation
    /// (each marks them up its own way: emphasis, a capital, a stop).
    pub const NONE: &str = "no expectation is stated for this step";
    /// The words for a step whose expectations hold.
    pub const HOLDS: &str = "equals the expected (textbook) form";
    /// The words for a step some of whose expectations fail.
    pub const FAILS: &str = "does not equal the expected form";
    /// What follows [`Verdict::FAILS`] where the differences are shown:
    /// `minus` is the backend's minus sign.
    pub fn fails_shown(minus: &str) -> String {
        format!("derived {minus} expected is shown")
    }
}

/// One shown step.
#[derive(Clone, Debug)]
pub struct StepBlock {
    /// Step name in the file.
    pub name: String,
    /// The label (`Sigma M`), without component.
    pub label: String,
    /// The label as the step's heading shows it: a name (ΣM) or
    /// mathematics (φ̈ sin θ, ∂T/∂θ̇, or `0` for an equation `… = 0`).
    pub heading: Lhs,
    /// What the step does (prose).
    pub doc: String,
    /// The formula as written in the file.
    pub formula: String,
    /// The frame a vector's components are in.
    pub frame: Option<String>,
    /// The result, one equation per component (a matrix's entries row by
    /// row).
    pub equations: Vec<Equation>,
    /// Rows and columns of a matrix result (an inertia tensor, a mass
    /// matrix), whose equations are its entries row by row; `None` for a
    /// scalar, vector or list.
    pub shape: Option<(usize, usize)>,
    /// Whether it equals its expectation.
    pub verdict: Verdict,
    /// The conditions the result holds under (its `given`: a constant,
    /// coordinate or rate fixed, a point at rest, a class of bodies), as
    /// prose with each formula between `$` signs — `$θ = π/2$, $O$ at
    /// rest`; empty for a step without conditions. The backends print it
    /// beside the step as "for …".
    pub condition: String,
    /// The number of terms of each equation's right side in canonical
    /// form, in the order of `equations`: what
    /// decides whether it is printed by name ([`StepBlock::named`]).
    pub terms: Vec<usize>,
    /// A square matrix equal to its transpose: an entry below the diagonal
    /// is printed by the name of the one above it.
    pub symmetric: bool,
}

/// The size above which a result is printed as a named coefficient: an
/// equation of a step whose right side has more than this many terms in
/// canonical form is written in its step by its name (M_{11}, f_{3}, E)
/// and defined at the end of its derivation's section, under
/// *Coefficients* (the LaTeX notes, fragments, Markdown and web pages; the
/// slides name it and refer to the notes). An equation labelled 0 has no
/// name and is printed whole. The one place of this rule; documented in
/// docs/notes/README.md (*Long results as named coefficients*).
pub const NAMED_ABOVE: usize = 120;

/// True for the expression `0`.
pub fn is_zero(e: &Expr) -> bool {
    e.is_empty() || matches!(e.node(e.root()), crate::expr::Node::Num(r) if r.is_zero())
}

/// The left side of component `component` of step `s`: the unknown of a
/// solved list (θ̈ in θ̈ = …), else the label with the component.
pub fn step_lhs(s: &Step, component: &str) -> Lhs {
    if let Value::List { labels, .. } = &s.value
        && let Some(a) = labels.iter().find(|a| a.to_string() == component)
    {
        let mut e = Expr::new();
        e.push(crate::expr::Node::Atom(*a));
        return Lhs::Expr(e);
    }
    match &s.label_math {
        Some(m) => Lhs::Math(m.clone(), component.to_owned()),
        None => Lhs::Label(s.label.clone(), component.to_owned()),
    }
}

impl StepBlock {
    /// True for a step labelled `0` whose result is identically zero: the
    /// relation it states holds for every value of the symbols, and the
    /// backends say so instead of printing `0 = 0`.
    pub fn vanishes(&self) -> bool {
        self.heading.is_zero() && self.equations.iter().all(|e| is_zero(&e.rhs))
    }

    /// True when equation `k` is printed by its name in the step and
    /// defined under *Coefficients*: more than [`NAMED_ABOVE`] terms, and a
    /// left side that names it (not `0`).
    /// In a symmetric matrix only the entry above the diagonal is named;
    /// the one below it shows that name.
    pub fn named(&self, k: usize) -> bool {
        let below = match self.shape {
            Some((_, m)) if self.symmetric => k % m < k / m,
            _ => false,
        };
        self.terms.get(k).is_some_and(|&t| t > NAMED_ABOVE)
            && !self.equations[k].lhs.is_zero()
            && !below
    }

    /// True when some equation of the step is printed by name.
    pub fn has_named(&self) -> bool {
        (0..self.equations.len()).any(|k| self.named(k))
    }

    /// The block of step `s`.
    pub fn of(s: &Step) -> StepBlock {
        let equations: Vec<Equation> = s
            .components()
            .iter()
            .map(|(c, e)| Equation {
                lhs: step_lhs(s, c),
                rhs: e.clone(),
            })
            .collect();
        let verdict = if s.checks.is_empty() {
            Verdict::NoExpectation
        } else if s.checks.iter().all(Check::holds) {
            Verdict::Holds
        } else {
            Verdict::Fails(
                s.checks
                    .iter()
                    .filter(|c| !c.holds())
                    .map(|c| {
                        (
                            Equation {
                                lhs: step_lhs(s, &c.component),
                                rhs: Arc::new(c.expected.clone()),
                            },
                            Equation {
                                lhs: step_lhs(s, &c.component),
                                rhs: Arc::new(Expr::from_poly(&c.difference)),
                            },
                        )
                    })
                    .collect(),
            )
        };
        StepBlock {
            name: s.name.clone(),
            label: s.label.clone(),
            heading: match &s.label_math {
                Some(m) => Lhs::Math(m.clone(), String::new()),
                None => Lhs::Label(s.label.clone(), String::new()),
            },
            doc: s.doc.clone(),
            formula: s.formula.clone(),
            frame: match &s.value {
                Value::Vector(_, f) => Some(f.clone()),
                _ => None,
            },
            shape: match &s.value {
                Value::Matrix(_) => Some((3, 3)),
                Value::Array(rows) => Some((rows.len(), rows.first().map_or(0, Vec::len))),
                _ => None,
            }
            .filter(|(n, m)| n * m == equations.len() && n * m > 0),
            symmetric: match &s.value {
                Value::Matrix(m) => (0..3).all(|i| (0..i).all(|j| m.0[i][j] == m.0[j][i])),
                Value::Array(rows) => rows
                    .iter()
                    .enumerate()
                    .all(|(i, r)| r.len() == rows.len() && (0..i).all(|j| r[j] == rows[j][i])),
                _ => false,
            },
            terms: if s.show {
                s.value
                    .components()
                    .iter()
                    .map(|p| p.terms().len())
                    .collect()
            } else {
                Vec::new()
            },
            equations,
            verdict,
            condition: condition(s),
        }
    }
}

/// The conditions of step `s` as prose (see [`StepBlock::condition`]):
/// its rules as equations in the printers' notation, then its points at
/// rest, then the inequalities selecting a class of bodies.
fn condition(s: &Step) -> String {
    use crate::derivation::physics::{RuleValue, StepMeaning};
    let Some(StepMeaning {
        given,
        at_rest,
        bounds,
        ..
    }) = &s.meaning
    else {
        return String::new();
    };
    let mut items: Vec<String> = given
        .iter()
        .map(|r| {
            let mut lhs = Expr::new();
            lhs.push(crate::expr::Node::Atom(r.target));
            let rhs = match &r.value {
                RuleValue::Expr(p) => print::unicode(&Expr::from_poly(p)),
                RuleValue::QuarterTurns(t) => quarter_turns(*t),
            };
            format!("${} = {rhs}$", print::unicode(&lhs))
        })
        .collect();
    items.extend(at_rest.iter().map(|(p, order)| match order {
        1 => format!("${p}$ at rest"),
        2 => format!("${p}$ without acceleration"),
        k => format!("the derivatives of ${p}$ from order {k} zero"),
    }));
    items.extend(bounds.iter().map(|(_, text)| format!("${}$", text.trim())));
    items.join(", ")
}

/// `t` quarter turns as an angle in the printers' notation: π/2, π,
/// −3π/2, 0.
fn quarter_turns(t: i64) -> String {
    let sign = if t < 0 { "−" } else { "" };
    match (t.unsigned_abs(), t % 2 == 0) {
        (0, _) => "0".to_owned(),
        (2, _) => format!("{sign}π"),
        (1, _) => format!("{sign}π/2"),
        (a, true) => format!("{sign}{}π", a / 2),
        (a, false) => format!("{sign}{a}π/2"),
    }
}

impl Section {
    /// The section of derivation `d`, showing the steps named in `show`
    /// (in the file's order), or the file's shown steps when `None`.
    pub fn of(d: &Derivation, show: Option<&[String]>) -> Section {
        // Symbols named in prose as in formulas (`theta'`) in their notation.
        let notation = |t: &str| crate::prose::in_notation(t, &d.symbols);
        let names = |want: fn(&Decl) -> bool| -> Vec<String> {
            d.symbols
                .names()
                .iter()
                .filter(|n| d.symbols.get(n).is_some_and(want))
                .cloned()
                .collect()
        };
        let frames = d
            .frames
            .iter()
            .skip(1)
            .map(|f| FrameItem {
                name: f.name.clone(),
                axes: f.axes.to_vec(),
                parent: f.parent.as_ref().map(|(p, _)| p.clone()),
                omega: f
                    .axes
                    .iter()
                    .zip(&f.omega.0)
                    .map(|(a, p)| Equation {
                        lhs: Lhs::Label("Omega".into(), a.clone()),
                        rhs: Arc::new(Expr::from_poly(p)),
                    })
                    .collect(),
                doc: notation(&f.doc),
            })
            .collect();
        let steps = d
            .steps
            .iter()
            .filter(|s| match show {
                Some(list) => list.contains(&s.name),
                None => s.show,
            })
            .map(|s| {
                let b = StepBlock::of(s);
                StepBlock {
                    doc: notation(&s.doc),
                    condition: notation(&b.condition),
                    ..b
                }
            })
            .collect();
        Section {
            name: d.name.clone(),
            title: notation(&d.title),
            source: d.source.clone(),
            path: d.path.clone(),
            summary: notation(d.summary.trim()),
            assumptions: d.assumptions.iter().map(|a| notation(a)).collect(),
            constants: names(|x| matches!(x, Decl::Constant)),
            time: names(|x| matches!(x, Decl::Time)),
            abbreviations: d
                .abbreviations
                .iter()
                .map(|a| {
                    (
                        a.name.clone(),
                        Expr::from_poly(&a.definition),
                        notation(&a.doc),
                    )
                })
                .collect(),
            frames,
            steps,
        }
    }
}

/// What a step labelled `0` whose result is identically zero shows
/// instead of `0 = 0` (see [`StepBlock::vanishes`]).
pub const VANISHES: &str = "the formula reduces to 0: the relation holds identically";

/// An output format of the document: it renders what a [`Section`] or a
/// [`Document`] holds, in its own language and layout, and decides
/// nothing about the content (every backend shows the same things in the
/// same order). The backends are listed in [`crate::notes::BACKENDS`].
pub trait Backend: Sync {
    /// The format's name (`unicode`, `latex`, `markdown`, `slides`).
    fn name(&self) -> &'static str;
    /// One derivation's section on its own, as `hdot derive` writes it.
    fn section(&self, s: &Section) -> String;
    /// A whole document (the notes), or `None` for a format without one.
    fn document(&self, doc: &Document) -> Option<String>;
}

/// Default title of notes without a manifest.
pub const DEFAULT_TITLE: &str = "Three-dimensional rigid-body kinetics: the derivations of hdot";

/// Default author line.
pub const DEFAULT_AUTHOR: &str = "Generated by hdot notes";

/// Default introduction.
pub const DEFAULT_INTRO: &str = "Every equation below is derived by hdot's exact engine from H = [I]ω, \
     the frames' angular velocities and the transport theorem, and checked \
     against the textbook form stated in the derivation file. Each section \
     says what is assumed, shows each step as written in the file and its \
     result in textbook form, and says whether the result equals the \
     expected form.";

/// How derivations are arranged into notes: title, author, chapters in
/// the order of a course, and which steps to show. Read from a manifest
/// (`derivations/notes.toml`, see [`crate::course`]) or
/// [`Course::plain`].
#[derive(Clone, Debug, Default)]
pub struct Course {
    /// Title.
    pub title: String,
    /// Author line.
    pub author: String,
    /// Introduction.
    pub intro: String,
    /// Chapters: title, introduction, derivation names.
    pub chapters: Vec<(String, String, Vec<String>)>,
    /// Steps to show, by derivation name (instead of the file's `show`).
    pub steps: BTreeMap<String, Vec<String>>,
}

impl Course {
    /// Notes without a manifest: the default title, every derivation in
    /// the order given, no chapters.
    pub fn plain(ds: &[Derivation]) -> Course {
        Course {
            title: DEFAULT_TITLE.into(),
            author: DEFAULT_AUTHOR.into(),
            intro: DEFAULT_INTRO.into(),
            chapters: vec![(
                String::new(),
                String::new(),
                ds.iter().map(|d| d.name.clone()).collect(),
            )],
            steps: BTreeMap::new(),
        }
    }

    /// The document of `ds` arranged by this course. Derivations the
    /// course does not name follow in a last chapter, *Further
    /// derivations* (or at the end when there are no chapters); names the
    /// course gives that are not among `ds` are skipped (a manifest is
    /// checked against the files when it is read).
    pub fn document(&self, ds: &[Derivation]) -> Document {
        let mut used = vec![false; ds.len()];
        let mut chapters: Vec<Chapter> = Vec::new();
        for (title, intro, names) in &self.chapters {
            let mut sections = Vec::new();
            for n in names {
                if let Some(k) = ds.iter().position(|d| d.name == *n) {
                    used[k] = true;
                    sections.push(Section::of(&ds[k], self.steps.get(n).map(Vec::as_slice)));
                }
            }
            chapters.push(Chapter {
                title: title.clone(),
                intro: intro.clone(),
                sections,
            });
        }
        let rest: Vec<Section> = ds
            .iter()
            .zip(&used)
            .filter(|(_, u)| !**u)
            .map(|(d, _)| Section::of(d, self.steps.get(&d.name).map(Vec::as_slice)))
            .collect();
        if !rest.is_empty() {
            match chapters.last_mut() {
                Some(c) if c.title.is_empty() => c.sections.extend(rest),
                _ => chapters.push(Chapter {
                    title: "Further derivations".into(),
                    intro: String::new(),
                    sections: rest,
                }),
            }
        }
        Document {
            title: self.title.clone(),
            author: self.author.clone(),
            intro: self.intro.clone(),
            chapters,
        }
    }
}
