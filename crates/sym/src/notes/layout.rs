//! The layout of equations in LaTeX math, shared by every LaTeX-math
//! backend (article, fragment, slides, Markdown): a rough width of printed
//! math, long equations broken on the expression tree, matrices set as
//! matrices with long entries named, the lines of a step and of a failed
//! expectation.

use crate::document::{Equation, StepBlock};
use crate::expr::Expr;
use crate::label::latex_name;
use crate::print;

// -------------------------------------------------------- line breaking --

/// A rough width of LaTeX math in characters: commands that only decorate
/// count nothing, a Greek letter or a digit counts one, scripts count less.
pub(super) fn math_width(s: &str) -> f32 {
    width_units(s) as f32 / 100.0
}

/// [`math_width`] in hundredths of a character, an integer: widths of
/// pieces add exactly, so a line's width is the sum of its pieces' (every
/// piece is balanced: no brace or script is open at its end, and the
/// pieces of a line are joined by spaces, which count nothing). One pass
/// over the bytes, no allocation.
fn width_units(s: &str) -> u32 {
    let b = s.as_bytes();
    let mut w = 0u32;
    let mut script = 0usize; // brace depth inside ^{…} / _{…}
    let mut pending_script = false;
    let scaled = |script: usize, units: u32| if script > 0 { units * 7 / 10 } else { units };
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        i += 1;
        match c {
            b'\\' => {
                let start = i;
                while i < b.len() && b[i].is_ascii_alphabetic() {
                    i += 1;
                }
                let name = &b[start..i];
                if name.is_empty() {
                    // `\,` and friends: the next character is part of it.
                    if i < b.len() {
                        i += 1;
                        while i < b.len() && b[i] & 0xC0 == 0x80 {
                            i += 1;
                        }
                    }
                    w += 30;
                    continue;
                }
                let units = match name {
                    b"left" | b"right" => 0,
                    b"dot" | b"ddot" | b"dddot" | b"ddddot" | b"mathrm" | b"frac" => 0,
                    b"sin" | b"cos" => 300,
                    _ => 100,
                };
                w += scaled(script, units);
            }
            b'^' | b'_' => pending_script = true,
            b'{' => {
                if pending_script || script > 0 {
                    script += 1;
                }
                pending_script = false;
            }
            b'}' => script = script.saturating_sub(1),
            b' ' => {}
            b'+' | b'-' | b'=' => w += 200,
            b'(' | b')' | b',' => w += scaled(script, 60),
            // The continuation bytes of a character in UTF-8: it counted
            // once, at its first byte.
            _ if c & 0xC0 == 0x80 => {}
            _ => {
                w += if pending_script {
                    70
                } else {
                    scaled(script, 100)
                };
                pending_script = false;
            }
        }
    }
    w
}

/// `rhs` printed whole when it fits in `budget` (estimated characters of
/// math). A sum of n terms prints n − 1 signs of width 2 between them, so
/// one of more terms than that allows is known not to fit without being
/// printed.
fn printed_if_fits(rhs: &Expr, budget: f32) -> Option<String> {
    let terms = match rhs.node(rhs.root()) {
        crate::expr::Node::Add(ts) if !rhs.is_empty() => ts.len(),
        _ => 1,
    };
    if 2.0 * (terms as f32 - 1.0) > budget {
        return None;
    }
    let printed = print::latex(rhs);
    (math_width(&printed) <= budget).then_some(printed)
}

/// The lines of one equation `lhs = rhs` for an `align*`/`aligned` block
/// no wider than `width` (estimated characters of math):
/// the first `lhs &= …`, continuation lines `&\quad + …`. The right side
/// is broken on its expression tree ([`print::measured_pieces`]): between its
/// top-level terms, and inside the bracket of a product term that is
/// itself too long, and inside a bracket in that bracket, to any depth;
/// each piece is printed by the printer and its width estimated on its
/// own. A break inside d brackets closes the line with d `\right.` and
/// opens the next with d `\left.`, so that every line is balanced.
pub(super) fn equation_lines(lhs: &str, rhs: &Expr, width: f32) -> Vec<String> {
    let mut text = String::new();
    let mut starts = vec![0];
    write_equation_lines(&mut text, lhs, rhs, width, "", &mut starts);
    starts.push(text.len());
    starts
        .windows(2)
        .map(|w| text[w[0]..w[1]].to_owned())
        .collect()
}

/// [`equation_lines`] appended to `o`, `sep` between two lines, each line
/// written there once, its lead first (`lhs &= `, `&\quad `): a chain-8
/// result has 10⁵ lines, which are neither strings of their own nor
/// copied. The position in `o` where each line after the first starts
/// (after its `sep`) is pushed to `starts`.
fn write_equation_lines(
    o: &mut String,
    lhs: &str,
    rhs: &Expr,
    width: f32,
    sep: &str,
    starts: &mut Vec<usize>,
) {
    let budget = (width - math_width(lhs)).max(24.0);
    o.push_str(lhs);
    o.push_str(" &= ");
    if let Some(printed) = printed_if_fits(rhs, budget) {
        o.push_str(&printed);
        return;
    }
    // Each piece is measured once; a line's width is the running sum of
    // its pieces' (see [`width_units`]), never re-measured.
    let budget_units = budget * 100.0;
    const REOPEN: &str = r"\left. ";
    // Where the line's text starts, after its lead.
    let mut text_start = o.len();
    let mut units_so_far = 0u32;
    let pieces = print::measured_pieces(rhs, &print::Latex, &width_units, &|units| {
        units as f32 / 100.0 > budget
    });
    for (piece, depth, units) in pieces.iter() {
        if o.len() > text_start && (units_so_far + units) as f32 > budget_units {
            for _ in 0..depth {
                o.push_str(r" \right.");
            }
            o.push_str(sep);
            starts.push(o.len());
            o.push_str(r"&\quad ");
            if depth > 0 {
                text_start = o.len();
                for _ in 0..depth {
                    o.push_str(REOPEN);
                }
                // `{}` keeps the sign that follows binary.
                o.push_str("{} ");
                units_so_far = width_units(&o[text_start..]);
            } else {
                if piece.starts_with("+ ") || piece.starts_with("- ") {
                    o.push_str("{} ");
                }
                text_start = o.len();
                units_so_far = 0;
            }
        }
        if o.len() > text_start && !o.ends_with(' ') {
            o.push(' ');
        }
        o.push_str(piece);
        units_so_far += units;
    }
}

// ------------------------------------------------------------- pieces --

pub(super) fn symbol_list(names: &[String]) -> String {
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
pub(super) fn equations_groups(eqs: &[Equation], width: f32) -> Vec<Vec<String>> {
    let zero_fits = |e: &Equation| printed_if_fits(&e.rhs, width - 4.0).is_some();
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

pub(super) fn equations_lines(eqs: &[Equation], width: f32) -> Vec<String> {
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
pub(super) fn matrix_groups(s: &StepBlock, width: f32) -> Option<Vec<Vec<String>>> {
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
    // Entries above the document's size are named whatever the width, and
    // defined under *Coefficients*, not after the matrix.
    let long: Vec<bool> = (0..n * m).map(|k| s.named(k)).collect();
    let mut named = long.clone();
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
            for k in (0..n * m).filter(|&k| named[k] && !long[k]) {
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
/// a matrix as a matrix ([`matrix_groups`]), else one group per equation;
/// the equations printed by name ([`StepBlock::named`]) are left out of
/// the list (see [`named_groups`] and [`write_coefficient_lines`]), so a step
/// whose equations are all named has no groups.
pub(super) fn step_groups(s: &StepBlock, width: f32) -> Vec<Vec<String>> {
    matrix_groups(s, width).unwrap_or_else(|| {
        if s.has_named() {
            let kept: Vec<Equation> = (0..s.equations.len())
                .filter(|&k| !s.named(k))
                .map(|k| s.equations[k].clone())
                .collect();
            equations_groups(&kept, width)
        } else {
            equations_groups(&s.equations, width)
        }
    })
}

/// The names of a step's equations printed by name, as LaTeX math
/// joined by commas (`M_{11}, M_{12}, f_{1}`), and the number of their
/// terms in all; `None` when the step names none.
pub(super) fn named_list(s: &StepBlock) -> Option<(String, usize)> {
    let ks: Vec<usize> = (0..s.equations.len()).filter(|&k| s.named(k)).collect();
    if ks.is_empty() {
        return None;
    }
    let names: Vec<String> = ks.iter().map(|&k| s.equations[k].lhs.latex()).collect();
    Some((
        names.join(",\\ \\allowbreak "),
        ks.iter().map(|&k| s.terms[k]).sum(),
    ))
}

/// The definitions of a section's named coefficients ([`Section::coefficients`])
/// as the lines of an `align*` block appended to `o`, separated by ` \\`,
/// each coefficient broken like any long equation. Each coefficient's
/// lines are written and dropped before the next one is broken: a large
/// section holds one coefficient's lines at a time, not every line and
/// then a joined copy of them (chain-8's definitions are 13 MB of LaTeX).
///
/// [`Section::coefficients`]: crate::document::Section::coefficients
pub(super) fn write_coefficient_lines(o: &mut String, s: &crate::document::Section, width: f32) {
    const SEP: &str = " \\\\\n";
    let mut starts = Vec::new();
    for (k, (e, _)) in s.coefficients().into_iter().enumerate() {
        if k > 0 {
            o.push_str(SEP);
        }
        starts.clear();
        write_equation_lines(o, &e.lhs.latex(), &e.rhs, width, SEP, &mut starts);
    }
}

/// `rhs = 0` broken like [`equation_lines`], set from the left edge of the
/// block: `& a + b`, `&\quad {} + c = 0`.
pub(super) fn zero_lines(rhs: &Expr, width: f32) -> Vec<String> {
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

/// The body of an `align*` (or `aligned`) block for one step.
pub(super) fn step_lines(s: &StepBlock, width: f32) -> String {
    let mut o = String::new();
    write_step_lines(&mut o, s, width);
    o
}

/// [`step_lines`] appended to `o`, each line moved there once (a large
/// result's lines are not copied again into a joined string).
pub(super) fn write_step_lines(o: &mut String, s: &StepBlock, width: f32) {
    let groups = step_groups(s, width);
    o.reserve(groups.iter().flatten().map(|l| l.len() + 4).sum());
    for (k, line) in groups.into_iter().flatten().enumerate() {
        if k > 0 {
            o.push_str(" \\\\\n");
        }
        o.push_str(&line);
    }
}

pub(super) fn failure_lines(fails: &[(Equation, Equation)], width: f32) -> String {
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
pub(super) fn omega_inline(f: &crate::document::FrameItem) -> String {
    let c: Vec<String> = f.omega.iter().map(|e| print::latex(&e.rhs)).collect();
    format!("({})", c.join(",\\ \\allowbreak "))
}
