//! Symbol tables: which names are constants, which are functions of time,
//! and which are named abbreviations (ω_z := ψ̇ + φ̇ cos θ).
//!
//! A table turns source text into atoms: the parser knows only names, the
//! table knows what they mean, so `theta'` is an error for a constant and
//! an unknown name is reported at its span.
//!
//! # Example
//! ```
//! use hdot_sym::Symbols;
//! let s = Symbols::parse_decl(&["I_x", "I_y", "I_z"], &["omega_x", "omega_y", "omega_z"]);
//! let e = s.expr("I_x*omega_x' - (I_y - I_z)*omega_y*omega_z").unwrap();
//! assert_eq!(e.to_string(), "I_x*omega_x' - (I_y - I_z)*omega_y*omega_z");
//! assert!(s.expr("I_x'").is_err());
//! ```

use std::collections::HashMap;

use crate::atom::Atom;
use crate::expr::{Expr, Id, Node};
use crate::parse::{Ast, AstKind, ParseError, Span, parse};
use crate::poly::Poly;
use crate::rational::Rational;

/// What a declared name means.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Decl {
    /// A constant (`I_x`, `m`).
    Constant,
    /// A function of time (`omega_x`, `theta`).
    Time,
    /// A function of time that abbreviates a longer expression.
    Abbrev(Poly),
}

/// A table of declared symbols, in declaration order.
#[derive(Clone, Debug, Default)]
pub struct Symbols {
    decls: HashMap<String, Decl>,
    order: Vec<String>,
}

impl Symbols {
    /// An empty table.
    pub fn new() -> Symbols {
        Symbols::default()
    }

    /// A table of constants and time-dependent symbols (for examples and tests).
    pub fn parse_decl(constants: &[&str], time: &[&str]) -> Symbols {
        let mut s = Symbols::new();
        for c in constants {
            s.declare(c, Decl::Constant);
        }
        for t in time {
            s.declare(t, Decl::Time);
        }
        s
    }

    /// Declares `name`; returns false when it was already declared.
    pub fn declare(&mut self, name: &str, decl: Decl) -> bool {
        if self.decls.contains_key(name) {
            return false;
        }
        self.decls.insert(name.to_owned(), decl);
        self.order.push(name.to_owned());
        true
    }

    /// What `name` means, if declared.
    pub fn get(&self, name: &str) -> Option<&Decl> {
        self.decls.get(name)
    }

    /// Names in declaration order.
    pub fn names(&self) -> &[String] {
        &self.order
    }

    /// The atom for `name` with `primes` derivatives, or an error at `span`.
    pub fn atom(&self, name: &str, primes: u32, span: Span) -> Result<Atom, ParseError> {
        match self.decls.get(name) {
            Some(Decl::Constant) if primes > 0 => Err(ParseError {
                span,
                message: format!(
                    "`{name}` is a constant and has no time derivative; declare it under `time` if it varies"
                ),
            }),
            Some(Decl::Constant) => Ok(Atom::constant(name)),
            Some(Decl::Time | Decl::Abbrev(_)) => Ok(Atom::time(name, primes)),
            None => Err(ParseError {
                span,
                message: format!("unknown symbol `{name}`; declare it under [symbols]"),
            }),
        }
    }

    /// Parses a scalar expression into a tree, keeping its written shape.
    pub fn expr(&self, text: &str) -> Result<Expr, ParseError> {
        let ast = parse(text)?;
        let mut e = Expr::new();
        self.lower(&ast, &mut e)?;
        Ok(e)
    }

    /// Parses and expands a scalar expression to canonical form.
    pub fn poly(&self, text: &str) -> Result<Poly, ParseError> {
        Ok(self.expr(text)?.to_poly())
    }

    /// `sin(q)` / `cos(q)` of a declared angle.
    pub fn trig(&self, func: &str, args: &[Ast], span: Span) -> Result<Atom, ParseError> {
        let [arg] = args else {
            return Err(ParseError {
                span,
                message: format!("`{func}` takes exactly one argument"),
            });
        };
        let AstKind::Name { name, primes: 0 } = &arg.kind else {
            return Err(ParseError {
                span: arg.span,
                message: format!(
                    "`{func}` takes an angle: a symbol, or a sum of integer multiples of angle symbols and of pi/2, such as `{func}(theta)` or `{func}(q1 + q2)`"
                ),
            });
        };
        let q = self.atom(name, 0, arg.span)?;
        Ok(if func == "sin" {
            Atom::sin(q)
        } else {
            Atom::cos(q)
        }
        .expect("order-0 symbol"))
    }

    /// `sin(x)` / `cos(x)` as a polynomial: of a declared angle its atom,
    /// of a sum of integer multiples of angles and of π/2 (`cos(q1 + q2)`,
    /// `sin(2*theta)`) the addition formulas' expansion
    /// ([`crate::angle_sum`]).
    pub fn trig_poly(&self, func: &str, args: &[Ast], span: Span) -> Result<Poly, ParseError> {
        if let [arg] = args
            && !matches!(arg.kind, AstKind::Name { .. })
            && let Some(p) =
                crate::angle_sum::expand(func, arg, &|name, at| self.atom(name, 0, at))?
        {
            return Ok(p);
        }
        self.trig(func, args, span).map(Poly::atom)
    }

    /// A divisor `/d` (see [`Poly::inverse_divisor`]): each factor becomes
    /// a negative power. Returns the factor nodes.
    fn lower_divisor(&self, d: &Ast, e: &mut Expr) -> Result<Vec<Id>, ParseError> {
        let fail = || ParseError {
            span: d.span,
            message: crate::poly::DIVISOR_RULE.to_owned(),
        };
        // `/I` and `/I^2` keep their written shape.
        match &d.kind {
            AstKind::Name { .. } => {
                let mut tmp = Expr::new();
                self.lower(d, &mut tmp)?;
                if let Node::Atom(a) = tmp.node(tmp.root()).clone()
                    && !a.is_time_dependent()
                {
                    let id = e.push(Node::Atom(a));
                    return Ok(vec![e.push(Node::Pow(id, -1))]);
                }
                return Err(fail());
            }
            AstKind::Pow(b, k) if matches!(b.kind, AstKind::Name { .. }) && *k >= 1 => {
                let mut ids = self.lower_divisor(b, e)?;
                if let Some(Node::Pow(base, _)) = ids.first().map(|i| e.node(*i).clone()) {
                    ids = vec![e.push(Node::Pow(base, -(*k as i32)))];
                }
                return Ok(ids);
            }
            _ => {}
        }
        let mut tmp = Expr::new();
        self.lower(d, &mut tmp)?;
        let inv = tmp.to_poly().inverse_divisor().ok_or_else(fail)?;
        let (m, c) = &inv.terms()[0];
        let mut ids = Vec::new();
        if !c.is_one() {
            ids.push(e.num(c));
        }
        for (a, k) in m.sorted_for_print() {
            ids.push(e.atom_pow(a, k));
        }
        Ok(ids)
    }

    /// Lowers a scalar syntax tree into `e`, returning the new node.
    pub fn lower(&self, ast: &Ast, e: &mut Expr) -> Result<Id, ParseError> {
        let fail = |span: Span, m: &str| {
            Err(ParseError {
                span,
                message: m.to_owned(),
            })
        };
        Ok(match &ast.kind {
            AstKind::Num(r) => e.push(Node::Num(r.clone())),
            AstKind::Name { name, primes } => {
                let a = self.atom(name, *primes, ast.span)?;
                e.push(Node::Atom(a))
            }
            AstKind::Call { func, args } if func == "sin" || func == "cos" => {
                let p = self.trig_poly(func, args, ast.span)?;
                match p.as_atom() {
                    Some(a) => e.push(Node::Atom(a)),
                    None => e.poly_node(&p),
                }
            }
            AstKind::Call { func, .. } => {
                return fail(
                    ast.span,
                    &format!(
                        "`{func}(…)` is not a scalar function; scalars allow + - * / ^ sin cos"
                    ),
                );
            }
            AstKind::Add(items) => {
                let ids = items
                    .iter()
                    .map(|i| self.lower(i, e))
                    .collect::<Result<Vec<_>, _>>()?;
                e.push(Node::Add(ids))
            }
            AstKind::Mul(items) => {
                let mut ids = Vec::new();
                for it in items {
                    if let AstKind::Recip(d) = &it.kind {
                        ids.extend(self.lower_divisor(d, e)?);
                    } else {
                        ids.push(self.lower(it, e)?);
                    }
                }
                e.mul(ids)
            }
            AstKind::Neg(x) => {
                let id = self.lower(x, e)?;
                e.push(Node::Neg(id))
            }
            AstKind::Pow(b, n) => {
                let id = self.lower(b, e)?;
                match n {
                    0 => e.push(Node::Num(Rational::ONE)),
                    1 => id,
                    n => e.push(Node::Pow(id, i32::try_from(*n).unwrap_or(i32::MAX))),
                }
            }
            AstKind::Recip(_) => unreachable!("divisors occur only inside products"),
            AstKind::Vector { .. } | AstKind::Cross(..) => {
                return fail(ast.span, "a vector where a scalar is expected");
            }
            AstKind::Member(..) => {
                return fail(
                    ast.span,
                    "components are not available in a scalar expression",
                );
            }
            AstKind::Assign { name_span, .. } => {
                return fail(*name_span, "`name = value` is only allowed in subst(…)");
            }
        })
    }
}

// ---------------------------------------------------------------- Greek --

/// The Greek letters, one table for every printer and for prose: the
/// symbol name used in derivation files, its LaTeX, its Unicode letter.
/// `epsilon` prints as ε / `\varepsilon`, the form textbooks use.
pub const GREEK: &[(&str, &str, char)] = &[
    ("alpha", r"\alpha", 'α'),
    ("beta", r"\beta", 'β'),
    ("gamma", r"\gamma", 'γ'),
    ("delta", r"\delta", 'δ'),
    ("epsilon", r"\varepsilon", 'ε'),
    ("zeta", r"\zeta", 'ζ'),
    ("eta", r"\eta", 'η'),
    ("theta", r"\theta", 'θ'),
    ("iota", r"\iota", 'ι'),
    ("kappa", r"\kappa", 'κ'),
    ("lambda", r"\lambda", 'λ'),
    ("mu", r"\mu", 'μ'),
    ("nu", r"\nu", 'ν'),
    ("xi", r"\xi", 'ξ'),
    ("pi", r"\pi", 'π'),
    ("rho", r"\rho", 'ρ'),
    ("sigma", r"\sigma", 'σ'),
    ("tau", r"\tau", 'τ'),
    ("upsilon", r"\upsilon", 'υ'),
    ("phi", r"\phi", 'φ'),
    ("chi", r"\chi", 'χ'),
    ("psi", r"\psi", 'ψ'),
    ("omega", r"\omega", 'ω'),
    ("Gamma", r"\Gamma", 'Γ'),
    ("Delta", r"\Delta", 'Δ'),
    ("Theta", r"\Theta", 'Θ'),
    ("Lambda", r"\Lambda", 'Λ'),
    ("Xi", r"\Xi", 'Ξ'),
    ("Pi", r"\Pi", 'Π'),
    ("Sigma", r"\Sigma", 'Σ'),
    ("Upsilon", r"\Upsilon", 'Υ'),
    ("Phi", r"\Phi", 'Φ'),
    ("Psi", r"\Psi", 'Ψ'),
    ("Omega", r"\Omega", 'Ω'),
];

/// Unicode Greek characters that have no name of their own in [`GREEK`]:
/// variant forms, and capitals that look like Latin letters.
const GREEK_VARIANTS: &[(char, &str)] = &[
    ('ϵ', r"\epsilon"),
    ('ϑ', r"\vartheta"),
    ('ϰ', r"\varkappa"),
    ('µ', r"\mu"),
    ('ο', "o"),
    ('ϖ', r"\varpi"),
    ('ϱ', r"\varrho"),
    ('ς', r"\varsigma"),
    ('ϕ', r"\phi"),
    ('Α', "A"),
    ('Β', "B"),
    ('Ε', "E"),
    ('Ζ', "Z"),
    ('Η', "H"),
    ('Ι', "I"),
    ('Κ', "K"),
    ('Μ', "M"),
    ('Ν', "N"),
    ('Ο', "O"),
    ('Ρ', "P"),
    ('Τ', "T"),
    ('Χ', "X"),
];

/// The Greek entry of a symbol name: `omega` → (`\omega`, `ω`).
pub fn greek(name: &str) -> Option<(&'static str, char)> {
    GREEK.iter().find(|g| g.0 == name).map(|g| (g.1, g.2))
}

/// The LaTeX of a Greek character: `ω` → `\omega`, `ϑ` → `\vartheta`.
pub fn greek_latex(c: char) -> Option<&'static str> {
    if c.is_ascii() {
        return None;
    }
    GREEK
        .iter()
        .find(|g| g.2 == c)
        .map(|g| g.1)
        .or_else(|| GREEK_VARIANTS.iter().find(|g| g.0 == c).map(|g| g.1))
}

/// The name of a Greek character, for plain ASCII (PDF bookmarks).
pub fn greek_name(c: char) -> Option<&'static str> {
    GREEK.iter().find(|g| g.2 == c).map(|g| g.0).or_else(|| {
        GREEK_VARIANTS
            .iter()
            .find(|g| g.0 == c)
            .map(|g| g.1.trim_start_matches('\\').trim_start_matches("var"))
    })
}
