//! Reading a file's declarations in order: how each frame moves, gravity,
//! the names of points and bodies, `[[known]]`s and `[motion]`; with the
//! small checks the other readers of the model share.

use std::collections::HashSet;

use toml::Spanned;

use super::bodies::{body, point};
use super::centres::centre_points;
use super::check::{constant, parse_spanned, unknown};
use super::conditions::rule;
use super::means::{check_shape, meaning};
use super::supports::supports;
use super::{FrameMotion, Known, Physics, PointKind, Shape};
use crate::atom::{Atom, AtomKind};
use crate::derivation::context::{Context, R};
use crate::derivation::raw::{RawFile, RawKnown};
use crate::derivation::value::Value;
use crate::vector::Mat3;

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

/// A hinge's axis and angle from its matrix cos q E + sin q [k]× +
/// (1 − cos q) k kᵀ (`derivation/joints.rs`): [k]× is the coefficient of
/// sin q.
fn hinge_of(m: &Mat3) -> Option<(crate::vector::Vec3, Atom)> {
    // The angle is the one whose sine's coefficients form a unit axis free
    // of it (the axis may hold sines of constants, such as a tilt).
    let mut angles: Vec<Atom> =
        m.0.iter()
            .flatten()
            .flat_map(|p| p.atoms())
            .filter_map(|a| match a.kind() {
                AtomKind::Sin(q) => Some(q),
                _ => None,
            })
            .collect();
    angles.dedup();
    angles.into_iter().find_map(|q| {
        let sin = Atom::sin(q)?;
        let k = |i: usize, j: usize| crate::derivation::ops::coefficient(&m.0[i][j], sin);
        let k = crate::vector::Vec3([k(2, 1), k(0, 2), k(1, 0)]);
        let free = k.0.iter().all(|p| !crate::subst::mentions_symbol(p, q));
        (free && k.dot(&k) == crate::poly::Poly::one()).then_some((k, q))
    })
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
                let parent = cx.frame_index(p).expect("parent exists");
                match (f.quaternion, rotation_of(m)) {
                    (Some(e), _) => FrameMotion::Quaternion { parent, e },
                    (None, Some((axis, angle))) => FrameMotion::Rotation {
                        parent,
                        axis,
                        angle,
                    },
                    (None, None) => {
                        let (axis, angle) = hinge_of(m).expect("frames turn about one axis");
                        FrameMotion::Hinge {
                            parent,
                            axis,
                            angle,
                        }
                    }
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
        cx.valid_name(s, what)?;
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
            // A [[point]] of the same name: accepted at the same place
            // (`centres.rs`), once.
            Some(c)
                if raw.points.iter().any(|p| p.name.get_ref() == c.get_ref())
                    && !centres.iter().flatten().any(|x: &String| x == c.get_ref()) =>
            {
                Some(c.get_ref().clone())
            }
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
    let mut point_names: Vec<String> = raw
        .points
        .iter()
        .map(|p| p.name.get_ref().clone())
        .collect();
    for c in centres.iter().flatten() {
        if !point_names.contains(c) {
            point_names.push(c.clone());
        }
    }
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
    ph.centres = centre_points(cx, raw, &ph)?;
    ph.supports = supports(cx, &ph, &raw.supports)?;
    for k in &raw.knowns {
        ph.knowns.push(known(cx, &ph, k)?);
    }
    if let Some(m) = &raw.motion {
        for r in &m.given {
            let r = rule(cx, &ph, r)?;
            ph.motion.push(r);
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
