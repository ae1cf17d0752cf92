//! Scenes: TOML files describing a body, its supports and its initial
//! motion. The format is documented in `docs/simulation.md`; what moves
//! (`g`, `[[body]]`, `[[cloud]]`) is the schema every scene shares,
//! `docs/scenes.md`, parsed with the rest of the scene and read by
//! [`hdot_num::scene::bodies_from`]. Every scene
//! bundled in `docs/examples/sim-*.toml` is an example of it.
//!
//! ```toml
//! name = "torque-free asymmetric body"
//! kind = "free"                        # free | heavy-top | fixed-axis | derived
//! t_end = 100.0
//! [[body]]                             # or shape = "prism", a = 1, b = 2, c = 3; several make a composite
//! principal_moments = [0.6, 0.8, 1.0]
//! mass = 1.0
//! [initial]
//! attitude = [1.0, 0.0, 0.0, 0.0]      # unit quaternion (w, x, y, z); or euler_angles = [φ, θ, ψ]
//! angular_momentum = [1.8, 0.4, -0.9]  # in the tables' axes; or angular_velocity = [...]
//! ```

use std::path::{Path, PathBuf};

use hdot_num::scene::Bodies;
use nalgebra::{Quaternion, Rotation3, UnitQuaternion, Vector3};

use crate::exact::SteadyTop;
use crate::systems::Shaft;
use crate::{PrincipalMoments, SimError};

mod bind;
mod derived;
mod holds;
mod raw;
mod resolve;
mod rigid;
mod shaft;
mod text;

pub use derived::DerivedScene;
pub use holds::{Pivot, Rigid};
use raw::{OwnTables, RawScene};
pub use resolve::{Resolve, resolve_near};
use text::{at_line_after, line_of};

/// Relative residual of §7's relation under which a heavy top counts as
/// being in steady precession.
pub const STEADY_TOL: f64 = 1e-12;

/// A validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Display name.
    pub name: String,
    /// Free text.
    pub description: String,
    /// File it was read from (for messages).
    pub file: PathBuf,
    /// Default end time.
    pub t_end: f64,
    /// What moves and how it is supported.
    pub kind: SceneKind,
    /// A free body's or heavy top's body frame in the axes of its
    /// `[[body]]` tables (what a drawing of the tables turns with).
    pub body_frame: Option<BodyFrame>,
    /// What moves (`g`, `[[body]]`, `[[cloud]]`), as read once with the
    /// rest of the scene (`hdot_num::scene::bodies_from`).
    pub bodies: Bodies,
}

/// The body frame of a free body or heavy top, in the tables' axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyFrame {
    /// Its origin: the mass centre G, or the pivot O of a heavy top.
    pub origin: Vector3<f64>,
    /// Its axes (the columns) in the tables' axes: a point `p` of the
    /// tables is at `axesᵀ (p − origin)` in the body frame.
    pub axes: Rotation3<f64>,
}

/// The three kinds of scene.
#[derive(Debug, Clone)]
pub enum SceneKind {
    /// No force, no support: motion about the mass centre.
    Free {
        /// Principal moments about G.
        moments: PrincipalMoments,
        /// Initial attitude.
        q0: UnitQuaternion<f64>,
        /// Initial body angular velocity.
        w0: Vector3<f64>,
    },
    /// A body on a fixed point O under gravity, G on body axis 3.
    HeavyTop {
        /// Principal moments about O.
        moments: PrincipalMoments,
        /// Weight × distance O→G.
        weight_arm: f64,
        /// Initial attitude.
        q0: UnitQuaternion<f64>,
        /// Initial body angular velocity.
        w0: Vector3<f64>,
        /// The steady precession it starts in, if it does (§7).
        steady: Option<SteadyTop>,
    },
    /// A shaft in two bearings driven by a motor.
    FixedAxis {
        /// The shaft.
        shaft: Shaft,
        /// Initial angle and rate.
        y0: [f64; 2],
    },
    /// The equations of motion a derivation file derived.
    Derived(Box<DerivedScene>),
}

/// The error of a scene's text that does not parse: an error of the
/// scene's own tables as the parser's message, one of the shared tables
/// (`g`, `[[body]]`, `[[cloud]]`) as the bodies reader reports it (with its
/// line and field, and the former `[body]` table named).
fn parse_failure(text: &str, file: &Path, e: toml::de::Error) -> SimError {
    let parse = |e: toml::de::Error| SimError::Parse {
        file: file.to_path_buf(),
        message: e.to_string(),
    };
    if let Err(own) = toml::from_str::<OwnTables>(text) {
        return parse(own);
    }
    match hdot_num::scene::bodies(file, text) {
        Err(shared) => shared.into(),
        Ok(_) => parse(e),
    }
}

impl Scene {
    /// The largest rate of the scene's motion, `|ω₀|` (`|ω|` of a shaft,
    /// the largest `|q̇|` of a derived scene).
    pub fn rate_scale(&self) -> f64 {
        match &self.kind {
            SceneKind::Free { w0, .. } | SceneKind::HeavyTop { w0, .. } => w0.norm(),
            SceneKind::FixedAxis { y0, .. } => y0[1].abs(),
            SceneKind::Derived(ds) => {
                let (n, base) = (ds.model.dof(), ds.model.carried_base());
                ds.y0[n..base].iter().fold(0.0, |m: f64, v| m.max(v.abs()))
            }
        }
    }
}

impl SceneKind {
    /// The `kind` string of the file.
    pub fn name(&self) -> &'static str {
        match self {
            SceneKind::Free { .. } => "free",
            SceneKind::HeavyTop { .. } => "heavy-top",
            SceneKind::FixedAxis { .. } => "fixed-axis",
            SceneKind::Derived(_) => "derived",
        }
    }
}

/// Checks an attitude quaternion: finite and of unit norm to `1e-12`.
pub fn unit_attitude(q: [f64; 4], field: &str) -> Result<UnitQuaternion<f64>, SimError> {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(n.is_finite() && (n - 1.0).abs() <= 1e-12) {
        return Err(SimError::NonUnitAttitude {
            field: field.to_string(),
            norm: n,
        });
    }
    Ok(UnitQuaternion::from_quaternion(Quaternion::new(
        q[0], q[1], q[2], q[3],
    )))
}

/// # Construction
impl Scene {
    /// Reads and validates a scene file; a derived scene's derivation is
    /// found by [`resolve_near`].
    pub fn from_file(path: &Path) -> Result<Scene, SimError> {
        Scene::from_file_with(path, &|name| resolve_near(path, name))
    }

    /// [`Scene::from_file`] with the derivation of a derived scene found
    /// by `resolve` (the command line also knows the bundled ones).
    pub fn from_file_with(path: &Path, resolve: Resolve<'_>) -> Result<Scene, SimError> {
        let text = hdot_sym::textfile::read(path).map_err(|e| match (e.io, e.line_column()) {
            (Some(kind), _) => SimError::Io {
                file: path.to_path_buf(),
                source: std::io::Error::new(kind, e.message),
            },
            (None, Some((l, c))) => SimError::Parse {
                file: path.to_path_buf(),
                message: format!("line {l}, column {c}: {}", e.message),
            },
            (None, None) => SimError::Parse {
                file: path.to_path_buf(),
                message: e.message,
            },
        })?;
        Scene::parse_with(&text, path, resolve)
    }

    /// Parses and validates scene text; `file` names it in messages.
    pub fn parse(text: &str, file: &Path) -> Result<Scene, SimError> {
        Scene::parse_with(text, file, &|name| resolve_near(file, name))
    }

    /// [`Scene::parse`] with a resolver for a derived scene's derivation.
    /// An error of a field the scene writes names its line (one place for
    /// every kind of scene: the checks name the field).
    pub fn parse_with(text: &str, file: &Path, resolve: Resolve<'_>) -> Result<Scene, SimError> {
        Scene::parse_fields(text, file, resolve).map_err(|e| match e {
            SimError::BadField {
                file,
                field,
                message,
            } if !message.starts_with("line ") => {
                let message = match text::line_of_field(text, &field) {
                    Some(n) => format!("line {n}: {message}"),
                    None => message,
                };
                SimError::BadField {
                    file,
                    field,
                    message,
                }
            }
            e => e,
        })
    }

    fn parse_fields(text: &str, file: &Path, resolve: Resolve<'_>) -> Result<Scene, SimError> {
        let mut raw: RawScene = toml::from_str(text).map_err(|e| parse_failure(text, file, e))?;
        let shared = raw.shared();
        let bad = |field: &str, message: String| bad_field(file, field, message);
        if !(raw.t_end.is_finite() && raw.t_end > 0.0) {
            return Err(bad(
                "t_end",
                format!("must be positive and finite, got {}", raw.t_end),
            ));
        }
        let initial = raw.initial.unwrap_or_default();
        let derived_fields = [
            ("derivation", raw.derivation.is_some()),
            ("constants", raw.constants.is_some()),
            ("inputs", raw.inputs.is_some()),
            ("initial.coordinates", initial.coordinates.is_some()),
            ("initial.rates", initial.rates.is_some()),
        ];
        if raw.kind != "derived"
            && let Some((field, _)) = derived_fields.iter().find(|(_, set)| *set)
        {
            return Err(bad(
                field,
                format!("only a scene of kind \"derived\" takes `{field}`"),
            ));
        }
        let mut body_frame = None;
        let (kind, bodies) = match raw.kind.as_str() {
            "free" | "heavy-top" => {
                let heavy = raw.kind == "heavy-top";
                let (kind, frame, bodies) =
                    rigid::read(raw.top, shared, &initial, heavy, file, text)?;
                body_frame = Some(frame);
                (kind, bodies)
            }
            "fixed-axis" => shaft::read(raw.shaft, raw.motor, shared, &initial, file, text)?,
            "derived" => {
                let (ds, bodies) = derived::read(
                    derived::Tables {
                        derivation: raw.derivation,
                        constants: raw.constants.unwrap_or_default(),
                        inputs: raw.inputs.unwrap_or_default(),
                        builtin: [
                            ("top", raw.top.is_some()),
                            ("shaft", raw.shaft.is_some()),
                            ("motor", raw.motor.is_some()),
                        ],
                        shared,
                    },
                    initial,
                    file,
                    text,
                    resolve,
                )?;
                (SceneKind::Derived(Box::new(ds)), bodies)
            }
            other => {
                return Err(bad(
                    "kind",
                    format!(
                        "unknown kind `{other}` (expected free, heavy-top, fixed-axis or derived)"
                    ),
                ));
            }
        };
        let scene = Scene {
            name: raw.name,
            description: raw.description,
            file: file.to_path_buf(),
            t_end: raw.t_end,
            kind,
            body_frame,
            bodies,
        };
        scene.check_initial_rates(text)?;
        Ok(scene)
    }

    /// Refuses initial rates so large that the phase `|ω| T` over the
    /// scene's own end time is beyond 2^52 or not finite (f64 time no
    /// longer resolves one turn), naming the field that gives them and
    /// its line — not the end time.
    fn check_initial_rates(&self, text: &str) -> Result<(), SimError> {
        let w = self.rate_scale();
        let phase = w * self.t_end;
        if phase.is_finite() && phase <= 2f64.powi(52) {
            return Ok(());
        }
        let has = |key: &str| line_of(text, key).is_some();
        let (field, key) = match &self.kind {
            SceneKind::Free { .. } | SceneKind::HeavyTop { .. } => {
                if has("angular_momentum") {
                    (
                        "initial.angular_momentum".to_string(),
                        "angular_momentum".to_string(),
                    )
                } else if has("angular_velocity") {
                    (
                        "initial.angular_velocity".to_string(),
                        "angular_velocity".to_string(),
                    )
                } else {
                    (
                        "initial.steady_precession.spin".to_string(),
                        "spin".to_string(),
                    )
                }
            }
            SceneKind::FixedAxis { .. } => ("initial.rate".to_string(), "rate".to_string()),
            SceneKind::Derived(ds) => {
                let n = ds.model.dof();
                let k = (n..ds.model.carried_base())
                    .max_by(|&a, &b| ds.y0[a].abs().total_cmp(&ds.y0[b].abs()))
                    .unwrap_or(n);
                if ds.model.is_first_order() {
                    let name = ds.model.speeds()[k - n].name().to_string();
                    (format!("initial.speeds.{name}"), name)
                } else {
                    let name = ds.model.coordinates()[k - n].name().to_string();
                    (format!("initial.rates.{name}"), name)
                }
            }
        };
        Err(SimError::BadField {
            file: self.file.clone(),
            field: field.clone(),
            message: format!(
                "{}the initial rate |ω| = {w:e} gives a phase |ω| T = {phase:e} over t_end = {}, \
                 beyond 2^52 (f64 time no longer resolves one turn) or not finite: give a \
                 smaller rate, or rescale the units (moments, masses)",
                at_line_after(
                    text,
                    &key,
                    if field.starts_with("initial.rates") {
                        "rates"
                    } else if field.starts_with("initial.speeds") {
                        "speeds"
                    } else {
                        ""
                    }
                ),
                self.t_end
            ),
        })
    }
}

/// The error of a scene field with a bad value.
pub(super) fn bad_field(file: &Path, field: &str, message: String) -> SimError {
    SimError::BadField {
        file: file.to_path_buf(),
        field: field.to_string(),
        message,
    }
}

/// A vector of a scene, checked finite; the error names the field's line.
pub(super) fn finite3(
    v: [f64; 3],
    field: &str,
    (file, text): (&Path, &str),
) -> Result<Vector3<f64>, SimError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(Vector3::from(v))
    } else {
        Err(bad_field(
            file,
            field,
            format!(
                "{}components must be finite, got {v:?}",
                text::at_field_line(text, field)
            ),
        ))
    }
}

/// Why a free body, heavy top or shaft without `[[body]]` tables is refused.
pub(super) const NO_BODY: &str = "no `[[body]]` or `[[cloud]]` table: give what moves, e.g. `[[body]]` with \
     `shape = \"cylinder\"`, `mass`, `radius`, `length` (docs/scenes.md)";
