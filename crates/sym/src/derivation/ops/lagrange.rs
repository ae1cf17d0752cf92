//! `lagrange(T, V, q)`: Lagrange's equations.

use super::{Call, Op};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::poly::Poly;

pub(crate) const LAGRANGE: Op = Op {
    names: &["lagrange"],
    signature: "lagrange(T, V, q), lagrange(T, V, [q1, q2, …], Q)",
    doc: "Lagrange's equation d/dt(∂T/∂q̇) − ∂T/∂q + ∂V/∂q − Q_q for each coordinate (= 0 along the motion); `Q` \
          (optional: a scalar, or a `list(…)` with one per coordinate) is the generalized force of the forces \
          not in V. One coordinate gives a scalar, several a list",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity_between(3, 4)?;
    let t = c.cx.unfold(&c.scalar(0)?);
    let v = c.cx.unfold(&c.scalar(1)?);
    let (qs, listed) = c.symbols(2)?;
    for (k, &q) in qs.iter().enumerate() {
        if q.order() != 0 || !q.is_time_dependent() {
            let span = match &c.args[2].kind {
                crate::parse::AstKind::Vector { items, .. } => items[k].span,
                _ => c.args[2].span,
            };
            return c.err(
                span,
                format!("`{q}` is not a coordinate: give time symbols such as theta, not rates or constants"),
            );
        }
    }
    let forces: Vec<Poly> = match c.args.get(3) {
        None => vec![Poly::zero(); qs.len()],
        Some(a) => match c.value(3)? {
            Value::Scalar(p) if qs.len() == 1 => vec![c.cx.unfold(&p)],
            Value::List { items, .. } if items.len() == qs.len() => {
                items.iter().map(|p| c.cx.unfold(p)).collect()
            }
            v => {
                return c.err(
                    a.span,
                    format!(
                        "the generalized forces must be {} (one per coordinate), found {}",
                        if qs.len() == 1 { "a scalar" } else { "a list" },
                        v.describe()
                    ),
                );
            }
        },
    };
    let eqs: Vec<Poly> = qs
        .iter()
        .zip(&forces)
        .map(|(&q, f)| lagrange_equation(&t, &v, q, f))
        .collect();
    Ok(if listed {
        Value::list(eqs)
    } else {
        Value::Scalar(eqs.into_iter().next().expect("one coordinate"))
    })
}

/// d/dt(∂T/∂q̇) − ∂T/∂q + ∂V/∂q − Q.
pub(crate) fn lagrange_equation(t: &Poly, v: &Poly, q: Atom, force: &Poly) -> Poly {
    let qd = q.derivative().expect("a time symbol");
    let momentum = t.partial(qd);
    &(&(&momentum.dt() - &t.partial(q)) + &v.partial(q)) - force
}
