//! `position(P, Q)`: the vector from declared point Q to declared point P,
//! summed along the points' `at` vectors back to a fixed point, and across
//! from one fixed point to another by their places (what `hdot verify`
//! measures as `position(point, from)`).

use super::express::express_in;
use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::physics::PointKind;
use crate::derivation::value::Value;
use crate::parse::AstKind;
use crate::vector::Vec3;

pub(crate) const POSITION: Op = Op {
    names: &["position"],
    signature: "position(P, Q)",
    doc: "the vector from the declared point `Q` to the declared point `P` (a body's centre is a point too): the \
          `at` vectors from each back to a fixed point (and between two fixed points their places in N), in the \
          components of the frame of `P`'s `at` (N for a fixed point)",
    eval,
};

/// The pieces (vector, frame index) from the fixed point at the root of
/// `name`'s chain to `name`, and that root.
pub(super) type Chain = (Vec<(Vec3, usize)>, String);

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let cx = c.cx;
    let (p, q) = (point(c, 0)?, point(c, 1)?);
    let (mut pp, proot) = chain(c, &p)?;
    let (mut qp, qroot) = chain(c, &q)?;
    if proot != qroot {
        // Two fixed points: their own places (from N's origin) join the
        // chains, so that the vector runs from one to the other.
        pp.push(fixed_place(c, &proot));
        qp.push(fixed_place(c, &qroot));
    }
    let to = pp.first().map_or(0, |(_, f)| *f);
    let mut r = Vec3::zero();
    for ((v, f), sign) in pp
        .iter()
        .map(|x| (x, false))
        .chain(qp.iter().map(|x| (x, true)))
        .map(|((v, f), s)| ((v.map(|x| cx.unfold(x)), *f), s))
    {
        let Some(v) = express_in(cx, v, f, to) else {
            return c.err(
                c.span,
                format!(
                    "no chain of rotations relates frames {} and {}",
                    cx.frames[f].name, cx.frames[to].name
                ),
            );
        };
        r = if sign { r.sub(&v) } else { r.add(&v) };
    }
    Ok(Value::Vector(r, cx.frames[to].name.clone()))
}

/// The place of the fixed point `name` from N's origin: its `at` (a
/// constant vector in an inertial frame), with that frame's index.
fn fixed_place(c: &Call<'_, '_>, name: &str) -> (Vec3, usize) {
    match c.cx.physics.point(name).map(|p| &p.kind) {
        Some(PointKind::Fixed(v, f)) => (
            v.clone(),
            c.cx.frame_index(f).expect("the point's frame exists"),
        ),
        _ => unreachable!("a chain ends at a fixed point"),
    }
}

/// Argument `i`, the name of a declared point.
fn point(c: &Call<'_, '_>, i: usize) -> R<String> {
    let ph = &c.cx.physics;
    if let AstKind::Name { name, primes: 0 } = &c.args[i].kind
        && ph.point(name).is_some()
    {
        return Ok(name.clone());
    }
    let names = ph.point_names();
    c.err(
        c.args[i].span,
        format!("expected a declared point (one of {})", names.join(", ")),
    )
}

/// The `at` vectors from point `name` back to the fixed point it hangs
/// from, each with its frame index, and that fixed point's name.
pub(super) fn chain(c: &Call<'_, '_>, name: &str) -> R<Chain> {
    let cx = c.cx;
    let mut pieces = Vec::new();
    let mut at = name.to_string();
    loop {
        let p = cx.physics.point(&at).expect("a declared point");
        match &p.kind {
            PointKind::Fixed(..) => return Ok((pieces, at)),
            PointKind::Free => {
                return c.err(
                    c.span,
                    format!("point `{at}` moves freely: its position is not declared"),
                );
            }
            PointKind::From { from, at: v, frame } => {
                if pieces.len() > cx.physics.point_names().len() {
                    return c.err(c.span, format!("point `{name}` leads back to itself"));
                }
                let f = cx.frame_index(frame).expect("the point's frame exists");
                pieces.push((v.clone(), f));
                at = from.clone();
            }
        }
    }
}
