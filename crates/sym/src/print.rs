//! Printers: source syntax, Unicode text, LaTeX and SymPy.
//!
//! One precedence-aware walk over an [`Expr`] ([`print()`]) is shared by all
//! four; a [`Style`] says how atoms, numbers, products and powers look.
//! Parentheses follow one rule set in every style, the one that makes the
//! source syntax round-trip: a sum inside a sum or product, a product or a
//! negation inside a product, and anything but an atom or integer under a
//! power are parenthesised. The textbook styles (Unicode, LaTeX) write a
//! fraction as a textbook does ([`Style::textbook_fraction`]): a rational
//! coefficient split over it, and no brackets around a LaTeX numerator
//! that is one sum.
//!
//! # Example
//! ```
//! use hdot_sym::{print, Symbols};
//! let s = Symbols::parse_decl(&["I_x"], &["omega_x", "theta"]);
//! let e = s.expr("I_x*omega_x' - sin(theta)*theta''").unwrap();
//! assert_eq!(print::latex(&e), r"I_x \dot{\omega}_x - \sin\theta \, \ddot{\theta}");
//! assert_eq!(print::unicode(&e), "I_x ω̇_x − sin θ θ̈");
//! ```

use crate::atom::{Atom, AtomKind};
use crate::expr::{Expr, Id, Node};
use crate::rational::Rational;

/// How the pieces of an expression are written.
pub trait Style {
    /// An atom (symbol, derivative, sin/cos).
    fn atom(&self, a: Atom) -> String;
    /// A non-negative number as a factor or term.
    fn num(&self, r: &Rational) -> String;
    /// Separator between factors of a product.
    fn mul_sep(&self, left: &Node, right: &Node) -> &'static str;
    /// `base^exp` for `exp ≥ 2`; `base` is already parenthesised when needed.
    fn pow(&self, base: &str, base_node: &Node, exp: u32) -> String;
    /// A quotient: the numerator (a product, possibly `1`) over denominator
    /// factors (each an atom or a power).
    fn fraction(&self, num: &str, dens: &[String]) -> String {
        let mut s = num.to_owned();
        for d in dens {
            s.push('/');
            s.push_str(d);
        }
        s
    }
    /// The minus sign (prefix and infix).
    fn minus(&self) -> &'static str {
        "-"
    }
    /// The plus sign between terms.
    fn plus(&self) -> &'static str {
        "+"
    }
    /// The digits of an integer that a textbook fraction writes on its own
    /// (the numerator and denominator of a rational coefficient split over
    /// the fraction bar).
    fn digits(&self, digits: &str) -> String {
        digits.to_owned()
    }
    /// Opening and closing parentheses.
    fn parens(&self) -> (&'static str, &'static str) {
        ("(", ")")
    }
    /// Whether a fraction that is a factor of a product, such as the ratio
    /// in `(m g l/I′) sin θ`, needs parentheses (not when it is set as a
    /// built-up fraction).
    fn paren_fraction_factor(&self) -> bool {
        true
    }
    /// Whether a fraction is written as a textbook writes it rather than
    /// as source text: a rational coefficient of a fraction goes numerator
    /// to numerator and denominator to denominator, `7 F²/(2 m)` rather
    /// than `(7/2) F²/m` (LaTeX `\frac{7 F^{2}}{2 m}`, never a fraction
    /// inside a fraction); and, when the fraction is built up (LaTeX), a
    /// numerator that is one bare sum is not bracketed: the fraction bar
    /// groups it.
    fn textbook_fraction(&self) -> bool {
        false
    }
}

/// Prints `e` in the given style.
pub fn print(e: &Expr, style: &dyn Style) -> String {
    if e.is_empty() {
        return style.num(&Rational::ZERO);
    }
    let cached = Cached {
        inner: style,
        atoms: Default::default(),
        pows: Default::default(),
        nums: Default::default(),
    };
    let mut out = String::new();
    write(e, e.root(), &cached, &mut out);
    out
}

/// Remembers how each atom was written: a long result names the same few
/// atoms thousands of times.
struct Cached<'a> {
    inner: &'a dyn Style,
    atoms: std::cell::RefCell<rustc_hash::FxHashMap<Atom, String>>,
    pows: std::cell::RefCell<rustc_hash::FxHashMap<(Atom, u32), String>>,
    nums: std::cell::RefCell<rustc_hash::FxHashMap<Rational, String>>,
}

impl Cached<'_> {
    /// Appends the atom's text without copying it out of the cache.
    fn write_atom(&self, a: Atom, out: &mut String) {
        let mut atoms = self.atoms.borrow_mut();
        out.push_str(atoms.entry(a).or_insert_with(|| self.inner.atom(a)));
    }

    /// Appends the number's text (a result repeats the same few numbers).
    fn write_num(&self, r: &Rational, out: &mut String) {
        let mut nums = self.nums.borrow_mut();
        if let Some(text) = nums.get(r) {
            out.push_str(text);
        } else {
            let text = self.inner.num(r);
            out.push_str(&text);
            nums.insert(r.clone(), text);
        }
    }

    /// Appends `a^exp` (an atom base needs no parentheses).
    fn write_atom_pow(&self, a: Atom, exp: u32, out: &mut String) {
        let mut pows = self.pows.borrow_mut();
        let text = pows.entry((a, exp)).or_insert_with(|| {
            let mut b = String::new();
            self.write_atom(a, &mut b);
            self.inner.pow(&b, &Node::Atom(a), exp)
        });
        out.push_str(text);
    }
}

fn paren(e: &Expr, id: Id, style: &Cached, out: &mut String) {
    let (l, r) = style.inner.parens();
    out.push_str(l);
    write(e, id, style, out);
    out.push_str(r);
}

fn write(e: &Expr, id: Id, style: &Cached, out: &mut String) {
    match e.node(id) {
        Node::Num(r) => style.write_num(r, out),
        Node::Atom(a) => style.write_atom(*a, out),
        Node::Add(terms) => {
            for (k, &t) in terms.iter().enumerate() {
                match e.node(t) {
                    Node::Neg(inner) if k > 0 => {
                        out.push(' ');
                        out.push_str(style.inner.minus());
                        out.push(' ');
                        write_under_neg(e, *inner, style, out);
                    }
                    Node::Add(_) => {
                        if k > 0 {
                            write_plus(style, out);
                        }
                        paren(e, t, style, out);
                    }
                    _ => {
                        if k > 0 {
                            write_plus(style, out);
                        }
                        write(e, t, style, out);
                    }
                }
            }
        }
        Node::Mul(factors) => {
            let is_denominator = |f: &Id| matches!(e.node(*f), Node::Pow(_, k) if *k < 0);
            if factors.iter().any(is_denominator) {
                let (dens, nums): (Vec<Id>, Vec<Id>) =
                    factors.iter().partition(|f| is_denominator(f));
                write_fraction(e, &nums, &dens, style, out);
            } else {
                write_product(e, factors, style, out);
            }
        }
        Node::Pow(_, k) if *k < 0 => write_fraction(e, &[], &[id], style, out),
        Node::Neg(inner) => {
            out.push_str(style.inner.minus());
            write_under_neg(e, *inner, style, out);
        }
        Node::Pow(base, exp) if matches!(e.node(*base), Node::Atom(_)) => {
            let Node::Atom(a) = e.node(*base) else {
                unreachable!()
            };
            style.write_atom_pow(*a, exp.unsigned_abs(), out);
        }
        Node::Pow(base, exp) => {
            let mut b = String::new();
            match e.node(*base) {
                Node::Atom(_) => write(e, *base, style, &mut b),
                Node::Num(r) if r.is_integer() => write(e, *base, style, &mut b),
                _ => paren(e, *base, style, &mut b),
            }
            out.push_str(&style.inner.pow(&b, e.node(*base), exp.unsigned_abs()));
        }
    }
}

/// ` + ` between two terms.
fn write_plus(style: &Cached, out: &mut String) {
    out.push(' ');
    out.push_str(style.inner.plus());
    out.push(' ');
}

fn write_product(e: &Expr, factors: &[Id], style: &Cached, out: &mut String) {
    for (k, &f) in factors.iter().enumerate() {
        if k > 0 {
            out.push_str(style.inner.mul_sep(e.node(factors[k - 1]), e.node(f)));
        }
        match e.node(f) {
            Node::Mul(fs)
                if !style.inner.paren_fraction_factor()
                    && fs
                        .iter()
                        .any(|g| matches!(e.node(*g), Node::Pow(_, k) if *k < 0)) =>
            {
                write(e, f, style, out)
            }
            Node::Add(_) | Node::Mul(_) | Node::Neg(_) => paren(e, f, style, out),
            _ => write(e, f, style, out),
        }
    }
}

/// `nums / dens`, each denominator a negative power of an atom. In a
/// textbook style ([`Style::textbook_fraction`]) a leading rational
/// number is split over the fraction (`7 F²/(2 m)`), and a built-up
/// fraction's numerator that is a single sum loses its brackets.
fn write_fraction(e: &Expr, nums: &[Id], dens: &[Id], style: &Cached, out: &mut String) {
    let textbook = style.inner.textbook_fraction();
    let mut num = String::new();
    let mut nums = nums;
    let mut den_number = None;
    if textbook
        && let Some(&first) = nums.first()
        && let Node::Num(r) = e.node(first)
        && !r.is_integer()
    {
        // Integers are written as their digits in every textbook style.
        let (n, d) = r.parts();
        nums = &nums[1..];
        if n != "1" || nums.is_empty() {
            num.push_str(&style.inner.digits(&n));
            if let Some(&next) = nums.first() {
                num.push_str(style.inner.mul_sep(e.node(first), e.node(next)));
            }
        }
        den_number = Some(style.inner.digits(&d));
    }
    match nums {
        [] if num.is_empty() => style.write_num(&Rational::ONE, &mut num),
        [] => {}
        [only]
            if textbook
                && num.is_empty()
                && !style.inner.paren_fraction_factor()
                && matches!(e.node(*only), Node::Add(_)) =>
        {
            write(e, *only, style, &mut num)
        }
        _ => write_product(e, nums, style, &mut num),
    }
    let dens: Vec<String> = den_number
        .into_iter()
        .chain(dens.iter().map(|&d| {
            let Node::Pow(base, k) = e.node(d) else {
                unreachable!("denominators are negative powers")
            };
            let mut b = String::new();
            match e.node(*base) {
                Node::Atom(_) => write(e, *base, style, &mut b),
                _ => paren(e, *base, style, &mut b),
            }
            if *k == -1 {
                b
            } else {
                style.inner.pow(&b, e.node(*base), k.unsigned_abs())
            }
        }))
        .collect();
    out.push_str(&style.inner.fraction(&num, &dens));
}

/// After a minus sign: sums and negations need parentheses, a bare number
/// too (so that `-(3)` stays distinct from the literal `-3` nowhere used).
fn write_under_neg(e: &Expr, id: Id, style: &Cached, out: &mut String) {
    match e.node(id) {
        Node::Add(_) | Node::Neg(_) => paren(e, id, style, out),
        _ => write(e, id, style, out),
    }
}

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
/// [`print()`]'s text (but for a fraction so rewritten), so a line break
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
    measured_pieces(e, style, too_long, &|long| long)
        .into_iter()
        .map(|(text, depth, _)| (text, depth > 0))
        .collect()
}

/// [`break_pieces`]' pieces with the number of brackets a break before
/// each would fall inside (0 between top-level terms, 1 inside a bracket,
/// 2 inside a bracket in a bracket, …) and each piece's measure: `measure`
/// is taken of every piece once (a term that is not split is measured as a
/// whole, and that measure is the piece's), and a term is split when
/// `too_long` holds of its measure. A line breaker that adds up widths so
/// measures each piece once, not once to decide the split and again to
/// fill the line; it closes a line broken at depth d with d `\right.` and
/// opens the next with d `\left.`.
pub fn measured_pieces<W: Copy>(
    e: &Expr,
    style: &dyn Style,
    measure: &dyn Fn(&str) -> W,
    too_long: &dyn Fn(W) -> bool,
) -> Vec<(String, usize, W)> {
    if e.is_empty() {
        let zero = style.num(&Rational::ZERO);
        let w = measure(&zero);
        return vec![(zero, 0, w)];
    }
    let cached = Cached {
        inner: style,
        atoms: Default::default(),
        pows: Default::default(),
        nums: Default::default(),
    };
    let splitter = Splitter {
        e,
        style: &cached,
        measure,
        too_long,
    };
    let mut out = Vec::new();
    for (prefix, id, bracketed) in sum_terms(e, e.root(), &cached) {
        let mut lead = String::new();
        prefix.write(&mut lead);
        splitter.term(id, bracketed, lead, "", 0, 1, &mut out);
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

/// Splits terms into pieces (see [`measured_pieces`]).
struct Splitter<'a, 's, W> {
    e: &'a Expr,
    style: &'a Cached<'s>,
    measure: &'a dyn Fn(&str) -> W,
    too_long: &'a dyn Fn(W) -> bool,
}

impl<W: Copy> Splitter<'_, '_, W> {
    /// Pushes the pieces of one term, `lead`, then node `id` (bracketed or
    /// not), then `trail`: the whole as one piece at depth `first`, or, when it is
    /// too long and has a bracket to break inside, the pieces of that
    /// bracket — the first at depth `first`, the others at `inner`.
    #[allow(clippy::too_many_arguments)]
    fn term(
        &self,
        id: Id,
        bracketed: bool,
        lead: String,
        trail: &str,
        first: usize,
        inner: usize,
        out: &mut Vec<(String, usize, W)>,
    ) {
        let mut text = lead;
        let lead_len = text.len();
        if bracketed {
            paren(self.e, id, self.style, &mut text);
        } else {
            write(self.e, id, self.style, &mut text);
        }
        text.push_str(trail);
        let w = (self.measure)(&text);
        if (self.too_long)(w) {
            text.truncate(lead_len);
            match self.split(id, text, trail, first, inner, out) {
                Ok(()) => return,
                Err(lead) => {
                    text = lead;
                    if bracketed {
                        paren(self.e, id, self.style, &mut text);
                    } else {
                        write(self.e, id, self.style, &mut text);
                    }
                    text.push_str(trail);
                }
            }
        }
        out.push((text, first, w));
    }

    /// A product term broken inside its longest bracketed sum (see
    /// [`break_pieces`]); `Err(lead)` (the lead handed back) when the term
    /// has no such bracket.
    fn split(
        &self,
        id: Id,
        lead: String,
        trail: &str,
        first: usize,
        inner: usize,
        out: &mut Vec<(String, usize, W)>,
    ) -> Result<(), String> {
        let (e, style) = (self.e, self.style);
        let factors: &[Id] = match e.node(id) {
            Node::Mul(factors) => factors,
            // A bracketed sum alone (after a minus sign: −(a + b + …)).
            Node::Add(_) => std::slice::from_ref(&id),
            _ => return Err(lead),
        };
        let is_den = |f: &Id| matches!(e.node(*f), Node::Pow(_, k) if *k < 0);
        let (dens, factors): (Vec<Id>, Vec<Id>) = factors.iter().partition(|f| is_den(f));
        // The longest bracket: the one a break helps most (the first of
        // equals).
        let Some(j) = factors
            .iter()
            .enumerate()
            .filter(|(_, f)| matches!(e.node(**f), Node::Add(_)))
            .map(|(k, &f)| {
                let mut text = String::new();
                write(e, f, style, &mut text);
                (k, text.len())
            })
            .fold(None, |best: Option<(usize, usize)>, (k, n)| match best {
                Some((_, m)) if m >= n => best,
                _ => Some((k, n)),
            })
            .map(|(k, _)| k)
        else {
            return Err(lead);
        };
        let terms = sum_terms(e, factors[j], style);
        let (l, r) = style.inner.parens();
        let mut before = lead;
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
            return Ok(());
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
        Ok(())
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
        out: &mut Vec<(String, usize, W)>,
    ) {
        let last = terms.len() - 1;
        let mut before = Some(before);
        for (k, (sign, t, bracketed)) in terms.into_iter().enumerate() {
            let mut lead = before.take().unwrap_or_default();
            sign.write(&mut lead);
            let trail = if k == last { after.as_str() } else { "" };
            let depth = if k == 0 { first } else { inner };
            self.term(t, bracketed, lead, trail, depth, inner + 1, out);
        }
    }
}

mod names;

pub use names::{greek_names, latex_symbol, unicode_symbol};
pub(crate) use names::{primed_base, split_name, superscript};

fn is_trig(n: &Node) -> bool {
    matches!(n, Node::Atom(a) if matches!(a.kind(), AtomKind::Sin(_) | AtomKind::Cos(_)))
}

// --------------------------------------------------------------- styles --

/// Source syntax of derivation files: `I_x*omega_x' - sin(theta)^2`.
pub struct Source;

impl Style for Source {
    fn atom(&self, a: Atom) -> String {
        a.to_string()
    }
    fn num(&self, r: &Rational) -> String {
        r.to_string()
    }
    fn mul_sep(&self, _: &Node, _: &Node) -> &'static str {
        "*"
    }
    fn pow(&self, base: &str, _: &Node, exp: u32) -> String {
        format!("{base}^{exp}")
    }
}

/// Unicode text: `I_x ω̇_x − (I_y − I_z) ω_y ω_z`.
pub struct Unicode;

impl Style for Unicode {
    fn atom(&self, a: Atom) -> String {
        match a.kind() {
            AtomKind::Var { name, order, .. } => unicode_symbol(name, order),
            AtomKind::Sin(q) => format!("sin {}", self.atom(q)),
            AtomKind::Cos(q) => format!("cos {}", self.atom(q)),
        }
    }
    fn num(&self, r: &Rational) -> String {
        if r.is_integer() {
            r.to_string()
        } else {
            let (n, d) = r.parts();
            format!("({n}/{d})")
        }
    }
    fn mul_sep(&self, _: &Node, _: &Node) -> &'static str {
        " "
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
            return format!("{f}{} {}", superscript(exp), self.atom(q));
        }
        format!("{base}{}", superscript(exp))
    }
    fn minus(&self) -> &'static str {
        "−"
    }
    fn textbook_fraction(&self) -> bool {
        true
    }
    fn fraction(&self, num: &str, dens: &[String]) -> String {
        if dens.len() == 1 {
            format!("{num}/{}", dens[0])
        } else {
            format!("{num}/({})", dens.join(" "))
        }
    }
}

/// LaTeX math (no surrounding `$`): `I_x \dot{\omega}_x - \left(I_y - I_z\right) \omega_y \omega_z`.
pub struct Latex;

impl Style for Latex {
    fn atom(&self, a: Atom) -> String {
        match a.kind() {
            AtomKind::Var { name, order, .. } => latex_symbol(name, order),
            AtomKind::Sin(q) => format!(r"\sin{}", latex_fn_arg(&self.atom(q))),
            AtomKind::Cos(q) => format!(r"\cos{}", latex_fn_arg(&self.atom(q))),
        }
    }
    fn num(&self, r: &Rational) -> String {
        if r.is_integer() {
            r.to_string()
        } else {
            let (n, d) = r.parts();
            format!(r"\frac{{{n}}}{{{d}}}")
        }
    }
    fn mul_sep(&self, left: &Node, _right: &Node) -> &'static str {
        // A thin space after sin/cos keeps `\sin\theta \, \dot\phi` from
        // reading as the sine of a product.
        if is_trig(left) { r" \, " } else { " " }
    }
    fn pow(&self, base: &str, node: &Node, exp: u32) -> String {
        if let Node::Atom(a) = node
            && let AtomKind::Sin(q) | AtomKind::Cos(q) = a.kind()
        {
            let f = if matches!(a.kind(), AtomKind::Sin(_)) {
                r"\sin"
            } else {
                r"\cos"
            };
            return format!("{f}^{{{exp}}}{}", latex_fn_arg(&self.atom(q)));
        }
        format!("{base}^{{{exp}}}")
    }
    fn parens(&self) -> (&'static str, &'static str) {
        (r"\left(", r"\right)")
    }
    fn paren_fraction_factor(&self) -> bool {
        false
    }
    fn textbook_fraction(&self) -> bool {
        true
    }
    fn fraction(&self, num: &str, dens: &[String]) -> String {
        format!(r"\frac{{{num}}}{{{}}}", dens.join(" "))
    }
}

/// `\sin\theta` for a command, `\sin x` for a letter.
fn latex_fn_arg(arg: &str) -> String {
    if arg.starts_with('\\') {
        arg.to_owned()
    } else {
        format!(" {arg}")
    }
}

/// SymPy source: `I_x*omega_x.diff(t) - sin(theta)**2`, with symbol names
/// mapped to Python identifiers by `var`.
pub struct Sympy<'a> {
    /// Maps a symbol name to the Python variable that holds it.
    pub var: &'a dyn Fn(&str) -> String,
}

impl Style for Sympy<'_> {
    fn atom(&self, a: Atom) -> String {
        match a.kind() {
            AtomKind::Var { name, order: 0, .. } => (self.var)(name),
            AtomKind::Var { name, order: 1, .. } => format!("{}.diff(t)", (self.var)(name)),
            AtomKind::Var { name, order, .. } => format!("{}.diff(t, {order})", (self.var)(name)),
            AtomKind::Sin(q) => format!("sin({})", self.atom(q)),
            AtomKind::Cos(q) => format!("cos({})", self.atom(q)),
        }
    }
    fn num(&self, r: &Rational) -> String {
        if r.is_integer() {
            format!("Integer({r})")
        } else {
            let (n, d) = r.parts();
            format!("Rational({n}, {d})")
        }
    }
    fn mul_sep(&self, _: &Node, _: &Node) -> &'static str {
        "*"
    }
    fn pow(&self, base: &str, _: &Node, exp: u32) -> String {
        format!("{base}**{exp}")
    }
}

/// Source syntax.
pub fn source(e: &Expr) -> String {
    print(e, &Source)
}

/// Unicode text.
pub fn unicode(e: &Expr) -> String {
    print(e, &Unicode)
}

/// LaTeX math.
pub fn latex(e: &Expr) -> String {
    print(e, &Latex)
}

/// Source syntax, parsed back by [`crate::Symbols::expr`] to the same tree.
impl std::fmt::Display for Expr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.is_empty() {
            return f.write_str("0");
        }
        f.write_str(&print(self, &Source))
    }
}

impl std::fmt::Debug for Expr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Expr({self})")
    }
}

impl crate::poly::Poly {
    /// Source syntax in a stable, name-sorted term order (for messages and
    /// JSON): the polynomial's [`Expr`] printed by [`Source`].
    pub fn to_source(&self) -> String {
        Expr::from_poly(self).to_string()
    }
}
