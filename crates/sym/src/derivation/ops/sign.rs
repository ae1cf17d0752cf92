//! `sign(x)`: the sign of an expression in positive symbols.

use super::{Call, Op};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::poly::Poly;

pub(crate) const SIGN: Op = Op {
    names: &["sign"],
    signature: "sign(x)",
    doc: "+1 or −1 when every term has that sign for the symbols declared `positive`; an error otherwise",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    let p = c.scalar(0)?;
    match sign_of(&p, &c.cx.positive) {
        Some(s) => Ok(Value::Scalar(Poly::int(s))),
        None => c.err(
            c.args[0].span,
            format!(
                "cannot decide the sign of {p}: every term must have the same sign in symbols declared \
                 under `positive`"
            ),
        ),
    }
}

/// +1 or −1 when every term of `p` has that sign for positive values of
/// the `positive` constants (even powers of any atom also count as
/// positive); `None` otherwise.
pub(crate) fn sign_of(p: &Poly, positive: &[Atom]) -> Option<i64> {
    if p.is_zero() {
        return None;
    }
    let mut sign = None;
    for (m, c) in p.terms() {
        if !m
            .factors()
            .iter()
            .all(|(a, e)| positive.contains(a) || e % 2 == 0)
        {
            return None;
        }
        let s = if c.is_negative() { -1 } else { 1 };
        if sign.is_some_and(|t| t != s) {
            return None;
        }
        sign = Some(s);
    }
    sign
}
