//! `sin(θ)`, `cos(θ)` of an angle symbol.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::poly::Poly;

pub(crate) const SIN_COS: Op = Op {
    names: &["sin", "cos"],
    signature: "sin(theta), cos(theta)",
    doc: "of a single angle symbol (a constant or a `time` symbol, not a rate)",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    let a =
        c.cx.symbols
            .trig(c.func, c.args, c.span)
            .map_err(|e| c.cx.at(c.base, e.span, e.message))?;
    Ok(Value::Scalar(Poly::atom(a)))
}
