//! Scenes (TOML) and worked problems: mass properties, the resultant
//! force and moment a motion requires, impulses, and named unknowns.
//!
//! The format is documented in `docs/cli-numeric.md`; in short:
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
//!                                # { axis = [...], angle_deg = 30 }, { euler_deg = [r, p, y] }
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
use toml::Spanned;

use crate::body::{Body, Composite, MassProperties, Part, Pose, Primitive};
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: Option<String>,
    description: Option<String>,
    g: Option<V3>,
    reference: Option<V3>,
    #[serde(default)]
    body: Vec<Spanned<RawBody>>,
    #[serde(default)]
    cloud: Vec<Spanned<RawCloud>>,
    motion: Option<Spanned<RawMotion>>,
    impulse: Option<Spanned<RawImpulse>>,
    #[serde(default)]
    force: Vec<Spanned<RawForce>>,
    #[serde(default)]
    couple: Vec<Spanned<RawForce>>,
    #[serde(default)]
    constraint: Vec<Spanned<RawConstraint>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    name: Option<String>,
    shape: String,
    mass: Option<f64>,
    weight: Option<f64>,
    position: Option<V3>,
    rotation: Option<RawRotation>,
    length: Option<f64>,
    a: Option<f64>,
    b: Option<f64>,
    c: Option<f64>,
    radius: Option<f64>,
    inner: Option<f64>,
    outer: Option<f64>,
    height: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRotation {
    axis: Option<V3>,
    angle_deg: Option<f64>,
    x_axis: Option<V3>,
    z_axis: Option<V3>,
    euler_deg: Option<V3>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCloud {
    file: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    omega: Option<V3>,
    alpha: Option<V3>,
    frame_rate: Option<V3>,
    v_g: Option<V3>,
    a_g: Option<V3>,
    fixed_point: Option<V3>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImpulse {
    v_before: Option<V3>,
    omega_before: Option<V3>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawForce {
    name: String,
    point: Option<V3>,
    value: Option<V3>,
    direction: Option<V3>,
    unknown: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConstraint {
    name: String,
    point: V3,
    direction: V3,
    #[serde(default)]
    value: f64,
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

/// Line (1-based) of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

fn v3(a: V3) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

impl Scene {
    /// Reads and validates a scene file.
    pub fn from_path(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: path.to_path_buf(),
            line: 0,
            field: "-".into(),
            message: format!("cannot read file: {e}"),
        })?;
        Self::from_str_at(path, &text)
    }

    /// Parses scene text; `file` names it in errors and anchors relative
    /// cloud paths.
    pub fn from_str_at(file: &Path, text: &str) -> Result<Self, SceneError> {
        let err = |line: usize, field: &str, message: String| SceneError {
            file: file.to_path_buf(),
            line,
            field: field.to_string(),
            message,
        };
        let raw: RawScene = toml::from_str(text).map_err(|e| {
            let line = e.span().map(|s| line_of(text, s.start)).unwrap_or(0);
            err(line, "-", e.message().to_string())
        })?;
        let finite = |line: usize, field: &str, v: &[f64]| -> Result<(), SceneError> {
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return Err(err(line, field, format!("not finite: {x}")));
            }
            Ok(())
        };
        let top = 1;
        if let Some(g) = raw.g {
            finite(top, "g", &g)?;
        }
        if let Some(r) = raw.reference {
            finite(top, "reference", &r)?;
        }
        let g = raw.g.map(v3);
        let mut parts = Vec::new();
        for (i, sb) in raw.body.iter().enumerate() {
            let line = line_of(text, sb.span().start);
            let b = sb.get_ref();
            let f = |name: &str| format!("body[{i}].{name}");
            let dim = |name: &'static str, v: Option<f64>| {
                v.ok_or_else(|| err(line, &f(name), format!("missing for shape {:?}", b.shape)))
            };
            let shape = match b.shape.as_str() {
                "rod" => Primitive::Rod {
                    length: dim("length", b.length)?,
                },
                "plate" => Primitive::Plate {
                    a: dim("a", b.a)?,
                    b: dim("b", b.b)?,
                },
                "prism" => Primitive::Prism {
                    a: dim("a", b.a)?,
                    b: dim("b", b.b)?,
                    c: dim("c", b.c)?,
                },
                "disk" => Primitive::Disk {
                    radius: dim("radius", b.radius)?,
                },
                "cylinder" => Primitive::Cylinder {
                    radius: dim("radius", b.radius)?,
                    length: dim("length", b.length)?,
                },
                "hollow_cylinder" => Primitive::HollowCylinder {
                    inner: dim("inner", b.inner)?,
                    outer: dim("outer", b.outer)?,
                    length: dim("length", b.length)?,
                },
                "ring" => Primitive::Ring {
                    radius: dim("radius", b.radius)?,
                },
                "sphere" => Primitive::Sphere {
                    radius: dim("radius", b.radius)?,
                },
                "spherical_shell" => Primitive::SphericalShell {
                    radius: dim("radius", b.radius)?,
                },
                "cone" => Primitive::Cone {
                    radius: dim("radius", b.radius)?,
                    height: dim("height", b.height)?,
                },
                other => {
                    return Err(err(line, &f("shape"), format!("unknown shape {other:?}")));
                }
            };
            let mass = match (b.mass, b.weight) {
                (Some(m), None) => m,
                (None, Some(w)) => {
                    let gn = g.map(|g| g.norm()).filter(|n| *n > 0.0).ok_or_else(|| {
                        err(line, &f("weight"), "a weight needs a non-zero g".into())
                    })?;
                    w / gn
                }
                (Some(_), Some(_)) => {
                    return Err(err(
                        line,
                        &f("mass"),
                        "give mass or weight, not both".into(),
                    ));
                }
                (None, None) => return Err(err(line, &f("mass"), "missing (or weight)".into())),
            };
            let position = b.position.unwrap_or([0.0; 3]);
            finite(line, &f("position"), &position)?;
            let rotation = match &b.rotation {
                None => UnitQuaternion::identity(),
                Some(r) => rotation_of(r).map_err(|m| err(line, &f("rotation"), m))?,
            };
            let pose = Pose {
                position: v3(position),
                rotation,
            };
            let body = Body::try_new(shape, mass, pose).map_err(|e| {
                let field = match &e {
                    crate::BodyError::NonPositiveMass { .. } => f("mass"),
                    crate::BodyError::BadDimension { field, .. }
                    | crate::BodyError::NotFinite { field, .. } => f(field),
                    _ => f("-"),
                };
                err(line, &field, e.to_string())
            })?;
            let _ = &b.name;
            parts.push(Part::Solid(body));
        }
        for (i, sc) in raw.cloud.iter().enumerate() {
            let line = line_of(text, sc.span().start);
            let p = file
                .parent()
                .unwrap_or(Path::new("."))
                .join(&sc.get_ref().file);
            let c = ParticleCloud::from_csv_path(&p)
                .map_err(|e| err(line, &format!("cloud[{i}].file"), e.to_string()))?;
            parts.push(Part::Cloud(c));
        }
        let body = Composite::try_new(parts)
            .map_err(|_| err(0, "body", "the scene has no body and no cloud".into()))?;

        let props = body.mass_properties();
        let problem = match (&raw.motion, &raw.impulse) {
            (Some(_), Some(s)) => {
                return Err(err(
                    line_of(text, s.span().start),
                    "impulse",
                    "give [motion] or [impulse], not both".into(),
                ));
            }
            (None, None) => Problem::Statics,
            (Some(sm), None) => {
                let line = line_of(text, sm.span().start);
                let m = sm.get_ref();
                for (name, v) in [
                    ("omega", m.omega),
                    ("alpha", m.alpha),
                    ("frame_rate", m.frame_rate),
                    ("v_g", m.v_g),
                    ("a_g", m.a_g),
                    ("fixed_point", m.fixed_point),
                ] {
                    if let Some(v) = v {
                        finite(line, &format!("motion.{name}"), &v)?;
                    }
                }
                let omega = v3(m.omega.unwrap_or([0.0; 3]));
                let alpha = match (m.alpha, m.frame_rate) {
                    (Some(_), Some(_)) => {
                        return Err(err(
                            line,
                            "motion.frame_rate",
                            "give alpha or frame_rate, not both".into(),
                        ));
                    }
                    (Some(a), None) => v3(a),
                    (None, Some(f)) => v3(f).cross(&omega),
                    (None, None) => Vector3::zeros(),
                };
                match m.fixed_point {
                    Some(o) => {
                        if m.v_g.is_some() || m.a_g.is_some() {
                            return Err(err(
                                line,
                                "motion.fixed_point",
                                "v_g and a_g follow from a fixed point; do not give them".into(),
                            ));
                        }
                        Problem::Motion(Motion::about_fixed_point(
                            v3(o),
                            props.center,
                            omega,
                            alpha,
                        ))
                    }
                    None => Problem::Motion(Motion {
                        omega,
                        alpha,
                        v_g: v3(m.v_g.unwrap_or([0.0; 3])),
                        a_g: v3(m.a_g.unwrap_or([0.0; 3])),
                    }),
                }
            }
            (None, Some(si)) => {
                let line = line_of(text, si.span().start);
                let i = si.get_ref();
                let vb = i.v_before.unwrap_or([0.0; 3]);
                let wb = i.omega_before.unwrap_or([0.0; 3]);
                finite(line, "impulse.v_before", &vb)?;
                finite(line, "impulse.omega_before", &wb)?;
                Problem::Impulse {
                    v_before: v3(vb),
                    omega_before: v3(wb),
                }
            }
        };
        let reference = raw
            .reference
            .map(v3)
            .or_else(|| {
                raw.motion
                    .as_ref()
                    .and_then(|m| m.get_ref().fixed_point.map(v3))
            })
            .unwrap_or_else(Vector3::zeros);

        let load = |kind: &str, i: usize, s: &Spanned<RawForce>, couple: bool| {
            let line = line_of(text, s.span().start);
            let l = s.get_ref();
            let f = |n: &str| format!("{kind}[{i}].{n}");
            let point = match (l.point, couple) {
                (Some(p), _) => {
                    finite(line, &f("point"), &p)?;
                    v3(p)
                }
                (None, true) => Vector3::zeros(),
                (None, false) => return Err(err(line, &f("point"), "missing".into())),
            };
            let known = v3(l.value.unwrap_or([0.0; 3]));
            finite(line, &f("value"), known.as_slice())?;
            let mut unknowns = Vec::new();
            if let Some(d) = l.direction {
                finite(line, &f("direction"), &d)?;
                let d = Unit::try_new(v3(d), 1e-300)
                    .ok_or_else(|| err(line, &f("direction"), "zero vector".into()))?;
                unknowns.push((l.name.clone(), d.into_inner()));
            }
            for c in l.unknown.iter().flatten() {
                let axis = match c.as_str() {
                    "x" => Vector3::x(),
                    "y" => Vector3::y(),
                    "z" => Vector3::z(),
                    other => {
                        return Err(err(
                            line,
                            &f("unknown"),
                            format!("unknown component {other:?} (use \"x\", \"y\", \"z\")"),
                        ));
                    }
                };
                unknowns.push((format!("{}_{c}", l.name), axis));
            }
            if l.value.is_none() && unknowns.is_empty() {
                return Err(err(
                    line,
                    &f("value"),
                    "give a value, a direction (unknown magnitude) or unknown components".into(),
                ));
            }
            Ok(Load {
                name: l.name.clone(),
                point,
                known,
                unknowns,
            })
        };
        let forces = raw
            .force
            .iter()
            .enumerate()
            .map(|(i, s)| load("force", i, s, false))
            .collect::<Result<Vec<_>, _>>()?;
        let couples = raw
            .couple
            .iter()
            .enumerate()
            .map(|(i, s)| load("couple", i, s, true))
            .collect::<Result<Vec<_>, _>>()?;
        let mut constraints = Vec::new();
        for (i, s) in raw.constraint.iter().enumerate() {
            let line = line_of(text, s.span().start);
            let c = s.get_ref();
            let f = |n: &str| format!("constraint[{i}].{n}");
            if !matches!(problem, Problem::Impulse { .. }) {
                return Err(err(
                    line,
                    &f("name"),
                    "constraints need an [impulse] problem".into(),
                ));
            }
            finite(line, &f("point"), &c.point)?;
            finite(line, &f("direction"), &c.direction)?;
            finite(line, &f("value"), &[c.value])?;
            let d = Unit::try_new(v3(c.direction), 1e-300)
                .ok_or_else(|| err(line, &f("direction"), "zero vector".into()))?;
            constraints.push(Constraint {
                name: c.name.clone(),
                point: v3(c.point),
                direction: d.into_inner(),
                value: c.value,
            });
        }
        let mut names = std::collections::BTreeSet::new();
        for l in forces.iter().chain(&couples) {
            for (n, _) in &l.unknowns {
                if !names.insert(n.clone()) {
                    return Err(err(0, n, "two unknowns with the same name".into()));
                }
            }
        }
        Ok(Scene {
            name: raw.name.unwrap_or_else(|| file.display().to_string()),
            description: raw.description.unwrap_or_default(),
            body,
            g,
            reference,
            problem,
            forces,
            couples,
            constraints,
        })
    }
}

fn rotation_of(r: &RawRotation) -> Result<UnitQuaternion<f64>, String> {
    let given = [
        r.axis.is_some() || r.angle_deg.is_some(),
        r.x_axis.is_some(),
        r.z_axis.is_some(),
        r.euler_deg.is_some(),
    ]
    .iter()
    .filter(|b| **b)
    .count();
    if given != 1 {
        return Err("give exactly one of {axis, angle_deg}, x_axis, z_axis, euler_deg".to_string());
    }
    let unit = |v: V3, name: &str| {
        if v.iter().any(|x| !x.is_finite()) {
            return Err(format!("{name} is not finite"));
        }
        Unit::try_new(v3(v), 1e-300).ok_or_else(|| format!("{name} is the zero vector"))
    };
    if let Some(a) = r.x_axis {
        let a = unit(a, "x_axis")?;
        return Ok(
            UnitQuaternion::rotation_between_axis(&Vector3::x_axis(), &a).unwrap_or_else(|| {
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI)
            }),
        );
    }
    if let Some(a) = r.z_axis {
        let a = unit(a, "z_axis")?;
        return Ok(
            UnitQuaternion::rotation_between_axis(&Vector3::z_axis(), &a).unwrap_or_else(|| {
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
            }),
        );
    }
    if let Some([r_, p, y]) = r.euler_deg {
        if [r_, p, y].iter().any(|x| !x.is_finite()) {
            return Err("euler_deg is not finite".into());
        }
        return Ok(UnitQuaternion::from_euler_angles(
            r_.to_radians(),
            p.to_radians(),
            y.to_radians(),
        ));
    }
    let axis = unit(r.axis.ok_or("axis missing (with angle_deg)")?, "axis")?;
    let angle = r.angle_deg.ok_or("angle_deg missing (with axis)")?;
    if !angle.is_finite() {
        return Err("angle_deg is not finite".into());
    }
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
                    sys.push(
                        format!("linear momentum {}", ["x", "y", "z"][axis]),
                        row,
                        m * v_before[axis] + f_known[axis],
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
                    sys.push(
                        format!("angular momentum {}", ["x", "y", "z"][axis]),
                        row,
                        h1[axis] + m_known_g[axis],
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
        let scale_h = s.h_g.norm() + s.h_o.norm() + (s.momentum.norm() * 1.0);
        let scale_a = s.force.norm() + s.hdot_g.norm() + s.moment_o.norm();
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
