//! The worked problem of a scene: `[motion]` or `[impulse]`, the reference
//! point, the `[[force]]` and `[[couple]]` loads with their named unknowns,
//! and the `[[constraint]]`s of an impact, read into a [`Scene`].

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use nalgebra::Vector3;
use serde::Deserialize;
use toml::Spanned;

use super::bodies::{Bodies, RawBodies, RawBody, RawCloud, from_raw, parse_error};
use super::read::{Cx, RF, RV, v3};
use super::{Constraint, Load, Problem, Scene, SceneError};
use crate::body::MassProperties;
use crate::sums::Motion;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: Option<String>,
    description: Option<String>,
    // The schema every scene shares (`bodies.rs`), read here so that the
    // text is parsed once: a scene of 100,000 tables spent half its time
    // parsing them a second time.
    g: Option<RV>,
    reference: Option<RV>,
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

impl Scene {
    /// Parses scene text; `file` names it in errors and anchors relative
    /// cloud paths.
    pub fn from_str_at(file: &Path, text: &str) -> Result<Self, SceneError> {
        let cx = Cx::new(file, text);
        let mut raw: RawScene = toml::from_str(text).map_err(|e| parse_error(&cx, &e))?;
        let reference = raw
            .reference
            .as_ref()
            .map(|r| cx.vec3("reference", r))
            .transpose()?;
        let shared = RawBodies {
            g: raw.g.take(),
            body: std::mem::take(&mut raw.body),
            cloud: std::mem::take(&mut raw.cloud),
        };
        let all = from_raw(&cx, shared)?;
        all.refuse_of(file)?;
        let Bodies { g, body, .. } = all;
        let body =
            body.ok_or_else(|| cx.err(0, "body", "the scene has no body and no cloud".into()))?;

        let props = body.mass_properties();
        let problem = problem_of(&cx, &raw, &props)?;
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
        let mut forces = Vec::new();
        for (i, s) in raw.force.iter().enumerate() {
            forces.push(load_of(&cx, &mut names, ("force", i), s, false)?);
        }
        let mut couples = Vec::new();
        for (i, s) in raw.couple.iter().enumerate() {
            couples.push(load_of(&cx, &mut names, ("couple", i), s, true)?);
        }
        let mut constraints = Vec::new();
        for (i, s) in raw.constraint.iter().enumerate() {
            constraints.push(constraint_of(&cx, &problem, i, s)?);
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

/// What the scene asks: statics, or the `[motion]` or `[impulse]` given.
fn problem_of(cx: &Cx<'_>, raw: &RawScene, props: &MassProperties) -> Result<Problem, SceneError> {
    match (&raw.motion, &raw.impulse) {
        (Some(_), Some(s)) => Err(cx.err(
            cx.lines.of(s.span().start),
            "impulse",
            "give [motion] or [impulse], not both".into(),
        )),
        (None, None) => Ok(Problem::Statics),
        (Some(sm), None) => motion_of(cx, sm.get_ref(), props),
        (None, Some(si)) => {
            let i = si.get_ref();
            let get = |name: &str, v: &Option<RV>| -> Result<Vector3<f64>, SceneError> {
                Ok(v.as_ref()
                    .map(|v| cx.vec3(&format!("impulse.{name}"), v).map(v3))
                    .transpose()?
                    .unwrap_or_else(Vector3::zeros))
            };
            Ok(Problem::Impulse {
                v_before: get("v_before", &i.v_before)?,
                omega_before: get("omega_before", &i.omega_before)?,
            })
        }
    }
}

/// The instantaneous motion of a `[motion]` table: ω, α (or the frame
/// rate Ω with α = Ω × ω), and v̄, ā or a fixed point.
fn motion_of(cx: &Cx<'_>, m: &RawMotion, props: &MassProperties) -> Result<Problem, SceneError> {
    let get = |name: &str, v: &Option<RV>| -> Result<Option<Vector3<f64>>, SceneError> {
        v.as_ref()
            .map(|v| cx.vec3(&format!("motion.{name}"), v).map(v3))
            .transpose()
    };
    let omega = get("omega", &m.omega)?.unwrap_or_else(Vector3::zeros);
    let alpha = get("alpha", &m.alpha)?;
    // ω² and α times the body's inertia and mass must stay in f64's range
    // with room (the moments square ω): else the rates are named, at
    // their line, not a resultant that came out infinite.
    let scale = props.inertia_g.matrix().amax() + props.mass;
    for (name, raw, size) in [
        ("omega", &m.omega, omega.norm_squared()),
        ("alpha", &m.alpha, alpha.map_or(0.0, |a| a.norm())),
    ] {
        if !(size * scale * 1e6).is_finite() {
            return Err(cx.err(
                raw.as_ref().map_or(0, |v| cx.line(v)),
                &format!("motion.{name}"),
                format!(
                    "with this body's mass and inertia the moments of `{name}` are beyond the range \
                     of f64: rescale the units"
                ),
            ));
        }
    }
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
            Ok(Problem::Motion(Motion::about_fixed_point(
                o,
                props.center,
                omega,
                alpha,
            )))
        }
        None => Ok(Problem::Motion(Motion {
            omega,
            alpha,
            v_g: v_g.unwrap_or_else(Vector3::zeros),
            a_g: a_g.unwrap_or_else(Vector3::zeros),
        })),
    }
}

/// A `[[force]]` or `[[couple]]` table (`kind`, index): its known part and
/// its unknown scalars, each name recorded in `names` with its line so
/// that a second unknown of the same name is refused.
fn load_of(
    cx: &Cx<'_>,
    names: &mut BTreeMap<String, usize>,
    (kind, i): (&str, usize),
    s: &Spanned<RawForce>,
    couple: bool,
) -> Result<Load, SceneError> {
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
    let mut axes = BTreeSet::new();
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
}

/// A `[[constraint]]` table (only an impulse problem has them).
fn constraint_of(
    cx: &Cx<'_>,
    problem: &Problem,
    i: usize,
    s: &Spanned<RawConstraint>,
) -> Result<Constraint, SceneError> {
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
    Ok(Constraint {
        name: c.name.clone(),
        point,
        direction,
        value,
    })
}
