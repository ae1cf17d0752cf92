//! A step's label checked against its value: a label that is mathematics
//! prints as the left side of the step's equations, so it must be what the
//! value is. A step `solve(eq, x)` (or a `subst` of one) is labelled by
//! its unknown x or by a name; an expression label (`phi''*sin(theta)`) or
//! a time symbol (`psi'`) on any other step must equal the value
//! identically; `partial(T, q)` must be ∂T/∂q of the earlier step `T`.
//! A label `0` states that the value vanishes: on a solve step that is
//! never so; elsewhere it is an identity or a law of motion, which
//! `hdot verify` checks through the step's meaning. A formula of symbols
//! and steps (`|H_G|^2` = H_G·H_G, `2T`, `m a_G` when every word is a
//! declared symbol or a step) must equal the value, the step's own name in
//! it standing for the value. A label that is a name (`Sigma M`, `H_G`, a
//! constant's name on a step that is not a solve) stays a name.

use super::context::{Context, R};
use super::raw::RawStep;
use super::unfold;
use super::value::Value;
use crate::label::{LabelMath, Piece, label_word};
use crate::parse::{Ast, AstKind, parse};
use crate::poly::Poly;
use crate::rational::Rational;
use crate::symbols::Decl;
use crate::vector::Vec3;

/// What a step's formula solves for, read from its outermost call
/// through `subst(…, rules)`.
enum Solved {
    /// Not a solve.
    No,
    /// `solve(eq, x)`: one unknown (or `solve(eq, x^k)`: its power).
    One(Poly),
    /// `solve(eqs, [x, y, …])`: several, each labelling its own item.
    Several,
}

impl Context<'_> {
    /// Checks that the label of step `s` (already read as `math`) is what
    /// its value is; the error names the step and the label.
    pub(crate) fn check_label(
        &self,
        s: &RawStep,
        value: &Value,
        math: Option<&LabelMath>,
    ) -> R<()> {
        let Some(label) = &s.label else {
            return Ok(());
        };
        let text = label.get_ref().trim();
        let n = s.name.get_ref();
        let fail = |msg: String| -> R<()> {
            Err(self.diag_string(
                label,
                0,
                label.get_ref().len(),
                format!("step `{n}`, field `label`: {msg}"),
            ))
        };
        let solved = self.solved(s.value.get_ref());
        // A plain word that is a declared symbol prints as that symbol.
        let symbol = self.symbol_label(text);
        match (solved, math, symbol) {
            (Solved::One(_) | Solved::Several, Some(LabelMath::Zero), _) => fail(
                "a step solved for its unknowns is not zero: `0 = …` would be false; label it with the unknown or a name"
                    .to_owned(),
            ),
            (Solved::Several, Some(_), _) | (Solved::Several, None, Some(_)) => fail(format!(
                "`{text}` labels a step solved for several unknowns, whose items are labelled by the unknowns \
                 themselves; label the step with a name (`accelerations`)"
            )),
            (Solved::One(x), Some(LabelMath::Expr(e)), _) => {
                self.same_unknown(text, &e.to_poly(), &x, &fail)
            }
            (Solved::One(x), None, Some(p)) => self.same_unknown(text, &p, &x, &fail),
            (Solved::One(x), Some(LabelMath::Partial(..) | LabelMath::Formula(_)), _) => fail(format!(
                "`{text}` is not what the step solves for: it gives {x}; label it `{x}` or with a name"
            )),
            (_, Some(LabelMath::Zero), _) | (Solved::One(_) | Solved::Several, None, None) => {
                Ok(())
            }
            (Solved::No, Some(LabelMath::Expr(e)), _) => {
                self.identical(text, value, &e.to_poly(), &fail)
            }
            (Solved::No, Some(LabelMath::Partial(f, q)), _) => {
                let Some(Value::Scalar(of)) = self.values.get(f) else {
                    return fail(format!(
                        "`{text}`: `{f}` is not an earlier step with a scalar value, so ∂{f}/∂{q} is not defined here"
                    ));
                };
                let want = unfold(&self.abbrevs, of).partial(*q);
                self.identical(text, value, &want, &fail)
            }
            // A time symbol (ψ̇) on a step that is not a solve: the
            // printed `ψ̇ = …` must be an identity.
            (Solved::No, None, Some(p)) if p.atoms().iter().any(|a| a.is_time_dependent()) => {
                self.identical(text, value, &p, &fail)
            }
            // A formula of symbols and steps (`|H_G|^2`, `2T`) is what it
            // evaluates to.
            (Solved::No, Some(LabelMath::Formula(ps)), _) => {
                self.formula_holds(text, ps, n, value, &fail)
            }
            // Words side by side that are all declared symbols or steps
            // (`m a_G`) are their product; other words are a name.
            (Solved::No, None, _) => match self.product_words(text, n) {
                Some(ps) => self.formula_holds(text, &ps, n, value, &fail),
                None => Ok(()),
            },
        }
    }

    /// Whether the label `text` is exactly a declared constant or time
    /// symbol (with its primes), as a polynomial; abbreviations and other
    /// words are names.
    fn symbol_label(&self, text: &str) -> Option<Poly> {
        let base = text.trim_end_matches('\'');
        match self.symbols.get(base) {
            Some(Decl::Constant | Decl::Time) => self.symbols.poly(text).ok(),
            _ => None,
        }
    }

    /// The label of a solve for `x` must be `x`.
    fn same_unknown(
        &self,
        text: &str,
        label: &Poly,
        x: &Poly,
        fail: &dyn Fn(String) -> R<()>,
    ) -> R<()> {
        if (label - x).is_zero() {
            return Ok(());
        }
        fail(format!(
            "`{text}` is not what the step solves for: it gives {x}, so `{text} = …` would print a false equation; \
             label it `{x}` or with a name"
        ))
    }

    /// An expression label must equal a scalar value identically.
    fn identical(
        &self,
        text: &str,
        value: &Value,
        label: &Poly,
        fail: &dyn Fn(String) -> R<()>,
    ) -> R<()> {
        let Value::Scalar(v) = value else {
            return fail(format!(
                "`{text}` is a scalar expression, and the step is {}: label it with a name",
                value.describe()
            ));
        };
        let diff = &unfold(&self.abbrevs, v) - &unfold(&self.abbrevs, label);
        if diff.is_zero() {
            return Ok(());
        }
        fail(format!(
            "`{text}` is not the step's value (their difference is {diff}), so `{text} = …` would print a false \
             equation; label it with a name, or solve for what the label names (`solve(eq, x)` labelled `x`)"
        ))
    }

    /// The words of a name label as a product, when there are two or more
    /// and each is a declared symbol or a step (earlier, or this one `own`).
    /// One word stays a name (`H'` on `dt(H)` is the rate it names).
    /// A leading minus sign (`-m a_G`, `−T`) makes the words a product
    /// even when there is one: a name does not start with a sign.
    fn product_words(&self, text: &str, own: &str) -> Option<Vec<Piece>> {
        let unsigned = text.strip_prefix(['-', '−']).map(str::trim_start);
        let words: Vec<&str> = unsigned.unwrap_or(text).split_whitespace().collect();
        if words.len() < 2 && (unsigned.is_none() || words.is_empty()) {
            return None;
        }
        let sign = unsigned.map(|_| Piece::Number("-1".to_owned()));
        sign.into_iter()
            .map(Some)
            .chain(words.iter().map(|w| {
                let (b, k) = label_word(w);
                (self.symbols.get(b).is_some() || self.is_step(b) || b == own)
                    .then(|| Piece::Name(b.to_owned(), k))
            }))
            .collect()
    }

    /// A label formula must equal the step's value; the error says what the
    /// label means and what the value is. A magnitude `|…|` not under an
    /// even power is no polynomial: then the squares are compared.
    fn formula_holds(
        &self,
        text: &str,
        pieces: &[Piece],
        own: &str,
        value: &Value,
        fail: &dyn Fn(String) -> R<()>,
    ) -> R<()> {
        let f = Formula {
            cx: self,
            own,
            value,
        };
        let bare = pieces.iter().any(bare_abs);
        let label = match f.product(pieces, if bare { Mode::Shape } else { Mode::Exact }) {
            Ok(t) => t,
            Err(m) => return fail(format!("`{text}`: {m}")),
        };
        let Some(is) = Term::of(value) else {
            return fail(format!(
                "`{text}` means {}, and the step is {}: label it with a name",
                label.describe(),
                value.describe()
            ));
        };
        let (label, is) = match (bare, label.is_vector() == is.is_vector()) {
            (_, false) => {
                // A magnitude's value is not known before squaring: say
                // what kind of thing the label is.
                let means = match (&label, bare) {
                    (Term::Scalar(_), true) => "a scalar (a magnitude)".to_owned(),
                    (Term::Vector(_, f), true) => format!("a vector in frame {f}"),
                    (_, false) => label.describe(),
                };
                return fail(format!(
                    "`{text}` means {means}, and the step's value is {}, so `{text} = …` would print a false \
                     equation; label it with a name",
                    is.describe()
                ));
            }
            (false, true) => (label, is),
            (true, true) => match f.product(pieces, Mode::Square) {
                Ok(sq) => (sq, Term::Scalar(is.square())),
                Err(m) => return fail(format!("`{text}`: {m}")),
            },
        };
        let squared = if bare { " squared" } else { "" };
        let diff = match (&label, &is) {
            (Term::Scalar(l), Term::Scalar(v)) => Term::Scalar(&self.unfold(v) - &self.unfold(l)),
            (Term::Vector(l, lf), Term::Vector(v, vf)) => {
                let Some(l) = f.express(l, lf, vf) else {
                    return fail(format!(
                        "`{text}` is a vector in frame {lf} and the step's value one in frame {vf}, which no \
                         chain of rotations relates"
                    ));
                };
                Term::Vector(
                    Vec3(std::array::from_fn(|k| {
                        &self.unfold(&v.0[k]) - &self.unfold(&l.0[k])
                    })),
                    vf.clone(),
                )
            }
            _ => unreachable!("shapes compared above"),
        };
        if diff.is_zero() {
            return Ok(());
        }
        fail(format!(
            "`{text}` means {}{squared}, and the step's value is {}{squared} (their difference is {}), so \
             `{text} = …` would print a false equation; label it with a name, or give the step the value the \
             label names",
            label.describe(),
            is.describe(),
            diff.describe()
        ))
    }

    /// What the formula of a step solves for.
    fn solved(&self, formula: &str) -> Solved {
        let Ok(mut ast) = parse(formula) else {
            return Solved::No;
        };
        loop {
            let AstKind::Call { func, args } = &ast.kind else {
                return Solved::No;
            };
            match (func.as_str(), args.as_slice()) {
                ("subst", [inner, ..]) => ast = inner.clone(),
                ("solve", [_, unknown]) => return self.unknown(unknown),
                _ => return Solved::No,
            }
        }
    }

    fn unknown(&self, a: &Ast) -> Solved {
        match &a.kind {
            AstKind::Name { name, primes } => self
                .symbols
                .atom(name, *primes, a.span)
                .map_or(Solved::No, |x| Solved::One(Poly::atom(x))),
            AstKind::Pow(base, k) => match self.unknown(base) {
                Solved::One(x) => Solved::One(x.pow(*k)),
                _ => Solved::No,
            },
            AstKind::Vector { .. } => Solved::Several,
            _ => Solved::No,
        }
    }
}

/// A scalar or a vector in a frame: what a label formula evaluates to.
enum Term {
    Scalar(Poly),
    Vector(Vec3, String),
}

impl Term {
    /// A step's value as a term; `None` for a matrix, list or array.
    fn of(v: &Value) -> Option<Term> {
        match v {
            Value::Scalar(p) => Some(Term::Scalar(p.clone())),
            Value::Vector(v, f) => Some(Term::Vector(v.clone(), f.clone())),
            _ => None,
        }
    }

    fn is_vector(&self) -> bool {
        matches!(self, Term::Vector(..))
    }

    fn is_zero(&self) -> bool {
        match self {
            Term::Scalar(p) => p.is_zero(),
            Term::Vector(v, _) => v.is_zero(),
        }
    }

    /// The square: s² or v·v.
    fn square(&self) -> Poly {
        match self {
            Term::Scalar(p) => p.pow(2),
            Term::Vector(v, _) => v.dot(v),
        }
    }

    fn pow(self, k: u32) -> Result<Term, String> {
        match self {
            Term::Scalar(p) => Ok(Term::Scalar(p.pow(k))),
            v @ Term::Vector(..) if k == 1 => Ok(v),
            v if k.is_multiple_of(2) => Ok(Term::Scalar(v.square().pow(k / 2))),
            _ => Err(format!(
                "a vector to the odd power {k} is not defined: write an even power (H^2 is H·H)"
            )),
        }
    }

    fn times(self, o: Term) -> Result<Term, String> {
        match (self, o) {
            (Term::Scalar(a), Term::Scalar(b)) => Ok(Term::Scalar(&a * &b)),
            (Term::Scalar(s), Term::Vector(v, f)) | (Term::Vector(v, f), Term::Scalar(s)) => {
                Ok(Term::Vector(v.scale(&s), f))
            }
            (Term::Vector(..), Term::Vector(..)) => Err(
                "two vectors side by side have no product: write their scalar product as a step (`dot(a, b)`) \
                 and label it with a name"
                    .into(),
            ),
        }
    }

    /// The term for a message: `m² (w_x² + w_y²)`, `[a, b, c] in B`.
    fn describe(&self) -> String {
        match self {
            Term::Scalar(p) => format!("{p}"),
            Term::Vector(v, f) => format!("[{}, {}, {}] in {f}", v.0[0], v.0[1], v.0[2]),
        }
    }
}

/// How a label formula is evaluated.
#[derive(Clone, Copy, PartialEq)]
enum Mode {
    /// Exactly (no magnitude outside an even power).
    Exact,
    /// Its shape only: each magnitude counts as 1 (scalar or vector?).
    Shape,
    /// Its square (each piece squared).
    Square,
}

/// Whether a piece is a magnitude that is no polynomial: `|…|` bare or to
/// an odd power.
fn bare_abs(p: &Piece) -> bool {
    match p {
        Piece::Abs(_) => true,
        Piece::Pow(b, k) => matches!(**b, Piece::Abs(_)) && k % 2 == 1,
        _ => false,
    }
}

/// A label formula's names read in a derivation: declared symbols, earlier
/// steps, and the step itself (`own`, whose value is `value`).
struct Formula<'c, 'a> {
    cx: &'c Context<'a>,
    own: &'c str,
    value: &'c Value,
}

impl Formula<'_, '_> {
    /// The pieces side by side: their product.
    fn product(&self, pieces: &[Piece], mode: Mode) -> Result<Term, String> {
        let mut acc = Term::Scalar(Poly::one());
        for p in pieces {
            acc = acc.times(self.piece(p, mode)?)?;
        }
        Ok(acc)
    }

    fn piece(&self, p: &Piece, mode: Mode) -> Result<Term, String> {
        let t = match p {
            Piece::Number(n) => Term::Scalar(Poly::constant(
                Rational::parse(n).ok_or_else(|| format!("`{n}` is too long a number"))?,
            )),
            Piece::Name(w, k) => self.name(w, *k)?,
            Piece::Abs(inner) => match mode {
                Mode::Exact => unreachable!("a bare magnitude is compared squared"),
                Mode::Shape => Term::Scalar(Poly::one()),
                Mode::Square => return Ok(Term::Scalar(self.abs_squared(inner)?)),
            },
            Piece::Pow(b, k) => match (&**b, mode) {
                (Piece::Abs(inner), Mode::Exact | Mode::Square) if k % 2 == 0 => {
                    Term::Scalar(self.abs_squared(inner)?.pow(k / 2))
                }
                (Piece::Abs(inner), Mode::Square) => {
                    return Ok(Term::Scalar(self.abs_squared(inner)?.pow(*k)));
                }
                (Piece::Abs(_), _) => Term::Scalar(Poly::one()),
                (b, _) => self.piece(b, Mode::Exact)?.pow(*k)?,
            },
        };
        Ok(match mode {
            Mode::Square => Term::Scalar(t.square()),
            _ => t,
        })
    }

    /// |x|² for the pieces `inner` of `|…|`.
    fn abs_squared(&self, inner: &[Piece]) -> Result<Poly, String> {
        if inner.iter().any(bare_abs) {
            return match self.product(inner, Mode::Square)? {
                Term::Scalar(p) => Ok(p),
                Term::Vector(..) => unreachable!("a square is a scalar"),
            };
        }
        Ok(self.product(inner, Mode::Exact)?.square())
    }

    /// A name with `k` primes: the step itself, an earlier step or a
    /// declared symbol; a step's primes are its time derivatives (of a
    /// vector, in the inertial sense).
    fn name(&self, w: &str, k: u32) -> Result<Term, String> {
        let step = if w == self.own {
            Some(self.value)
        } else {
            self.cx.values.get(w)
        };
        let Some(v) = step else {
            return self
                .cx
                .symbols
                .atom(w, k, crate::parse::Span::default())
                .map(|a| Term::Scalar(Poly::atom(a)))
                .map_err(|e| e.message);
        };
        let mut t = Term::of(v).ok_or_else(|| {
            format!(
                "`{w}` is {}: a label formula is made of scalars and vectors",
                v.describe()
            )
        })?;
        for _ in 0..k {
            t = match t {
                Term::Scalar(p) => Term::Scalar(p.dt()),
                Term::Vector(v, f) => {
                    let d = self.cx.frame(&f).dt(&v);
                    Term::Vector(d, f)
                }
            };
        }
        Ok(t)
    }

    /// `v` in frame `from`, in frame `to`'s components.
    fn express(&self, v: &Vec3, from: &str, to: &str) -> Option<Vec3> {
        let (i, j) = (self.cx.frame_index(from)?, self.cx.frame_index(to)?);
        super::ops::express_in(self.cx, v.clone(), i, j)
    }
}
