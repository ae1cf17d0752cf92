//! `dt(x)` and `dt_rel(v)`: time derivatives.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const DT: Op = Op {
    names: &["dt"],
    signature: "dt(x)",
    doc: "time derivative; for a vector in frame `B` the transport theorem: components' derivatives + Ω_B × v",
    eval: dt,
};

pub(crate) const DT_REL: Op = Op {
    names: &["dt_rel"],
    signature: "dt_rel(v)",
    doc: "components' derivatives only, (dv/dt) relative to the frame",
    eval: dt_rel,
};

fn dt(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    Ok(match c.value(0)? {
        Value::Vector(v, f) => {
            let fr = c.cx.frame(&f);
            Value::Vector(fr.dt(&v), f)
        }
        v => v.map(&mut |p| p.dt()),
    })
}

fn dt_rel(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    Ok(c.value(0)?.map(&mut |p| p.dt()))
}
