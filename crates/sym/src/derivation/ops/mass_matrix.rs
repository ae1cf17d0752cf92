//! `mass_matrix(eqs, [q1'', …])` and `forcing(eqs, [q1'', …])`: the
//! equations of motion as M(q) q̈ = f(q, q̇, t), the standard form for
//! numeric integration when M cannot be inverted symbolically.

use super::{Call, Op, coefficient};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::poly::Poly;

pub(crate) const MASS_MATRIX: Op = Op {
    names: &["mass_matrix"],
    signature: "mass_matrix(eqs, [q1'', q2'', …])",
    doc: "the matrix M of equations linear in the unknowns, written M u = f (the mass matrix when the unknowns are \
          accelerations)",
    eval: mass_matrix,
};

pub(crate) const FORCING: Op = Op {
    names: &["forcing"],
    signature: "forcing(eqs, [q1'', q2'', …])",
    doc: "the right-hand side f of the same equations written M u = f",
    eval: forcing,
};

/// The equations `eqs = 0` as `M u = f`: `M[i][j]` the coefficient of
/// `u_j` in equation `i`, `f = −(eqs at u = 0)`. An error message when an
/// unknown does not occur linearly.
pub(crate) fn linear_system(
    eqs: &[Poly],
    unknowns: &[Atom],
) -> Result<(Vec<Vec<Poly>>, Vec<Poly>), String> {
    for (i, e) in eqs.iter().enumerate() {
        for (m, _) in e.terms() {
            let present: Vec<Atom> = unknowns
                .iter()
                .copied()
                .filter(|&u| m.exponent(u) != 0)
                .collect();
            let which = if eqs.len() == 1 {
                String::new()
            } else {
                format!(" (equation {})", i + 1)
            };
            if let Some(&u) = present.iter().find(|&&u| m.exponent(u) > 1) {
                return Err(format!(
                    "`{u}` occurs squared{which}: only equations linear in the unknowns can be solved (a quadratic \
                     such as the rate of steady precession is out of scope; solve for another symbol)"
                ));
            }
            if let Some(&u) = present.iter().find(|&&u| m.exponent(u) < 0) {
                return Err(format!(
                    "`{u}` occurs in a denominator{which}: the equations are not linear in it"
                ));
            }
            if present.len() > 1 {
                return Err(format!(
                    "`{}` and `{}` occur multiplied together{which}: the equations are not linear in the unknowns",
                    present[0], present[1]
                ));
            }
        }
    }
    let m: Vec<Vec<Poly>> = eqs
        .iter()
        .map(|e| unknowns.iter().map(|&u| coefficient(e, u)).collect())
        .collect();
    let f = eqs
        .iter()
        .zip(&m)
        .map(|(e, row)| {
            let lhs: Poly = row
                .iter()
                .zip(unknowns)
                .map(|(c, &u)| c * &Poly::atom(u))
                .sum();
            &lhs - e
        })
        .collect();
    Ok((m, f))
}

/// The equations of a call `op(eqs, [u…])` as `M u = f`.
pub(crate) struct System {
    /// The coefficients, by equation then unknown.
    pub m: Vec<Vec<Poly>>,
    /// The right-hand sides.
    pub f: Vec<Poly>,
    /// The unknowns, in the order given.
    pub unknowns: Vec<Atom>,
    /// Whether the unknowns were given in brackets.
    pub listed: bool,
    /// The equations' value as written (a scalar, vector or list).
    pub value: Value,
}

/// The equations and unknowns of a call `op(eqs, [u…])`, as M and f.
pub(crate) fn system(c: &Call<'_, '_>) -> R<System> {
    c.arity(2)?;
    let v = c.value(0)?;
    let Some(eqs) = v.equations() else {
        return c.err(
            c.args[0].span,
            format!(
                "expected equations (a scalar, a vector or a list), found {}",
                v.describe()
            ),
        );
    };
    let (unknowns, listed) = c.symbols(1)?;
    if eqs.len() != unknowns.len() {
        return c.err(
            c.span,
            format!(
                "{} equation{} for {} unknown{}: give as many unknowns as equations",
                eqs.len(),
                if eqs.len() == 1 { "" } else { "s" },
                unknowns.len(),
                if unknowns.len() == 1 { "" } else { "s" },
            ),
        );
    }
    let eqs: Vec<Poly> = eqs.iter().map(|e| c.cx.unfold(e)).collect();
    for &u in &unknowns {
        if !eqs.iter().any(|e| e.contains(u)) {
            return c.err(
                c.args[1].span,
                format!("`{u}` does not occur in the equations"),
            );
        }
    }
    let (m, f) =
        linear_system(&eqs, &unknowns).map_err(|msg| c.cx.at(c.base, c.args[1].span, msg))?;
    Ok(System {
        m,
        f,
        unknowns,
        listed,
        value: v,
    })
}

fn mass_matrix(c: &Call<'_, '_>) -> R<Value> {
    Ok(Value::Array(system(c)?.m))
}

fn forcing(c: &Call<'_, '_>) -> R<Value> {
    Ok(Value::list(system(c)?.f))
}
