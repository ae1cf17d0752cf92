//! Scenes (TOML) and worked problems: mass properties, the resultant
//! force and moment a motion requires, impulses, and named unknowns.
//!
//! The format is documented in `docs/scenes.md` (what moves: `g`,
//! `[[body]]`, `[[cloud]]`, shared with `hdot simulate`, read by [`bodies`])
//! and `docs/cli-numeric.md` (the problem); in short:
//!
//! ```toml
//! name = "rod on a vertical axle"
//! g = [0.0, -9.81, 0.0]          # optional: adds each body's weight at its G
//! reference = [0.0, 0.0, 0.0]    # point O for H_O, inertia_O and moments
//!
//! [[body]]
//! shape = "rod"                  # rod plate prism disk cylinder hollow_cylinder
//! length = 2.0                   # ring sphere spherical_shell cone
//! mass = 3.0                     # or weight = 29.43 (needs g)
//! position = [0.5, 0.8, 0.0]     # of the body's G
//! rotation = { x_axis = [0.5, 0.8, 0.0] }  # or { z_axis = [...] },
//!                                # { axis = [...], angle_deg = 30 }, { euler_angles = [φ, θ, ψ] }
//!
//! [motion]                       # instantaneous motion (or [impulse])
//! omega = [0.0, 15.0, 0.0]
//! alpha = [0.0, 0.0, 0.0]        # or frame_rate = Ω: α = Ω × ω
//! fixed_point = [0.0, 0.0, 0.0]  # or v_g / a_g
//!
//! [[force]]                      # known: value; unknown: direction or unknown = ["x", "z"]
//! name = "T"
//! point = [1.0, 1.6, 0.0]
//! direction = [-1.0, 0.0, 0.0]
//! ```

//!
//! The reader is split by what it reads: `read` holds the place of
//! a value and the checks every value passes, `bodies` the schema every
//! scene shares, `problem` the worked problem, `dynamics` what it yields.

use std::path::{Path, PathBuf};

use nalgebra::{Rotation3, Vector3};

use crate::body::Composite;
use crate::sums::Motion;

mod bodies;
mod dynamics;
mod problem;
mod read;

pub use bodies::{Bodies, Group, RawBodies, RawBody, RawCloud, bodies, bodies_from};
pub use dynamics::{CHECK_DISCRETIZATION, DynamicsReport, InertiaReport};
pub use read::unit_of;

/// A scene file that cannot be used, with where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {field}: {message}", crate::error::at(file, *line))]
pub struct SceneError {
    /// The scene file.
    pub file: PathBuf,
    /// 1-based line (of the offending table or value; 0 if unknown).
    pub line: usize,
    /// The field, e.g. `body[2].mass`.
    pub field: String,
    /// What is wrong.
    pub message: String,
}

/// A force (or impulse) or couple: known, or with unknown parts.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// Name (unknown scalars are named after it).
    pub name: String,
    /// Point of application (unused for couples).
    pub point: Vector3<f64>,
    /// Known part of the vector.
    pub known: Vector3<f64>,
    /// Unknown scalars: name and the unit direction they act along.
    pub unknowns: Vec<(String, Vector3<f64>)>,
}

/// What the scene asks.
#[derive(Debug, Clone, PartialEq)]
pub enum Problem {
    /// Mass properties only.
    Statics,
    /// An instantaneous motion: the external loads it requires.
    Motion(Motion),
    /// An impact: velocities after it from impulse–momentum.
    Impulse {
        /// v̄ before.
        v_before: Vector3<f64>,
        /// ω before.
        omega_before: Vector3<f64>,
    },
}

/// A kinematic constraint of an impulse problem: the velocity after the
/// impact of the body point at `point`, along `direction`, equals `value`.
#[derive(Debug, Clone, PartialEq)]
pub struct Constraint {
    /// Name of the equation.
    pub name: String,
    /// Body point.
    pub point: Vector3<f64>,
    /// Unit direction.
    pub direction: Vector3<f64>,
    /// Prescribed velocity component.
    pub value: f64,
}

/// A parsed, validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Title.
    pub name: String,
    /// Free text.
    pub description: String,
    /// The rigid body (all bodies and clouds together).
    pub body: Composite,
    /// Gravity, if given.
    pub g: Option<Vector3<f64>>,
    /// Reference point O.
    pub reference: Vector3<f64>,
    /// What is asked.
    pub problem: Problem,
    /// Forces (impulses in an impulse problem), weight not included.
    pub forces: Vec<Load>,
    /// Couples.
    pub couples: Vec<Load>,
    /// Constraints (impulse problems).
    pub constraints: Vec<Constraint>,
}

impl Scene {
    /// Reads and validates a scene file.
    pub fn from_path(path: &Path) -> Result<Self, SceneError> {
        let text = hdot_sym::textfile::read(path).map_err(|e| SceneError {
            file: path.to_path_buf(),
            line: e.line_column().map_or(0, |(l, _)| l),
            field: "-".into(),
            message: match e.line_column() {
                Some((_, c)) => format!("column {c}: {}", e.message),
                None => e.message,
            },
        })?;
        Self::from_str_at(path, &text)
    }
}

/// Rotation helper for scene builders and tests: the rotation taking
/// local x onto `dir`.
pub fn x_axis_to(dir: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(&Vector3::x(), dir)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI))
}
