//! `in_speeds(x)`: coordinates' rates replaced by the kinematic equations.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const IN_SPEEDS: Op = Op {
    names: &["in_speeds"],
    signature: "in_speeds(x)",
    doc: "`x` with every rate of a coordinate that `[kinematics]` gives replaced by its kinematic equation \
          (q̇ → f(q, u), q̈ → ḟ, …): written in the coordinates and the generalized speeds",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    if c.cx.speeds.kinematics.is_empty() {
        return c.err(
            c.span,
            "no kinematic equations: declare [symbols] speeds and a [kinematics] table giving each coordinate's rate",
        );
    }
    let v = c.value(0)?;
    Ok(v.map(&mut |p| c.cx.speeds.in_speeds(&c.cx.unfold(p))))
}
