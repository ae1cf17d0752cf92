//! The vocabulary of the `means` language: what can be measured on the
//! particles ([`QUANTITIES`]: each quantity's name, arguments and shape),
//! the functions that combine measurements ([`COMBINATORS`]) and the tree
//! a meaning is read into ([`Meaning`]). The parser is `means.rs`; the
//! numeric side (`hdot_num::verify`) evaluates the tree.

use crate::atom::Atom;
use crate::poly::Poly;
use crate::rational::Rational;
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
    /// A generalized speed (declared in `[symbols] speeds`).
    Speed(Atom),
    /// A vector expression of the file's symbols (abbreviations unfolded)
    /// and the frame it is written in: an impulse F̂.
    Vector(Vec3, String),
    /// A declared support, by index.
    Support(usize),
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
    /// A declared generalized speed.
    Speed,
    /// A vector expression (`[F_x, F_y, F_z] in N`, or a step's name).
    Vector,
    /// A declared support.
    Support,
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
    /// Σ m v · (a − g): the rate of the kinetic energy plus the weight's
    /// potential energy about a fixed point.
    EnergyRate,
    /// Σ m a · ∂r/∂q.
    GeneralizedForce,
    /// Σ m v · ∂r/∂q (= ∂T/∂q̇).
    GeneralizedMomentum,
    /// Σ m g · ∂r/∂q.
    GeneralizedWeight,
    /// ∂T/∂q with the rates held: T = Σ ½ m v² at neighbouring values of q.
    KineticEnergyPartial,
    /// Kane's generalized active force F_r: Σ m g · v_r over the particles
    /// and each `[[load]]`'s v_r · F or ω_r · T, with the constrained
    /// partial velocities v_r = ∂v/∂u_r (dependent speeds eliminated).
    GeneralizedActiveForce,
    /// Kane's generalized inertia force F_r* = −Σ m a · v_r.
    GeneralizedInertiaForce,
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
    /// The force a declared support exerts on its body: Σ m a less the
    /// weight, with Σ (r − r_O) × m a less the weight's moment,
    /// distributed over the body's supports by solving their equilibrium.
    Reaction,
    /// The couple a declared support (a clamp, a drive) exerts on its
    /// body, from the same solve.
    ReactionCouple,
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
    sig(Q::EnergyRate,                  "energy_rate",                    &[K::Body],                      S::Scalar),
    sig(Q::GeneralizedForce,            "generalized_force",              &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::GeneralizedMomentum,         "generalized_momentum",           &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::GeneralizedWeight,           "generalized_weight",             &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::KineticEnergyPartial,        "kinetic_energy_partial",         &[K::Body, K::Coordinate],       S::Scalar),
    sig(Q::GeneralizedActiveForce,      "generalized_active_force",       &[K::Body, K::Speed],            S::Scalar),
    sig(Q::GeneralizedInertiaForce,     "generalized_inertia_force",      &[K::Body, K::Speed],            S::Scalar),
    sig(Q::PointVelocity,               "point_velocity",                 &[K::Body, K::Point],            S::Vector),
    sig(Q::PointAcceleration,           "point_acceleration",             &[K::Body, K::Point],            S::Vector),
    sig(Q::VelocityAfterImpulse,        "velocity_after_impulse",         &[K::Body, K::Point, K::Vector], S::Vector),
    sig(Q::AngularVelocityAfterImpulse, "angular_velocity_after_impulse", &[K::Body, K::Point, K::Vector], S::Vector),
    sig(Q::Reaction,                    "reaction",                       &[K::Support],                   S::Vector),
    sig(Q::ReactionCouple,              "reaction_couple",                &[K::Support],                   S::Vector),
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

    /// Whether it is a reaction of a declared support (the weight enters
    /// it when the file declares `gravity`; it does not need it).
    pub fn is_reaction(self) -> bool {
        matches!(self, Quantity::Reaction | Quantity::ReactionCouple)
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
    /// `applied(e)` of a vector expression: a vector the file states (a
    /// rotor's momentum h in the body's axes, its gyroscopic torque),
    /// evaluated, not measured; its components and their frame.
    AppliedVector(Vec3, String),
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
            Meaning::AppliedVector(..) => Shape::Vector,
            Meaning::Solves(x)
            | Meaning::MassMatrix(x, _)
            | Meaning::Forcing(x, _)
            | Meaning::Scaled(_, x)
            | Meaning::Linear(x) => x.shape(),
        }
    }

    /// Every expression it holds (a vector argument's components, an
    /// applied expression, a scale factor), appended to `out`: what it
    /// reads of the motion besides its quantities.
    pub fn expressions<'m>(&'m self, out: &mut Vec<&'m Poly>) {
        match self {
            Meaning::Quantity(_, args) => {
                for a in args {
                    if let Arg::Vector(v, _) = a {
                        out.extend(&v.0);
                    }
                }
            }
            Meaning::Sum(terms) => terms.iter().for_each(|(_, x)| x.expressions(out)),
            Meaning::Along(x, v, _) => {
                out.extend(&v.0);
                x.expressions(out);
            }
            Meaning::List(xs) => xs.iter().for_each(|x| x.expressions(out)),
            Meaning::Applied(p) => out.push(p),
            Meaning::AppliedVector(v, _) => out.extend(&v.0),
            Meaning::Scaled(p, x) => {
                out.push(p);
                x.expressions(out);
            }
            Meaning::Solves(x)
            | Meaning::MassMatrix(x, _)
            | Meaning::Forcing(x, _)
            | Meaning::Linear(x)
            | Meaning::Rate(_, x)
            | Meaning::Coefficient(x, _)
            | Meaning::Sign(x) => x.expressions(out),
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
            Meaning::Applied(_) | Meaning::AppliedVector(..) => Vec::new(),
        }
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
