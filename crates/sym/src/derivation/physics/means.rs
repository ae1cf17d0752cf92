//! The `means` language: what a step (or a known) means, as an expression
//! over quantities measured on the particles — its vocabulary
//! ([`QUANTITIES`]: each quantity's name, arguments and shape), its tree
//! ([`Meaning`]) and its parser, which checks names, arguments and shapes
//! when the file loads. The numeric side (`hdot_num::verify`) evaluates a
//! [`Meaning`]; this file only reads it.
//!
//! Its interface to the rest of the engine is two functions: [`meaning`]
//! (a `means` string to a [`Meaning`]) and [`check_shape`] (a meaning
//! against the value of its step or known).

use toml::Spanned;

use super::Physics;
use super::check::{no_step_names, parse_spanned, unknown};
use crate::atom::Atom;
use crate::derivation::context::{Context, R};
use crate::derivation::value::Value;
use crate::parse::{Ast, AstKind};
use crate::poly::Poly;
use crate::rational::Rational;
use crate::symbols::Decl;
use crate::vector::Vec3;

/// The bodies a quantity is summed over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bodies {
    /// One body, by index.
    One(usize),
    /// All bodies together (`system`).
    System,
}

/// One argument of a quantity.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// A body or the system.
    Body(Bodies),
    /// A point, by name (a declared point or a body's centre).
    Point(String),
    /// A frame, by index.
    Frame(usize),
    /// A coordinate (a time symbol).
    Coordinate(Atom),
    /// A vector expression of the file's symbols (abbreviations unfolded)
    /// and the frame it is written in: an impulse F̂.
    Vector(Vec3, String),
}

/// The kind of an argument, for signatures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgKind {
    /// A body name or `system`.
    Body,
    /// A point.
    Point,
    /// A frame.
    Frame,
    /// A time symbol.
    Coordinate,
    /// A vector expression (`[F_x, F_y, F_z] in N`, or a step's name).
    Vector,
}

/// The shape of a quantity or a meaning.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A scalar.
    Scalar,
    /// A vector (compared in the frame of the step's value).
    Vector,
    /// A 3×3 matrix (compared in the frame its quantity names).
    Matrix,
    /// A list of this many scalars.
    List(usize),
}

impl Shape {
    pub(super) fn describe(self) -> String {
        match self {
            Shape::Scalar => "a scalar".into(),
            Shape::Vector => "a vector".into(),
            Shape::Matrix => "a matrix".into(),
            Shape::List(n) => format!("a list of {n}"),
        }
    }
}

/// The quantities that can be measured on the particles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Σ m.
    Mass,
    /// r_point − r_from.
    Position,
    /// ṙ of a point.
    Velocity,
    /// r̈ of a point.
    Acceleration,
    /// ω of a frame relative to N.
    AngularVelocity,
    /// α of a frame relative to N.
    AngularAcceleration,
    /// Σ m v.
    Momentum,
    /// Σ m a.
    Force,
    /// Σ m (r − r_P) × v.
    AngularMomentum,
    /// Σ m (r − r_P) × a.
    Moment,
    /// Σ ½ m v².
    KineticEnergy,
    /// Σ m (|ρ|² E − ρ ρᵀ) in a frame's axes.
    Inertia,
    /// Σ m g.
    Weight,
    /// Σ (r − r_P) × m g.
    WeightMoment,
    /// −Σ m g · (r − r_P).
    PotentialEnergy,
    /// Σ m a · ∂r/∂q.
    GeneralizedForce,
    /// Σ m v · ∂r/∂q (= ∂T/∂q̇).
    GeneralizedMomentum,
    /// Σ m g · ∂r/∂q.
    GeneralizedWeight,
    /// ṙ of the body's material point at a point's place.
    PointVelocity,
    /// r̈ of the body's material point at a point's place.
    PointAcceleration,
    /// v̄ of a body at rest just after an impulse F̂ at a point: the v̄ of
    /// the particle velocities v = v̄ + ω × (r − r_G) that satisfy
    /// Σ m v = F̂ and Σ m (r − r_G) × v = (r_P − r_G) × F̂.
    VelocityAfterImpulse,
    /// ω of a body at rest just after an impulse F̂ at a point (the same
    /// solve).
    AngularVelocityAfterImpulse,
}

/// The signature of a quantity: the single description of its name,
/// arguments and shape (the numeric side keys its particle sums by
/// [`Quantity`]).
#[derive(Clone, Copy, Debug)]
pub struct QuantitySig {
    /// Which quantity.
    pub quantity: Quantity,
    /// Its name in `means`.
    pub name: &'static str,
    /// Its arguments.
    pub args: &'static [ArgKind],
    /// Its shape.
    pub shape: Shape,
}

use ArgKind as K;
use Quantity as Q;
use Shape as S;

/// Every quantity, in the order of the docs table.
#[rustfmt::skip]
pub static QUANTITIES: &[QuantitySig] = &[
    sig(Q::Mass,                        "mass",                           &[K::Body],                      S::Scalar),
    sig(Q::Position,                    "position",                       &[K::Point, K::Point],           S::Vector),
    sig(Q::Velocity,                    "velocity",                       &[K::Point],                     S::Vector),
    sig(Q::Acceleration,                "acceleration",                   &[K::Point],                     S::Vector),
    sig(Q::AngularVelocity,             "angular_velocity",               &[K::Frame],                     S::Vector),
    sig(Q::AngularAcceleration,         "angular_acceleration",           &[K::Frame],                     S::Vector),
    sig(Q::Momentum,                    "momentum",                       &[K::Body],                      S::Vector),
    sig(Q::Force,                       "force",                          &[K::Body],                      S::Vector),
    sig(Q::AngularMomentum,             "angular_momentum",               &[K::Body, K::Point],            S::Vector),
    sig(Q::Moment,                      "moment",                         &[K::Body, K::Point],            S::Vector),
    sig(Q::KineticEnergy,               "kinetic_energy",                 &[K::Body],                      S::Scalar),
    sig(Q::Inertia,                     "inertia",                        &[K::Body, K::Point, K::Frame],  S::Matrix),
    sig(Q::Weight,                      "weight",                         &[K::Body],                      S::Vector),
    sig(Q::WeightMoment,                "weight_moment",                  &[K::Body, K::Point],            S::Vector),
    sig(Q::PotentialEnergy,             "potential_energy",               &[K::Body, K::Point],            S::Scalar),
    sig(Q::GeneralizedForce,            "generalized_force",              &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::GeneralizedMomentum,         "generalized_momentum",           &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::GeneralizedWeight,           "generalized_weight",             &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::PointVelocity,               "point_velocity",                 &[K::Body, K::Point],            S::Vector),
    sig(Q::PointAcceleration,           "point_acceleration",             &[K::Body, K::Point],            S::Vector),
    sig(Q::VelocityAfterImpulse,        "velocity_after_impulse",         &[K::Body, K::Point, K::Vector], S::Vector),
    sig(Q::AngularVelocityAfterImpulse, "angular_velocity_after_impulse", &[K::Body, K::Point, K::Vector], S::Vector),
];

const fn sig(
    quantity: Quantity,
    name: &'static str,
    args: &'static [ArgKind],
    shape: Shape,
) -> QuantitySig {
    QuantitySig {
        quantity,
        name,
        args,
        shape,
    }
}

impl Quantity {
    /// Its signature.
    pub fn sig(self) -> &'static QuantitySig {
        QUANTITIES
            .iter()
            .find(|s| s.quantity == self)
            .expect("every quantity has a signature")
    }

    /// Whether it needs `gravity`.
    pub fn needs_gravity(self) -> bool {
        matches!(
            self,
            Quantity::Weight
                | Quantity::WeightMoment
                | Quantity::PotentialEnergy
                | Quantity::GeneralizedWeight
        )
    }
}

/// What a step (or a known) means: an expression over quantities.
#[derive(Clone, Debug, PartialEq)]
pub enum Meaning {
    /// A measured quantity.
    Quantity(Quantity, Vec<Arg>),
    /// Σ cₖ Xₖ (rational factors; all terms of one shape).
    Sum(Vec<(Rational, Meaning)>),
    /// The component of a vector along a vector expression (scalar).
    Along(Box<Meaning>, Vec3, String),
    /// A list of scalar meanings.
    List(Vec<Meaning>),
    /// `solves(X)`: the step is a list of accelerations; X, evaluated with
    /// them, vanishes.
    Solves(Box<Meaning>),
    /// `mass_matrix(X, [q1'', …])`: the step is the n × n array whose
    /// column j is X at q̈ = e_j minus X at q̈ = 0.
    MassMatrix(Box<Meaning>, Vec<Atom>),
    /// `forcing(X, [q1'', …])`: the step is −X at q̈ = 0.
    Forcing(Box<Meaning>, Vec<Atom>),
    /// `applied(e)`: a scalar the file states (an applied torque or
    /// generalized force such as `M_a`), evaluated, not measured.
    Applied(Poly),
    /// `e * X`, `X / e`: a meaning times a scalar expression of the
    /// file's symbols (not a number: numbers go in [`Meaning::Sum`]).
    Scaled(Poly, Box<Meaning>),
    /// `linear(X)`: X to first order in the small symbols (its value at
    /// zero disturbance plus its first-order part).
    Linear(Box<Meaning>),
    /// `rate(e', X)`, `rate(e'', X)`: the derivative of the small symbol
    /// `e` (the atom carries the order) on the motion along which the
    /// first-order part of X vanishes, at the drawn disturbance.
    Rate(Atom, Box<Meaning>),
    /// `coefficient(X, e)`: the coefficient of the small symbol `e` (with
    /// its order) in the scalar X: ∂X/∂e at e = 0.
    Coefficient(Box<Meaning>, Atom),
    /// `sign(X)`: the sign (−1, 0, +1) of the scalar X.
    Sign(Box<Meaning>),
}

impl Meaning {
    /// Its shape.
    pub fn shape(&self) -> Shape {
        match self {
            Meaning::Quantity(q, _) => q.sig().shape,
            Meaning::Sum(terms) => terms[0].1.shape(),
            Meaning::Along(..)
            | Meaning::Applied(_)
            | Meaning::Rate(..)
            | Meaning::Coefficient(..)
            | Meaning::Sign(_) => Shape::Scalar,
            Meaning::List(items) => Shape::List(items.len()),
            Meaning::Solves(x)
            | Meaning::MassMatrix(x, _)
            | Meaning::Forcing(x, _)
            | Meaning::Scaled(_, x)
            | Meaning::Linear(x) => x.shape(),
        }
    }

    /// Every quantity it uses, with its arguments.
    pub fn quantities(&self) -> Vec<(Quantity, &[Arg])> {
        match self {
            Meaning::Quantity(q, a) => vec![(*q, a.as_slice())],
            Meaning::Sum(t) => t.iter().flat_map(|(_, m)| m.quantities()).collect(),
            Meaning::Along(m, ..)
            | Meaning::Solves(m)
            | Meaning::MassMatrix(m, _)
            | Meaning::Forcing(m, _)
            | Meaning::Scaled(_, m)
            | Meaning::Linear(m)
            | Meaning::Rate(_, m)
            | Meaning::Coefficient(m, _)
            | Meaning::Sign(m) => m.quantities(),
            Meaning::List(items) => items.iter().flat_map(Meaning::quantities).collect(),
            Meaning::Applied(_) => Vec::new(),
        }
    }
}

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

/// The functions that combine meanings (their docs and evaluation are
/// entries of `hdot_num::verify::means::COMBINATORS`).
pub const COMBINATORS: &[&str] = &[
    "list",
    "along",
    "applied",
    "solves",
    "mass_matrix",
    "forcing",
    "linear",
    "rate",
    "coefficient",
    "sign",
];

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
                    return self.err(ast, "applied(e) takes one scalar expression");
                };
                no_step_names(self.cx, e, self.base)?;
                let p = self.cx.scalar(e, self.base)?;
                Ok(Meaning::Applied(self.cx.unfold(&p)))
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
        }
    }
}

fn kind_name(k: ArgKind) -> &'static str {
    match k {
        ArgKind::Body => "body",
        ArgKind::Point => "point",
        ArgKind::Frame => "frame",
        ArgKind::Coordinate => "coordinate",
        ArgKind::Vector => "vector",
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
