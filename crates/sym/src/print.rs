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
    let cached = Cached::new(e, style, None);
    let mut out = String::new();
    write(e, e.root(), &cached, &mut out);
    out
}

/// Remembers how each atom was written: a long result names the same few
/// atoms thousands of times. An atom's text is read from a table indexed
/// by the atom's id (a hash lookup per atom written was a tenth of the
/// printing).
///
/// With a `measure` (an additive one, see [`measured_pieces`]), every text
/// written is measured as it is written: an atom's, a number's and a
/// power's measure once, when it is first written, the signs and
/// separators as they are written, and `written` holds the sum, so that a
/// piece's width is known without reading it again.
struct Cached<'a> {
    inner: &'a dyn Style,
    atoms: std::cell::RefCell<Vec<Option<Measured>>>,
    pows: std::cell::RefCell<rustc_hash::FxHashMap<(Atom, u32), (String, u32)>>,
    nums: std::cell::RefCell<rustc_hash::FxHashMap<Rational, (String, u32)>>,
    measure: Option<&'a dyn Fn(&str) -> u32>,
    /// The measures of the signs and separators written (static texts,
    /// keyed by address and length): a long result writes the same few
    /// tens of thousands of times, and measuring each was 3 % of chain-6.
    seps: std::cell::RefCell<Vec<(usize, usize, u32)>>,
    /// Each atom's text after a separator (`" \\, \\dot{q}_{2}"`), by the
    /// atom's id, one entry per separator seen before it (one or two): most
    /// factors of a long result are atoms after a separator, and one text
    /// appended for the two halves saves the work of the second (chain-8's
    /// LaTeX: −5 % of the process). `None` for an expression of fewer than
    /// [`SEP_ATOMS_FROM`] nodes, where few texts would be read twice.
    sep_atoms: Option<std::cell::RefCell<Vec<SepAtoms>>>,
    written: std::cell::Cell<u32>,
}

/// A text and its measure.
type Measured = (Box<str>, u32);

/// An atom's texts after separators: (separator's address and length,
/// the separator and the atom's text, its measure).
type SepAtoms = smallvec::SmallVec<[(usize, usize, Measured); 2]>;

/// The number of nodes from which an expression's printer keeps each
/// atom's text after a separator ([`Cached::write_sep_atom`]).
const SEP_ATOMS_FROM: usize = 512;

impl<'a> Cached<'a> {
    /// The printer's cache for expression `e`.
    fn new(e: &Expr, inner: &'a dyn Style, measure: Option<&'a dyn Fn(&str) -> u32>) -> Self {
        Cached {
            inner,
            atoms: Default::default(),
            pows: Default::default(),
            nums: Default::default(),
            measure,
            seps: Default::default(),
            sep_atoms: (e.len() >= SEP_ATOMS_FROM).then(Default::default),
            written: Default::default(),
        }
    }

    /// The measure of `text` (0 when nothing is measured).
    fn measure_of(&self, text: &str) -> u32 {
        self.measure.map_or(0, |m| m(text))
    }

    /// Appends `text` whose measure is `width`.
    #[inline]
    fn push_measured(&self, out: &mut String, text: &str, width: u32) {
        out.push_str(text);
        self.written.set(self.written.get() + width);
    }

    /// Appends `text` (a sign, a separator, a bracket), measured once per
    /// distinct text.
    #[inline]
    fn push(&self, out: &mut String, text: &'static str) {
        let width = match self.measure {
            None => 0,
            Some(m) => self.sep_width(text, m),
        };
        self.push_measured(out, text, width);
    }

    /// The measure of a static text, measured once per distinct text.
    fn sep_width(&self, text: &'static str, m: &dyn Fn(&str) -> u32) -> u32 {
        let key = (text.as_ptr() as usize, text.len());
        let mut seps = self.seps.borrow_mut();
        match seps.iter().find(|s| (s.0, s.1) == key) {
            Some(s) => s.2,
            None => {
                let w = m(text);
                seps.push((key.0, key.1, w));
                w
            }
        }
    }

    /// Appends the text of a composite (a fraction, a power of a bracket)
    /// assembled from parts written to the side since `mark` (the measure
    /// written then), measured as a whole: what the parts added to
    /// `written` is taken back.
    fn push_composite(&self, out: &mut String, text: &str, mark: u32) {
        self.written.set(mark);
        self.push_measured(out, text, self.measure_of(text));
    }

    /// Appends the atom's text without copying it out of the cache.
    #[inline]
    fn write_atom(&self, a: Atom, out: &mut String) {
        let mut atoms = self.atoms.borrow_mut();
        let i = a.id() as usize;
        if i >= atoms.len() {
            atoms.resize(i + 1, None);
        }
        let (text, width) = atoms[i].get_or_insert_with(|| {
            let text = self.inner.atom(a);
            let width = self.measure_of(&text);
            (text.into_boxed_str(), width)
        });
        self.push_measured(out, text, *width);
    }

    /// Appends `sep` then the atom's text, as [`Cached::push`] and
    /// [`Cached::write_atom`] would one after the other (the same text, the
    /// same measure: the sum of the two), from one cached text.
    #[inline]
    fn write_sep_atom(&self, sep: &'static str, a: Atom, out: &mut String) {
        let Some(sep_atoms) = &self.sep_atoms else {
            self.push(out, sep);
            self.write_atom(a, out);
            return;
        };
        let key = (sep.as_ptr() as usize, sep.len());
        let i = a.id() as usize;
        if let Some(e) = sep_atoms
            .borrow()
            .get(i)
            .and_then(|list| list.iter().find(|e| (e.0, e.1) == key))
        {
            self.push_measured(out, &e.2.0, e.2.1);
            return;
        }
        let mark = self.written.get();
        let mut text = String::new();
        self.push(&mut text, sep);
        self.write_atom(a, &mut text);
        let width = self.written.get() - mark;
        self.written.set(mark);
        self.push_measured(out, &text, width);
        let mut table = sep_atoms.borrow_mut();
        if i >= table.len() {
            table.resize_with(i + 1, Default::default);
        }
        table[i].push((key.0, key.1, (text.into_boxed_str(), width)));
    }

    /// Appends the number's text (a result repeats the same few numbers).
    fn write_num(&self, r: &Rational, out: &mut String) {
        let mut nums = self.nums.borrow_mut();
        if let Some((text, width)) = nums.get(r) {
            self.push_measured(out, text, *width);
        } else {
            let text = self.inner.num(r);
            let width = self.measure_of(&text);
            self.push_measured(out, &text, width);
            nums.insert(r.clone(), (text, width));
        }
    }

    /// Appends `a^exp` (an atom base needs no parentheses).
    fn write_atom_pow(&self, a: Atom, exp: u32, out: &mut String) {
        let mut pows = self.pows.borrow_mut();
        let (text, width) = pows.entry((a, exp)).or_insert_with(|| {
            let mark = self.written.get();
            let mut b = String::new();
            self.write_atom(a, &mut b);
            self.written.set(mark);
            let text = self.inner.pow(&b, &Node::Atom(a), exp);
            let width = self.measure_of(&text);
            (text, width)
        });
        self.push_measured(out, text, *width);
    }
}

fn paren(e: &Expr, id: Id, style: &Cached, out: &mut String) {
    let (l, r) = style.inner.parens();
    style.push(out, l);
    write(e, id, style, out);
    style.push(out, r);
}

fn write(e: &Expr, id: Id, style: &Cached, out: &mut String) {
    match e.node(id) {
        Node::Num(r) => style.write_num(r, out),
        Node::Atom(a) => style.write_atom(*a, out),
        Node::Add(terms) => {
            for (k, &t) in terms.iter().enumerate() {
                match e.node(t) {
                    Node::Neg(inner) if k > 0 => {
                        style.push(out, " ");
                        style.push(out, style.inner.minus());
                        style.push(out, " ");
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
            style.push(out, style.inner.minus());
            write_under_neg(e, *inner, style, out);
        }
        Node::Pow(base, exp) if matches!(e.node(*base), Node::Atom(_)) => {
            let Node::Atom(a) = e.node(*base) else {
                unreachable!()
            };
            style.write_atom_pow(*a, exp.unsigned_abs(), out);
        }
        Node::Pow(base, exp) => {
            let mark = style.written.get();
            let mut b = String::new();
            match e.node(*base) {
                Node::Atom(_) => write(e, *base, style, &mut b),
                Node::Num(r) if r.is_integer() => write(e, *base, style, &mut b),
                _ => paren(e, *base, style, &mut b),
            }
            let text = style.inner.pow(&b, e.node(*base), exp.unsigned_abs());
            style.push_composite(out, &text, mark);
        }
    }
}

/// ` + ` between two terms.
fn write_plus(style: &Cached, out: &mut String) {
    style.push(out, " ");
    style.push(out, style.inner.plus());
    style.push(out, " ");
}

fn write_product(e: &Expr, factors: &[Id], style: &Cached, out: &mut String) {
    // Each factor's node is read once, and serves as the left one of the
    // next separator; an atom, most factors of a long result, is written
    // straight from the cache, with the separator before it.
    let mut left: Option<&Node> = None;
    for &f in factors {
        let node = e.node(f);
        if let Some(prev) = left.replace(node) {
            let sep = style.inner.mul_sep(prev, node);
            if let Node::Atom(a) = node {
                style.write_sep_atom(sep, *a, out);
                continue;
            }
            style.push(out, sep);
        }
        match node {
            Node::Atom(a) => style.write_atom(*a, out),
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
    let mark = style.written.get();
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
    // A built-up fraction over one sum of constants needs no brackets:
    // the fraction bar groups it (`\frac{M_a}{I' + I L^2}`).
    let alone = den_number.is_none() && dens.len() == 1 && !style.inner.paren_fraction_factor();
    let dens: Vec<String> = den_number
        .into_iter()
        .chain(dens.iter().map(|&d| {
            let Node::Pow(base, k) = e.node(d) else {
                unreachable!("denominators are negative powers")
            };
            let mut b = String::new();
            match e.node(*base) {
                Node::Atom(a) if alone && *k == -1 && matches!(a.kind(), AtomKind::Sum { .. }) => {
                    if let AtomKind::Sum { sum, .. } = a.kind() {
                        b = print(&shown_sum(sum), style.inner);
                    }
                }
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
    style.push_composite(out, &style.inner.fraction(&num, &dens), mark);
}

/// After a minus sign: sums and negations need parentheses, a bare number
/// too (so that `-(3)` stays distinct from the literal `-3` nowhere used).
fn write_under_neg(e: &Expr, id: Id, style: &Cached, out: &mut String) {
    match e.node(id) {
        Node::Add(_) | Node::Neg(_) => paren(e, id, style, out),
        _ => write(e, id, style, out),
    }
}

mod breaking;
mod names;

pub use breaking::{break_pieces, measured_pieces};

pub use names::{greek_names, latex_symbol, unicode_symbol};
pub(crate) use names::{primed_base, split_name, superscript};

/// A sum of constants standing as one factor (`poly/sums.rs`): its terms
/// in the style's brackets, `(I′ r² + I L²)`.
pub(crate) fn sum_atom(style: &dyn Style, sum: &crate::poly::Poly) -> String {
    let (l, r) = style.parens();
    format!("{l}{}{r}", print(&shown_sum(sum), style))
}

/// A sum atom (a sum of constants held to a negative power) as the
/// textbook writes it: its constants sharing a coefficient as one term,
/// J + R² (m_1 + m_2), not the canonical terms in name order.
fn shown_sum(sum: &crate::poly::Poly) -> Expr {
    crate::present::present(sum, &crate::present::Presentation::default())
}

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
            AtomKind::Sum { sum, .. } => sum_atom(self, sum),
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
            AtomKind::Sum { sum, .. } => sum_atom(self, sum),
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
            AtomKind::Sum { sum, .. } => sum_atom(self, sum),
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
