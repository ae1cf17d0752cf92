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
pub(crate) fn label_word(w: &str) -> (&str, u32) {
    let base = w.trim_end_matches('\'');
    (base, (w.len() - base.len()) as u32)
}

/// Whether a word is shaped like a symbol name the printers write as a
/// symbol: ASCII letters and digits, `_` between them, and brackets
/// (`I_x(P)`).
pub(crate) fn name_shaped(w: &str) -> bool {
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

/// A label with component in Unicode: `ΣM_x`; words after an operator
/// letter (Σ, Δ) are joined to it, other words keep their space (`m a_G`,
/// never `ma_G`).
///
/// # Example
/// ```
/// use hdot_sym::label::unicode_label;
/// assert_eq!(unicode_label("Sigma M", "x"), "ΣM_x");
/// assert_eq!(unicode_label("m a_G", ""), "m a_G");
/// ```
pub fn unicode_label(label: &str, component: &str) -> String {
    let mut body = String::new();
    for w in label.split_whitespace() {
        let (b, k) = label_word(w);
        if !body.is_empty() && !body.ends_with(['Σ', 'Δ']) {
            body.push(' ');
        }
        body.push_str(&print::unicode_symbol(b, k));
    }
    let subscripted = label
        .split_whitespace()
        .last()
        .is_some_and(|w| w.contains('_'));
    match ((body, subscripted), component.is_empty()) {
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
    /// A formula of names the printers cannot evaluate — symbols and
    /// steps with a number before them, `|…|` and powers (`|H_G|^2`,
    /// `H^2`, `2T`) — printed piece by piece.
    Formula(Vec<Piece>),
    /// The equation is `result = 0`.
    Zero,
}

/// A piece of a label formula ([`LabelMath::Formula`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Piece {
    /// A number (digits).
    Number(String),
    /// A symbol or step name with its time derivatives.
    Name(String, u32),
    /// `|…|`.
    Abs(Vec<Piece>),
    /// A piece to a power.
    Pow(Box<Piece>, u32),
}

/// Reads a label formula: numbers, names (`known`: declared symbols and
/// steps), `|…|` and `^k` after a name or a bar, pieces side by side.
fn formula(t: &str, known: &dyn Fn(&str) -> bool) -> Result<Vec<Piece>, String> {
    fn items(
        cs: &mut std::iter::Peekable<std::str::Chars<'_>>,
        known: &dyn Fn(&str) -> bool,
        inside: bool,
    ) -> Result<Vec<Piece>, String> {
        let mut out = Vec::new();
        while let Some(&c) = cs.peek() {
            let piece = if c.is_whitespace() {
                cs.next();
                continue;
            } else if c == '|' {
                if inside {
                    break;
                }
                cs.next();
                let inner = items(cs, known, true)?;
                if cs.next() != Some('|') || inner.is_empty() {
                    return Err("a `|` without its closing `|`".into());
                }
                Piece::Abs(inner)
            } else if c.is_ascii_digit() {
                let mut n = String::new();
                while let Some(&d) = cs.peek().filter(|d| d.is_ascii_digit()) {
                    n.push(d);
                    cs.next();
                }
                Piece::Number(n)
            } else if c.is_alphabetic() {
                let mut w = String::new();
                while let Some(&d) = cs.peek().filter(|d| d.is_alphanumeric() || **d == '_') {
                    w.push(d);
                    cs.next();
                }
                let mut primes = 0;
                while cs.peek() == Some(&'\'') {
                    primes += 1;
                    cs.next();
                }
                if !known(&w) {
                    return Err(format!(
                        "`{w}` is neither a declared symbol nor a step before this one"
                    ));
                }
                Piece::Name(w, primes)
            } else {
                return Err(format!("`{c}` cannot be written in a label formula"));
            };
            let piece = if cs.peek() == Some(&'^') {
                cs.next();
                let mut n = String::new();
                while let Some(&d) = cs.peek().filter(|d| d.is_ascii_digit()) {
                    n.push(d);
                    cs.next();
                }
                let k = n
                    .parse::<u32>()
                    .ok()
                    .filter(|k| (1..=99).contains(k))
                    .ok_or("a power in a label is a whole number from 1 to 99")?;
                if matches!(piece, Piece::Number(_)) {
                    return Err("a number to a power cannot be a label".into());
                }
                Piece::Pow(Box::new(piece), k)
            } else {
                piece
            };
            out.push(piece);
        }
        Ok(out)
    }
    let mut cs = t.chars().peekable();
    let out = items(&mut cs, known, false)?;
    if cs.next().is_some() {
        return Err("a `|` without its opening `|`".into());
    }
    Ok(out)
}

fn latex_pieces(ps: &[Piece]) -> String {
    let one = |p: &Piece| match p {
        Piece::Number(n) => n.clone(),
        Piece::Name(w, k) => latex_name(w, *k),
        Piece::Abs(inner) => format!(r"\left|{}\right|", latex_pieces(inner)),
        Piece::Pow(b, k) => match &**b {
            Piece::Name(w, o) if *o == 0 && !w.contains('_') => {
                format!("{}^{{{k}}}", latex_name(w, 0))
            }
            b => format!("{{{}}}^{{{k}}}", latex_pieces(std::slice::from_ref(b))),
        },
    };
    ps.iter().map(one).collect::<Vec<_>>().join(r"\,")
}

fn unicode_pieces(ps: &[Piece]) -> String {
    let mut o = String::new();
    for (k, p) in ps.iter().enumerate() {
        // A number is set against the name after it (2T); names apart.
        if k > 0 && !matches!(ps[k - 1], Piece::Number(_)) {
            o.push(' ');
        }
        match p {
            Piece::Number(n) => o.push_str(n),
            Piece::Name(w, d) => o.push_str(&print::unicode_symbol(w, *d)),
            Piece::Abs(inner) => o.push_str(&format!("|{}|", unicode_pieces(inner))),
            Piece::Pow(b, e) => {
                o.push_str(&unicode_pieces(std::slice::from_ref(b)));
                o.push_str(&print::superscript(*e));
            }
        }
    }
    o
}

impl LabelMath {
    /// Reads a label: `None` for a plain name (`Sigma M`, `I_x(P)`); a
    /// label with `*`, `/` or `^`, or one written `partial(f, q)`, must be
    /// an expression of the declared symbols, and one with `|` or `^`, or
    /// a number before a name, may be a formula of declared symbols and
    /// steps (`known`) with `|…|` and powers (the error says why not).
    pub fn parse(
        label: &str,
        symbols: &Symbols,
        known: &dyn Fn(&str) -> bool,
    ) -> Result<Option<LabelMath>, String> {
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
        let numbered =
            t.starts_with(|c: char| c.is_ascii_digit()) && t.contains(|c: char| c.is_alphabetic());
        if !t.contains(['*', '/', '^', '|']) && !numbered {
            return Ok(None);
        }
        let expr = if t.contains('|') {
            None
        } else {
            Some(symbols.expr(t))
        };
        match expr {
            Some(Ok(e)) => Ok(Some(LabelMath::Expr(e))),
            Some(Err(e)) if t.contains(['*', '/']) => Err(format!(
                "`{t}` is not an expression of the declared symbols: {}",
                e.message
            )),
            _ => formula(t, &|w| symbols.get(w).is_some() || known(w))
                .map(|ps| Some(LabelMath::Formula(ps)))
                .map_err(|m| {
                    format!(
                        "`{t}` is neither an expression of the declared symbols nor a formula of \
                         symbols and steps with |…| and powers: {m}"
                    )
                }),
        }
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
            LabelMath::Formula(ps) => latex_pieces(ps),
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
            LabelMath::Formula(ps) => unicode_pieces(ps),
            LabelMath::Zero => "0".to_owned(),
        }
    }

    /// Whether the body needs parentheses before a component subscript.
    pub fn compound(&self) -> bool {
        match self {
            LabelMath::Expr(e) => !matches!(e.node(e.root()), Node::Atom(_)),
            LabelMath::Partial(..) => true,
            LabelMath::Formula(ps) => ps.len() > 1 || matches!(ps[..], [Piece::Pow(..)]),
            LabelMath::Zero => false,
        }
    }
}
