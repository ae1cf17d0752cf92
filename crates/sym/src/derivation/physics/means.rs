//! The parser of the `means` language: a `means` string read into a
//! [`Meaning`] (names, arguments and shapes checked when the file loads,
//! reported at file:line:column), and a meaning checked against the value
//! of its step or known. The vocabulary it reads is `vocabulary.rs`.
//!
//! Its interface to the rest of the engine is two functions: [`meaning`]
//! (a `means` string to a [`Meaning`]) and [`check_shape`] (a meaning
//! against the value of its step or known).

use toml::Spanned;

use super::Physics;
use super::check::{no_step_names, parse_spanned, unknown};
use super::vocabulary::{Arg, ArgKind, Bodies, COMBINATORS, Meaning, QUANTITIES, Quantity, Shape};
use crate::atom::Atom;
use crate::derivation::context::{Context, R};
use crate::derivation::value::Value;
use crate::parse::{Ast, AstKind};
use crate::rational::Rational;
use crate::symbols::Decl;
use crate::vector::Vec3;

/// Whether `a` is (or contains) a meaning: a call of a quantity or of a
/// meaning's combinator.
fn is_meaning(a: &Ast) -> bool {
    match &a.kind {
        AstKind::Call { func, .. } => {
            COMBINATORS.contains(&func.as_str()) || QUANTITIES.iter().any(|s| s.name == func)
        }
        AstKind::Add(items) | AstKind::Mul(items) => items.iter().any(is_meaning),
        AstKind::Neg(x) | AstKind::Recip(x) => is_meaning(x),
        _ => false,
    }
}

/// The number of scalar equations of a meaning set to zero.
fn equations(m: &Meaning) -> usize {
    match m.shape() {
        Shape::Vector => 3,
        Shape::List(n) => n,
        Shape::Scalar => 1,
        Shape::Matrix => 0,
    }
}

pub(super) fn check_shape(
    cx: &Context<'_>,
    at: &Spanned<String>,
    m: &Meaning,
    value: &Value,
) -> R<()> {
    let ok = match (m, value) {
        (Meaning::MassMatrix(x, q), Value::Array(rows)) => {
            rows.len() == equations(x) && rows.iter().all(|r| r.len() == q.len())
        }
        (Meaning::Forcing(x, _), Value::List { items, .. }) => items.len() == equations(x),
        (Meaning::MassMatrix(..) | Meaning::Forcing(..), _) => false,
        (Meaning::Solves(x), Value::List { items, labels }) => {
            labels.len() == items.len() && equations(x) == items.len()
        }
        (Meaning::Solves(_), _) => false,
        (_, Value::Scalar(_)) => m.shape() == Shape::Scalar,
        (_, Value::Vector(..)) => m.shape() == Shape::Vector,
        (_, Value::Matrix(_)) => m.shape() == Shape::Matrix,
        (_, Value::List { items, .. }) => m.shape() == Shape::List(items.len()),
        (_, Value::Array(_)) => false,
    };
    if ok {
        return Ok(());
    }
    let n = at.get_ref().len();
    let msg = match m {
        Meaning::MassMatrix(x, q) => format!(
            "`mass_matrix(X, …)` means a {}×{} array; the step is {}",
            equations(x),
            q.len(),
            value.describe()
        ),
        Meaning::Forcing(x, _) => format!(
            "`forcing(X, …)` means a list of {}; the step is {}",
            equations(x),
            value.describe()
        ),
        Meaning::Solves(x) => format!(
            "`solves(X)` means a step `solve(X, [q1'', …])` giving one named acceleration per component of X ({}); the step is {}: solve for a list, e.g. `solve(eq, [phi''])` for a single equation",
            x.shape().describe(),
            value.describe()
        ),
        _ => format!(
            "the meaning is {}, but the step is {}",
            m.shape().describe(),
            value.describe()
        ),
    };
    Err(cx.diag_string(at, 0, n, msg))
}

/// Parses a meaning.
pub(super) fn meaning(cx: &Context<'_>, ph: &Physics, s: &Spanned<String>) -> R<Meaning> {
    let (ast, base) = parse_spanned(cx, s)?;
    let m = MeaningParser { cx, ph, base }.parse(&ast)?;
    if let Some(q) = m.quantities().iter().find(|(q, _)| q.needs_gravity())
        && ph.gravity.is_none()
    {
        return Err(cx.diag_string(
            s,
            0,
            s.get_ref().len(),
            format!(
                "`{}` needs `gravity` (top level, e.g. gravity = \"[0, 0, -g] in N\")",
                q.0.sig().name
            ),
        ));
    }
    Ok(m)
}

struct MeaningParser<'c, 'a> {
    cx: &'c Context<'a>,
    ph: &'c Physics,
    base: usize,
}

impl MeaningParser<'_, '_> {
    fn err<T>(&self, ast: &Ast, msg: impl Into<String>) -> R<T> {
        Err(self.cx.at(self.base, ast.span, msg))
    }

    fn parse(&self, ast: &Ast) -> R<Meaning> {
        match &ast.kind {
            AstKind::Add(items) => {
                let terms = items.iter().map(|t| self.term(t)).collect::<R<Vec<_>>>()?;
                let shape = terms[0].1.shape();
                if let Some((k, _)) = terms.iter().enumerate().find(|(_, t)| t.1.shape() != shape) {
                    return self.err(
                        &items[k],
                        format!(
                            "cannot add {} to {}",
                            terms[k].1.shape().describe(),
                            shape.describe()
                        ),
                    );
                }
                Ok(Meaning::Sum(terms))
            }
            AstKind::Neg(_) | AstKind::Mul(_) => {
                let t = self.term(ast)?;
                Ok(Meaning::Sum(vec![t]))
            }
            AstKind::Call { func, args } => self.call(ast, func, args),
            _ => self.err(
                ast,
                format!(
                    "expected a quantity such as moment(body, O); quantities: {}",
                    quantity_names()
                ),
            ),
        }
    }

    /// A term `c * X`, `-X`, `X / c`, `e * X`, `X / e` (c a number, e a
    /// scalar expression of the file's symbols).
    fn term(&self, ast: &Ast) -> R<(Rational, Meaning)> {
        match &ast.kind {
            AstKind::Neg(x) => {
                let (c, m) = self.term(x)?;
                Ok((-c, m))
            }
            AstKind::Mul(items) => {
                let mut c = Rational::ONE;
                let mut m = None;
                let mut factors = Vec::new();
                for it in items {
                    match &it.kind {
                        AstKind::Num(r) => c = &c * r,
                        AstKind::Recip(d) if is_meaning(d) => {
                            return self.err(it, "a meaning cannot divide");
                        }
                        _ if !is_meaning(it) => factors.push(it.clone()),
                        _ if m.is_none() => m = Some(self.parse(it)?),
                        _ => return self.err(it, "a meaning is a sum of quantities times factors"),
                    }
                }
                let Some(m) = m else {
                    return self.err(ast, "a number is not a quantity");
                };
                if factors.is_empty() {
                    return Ok((c, m));
                }
                let e = Ast {
                    kind: AstKind::Mul(factors),
                    span: ast.span,
                };
                no_step_names(self.cx, &e, self.base)?;
                let p = self.cx.unfold(&self.cx.scalar(&e, self.base)?);
                Ok(match p.as_constant() {
                    Some(k) => (&c * &k, m),
                    None => (c, Meaning::Scaled(p, Box::new(m))),
                })
            }
            _ => Ok((Rational::ONE, self.parse(ast)?)),
        }
    }

    /// The small symbol (with its order) named by `a`.
    fn small(&self, a: &Ast) -> R<Atom> {
        if self.ph.small.is_empty() {
            return self.err(
                a,
                "no symbol is declared small: add [symbols] small = [...]",
            );
        }
        let s = self.cx.symbol_arg(a, self.base)?;
        if !self.ph.small.contains(&s.base()) {
            let names: Vec<&str> = self.ph.small.iter().map(|x| x.name()).collect();
            return self.err(
                a,
                format!(
                    "`{}` is not declared small (small: {})",
                    s.name(),
                    names.join(", ")
                ),
            );
        }
        Ok(s)
    }

    fn call(&self, ast: &Ast, func: &str, args: &[Ast]) -> R<Meaning> {
        match func {
            "list" => {
                let items = args.iter().map(|a| self.parse(a)).collect::<R<Vec<_>>>()?;
                if let Some(k) = items.iter().position(|m| m.shape() != Shape::Scalar) {
                    return self.err(&args[k], "the items of list(…) are scalar meanings");
                }
                Ok(Meaning::List(items))
            }
            "along" => {
                if args.len() != 2 {
                    return self.err(
                        ast,
                        "along(X, e) takes a vector meaning and a vector expression",
                    );
                }
                let m = self.parse(&args[0])?;
                if m.shape() != Shape::Vector {
                    return self.err(&args[0], "along(X, e): X is a vector meaning");
                }
                no_step_names(self.cx, &args[1], self.base)?;
                let (v, f) = self.cx.vector(&args[1], self.base)?;
                Ok(Meaning::Along(Box::new(m), v, f))
            }
            "applied" => {
                let [e] = args else {
                    return self.err(ast, "applied(e) takes one scalar or vector expression");
                };
                no_step_names(self.cx, e, self.base)?;
                match self.cx.eval(e, self.base)? {
                    Value::Scalar(p) => Ok(Meaning::Applied(self.cx.unfold(&p))),
                    Value::Vector(v, f) => Ok(Meaning::AppliedVector(
                        Vec3(v.0.map(|c| self.cx.unfold(&c))),
                        f,
                    )),
                    v => self.err(
                        e,
                        format!(
                            "applied(e) takes a scalar or a vector expression, found {}",
                            v.describe()
                        ),
                    ),
                }
            }
            "solves" => {
                if args.len() != 1 {
                    return self.err(ast, "solves(X) takes one meaning");
                }
                let m = self.parse(&args[0])?;
                if matches!(m.shape(), Shape::Matrix) {
                    return self.err(&args[0], "solves(X): X is a vector, a scalar or a list");
                }
                Ok(Meaning::Solves(Box::new(m)))
            }
            "linear" => {
                let [x] = args else {
                    return self.err(ast, "linear(X) takes one meaning");
                };
                if self.ph.small.is_empty() {
                    return self.err(
                        ast,
                        "linear(X) is X to first order in the small symbols: declare them, [symbols] small = [...]",
                    );
                }
                Ok(Meaning::Linear(Box::new(self.parse(x)?)))
            }
            "rate" => self.rate(ast, args),
            "coefficient" => {
                let [x, e] = args else {
                    return self.err(
                        ast,
                        "coefficient(X, e) takes a scalar meaning and a small symbol",
                    );
                };
                let m = self.parse(x)?;
                if m.shape() != Shape::Scalar {
                    return self.err(x, "coefficient(X, e): X is a scalar meaning");
                }
                Ok(Meaning::Coefficient(Box::new(m), self.small(e)?))
            }
            "sign" => {
                let [x] = args else {
                    return self.err(ast, "sign(X) takes one scalar meaning");
                };
                let m = self.parse(x)?;
                if m.shape() != Shape::Scalar {
                    return self.err(x, "sign(X): X is a scalar meaning");
                }
                Ok(Meaning::Sign(Box::new(m)))
            }
            "mass_matrix" | "forcing" => self.matrix_form(ast, func, args),
            _ => self.quantity(ast, func, args),
        }
    }

    /// A measured quantity: `moment(body, O)`.
    fn quantity(&self, ast: &Ast, func: &str, args: &[Ast]) -> R<Meaning> {
        let Some(sig) = QUANTITIES.iter().find(|s| s.name == func) else {
            return self.err(
                ast,
                format!(
                    "unknown quantity `{func}`; quantities: {}, and {}",
                    quantity_names(),
                    COMBINATORS.join(", ")
                ),
            );
        };
        if args.len() != sig.args.len() {
            return self.err(
                ast,
                format!(
                    "`{func}` takes {} argument{} ({})",
                    sig.args.len(),
                    if sig.args.len() == 1 { "" } else { "s" },
                    arg_list(sig.args)
                ),
            );
        }
        let parsed = sig
            .args
            .iter()
            .zip(args)
            .map(|(k, a)| self.arg(*k, a))
            .collect::<R<Vec<_>>>()?;
        if matches!(
            sig.quantity,
            Quantity::PointVelocity | Quantity::PointAcceleration
        ) && parsed[0] == Arg::Body(Bodies::System)
        {
            return self.err(
                &args[0],
                format!("`{func}` is the motion of one body's point: name the body, not `system`"),
            );
        }
        if matches!(
            sig.quantity,
            Quantity::VelocityAfterImpulse | Quantity::AngularVelocityAfterImpulse
        ) && parsed[0] == Arg::Body(Bodies::System)
        {
            return self.err(
                &args[0],
                format!("`{func}` is the response of one free body: name the body, not `system`"),
            );
        }
        if let [Arg::Support(i)] = parsed.as_slice() {
            let s = &self.ph.supports[*i];
            let (forces, couples) = s.kind.unknowns();
            if sig.quantity == Quantity::Reaction && forces == 0 {
                return self.err(
                    &args[0],
                    format!(
                        "`{}` carries a couple and no force: its reaction is `reaction_couple({})`",
                        s.name, s.name
                    ),
                );
            }
            if sig.quantity == Quantity::ReactionCouple && couples == 0 {
                return self.err(
                    &args[0],
                    format!("`{}` carries no couple (only a clamp or a drive does): its reaction is `reaction({})`", s.name, s.name),
                );
            }
        }
        Ok(Meaning::Quantity(sig.quantity, parsed))
    }

    /// `rate(e', X)`.
    fn rate(&self, ast: &Ast, args: &[Ast]) -> R<Meaning> {
        let [e, x] = args else {
            return self.err(
                ast,
                "rate(e', X) takes a small symbol's derivative and the meaning whose first-order part vanishes",
            );
        };
        let s = self.small(e)?;
        if s.order() == 0 {
            return self.err(
                e,
                "rate(e', X): a derivative of a small symbol (e', e'', …)",
            );
        }
        let m = self.parse(x)?;
        let n = self.ph.small.len();
        if equations(&m) != n {
            return self.err(
                x,
                format!(
                    "rate(e', X): X = 0 gives the rates of the {n} small symbols, so X has {n} components; this is {}",
                    m.shape().describe()
                ),
            );
        }
        Ok(Meaning::Rate(s, Box::new(m)))
    }

    /// `mass_matrix(X, [q1'', …])` and `forcing(X, [q1'', …])`.
    fn matrix_form(&self, ast: &Ast, func: &str, args: &[Ast]) -> R<Meaning> {
        let unknowns = match args {
            [
                _,
                Ast {
                    kind: AstKind::Vector { items, frame: None },
                    ..
                },
            ] => items
                .iter()
                .map(|it| self.cx.symbol_arg(it, self.base))
                .collect::<R<Vec<_>>>()?,
            _ => {
                return self.err(
                    ast,
                    format!("{func}(X, [q1'', q2'', …]) takes a meaning and the accelerations"),
                );
            }
        };
        let m = self.parse(&args[0])?;
        if matches!(m.shape(), Shape::Matrix | Shape::Vector) {
            return self.err(&args[0], format!("{func}(X, …): X is a scalar or a list (the components of a vector with along(…))"));
        }
        Ok(if func == "forcing" {
            Meaning::Forcing(Box::new(m), unknowns)
        } else {
            Meaning::MassMatrix(Box::new(m), unknowns)
        })
    }

    fn arg(&self, kind: ArgKind, a: &Ast) -> R<Arg> {
        if kind == ArgKind::Vector {
            no_step_names(self.cx, a, self.base)?;
            let (v, f) = self.cx.vector(a, self.base)?;
            let v = Vec3(v.0.map(|c| self.cx.unfold(&c)));
            return Ok(Arg::Vector(v, f));
        }
        let AstKind::Name { name, primes } = &a.kind else {
            return self.err(a, format!("expected a {} name", kind_name(kind)));
        };
        let ph = self.ph;
        match kind {
            ArgKind::Support => match ph.supports.iter().position(|s| &s.name == name) {
                Some(i) if *primes == 0 => Ok(Arg::Support(i)),
                _ => {
                    let known: Vec<String> = ph.supports.iter().map(|s| s.name.clone()).collect();
                    if known.is_empty() {
                        self.err(
                            a,
                            format!("unknown support `{name}`: declare it with [[support]]"),
                        )
                    } else {
                        self.err(a, unknown("support", name, &known))
                    }
                }
            },
            ArgKind::Body => {
                if name == "system" && *primes == 0 {
                    return Ok(Arg::Body(Bodies::System));
                }
                match ph.bodies.iter().position(|b| &b.name == name) {
                    Some(i) if *primes == 0 => Ok(Arg::Body(Bodies::One(i))),
                    _ => {
                        let known: Vec<String> = ph
                            .bodies
                            .iter()
                            .map(|b| b.name.clone())
                            .chain(["system".to_owned()])
                            .collect();
                        if ph.bodies.is_empty() {
                            self.err(
                                a,
                                format!("unknown body `{name}`: declare it with [[body]]"),
                            )
                        } else {
                            self.err(a, unknown("body", name, &known))
                        }
                    }
                }
            }
            ArgKind::Point => {
                let known: Vec<String> = ph
                    .points
                    .iter()
                    .map(|p| p.name.clone())
                    .chain(ph.bodies.iter().filter_map(|b| b.centre.clone()))
                    .collect();
                if *primes == 0 && known.contains(name) {
                    Ok(Arg::Point(name.clone()))
                } else {
                    self.err(a, unknown("point", name, &known))
                }
            }
            ArgKind::Frame => match self.cx.frame_index(name) {
                Some(i) if *primes == 0 => Ok(Arg::Frame(i)),
                _ => {
                    let known: Vec<String> =
                        self.cx.frames.iter().map(|f| f.name.clone()).collect();
                    self.err(a, unknown("frame", name, &known))
                }
            },
            ArgKind::Vector => unreachable!("handled above"),
            ArgKind::Coordinate => match self.cx.symbols.get(name) {
                Some(Decl::Time) if *primes == 0 => Ok(Arg::Coordinate(Atom::time(name, 0))),
                _ => self.err(
                    a,
                    format!("`{name}` is not a coordinate: name a time symbol (without primes)"),
                ),
            },
            ArgKind::Speed => {
                let u = Atom::time(name, 0);
                if *primes == 0 && self.cx.speeds.speeds.contains(&u) {
                    Ok(Arg::Speed(u))
                } else {
                    let known: Vec<String> = self
                        .cx
                        .speeds
                        .speeds
                        .iter()
                        .map(ToString::to_string)
                        .collect();
                    self.err(
                        a,
                        unknown("generalized speed ([symbols] speeds)", name, &known),
                    )
                }
            }
        }
    }
}

fn kind_name(k: ArgKind) -> &'static str {
    match k {
        ArgKind::Body => "body",
        ArgKind::Point => "point",
        ArgKind::Frame => "frame",
        ArgKind::Coordinate => "coordinate",
        ArgKind::Speed => "speed",
        ArgKind::Vector => "vector",
        ArgKind::Support => "support",
    }
}

fn arg_list(args: &[ArgKind]) -> String {
    args.iter()
        .map(|k| kind_name(*k))
        .collect::<Vec<_>>()
        .join(", ")
}

fn quantity_names() -> String {
    QUANTITIES
        .iter()
        .map(|s| s.name)
        .collect::<Vec<_>>()
        .join(", ")
}
