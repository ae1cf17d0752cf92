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

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use nalgebra::{Rotation3, Unit, UnitQuaternion, Vector3};
use serde::Deserialize;
use serde::de::IgnoredAny;
use toml::Spanned;

use crate::body::{Body, Composite, MassProperties, Part, Pose, Primitive, eulerian_rotation};
use crate::cloud::ParticleCloud;
use crate::discretize::{Discretization, DiscretizedComposite};
use crate::inertia::{Inertia, Principal};
use crate::solve::{LinearSystem, SolveError};
use crate::sums::{Kinetics, Motion, kinetics, mass_properties, rigid_kinetics};

/// A scene file that cannot be used, with where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}:{line}: {field}: {message}", file.display())]
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

type V3 = [f64; 3];
/// A vector as written: checked for three finite components when read,
/// so that a fourth component or a NaN is an error at the key's line.
type RV = Spanned<Vec<f64>>;
/// A number as written, with its place.
type RF = Spanned<f64>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: Option<String>,
    description: Option<String>,
    // Read by [`bodies`], the schema every scene shares.
    #[allow(dead_code)]
    g: Option<IgnoredAny>,
    reference: Option<RV>,
    #[allow(dead_code)]
    body: Option<IgnoredAny>,
    #[allow(dead_code)]
    cloud: Option<IgnoredAny>,
    motion: Option<Spanned<RawMotion>>,
    impulse: Option<Spanned<RawImpulse>>,
    #[serde(default)]
    force: Vec<Spanned<RawForce>>,
    #[serde(default)]
    couple: Vec<Spanned<RawForce>>,
    #[serde(default)]
    constraint: Vec<Spanned<RawConstraint>>,
}

/// The part of every scene that says what moves: gravity, `[[body]]` and
/// `[[cloud]]` (unknown keys are left to the scene's own reader).
#[derive(Debug, Deserialize)]
struct RawBodies {
    g: Option<RV>,
    #[serde(default)]
    body: Vec<Spanned<RawBody>>,
    #[serde(default)]
    cloud: Vec<Spanned<RawCloud>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    name: Option<String>,
    of: Option<Spanned<String>>,
    shape: Option<String>,
    principal_moments: Option<RV>,
    mass: Option<RF>,
    weight: Option<RF>,
    position: Option<RV>,
    rotation: Option<Spanned<RawRotation>>,
    length: Option<RF>,
    a: Option<RF>,
    b: Option<RF>,
    c: Option<RF>,
    radius: Option<RF>,
    inner: Option<RF>,
    outer: Option<RF>,
    height: Option<RF>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRotation {
    axis: Option<RV>,
    angle_deg: Option<RF>,
    x_axis: Option<RV>,
    z_axis: Option<RV>,
    euler_angles: Option<RV>,
    /// Refused (roll–pitch–yaw, replaced by `euler_angles`).
    euler_deg: Option<IgnoredAny>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCloud {
    file: String,
    of: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    omega: Option<RV>,
    alpha: Option<RV>,
    frame_rate: Option<RV>,
    v_g: Option<RV>,
    a_g: Option<RV>,
    fixed_point: Option<RV>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImpulse {
    v_before: Option<RV>,
    omega_before: Option<RV>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawForce {
    name: Spanned<String>,
    point: Option<RV>,
    value: Option<RV>,
    direction: Option<RV>,
    unknown: Option<Vec<Spanned<String>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConstraint {
    name: String,
    point: RV,
    direction: RV,
    value: Option<RF>,
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

/// The byte offsets of a text's line breaks, found once, so that the line
/// of an offset is a binary search: a scene of N bodies asks N times, and
/// counting from the start each time made loading quadratic in N.
struct Lines(Vec<usize>);

impl Lines {
    fn new(text: &str) -> Lines {
        Lines(text.match_indices('\n').map(|(i, _)| i).collect())
    }

    /// Line (1-based) of a byte offset.
    fn of(&self, offset: usize) -> usize {
        self.0.partition_point(|&nl| nl < offset) + 1
    }
}

fn v3(a: V3) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
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

    /// Parses scene text; `file` names it in errors and anchors relative
    /// cloud paths.
    pub fn from_str_at(file: &Path, text: &str) -> Result<Self, SceneError> {
        let cx = Cx::new(file, text);
        let raw: RawScene = toml::from_str(text).map_err(|e| {
            let line = e.span().map(|s| cx.lines.of(s.start)).unwrap_or(0);
            cx.err(line, "-", e.message().to_string())
        })?;
        let reference = raw
            .reference
            .as_ref()
            .map(|r| cx.vec3("reference", r))
            .transpose()?;
        let all = bodies(file, text)?;
        all.refuse_of(file)?;
        let Bodies { g, body, .. } = all;
        let g = g.map(|g| [g.x, g.y, g.z]);
        let body =
            body.ok_or_else(|| cx.err(0, "body", "the scene has no body and no cloud".into()))?;

        let props = body.mass_properties();
        let problem = match (&raw.motion, &raw.impulse) {
            (Some(_), Some(s)) => {
                return Err(cx.err(
                    cx.lines.of(s.span().start),
                    "impulse",
                    "give [motion] or [impulse], not both".into(),
                ));
            }
            (None, None) => Problem::Statics,
            (Some(sm), None) => {
                let m = sm.get_ref();
                let get =
                    |name: &str, v: &Option<RV>| -> Result<Option<Vector3<f64>>, SceneError> {
                        v.as_ref()
                            .map(|v| cx.vec3(&format!("motion.{name}"), v).map(v3))
                            .transpose()
                    };
                let omega = get("omega", &m.omega)?.unwrap_or_else(Vector3::zeros);
                let alpha = get("alpha", &m.alpha)?;
                let frame_rate = get("frame_rate", &m.frame_rate)?;
                let v_g = get("v_g", &m.v_g)?;
                let a_g = get("a_g", &m.a_g)?;
                let fixed_point = get("fixed_point", &m.fixed_point)?;
                let alpha = match (alpha, frame_rate) {
                    (Some(_), Some(_)) => {
                        return Err(cx.err(
                            m.frame_rate.as_ref().map_or(0, |v| cx.line(v)),
                            "motion.frame_rate",
                            "give alpha or frame_rate, not both".into(),
                        ));
                    }
                    (Some(a), None) => a,
                    (None, Some(f)) => f.cross(&omega),
                    (None, None) => Vector3::zeros(),
                };
                match fixed_point {
                    Some(o) => {
                        if v_g.is_some() || a_g.is_some() {
                            return Err(cx.err(
                                m.fixed_point.as_ref().map_or(0, |v| cx.line(v)),
                                "motion.fixed_point",
                                "v_g and a_g follow from a fixed point; do not give them".into(),
                            ));
                        }
                        Problem::Motion(Motion::about_fixed_point(o, props.center, omega, alpha))
                    }
                    None => Problem::Motion(Motion {
                        omega,
                        alpha,
                        v_g: v_g.unwrap_or_else(Vector3::zeros),
                        a_g: a_g.unwrap_or_else(Vector3::zeros),
                    }),
                }
            }
            (None, Some(si)) => {
                let i = si.get_ref();
                let get = |name: &str, v: &Option<RV>| -> Result<Vector3<f64>, SceneError> {
                    Ok(v.as_ref()
                        .map(|v| cx.vec3(&format!("impulse.{name}"), v).map(v3))
                        .transpose()?
                        .unwrap_or_else(Vector3::zeros))
                };
                Problem::Impulse {
                    v_before: get("v_before", &i.v_before)?,
                    omega_before: get("omega_before", &i.omega_before)?,
                }
            }
        };
        let reference = match reference {
            Some(r) => v3(r),
            None => match &problem {
                Problem::Motion(_) => raw
                    .motion
                    .as_ref()
                    .and_then(|m| m.get_ref().fixed_point.as_ref())
                    .map(|v| cx.vec3("motion.fixed_point", v).map(v3))
                    .transpose()?
                    .unwrap_or_else(Vector3::zeros),
                _ => Vector3::zeros(),
            },
        };
        let about_o = props.inertia_about(&reference);
        if about_o.matrix().iter().any(|x| !x.is_finite()) {
            return Err(cx.err(
                raw.reference.as_ref().map_or(0, |r| cx.line(r)),
                "reference",
                "the inertia about the reference point overflows (bodies too far from it)".into(),
            ));
        }

        // Unknown scalars by name, with the line that names each.
        let mut names: BTreeMap<String, usize> = BTreeMap::new();
        let mut load = |kind: &str, i: usize, s: &Spanned<RawForce>, couple: bool| {
            let line = cx.lines.of(s.span().start);
            let l = s.get_ref();
            let f = |n: &str| format!("{kind}[{i}].{n}");
            let point = match (&l.point, couple) {
                (Some(p), _) => v3(cx.vec3(&f("point"), p)?),
                (None, true) => Vector3::zeros(),
                (None, false) => return Err(cx.err(line, &f("point"), "missing".into())),
            };
            let known = match &l.value {
                Some(v) => v3(cx.vec3(&f("value"), v)?),
                None => Vector3::zeros(),
            };
            let name = l.name.get_ref().clone();
            let mut unknowns = Vec::new();
            let mut add = |n: String, d: Vector3<f64>, at: usize| {
                if let Some(first) = names.insert(n.clone(), at) {
                    return Err(cx.err(
                        at,
                        &f("name"),
                        format!("a second unknown named {n:?} (the first is on line {first})"),
                    ));
                }
                unknowns.push((n, d));
                Ok(())
            };
            if let Some(d) = &l.direction {
                let d = cx.unit(&f("direction"), d)?;
                add(name.clone(), d, cx.line(&l.name))?;
            }
            let mut axes = std::collections::BTreeSet::new();
            for c in l.unknown.iter().flatten() {
                let at = cx.line(c);
                let axis = match c.get_ref().as_str() {
                    "x" => Vector3::x(),
                    "y" => Vector3::y(),
                    "z" => Vector3::z(),
                    other => {
                        return Err(cx.err(
                            at,
                            &f("unknown"),
                            format!("unknown component {other:?} (use \"x\", \"y\", \"z\")"),
                        ));
                    }
                };
                if !axes.insert(c.get_ref().clone()) {
                    return Err(cx.err(
                        at,
                        &f("unknown"),
                        format!("the component {:?} is listed twice", c.get_ref()),
                    ));
                }
                add(format!("{name}_{}", c.get_ref()), axis, at)?;
            }
            if l.value.is_none() && unknowns.is_empty() {
                return Err(cx.err(
                    line,
                    &f("value"),
                    "give a value, a direction (unknown magnitude) or unknown components".into(),
                ));
            }
            Ok(Load {
                name,
                point,
                known,
                unknowns,
            })
        };
        let mut forces = Vec::new();
        for (i, s) in raw.force.iter().enumerate() {
            forces.push(load("force", i, s, false)?);
        }
        let mut couples = Vec::new();
        for (i, s) in raw.couple.iter().enumerate() {
            couples.push(load("couple", i, s, true)?);
        }
        let mut constraints = Vec::new();
        for (i, s) in raw.constraint.iter().enumerate() {
            let line = cx.lines.of(s.span().start);
            let c = s.get_ref();
            let f = |n: &str| format!("constraint[{i}].{n}");
            if !matches!(problem, Problem::Impulse { .. }) {
                return Err(cx.err(
                    line,
                    &f("name"),
                    "constraints need an [impulse] problem".into(),
                ));
            }
            let point = v3(cx.vec3(&f("point"), &c.point)?);
            let direction = cx.unit(&f("direction"), &c.direction)?;
            let value = match &c.value {
                Some(v) => cx.scalar(&f("value"), v)?,
                None => 0.0,
            };
            constraints.push(Constraint {
                name: c.name.clone(),
                point,
                direction,
                value,
            });
        }
        Ok(Scene {
            name: raw.name.unwrap_or_else(|| file.display().to_string()),
            description: raw.description.unwrap_or_default(),
            body,
            g: g.map(v3),
            reference,
            problem,
            forces,
            couples,
            constraints,
        })
    }
}

/// What moves in a scene: gravity and the rigid body the `[[body]]` and
/// `[[cloud]]` tables make. Every scene shares this schema (`hdot dynamics`
/// and `hdot simulate` alike; `docs/scenes.md`).
#[derive(Debug, Clone, PartialEq)]
pub struct Bodies {
    /// Gravity `g`, if given (a vector, in the scene's axes).
    pub g: Option<Vector3<f64>>,
    /// Line of `g` (0 when absent).
    pub g_line: usize,
    /// All bodies and clouds together; `None` when there are none.
    pub body: Option<Composite>,
    /// The tables grouped by their `of` key (the derivation body they make
    /// up in a derived scene; `None`: tables without `of`), in the order
    /// of their first table.
    pub groups: Vec<Group>,
}

/// The `[[body]]` and `[[cloud]]` tables with the same `of`, together.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// The derivation body they make up (`of = "…"`), if named.
    pub of: Option<String>,
    /// The field of its first table's `of` (e.g. `body[2].of`), or of
    /// its first table (`body[0]`) when `of` is not given.
    pub field: String,
    /// The line of that table.
    pub line: usize,
    /// The parts together.
    pub body: Composite,
}

impl Bodies {
    /// Refuses `of` in a scene whose tables all make one body (every
    /// scene but a derived one).
    pub fn refuse_of(&self, file: &Path) -> Result<(), SceneError> {
        match self.groups.iter().find(|g| g.of.is_some()) {
            Some(g) => Err(SceneError {
                file: file.to_path_buf(),
                line: g.line,
                field: g.field.clone(),
                message:
                    "only the bodies of a derived scene name the derivation body they make up; \
                          here all tables make one body"
                        .into(),
            }),
            None => Ok(()),
        }
    }
}

/// Reads the shared part of a scene (`g`, `[[body]]`, `[[cloud]]`) from its
/// text; other keys are left to the scene's own reader. `file` names the
/// scene in errors and anchors relative cloud paths.
pub fn bodies(file: &Path, text: &str) -> Result<Bodies, SceneError> {
    let cx = Cx::new(file, text);
    let raw: RawBodies = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| cx.lines.of(s.start)).unwrap_or(0);
        if let Some(err) = old_body_table(&cx) {
            return err;
        }
        cx.err(line, "-", e.message().to_string())
    })?;
    let g = raw.g.as_ref().map(|g| cx.vec3("g", g)).transpose()?;
    let g_line = raw.g.as_ref().map_or(0, |g| cx.line(g));
    let mut parts = Vec::new();
    // Per part: its `of`, the field naming it and the line.
    let mut owners: Vec<(Option<String>, String, usize)> = Vec::new();
    for (i, sb) in raw.body.iter().enumerate() {
        let line = cx.lines.of(sb.span().start);
        let b = sb.get_ref();
        let f = |name: &str| format!("body[{i}].{name}");
        owners.push(match &b.of {
            Some(o) => (Some(o.get_ref().clone()), f("of"), cx.line(o)),
            None => (None, format!("body[{i}]"), line),
        });
        let (mass, mass_field) = match (&b.mass, &b.weight) {
            (Some(m), None) => (cx.scalar(&f("mass"), m)?, m),
            (None, Some(w)) => {
                let wv = cx.scalar(&f("weight"), w)?;
                let gn = g
                    .map(|g| safe_norm(&v3(g)))
                    .filter(|n| *n > 0.0)
                    .ok_or_else(|| {
                        cx.err(
                            cx.line(w),
                            &f("weight"),
                            "a weight needs a non-zero g".into(),
                        )
                    })?;
                (wv / gn, w)
            }
            (Some(m), Some(_)) => {
                return Err(cx.err(
                    cx.line(m),
                    &f("mass"),
                    "give mass or weight, not both".into(),
                ));
            }
            (None, None) => {
                return Err(cx.err(line, &f("mass"), "missing (or weight)".into()));
            }
        };
        let position = match &b.position {
            Some(p) => cx.vec3(&f("position"), p)?,
            None => [0.0; 3],
        };
        let rotation = match &b.rotation {
            None => UnitQuaternion::identity(),
            Some(r) => rotation_of(&cx, &f("rotation"), r)?,
        };
        let pose = Pose {
            position: v3(position),
            rotation,
        };
        let shape_name = match (&b.shape, &b.principal_moments) {
            (Some(s), None) => s.as_str(),
            (None, Some(pm)) => {
                let m = check_part_mass(&cx, &f("mass"), mass_field, mass)?;
                parts.push(Part::Cloud(equivalent_points(
                    &cx,
                    &f("principal_moments"),
                    pm,
                    m,
                    &pose,
                )?));
                continue;
            }
            (Some(_), Some(pm)) => {
                return Err(cx.err(
                    cx.line(pm),
                    &f("principal_moments"),
                    "give `shape` or `principal_moments`, not both".into(),
                ));
            }
            (None, None) => {
                return Err(cx.err(line, &f("shape"), "missing (or `principal_moments`)".into()));
            }
        };
        if shape_name == "point" {
            let m = check_part_mass(&cx, &f("mass"), mass_field, mass)?;
            let c = ParticleCloud::try_from_particles([(pose.position, m)])
                .map_err(|e| cx.err(line, &f("position"), e.to_string()))?;
            parts.push(Part::Cloud(c));
            continue;
        }
        let dim = |name: &'static str, v: &Option<RF>| match v {
            Some(v) => cx.scalar(&f(name), v),
            None => Err(cx.err(line, &f(name), format!("missing for shape {shape_name:?}"))),
        };
        let shape = match shape_name {
            "rod" => Primitive::Rod {
                length: dim("length", &b.length)?,
            },
            "plate" => Primitive::Plate {
                a: dim("a", &b.a)?,
                b: dim("b", &b.b)?,
            },
            "prism" => Primitive::Prism {
                a: dim("a", &b.a)?,
                b: dim("b", &b.b)?,
                c: dim("c", &b.c)?,
            },
            "disk" => Primitive::Disk {
                radius: dim("radius", &b.radius)?,
            },
            "cylinder" => Primitive::Cylinder {
                radius: dim("radius", &b.radius)?,
                length: dim("length", &b.length)?,
            },
            "hollow_cylinder" => Primitive::HollowCylinder {
                inner: dim("inner", &b.inner)?,
                outer: dim("outer", &b.outer)?,
                length: dim("length", &b.length)?,
            },
            "ring" => Primitive::Ring {
                radius: dim("radius", &b.radius)?,
            },
            "sphere" => Primitive::Sphere {
                radius: dim("radius", &b.radius)?,
            },
            "spherical_shell" => Primitive::SphericalShell {
                radius: dim("radius", &b.radius)?,
            },
            "cone" => Primitive::Cone {
                radius: dim("radius", &b.radius)?,
                height: dim("height", &b.height)?,
            },
            other => {
                return Err(cx.err(line, &f("shape"), format!("unknown shape {other:?}")));
            }
        };
        // The line of the key a body error is about.
        let line_of_field = |field: &str| -> usize {
            let v = match field {
                "mass" => Some(mass_field),
                "length" => b.length.as_ref(),
                "a" => b.a.as_ref(),
                "b" => b.b.as_ref(),
                "c" => b.c.as_ref(),
                "radius" => b.radius.as_ref(),
                "inner" => b.inner.as_ref(),
                "outer" => b.outer.as_ref(),
                "height" => b.height.as_ref(),
                _ => None,
            };
            v.map_or(line, |v| cx.line(v))
        };
        let body = Body::try_new(shape, mass, pose).map_err(|e| {
            let field = match &e {
                crate::BodyError::NonPositiveMass { .. } => "mass",
                crate::BodyError::BadDimension { field, .. }
                | crate::BodyError::NotFinite { field, .. } => field,
                _ => "-",
            };
            cx.err(line_of_field(field), &f(field), e.to_string())
        })?;
        let p = body.mass_properties();
        if !props_finite(&p) {
            return Err(cx.err(
                line,
                &f("shape"),
                "the mass properties overflow (mass or dimensions too large)".into(),
            ));
        }
        let _ = &b.name;
        parts.push(Part::Solid(body));
    }
    for (i, sc) in raw.cloud.iter().enumerate() {
        let line = cx.lines.of(sc.span().start);
        let p = file
            .parent()
            .unwrap_or(Path::new("."))
            .join(&sc.get_ref().file);
        let c = ParticleCloud::from_csv_path(&p)
            .map_err(|e| cx.err(line, &format!("cloud[{i}].file"), e.to_string()))?;
        parts.push(Part::Cloud(c));
        owners.push(match &sc.get_ref().of {
            Some(o) => (
                Some(o.get_ref().clone()),
                format!("cloud[{i}].of"),
                cx.line(o),
            ),
            None => (None, format!("cloud[{i}]"), line),
        });
    }
    // The parts together must stay finite too (two masses near the
    // largest f64 sum past it).
    let all: Vec<MassProperties> = parts.iter().map(Part::mass_properties).collect();
    match MassProperties::combine(&all) {
        Ok(p) if props_finite(&p) => {}
        Ok(_) | Err(crate::BodyError::NotFinite { .. }) => {
            return Err(cx.err(
                0,
                "body",
                "the mass properties of the bodies together overflow (masses summing past the largest number, or bodies too far apart)".into(),
            ));
        }
        Err(_) => {}
    }
    let mut groups: Vec<Group> = Vec::new();
    for (of, field, line) in &owners {
        if groups.iter().any(|g| &g.of == of) {
            continue;
        }
        let mine: Vec<Part> = parts
            .iter()
            .zip(&owners)
            .filter(|(_, o)| &o.0 == of)
            .map(|(p, _)| p.clone())
            .collect();
        groups.push(Group {
            of: of.clone(),
            field: field.clone(),
            line: *line,
            body: Composite::try_new(mine).map_err(|e| cx.err(*line, field, e.to_string()))?,
        });
    }
    let body = if parts.is_empty() {
        None
    } else {
        Some(Composite::try_new(parts).map_err(|e| cx.err(0, "body", e.to_string()))?)
    };
    Ok(Bodies {
        g: g.map(v3),
        g_line,
        body,
        groups,
    })
}

/// A part's mass, checked positive and finite (for the parts that are not
/// primitives, whose mass [`Body::try_new`] checks).
fn check_part_mass(cx: &Cx<'_>, field: &str, at: &RF, mass: f64) -> Result<f64, SceneError> {
    crate::mass::check_mass("body", mass).map_err(|e| cx.err(cx.line(at), field, e.to_string()))?;
    Ok(mass)
}

/// A part known by its mass and principal moments about its G (in its
/// local axes): six particles of mass m/6 at ±a, ±b, ±c on the local axes,
/// with the same mass, centre and inertia, `I_x = (m/3)(b² + c²)` and so on
/// (a real body exists for these moments exactly when the triangle
/// inequalities hold, and then a², b², c² ≥ 0).
fn equivalent_points(
    cx: &Cx<'_>,
    field: &str,
    v: &RV,
    mass: f64,
    pose: &Pose,
) -> Result<ParticleCloud, SceneError> {
    let [ix, iy, iz] = cx.vec3(field, v)?;
    let bad = |message: String| cx.err(cx.line(v), field, message);
    Inertia::try_new(nalgebra::Matrix3::from_diagonal(&Vector3::new(ix, iy, iz)))
        .map_err(|e| bad(e.to_string()))?;
    let k = 1.5 / mass;
    let half = |a: f64, b: f64, c: f64| (k * (b + c - a)).max(0.0).sqrt();
    let (a, b, c) = (half(ix, iy, iz), half(iy, iz, ix), half(iz, ix, iy));
    let points = [
        Vector3::new(a, 0.0, 0.0),
        Vector3::new(-a, 0.0, 0.0),
        Vector3::new(0.0, b, 0.0),
        Vector3::new(0.0, -b, 0.0),
        Vector3::new(0.0, 0.0, c),
        Vector3::new(0.0, 0.0, -c),
    ];
    let cloud =
        ParticleCloud::try_from_particles(points.map(|p| (pose.transform_point(&p), mass / 6.0)))
            .map_err(|e| bad(e.to_string()))?;
    if !props_finite(&cloud.mass_properties()) {
        return Err(bad(
            "the mass properties overflow (mass or moments too large)".into(),
        ));
    }
    Ok(cloud)
}

/// A `[body]` table (one body, the former `hdot simulate` form) instead of
/// `[[body]]` tables: the error names the new form.
fn old_body_table(cx: &Cx<'_>) -> Option<SceneError> {
    let table: toml::Table = toml::from_str(cx.text).ok()?;
    if !table.get("body")?.is_table() {
        return None;
    }
    let line = cx
        .text
        .lines()
        .position(|l| l.trim_start().starts_with("[body]"))
        .map_or(0, |i| i + 1);
    Some(
        cx.err(
            line,
            "body",
            "a body is given by `[[body]]` tables (two brackets), one per part: \
         `shape = \"cylinder\"`, `mass = …`, its dimensions, `position`, `rotation`; or \
         `principal_moments = [I_1, I_2, I_3]` and `mass = …` (the former `[body]` table with \
         `shape = { kind = … }` is no longer read; see docs/scenes.md)"
                .into(),
        ),
    )
}

/// The file being read, for errors that name a line and a field.
struct Cx<'a> {
    file: &'a Path,
    text: &'a str,
    lines: Lines,
}

impl<'a> Cx<'a> {
    fn new(file: &'a Path, text: &'a str) -> Cx<'a> {
        Cx {
            file,
            text,
            lines: Lines::new(text),
        }
    }

    fn err(&self, line: usize, field: &str, message: String) -> SceneError {
        SceneError {
            file: self.file.to_path_buf(),
            line,
            field: field.to_string(),
            message,
        }
    }

    /// The line a value is written on (that of its key, unless the value
    /// itself spans lines).
    fn line<T>(&self, v: &Spanned<T>) -> usize {
        self.lines.of(v.span().start)
    }

    /// A number, checked finite.
    fn scalar(&self, field: &str, v: &RF) -> Result<f64, SceneError> {
        let x = *v.get_ref();
        if !x.is_finite() {
            return Err(self.err(self.line(v), field, format!("not finite: {x}")));
        }
        Ok(x)
    }

    /// A vector, checked to have three finite components.
    fn vec3(&self, field: &str, v: &RV) -> Result<V3, SceneError> {
        let c = v.get_ref();
        let line = self.line(v);
        let Ok(a) = <V3>::try_from(c.as_slice()) else {
            return Err(self.err(
                line,
                field,
                format!("a vector has 3 components, not {}", c.len()),
            ));
        };
        if let Some(x) = a.iter().find(|x| !x.is_finite()) {
            return Err(self.err(line, field, format!("not finite: {x}")));
        }
        Ok(a)
    }

    /// A direction: a non-zero vector, normalised without overflow.
    fn unit(&self, field: &str, v: &RV) -> Result<Vector3<f64>, SceneError> {
        let a = self.vec3(field, v)?;
        unit_of(&v3(a)).ok_or_else(|| self.err(self.line(v), field, "zero vector".into()))
    }
}

/// `|v|` without overflow or underflow of the squares (components of 1e200
/// or 1e-200 are fine).
fn safe_norm(v: &Vector3<f64>) -> f64 {
    let m = v.amax();
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * (v / m).norm()
}

/// `v / |v|` without overflow or underflow; `None` for the zero vector.
pub fn unit_of(v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let m = v.amax();
    if m == 0.0 || !m.is_finite() {
        return None;
    }
    let w = v / m;
    Some(w / w.norm())
}

fn props_finite(p: &MassProperties) -> bool {
    p.mass.is_finite()
        && p.center.iter().all(|x| x.is_finite())
        && p.inertia_g.matrix().iter().all(|x| x.is_finite())
}

fn rotation_of(
    cx: &Cx<'_>,
    field: &str,
    sr: &Spanned<RawRotation>,
) -> Result<UnitQuaternion<f64>, SceneError> {
    let r = sr.get_ref();
    let line = cx.lines.of(sr.span().start);
    if r.euler_deg.is_some() {
        return Err(cx.err(
            line,
            &format!("{field}.euler_deg"),
            "roll–pitch–yaw angles are no longer read: give the Eulerian angles \
             `euler_angles = [φ, θ, ψ]` in radians (z-y-z, R = R_Z(φ) R_y(θ) R_z(ψ), the \
             convention of every scene; docs/scenes.md), or `{ axis = […], angle_deg = … }`"
                .into(),
        ));
    }
    let given = [
        r.axis.is_some() || r.angle_deg.is_some(),
        r.x_axis.is_some(),
        r.z_axis.is_some(),
        r.euler_angles.is_some(),
    ]
    .iter()
    .filter(|b| **b)
    .count();
    if given != 1 {
        return Err(cx.err(
            line,
            field,
            "give exactly one of {axis, angle_deg}, x_axis, z_axis, euler_angles".to_string(),
        ));
    }
    let sub = |n: &str| format!("{field}.{n}");
    if let Some(a) = &r.x_axis {
        let a = Unit::new_unchecked(cx.unit(&sub("x_axis"), a)?);
        return Ok(
            UnitQuaternion::rotation_between_axis(&Vector3::x_axis(), &a).unwrap_or_else(|| {
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI)
            }),
        );
    }
    if let Some(a) = &r.z_axis {
        let a = Unit::new_unchecked(cx.unit(&sub("z_axis"), a)?);
        return Ok(
            UnitQuaternion::rotation_between_axis(&Vector3::z_axis(), &a).unwrap_or_else(|| {
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
            }),
        );
    }
    if let Some(e) = &r.euler_angles {
        let [phi, theta, psi] = cx.vec3(&sub("euler_angles"), e)?;
        return Ok(eulerian_rotation(phi, theta, psi));
    }
    let axis = match &r.axis {
        Some(a) => Unit::new_unchecked(cx.unit(&sub("axis"), a)?),
        None => return Err(cx.err(line, &sub("axis"), "missing (with angle_deg)".into())),
    };
    let angle = match &r.angle_deg {
        Some(a) => cx.scalar(&sub("angle_deg"), a)?,
        None => return Err(cx.err(line, &sub("angle_deg"), "missing (with axis)".into())),
    };
    Ok(UnitQuaternion::from_axis_angle(&axis, angle.to_radians()))
}

/// Unknown names, their force and moment columns (about O), and the known
/// resultant force and moment about O.
type LoadSystem = (
    Vec<String>,
    Vec<Vector3<f64>>,
    Vec<Vector3<f64>>,
    Vector3<f64>,
    Vector3<f64>,
);

/// Mass properties of a scene's body, about G and about the reference.
#[derive(Debug, Clone, PartialEq)]
pub struct InertiaReport {
    /// Mass, centre, inertia about G (world axes).
    pub props: MassProperties,
    /// Inertia about the reference point O (world axes).
    pub inertia_o: Inertia,
    /// Principal moments and axes about G.
    pub principal: Principal,
}

/// Everything `hdot dynamics` reports.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsReport {
    /// Mass properties.
    pub inertia: InertiaReport,
    /// The motion used (after the impact, for impulse problems).
    pub motion: Motion,
    /// Kinetic quantities from the rigid-body formulas (analytic inertia).
    pub kinetics: Kinetics,
    /// The same quantities by particle sums over a discretised copy of the
    /// body, with the rigid formulas evaluated on the *discretised* mass
    /// properties: their largest relative difference (round-off level).
    pub particle_check: f64,
    /// Solved unknowns, by name (empty when there are none).
    pub unknowns: BTreeMap<String, f64>,
    /// Why the unknowns could not be solved, if so.
    pub unsolved: Option<SolveError>,
}

/// Discretisation used for the particle cross-check of scenes.
pub const CHECK_DISCRETIZATION: Discretization = Discretization {
    method: crate::discretize::Method::GaussLegendre(2),
    cells: 6,
};

impl Scene {
    /// Mass properties.
    pub fn inertia(&self) -> InertiaReport {
        let props = self.body.mass_properties();
        InertiaReport {
            inertia_o: props.inertia_about(&self.reference),
            principal: props.principal(),
            props,
        }
    }

    /// The known resultant (weight + known loads) and the equations
    /// `Σ F = rhs_f`, `Σ M_O = rhs_m` in the unknowns.
    fn load_system(&self, props: &MassProperties) -> LoadSystem {
        let o = self.reference;
        let mut names = Vec::new();
        let mut fcols = Vec::new();
        let mut mcols = Vec::new();
        let (mut f_known, mut m_known) = (Vector3::zeros(), Vector3::zeros());
        if let (Some(g), Problem::Motion(_)) = (self.g, &self.problem) {
            let w = g * props.mass;
            f_known += w;
            m_known += (props.center - o).cross(&w);
        }
        for l in &self.forces {
            f_known += l.known;
            m_known += (l.point - o).cross(&l.known);
            for (n, d) in &l.unknowns {
                names.push(n.clone());
                fcols.push(*d);
                mcols.push((l.point - o).cross(d));
            }
        }
        for c in &self.couples {
            m_known += c.known;
            for (n, d) in &c.unknowns {
                names.push(n.clone());
                fcols.push(Vector3::zeros());
                mcols.push(*d);
            }
        }
        (names, fcols, mcols, f_known, m_known)
    }

    /// Solves the scene: kinetic quantities, resultants, unknowns, and the
    /// particle-sum cross-check.
    pub fn dynamics(&self) -> DynamicsReport {
        let inertia = self.inertia();
        let props = inertia.props;
        let o = self.reference;
        let (names, fcols, mcols, f_known, m_known) = self.load_system(&props);
        let mut unknowns = BTreeMap::new();
        let mut unsolved = None;
        let motion = match &self.problem {
            Problem::Statics | Problem::Motion(_) => {
                let motion = match &self.problem {
                    Problem::Motion(m) => *m,
                    _ => Motion::default(),
                };
                let k = rigid_kinetics(&props, &motion, o);
                let rbar = props.center - o;
                let mut scale_f = k.force.norm() + f_known.norm();
                let mut scale_m = rbar.norm() * k.force.norm() + k.hdot_g.norm() + m_known.norm();
                if let Some(g) = self.g {
                    scale_f += (g * props.mass).norm();
                    scale_m += rbar.norm() * (g * props.mass).norm();
                }
                for l in self.forces.iter().chain(&self.couples) {
                    scale_f += l.known.norm();
                    scale_m += ((l.point - o).norm() + 1.0) * l.known.norm();
                }
                if !names.is_empty() {
                    let mut sys = LinearSystem {
                        unknowns: names.clone(),
                        ..Default::default()
                    };
                    for (axis, c) in ["x", "y", "z"].iter().enumerate() {
                        sys.push_scaled(
                            format!("ΣF_{c}"),
                            fcols.iter().map(|v| v[axis]).collect(),
                            k.force[axis] - f_known[axis],
                            scale_f,
                        );
                    }
                    for (axis, c) in ["x", "y", "z"].iter().enumerate() {
                        sys.push_scaled(
                            format!("ΣM_{c}"),
                            mcols.iter().map(|v| v[axis]).collect(),
                            k.moment_o[axis] - m_known[axis],
                            scale_m,
                        );
                    }
                    match sys.solve() {
                        Ok(x) => unknowns.extend(names.iter().cloned().zip(x)),
                        Err(e) => unsolved = Some(e),
                    }
                }
                motion
            }
            Problem::Impulse {
                v_before,
                omega_before,
            } => {
                // unknowns: v̄ (3), ω (3), then the unknown impulses
                let mut all: Vec<String> = ["v_x", "v_y", "v_z", "omega_x", "omega_y", "omega_z"]
                    .iter()
                    .map(|s| s.to_string())
                    .collect();
                all.extend(names.iter().cloned());
                let n = all.len();
                let mut sys = LinearSystem {
                    unknowns: all.clone(),
                    ..Default::default()
                };
                let m = props.mass;
                let ig = props.inertia_g.matrix();
                let g = props.center;
                // m v̄₂ − Σ J = m v̄₁ + J_known
                for axis in 0..3 {
                    let mut row = vec![0.0; n];
                    row[axis] = m;
                    for (k, c) in fcols.iter().enumerate() {
                        row[6 + k] = -c[axis];
                    }
                    // The scale holds the terms that cancel in the sum.
                    sys.push_scaled(
                        format!("linear momentum {}", ["x", "y", "z"][axis]),
                        row,
                        m * v_before[axis] + f_known[axis],
                        m * v_before.norm() + f_known.norm(),
                    );
                }
                // I_G ω₂ − Σ (r − G) × J = I_G ω₁ + known angular impulse about G
                let m_known_g = m_known - (g - o).cross(&f_known);
                let h1 = ig * omega_before;
                for axis in 0..3 {
                    let mut row = vec![0.0; n];
                    for j in 0..3 {
                        row[3 + j] = ig[(axis, j)];
                    }
                    for (k, (fc, mc)) in fcols.iter().zip(&mcols).enumerate() {
                        // moment about G = moment about O − (G − O) × J
                        row[6 + k] = -(mc - (g - o).cross(fc))[axis];
                    }
                    sys.push_scaled(
                        format!("angular momentum {}", ["x", "y", "z"][axis]),
                        row,
                        h1[axis] + m_known_g[axis],
                        props.inertia_g.trace().abs() * omega_before.norm()
                            + m_known.norm()
                            + (g - o).norm() * f_known.norm(),
                    );
                }
                // constraints: d · (v̄ + ω × (P − G)) = value
                for c in &self.constraints {
                    let mut row = vec![0.0; n];
                    let r = c.point - g;
                    // d · (ω × r) = ω · (r × d)
                    let rd = r.cross(&c.direction);
                    row[..3].copy_from_slice(c.direction.as_slice());
                    row[3..6].copy_from_slice(rd.as_slice());
                    sys.push(c.name.clone(), row, c.value);
                }
                match sys.solve() {
                    Ok(x) => {
                        unknowns.extend(all.iter().cloned().zip(x.iter().copied()));
                        Motion {
                            omega: Vector3::new(x[3], x[4], x[5]),
                            alpha: Vector3::zeros(),
                            v_g: Vector3::new(x[0], x[1], x[2]),
                            a_g: Vector3::zeros(),
                        }
                    }
                    Err(e) => {
                        unsolved = Some(e);
                        Motion::default()
                    }
                }
            }
        };
        let kin = rigid_kinetics(&props, &motion, o);
        DynamicsReport {
            particle_check: self.particle_check(&motion),
            inertia,
            motion,
            kinetics: kin,
            unknowns,
            unsolved,
        }
    }

    /// Largest relative difference between particle sums over a
    /// discretised copy of the body and the rigid-body formulas applied to
    /// that copy's mass properties (a round-off-level check that the
    /// formulas and the sums agree on this scene).
    pub fn particle_check(&self, motion: &Motion) -> f64 {
        let src = DiscretizedComposite::new(&self.body, &CHECK_DISCRETIZATION);
        let Ok(p) = mass_properties(&src) else {
            return f64::NAN;
        };
        // the motion is given for the analytic centre; re-express it for
        // the discretised one (same rigid velocity field)
        let m = Motion {
            v_g: motion.velocity_at(&self.body.mass_properties().center, &p.center),
            a_g: motion.acceleration_at(&self.body.mass_properties().center, &p.center),
            ..*motion
        };
        let s = kinetics(&src, &m, p.center, self.reference);
        let r = rigid_kinetics(&p, &m, self.reference);
        let pairs = [
            (s.h_g, r.h_g),
            (s.h_o, r.h_o),
            (s.force, r.force),
            (s.hdot_g, r.hdot_g),
            (s.moment_o, r.moment_o),
        ];
        // Scales that include the magnitudes of the terms that cancel in
        // the sums (a prism spinning steadily about a principal axis has
        // zero resultants, made of particle terms of size m ω² r): a
        // relative difference is round-off against these, not against a
        // zero result.
        let rg = (p.inertia_g.trace() / p.mass).max(0.0).sqrt();
        let lever = 1.0 + (p.center - self.reference).norm() + rg;
        let (w, al) = (m.omega.norm(), m.alpha.norm());
        let speed = m.v_g.norm() + w * rg;
        let accel = m.a_g.norm() + (al + w * w) * rg;
        let i = p.inertia_g.trace().abs();
        let scale_h =
            s.h_g.norm() + s.h_o.norm() + s.momentum.norm() + i * w + p.mass * speed * lever;
        let scale_a = s.force.norm()
            + s.hdot_g.norm()
            + s.moment_o.norm()
            + i * (al + w * w)
            + p.mass * accel * lever;
        let mut worst: f64 = 0.0;
        for (k, (a, b)) in pairs.iter().enumerate() {
            let scale = if k < 2 { scale_h } else { scale_a };
            if scale > 0.0 {
                worst = worst.max((a - b).norm() / scale);
            }
        }
        if s.kinetic_energy > 0.0 {
            worst = worst.max((s.kinetic_energy - r.kinetic_energy).abs() / s.kinetic_energy);
        }
        worst
    }
}

/// Rotation helper for scene builders and tests: the rotation taking
/// local x onto `dir`.
pub fn x_axis_to(dir: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(&Vector3::x(), dir)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI))
}
