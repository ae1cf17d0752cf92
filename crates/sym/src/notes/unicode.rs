//! The Unicode backend: one derivation's section as text for a terminal
//! (`hdot derive`), showing what the LaTeX and Markdown show, in the same
//! order.

use std::fmt::Write;

use crate::document::{Backend, Document, Equation, Section, StepBlock, VANISHES, Verdict};
use crate::print::{self, unicode_symbol};
use crate::prose;

/// The Unicode backend (a section only: the notes are LaTeX and Markdown).
pub struct Unicode;

impl Backend for Unicode {
    fn name(&self) -> &'static str {
        "unicode"
    }

    fn section(&self, s: &Section) -> String {
        unicode_section(s)
    }

    fn document(&self, _: &Document) -> Option<String> {
        None
    }
}

/// One derivation's section as Unicode text for a terminal (`hdot
/// derive`): the backend of [`Section`] that the other backends render as
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
        } else if let Some(grid) = matrix_grid(st) {
            o.push_str(&grid);
        } else {
            for e in &st.equations {
                let _ = writeln!(o, "   {}", equation_unicode(e));
            }
        }
        if !st.condition.is_empty() {
            let _ = writeln!(o, "   (for {})", prose::unicode(&st.condition));
        }
        match &st.verdict {
            Verdict::NoExpectation => {}
            Verdict::Holds => {
                let _ = writeln!(o, "   ✓ {}", Verdict::HOLDS);
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
    // Text for a terminal: what the file holds is shown, never obeyed.
    crate::escape::terminal(&o)
}

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

/// The widest matrix printed as a grid, in columns of the terminal: wider
/// (or with an entry that is not one line), its entries are printed one
/// per line, `M_11 = …`.
pub const GRID_WIDTH: usize = 100;

/// A matrix result (`mass_matrix`, `jacobian`, an inertia tensor) as a
/// grid in brackets, its name on the middle row, the columns aligned:
///
/// ```text
///        ⎡ I cos² θ + I′ sin² θ  0   I cos θ ⎤
///    M = ⎢ 0                     I′  0       ⎥
///        ⎣ I cos θ               0   I       ⎦
/// ```
///
/// `None` for a result that is not a matrix of at least two entries, is
/// labelled 0, or is wider than [`GRID_WIDTH`].
fn matrix_grid(st: &StepBlock) -> Option<String> {
    let (rows, cols) = st.shape?;
    if rows * cols < 2 || st.equations.len() != rows * cols || st.heading.is_zero() {
        return None;
    }
    let cells: Vec<String> = st
        .equations
        .iter()
        .map(|e| print::unicode(&e.rhs))
        .collect();
    if cells.iter().any(|c| c.contains('\n')) {
        return None;
    }
    let widths: Vec<usize> = (0..cols)
        .map(|j| {
            (0..rows)
                .map(|i| width(&cells[i * cols + j]))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let name = format!("{} = ", st.heading.unicode());
    let pad = width(&name);
    if 3 + pad + widths.iter().sum::<usize>() + 2 * cols + 2 > GRID_WIDTH {
        return None;
    }
    let mut o = String::new();
    for i in 0..rows {
        let (l, r) = match (rows, i) {
            (1, _) => ('[', ']'),
            (_, 0) => ('⎡', '⎤'),
            (n, i) if i + 1 == n => ('⎣', '⎦'),
            _ => ('⎢', '⎥'),
        };
        let lead = if i == (rows - 1) / 2 {
            name.clone()
        } else {
            " ".repeat(pad)
        };
        let row: Vec<String> = (0..cols)
            .map(|j| {
                let c = &cells[i * cols + j];
                format!("{c}{}", " ".repeat(widths[j] - width(c)))
            })
            .collect();
        let _ = writeln!(o, "   {lead}{l} {} {r}", row.join("  "));
    }
    Some(o)
}

/// Columns `s` takes in a terminal: its characters less the combining
/// marks (the dot of θ̇ sits on its letter).
fn width(s: &str) -> usize {
    s.chars()
        .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
        .count()
}
