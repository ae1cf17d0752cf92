//! Matrices: `inertia(…)`, `principal(…)`/`diag(…)`, `transpose(M)`.

use super::{Call, Op};
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::poly::Poly;
use crate::vector::Mat3;

pub(crate) const INERTIA: Op = Op {
    names: &["inertia"],
    signature: "inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx)",
    doc: "inertia tensor; products enter with a **minus** sign",
    eval: inertia,
};

pub(crate) const PRINCIPAL: Op = Op {
    names: &["principal", "diag"],
    signature: "principal(A, B, C), diag(a, b, c)",
    doc: "diagonal matrix",
    eval: principal,
};

pub(crate) const TRANSPOSE: Op = Op {
    names: &["transpose"],
    signature: "transpose(M)",
    doc: "the transposed matrix",
    eval: transpose,
};

fn scalars<const N: usize>(c: &Call<'_, '_>) -> R<[Poly; N]> {
    c.arity(N)?;
    let v: Vec<Poly> = (0..N).map(|i| c.scalar(i)).collect::<R<_>>()?;
    Ok(v.try_into().expect("arity checked"))
}

fn inertia(c: &Call<'_, '_>) -> R<Value> {
    let [ix, iy, iz, pxy, pyz, pzx] = scalars::<6>(c)?;
    Ok(Value::Matrix(Mat3::inertia([ix, iy, iz], [pxy, pyz, pzx])))
}

fn principal(c: &Call<'_, '_>) -> R<Value> {
    Ok(Value::Matrix(Mat3::principal(scalars::<3>(c)?)))
}

fn transpose(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    match c.value(0)? {
        Value::Matrix(m) => Ok(Value::Matrix(m.transpose())),
        Value::Array(rows) => {
            let n = rows.first().map_or(0, Vec::len);
            Ok(Value::Array(
                (0..n)
                    .map(|j| rows.iter().map(|r| r[j].clone()).collect())
                    .collect(),
            ))
        }
        v => c.err(
            c.args[0].span,
            format!("expected a matrix, found {}", v.describe()),
        ),
    }
}
