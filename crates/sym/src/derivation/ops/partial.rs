//! `partial(x, q)`: the partial derivative.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const PARTIAL: Op = Op {
    names: &["partial"],
    signature: "partial(x, q)",
    doc: "∂x/∂q for a symbol `q` or a rate `q'` (a symbol and its rates are independent, as in Lagrange's equations); \
          through sin, cos and their denominators, with abbreviations expanded first",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let x = c.value(0)?;
    let q = c.symbol(1)?;
    Ok(x.map(&mut |p| c.cx.unfold(p).partial(q)))
}
