//! `sin(θ)`, `cos(θ)` of an angle symbol, or of a sum of angles
//! (`crate::angle_sum`).

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const SIN_COS: Op = Op {
    names: &["sin", "cos"],
    signature: "sin(theta), cos(theta), cos(q1 + q2), sin(2*theta)",
    doc: "of an angle symbol (a constant or a `time` symbol, not a rate), or of a sum of integer multiples of angle symbols and of pi/2, written out by the addition formulas (cos(q1 + q2) = cos q1 cos q2 − sin q1 sin q2)",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    let p =
        c.cx.symbols
            .trig_poly(c.func, c.args, c.span)
            .map_err(|e| c.cx.at(c.base, e.span, e.message))?;
    Ok(Value::Scalar(p))
}
