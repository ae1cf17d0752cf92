//! An operating point — the values of coordinates, speeds and rates along
//! a steady motion (`phi = 0, u_6 = -v/r_R`), read from `name = value`
//! arguments — and the first-order Taylor expansion of a polynomial about
//! it, f(x₀) + Σ ∂f/∂x(x₀) (x − x₀), shared by `linearize` and the
//! linearized form of `kane`. An angle's value may be a multiple of π/2
//! (`q1 = pi`, the inverted pendulum): π is no number of the algebra, so
//! the result is written in the angle's deviation from that value, its
//! sine and cosine exact (sin(π + q) = −sin q).

use crate::atom::{Atom, AtomKind};
use crate::derivation::context::R;
use crate::derivation::ops::Call;
use crate::parse::{Ast, AstKind};
use crate::poly::Poly;

/// The values of the listed symbols along a steady motion. A symbol's
/// rates of higher order than a listed one are zero there (the values are
/// constants): `phi = 0` gives φ̇ = φ̈ = 0, `u = -v/r` gives u̇ = 0.
#[derive(Clone, Debug, Default)]
pub(crate) struct OperatingPoint {
    /// Each listed symbol (a time symbol of any order) with its value, an
    /// expression in constants (0 for an angle in `turns`).
    pub values: Vec<(Atom, Poly)>,
    /// The angles whose value is k π/2, with k: the result is in their
    /// deviation from that value.
    pub turns: Vec<(Atom, i64)>,
}

impl OperatingPoint {
    /// Reads the `name = value` arguments `args` of a call; an error at
    /// the argument when a name is not a time symbol, is listed twice, or
    /// its value is not an expression in constants.
    pub fn read(c: &Call<'_, '_>, args: &[Ast]) -> R<OperatingPoint> {
        let mut values: Vec<(Atom, Poly)> = Vec::with_capacity(args.len());
        let mut turns = Vec::new();
        for r in args {
            let AstKind::Assign {
                name,
                primes,
                name_span,
                value,
            } = &r.kind
            else {
                return c.err(
                    r.span,
                    "expected an operating value `name = value` (such as phi = 0 or u_6 = -v/r_R)",
                );
            };
            let a =
                c.cx.symbols
                    .atom(name, *primes, *name_span)
                    .map_err(|e| c.cx.at(c.base, e.span, e.message))?;
            if !a.is_time_dependent() {
                return c.err(
                    *name_span,
                    format!(
                        "`{name}` is a constant: an operating point gives values to coordinates, speeds and rates"
                    ),
                );
            }
            if values.iter().any(|(b, _)| *b == a) {
                return c.err(*name_span, format!("`{a}` is given twice"));
            }
            if let Some(k) = crate::derivation::ops::quarter_turns(value) {
                if *primes > 0 {
                    return c.err(value.span, "a multiple of pi is an angle, not a rate");
                }
                values.push((a, Poly::zero()));
                turns.push((a, k));
                continue;
            }
            let v = c.cx.unfold(&c.cx.scalar(value, c.base)?);
            if let Some(t) = v.atoms().into_iter().find(|t| t.is_time_dependent()) {
                return c.err(
                    value.span,
                    format!(
                        "an operating value is written in constants, found `{t}`: the steady motion's values are fixed"
                    ),
                );
            }
            values.push((a, v));
        }
        Ok(OperatingPoint { values, turns })
    }

    /// Whether no symbol is listed.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The value of the time symbol `a` (any order) at the operating
    /// point: listed, or zero as a rate of a listed symbol.
    pub fn value(&self, a: Atom) -> Option<Poly> {
        if let Some((_, v)) = self.values.iter().find(|(b, _)| *b == a) {
            return Some(v.clone());
        }
        self.values
            .iter()
            .any(|(b, _)| b.base() == a.base() && b.order() < a.order())
            .then(Poly::zero)
    }

    /// An angle given a multiple of π/2 that occurs in `p` outside sin
    /// and cos (q + π is no polynomial): the operations check what the
    /// file wrote with it, since a bare angle in their own expansions is
    /// already a deviation.
    pub fn outside_trig(&self, p: &Poly) -> Option<Atom> {
        p.atoms().into_iter().find(|a| {
            matches!(a.kind(), AtomKind::Var { time: true, .. })
                && self.turns.iter().any(|(q, _)| q == a)
        })
    }

    /// `p` in the deviations of the angles given a multiple of π/2 (and
    /// passing `which`): sin q → sin(q + k π/2), cos q likewise, exactly;
    /// the angle itself outside sin and cos is read as its deviation
    /// ([`OperatingPoint::outside_trig`] refuses it in what the file
    /// wrote).
    fn shifted(&self, p: &Poly, which: &dyn Fn(Atom) -> bool) -> Poly {
        let turned = |q: Atom| {
            self.turns
                .iter()
                .find(|(a, _)| *a == q && which(q))
                .map(|(_, k)| k.rem_euclid(4))
        };
        p.subst(&mut |a| {
            let (q, sin) = match a.kind() {
                AtomKind::Sin(q) => (q, true),
                AtomKind::Cos(q) => (q, false),
                _ => return None,
            };
            let k = turned(q)?;
            let (s, c) = (
                Poly::atom(Atom::sin(q).expect("an angle")),
                Poly::atom(Atom::cos(q).expect("an angle")),
            );
            // sin(q + k π/2) and cos(q + k π/2).
            Some(match (k, sin) {
                (0, true) | (3, false) => s,
                (0, false) | (1, true) => c,
                (1, false) | (2, true) => -&s,
                _ => -&c,
            })
        })
    }

    /// `p` at the operating point: each symbol with a value (and passing
    /// `which`) replaced, sin and cos of a listed angle too. `Err(a)` when
    /// the angle `a`'s value is neither 0, a multiple of π/2 nor a
    /// constant symbol, or its sine or cosine divides and vanishes there.
    pub fn at(&self, p: &Poly, which: &dyn Fn(Atom) -> bool) -> Result<Poly, Atom> {
        self.at_shifted(&self.shifted(p, which), which)
    }

    /// [`OperatingPoint::at`] of a `p` already in the deviations.
    fn at_shifted(&self, p: &Poly, which: &dyn Fn(Atom) -> bool) -> Result<Poly, Atom> {
        let mut bad = None;
        let out = p.subst(&mut |a| match a.kind() {
            AtomKind::Var { time: true, .. } if which(a) => self.value(a),
            AtomKind::Sin(q) | AtomKind::Cos(q) if q.is_time_dependent() && which(q) => {
                let v = self.value(q)?;
                let sin = matches!(a.kind(), AtomKind::Sin(_));
                if v.is_zero() {
                    return Some(if sin { Poly::zero() } else { Poly::one() });
                }
                match v.as_atom().filter(|b| b.is_angle()) {
                    Some(b) if sin => Some(Poly::atom(Atom::sin(b).expect("an angle"))),
                    Some(b) => Some(Poly::atom(Atom::cos(b).expect("an angle"))),
                    None => {
                        bad = Some(q);
                        None
                    }
                }
            }
            _ => None,
        });
        if let Some(q) = bad {
            return Err(q);
        }
        // A sine or cosine that vanishes where it divides stays an atom.
        let left = out.atoms().into_iter().find(|a| match a.kind() {
            AtomKind::Var { time: true, .. } => which(*a) && self.value(*a).is_some(),
            AtomKind::Sin(q) | AtomKind::Cos(q) => {
                q.is_time_dependent() && which(q) && self.value(q).is_some()
            }
            AtomKind::Var { .. } | AtomKind::Sum { .. } => false,
        });
        match left {
            Some(a) => Err(match a.kind() {
                AtomKind::Sin(q) | AtomKind::Cos(q) => q,
                _ => a,
            }),
            None => Ok(out),
        }
    }

    /// The first-order Taylor polynomial of `p` about the operating point
    /// in the symbols that have a value there and pass `which`:
    /// f(x₀) + Σ ∂f/∂x(x₀) (x − x₀). Other symbols are held as they are.
    pub fn first_order(&self, p: &Poly, which: &dyn Fn(Atom) -> bool) -> Result<Poly, Atom> {
        let p = &self.without_second_order(self.shifted(p, which), which);
        let mut vars: Vec<Atom> = Vec::new();
        for a in p.atoms() {
            let x = match a.kind() {
                AtomKind::Var { time: true, .. } => a,
                AtomKind::Sin(q) | AtomKind::Cos(q) if q.is_time_dependent() => q,
                _ => continue,
            };
            if which(x) && self.value(x).is_some() && !vars.contains(&x) {
                vars.push(x);
            }
        }
        let mut out = self.at_shifted(p, which)?;
        for x in vars {
            let dx = self.at_shifted(&p.partial(x), which)?;
            if dx.is_zero() {
                continue;
            }
            let x0 = self.value(x).expect("a value");
            out = &out + &(&dx * &(&Poly::atom(x) - &x0));
        }
        Ok(out)
    }
}

/// The fewest terms [`OperatingPoint::without_second_order`] looks for
/// negligible terms in.
const PRUNED_FROM: usize = 16;

/// How an atom of a polynomial stands at the operating point, for
/// [`OperatingPoint::without_second_order`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum AtPoint {
    /// Zero there: a symbol of value 0, the sine of an angle of value 0.
    Vanishes,
    /// Given another value there.
    Valued,
    /// Held as it is.
    Free,
}

impl OperatingPoint {
    /// `p` less the terms of second order in what vanishes at the
    /// operating point — two factors that are zero there, or one squared:
    /// the term and all its first derivatives are zero there, so it adds
    /// nothing to the first-order polynomial (the result is the same
    /// polynomial). The Taylor polynomial differentiates `p` once per
    /// symbol, and most terms of a body's acceleration about a steady
    /// motion are products of two small quantities (two rates, a rate and
    /// a lean): the linearised Kane equations of the nonlinear bicycle
    /// differentiated every one of them. A term dividing by an atom that
    /// has a value is kept (its error, or its inverse, is
    /// [`OperatingPoint::at_shifted`]'s), and `p` is kept whole when one
    /// of its angles has a value `at_shifted` refuses, or when it has a
    /// trigonometric denominator (a part of it need not be reduced).
    fn without_second_order(&self, p: Poly, which: &dyn Fn(Atom) -> bool) -> Poly {
        // A short polynomial is differentiated quickly: not worth sorting.
        if p.len() < PRUNED_FROM {
            return p;
        }
        let mut class: rustc_hash::FxHashMap<Atom, AtPoint> = Default::default();
        for a in p.atoms() {
            let (value, sin) = match a.kind() {
                AtomKind::Var { time: true, .. } if which(a) => (self.value(a), true),
                AtomKind::Sin(q) | AtomKind::Cos(q) if q.is_time_dependent() && which(q) => {
                    let v = self.value(q);
                    if let Some(v) = &v
                        && !v.is_zero()
                        && v.as_atom().filter(|b| b.is_angle()).is_none()
                    {
                        // `at_shifted` refuses this angle's value.
                        return p;
                    }
                    (v, matches!(a.kind(), AtomKind::Sin(_)))
                }
                _ => (None, false),
            };
            let c = match value {
                None => AtPoint::Free,
                Some(v) if v.is_zero() && sin => AtPoint::Vanishes,
                Some(_) => AtPoint::Valued,
            };
            class.insert(a, c);
        }
        if !class.values().any(|c| *c == AtPoint::Vanishes) {
            return p;
        }
        let negligible = |m: &crate::poly::Monomial| {
            let mut order = 0;
            for &(a, e) in m.factors() {
                match class[&a] {
                    AtPoint::Free => {}
                    _ if e < 0 => return false,
                    AtPoint::Vanishes => order += e,
                    AtPoint::Valued => {}
                }
            }
            order >= 2
        };
        if !p.terms().iter().any(|(m, _)| negligible(m)) {
            return p;
        }
        p.retain_terms(|m| !negligible(m)).unwrap_or(p)
    }
}

/// The angles a step's value is written in the deviation of: those its
/// own `kane(…, q = pi)` or `linearize(x, q = pi/2)` give a multiple k ≠ 0
/// of π/2, and those of the earlier steps it names (`earlier`, by step
/// name), in the order met, each with its k.
pub(crate) fn shifted_angles(
    ast: &Ast,
    earlier: &std::collections::HashMap<String, Vec<(String, i64)>>,
) -> Vec<(String, i64)> {
    fn walk(
        a: &Ast,
        earlier: &std::collections::HashMap<String, Vec<(String, i64)>>,
        out: &mut Vec<(String, i64)>,
    ) {
        let mut add = |name: &str, k: i64| {
            if !out.iter().any(|(n, _)| n == name) {
                out.push((name.to_owned(), k));
            }
        };
        match &a.kind {
            AstKind::Num(_) => {}
            AstKind::Name { name, .. } => {
                for (n, k) in earlier.get(name).into_iter().flatten() {
                    add(n, *k);
                }
            }
            AstKind::Call { func, args } => {
                if crate::derivation::ops::takes_operating_point(func) {
                    for r in args {
                        if let AstKind::Assign {
                            name,
                            primes: 0,
                            value,
                            ..
                        } = &r.kind
                            && let Some(k) = crate::derivation::ops::quarter_turns(value)
                            && k != 0
                        {
                            add(name, k);
                        }
                    }
                }
                for r in args {
                    walk(r, earlier, out);
                }
            }
            AstKind::Assign { value, .. } => walk(value, earlier, out),
            AstKind::Vector { items, .. } | AstKind::Add(items) | AstKind::Mul(items) => {
                for x in items {
                    walk(x, earlier, out);
                }
            }
            AstKind::Recip(x) | AstKind::Neg(x) | AstKind::Pow(x, _) | AstKind::Member(x, ..) => {
                walk(x, earlier, out)
            }
            AstKind::Cross(x, y) => {
                walk(x, earlier, out);
                walk(y, earlier, out);
            }
        }
    }
    let mut out = Vec::new();
    walk(ast, earlier, &mut out);
    out
}

/// What a printed step says of the angles it is written in the deviation
/// of (`shifted`, each with its multiple k of π/2, those the value holds):
/// "q stands for q − π, its deviation from the operating point".
pub(crate) fn deviation_note(shifted: &[(String, i64)]) -> String {
    let offset = |k: i64| -> String {
        let (sign, k) = if k < 0 { ("+", -k) } else { ("−", k) };
        let v = match (k % 2, k / 2) {
            (0, 1) => "π".to_owned(),
            (0, h) => format!("{h}π"),
            (_, 0) => "π/2".to_owned(),
            _ => format!("{k}π/2"),
        };
        format!("{sign} {v}")
    };
    let parts: Vec<String> = shifted
        .iter()
        .enumerate()
        .map(|(i, (q, k))| {
            if i == 0 {
                format!("{q} stands for {q} {}", offset(*k))
            } else {
                format!("{q} for {q} {}", offset(*k))
            }
        })
        .collect();
    let what = if shifted.len() == 1 {
        "its deviation"
    } else {
        "their deviations"
    };
    let list = match parts.as_slice() {
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
        [] => String::new(),
    };
    format!("{list}, {what} from the operating point")
}
