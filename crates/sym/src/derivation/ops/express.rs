//! `express(v, C)`: a vector in another frame's components.

use super::{Call, Op};
use crate::derivation::context::{Context, R};
use crate::derivation::value::Value;
use crate::vector::Vec3;

pub(crate) const EXPRESS: Op = Op {
    names: &["express"],
    signature: "express(v, C)",
    doc: "the vector `v` in the components of frame `C` (through the frames' rotations)",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let (v, from) = c.vector(0)?;
    let to = c.frame(1)?;
    let cx = c.cx;
    let from_i = cx.frame_index(&from).expect("frame");
    let to_name = cx.frames[to].name.clone();
    match express_in(cx, v, from_i, to) {
        Some(v) => Ok(Value::Vector(v, to_name)),
        None => c.err(
            c.span,
            format!("no chain of rotations relates frames {from} and {to_name}"),
        ),
    }
}

/// `v`, in the components of frame `from`, in those of frame `to`;
/// `None` when no chain of rotations relates the two frames.
pub(crate) fn express_in(cx: &Context<'_>, v: Vec3, from: usize, to: usize) -> Option<Vec3> {
    if let Some(v) = cx.along_chain(v.clone(), from, to) {
        return Some(v);
    }
    let (ra, ma) = cx.to_root(from);
    let (rb, mb) = cx.to_root(to);
    (ra == rb).then(|| mb.transpose().mul_vec(&ma.mul_vec(&v)))
}
