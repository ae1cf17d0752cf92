//! `[[load]]`: applied forces at declared points and torques on frames,
//! read and checked against the file's points and frames; Kane's method
//! (`ops/kane.rs`) takes their generalized active forces.

use super::context::{Context, R};
use super::multibody::Load;
use super::raw::{RawFile, RawLoad};
use crate::vector::Vec3;

pub(crate) fn declare(cx: &Context<'_>, raw: &RawFile) -> R<Vec<Load>> {
    raw.loads.iter().map(|l| load(cx, l)).collect()
}

fn vector(cx: &Context<'_>, s: &toml::Spanned<String>) -> R<(Vec3, usize)> {
    let base = cx.content_start(s);
    let ast = cx.parse_at(s.get_ref(), base)?;
    let (v, f) = cx.vector(&ast, base)?;
    Ok((v, cx.frame_index(&f).expect("a vector's frame exists")))
}

fn load(cx: &Context<'_>, l: &RawLoad) -> R<Load> {
    match (&l.point, &l.force, &l.frame, &l.torque) {
        (Some(p), Some(f), None, None) => {
            let name = p.get_ref();
            if cx.physics.point(name).is_none() {
                let known = cx.physics.point_names();
                return Err(cx.diag_string(
                    p,
                    0,
                    name.len(),
                    format!(
                        "`{name}` is not a declared point (one of {})",
                        known.join(", ")
                    ),
                ));
            }
            let (force, frame) = vector(cx, f)?;
            Ok(Load::Force {
                point: name.clone(),
                force,
                frame,
            })
        }
        (None, None, Some(fr), Some(t)) => {
            let Some(on) = cx.frame_index(fr.get_ref()) else {
                let n = fr.get_ref();
                return Err(cx.diag_string(
                    fr,
                    0,
                    n.len(),
                    format!("`{n}` is not a declared frame"),
                ));
            };
            let (torque, in_frame) = vector(cx, t)?;
            Ok(Load::Torque {
                on,
                torque,
                in_frame,
            })
        }
        _ => {
            let at = l
                .point
                .as_ref()
                .or(l.frame.as_ref())
                .or(l.force.as_ref())
                .or(l.torque.as_ref());
            let msg = "a [[load]] is either `point` with `force`, or `frame` with `torque`";
            match at {
                Some(s) => Err(cx.diag_string(s, 0, s.get_ref().len(), msg)),
                None => Err(cx.diag(0, 0, msg)),
            }
        }
    }
}
