//! `cross(a, b)` and `dot(a, b)`.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const CROSS: Op = Op {
    names: &["cross"],
    signature: "cross(a, b)",
    doc: "vector product (also `a × b`); both vectors in the same frame",
    eval: cross,
};

pub(crate) const DOT: Op = Op {
    names: &["dot"],
    signature: "dot(a, b)",
    doc: "scalar product; both vectors in the same frame",
    eval: dot,
};

fn cross(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    c.cx.cross(&c.args[0], &c.args[1], c.base, c.span)
}

fn dot(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let (x, fx) = c.vector(0)?;
    let (y, fy) = c.vector(1)?;
    c.cx.same_frame(c.base, c.span, &fx, &fy)?;
    Ok(Value::Scalar(x.dot(&y)))
}
