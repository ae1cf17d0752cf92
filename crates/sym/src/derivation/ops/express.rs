//! `express(v, C)`: a vector in another frame's components.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

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
    if let Some(v) = cx.along_chain(v.clone(), from_i, to) {
        return Ok(Value::Vector(v, to_name));
    }
    let (ra, ma) = cx.to_root(from_i);
    let (rb, mb) = cx.to_root(to);
    if ra != rb {
        return c.err(
            c.span,
            format!("no chain of rotations relates frames {from} and {to_name}"),
        );
    }
    Ok(Value::Vector(
        mb.transpose().mul_vec(&ma.mul_vec(&v)),
        to_name,
    ))
}
