//! Equations as MathML (for the web pages of the notes), generated from
//! the expression tree by the printer's own walk ([`print::print`] with
//! the [`MathMl`] style): the same parentheses, fractions and line
//! breaks as the LaTeX, with no LaTeX in between. Names follow the LaTeX
//! printer's conventions (Greek by name, dots for time derivatives, `_`
//! subscripts, `Ip` as I′, `xbar` as x̄); a label word that is not shaped
//! like a symbol is upright text, escaped.

use crate::atom::{Atom, AtomKind};
use crate::document::{Equation, LabelMath, Lhs};
use crate::escape;
use crate::expr::{Expr, Node};
use crate::label::{label_word, name_shaped};
use crate::print::{self, Style, primed_base, split_name};
use crate::rational::Rational;

/// Invisible times between the factors of a product.
const TIMES: &str = "<mo>&#x2062;</mo>";

/// Function application between sin/cos and their argument,
/// and the thin space TeX puts there.
const APPLY: &str = "<mo>&#x2061;</mo><mspace width=\"0.1667em\"/>";

/// The MathML style of the printer: every piece is one element (or, for a
/// bracket, an operator), so the walk's concatenation is valid MathML.
pub struct MathMl;

impl Style for MathMl {
    fn atom(&self, a: Atom) -> String {
        match a.kind() {
            AtomKind::Var { name, order, .. } => symbol(name, order),
            AtomKind::Sin(q) => format!("<mrow><mi>sin</mi>{APPLY}{}</mrow>", self.atom(q)),
            AtomKind::Cos(q) => format!("<mrow><mi>cos</mi>{APPLY}{}</mrow>", self.atom(q)),
            AtomKind::Sum { sum, .. } => format!("<mrow>{}</mrow>", print::sum_atom(self, sum)),
        }
    }
    fn num(&self, r: &Rational) -> String {
        if r.is_integer() {
            format!("<mn>{r}</mn>")
        } else {
            let (n, d) = r.parts();
            format!("<mfrac><mn>{n}</mn><mn>{d}</mn></mfrac>")
        }
    }
    fn mul_sep(&self, left: &Node, right: &Node) -> &'static str {
        // A thin space after sin/cos, as in the LaTeX (`\sin\theta \, \dot\phi`),
        // and before it, where TeX spaces an operator name.
        let trig = |n: &Node| matches!(n, Node::Atom(a) if matches!(a.kind(), AtomKind::Sin(_) | AtomKind::Cos(_)));
        if trig(left) || trig(right) {
            "<mspace width=\"0.1667em\"/><mo>&#x2062;</mo>"
        } else {
            TIMES
        }
    }
    fn pow(&self, base: &str, node: &Node, exp: u32) -> String {
        if let Node::Atom(a) = node
            && let AtomKind::Sin(q) | AtomKind::Cos(q) = a.kind()
        {
            let f = if matches!(a.kind(), AtomKind::Sin(_)) {
                "sin"
            } else {
                "cos"
            };
            return format!(
                "<mrow><msup><mi>{f}</mi><mn>{exp}</mn></msup>{APPLY}{}</mrow>",
                self.atom(q)
            );
        }
        format!("<msup><mrow>{base}</mrow><mn>{exp}</mn></msup>")
    }
    fn fraction(&self, num: &str, dens: &[String]) -> String {
        format!(
            "<mfrac><mrow>{num}</mrow><mrow>{}</mrow></mfrac>",
            dens.join(TIMES)
        )
    }
    fn minus(&self) -> &'static str {
        "<mo>−</mo>"
    }
    fn plus(&self) -> &'static str {
        "<mo>+</mo>"
    }
    fn digits(&self, digits: &str) -> String {
        format!("<mn>{digits}</mn>")
    }
    fn parens(&self) -> (&'static str, &'static str) {
        ("<mo>(</mo>", "<mo>)</mo>")
    }
    fn paren_fraction_factor(&self) -> bool {
        false
    }
    fn textbook_fraction(&self) -> bool {
        true
    }
}

/// An expression as MathML (the content of an `<mrow>`).
pub(super) fn expr(e: &Expr) -> String {
    print::print(e, &MathMl)
}

/// The base of a symbol name (no derivative marks): a Greek letter by
/// name, `xbar` as x̄, `Ip` as I′, a longer name upright.
fn base(b: &str) -> String {
    if let Some(inner) = b.strip_suffix("bar").filter(|i| !i.is_empty()) {
        return format!("<mover accent=\"true\">{}<mo>¯</mo></mover>", base(inner));
    }
    if let Some((_, c)) = crate::symbols::greek(b) {
        // Capital Greek is upright, as in TeX.
        return if c.is_uppercase() {
            format!("<mi mathvariant=\"normal\">{c}</mi>")
        } else {
            format!("<mi>{c}</mi>")
        };
    }
    if let Some(c) = primed_base(b) {
        return format!("<mrow><mi>{c}</mi><mo>′</mo></mrow>");
    }
    if b.chars().count() == 1 {
        format!("<mi>{}</mi>", escape::html(b))
    } else {
        format!("<mi mathvariant=\"normal\">{}</mi>", escape::html(b))
    }
}

/// A subscript: its parts (Greek by name) separated by commas, each
/// character of a part italic as in TeX's `_{xy}`.
fn subscript(sub: &str) -> String {
    let parts: Vec<String> = sub
        .split('_')
        .map(|p| match crate::symbols::greek(p) {
            Some((_, c)) => format!("<mi>{c}</mi>"),
            None => p
                .chars()
                .map(|c| {
                    let c = escape::html(&c.to_string());
                    if c.chars().all(|d| d.is_ascii_digit()) {
                        format!("<mn>{c}</mn>")
                    } else {
                        format!("<mi>{c}</mi>")
                    }
                })
                .collect(),
        })
        .collect();
    format!("<mrow>{}</mrow>", parts.join("<mo>,</mo>"))
}

/// `body` with `order` time derivatives: dots over it, or `(n)` above
/// from the fifth on.
fn dotted(body: String, order: u32) -> String {
    let dots = match order {
        0 => return body,
        1 => "˙",
        2 => "¨",
        3 => "⃛",
        4 => "⃜",
        n => {
            return format!(
                "<msup><mrow>{body}</mrow><mrow><mo>(</mo><mn>{n}</mn><mo>)</mo></mrow></msup>"
            );
        }
    };
    // Set as an over-script, not an accent: Chromium places an accent dot
    // at the glyph's top-accent point, which on Latin Modern's φ touches
    // the stroke at text size, so φ̇ read as φ; the script's gap keeps the
    // dot clear of every letter.
    format!("<mover accent=\"false\"><mrow>{body}</mrow><mo>{dots}</mo></mover>")
}

/// A symbol name with `order` time derivatives: ω̇_x.
pub(super) fn symbol(name: &str, order: u32) -> String {
    let (b, sub) = split_name(name);
    let body = dotted(base(b), order);
    match sub {
        Some(s) => format!("<msub>{body}{}</msub>", subscript(s)),
        None => body,
    }
}

/// A name (a label word, a frame, an axis): a symbol when it is shaped
/// like one, else upright text with every character escaped.
pub(super) fn name(name: &str, order: u32) -> String {
    if name_shaped(name) {
        symbol(name, order)
    } else {
        dotted(format!("<mtext>{}</mtext>", escape::html(name)), order)
    }
}

/// A label (`Sigma M`) with a component (`x`, or empty): ΣM_x, or
/// (I_x(P))_y when the label already carries a subscript.
pub(super) fn label(label: &str, component: &str) -> String {
    let words: Vec<String> = label
        .split_whitespace()
        .map(|w| {
            let (b, k) = label_word(w);
            name(b, k)
        })
        .collect();
    let subscripted = label
        .split_whitespace()
        .last()
        .is_some_and(|w| w.contains('_'));
    let body = words.concat();
    if component.is_empty() {
        format!("<mrow>{body}</mrow>")
    } else if subscripted {
        format!(
            "<msub><mrow><mo>(</mo>{body}<mo>)</mo></mrow>{}</msub>",
            component_ml(component)
        )
    } else {
        format!(
            "<msub><mrow>{body}</mrow>{}</msub>",
            component_ml(component)
        )
    }
}

fn component_ml(c: &str) -> String {
    if name_shaped(c) {
        subscript(c)
    } else {
        format!("<mtext>{}</mtext>", escape::html(c))
    }
}

/// The left side of an equation.
pub(super) fn lhs(l: &Lhs) -> String {
    match l {
        Lhs::Label(l, c) => label(l, c),
        Lhs::Expr(e) => format!("<mrow>{}</mrow>", expr(e)),
        Lhs::Math(m, c) => {
            let body = match m {
                LabelMath::Expr(e) => expr(e),
                LabelMath::Partial(f, q) => format!(
                    "<mfrac><mrow><mo>∂</mo>{}</mrow><mrow><mo>∂</mo>{}</mrow></mfrac>",
                    label(f, ""),
                    MathMl.atom(*q)
                ),
                LabelMath::Formula(ps) => formula(ps),
                LabelMath::Zero => "<mn>0</mn>".to_owned(),
            };
            if c.is_empty() {
                format!("<mrow>{body}</mrow>")
            } else if m.compound() {
                format!(
                    "<msub><mrow><mo>(</mo>{body}<mo>)</mo></mrow>{}</msub>",
                    component_ml(c)
                )
            } else {
                format!("<msub><mrow>{body}</mrow>{}</msub>", component_ml(c))
            }
        }
    }
}

/// A label formula (`|H_G|^2`, `2T`) piece by piece.
fn formula(ps: &[crate::label::Piece]) -> String {
    use crate::label::Piece;
    let one = |p: &Piece| match p {
        Piece::Number(n) => format!("<mn>{}</mn>", escape::html(n)),
        Piece::Name(w, k) => name(w, *k),
        Piece::Abs(inner) => format!("<mrow><mo>|</mo>{}<mo>|</mo></mrow>", formula(inner)),
        Piece::Pow(b, k) => format!(
            "<msup><mrow>{}</mrow><mn>{k}</mn></msup>",
            formula(std::slice::from_ref(&**b))
        ),
    };
    ps.iter().map(one).collect::<Vec<_>>().join(TIMES)
}

// -------------------------------------------------------- line breaking --

/// A rough width of MathML in characters: the text of its elements, with
/// invisible operators counting nothing and `+ − =` counting their
/// spacing.
pub(super) fn width(s: &str) -> f32 {
    let mut w = 0.0;
    let mut in_tag = false;
    let mut entity = false;
    for c in s.chars() {
        match c {
            '<' => in_tag = true,
            '>' => in_tag = false,
            _ if in_tag => {}
            '&' => entity = true,
            ';' if entity => entity = false,
            _ if entity => {}
            '+' | '−' | '=' => w += 2.0,
            '(' | ')' | ',' => w += 0.6,
            _ => w += 1.0,
        }
    }
    w
}

/// One line of a block: the left cell (the left side, or empty on a
/// continuation line) and the right cell.
pub(super) type Row = (String, String);

/// The rows of one equation `lhs = rhs` no wider than `width` (estimated
/// characters): broken on the expression tree between terms and inside a
/// long bracket ([`print::break_pieces`]), continuation lines indented.
pub(super) fn equation_rows(lhs: &str, rhs: &Expr, budget: f32) -> Vec<Row> {
    let budget = (budget - width(lhs)).max(24.0);
    let lines = broken(rhs, budget);
    lines
        .into_iter()
        .enumerate()
        .map(|(k, l)| {
            if k == 0 {
                (lhs.to_owned(), format!("<mo>=</mo><mrow>{l}</mrow>"))
            } else {
                (String::new(), format!("<mspace width=\"2em\"/>{l}"))
            }
        })
        .collect()
}

/// `rhs` broken into lines of at most `budget` estimated characters.
fn broken(rhs: &Expr, budget: f32) -> Vec<String> {
    let printed = expr(rhs);
    if width(&printed) <= budget {
        return vec![printed];
    }
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for (piece, _) in print::break_pieces(rhs, &MathMl, &|t| width(t) > budget) {
        if !current.is_empty() && width(&current) + width(&piece) > budget {
            lines.push(std::mem::take(&mut current));
        }
        current.push_str(&piece);
    }
    lines.push(current);
    lines
}

/// The rows of an equation: `lhs = rhs`, or `rhs = 0` for a left side
/// `0` (set from the left edge when it must be broken).
pub(super) fn rows(e: &Equation, budget: f32) -> Vec<Row> {
    if !e.lhs.is_zero() {
        return equation_rows(&lhs(&e.lhs), &e.rhs, budget);
    }
    let mut lines = broken(&e.rhs, budget - 4.0);
    if lines.len() == 1 {
        return vec![(
            format!("<mrow>{}</mrow>", lines.remove(0)),
            "<mo>=</mo><mn>0</mn>".to_owned(),
        )];
    }
    let last = lines.len() - 1;
    lines
        .into_iter()
        .enumerate()
        .map(|(k, l)| {
            let indent = if k == 0 {
                ""
            } else {
                "<mspace width=\"2em\"/>"
            };
            let end = if k == last {
                "<mo>=</mo><mn>0</mn>"
            } else {
                ""
            };
            (String::new(), format!("{indent}{l}{end}"))
        })
        .collect()
}

/// Rows as an aligned table: left cells to the right, right cells to the
/// left, as LaTeX's `aligned`.
pub(super) fn table(rows: &[Row]) -> String {
    let mut o = String::from("<mtable columnalign=\"right left\" class=\"aligned\">");
    for (l, r) in rows {
        o.push_str("<mtr><mtd>");
        o.push_str(l);
        o.push_str("</mtd><mtd>");
        o.push_str(r);
        o.push_str("</mtd></mtr>");
    }
    o.push_str("</mtable>");
    o
}

/// A matrix of entries (row by row) in square brackets.
pub(super) fn matrix(entries: &[String], columns: usize) -> String {
    let mut o = String::from("<mrow><mo>[</mo><mtable class=\"matrix\">");
    for row in entries.chunks(columns) {
        o.push_str("<mtr>");
        for e in row {
            o.push_str("<mtd>");
            o.push_str(e);
            o.push_str("</mtd>");
        }
        o.push_str("</mtr>");
    }
    o.push_str("</mtable><mo>]</mo></mrow>");
    o
}

/// A `<math>` element holding `body`, its LaTeX as `alttext`; an inline
/// one in a box of its own that scrolls when it is wider than the line
/// (a formula cannot wrap).
pub(super) fn math(body: &str, latex: &str, display: bool) -> String {
    let alt = escape::html(latex);
    if display {
        format!("<math display=\"block\" alttext=\"{alt}\">{body}</math>")
    } else {
        format!("<span class=\"math\"><math alttext=\"{alt}\">{body}</math></span>")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::symbols::Symbols;

    #[test]
    fn expressions_are_mathml_elements() {
        let s = Symbols::parse_decl(&["I_x", "m", "g", "l", "Ip"], &["omega_x", "theta", "phi"]);
        let e = s
            .expr("I_x*omega_x' - sin(theta)*phi'' + 7/2*m*g*l/Ip + sin(theta)^2")
            .unwrap();
        let m = expr(&e);
        assert!(m.contains("<msub><mover accent=\"false\"><mrow><mi>ω</mi></mrow><mo>˙</mo></mover><mrow><mi>x</mi></mrow></msub>"), "{m}");
        assert!(m.contains(&format!("<mi>sin</mi>{APPLY}<mi>θ</mi>")), "{m}");
        assert!(m.contains("<mfrac><mrow><mn>7</mn>"), "{m}");
        assert!(m.contains("<mi>I</mi><mo>′</mo>"), "{m}");
        assert!(m.contains("<msup><mi>sin</mi><mn>2</mn></msup>"), "{m}");
        // No text outside a token element: every character between tags
        // is inside <mi>, <mn>, <mo> or <mtext>.
        let mut depth_token = 0;
        for piece in m.split('<').skip(1) {
            let (tag, text) = piece.split_once('>').unwrap();
            let name = tag.trim_start_matches('/').split(' ').next().unwrap();
            let token = matches!(name, "mi" | "mn" | "mo" | "mtext");
            if token && !tag.starts_with('/') {
                depth_token += 1;
            } else if token {
                depth_token -= 1;
            }
            assert!(
                depth_token > 0 || text.trim().is_empty(),
                "text {text:?} outside a token in {m}"
            );
        }
        // The same tree in LaTeX and MathML breaks into as many pieces.
        let ml = print::break_pieces(&e, &MathMl, &|_| true);
        let latex = print::break_pieces(&e, &print::Latex, &|_| true);
        assert_eq!(ml.len(), 4, "{ml:?}");
        assert_eq!(ml.len(), latex.len());
    }

    #[test]
    fn hostile_label_words_are_text() {
        let l = label("<script>alert(1)</script> M", "x");
        assert!(!l.contains("<script>"), "{l}");
        assert!(
            l.contains("<mtext>&lt;script&gt;alert(1)&lt;/script&gt;</mtext>"),
            "{l}"
        );
        assert!(l.contains("<mi>M</mi>"), "{l}");
    }

    #[test]
    fn long_sums_break_into_rows() {
        let names: Vec<String> = (1..=30).map(|k| format!("v_{k}")).collect();
        let time: Vec<&str> = names.iter().map(String::as_str).collect();
        let s = Symbols::parse_decl(&["I_x"], &time);
        let sum = names
            .iter()
            .map(|n| format!("I_x*{n}"))
            .collect::<Vec<_>>()
            .join(" - ");
        let rows = equation_rows("<mi>H</mi>", &s.expr(&sum).unwrap(), 58.0);
        assert!(rows.len() > 2, "{rows:?}");
        assert_eq!(rows[0].0, "<mi>H</mi>");
        for (l, r) in &rows {
            assert!(width(l) + width(r) <= 58.0 + 8.0, "{r}");
        }
        // Every term is on exactly one row.
        let all: String = rows.iter().map(|r| r.1.as_str()).collect();
        assert_eq!(all.matches("<mo>−</mo>").count(), 29);
    }
}
