//! Scenes: TOML files describing a body, its supports and its initial
//! motion. The format is documented in `docs/simulation.md`; what moves
//! (`g`, `[[body]]`, `[[cloud]]`) is the schema every scene shares,
//! `docs/scenes.md`, read by [`hdot_num::scene::bodies`]. Every scene
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

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use hdot_num::scene::{Bodies, bodies};
use nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};
use serde::Deserialize;
use serde::de::IgnoredAny;

use crate::exact::SteadyTop;
use crate::systems::Shaft;
use crate::{PrincipalMoments, SimError};

mod derived;
pub use derived::{DerivedScene, Resolve, resolve_near};

/// Relative residual of §7's relation under which a heavy top counts as
/// being in steady precession.
pub const STEADY_TOL: f64 = 1e-12;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: String,
    #[serde(default)]
    description: String,
    kind: String,
    t_end: f64,
    // `g`, `[[body]]` and `[[cloud]]`: the schema every scene shares, read
    // by `hdot_num::scene::bodies`.
    #[allow(dead_code)]
    g: Option<IgnoredAny>,
    #[allow(dead_code)]
    body: Option<IgnoredAny>,
    #[allow(dead_code)]
    cloud: Option<IgnoredAny>,
    initial: Option<RawInitial>,
    top: Option<RawTop>,
    shaft: Option<RawShaft>,
    motor: Option<RawMotor>,
    derivation: Option<derived::RawDerivation>,
    constants: Option<BTreeMap<String, f64>>,
    inputs: Option<BTreeMap<String, String>>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawInitial {
    attitude: Option<[f64; 4]>,
    euler_angles: Option<[f64; 3]>,
    angular_momentum: Option<[f64; 3]>,
    angular_velocity: Option<[f64; 3]>,
    steady_precession: Option<RawSteady>,
    angle: Option<f64>,
    rate: Option<f64>,
    coordinates: Option<BTreeMap<String, f64>>,
    rates: Option<BTreeMap<String, f64>>,
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
struct RawSteady {
    theta: f64,
    spin: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTop {
    fixed_point: Option<[f64; 3]>,
    // Former keys, refused with the new ones named.
    distance: Option<IgnoredAny>,
    g: Option<IgnoredAny>,
    mass: Option<IgnoredAny>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShaft {
    bearings: [f64; 2],
    #[serde(default)]
    friction: f64,
    // Former keys, refused with the new ones named.
    rotor_moment: Option<IgnoredAny>,
    masses: Option<IgnoredAny>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotor {
    stall_torque: f64,
    no_load_speed: Option<f64>,
}

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

impl Scene {
    /// The largest rate of the scene's motion, `|ω₀|` (`|ω|` of a shaft,
    /// the largest `|q̇|` of a derived scene).
    pub fn rate_scale(&self) -> f64 {
        match &self.kind {
            SceneKind::Free { w0, .. } | SceneKind::HeavyTop { w0, .. } => w0.norm(),
            SceneKind::FixedAxis { y0, .. } => y0[1].abs(),
            SceneKind::Derived(ds) => {
                let n = ds.y0.len() / 2;
                ds.y0[n..].iter().fold(0.0, |m: f64, v| m.max(v.abs()))
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
    pub fn parse_with(text: &str, file: &Path, resolve: Resolve<'_>) -> Result<Scene, SimError> {
        let raw: RawScene = toml::from_str(text).map_err(|e| SimError::Parse {
            file: file.to_path_buf(),
            message: e.to_string(),
        })?;
        let bad = |field: &str, message: String| SimError::BadField {
            file: file.to_path_buf(),
            field: field.to_string(),
            message,
        };
        if !(raw.t_end.is_finite() && raw.t_end > 0.0) {
            return Err(bad(
                "t_end",
                format!("must be positive and finite, got {}", raw.t_end),
            ));
        }
        let mut initial = raw.initial.unwrap_or_default();
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
        let finite3 = |v: [f64; 3], field: &str| -> Result<Vector3<f64>, SimError> {
            if v.iter().all(|x| x.is_finite()) {
                Ok(Vector3::from(v))
            } else {
                Err(bad(field, format!("components must be finite, got {v:?}")))
            }
        };
        let mut body_frame = None;
        let kind = match raw.kind.as_str() {
            "free" | "heavy-top" => {
                let all = bodies(file, text)?;
                all.refuse_of(file)?;
                let Bodies {
                    g, g_line, body, ..
                } = all;
                let body = body.ok_or_else(|| bad("body", NO_BODY.into()))?;
                let props = body.mass_properties();
                let heavy = raw.kind == "heavy-top";
                let (about, axis3, weight_arm) = if heavy {
                    let top = raw.top.ok_or_else(|| {
                        bad(
                            "top",
                            "missing table [top] (fixed_point = [x, y, z])".into(),
                        )
                    })?;
                    if let Some((key, _)) = [
                        ("distance", top.distance.is_some()),
                        ("mass", top.mass.is_some()),
                        ("g", top.g.is_some()),
                    ]
                    .iter()
                    .find(|(_, set)| *set)
                    {
                        return Err(bad(
                            &format!("top.{key}"),
                            "no longer read: the mass comes from the `[[body]]` tables, the pivot is \
                             `top.fixed_point = [x, y, z]` in the body's axes (a distance l below G on \
                             the axis: [0, 0, -l] for a body centred at the origin), and gravity is \
                             `g = [0.0, 0.0, -9.81]` at the top of the file (docs/scenes.md)"
                                .into(),
                        ));
                    }
                    let o = top.fixed_point.ok_or_else(|| {
                        bad(
                            "top.fixed_point",
                            "missing: the pivot O in the body's axes".into(),
                        )
                    })?;
                    let o = finite3(o, "top.fixed_point")?;
                    let g = g.ok_or_else(|| {
                        bad(
                            "g",
                            "a heavy top needs gravity: `g = [0.0, 0.0, -9.81]` (space Z up)"
                                .into(),
                        )
                    })?;
                    let gn = g.norm();
                    if !(gn > 0.0 && gn.is_finite() && g.x.hypot(g.y) <= 1e-12 * gn && g.z < 0.0) {
                        return Err(bad(
                            "g",
                            format!(
                                "line {g_line}: the heavy top's space Z is up, so gravity points along −Z: \
                                 give g = [0.0, 0.0, -g] (got {:?})",
                                [g.x, g.y, g.z]
                            ),
                        ));
                    }
                    let arm = props.center - o;
                    let l = arm.norm();
                    if l.is_nan() || l <= 0.0 {
                        return Err(bad(
                            "top.fixed_point",
                            "the pivot is at the mass centre: no gravity torque (give a free scene)".into(),
                        ));
                    }
                    (
                        *props.inertia_about(&o).matrix(),
                        Some(arm),
                        props.mass * gn * l,
                    )
                } else {
                    if raw.top.is_some() {
                        return Err(bad(
                            "top",
                            "only a scene of kind \"heavy-top\" has a pivot".into(),
                        ));
                    }
                    (*props.inertia_g.matrix(), None, 0.0)
                };
                let (moments, axes) = body_axes(&about, axis3).map_err(|m| bad("body", m))?;
                body_frame = Some(BodyFrame {
                    origin: props.center - axis3.unwrap_or_else(Vector3::zeros),
                    axes,
                });
                let moments =
                    PrincipalMoments::new(moments).map_err(|e| bad("body", e.to_string()))?;
                // ω and H are given in the axes of the [[body]] tables; the
                // models take them in the body (principal) axes.
                let to_body = axes.transpose();
                let axes_q = UnitQuaternion::from_rotation_matrix(&axes);
                let i = moments.get();
                let (q0, w0, steady) = if let Some(s) = initial.steady_precession {
                    if !heavy {
                        return Err(bad(
                            "initial.steady_precession",
                            "only a heavy top has a forced steady precession; a free axisymmetric body precesses by itself".into(),
                        ));
                    }
                    if (i[0] - i[1]).abs() > 1e-12 * i[0] {
                        return Err(bad(
                            "body",
                            "steady precession needs I_1 = I_2 (symmetric top)".into(),
                        ));
                    }
                    if !(s.theta > 0.0 && s.theta < std::f64::consts::PI) {
                        return Err(bad(
                            "initial.steady_precession.theta",
                            "must lie in (0, π)".into(),
                        ));
                    }
                    if !s.spin.is_finite() {
                        return Err(bad(
                            "initial.steady_precession.spin",
                            format!("{}must be finite, got {}", at_line(text, "spin"), s.spin),
                        ));
                    }
                    let phi_dot =
                        SteadyTop::slow_precession_rate(i[2], i[0], weight_arm, s.theta, s.spin)
                            .ok_or_else(|| {
                                bad(
                                    "initial.steady_precession.spin",
                                    "too slow for a steady precession at this θ".into(),
                                )
                            })?;
                    let top = SteadyTop {
                        phi0: 0.0,
                        theta: s.theta,
                        psi0: 0.0,
                        phi_dot,
                        psi_dot: s.spin - phi_dot * s.theta.cos(),
                        omega_z: s.spin,
                    };
                    let y = top.state(0.0);
                    (
                        crate::systems::free::attitude(&y),
                        Vector3::new(y[4], y[5], y[6]),
                        Some(top),
                    )
                } else {
                    let q0 = match (initial.attitude, initial.euler_angles) {
                        (Some(q), None) => {
                            unit_attitude(q, &format!("{}: initial.attitude", file.display()))?
                        }
                        (None, Some(e)) => {
                            let e = finite3(e, "initial.euler_angles")?;
                            hdot_num::body::eulerian_rotation(e.x, e.y, e.z)
                        }
                        (None, None) => UnitQuaternion::identity(),
                        _ => {
                            return Err(bad(
                                "initial",
                                "give at most one of `attitude` and `euler_angles`".into(),
                            ));
                        }
                    };
                    // |H|² and 2E·I must be finite with room to spare: the
                    // closed forms and the invariants square them.
                    let in_range = |w: &Vector3<f64>| {
                        let h2: f64 = (0..3).map(|k| (i[k] * w[k]).powi(2)).sum();
                        let e2: f64 = (0..3).map(|k| i[k] * w[k] * w[k]).sum();
                        let imax = i[0].max(i[1]).max(i[2]);
                        (h2 * 1e6).is_finite() && (e2 * imax * 1e6).is_finite()
                    };
                    let overflow = |field: &str, v: &Vector3<f64>| {
                        bad(
                            field,
                            format!(
                                "|H|² = Σ (I_i ω_i)² is beyond the range of f64 (components {:?}): \
                                 rescale the units",
                                [v.x, v.y, v.z]
                            ),
                        )
                    };
                    let q0 = q0 * axes_q;
                    let w0 = match (initial.angular_momentum, initial.angular_velocity) {
                        (Some(h), None) => {
                            let h = to_body * finite3(h, "initial.angular_momentum")?;
                            let w = Vector3::new(h.x / i[0], h.y / i[1], h.z / i[2]);
                            if !in_range(&w) {
                                return Err(overflow("initial.angular_momentum", &h));
                            }
                            w
                        }
                        (None, Some(w)) => {
                            let w = to_body * finite3(w, "initial.angular_velocity")?;
                            if !in_range(&w) {
                                return Err(overflow("initial.angular_velocity", &w));
                            }
                            w
                        }
                        _ => {
                            return Err(bad(
                                "initial",
                                "give exactly one of `angular_momentum` and `angular_velocity`"
                                    .into(),
                            ));
                        }
                    };
                    // ω² must not underflow: the invariants and the closed
                    // forms square it.
                    let w2 = w0.norm_squared();
                    if w0.amax() != 0.0 && w2 < 1e-290 {
                        let (field, key) = if initial.angular_momentum.is_some() {
                            ("initial.angular_momentum", "angular_momentum")
                        } else {
                            ("initial.angular_velocity", "angular_velocity")
                        };
                        return Err(bad(
                            field,
                            format!(
                                "{}the angular velocity |ω| = {:e} (in body axes) is so small that \
                                 ω² underflows f64: rescale the units (moments, time)",
                                at_line(text, key),
                                w0.amax()
                            ),
                        ));
                    }
                    let steady = if heavy {
                        detect_steady(i, weight_arm, &q0, &w0)
                    } else {
                        None
                    };
                    (q0, w0, steady)
                };
                if heavy {
                    SceneKind::HeavyTop {
                        moments,
                        weight_arm,
                        q0,
                        w0,
                        steady,
                    }
                } else {
                    SceneKind::Free { moments, q0, w0 }
                }
            }
            "fixed-axis" => {
                let s = raw
                    .shaft
                    .ok_or_else(|| bad("shaft", "missing table [shaft]".into()))?;
                let motor = raw
                    .motor
                    .ok_or_else(|| bad("motor", "missing table [motor]".into()))?;
                if s.rotor_moment.is_some() || s.masses.is_some() {
                    return Err(bad(
                        if s.masses.is_some() { "shaft.masses" } else { "shaft.rotor_moment" },
                        "no longer read: what turns is given by `[[body]]` tables in the shaft's axes \
                         (z along the shaft through the origin), e.g. a point mass \
                         `[[body]] shape = \"point\", mass = 0.05, position = [0.04, 0.0, 0.06]`, and a \
                         balanced rotor `[[body]] shape = \"disk\"` or `principal_moments = […]` with \
                         its mass (docs/scenes.md)"
                            .into(),
                    ));
                }
                if !(s.bearings[0].is_finite()
                    && s.bearings[1].is_finite()
                    && s.bearings[0] != s.bearings[1])
                {
                    return Err(bad(
                        "shaft.bearings",
                        "two distinct finite positions needed".into(),
                    ));
                }
                let all = bodies(file, text)?;
                all.refuse_of(file)?;
                let Bodies { body, .. } = all;
                let body = body.ok_or_else(|| bad("body", NO_BODY.into()))?;
                let props = body.mass_properties();
                // Inertia about the origin O on the axis, in the shaft's
                // axes: I_z on the diagonal, products ∫xz dm = −I[0][2].
                let about_o = props.inertia_about(&Vector3::zeros());
                let io = about_o.matrix();
                let (iz, ixz, iyz) = (io[(2, 2)], -io[(0, 2)], -io[(1, 2)]);
                if !(iz > 0.0 && iz.is_finite()) {
                    return Err(bad(
                        "body",
                        "the moment about the shaft's axis (z through the origin) must be positive"
                            .into(),
                    ));
                }
                let no_load = motor.no_load_speed.unwrap_or(f64::INFINITY);
                if !(motor.stall_torque.is_finite() && no_load > 0.0 && s.friction >= 0.0) {
                    return Err(bad(
                        "motor",
                        "stall torque finite, no-load speed positive, friction ≥ 0".into(),
                    ));
                }
                let shaft = Shaft {
                    i_z: iz,
                    i_xz: ixz,
                    i_yz: iyz,
                    mass: props.mass,
                    xbar: props.center.x,
                    ybar: props.center.y,
                    stall_torque: motor.stall_torque,
                    no_load_speed: no_load,
                    friction: s.friction,
                    bearings: s.bearings,
                };
                let y0 = [initial.angle.unwrap_or(0.0), initial.rate.unwrap_or(0.0)];
                if !(y0[0].is_finite() && y0[1].is_finite()) {
                    return Err(bad("initial", "angle and rate must be finite".into()));
                }
                SceneKind::FixedAxis { shaft, y0 }
            }
            "derived" => {
                let builtin = [
                    ("top", raw.top.is_some()),
                    ("shaft", raw.shaft.is_some()),
                    ("motor", raw.motor.is_some()),
                    ("initial.attitude", initial.attitude.is_some()),
                    ("initial.euler_angles", initial.euler_angles.is_some()),
                    (
                        "initial.angular_momentum",
                        initial.angular_momentum.is_some(),
                    ),
                    (
                        "initial.angular_velocity",
                        initial.angular_velocity.is_some(),
                    ),
                    (
                        "initial.steady_precession",
                        initial.steady_precession.is_some(),
                    ),
                    ("initial.angle", initial.angle.is_some()),
                    ("initial.rate", initial.rate.is_some()),
                ];
                if let Some((field, _)) = builtin.iter().find(|(_, set)| *set) {
                    return Err(bad(
                        field,
                        "a derived scene gives its state as `initial.coordinates` and `initial.rates`, \
                         its bodies as `[[body]]` tables (or their masses and moments under \
                         `[constants]`) and g under `[constants]`"
                            .into(),
                    ));
                }
                let start = derived::RawStart {
                    coordinates: initial.coordinates.take().unwrap_or_default(),
                    rates: initial.rates.take().unwrap_or_default(),
                };
                SceneKind::Derived(Box::new(derived::parse(
                    raw.derivation,
                    raw.constants.unwrap_or_default(),
                    bodies(file, text)?,
                    raw.inputs.unwrap_or_default(),
                    start,
                    file,
                    resolve,
                )?))
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
                let n = ds.y0.len() / 2;
                let k = (0..n)
                    .max_by(|&a, &b| ds.y0[n + a].abs().total_cmp(&ds.y0[n + b].abs()))
                    .unwrap_or(0);
                let name = ds.model.coordinates()[k].name().to_string();
                (format!("initial.rates.{name}"), name)
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
                    } else {
                        ""
                    }
                ),
                self.t_end
            ),
        })
    }
}

/// The 1-based line of the first `key = …` in `text` (at a line's start or
/// inside an inline table), if any.
fn line_of(text: &str, key: &str) -> Option<usize> {
    line_of_after(text, key, "")
}

/// [`line_of`] among the lines that also contain `context`.
fn line_of_after(text: &str, key: &str, context: &str) -> Option<usize> {
    text.lines()
        .position(|l| {
            l.contains(context)
                && l.match_indices(key).any(|(i, _)| {
                    let before = l[..i].chars().next_back();
                    let after = l[i + key.len()..].trim_start();
                    before.is_none_or(|c| c.is_whitespace() || c == '{' || c == ',')
                        && after.starts_with('=')
                })
        })
        .map(|k| k + 1)
}

/// `line N: ` for the line of `key`, or nothing when it is not found.
fn at_line(text: &str, key: &str) -> String {
    at_line_after(text, key, "")
}

/// [`at_line`] among the lines that also contain `context`.
fn at_line_after(text: &str, key: &str, context: &str) -> String {
    line_of_after(text, key, context)
        .or_else(|| line_of(text, key))
        .map_or(String::new(), |n| format!("line {n}: "))
}

/// Why a free body, heavy top or shaft without `[[body]]` tables is refused.
const NO_BODY: &str = "no `[[body]]` or `[[cloud]]` table: give what moves, e.g. `[[body]]` with \
     `shape = \"cylinder\"`, `mass`, `radius`, `length` (docs/scenes.md)";

/// Relative size of the products of inertia (to the trace) under which
/// the axes of the `[[body]]` tables are taken as the body's principal axes.
const DIAGONAL_TOL: f64 = 1e-12;

/// The body axes of a simulation: principal axes of `inertia` (about G, or
/// about the pivot O; in the axes of the `[[body]]` tables), with axis 3
/// along `axis3` (from O to G) when given. The tables' own axes are kept
/// when they are principal already (so that ω is given in them as
/// written); otherwise the principal axes are found. Returns the moments
/// and the rotation whose columns are the body axes in the tables' axes.
fn body_axes(
    inertia: &Matrix3<f64>,
    axis3: Option<Vector3<f64>>,
) -> Result<([f64; 3], Rotation3<f64>), String> {
    let trace = inertia.trace();
    let off = inertia[(0, 1)]
        .abs()
        .max(inertia[(0, 2)].abs())
        .max(inertia[(1, 2)].abs());
    let along_z = axis3.is_none_or(|a| a.x.hypot(a.y) <= DIAGONAL_TOL * a.norm() && a.z > 0.0);
    if off <= DIAGONAL_TOL * trace && along_z {
        return Ok((
            [inertia[(0, 0)], inertia[(1, 1)], inertia[(2, 2)]],
            Rotation3::identity(),
        ));
    }
    let Some(a) = axis3 else {
        let p = hdot_num::Inertia::new_unchecked(*inertia).principal();
        return Ok((p.moments.into(), p.axes));
    };
    let e3 = a.normalize();
    let ie3 = inertia * e3;
    let i3 = e3.dot(&ie3);
    if (ie3 - e3 * i3).norm() > 1e-9 * trace {
        return Err(
            "the mass centre G is not on a principal axis of inertia through the pivot O: the built-in \
             heavy top needs G on such an axis (the axis of a symmetric top); a derived scene \
             integrates other bodies"
                .into(),
        );
    }
    // Principal axes in the plane normal to e3.
    let u = if e3.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = (u - e3 * e3.dot(&u)).normalize();
    let v = e3.cross(&u);
    let (uu, vv, uv) = (
        u.dot(&(inertia * u)),
        v.dot(&(inertia * v)),
        u.dot(&(inertia * v)),
    );
    let alpha = 0.5 * (2.0 * uv).atan2(uu - vv);
    let e1 = u * alpha.cos() + v * alpha.sin();
    let e2 = e3.cross(&e1);
    let axes = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[e1, e2, e3]));
    Ok(([e1.dot(&(inertia * e1)), e2.dot(&(inertia * e2)), i3], axes))
}

/// A heavy top given by attitude and ω is in steady precession when θ̇ = 0,
/// it is symmetric and §7's relation holds to [`STEADY_TOL`].
fn detect_steady(
    i: [f64; 3],
    weight_arm: f64,
    q0: &UnitQuaternion<f64>,
    w0: &Vector3<f64>,
) -> Option<SteadyTop> {
    if (i[0] - i[1]).abs() > 1e-12 * i[0] {
        return None;
    }
    let (phi, theta, psi) = crate::systems::euler_angles::angles_from_quaternion(q0);
    if theta.sin() < 1e-8 {
        return None;
    }
    let (s, c) = psi.sin_cos();
    // §7 frame components: ω' = R_z(ψ) ω.
    let wx = c * w0.x - s * w0.y;
    let wy = s * w0.x + c * w0.y;
    let scale = w0.norm().max(f64::MIN_POSITIVE);
    if wy.abs() > 1e-12 * scale {
        return None;
    }
    let phi_dot = -wx / theta.sin();
    let top = SteadyTop {
        phi0: phi,
        theta,
        psi0: psi,
        phi_dot,
        psi_dot: w0.z - phi_dot * theta.cos(),
        omega_z: w0.z,
    };
    (top.residual(i[2], i[0], weight_arm) <= STEADY_TOL).then_some(top)
}
