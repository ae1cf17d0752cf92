//! A body's mass centre as a point: where its body places it (`from` the
//! reference point by `mass_centre`, free for a body about its own
//! centre), so that `position`, `velocity`, `rolling`, a `[[load]]` and a
//! `[[contact]]` take it wherever they take a `[[point]]`; and a
//! `[[point]]` of the same name, accepted when it is the same place.

use super::{Body, Physics, Point, PointKind};
use crate::derivation::context::{Context, R};
use crate::derivation::ops::express_in;
use crate::derivation::raw::RawFile;

/// The centres of `ph`'s bodies as points (after its points and bodies
/// are read); a centre that is also a `[[point]]` must be that point's
/// place, and is left to `ph.points`.
pub(super) fn centre_points(cx: &Context<'_>, raw: &RawFile, ph: &Physics) -> R<Vec<Point>> {
    let mut out = Vec::new();
    for (b, rb) in ph.bodies.iter().zip(&raw.bodies) {
        let Some(name) = &b.centre else { continue };
        if let Some(i) = ph.points.iter().position(|p| &p.name == name) {
            same_place(cx, raw, b, &ph.points[i], i)?;
            continue;
        }
        let kind = if b.about_centre() {
            PointKind::Free
        } else if let Some(at) = &b.mass_centre {
            PointKind::From {
                from: b.point.clone(),
                at: at.clone(),
                frame: cx.frames[b.frame].name.clone(),
            }
        } else {
            // Not placed: a step that needs its position says so.
            continue;
        };
        out.push(Point {
            name: name.clone(),
            doc: format!("the mass centre of {}", rb.name.get_ref()),
            kind,
        });
    }
    Ok(out)
}

/// Accepts the `[[point]]` `p` (the file's `i`-th) named as body `b`'s
/// centre when it is the body's reference point, or placed `from` it at
/// the body's `mass_centre`; otherwise a located error naming both.
fn same_place(cx: &Context<'_>, raw: &RawFile, b: &Body, p: &Point, i: usize) -> R<()> {
    if b.point == p.name {
        return Ok(());
    }
    let bi = raw
        .bodies
        .iter()
        .position(|r| r.name.get_ref() == &b.name)
        .expect("a read body");
    let key = raw.bodies[bi]
        .centre
        .as_ref()
        .expect("a centre that is a [[point]] is named by `centre`");
    let line = cx.diag_string(&raw.points[i].name, 0, 0, "").line;
    let same = match (&p.kind, &b.mass_centre) {
        (PointKind::From { from, at, frame }, Some(mc)) if *from == b.point => {
            let f = cx.frame_index(frame).expect("the point's frame exists");
            express_in(cx, at.clone(), f, b.frame).is_some_and(|v| {
                v.0.iter()
                    .zip(&mc.0)
                    .all(|(x, y)| cx.unfold(x) == cx.unfold(y))
            })
        }
        _ => false,
    };
    if same {
        return Ok(());
    }
    let how = match &b.mass_centre {
        Some(_) => format!(
            "the [[point]] is not `from` the body's reference point `{}` at its `mass_centre`",
            b.point
        ),
        None => format!(
            "the body does not say where its centre is: give it `mass_centre` (G from `{}`, in the body frame)",
            b.point
        ),
    };
    let n = key.get_ref().len();
    Err(cx.diag_string(
        key,
        0,
        n,
        format!(
            "`{}` is both the [[point]] of line {line} and body `{}`'s centre, at different places ({how}); \
             the centre is a point already (`position({0}, …)`, `velocity({0})`, a [[load]] at it): \
             leave the [[point]] out, or name the centre otherwise",
            p.name, b.name
        ),
    ))
}
