//! Line breaking on the expression tree: the pieces a long expression may
//! be broken between — top-level terms, and the terms of a bracket (or of
//! a bracket in a bracket, to any depth) in a term too long for a line —
//! each printed by the shared walk of [`super`].

use super::{Cached, paren, write, write_fraction, write_product};
use crate::expr::{Expr, Id, Node};
use crate::print::Style;
use crate::rational::Rational;

// ------------------------------------------------------- line breaking --

/// The pieces a long expression may be broken between, each printed by
/// the printer in `style`: the top-level terms of a sum, each with the
/// sign that joins it to the one before (`a`, `+ b`, `- c`); and, inside a
/// term for which `too_long` holds and that is a bracketed sum (−(a + b))
/// or a product with a bracketed sum among its factors, the terms of that
/// bracket (the longest when there are several) — the factors before it
/// and the opening parenthesis go with its first term, the closing
/// parenthesis and the factors after it with its last; a fraction with a
/// bracket in its numerator, which cannot be broken, is written with that
/// bracket after it, `c/(a b) (x + y + …)`. A term of that
/// bracket that is itself too long is split the same way, inside its own
/// bracket, to any depth. Each piece says whether a break before it falls
/// inside a bracket. Joined by single spaces the pieces are exactly
/// [`super::print()`]'s text (but for a fraction so rewritten), so a line break
/// only ever replaces a space.
///
/// # Example
/// ```
/// use hdot_sym::{print, Symbols};
/// let s = Symbols::parse_decl(&["m", "a", "b"], &["x"]);
/// let e = s.expr("m*x'' - (a + b)*x + 1/2*a*x'").unwrap();
/// let pieces = print::break_pieces(&e, &print::Unicode, &|t| t.contains('('));
/// let texts: Vec<&str> = pieces.iter().map(|p| p.0.as_str()).collect();
/// assert_eq!(texts, ["m x\u{308}", "− (a", "+ b) x", "+ (1/2) a x\u{307}"]);
/// assert_eq!(texts.join(" "), print::unicode(&e));
/// assert_eq!(pieces[2].1, true);
/// ```
pub fn break_pieces(
    e: &Expr,
    style: &dyn Style,
    too_long: &dyn Fn(&str) -> bool,
) -> Vec<(String, bool)> {
    let measure = |text: &str| u32::from(too_long(text));
    pieces(e, style, &measure, &|long| long != 0, false)
        .iter()
        .map(|(text, depth, _)| (text.to_owned(), depth > 0))
        .collect()
}

/// The pieces of a broken expression ([`measured_pieces`]): their texts
/// one after another in one string, a space between two, and each
/// piece's span in it, depth and measure. One string for all the pieces,
/// not one per piece (a chain-8 result has 10⁵ pieces), and the pieces of
/// a term joined back are one span, never copied.
#[derive(Debug, Default)]
pub struct Pieces {
    text: String,
    spans: Vec<Span>,
}

/// A piece of [`Pieces`]: its bytes `start..end` in the text, the number
/// of brackets a break before it falls inside, and its measure.
#[derive(Clone, Copy, Debug)]
struct Span {
    start: usize,
    end: usize,
    depth: usize,
    measure: u32,
}

impl Pieces {
    /// Each piece's text, depth and measure, in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, usize, u32)> {
        self.spans
            .iter()
            .map(|s| (&self.text[s.start..s.end], s.depth, s.measure))
    }

    /// Where the next piece's text starts: after a space when a piece is
    /// before it. Returns the text's length before that space, to truncate
    /// back to.
    fn open(&mut self) -> (usize, usize) {
        let mark = self.text.len();
        if !self.spans.is_empty() {
            self.text.push(' ');
        }
        (mark, self.text.len())
    }
}

/// [`break_pieces`]' pieces with the number of brackets a break before
/// each would fall inside (0 between top-level terms, 1 inside a bracket,
/// 2 inside a bracket in a bracket, …) and each piece's measure, and a
/// term is split when `too_long` holds of its measure. A line breaker that
/// adds up widths so measures each piece once, not once to decide the
/// split and again to fill the line; it closes a line broken at depth d
/// with d `\right.` and opens the next with d `\left.`.
///
/// `measure` must be additive over what the printer writes: the measure
/// of a text is the sum of the measures of the atoms, numbers, powers,
/// signs and separators it is written from (as a width is, when every
/// one of them is balanced: no brace or script open at its end). A piece
/// is then measured while it is written, each atom's text measured once
/// for all the pieces, not read again after it is printed. (Debug builds
/// check the sum against the measure of the whole piece.)
pub fn measured_pieces(
    e: &Expr,
    style: &dyn Style,
    measure: &dyn Fn(&str) -> u32,
    too_long: &dyn Fn(u32) -> bool,
) -> Pieces {
    pieces(e, style, measure, too_long, true)
}

/// The pieces of [`break_pieces`] and [`measured_pieces`]; `additive`:
/// whether `measure` is additive, so that a piece is measured while it is
/// written (otherwise each piece is measured whole).
fn pieces(
    e: &Expr,
    style: &dyn Style,
    measure: &dyn Fn(&str) -> u32,
    too_long: &dyn Fn(u32) -> bool,
    additive: bool,
) -> Pieces {
    if e.is_empty() {
        let zero = style.num(&Rational::ZERO);
        let measure = measure(&zero);
        let end = zero.len();
        return Pieces {
            text: zero,
            spans: vec![Span {
                start: 0,
                end,
                depth: 0,
                measure,
            }],
        };
    }
    let cached = Cached::new(e, style, additive.then_some(measure));
    let splitter = Splitter {
        e,
        style: &cached,
        measure,
        too_long,
        additive,
        scratch: Default::default(),
        lens: Default::default(),
    };
    let mut out = Pieces::default();
    let mut lead = String::new();
    for (prefix, id, bracketed) in sum_terms(e, e.root(), &cached) {
        lead.clear();
        prefix.write(&mut lead);
        splitter.term(id, bracketed, &lead, "", 0, 1, &mut out);
    }
    out
}

/// The text that joins a term to the one before it: a sign (empty for
/// the first term unless it is negated) and whether a space follows it.
#[derive(Clone, Copy)]
struct Prefix(&'static str, bool);

impl Prefix {
    fn write(self, out: &mut String) {
        out.push_str(self.0);
        if self.1 {
            out.push(' ');
        }
    }
}

/// The terms of the sum at `id` as [`write`] prints them: the sign text
/// that precedes each (empty, `+ `, `- `, or the minus of a leading
/// negation), the node written after it, and whether that node is put in
/// parentheses. A node that is not a sum is one term.
fn sum_terms(e: &Expr, id: Id, style: &Cached) -> Vec<(Prefix, Id, bool)> {
    let minus = style.inner.minus();
    let plus = style.inner.plus();
    let one = |k: usize, t: Id| -> (Prefix, Id, bool) {
        match e.node(t) {
            Node::Neg(inner) => {
                let under = matches!(e.node(*inner), Node::Add(_) | Node::Neg(_));
                (Prefix(minus, k > 0), *inner, under)
            }
            Node::Add(_) => (
                if k > 0 {
                    Prefix(plus, true)
                } else {
                    Prefix("", false)
                },
                t,
                true,
            ),
            _ if k > 0 => (Prefix(plus, true), t, false),
            _ => (Prefix("", false), t, false),
        }
    };
    match e.node(id) {
        Node::Add(terms) => terms.iter().enumerate().map(|(k, &t)| one(k, t)).collect(),
        _ => vec![one(0, id)],
    }
}

/// The number of terms from which a bracket is taken as too long for a
/// line before it is measured ([`Splitter::speculate`]).
const SPECULATE: usize = 6;

/// Splits terms into pieces (see [`measured_pieces`]).
struct Splitter<'a, 's> {
    e: &'a Expr,
    style: &'a Cached<'s>,
    measure: &'a dyn Fn(&str) -> u32,
    too_long: &'a dyn Fn(u32) -> bool,
    /// Whether `measure` is additive: a piece's measure is then summed
    /// while it is written (`style.written`), not taken of the whole.
    additive: bool,
    /// The buffer a bracket is written into to compare lengths
    /// ([`Splitter::text_len`]).
    scratch: std::cell::Cell<String>,
    /// The text lengths of the brackets compared ([`Splitter::text_len`]).
    lens: std::cell::RefCell<rustc_hash::FxHashMap<Id, usize>>,
}

impl Splitter<'_, '_> {
    /// Pushes the pieces of one term, `lead`, then node `id` (bracketed or
    /// not), then `trail`: the whole as one piece at depth `first`, or, when it is
    /// too long and has a bracket to break inside, the pieces of that
    /// bracket — the first at depth `first`, the others at `inner`.
    #[allow(clippy::too_many_arguments)]
    fn term(
        &self,
        id: Id,
        bracketed: bool,
        lead: &str,
        trail: &str,
        first: usize,
        inner: usize,
        out: &mut Pieces,
    ) {
        if self.additive && self.speculate(id, bracketed) {
            // Broken first, and joined back when the whole fits: a long
            // term is written once, not whole, then its bracket again to
            // choose it, then piece by piece. The pieces with the spaces
            // between them are the whole term's text, and its measure
            // their sum.
            let start = out.spans.len();
            let split = self.split(id, lead, trail, first, inner, out);
            debug_assert!(split, "a speculated term has a bracket");
            let w: u32 = out.spans[start..].iter().map(|p| p.measure).sum();
            if !(self.too_long)(w) && out.spans.len() > start + 1 {
                let whole = Span {
                    start: out.spans[start].start,
                    end: out.text.len(),
                    depth: first,
                    measure: w,
                };
                out.spans.truncate(start);
                debug_assert_eq!(
                    w,
                    (self.measure)(&out.text[whole.start..whole.end]),
                    "a measure not additive: {}",
                    &out.text[whole.start..whole.end]
                );
                out.spans.push(whole);
            }
            return;
        }
        let (mark, start) = out.open();
        let text = &mut out.text;
        text.push_str(lead);
        self.style.written.set(0);
        if bracketed {
            paren(self.e, id, self.style, text);
        } else {
            write(self.e, id, self.style, text);
        }
        text.push_str(trail);
        let w = if self.additive {
            let w = (self.measure)(lead) + self.style.written.get() + (self.measure)(trail);
            debug_assert_eq!(
                w,
                (self.measure)(&text[start..]),
                "a measure not additive: {}",
                &text[start..]
            );
            w
        } else {
            (self.measure)(&text[start..])
        };
        // A term too long with no bracket to break inside is one piece.
        let bracket = (self.too_long)(w).then(|| self.bracket(id)).flatten();
        if let Some(bracket) = bracket {
            out.text.truncate(mark);
            self.split_at(bracket, lead, trail, first, inner, out);
        } else {
            let end = out.text.len();
            out.spans.push(Span {
                start,
                end,
                depth: first,
                measure: w,
            });
        }
    }

    /// Whether the term at `id` is broken before it is measured: a product
    /// with no denominator (or a bracketed sum alone) holding a bracketed
    /// sum of at least [`SPECULATE`] terms, which is most often too long for
    /// a line. Only what it costs depends on this, never the pieces.
    fn speculate(&self, id: Id, bracketed: bool) -> bool {
        let e = self.e;
        let big = |f: &Id| matches!(e.node(*f), Node::Add(ts) if ts.len() >= SPECULATE);
        match e.node(id) {
            Node::Mul(fs) if !bracketed => {
                fs.iter().any(big)
                    && !fs
                        .iter()
                        .any(|f| matches!(e.node(*f), Node::Pow(_, k) if *k < 0))
            }
            Node::Add(ts) if bracketed => ts.len() >= SPECULATE,
            _ => false,
        }
    }

    /// A product term broken inside its longest bracketed sum (see
    /// [`break_pieces`]); false (nothing pushed) when the term has no such
    /// bracket.
    fn split(
        &self,
        id: Id,
        lead: &str,
        trail: &str,
        first: usize,
        inner: usize,
        out: &mut Pieces,
    ) -> bool {
        match self.bracket(id) {
            Some(bracket) => {
                self.split_at(bracket, lead, trail, first, inner, out);
                true
            }
            None => false,
        }
    }

    /// [`Splitter::split`] inside the bracket `bracket` found by
    /// [`Splitter::bracket`].
    fn split_at(
        &self,
        (dens, factors, j): (Vec<Id>, Vec<Id>, usize),
        lead: &str,
        trail: &str,
        first: usize,
        inner: usize,
        out: &mut Pieces,
    ) {
        let (e, style) = (self.e, self.style);
        let terms = sum_terms(e, factors[j], style);
        let (l, r) = style.inner.parens();
        let mut before = lead.to_owned();
        if !dens.is_empty() {
            // A fraction's numerator cannot be broken: the bracket is
            // written after the rest of the fraction, (c/(a b)) (x + y + …).
            let rest: Vec<Id> = factors
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != j)
                .map(|(_, &f)| f)
                .collect();
            let bracket_paren = style.inner.paren_fraction_factor();
            if bracket_paren {
                before.push_str(l);
            }
            write_fraction(e, &rest, &dens, style, &mut before);
            if bracket_paren {
                before.push_str(r);
            }
            before.push_str(style.inner.mul_sep(e.node(factors[j]), e.node(factors[j])));
            before.push_str(l);
            let mut after = r.to_owned();
            after.push_str(trail);
            self.bracket_terms(terms, before, after, first, inner, out);
            return;
        }
        if j > 0 {
            write_product(e, &factors[..j], style, &mut before);
            before.push_str(
                style
                    .inner
                    .mul_sep(e.node(factors[j - 1]), e.node(factors[j])),
            );
        }
        before.push_str(l);
        let mut after = r.to_owned();
        if j + 1 < factors.len() {
            after.push_str(
                style
                    .inner
                    .mul_sep(e.node(factors[j]), e.node(factors[j + 1])),
            );
            write_product(e, &factors[j + 1..], style, &mut after);
        }
        after.push_str(trail);
        self.bracket_terms(terms, before, after, first, inner, out);
    }

    /// The term at `id` as its denominators, its other factors and which
    /// of those is the bracket to break inside: the longest bracketed sum
    /// (the one a break helps most, the first of equals); `None` when it
    /// has none. A term with one bracket (most) is not written to choose
    /// it; each bracket's length is written once per node.
    fn bracket(&self, id: Id) -> Option<(Vec<Id>, Vec<Id>, usize)> {
        let e = self.e;
        let factors: &[Id] = match e.node(id) {
            Node::Mul(factors) => factors,
            // A bracketed sum alone (after a minus sign: −(a + b + …)).
            Node::Add(_) => std::slice::from_ref(&id),
            _ => return None,
        };
        let is_bracket = |f: &Id| matches!(e.node(*f), Node::Add(_));
        if !factors.iter().any(is_bracket) {
            return None;
        }
        let is_den = |f: &Id| matches!(e.node(*f), Node::Pow(_, k) if *k < 0);
        let (dens, factors): (Vec<Id>, Vec<Id>) = factors.iter().partition(|f| is_den(f));
        let brackets = || factors.iter().enumerate().filter(|(_, f)| is_bracket(f));
        let j = match brackets().count() {
            0 => return None,
            1 => brackets().next().map_or(0, |(k, _)| k),
            _ => {
                let mut best: Option<(usize, usize)> = None;
                for (k, &f) in brackets() {
                    let n = self.text_len(f);
                    if best.is_none_or(|(_, m)| n > m) {
                        best = Some((k, n));
                    }
                }
                best.map_or(0, |(k, _)| k)
            }
        };
        Some((dens, factors, j))
    }

    /// The length in bytes of the text of node `id`, written once per node.
    fn text_len(&self, id: Id) -> usize {
        if let Some(&n) = self.lens.borrow().get(&id) {
            return n;
        }
        let mut text = self.scratch.take();
        text.clear();
        write(self.e, id, self.style, &mut text);
        let n = text.len();
        self.scratch.set(text);
        self.lens.borrow_mut().insert(id, n);
        n
    }

    /// The pieces of a bracket's terms: `before` (up to the opening
    /// parenthesis) leads the first, `after` (from the closing one) ends
    /// the last.
    fn bracket_terms(
        &self,
        terms: Vec<(Prefix, Id, bool)>,
        before: String,
        after: String,
        first: usize,
        inner: usize,
        out: &mut Pieces,
    ) {
        let last = terms.len() - 1;
        let mut before = Some(before);
        for (k, (sign, t, bracketed)) in terms.into_iter().enumerate() {
            let mut lead = before.take().unwrap_or_default();
            sign.write(&mut lead);
            let trail = if k == last { after.as_str() } else { "" };
            let depth = if k == 0 { first } else { inner };
            self.term(t, bracketed, &lead, trail, depth, inner + 1, out);
        }
    }
}
