//! `coeff(x, a)` and `jacobian(v, [a, b, …])`: coefficients of symbols.

use super::{Call, Op, coefficient};
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::vector::Mat3;

pub(crate) const COEFF: Op = Op {
    names: &["coeff"],
    signature: "coeff(x, a)",
    doc: "the coefficient of `a` (first power)",
    eval: coeff,
};

pub(crate) const JACOBIAN: Op = Op {
    names: &["jacobian"],
    signature: "jacobian(v, [a, b, c])",
    doc: "the matrix of coefficients of a vector (or list) linear in a, b, c, …",
    eval: jacobian,
};

fn coeff(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let x = c.value(0)?;
    let a = c.symbol(1)?;
    Ok(x.map(&mut |p| coefficient(p, a)))
}

fn jacobian(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let v = c.value(0)?;
    let (vars, _) = c.symbols(1)?;
    let Some(eqs) = v.equations() else {
        return c.err(
            c.args[0].span,
            format!("expected a vector or a list, found {}", v.describe()),
        );
    };
    if let (Value::Vector(..), 3) = (&v, vars.len()) {
        return Ok(Value::Matrix(Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| coefficient(&eqs[i], vars[j]))
        }))));
    }
    Ok(Value::Array(
        eqs.iter()
            .map(|e| vars.iter().map(|&a| coefficient(e, a)).collect())
            .collect(),
    ))
}
