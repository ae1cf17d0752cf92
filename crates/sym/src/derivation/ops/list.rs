//! `list(e1, e2, …)`: a list of scalars (equations, for `solve`).

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;

pub(crate) const LIST: Op = Op {
    names: &["list"],
    signature: "list(e1, e2, …)",
    doc: "a list of scalars, such as the equations of motion to `solve` (`l.1` is its first item)",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    if c.args.is_empty() {
        return c.err(c.span, "list(…) needs at least one item");
    }
    let items = (0..c.args.len()).map(|i| c.scalar(i)).collect::<R<_>>()?;
    Ok(Value::list(items))
}
