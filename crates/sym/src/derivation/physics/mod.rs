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
//!
//! This file holds the model's types; the reading is split by job:
//! `declare.rs` reads a file's declarations in order (frames' motion,
//! gravity, names, knowns, `[motion]`), `bodies.rs` a `[[point]]` and a
//! `[[body]]` table, `centres.rs` a body's mass centre as a point,
//! `supports.rs` a `[[support]]` table, `vocabulary.rs` the `means`
//! language's quantities and its tree [`Meaning`], `means.rs`
//! its parser and `conditions.rs` a step's meaning with its conditions
//! (`given`, `symmetry`); `check.rs` holds the small checks they share.

mod bodies;
mod centres;
mod check;
mod conditions;
mod declare;
mod means;
mod supports;
mod vocabulary;

pub(crate) use conditions::{abbreviation_meaning, step_meaning};
pub(crate) use declare::declarations;
pub use vocabulary::{
    Arg, ArgKind, Bodies, COMBINATORS, Meaning, QUANTITIES, Quantity, QuantitySig, Shape,
};

use super::value::Value;
use crate::atom::Atom;
use crate::poly::Poly;
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
    /// The bodies' mass centres as points, where the file places them
    /// (`centres.rs`): `from` the reference point by `mass_centre`, or
    /// free for a body about its own centre. A centre that is also a
    /// `[[point]]` (at the same place) is in `points` only.
    pub centres: Vec<Point>,
    /// Declared bodies.
    pub bodies: Vec<Body>,
    /// Declared supports: what holds the bodies (`[[support]]`).
    pub supports: Vec<Support>,
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

impl Physics {
    /// The point `name`: a declared `[[point]]` (a contact point too) or a
    /// body's mass centre placed by its body.
    pub fn point(&self, name: &str) -> Option<&Point> {
        self.points
            .iter()
            .chain(&self.centres)
            .find(|p| p.name == name)
    }

    /// The names of every point [`Physics::point`] finds, for messages.
    pub fn point_names(&self) -> Vec<&str> {
        self.points
            .iter()
            .chain(&self.centres)
            .map(|p| p.name.as_str())
            .collect()
    }
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
    /// Its parent turned by `angle` about a hinge: `axis` is a unit vector
    /// of constants in the parent's components (`rotation = "about(k, q)"`).
    Hinge {
        /// Index of the parent frame.
        parent: usize,
        /// The hinge axis, parent's components.
        axis: crate::vector::Vec3,
        /// The angle symbol.
        angle: Atom,
    },
    /// Its parent turned by Euler parameters (`rotation =
    /// "quaternion(e_0, e_1, e_2, e_3)"`): the attitude is the frame's
    /// direction cosine matrix, quadratic in them, of unit norm.
    Quaternion {
        /// Index of the parent frame.
        parent: usize,
        /// The parameters, scalar part first.
        e: [Atom; 4],
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

/// A declared support: where and how a body is held. Its reaction is what
/// the verifier measures for `reaction(S)` and `reaction_couple(S)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Support {
    /// Its name (`reaction(name)`).
    pub name: String,
    /// One line.
    pub doc: String,
    /// Index of the body it holds.
    pub body: usize,
    /// The point it acts at (none for a drive, which is a couple).
    pub point: Option<String>,
    /// What it can carry.
    pub kind: SupportKind,
    /// The shaft's axis of a bearing or a drive, the floor's normal: a
    /// vector expression and the frame of its components.
    pub axis: Option<(Vec3, String)>,
}

/// What a support can carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SupportKind {
    /// A bearing on a shaft: a force across the axis, and along it too
    /// when `axial`.
    Bearing {
        /// It carries an axial force (a thrust bearing).
        axial: bool,
    },
    /// A ball-and-socket joint, or a fixed point (a top's tip): a force in
    /// every direction.
    Ball,
    /// A clamp (the body welded to the ground): a force and a couple in
    /// every direction.
    Clamp,
    /// A contact with the floor: a force along its normal, and across it
    /// too with `friction`.
    Floor {
        /// It carries friction (a rolling contact).
        friction: bool,
    },
    /// A drive (a motor) turning a shaft: a couple about the axis.
    Drive,
}

impl SupportKind {
    /// How many force and couple components it carries.
    pub fn unknowns(self) -> (usize, usize) {
        match self {
            SupportKind::Bearing { axial: false } => (2, 0),
            SupportKind::Bearing { axial: true } | SupportKind::Ball => (3, 0),
            SupportKind::Clamp => (3, 3),
            SupportKind::Floor { friction: false } => (1, 0),
            SupportKind::Floor { friction: true } => (3, 0),
            SupportKind::Drive => (0, 1),
        }
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
