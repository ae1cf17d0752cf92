//! Step labels: how the left side of a step's equations is written. A
//! label is a name (`Sigma M`, `I_x(P)`: words printed as symbols) or
//! mathematics ([`LabelMath`]: an expression of the declared symbols, a
//! partial derivative, or `0`). The derivation engine reads a label when
//! it loads a file ([`LabelMath::parse`]); the document prints it. Neither
//! imports the other through this module: it knows symbols and
//! expressions only.
//!
//! A label word that is not shaped like a symbol name (letters, digits,
//! `_` between them, brackets) is set as upright text in math with every
//! character escaped ([`crate::escape::latex_math`]): no string of a file
//! reaches LaTeX as commands.

use crate::atom::Atom;
use crate::escape;
use crate::expr::{Expr, Node};
use crate::print;
use crate::symbols::Symbols;

/// A label word with trailing primes: `epsilon_2''` → (`epsilon_2`, 2).
fn label_word(w: &str) -> (&str, u32) {
    let base = w.trim_end_matches('\'');
    (base, (w.len() - base.len()) as u32)
}

/// Whether a word is shaped like a symbol name the printers write as a
/// symbol: ASCII letters and digits, `_` between them, and brackets
/// (`I_x(P)`).
fn name_shaped(w: &str) -> bool {
    let ok = w
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '(' | ')'));
    ok && !w.is_empty() && !w.starts_with('_') && !w.ends_with('_') && !w.contains("__")
}

/// A name (a label word, a frame, an axis) in LaTeX math: a symbol when it
/// is shaped like one (`omega_x` → `\omega_x`), else upright text with
/// every character escaped.
pub fn latex_name(name: &str, order: u32) -> String {
    if name_shaped(name) {
        return print::latex_symbol(name, order);
    }
    let body = format!(r"\mathrm{{{}}}", escape::latex_math(name));
    match order {
        0 => body,
        1 => format!(r"\dot{{{body}}}"),
        2 => format!(r"\ddot{{{body}}}"),
        3 => format!(r"\dddot{{{body}}}"),
        4 => format!(r"\ddddot{{{body}}}"),
        n => format!("{{{body}}}^{{({n})}}"),
    }
}

/// The body of a label (its words written by `symbol`, joined by `sep`)
/// and whether it already carries a subscript, so that a component must be
/// attached around parentheses.
fn label_body(label: &str, symbol: fn(&str, u32) -> String, sep: &str) -> (String, bool) {
    let words: Vec<String> = label
        .split_whitespace()
        .map(|w| {
            let (b, k) = label_word(w);
            symbol(b, k)
        })
        .collect();
    let subscripted = label
        .split_whitespace()
        .last()
        .is_some_and(|w| w.contains('_'));
    (words.join(sep), subscripted)
}

/// A label such as `Sigma M` with component `x`, in LaTeX: `\Sigma M_{x}`.
///
/// # Example
/// ```
/// use hdot_sym::label::latex_label;
/// assert_eq!(latex_label("Sigma M", "x"), r"\Sigma M_{x}");
/// assert_eq!(latex_label(r"\input x", ""), r"\mathrm{\backslash input} x");
/// ```
pub fn latex_label(label: &str, component: &str) -> String {
    let (body, sub) = label_body(label, latex_name, " ");
    let component = escape::latex_math(component);
    match ((body, sub), component.is_empty()) {
        ((body, _), true) => body,
        ((body, false), false) => format!("{body}_{{{component}}}"),
        ((body, true), false) => format!(r"\left({body}\right)_{{{component}}}"),
    }
}

/// A label with component in Unicode: `ΣM_x`.
pub fn unicode_label(label: &str, component: &str) -> String {
    match (
        label_body(label, print::unicode_symbol, ""),
        component.is_empty(),
    ) {
        ((body, _), true) => body,
        ((body, false), false) => format!("{body}_{component}"),
        ((body, true), false) => format!("({body})_{component}"),
    }
}

/// A step label written as mathematics rather than a name: an expression
/// of the file's symbols (`phi''*sin(theta)` prints φ̈ sin θ), a partial
/// derivative (`partial(T, theta')` prints ∂T/∂θ̇), or `0`, which prints
/// the equation as `… = 0`.
#[derive(Clone, Debug)]
pub enum LabelMath {
    /// An expression as written.
    Expr(Expr),
    /// ∂f/∂q: the name of f (a label word) and q.
    Partial(String, Atom),
    /// The equation is `result = 0`.
    Zero,
}

impl LabelMath {
    /// Reads a label: `None` for a plain name (`Sigma M`, `I_x(P)`); a
    /// label with `*`, `/` or `^`, or one written `partial(f, q)`, must be
    /// an expression of the declared symbols (the error says why not).
    pub fn parse(label: &str, symbols: &Symbols) -> Result<Option<LabelMath>, String> {
        let t = label.trim();
        if t == "0" {
            return Ok(Some(LabelMath::Zero));
        }
        if let Some(args) = t.strip_prefix("partial(").and_then(|a| a.strip_suffix(')')) {
            let Some((f, q)) = args.split_once(',') else {
                return Err(format!(
                    "`{t}`: write a partial derivative as partial(T, theta')"
                ));
            };
            let q = q.trim();
            let base = q.trim_end_matches('\'');
            let primes = (q.len() - base.len()) as u32;
            let atom = symbols
                .atom(base, primes, crate::parse::Span::default())
                .map_err(|e| format!("`{t}`: {}", e.message))?;
            return Ok(Some(LabelMath::Partial(f.trim().to_owned(), atom)));
        }
        if !t.contains(['*', '/', '^']) {
            return Ok(None);
        }
        symbols
            .expr(t)
            .map(|e| Some(LabelMath::Expr(e)))
            .map_err(|e| {
                format!(
                    "`{t}` is not an expression of the declared symbols: {}",
                    e.message
                )
            })
    }

    /// LaTeX.
    pub fn latex(&self) -> String {
        match self {
            LabelMath::Expr(e) => print::latex(e),
            LabelMath::Partial(f, q) => format!(
                r"\frac{{\partial {}}}{{\partial {}}}",
                latex_label(f, ""),
                print::Style::atom(&print::Latex, *q)
            ),
            LabelMath::Zero => "0".to_owned(),
        }
    }

    /// Unicode.
    pub fn unicode(&self) -> String {
        match self {
            LabelMath::Expr(e) => print::unicode(e),
            LabelMath::Partial(f, q) => format!(
                "∂{}/∂{}",
                unicode_label(f, ""),
                print::Style::atom(&print::Unicode, *q)
            ),
            LabelMath::Zero => "0".to_owned(),
        }
    }

    /// Whether the body needs parentheses before a component subscript.
    pub fn compound(&self) -> bool {
        match self {
            LabelMath::Expr(e) => !matches!(e.node(e.root()), Node::Atom(_)),
            LabelMath::Partial(..) => true,
            LabelMath::Zero => false,
        }
    }
}
