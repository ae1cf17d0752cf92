//! Reading a `[[support]]` table: where and how a body is held (a bearing
//! with the components it carries, a ball-and-socket joint or fixed
//! point, a clamp, a contact with the floor, a drive about an axis), with
//! the count of its reaction components checked against the six
//! equations of the body's motion. The verifier solves for the reactions
//! (`hdot_num::verify::reactions`).

use toml::Spanned;

use super::check::{parse_spanned, unknown};
use super::{Physics, Support, SupportKind};
use crate::derivation::context::{Context, R};
use crate::derivation::raw::RawSupport;

/// The words of `kind`, for messages.
const KINDS: &str = "bearing, ball, fixed, clamp, floor, drive";

/// Reads the supports of `raw` (after the points and bodies).
pub(super) fn supports(cx: &Context<'_>, ph: &Physics, raw: &[RawSupport]) -> R<Vec<Support>> {
    let mut out: Vec<Support> = Vec::new();
    for s in raw {
        let sup = support(cx, ph, s)?;
        if out.iter().any(|o| o.name == sup.name) {
            return Err(whole(
                cx,
                &s.name,
                "a support of this name is already declared",
            ));
        }
        out.push(sup);
    }
    for (b, body) in ph.bodies.iter().enumerate() {
        let held: Vec<&Support> = out.iter().filter(|s| s.body == b).collect();
        let n: usize = held
            .iter()
            .map(|s| {
                let (f, c) = s.kind.unknowns();
                f + c
            })
            .sum();
        if n > 6 {
            let last = raw
                .iter()
                .rev()
                .find(|r| held.iter().any(|s| &s.name == r.name.get_ref()))
                .expect("a held body has a support");
            let names: Vec<&str> = held.iter().map(|s| s.name.as_str()).collect();
            return Err(whole(
                cx,
                &last.name,
                format!(
                    "the supports of `{}` ({}) are statically indeterminate: they carry {n} reaction components, and the motion of a rigid body gives six equations (three of force, three of moment)",
                    body.name,
                    names.join(", ")
                ),
            ));
        }
    }
    Ok(out)
}

fn whole(
    cx: &Context<'_>,
    s: &Spanned<String>,
    msg: impl Into<String>,
) -> crate::derivation::Diagnostic {
    cx.diag_string(s, 0, s.get_ref().len(), msg)
}

fn support(cx: &Context<'_>, ph: &Physics, s: &RawSupport) -> R<Support> {
    let name = s.name.get_ref();
    cx.valid_name(&s.name, "support")?;
    let body = match &s.body {
        Some(b) => ph
            .bodies
            .iter()
            .position(|x| &x.name == b.get_ref())
            .ok_or_else(|| {
                let known: Vec<String> = ph.bodies.iter().map(|x| x.name.clone()).collect();
                whole(cx, b, unknown("body", b.get_ref(), &known))
            })?,
        None if ph.bodies.len() == 1 => 0,
        None => {
            return Err(whole(
                cx,
                &s.name,
                "name the body this support holds (`body = \"…\"`): the file declares none or several",
            ));
        }
    };
    let word = s.kind.get_ref().as_str();
    let kind = match word {
        "bearing" => {
            let Some(c) = &s.carries else {
                return Err(whole(
                    cx,
                    &s.kind,
                    "a bearing says what it carries: `carries = \"radial\"` (a force across the shaft) or `carries = \"radial and axial\"` (a thrust bearing)",
                ));
            };
            match c.get_ref().as_str() {
                "radial" => SupportKind::Bearing { axial: false },
                "radial and axial" => SupportKind::Bearing { axial: true },
                other => {
                    return Err(whole(
                        cx,
                        c,
                        format!("a bearing carries `radial` or `radial and axial`, not `{other}`"),
                    ));
                }
            }
        }
        "ball" | "fixed" => SupportKind::Ball,
        "clamp" => SupportKind::Clamp,
        "floor" => SupportKind::Floor {
            friction: s.friction.as_ref().is_some_and(|f| *f.get_ref()),
        },
        "drive" => SupportKind::Drive,
        other => {
            return Err(whole(
                cx,
                &s.kind,
                format!("unknown kind of support `{other}` (kinds: {KINDS})"),
            ));
        }
    };
    if let Some(c) = &s.carries
        && !matches!(kind, SupportKind::Bearing { .. })
    {
        return Err(whole(
            cx,
            c,
            "`carries` says what a bearing carries; this support is not one",
        ));
    }
    if let Some(f) = &s.friction
        && !matches!(kind, SupportKind::Floor { .. })
    {
        let span = f.span();
        return Err(cx.diag(
            span.start,
            span.end,
            "`friction` is said of a contact with the floor (`kind = \"floor\"`)",
        ));
    }
    let point = match (&s.point, kind) {
        (Some(p), SupportKind::Drive) => {
            return Err(whole(
                cx,
                p,
                "a drive is a couple about its axis and acts at no point: leave `point` out",
            ));
        }
        (None, SupportKind::Drive) => None,
        (Some(p), _) => {
            let known: Vec<String> = ph
                .points
                .iter()
                .map(|x| x.name.clone())
                .chain(ph.bodies.iter().filter_map(|b| b.centre.clone()))
                .collect();
            if !known.contains(p.get_ref()) {
                return Err(whole(cx, p, unknown("point", p.get_ref(), &known)));
            }
            Some(p.get_ref().clone())
        }
        (None, _) => {
            return Err(whole(
                cx,
                &s.name,
                format!(
                    "a `{word}` support acts at a point: add `point = \"…\"` (a declared point)"
                ),
            ));
        }
    };
    let needs_axis = matches!(
        kind,
        SupportKind::Bearing { .. } | SupportKind::Drive | SupportKind::Floor { .. }
    );
    let axis = match (&s.axis, needs_axis) {
        (Some(a), true) => {
            let (ast, base) = parse_spanned(cx, a)?;
            let (v, f) = cx.vector(&ast, base)?;
            if v.0.iter().all(|c| c.is_zero()) {
                return Err(whole(cx, a, "the axis has zero length"));
            }
            if v.0
                .iter()
                .any(|p| p.atoms().iter().any(|x| x.is_time_dependent()))
            {
                return Err(whole(
                    cx,
                    a,
                    "the axis is a direction fixed in its frame: an expression of constants (`[0, 0, 1] in S`)",
                ));
            }
            Some((v, f))
        }
        (None, true) => {
            let what = if matches!(kind, SupportKind::Floor { .. }) {
                "the floor's normal"
            } else {
                "the shaft's axis"
            };
            return Err(whole(
                cx,
                &s.kind,
                format!("a `{word}` support needs `axis`, {what} (`axis = \"[0, 0, 1] in N\"`)"),
            ));
        }
        (Some(a), false) => {
            return Err(whole(
                cx,
                a,
                format!("a `{word}` support carries a force in every direction: it has no `axis`"),
            ));
        }
        (None, false) => None,
    };
    Ok(Support {
        name: name.clone(),
        doc: s.doc.clone(),
        body,
        point,
        kind,
        axis,
    })
}
