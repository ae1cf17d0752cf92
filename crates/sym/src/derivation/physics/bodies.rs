//! Reading a `[[point]]` table into a [`Point`] and a `[[body]]` table
//! into a [`Body`] (its frame, reference point, mass, mass centre, inertia
//! and symmetry), each checked against the file's frames and points.

use toml::Spanned;

use super::check::{constant, parse_spanned, unknown};
use super::{Body, Point, PointKind, Symmetry};
use crate::derivation::context::{Context, R};
use crate::derivation::raw::{RawBody, RawPoint};
use crate::derivation::value::Value;
use crate::vector::Vec3;

pub(super) fn point(
    cx: &Context<'_>,
    p: &RawPoint,
    known_point: &dyn Fn(&Spanned<String>) -> R<String>,
) -> R<Point> {
    let fixed = p.fixed.as_ref().is_some_and(|f| *f.get_ref());
    let at = match &p.at {
        Some(a) => {
            let (ast, base) = parse_spanned(cx, a)?;
            Some(cx.vector(&ast, base)?)
        }
        None => None,
    };
    let kind = match (fixed, &p.from, at) {
        (true, Some(f), _) => {
            let n = f.get_ref().len();
            return Err(cx.diag_string(f, 0, n, "a fixed point is at `at` from the origin of N; `from` is for a point that moves with others"));
        }
        (true, None, Some((v, f))) => {
            constant(cx, &v, p.at.as_ref().expect("at"), "at")?;
            if cx.frame(&f).parent.is_some() || !cx.frame(&f).omega.is_zero() {
                let a = p.at.as_ref().expect("at");
                return Err(cx.diag_string(
                    a,
                    0,
                    a.get_ref().len(),
                    "a fixed point's `at` is in the components of an inertial frame (`in N`)",
                ));
            }
            PointKind::Fixed(v, f)
        }
        (true, None, None) => PointKind::Fixed(Vec3::zero(), "N".into()),
        (false, Some(from), Some((at, frame))) => PointKind::From {
            from: known_point(from)?,
            at,
            frame,
        },
        (false, Some(f), None) => {
            let n = f.get_ref().len();
            return Err(cx.diag_string(f, 0, n, "`from` needs `at`, the vector from that point"));
        }
        (false, None, Some(_)) => {
            let a = p.at.as_ref().expect("at");
            return Err(cx.diag_string(
                a,
                0,
                a.get_ref().len(),
                "`at` needs `from` (or `fixed = true`)",
            ));
        }
        (false, None, None) => PointKind::Free,
    };
    Ok(Point {
        name: p.name.get_ref().clone(),
        doc: p.doc.clone(),
        kind,
    })
}

pub(super) fn body(
    cx: &Context<'_>,
    b: &RawBody,
    centre: Option<String>,
    known_point: &dyn Fn(&Spanned<String>) -> R<String>,
) -> R<Body> {
    let frames: Vec<String> = cx.frames.iter().map(|f| f.name.clone()).collect();
    let frame = cx.frame_index(b.frame.get_ref()).ok_or_else(|| {
        cx.diag_string(
            &b.frame,
            0,
            b.frame.get_ref().len(),
            unknown("frame", b.frame.get_ref(), &frames),
        )
    })?;
    let point = match &b.point {
        Some(p) => known_point(p)?,
        None => match &centre {
            Some(c) => c.clone(),
            None => {
                let n = b.name.get_ref().len();
                return Err(cx.diag_string(&b.name, 0, n, "say the body's reference point with `point` (or name its centre with `centre`)"));
            }
        },
    };
    let mass = match &b.mass {
        None => None,
        Some(s) => {
            let mass = cx.scalar_in(s)?;
            if mass.atoms().iter().any(|a| a.is_time_dependent()) || mass.is_zero() {
                let n = s.get_ref().len();
                return Err(cx.diag_string(
                    s,
                    0,
                    n,
                    "`mass` is a non-zero expression of constants",
                ));
            }
            Some(mass)
        }
    };
    let own = &cx.frames[frame].name;
    let mass_centre = match &b.mass_centre {
        Some(s) => {
            let (ast, base) = parse_spanned(cx, s)?;
            let (v, f) = cx.vector(&ast, base)?;
            if &f != own {
                return Err(cx.at(
                    base,
                    ast.span,
                    format!("`mass_centre` is given in the body frame's components (`in {own}`)"),
                ));
            }
            constant(cx, &v, s, "mass_centre")?;
            if centre.as_deref() == Some(point.as_str()) && !v.is_zero() {
                return Err(cx.at(
                    base,
                    ast.span,
                    "the reference point is the mass centre, so `mass_centre` is zero",
                ));
            }
            Some(v)
        }
        None if centre.as_deref() == Some(point.as_str()) => Some(Vec3::zero()),
        // G wherever the drawn body has it (no step may use its position).
        None => None,
    };
    let inertia_about_centre = match &b.inertia_about {
        None => false,
        Some(a) if Some(a.get_ref()) == centre.as_ref() => {
            if mass_centre.is_none() {
                return Err(cx.diag_string(
                    a,
                    0,
                    a.get_ref().len(),
                    "with the inertia about the centre, `mass_centre` says where the centre is from the reference point",
                ));
            }
            centre.as_deref() != Some(point.as_str())
        }
        Some(a) if a.get_ref() == &point => false,
        Some(a) => {
            return Err(cx.diag_string(
                a,
                0,
                a.get_ref().len(),
                format!(
                    "`inertia_about` is the reference point ({point}) or the body's centre ({})",
                    centre
                        .as_deref()
                        .unwrap_or("unnamed: name it with `centre`")
                ),
            ));
        }
    };
    let (ast, base) = parse_spanned(cx, &b.inertia)?;
    let inertia = match cx.eval(&ast, base)? {
        Value::Matrix(m) => m,
        v => {
            return Err(cx.at(
                base,
                ast.span,
                format!(
                    "`inertia` is a matrix, such as principal(A, B, C); found {}",
                    v.describe()
                ),
            ));
        }
    };
    if inertia
        .0
        .iter()
        .flatten()
        .any(|p| p.atoms().iter().any(|a| a.is_time_dependent()))
    {
        return Err(cx.at(
            base,
            ast.span,
            "`inertia` must be an expression of constants",
        ));
    }
    if !inertia.is_symmetric() {
        return Err(cx.at(base, ast.span, "an inertia tensor is symmetric"));
    }
    let symmetry = match &b.symmetry {
        None => Symmetry::None,
        Some(s) => symmetry(cx, s, &cx.frames[frame].axes)?,
    };
    Ok(Body {
        name: b.name.get_ref().clone(),
        doc: b.doc.clone(),
        frame,
        point,
        centre,
        mass,
        mass_centre,
        inertia,
        inertia_about_centre,
        symmetry,
    })
}

pub(super) fn symmetry(cx: &Context<'_>, s: &Spanned<String>, axes: &[String; 3]) -> R<Symmetry> {
    let text = s.get_ref();
    let words: Vec<&str> = text.split_whitespace().collect();
    let axis = |a: &str| axes.iter().position(|x| x == a);
    let sym = match words.as_slice() {
        ["none"] => Some(Symmetry::None),
        ["principal"] => Some(Symmetry::Principal),
        ["axisymmetric", a] => axis(a).map(Symmetry::Axisymmetric),
        ["plane", p] => {
            let ks: Vec<usize> = axes
                .iter()
                .enumerate()
                .filter(|(_, a)| p.contains(a.as_str()))
                .map(|(k, _)| k)
                .collect();
            let joined = |i: usize, j: usize| format!("{}{}", axes[i], axes[j]);
            match ks.as_slice() {
                [i, j] if *p == joined(*i, *j) || *p == joined(*j, *i) => {
                    Some(Symmetry::Plane(3 - i - j))
                }
                _ => None,
            }
        }
        _ => None,
    };
    sym.ok_or_else(|| {
        cx.diag_string(
            s,
            0,
            text.len(),
            format!(
                "expected `none`, `principal`, `axisymmetric {z}` (an axis of the body frame: {a}) or `plane {x}{y}`",
                z = axes[2],
                x = axes[0],
                y = axes[1],
                a = axes.join(", ")
            ),
        )
    })
}
