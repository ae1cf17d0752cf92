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
    let mut w = 0.0;
    let mut script = 0usize; // brace depth inside ^{…} / _{…}
    let mut depth = 0usize;
    let mut chars = s.chars().peekable();
    let mut pending_script = false;
    let scale = |script: usize| if script > 0 { 0.7 } else { 1.0 };
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                // The command's name, without allocating (the names that
                // matter are short; a longer one counts as any other).
                let (mut name, mut len) = ([0u8; 8], 0);
                while let Some(&n) = chars.peek().filter(|n| n.is_ascii_alphabetic()) {
                    name[len.min(7)] = n as u8;
                    len += 1;
                    chars.next();
                }
                let name = if len <= 7 {
                    std::str::from_utf8(&name[..len]).unwrap_or("")
                } else {
                    "long"
                };
                if name.is_empty() {
                    chars.next(); // `\,` and friends
                    w += 0.3;
                    continue;
                }
                w += scale(script)
                    * match name {
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

/// The lines of one equation `lhs = rhs` for an `align*`/`aligned` block
/// no wider than `width` (estimated characters of math):
/// the first `lhs &= …`, continuation lines `&\quad + …`. The right side
/// is broken on its expression tree ([`print::break_pieces`]): between its
/// top-level terms, and inside the bracket of a product term that is
/// itself too long; each piece is printed by the printer and its width
/// estimated on its own. A break inside the bracket closes the line with
/// `\right.` and opens the next with `\left.`, so that every line is
/// balanced.
pub(super) fn equation_lines(lhs: &str, rhs: &Expr, width: f32) -> Vec<String> {
    let budget = (width - math_width(lhs)).max(24.0);
    let printed = print::latex(rhs);
    if math_width(&printed) <= budget {
        return vec![format!("{lhs} &= {printed}")];
    }
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for (piece, inside) in print::break_pieces(rhs, &print::Latex, &|t| math_width(t) > budget) {
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
    let zero_fits = |e: &Equation| math_width(&print::latex(&e.rhs)) + 4.0 <= width;
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
    let mut named = vec![false; n * m];
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
            for k in (0..n * m).filter(|&k| named[k]) {
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
/// a matrix as a matrix ([`matrix_groups`]), else one group per equation.
pub(super) fn step_groups(s: &StepBlock, width: f32) -> Vec<Vec<String>> {
    matrix_groups(s, width).unwrap_or_else(|| equations_groups(&s.equations, width))
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
    step_groups(s, width).concat().join(" \\\\\n")
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
