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
          not in V. One coordinate gives a scalar, several a list. T and V are written in the coordinates and \
          their rates: one that holds a generalized speed (a T built from `velocity()` in a file with \
          `[kinematics]`) is an error saying how to write it",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity_between(3, 4)?;
    let t = c.cx.unfold(&c.scalar(0)?);
    let v = c.cx.unfold(&c.scalar(1)?);
    no_speeds(c, 0, &t, "T")?;
    no_speeds(c, 1, &v, "V")?;
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

/// Refuses, at argument `i`, an energy `p` that holds a generalized
/// speed: ∂/∂q̇ would treat the speed as another function of time and
/// drop its terms without a word (a T built from `velocity()`, which is
/// written in the speeds). The message says what to write instead.
fn no_speeds(c: &Call<'_, '_>, i: usize, p: &Poly, what: &str) -> R<()> {
    let speeds = &c.cx.speeds;
    let held: Vec<Atom> = speeds
        .speeds
        .iter()
        .copied()
        .filter(|u| p.atoms().iter().any(|a| a.base() == *u))
        .collect();
    let Some(first) = held.first() else {
        return Ok(());
    };
    // q̇ = u for each speed held: the substitution that writes p in rates.
    let rates: Option<Vec<String>> = held
        .iter()
        .map(|u| {
            speeds
                .kinematics
                .iter()
                .find(|(_, f)| *f == Poly::atom(*u))
                .map(|(q, _)| format!("{u} = {q}'"))
        })
        .collect();
    let instead = match rates {
        Some(r) => format!("`subst({what}, {})` (q̇ = u here)", r.join(", ")),
        None => "velocities from `dt(position(P, O))`".to_string(),
    };
    c.err(
        c.args[i].span,
        format!(
            "{what} holds the generalized speed `{first}`: Lagrange's equations take ∂{what}/∂q̇ and would treat \
             `{first}` as another function of time, dropping its terms. `velocity()` is written in the speeds \
             when [kinematics] gives them; write {what} in the coordinates' rates — {instead} — or take Kane's \
             equations, `kane([…])`, in the speeds"
        ),
    )
}

/// d/dt(∂T/∂q̇) − ∂T/∂q + ∂V/∂q − Q.
pub(crate) fn lagrange_equation(t: &Poly, v: &Poly, q: Atom, force: &Poly) -> Poly {
    let qd = q.derivative().expect("a time symbol");
    let momentum = t.partial(qd);
    &(&(&momentum.dt() - &t.partial(q)) + &v.partial(q)) - force
}
