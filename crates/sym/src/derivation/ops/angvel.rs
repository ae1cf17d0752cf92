//! `angvel(B)`: a frame's angular velocity.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const ANGVEL: Op = Op {
    names: &["angvel"],
    signature: "angvel(B)",
    doc: "the angular velocity Ω of frame `B` relative to N, in `B`'s components",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    let i = c.frame(0)?;
    let f = &c.cx.frames[i];
    Ok(Value::Vector(f.omega.clone(), f.name.clone()))
}
