//! What moves in a scene, the schema every scene shares: gravity `g`,
//! the `[[body]]` tables (primitives, points, principal moments or an
//! inertia tensor) and the
//! `[[cloud]]` tables, grouped by the derivation body they make up.

use std::path::Path;

use nalgebra::{Unit, UnitQuaternion, Vector3};
use serde::Deserialize;
use serde::de::IgnoredAny;
use toml::Spanned;

use super::SceneError;
use super::read::{Cx, RF, RV, props_finite, safe_norm, v3};
use crate::body::{Body, Composite, MassProperties, Part, Pose, Primitive, eulerian_rotation};
use crate::cloud::ParticleCloud;
use crate::inertia::Inertia;

/// The part of every scene that says what moves, as written: gravity,
/// `[[body]]` and `[[cloud]]` (unknown keys are left to the scene's own
/// reader). A scene's own reader (a worked problem's, a simulation's)
/// reads these fields in its own parse of the text and hands them to
/// [`bodies_from`], so that a scene of many tables is parsed once.
#[derive(Debug, Deserialize)]
pub struct RawBodies {
    /// `g`.
    pub g: Option<Spanned<Vec<f64>>>,
    /// The `[[body]]` tables.
    #[serde(default)]
    pub body: Vec<Spanned<RawBody>>,
    /// The `[[cloud]]` tables.
    #[serde(default)]
    pub cloud: Vec<Spanned<RawCloud>>,
}

/// One `[[body]]` table as written (read by [`bodies_from`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    name: Option<String>,
    of: Option<Spanned<String>>,
    shape: Option<String>,
    principal_moments: Option<RV>,
    inertia: Option<Spanned<Vec<Vec<f64>>>>,
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

/// One `[[cloud]]` table as written (read by [`bodies_from`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCloud {
    file: String,
    of: Option<Spanned<String>>,
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
    let raw: RawBodies = toml::from_str(text).map_err(|e| parse_error(&cx, &e))?;
    from_raw(&cx, raw)
}

/// [`bodies`] from the tables a scene's own reader parsed (`text` is the
/// scene's text, for the lines of errors).
pub fn bodies_from(file: &Path, text: &str, raw: RawBodies) -> Result<Bodies, SceneError> {
    from_raw(&Cx::new(file, text), raw)
}

/// The error of a scene's text that does not parse into its tables: the
/// former `[body]` table named as such, otherwise the parser's message at
/// its line.
pub(super) fn parse_error(cx: &Cx<'_>, e: &toml::de::Error) -> SceneError {
    if let Some(err) = old_body_table(cx) {
        return err;
    }
    let line = e.span().map(|s| cx.lines.of(s.start)).unwrap_or(0);
    cx.err(line, "-", e.message().to_string())
}

/// [`bodies`] from the tables as parsed.
pub(super) fn from_raw(cx: &Cx<'_>, raw: RawBodies) -> Result<Bodies, SceneError> {
    let file = cx.file;
    let g = raw.g.as_ref().map(|g| cx.vec3("g", g)).transpose()?;
    let g_line = raw.g.as_ref().map_or(0, |g| cx.line(g));
    let g = g.map(v3);
    let mut parts = Vec::new();
    // Per part: its `of`, the field naming it and the line.
    let mut owners: Vec<Owner> = Vec::new();
    for (i, sb) in raw.body.iter().enumerate() {
        let line = cx.lines.of(sb.span().start);
        owners.push(match &sb.get_ref().of {
            Some(o) => (
                Some(o.get_ref().clone()),
                format!("body[{i}].of"),
                cx.line(o),
            ),
            None => (None, format!("body[{i}]"), line),
        });
        parts.push(part_of(cx, i, sb, g)?);
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
    let overflows = |parts: &[MassProperties]| match MassProperties::combine(parts) {
        Ok(p) => !props_finite(&p),
        Err(e) => matches!(e, crate::BodyError::NotFinite { .. }),
    };
    if overflows(&all) {
        // The table that takes the sums past the largest number: the last
        // of the shortest overflowing prefix (found by bisection; the
        // first part alone is finite, checked when it was read).
        let (mut ok, mut bad) = (0, all.len());
        while bad - ok > 1 {
            let mid = (ok + bad) / 2;
            if overflows(&all[..mid]) {
                bad = mid;
            } else {
                ok = mid;
            }
        }
        let (_, field, line) = &owners[bad - 1];
        let table = field.strip_suffix(".of").unwrap_or(field);
        return Err(cx.err(
            *line,
            table,
            "with the tables before it, the mass properties of the bodies together overflow (masses \
             summing past the largest number, or bodies too far apart)"
                .into(),
        ));
    }
    let groups = groups_of(cx, &parts, &owners)?;
    let body = if parts.is_empty() {
        None
    } else {
        Some(Composite::try_new(parts).map_err(|e| cx.err(0, "body", e.to_string()))?)
    };
    Ok(Bodies {
        g,
        g_line,
        body,
        groups,
    })
}

/// Who a part belongs to: its `of` (if any), the field naming it, its line.
type Owner = (Option<String>, String, usize);

/// The parts grouped by their `of`, in the order of each group's first part.
fn groups_of(cx: &Cx<'_>, parts: &[Part], owners: &[Owner]) -> Result<Vec<Group>, SceneError> {
    let mut groups: Vec<Group> = Vec::new();
    for (of, field, line) in owners {
        if groups.iter().any(|g| &g.of == of) {
            continue;
        }
        let mine: Vec<Part> = parts
            .iter()
            .zip(owners)
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
    Ok(groups)
}

/// The `i`-th `[[body]]` table as a part: a primitive shape, a point, or
/// the six points equivalent to given principal moments.
fn part_of(
    cx: &Cx<'_>,
    i: usize,
    sb: &Spanned<RawBody>,
    g: Option<Vector3<f64>>,
) -> Result<Part, SceneError> {
    let line = cx.lines.of(sb.span().start);
    let b = sb.get_ref();
    let f = |name: &str| format!("body[{i}].{name}");
    let (mass, mass_field) = mass_of(cx, i, line, b, g)?;
    let position = match &b.position {
        Some(p) => cx.vec3(&f("position"), p)?,
        None => [0.0; 3],
    };
    let rotation = match &b.rotation {
        None => UnitQuaternion::identity(),
        Some(r) => rotation_of(cx, &f("rotation"), r)?,
    };
    let pose = Pose {
        position: v3(position),
        rotation,
    };
    let given = [
        b.shape.is_some(),
        b.principal_moments.is_some(),
        b.inertia.is_some(),
    ];
    if given.iter().filter(|g| **g).count() > 1 {
        let (key, at) = match (&b.principal_moments, &b.inertia) {
            (Some(pm), None) => ("principal_moments", cx.line(pm)),
            (_, Some(t)) => ("inertia", cx.line(t)),
            (None, None) => ("shape", line),
        };
        return Err(cx.err(
            at,
            &f(key),
            "give one of `shape`, `principal_moments` or `inertia`, not several".into(),
        ));
    }
    if let Some(pm) = &b.principal_moments {
        let m = check_part_mass(cx, &f("mass"), mass_field, mass)?;
        let field = f("principal_moments");
        let moments = cx.vec3(&field, pm)?;
        return Ok(Part::Cloud(equivalent_points(
            cx,
            (&field, cx.line(pm)),
            moments,
            m,
            &pose,
        )?));
    }
    if let Some(t) = &b.inertia {
        let m = check_part_mass(cx, &f("mass"), mass_field, mass)?;
        return Ok(Part::Cloud(tensor_points(cx, &f("inertia"), t, m, &pose)?));
    }
    let Some(shape_name) = b.shape.as_deref() else {
        return Err(cx.err(
            line,
            &f("shape"),
            "missing (or `principal_moments`, or `inertia`)".into(),
        ));
    };
    if shape_name == "point" {
        let m = check_part_mass(cx, &f("mass"), mass_field, mass)?;
        let c = ParticleCloud::try_from_particles([(pose.position, m)])
            .map_err(|e| cx.err(line, &f("position"), e.to_string()))?;
        return Ok(Part::Cloud(c));
    }
    let shape = primitive_of(cx, i, line, shape_name, b)?;
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
            crate::BodyError::NonPositiveMass { .. } | crate::BodyError::TinyMass { .. } => "mass",
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
    Ok(Part::Solid(body))
}

/// A body table's mass, given as `mass` or as `weight` (with a non-zero
/// `g`), and the value it was read from.
fn mass_of<'b>(
    cx: &Cx<'_>,
    i: usize,
    line: usize,
    b: &'b RawBody,
    g: Option<Vector3<f64>>,
) -> Result<(f64, &'b RF), SceneError> {
    let f = |name: &str| format!("body[{i}].{name}");
    match (&b.mass, &b.weight) {
        (Some(m), None) => Ok((cx.scalar(&f("mass"), m)?, m)),
        (None, Some(w)) => {
            let wv = cx.scalar(&f("weight"), w)?;
            let gn = g
                .map(|g| safe_norm(&g))
                .filter(|n| *n > 0.0)
                .ok_or_else(|| {
                    cx.err(
                        cx.line(w),
                        &f("weight"),
                        "a weight needs a non-zero g".into(),
                    )
                })?;
            Ok((wv / gn, w))
        }
        (Some(m), Some(_)) => Err(cx.err(
            cx.line(m),
            &f("mass"),
            "give mass or weight, not both".into(),
        )),
        (None, None) => Err(cx.err(line, &f("mass"), "missing (or weight)".into())),
    }
}

/// The primitive a body table's `shape` names, with its dimensions.
fn primitive_of(
    cx: &Cx<'_>,
    i: usize,
    line: usize,
    shape_name: &str,
    b: &RawBody,
) -> Result<Primitive, SceneError> {
    let f = |name: &str| format!("body[{i}].{name}");
    let dim = |name: &'static str, v: &Option<RF>| match v {
        Some(v) => cx.scalar(&f(name), v),
        None => Err(cx.err(line, &f(name), format!("missing for shape {shape_name:?}"))),
    };
    Ok(match shape_name {
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
    })
}

/// A part's mass, checked positive and finite (for the parts that are not
/// primitives, whose mass [`Body::try_new`] checks).
fn check_part_mass(cx: &Cx<'_>, field: &str, at: &RF, mass: f64) -> Result<f64, SceneError> {
    crate::mass::check_mass("body", mass).map_err(|e| cx.err(cx.line(at), field, e.to_string()))?;
    Ok(mass)
}

/// A part known by its mass and inertia tensor about its G, in its local
/// axes (`inertia = [[I_xx, -P_xy, …], …]`, the tensor's entries): the six
/// points of [`equivalent_points`] along its principal axes.
fn tensor_points(
    cx: &Cx<'_>,
    field: &str,
    t: &Spanned<Vec<Vec<f64>>>,
    mass: f64,
    pose: &Pose,
) -> Result<ParticleCloud, SceneError> {
    let line = cx.line(t);
    let bad = |message: String| cx.err(line, field, message);
    let rows = t.get_ref();
    if rows.len() != 3 || rows.iter().any(|r| r.len() != 3) {
        return Err(bad(
            "an inertia tensor is 3 rows of 3 numbers, [[I_xx, I_xy, I_xz], [I_xy, I_yy, I_yz],              [I_xz, I_yz, I_zz]]"
                .into(),
        ));
    }
    if let Some(x) = rows.iter().flatten().find(|x| !x.is_finite()) {
        return Err(bad(format!("not finite: {x}")));
    }
    let m = nalgebra::Matrix3::from_fn(|r, c| rows[r][c]);
    let i = Inertia::try_new(m).map_err(|e| bad(e.to_string()))?;
    let p = i.principal();
    let along = Pose {
        position: pose.position,
        rotation: pose.rotation * UnitQuaternion::from_rotation_matrix(&p.axes),
    };
    equivalent_points(cx, (field, line), p.moments.into(), mass, &along)
}

/// A part known by its mass and principal moments about its G (in its
/// local axes): six particles of mass m/6 at ±a, ±b, ±c on the local axes,
/// with the same mass, centre and inertia, `I_x = (m/3)(b² + c²)` and so on
/// (a real body exists for these moments exactly when the triangle
/// inequalities hold, and then a², b², c² ≥ 0). `at` is the field and line
/// the moments were given at.
fn equivalent_points(
    cx: &Cx<'_>,
    at: (&str, usize),
    moments: [f64; 3],
    mass: f64,
    pose: &Pose,
) -> Result<ParticleCloud, SceneError> {
    let [ix, iy, iz] = moments;
    let bad = |message: String| cx.err(at.1, at.0, message);
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
