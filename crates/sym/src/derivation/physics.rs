//! The physical model a derivation declares: bodies, points, gravity,
//! what symbols stand for (`[[known]]`), conditions on the motion and what
//! a step means (`means`). Documented in `docs/derivation-format.md`,
//! section *Physics: bodies, points and what a step means*.
//!
//! Everything here is checked when the file loads — unknown bodies, points
//! and frames, a meaning whose shape differs from the step's value — and
//! reported at file:line:column. `hdot_num::verify` reads the result: it
//! draws bodies and motions from the declarations and compares every step
//! that has a meaning with particle sums.

use std::collections::HashSet;

use toml::Spanned;

use super::eval::{Context, R};
use super::raw::{RawBody, RawFile, RawKnown, RawPoint, RawStep};
use super::value::Value;
use crate::atom::{Atom, AtomKind};
use crate::parse::{Ast, AstKind};
use crate::poly::Poly;
use crate::rational::Rational;
use crate::symbols::Decl;
use crate::vector::{Mat3, Vec3};

/// The declarations of a file (all empty for a file without them).
#[derive(Clone, Debug, Default)]
pub struct Physics {
    /// The weight per unit mass and the frame of its components.
    pub gravity: Option<(Vec3, String)>,
    /// How each frame moves, parallel to the derivation's frames.
    pub frames: Vec<FrameMotion>,
    /// Declared points (not the bodies' centres).
    pub points: Vec<Point>,
    /// Declared bodies.
    pub bodies: Vec<Body>,
    /// What symbols stand for.
    pub knowns: Vec<Known>,
    /// Rules every motion satisfies (`[motion] given`).
    pub motion: Vec<Rule>,
    /// Quantities that vanish along every motion the rules allow
    /// (`[motion] vanishes`: a rolling contact's velocity), each with its
    /// text; the verifier measures them.
    pub vanishes: Vec<(Meaning, String)>,
    /// The symbols declared small (`[symbols] small`), in order: the
    /// disturbance `linear`, `rate` and `coefficient` are taken in.
    pub small: Vec<Atom>,
    /// What `[symbols] positive` declares positive (constants, sin or cos
    /// of an angle): the values the verifier draws respect it.
    pub positive: Vec<Atom>,
}

/// How a frame moves relative to its parent.
#[derive(Clone, Debug, PartialEq)]
pub enum FrameMotion {
    /// The inertial frame N (or a frame declared with zero angular velocity).
    Inertial,
    /// Its parent turned about the parent's axis `axis` by `angle`.
    Rotation {
        /// Index of the parent frame.
        parent: usize,
        /// 0, 1, 2 for the parent's first, second, third axis.
        axis: usize,
        /// The angle symbol.
        angle: Atom,
    },
    /// Given by its angular velocity (the frame's `omega`, own components);
    /// its attitude is free.
    AngularVelocity,
}

/// A declared point.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Its name.
    pub name: String,
    /// One line.
    pub doc: String,
    /// How it moves.
    pub kind: PointKind,
}

/// How a point moves.
#[derive(Clone, Debug, PartialEq)]
pub enum PointKind {
    /// It does not move; at the vector (a constant expression) from the
    /// origin of N.
    Fixed(Vec3, String),
    /// At the vector (components in the frame named) from the point `from`.
    From {
        /// The point it is measured from.
        from: String,
        /// The vector from `from`.
        at: Vec3,
        /// The frame of `at`'s components.
        frame: String,
    },
    /// It moves freely (the verifier draws its motion).
    Free,
}

/// The symmetry that makes a body's declared inertia form true.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Symmetry {
    /// None: all six components of the inertia tensor are free.
    None,
    /// The body axes are principal axes at the reference point.
    Principal,
    /// Axisymmetric about the body axis of this index, through the
    /// reference point.
    Axisymmetric(usize),
    /// Symmetric about the plane through the reference point whose normal
    /// is the body axis of this index.
    Plane(usize),
}

/// A declared body.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Its name.
    pub name: String,
    /// One line.
    pub doc: String,
    /// Index of the frame fixed in it.
    pub frame: usize,
    /// Its reference point: a declared point or its own centre.
    pub point: String,
    /// The name of its mass centre as a point (when it has one).
    pub centre: Option<String>,
    /// Its mass (an expression of constants), when the file names it.
    pub mass: Option<Poly>,
    /// G from the reference point, in the body frame's components (zero
    /// for a body about its centre; `None` when the file leaves it free).
    pub mass_centre: Option<Vec3>,
    /// The inertia tensor in the body axes, about the reference point, or
    /// about the centre when `inertia_about_centre`.
    pub inertia: Mat3,
    /// `inertia` is about the mass centre while the reference point is
    /// another point (`inertia_about = "G"`); `mass_centre` then places G
    /// from the reference point.
    pub inertia_about_centre: bool,
    /// The symmetry that makes `inertia`'s form true.
    pub symmetry: Symmetry,
}

impl Body {
    /// Whether the reference point is the body's own mass centre.
    pub fn about_centre(&self) -> bool {
        self.centre.as_deref() == Some(self.point.as_str())
    }
}

/// What symbols stand for: `value` is the measured `meaning`.
#[derive(Clone, Debug, PartialEq)]
pub struct Known {
    /// The value, in the declared symbols.
    pub value: Value,
    /// What it is.
    pub meaning: Meaning,
    /// The meaning as written.
    pub text: String,
}

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
    fn describe(self) -> String {
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

/// Every quantity, in the order of the docs table.
pub static QUANTITIES: &[QuantitySig] = &[
    sig(Quantity::Mass, "mass", &[K::Body], Shape::Scalar),
    sig(
        Quantity::Position,
        "position",
        &[K::Point, K::Point],
        Shape::Vector,
    ),
    sig(Quantity::Velocity, "velocity", &[K::Point], Shape::Vector),
    sig(
        Quantity::Acceleration,
        "acceleration",
        &[K::Point],
        Shape::Vector,
    ),
    sig(
        Quantity::AngularVelocity,
        "angular_velocity",
        &[K::Frame],
        Shape::Vector,
    ),
    sig(
        Quantity::AngularAcceleration,
        "angular_acceleration",
        &[K::Frame],
        Shape::Vector,
    ),
    sig(Quantity::Momentum, "momentum", &[K::Body], Shape::Vector),
    sig(Quantity::Force, "force", &[K::Body], Shape::Vector),
    sig(
        Quantity::AngularMomentum,
        "angular_momentum",
        &[K::Body, K::Point],
        Shape::Vector,
    ),
    sig(
        Quantity::Moment,
        "moment",
        &[K::Body, K::Point],
        Shape::Vector,
    ),
    sig(
        Quantity::KineticEnergy,
        "kinetic_energy",
        &[K::Body],
        Shape::Scalar,
    ),
    sig(
        Quantity::Inertia,
        "inertia",
        &[K::Body, K::Point, K::Frame],
        Shape::Matrix,
    ),
    sig(Quantity::Weight, "weight", &[K::Body], Shape::Vector),
    sig(
        Quantity::WeightMoment,
        "weight_moment",
        &[K::Body, K::Point],
        Shape::Vector,
    ),
    sig(
        Quantity::PotentialEnergy,
        "potential_energy",
        &[K::Body, K::Point],
        Shape::Scalar,
    ),
    sig(
        Quantity::GeneralizedForce,
        "generalized_force",
        &[K::Body, K::Coordinate],
        Shape::Scalar,
    ),
    sig(
        Quantity::GeneralizedMomentum,
        "generalized_momentum",
        &[K::Body, K::Coordinate],
        Shape::Scalar,
    ),
    sig(
        Quantity::GeneralizedWeight,
        "generalized_weight",
        &[K::Body, K::Coordinate],
        Shape::Scalar,
    ),
    sig(
        Quantity::PointVelocity,
        "point_velocity",
        &[K::Body, K::Point],
        Shape::Vector,
    ),
    sig(
        Quantity::PointAcceleration,
        "point_acceleration",
        &[K::Body, K::Point],
        Shape::Vector,
    ),
    sig(
        Quantity::VelocityAfterImpulse,
        "velocity_after_impulse",
        &[K::Body, K::Point, K::Vector],
        Shape::Vector,
    ),
    sig(
        Quantity::AngularVelocityAfterImpulse,
        "angular_velocity_after_impulse",
        &[K::Body, K::Point, K::Vector],
        Shape::Vector,
    ),
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

/// A condition on the motion: the symbol `target` (with its derivative
/// order: `q' = e` sets q̇, q̈, … to e, ė, …) takes `value`.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    /// The symbol and the derivative order the rule sets from.
    pub target: Atom,
    /// The value.
    pub value: RuleValue,
    /// The rule as written.
    pub text: String,
}

/// The right side of a rule.
#[derive(Clone, Debug, PartialEq)]
pub enum RuleValue {
    /// An expression of the declared symbols.
    Expr(Poly),
    /// A multiple of π/2 (an angle).
    QuarterTurns(i64),
}

/// What a step means and under which conditions, as checked at load.
#[derive(Clone, Debug, PartialEq)]
pub struct StepMeaning {
    /// The meaning.
    pub meaning: Meaning,
    /// The meaning as written.
    pub text: String,
    /// Conditions of this step (besides `[motion]`'s).
    pub given: Vec<Rule>,
    /// Free points at rest for this step (`O' = 0`): the name and the
    /// derivative order from which the point's motion vanishes.
    pub at_rest: Vec<(String, usize)>,
    /// Symmetries bodies have for this step (body index, symmetry), on top
    /// of their declared one.
    pub symmetry: Vec<(usize, Symmetry)>,
    /// Inequalities the drawn bodies satisfy for this step (`given =
    /// ["A > B"]`): each as `lhs − rhs`, positive, with its text. They
    /// select a class of bodies (A the largest moment) for a verdict.
    pub bounds: Vec<(Poly, String)>,
    /// The step's conditions as written (`given = [...]`, `symmetry =
    /// {...}`), for reports; empty without conditions.
    pub conditions: String,
}

/// The frame's rotation (axis, angle) when its matrix is a rotation about
/// one axis of its parent.
fn rotation_of(m: &Mat3) -> Option<(usize, Atom)> {
    (0..3).find_map(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        match m.0[j][i].as_atom()?.kind() {
            AtomKind::Sin(q) => Some((k, q)),
            _ => None,
        }
    })
}

/// Parses a spanned string; the AST and the byte offset of its contents.
fn parse_spanned(cx: &Context<'_>, s: &Spanned<String>) -> R<(Ast, usize)> {
    let base = cx.content_start(s);
    Ok((cx.parse_at(s.get_ref(), base)?, base))
}

/// Reads the declarations of `raw` (after its symbols and frames).
pub(crate) fn declarations(cx: &Context<'_>, raw: &RawFile) -> R<Physics> {
    let mut ph = Physics {
        small: cx.small.clone(),
        positive: cx.positive.clone(),
        ..Physics::default()
    };
    for f in &cx.frames {
        ph.frames.push(match &f.parent {
            Some((p, m)) => {
                let (axis, angle) = rotation_of(m).expect("frames turn about one axis");
                FrameMotion::Rotation {
                    parent: cx.frame_index(p).expect("parent exists"),
                    axis,
                    angle,
                }
            }
            None if f.omega.is_zero() => FrameMotion::Inertial,
            None => FrameMotion::AngularVelocity,
        });
    }
    if let Some(g) = &raw.gravity {
        let (ast, base) = parse_spanned(cx, g)?;
        let (v, f) = cx.vector(&ast, base)?;
        constant(cx, &v, g, "gravity")?;
        ph.gravity = Some((v, f));
    }
    let mut names: HashSet<String> = HashSet::new();
    let taken = |names: &mut HashSet<String>, s: &Spanned<String>, what: &str| -> R<()> {
        let n = s.get_ref();
        let valid = n.chars().next().is_some_and(char::is_alphabetic)
            && n.chars().all(|c| c.is_alphanumeric() || c == '_');
        if !valid {
            return Err(cx.diag_string(
                s,
                0,
                n.len(),
                format!("`{n}` is not a valid {what} name (letters, digits, _)"),
            ));
        }
        if n == "system" || !names.insert(n.clone()) || cx.frame_index(n).is_some() {
            return Err(cx.diag_string(
                s,
                0,
                n.len(),
                format!("`{n}` is already the name of a point, a body or a frame"),
            ));
        }
        Ok(())
    };
    for p in &raw.points {
        taken(&mut names, &p.name, "point")?;
    }
    let one_body = raw.bodies.len() == 1;
    let mut centres = Vec::new();
    for b in &raw.bodies {
        taken(&mut names, &b.name, "body")?;
        let centre = match &b.centre {
            Some(c) => {
                taken(&mut names, c, "point")?;
                Some(c.get_ref().clone())
            }
            None if one_body && !names.contains("G") => {
                names.insert("G".into());
                Some("G".into())
            }
            None => None,
        };
        centres.push(centre);
    }
    let point_names: Vec<String> = raw
        .points
        .iter()
        .map(|p| p.name.get_ref().clone())
        .chain(centres.iter().flatten().cloned())
        .collect();
    let known_point = |s: &Spanned<String>| -> R<String> {
        let n = s.get_ref();
        if point_names.contains(n) {
            Ok(n.clone())
        } else {
            Err(cx.diag_string(s, 0, n.len(), unknown("point", n, &point_names)))
        }
    };
    for p in &raw.points {
        ph.points.push(point(cx, p, &known_point)?);
    }
    // A point measured from another must not lead back to itself.
    for p in &raw.points {
        let mut at = p.name.get_ref().clone();
        for _ in 0..=ph.points.len() {
            match ph.points.iter().find(|q| q.name == at).map(|q| &q.kind) {
                Some(PointKind::From { from, .. }) => at = from.clone(),
                _ => break,
            }
            if &at == p.name.get_ref() {
                let n = at.len();
                return Err(cx.diag_string(
                    &p.name,
                    0,
                    n,
                    "this point is measured from itself (through `from`)",
                ));
            }
        }
    }
    for (b, centre) in raw.bodies.iter().zip(centres) {
        ph.bodies.push(body(cx, b, centre, &known_point)?);
    }
    for k in &raw.knowns {
        ph.knowns.push(known(cx, &ph, k)?);
    }
    if let Some(m) = &raw.motion {
        for r in &m.given {
            ph.motion.push(rule(cx, r)?);
        }
        for v in &m.vanishes {
            let m = meaning(cx, &ph, v)?;
            if !matches!(m.shape(), Shape::Scalar | Shape::Vector) {
                let n = v.get_ref().len();
                return Err(cx.diag_string(
                    v,
                    0,
                    n,
                    format!(
                        "`vanishes` takes a scalar or vector quantity; this is {}",
                        m.shape().describe()
                    ),
                ));
            }
            ph.vanishes.push((m, v.get_ref().clone()));
        }
    }
    Ok(ph)
}

fn unknown(what: &str, name: &str, known: &[String]) -> String {
    if known.is_empty() {
        format!("unknown {what} `{name}`: none is declared")
    } else {
        format!("unknown {what} `{name}` (declared: {})", known.join(", "))
    }
}

/// Checks `v` uses constants only.
fn constant(cx: &Context<'_>, v: &Vec3, at: &Spanned<String>, key: &str) -> R<()> {
    if v.0
        .iter()
        .any(|p| p.atoms().iter().any(|a| a.is_time_dependent()))
    {
        let n = at.get_ref().len();
        return Err(cx.diag_string(
            at,
            0,
            n,
            format!("`{key}` must be an expression of constants"),
        ));
    }
    Ok(())
}

fn point(
    cx: &Context<'_>,
    p: &RawPoint,
    known_point: &dyn Fn(&Spanned<String>) -> R<String>,
) -> R<Point> {
    let fixed = p.fixed.as_ref().is_some_and(|f| *f.get_ref());
    let at = match &p.at {
        Some(a) => {
            let (ast, base) = parse_spanned(cx, a)?;
            Some(cx.vector(&ast, base)?)
        }
        None => None,
    };
    let kind = match (fixed, &p.from, at) {
        (true, Some(f), _) => {
            let n = f.get_ref().len();
            return Err(cx.diag_string(f, 0, n, "a fixed point is at `at` from the origin of N; `from` is for a point that moves with others"));
        }
        (true, None, Some((v, f))) => {
            constant(cx, &v, p.at.as_ref().expect("at"), "at")?;
            if cx.frame(&f).parent.is_some() || !cx.frame(&f).omega.is_zero() {
                let a = p.at.as_ref().expect("at");
                return Err(cx.diag_string(
                    a,
                    0,
                    a.get_ref().len(),
                    "a fixed point's `at` is in the components of an inertial frame (`in N`)",
                ));
            }
            PointKind::Fixed(v, f)
        }
        (true, None, None) => PointKind::Fixed(Vec3::zero(), "N".into()),
        (false, Some(from), Some((at, frame))) => PointKind::From {
            from: known_point(from)?,
            at,
            frame,
        },
        (false, Some(f), None) => {
            let n = f.get_ref().len();
            return Err(cx.diag_string(f, 0, n, "`from` needs `at`, the vector from that point"));
        }
        (false, None, Some(_)) => {
            let a = p.at.as_ref().expect("at");
            return Err(cx.diag_string(
                a,
                0,
                a.get_ref().len(),
                "`at` needs `from` (or `fixed = true`)",
            ));
        }
        (false, None, None) => PointKind::Free,
    };
    Ok(Point {
        name: p.name.get_ref().clone(),
        doc: p.doc.clone(),
        kind,
    })
}

fn body(
    cx: &Context<'_>,
    b: &RawBody,
    centre: Option<String>,
    known_point: &dyn Fn(&Spanned<String>) -> R<String>,
) -> R<Body> {
    let frames: Vec<String> = cx.frames.iter().map(|f| f.name.clone()).collect();
    let frame = cx.frame_index(b.frame.get_ref()).ok_or_else(|| {
        cx.diag_string(
            &b.frame,
            0,
            b.frame.get_ref().len(),
            unknown("frame", b.frame.get_ref(), &frames),
        )
    })?;
    let point = match &b.point {
        Some(p) => known_point(p)?,
        None => match &centre {
            Some(c) => c.clone(),
            None => {
                let n = b.name.get_ref().len();
                return Err(cx.diag_string(&b.name, 0, n, "say the body's reference point with `point` (or name its centre with `centre`)"));
            }
        },
    };
    let mass = match &b.mass {
        None => None,
        Some(s) => {
            let mass = cx.scalar_in(s)?;
            if mass.atoms().iter().any(|a| a.is_time_dependent()) || mass.is_zero() {
                let n = s.get_ref().len();
                return Err(cx.diag_string(
                    s,
                    0,
                    n,
                    "`mass` is a non-zero expression of constants",
                ));
            }
            Some(mass)
        }
    };
    let own = &cx.frames[frame].name;
    let mass_centre = match &b.mass_centre {
        Some(s) => {
            let (ast, base) = parse_spanned(cx, s)?;
            let (v, f) = cx.vector(&ast, base)?;
            if &f != own {
                return Err(cx.at(
                    base,
                    ast.span,
                    format!("`mass_centre` is given in the body frame's components (`in {own}`)"),
                ));
            }
            constant(cx, &v, s, "mass_centre")?;
            if centre.as_deref() == Some(point.as_str()) && !v.is_zero() {
                return Err(cx.at(
                    base,
                    ast.span,
                    "the reference point is the mass centre, so `mass_centre` is zero",
                ));
            }
            Some(v)
        }
        None if centre.as_deref() == Some(point.as_str()) => Some(Vec3::zero()),
        // G wherever the drawn body has it (no step may use its position).
        None => None,
    };
    let inertia_about_centre = match &b.inertia_about {
        None => false,
        Some(a) if Some(a.get_ref()) == centre.as_ref() => {
            if mass_centre.is_none() {
                return Err(cx.diag_string(
                    a,
                    0,
                    a.get_ref().len(),
                    "with the inertia about the centre, `mass_centre` says where the centre is from the reference point",
                ));
            }
            centre.as_deref() != Some(point.as_str())
        }
        Some(a) if a.get_ref() == &point => false,
        Some(a) => {
            return Err(cx.diag_string(
                a,
                0,
                a.get_ref().len(),
                format!(
                    "`inertia_about` is the reference point ({point}) or the body's centre ({})",
                    centre
                        .as_deref()
                        .unwrap_or("unnamed: name it with `centre`")
                ),
            ));
        }
    };
    let (ast, base) = parse_spanned(cx, &b.inertia)?;
    let inertia = match cx.eval(&ast, base)? {
        Value::Matrix(m) => m,
        v => {
            return Err(cx.at(
                base,
                ast.span,
                format!(
                    "`inertia` is a matrix, such as principal(A, B, C); found {}",
                    v.describe()
                ),
            ));
        }
    };
    if inertia
        .0
        .iter()
        .flatten()
        .any(|p| p.atoms().iter().any(|a| a.is_time_dependent()))
    {
        return Err(cx.at(
            base,
            ast.span,
            "`inertia` must be an expression of constants",
        ));
    }
    if !inertia.is_symmetric() {
        return Err(cx.at(base, ast.span, "an inertia tensor is symmetric"));
    }
    let symmetry = match &b.symmetry {
        None => Symmetry::None,
        Some(s) => symmetry(cx, s, &cx.frames[frame].axes)?,
    };
    Ok(Body {
        name: b.name.get_ref().clone(),
        doc: b.doc.clone(),
        frame,
        point,
        centre,
        mass,
        mass_centre,
        inertia,
        inertia_about_centre,
        symmetry,
    })
}

fn symmetry(cx: &Context<'_>, s: &Spanned<String>, axes: &[String; 3]) -> R<Symmetry> {
    let text = s.get_ref();
    let words: Vec<&str> = text.split_whitespace().collect();
    let axis = |a: &str| axes.iter().position(|x| x == a);
    let sym = match words.as_slice() {
        ["none"] => Some(Symmetry::None),
        ["principal"] => Some(Symmetry::Principal),
        ["axisymmetric", a] => axis(a).map(Symmetry::Axisymmetric),
        ["plane", p] => {
            let ks: Vec<usize> = axes
                .iter()
                .enumerate()
                .filter(|(_, a)| p.contains(a.as_str()))
                .map(|(k, _)| k)
                .collect();
            let joined = |i: usize, j: usize| format!("{}{}", axes[i], axes[j]);
            match ks.as_slice() {
                [i, j] if *p == joined(*i, *j) || *p == joined(*j, *i) => {
                    Some(Symmetry::Plane(3 - i - j))
                }
                _ => None,
            }
        }
        _ => None,
    };
    sym.ok_or_else(|| {
        cx.diag_string(
            s,
            0,
            text.len(),
            format!(
                "expected `none`, `principal`, `axisymmetric {z}` (an axis of the body frame: {a}) or `plane {x}{y}`",
                z = axes[2],
                x = axes[0],
                y = axes[1],
                a = axes.join(", ")
            ),
        )
    })
}

fn known(cx: &Context<'_>, ph: &Physics, k: &RawKnown) -> R<Known> {
    let (ast, base) = parse_spanned(cx, &k.value)?;
    let value = cx.eval(&ast, base)?;
    if !matches!(
        value,
        Value::Scalar(_) | Value::Vector(..) | Value::Matrix(_)
    ) {
        return Err(cx.at(
            base,
            ast.span,
            format!(
                "a known's value is a scalar, a vector or a matrix, found {}",
                value.describe()
            ),
        ));
    }
    let meaning = meaning(cx, ph, &k.means)?;
    check_shape(cx, &k.means, &meaning, &value)?;
    Ok(Known {
        value,
        meaning,
        text: k.means.get_ref().clone(),
    })
}

/// Reads a step's `means` and `given` and checks the meaning's shape
/// against the step's value.
pub(crate) fn step_meaning(
    cx: &Context<'_>,
    ph: &Physics,
    s: &RawStep,
    value: &Value,
) -> R<Option<StepMeaning>> {
    let Some(means) = &s.means else {
        if let Some(g) = s.given.first() {
            let n = g.get_ref().len();
            return Err(cx.diag_string(
                g,
                0,
                n,
                "`given` is the condition of a step's `means`; this step has none",
            ));
        }
        if let Some(t) = &s.symmetry {
            let span = t.span();
            return Err(cx.diag(
                span.start,
                span.end,
                "`symmetry` is the condition of a step's `means`; this step has none",
            ));
        }
        return Ok(None);
    };
    let meaning = meaning(cx, ph, means)?;
    check_shape(cx, means, &meaning, value)?;
    let mut given = Vec::new();
    let mut at_rest = Vec::new();
    let mut bounds = Vec::new();
    for r in &s.given {
        if r.get_ref().contains(['<', '>']) {
            bounds.push(bound(cx, r)?);
            continue;
        }
        match point_at_rest(cx, ph, r)? {
            Some(p) => at_rest.push(p),
            None => given.push(rule(cx, r)?),
        }
    }
    let mut conditions = Vec::new();
    if !s.given.is_empty() {
        let items: Vec<String> = s
            .given
            .iter()
            .map(|g| format!("{:?}", g.get_ref()))
            .collect();
        conditions.push(format!("given = [{}]", items.join(", ")));
    }
    if let Some(t) = &s.symmetry {
        let items: Vec<String> = t
            .get_ref()
            .iter()
            .map(|(k, v)| format!("{k} = {:?}", v.get_ref()))
            .collect();
        conditions.push(format!("symmetry = {{{}}}", items.join(", ")));
    }
    let mut symmetry = Vec::new();
    for (name, sym) in s.symmetry.iter().flat_map(|t| t.get_ref()) {
        let table = s.symmetry.as_ref().expect("present");
        let Some(i) = ph.bodies.iter().position(|b| &b.name == name) else {
            let known: Vec<String> = ph.bodies.iter().map(|b| b.name.clone()).collect();
            let span = table.span();
            return Err(cx.diag(span.start, span.end, unknown("body", name, &known)));
        };
        symmetry.push((
            i,
            self::symmetry(cx, sym, &cx.frames[ph.bodies[i].frame].axes)?,
        ));
    }
    Ok(Some(StepMeaning {
        meaning,
        text: means.get_ref().clone(),
        given,
        at_rest,
        symmetry,
        bounds,
        conditions: conditions.join(", "),
    }))
}

/// Parses an inequality `a > b` or `a < b` of the file's symbols into
/// `a − b` (or `b − a`), positive.
fn bound(cx: &Context<'_>, s: &Spanned<String>) -> R<(Poly, String)> {
    let text = s.get_ref();
    let base = cx.content_start(s);
    let bad = |msg: &str| cx.diag_string(s, 0, text.len(), msg);
    let Some(i) = text.find(['<', '>']) else {
        return Err(bad("expected an inequality `a > b`"));
    };
    if text[i + 1..].contains(['<', '>', '=']) || text[..i].contains('=') {
        return Err(bad(
            "a class of bodies is given by strict inequalities, one per item: `A > B`, `B > C`",
        ));
    }
    let side = |from: usize, to: usize| -> R<Poly> {
        let ast = cx.parse_at(&text[from..to], base + from)?;
        no_step_names(cx, &ast, base + from)?;
        Ok(cx.unfold(&cx.scalar(&ast, base + from)?))
    };
    let (lhs, rhs) = (side(0, i)?, side(i + 1, text.len())?);
    if lhs
        .atoms()
        .into_iter()
        .chain(rhs.atoms())
        .any(Atom::is_time_dependent)
    {
        return Err(bad(
            "an inequality selects a class of bodies: it is written in constants (the moments A, B, C), not functions of time",
        ));
    }
    let p = if text.as_bytes()[i] == b'>' {
        &lhs - &rhs
    } else {
        &rhs - &lhs
    };
    Ok((p, text.clone()))
}

/// Refuses a step's name inside a meaning's arguments or a condition:
/// they are written in the file's symbols (a step would bring its derived
/// value into what it is compared with).
fn no_step_names(cx: &Context<'_>, ast: &Ast, base: usize) -> R<()> {
    let mut err = None;
    walk(ast, &mut |a| {
        if let AstKind::Name { name, .. } = &a.kind
            && err.is_none()
            && cx.is_step(name)
        {
            err = Some(cx.at(
                base,
                a.span,
                format!(
                    "`{name}` is a step: a meaning's arguments and a step's conditions are written in the file's symbols (write what the step stands for, e.g. the impulse's components), so that the derived result is not compared with itself"
                ),
            ));
        }
    });
    err.map_or(Ok(()), Err)
}

/// Calls `f` on `a` and every node below it.
fn walk(a: &Ast, f: &mut dyn FnMut(&Ast)) {
    f(a);
    match &a.kind {
        AstKind::Num(_) | AstKind::Name { .. } => {}
        AstKind::Call { args, .. } => args.iter().for_each(|x| walk(x, f)),
        AstKind::Assign { value, .. } => walk(value, f),
        AstKind::Vector { items, .. } | AstKind::Add(items) | AstKind::Mul(items) => {
            items.iter().for_each(|x| walk(x, f))
        }
        AstKind::Recip(x) | AstKind::Neg(x) | AstKind::Pow(x, _) | AstKind::Member(x, ..) => {
            walk(x, f)
        }
        AstKind::Cross(x, y) => {
            walk(x, f);
            walk(y, f)
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

/// The functions that combine meanings.
const COMBINATORS: &[&str] = &[
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

fn check_shape(cx: &Context<'_>, at: &Spanned<String>, m: &Meaning, value: &Value) -> R<()> {
    let ok = match (m, value) {
        (Meaning::MassMatrix(x, q), Value::Array(rows)) => {
            rows.len() == equations(x) && rows.iter().all(|r| r.len() == q.len())
        }
        (Meaning::Forcing(x, _), Value::List { items, .. }) => items.len() == equations(x),
        (Meaning::MassMatrix(..) | Meaning::Forcing(..), _) => false,
        (Meaning::Solves(x), Value::List { items, labels }) => {
            let n = match x.shape() {
                Shape::Vector => 3,
                Shape::List(n) => n,
                Shape::Scalar => 1,
                Shape::Matrix => 0,
            };
            labels.len() == items.len() && n == items.len()
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
fn meaning(cx: &Context<'_>, ph: &Physics, s: &Spanned<String>) -> R<Meaning> {
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
                return Ok(Meaning::List(items));
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
                return Ok(Meaning::Along(Box::new(m), v, f));
            }
            "applied" => {
                let [e] = args else {
                    return self.err(ast, "applied(e) takes one scalar expression");
                };
                no_step_names(self.cx, e, self.base)?;
                let p = self.cx.scalar(e, self.base)?;
                return Ok(Meaning::Applied(self.cx.unfold(&p)));
            }
            "solves" => {
                if args.len() != 1 {
                    return self.err(ast, "solves(X) takes one meaning");
                }
                let m = self.parse(&args[0])?;
                if matches!(m.shape(), Shape::Matrix) {
                    return self.err(&args[0], "solves(X): X is a vector, a scalar or a list");
                }
                return Ok(Meaning::Solves(Box::new(m)));
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
                return Ok(Meaning::Linear(Box::new(self.parse(x)?)));
            }
            "rate" => {
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
                let k = match m.shape() {
                    Shape::Vector => 3,
                    Shape::Scalar => 1,
                    Shape::List(k) => k,
                    Shape::Matrix => 0,
                };
                if k != n {
                    return self.err(
                        x,
                        format!(
                            "rate(e', X): X = 0 gives the rates of the {n} small symbols, so X has {n} components; this is {}",
                            m.shape().describe()
                        ),
                    );
                }
                return Ok(Meaning::Rate(s, Box::new(m)));
            }
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
                return Ok(Meaning::Coefficient(Box::new(m), self.small(e)?));
            }
            "sign" => {
                let [x] = args else {
                    return self.err(ast, "sign(X) takes one scalar meaning");
                };
                let m = self.parse(x)?;
                if m.shape() != Shape::Scalar {
                    return self.err(x, "sign(X): X is a scalar meaning");
                }
                return Ok(Meaning::Sign(Box::new(m)));
            }
            "mass_matrix" | "forcing" => {
                let unknowns =
                    match args {
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
                        _ => return self.err(
                            ast,
                            format!(
                                "{func}(X, [q1'', q2'', …]) takes a meaning and the accelerations"
                            ),
                        ),
                    };
                let m = self.parse(&args[0])?;
                if matches!(m.shape(), Shape::Matrix | Shape::Vector) {
                    return self.err(&args[0], format!("{func}(X, …): X is a scalar or a list (the components of a vector with along(…))"));
                }
                return Ok(if func == "forcing" {
                    Meaning::Forcing(Box::new(m), unknowns)
                } else {
                    Meaning::MassMatrix(Box::new(m), unknowns)
                });
            }
            _ => {}
        }
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

/// `P' = 0` (`P'' = 0`, …) for a point P that the verifier moves freely:
/// the point's velocity (acceleration, …) vanishes. `None` when the
/// condition is not about a point.
fn point_at_rest(
    cx: &Context<'_>,
    ph: &Physics,
    s: &Spanned<String>,
) -> R<Option<(String, usize)>> {
    let Some((lhs, rhs)) = s.get_ref().split_once('=') else {
        return Ok(None);
    };
    let name = lhs.trim().trim_end_matches('\'');
    let order = lhs.trim().len() - name.len();
    let declared = ph.points.iter().find(|p| p.name == name);
    let centre = ph.bodies.iter().find(|b| b.centre.as_deref() == Some(name));
    if declared.is_none() && centre.is_none() {
        return Ok(None);
    }
    let n = s.get_ref().len();
    if order == 0 || rhs.trim() != "0" {
        return Err(cx.diag_string(
            s,
            0,
            n,
            format!("a condition on point {name} is `{name}' = 0` (at rest) or `{name}'' = 0` (no acceleration)"),
        ));
    }
    let free = match (declared, centre) {
        (Some(p), _) => p.kind == PointKind::Free,
        (None, Some(b)) => b.about_centre(),
        (None, None) => false,
    };
    if !free {
        return Err(cx.diag_string(
            s,
            0,
            n,
            format!("point {name} moves as its declaration says; only a point that moves freely (a `[[point]]` without `fixed` or `from`, or the centre of a body about its centre) can be set at rest"),
        ));
    }
    Ok(Some((name.to_owned(), order)))
}

/// Parses a rule `q = e`, `q' = e`, `q = pi/2`.
fn rule(cx: &Context<'_>, s: &Spanned<String>) -> R<Rule> {
    // Parsed as the argument of a call, where `name = value` is allowed.
    let base = cx.content_start(s);
    let wrapped = format!("f({})", s.get_ref());
    let shifted = base.wrapping_sub(2);
    let ast = crate::parse::parse(&wrapped).map_err(|e| cx.at(shifted, e.span, e.message))?;
    let bad = || {
        cx.diag_string(
            s,
            0,
            s.get_ref().len(),
            "a condition is written `q = e`, `q' = e` or `q = pi/2`, q a time symbol",
        )
    };
    let AstKind::Call { args, .. } = &ast.kind else {
        return Err(bad());
    };
    let [arg] = args.as_slice() else {
        return Err(bad());
    };
    let AstKind::Assign {
        name,
        primes,
        name_span,
        value,
    } = &arg.kind
    else {
        return Err(bad());
    };
    if !matches!(cx.symbols.get(name), Some(Decl::Time)) {
        return Err(cx.at(
            shifted,
            *name_span,
            format!("`{name}` is not a time symbol: a condition sets a coordinate or a rate"),
        ));
    }
    let target = Atom::time(name, *primes);
    let value = match super::ops::quarter_turns(value) {
        Some(t) if *primes == 0 => RuleValue::QuarterTurns(t),
        Some(_) => {
            return Err(cx.at(
                shifted,
                value.span,
                "a multiple of pi is an angle, not a rate",
            ));
        }
        None => {
            no_step_names(cx, value, shifted)?;
            let p = cx.scalar(value, shifted)?;
            if p.atoms()
                .iter()
                .any(|a| a.base() == target.base() && a.order() >= *primes)
            {
                return Err(cx.at(
                    shifted,
                    value.span,
                    format!("the value of `{name}` cannot depend on it"),
                ));
            }
            RuleValue::Expr(cx.unfold(&p))
        }
    };
    Ok(Rule {
        target,
        value,
        text: s.get_ref().clone(),
    })
}
