//! `state_matrix`, `input_matrix` and `state_mass`: linearized equations of
//! motion M u̇ + C u + K q + F r = 0, with the kinematic equations
//! q̇ = … of the coordinates, as a first-order system E ẋ = A x + B r in
//! the state x = (q, u) — what SymPy's `linearize` returns. M is divided
//! out (E = I: SymPy's `A_and_B=True`) when the exact algebra can divide by
//! its determinant, as `solve` does; otherwise E holds M (SymPy's default
//! form), and A = E⁻¹ A is formed numerically (`hdot stability`) or by
//! the SymPy export's reader (`E.LUsolve(A)`).

use super::solve::{determinant, sum_inverse};
use super::{Call, Op, coefficient};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::poly::Poly;

/// An operation's own words, then the form the three share.
macro_rules! with_form {
    ($own:literal) => {
        concat!(
            $own,
            " the linearized equations (a list equal to 0, linear in the speeds' rates, the speeds, the \
             coordinates and the inputs listed last, with constant coefficients and no constant term) as the \
             first-order \
             system E ẋ = A x + B r in the state x = (q₁, …, u₁, …); a coordinate's rate is its `[kinematics]` \
             equation (linear in the state), or a listed speed that is its rate (`theta'`). M is divided out \
             where `solve` could divide by its determinant (then E is the identity: SymPy's \
             `linearize(A_and_B=True)`); otherwise E = diag(I, M) (SymPy's `linearize()`)"
        )
    };
}

pub(crate) const STATE_MATRIX: Op = Op {
    names: &["state_matrix"],
    signature: "state_matrix(eqs, [q1, …], [u1, …]), state_matrix(eqs, [q1, …], [u1, …], [r1, …])",
    doc: with_form!("the state matrix A of"),
    eval: state_matrix,
};

pub(crate) const INPUT_MATRIX: Op = Op {
    names: &["input_matrix"],
    signature: "input_matrix(eqs, [q1, …], [u1, …], [r1, …])",
    doc: with_form!(
        "the input matrix B (a column for each input r: an applied torque or force, a constant or a function of \
         time) of"
    ),
    eval: input_matrix,
};

pub(crate) const STATE_MASS: Op = Op {
    names: &["state_mass"],
    signature: "state_mass(eqs, [q1, …], [u1, …]), state_mass(eqs, [q1, …], [u1, …], [r1, …])",
    doc: with_form!("the matrix E (the identity, or diag(I, M)) of"),
    eval: state_mass,
};

fn state_matrix(c: &Call<'_, '_>) -> R<Value> {
    c.arity_between(3, 4)?;
    let s = System::read(c)?;
    let n = s.n;
    let mut rows: Vec<Vec<Poly>> =
        s.kq.iter()
            .zip(&s.ku)
            .map(|(q, u)| q.iter().chain(u).cloned().collect())
            .collect();
    // −M⁻¹ [K | C], or −[K | C] when E holds M.
    let right: Vec<Vec<Poly>> = (0..n)
        .map(|i| s.k[i].iter().chain(&s.c[i]).map(|p| -p).collect())
        .collect();
    rows.extend(s.divided(&right));
    Ok(Value::Array(rows))
}

fn input_matrix(c: &Call<'_, '_>) -> R<Value> {
    c.arity(4)?;
    let s = System::read(c)?;
    let r = s.f.first().map_or(0, Vec::len);
    let mut rows = vec![vec![Poly::zero(); r]; s.n];
    let right: Vec<Vec<Poly>> =
        s.f.iter()
            .map(|row| row.iter().map(|p| -p).collect())
            .collect();
    rows.extend(s.divided(&right));
    Ok(Value::Array(rows))
}

fn state_mass(c: &Call<'_, '_>) -> R<Value> {
    c.arity_between(3, 4)?;
    let s = System::read(c)?;
    let n = s.n;
    let rows = (0..2 * n)
        .map(|i| {
            (0..2 * n)
                .map(|j| match (i < n, j < n) {
                    _ if i == j && (i < n || s.inverse.is_some()) => Poly::one(),
                    (false, false) if s.inverse.is_none() => s.m[i - n][j - n].clone(),
                    _ => Poly::zero(),
                })
                .collect()
        })
        .collect();
    Ok(Value::Array(rows))
}

/// Linearized equations read by coefficients: M u̇ + C u + K q + F r = 0
/// and q̇ = Kq q + Ku u.
struct System {
    n: usize,
    kq: Vec<Vec<Poly>>,
    ku: Vec<Vec<Poly>>,
    m: Vec<Vec<Poly>>,
    c: Vec<Vec<Poly>>,
    k: Vec<Vec<Poly>>,
    f: Vec<Vec<Poly>>,
    /// 1/det M, where the algebra can divide by it.
    inverse: Option<Poly>,
}

impl System {
    /// The equations, coordinates, speeds and (a fourth argument) inputs
    /// of a call.
    fn read(c: &Call<'_, '_>) -> R<System> {
        let v = c.value(0)?;
        let Some(eqs) = v.equations() else {
            return c.err(
                c.args[0].span,
                format!(
                    "expected linearized equations (a list), found {}",
                    v.describe()
                ),
            );
        };
        let eqs: Vec<Poly> = eqs.iter().map(|e| c.cx.unfold(e)).collect();
        let (qs, _) = c.symbols(1)?;
        let (us, _) = c.symbols(2)?;
        let rs = if c.args.len() > 3 {
            c.symbols(3)?.0
        } else {
            Vec::new()
        };
        let n = eqs.len();
        for (i, list, what) in [(1, &qs, "coordinates"), (2, &us, "speeds")] {
            if list.len() != n {
                return c.err(
                    c.args[i].span,
                    format!(
                        "{} {what} for {n} equation{}: the state has as many coordinates and speeds as \
                         there are equations",
                        list.len(),
                        if n == 1 { "" } else { "s" }
                    ),
                );
            }
            if let Some(a) = list.iter().find(|a| !a.is_time_dependent()) {
                return c.err(
                    c.args[i].span,
                    format!("`{a}` is a constant: list functions of time"),
                );
            }
        }
        let rates: Vec<Atom> = us
            .iter()
            .map(|u| u.derivative().expect("a function of time"))
            .collect();
        // The kinematic equations, linear in the state.
        let state: Vec<Atom> = qs.iter().chain(&us).copied().collect();
        let mut kq = Vec::with_capacity(n);
        let mut ku = Vec::with_capacity(n);
        for &q in &qs {
            let rate = match c.cx.speeds.kinematics.iter().find(|(a, _)| *a == q) {
                Some((_, f)) => c.cx.unfold(f),
                None => match q.derivative().filter(|d| us.contains(d)) {
                    Some(d) => Poly::atom(d),
                    None => {
                        return c.err(
                            c.args[1].span,
                            format!(
                                "`{q}` has no kinematic equation and its rate is not a listed speed: give \
                                 `{q}` under [kinematics], or list `{q}'` among the speeds"
                            ),
                        );
                    }
                },
            };
            let (row, rest) = linear(&rate, &state).map_err(|m| {
                c.cx.at(
                    c.base,
                    c.args[1].span,
                    format!("the kinematic equation of `{q}`: {m}"),
                )
            })?;
            if !rest.is_zero() {
                return c.err(
                    c.args[1].span,
                    format!(
                        "the kinematic equation of `{q}` is {rate}, which is not linear in the state: \
                         linearize it about the operating point (or list the rate `{q}'` as a speed)"
                    ),
                );
            }
            kq.push(row[..n].to_vec());
            ku.push(row[n..].to_vec());
        }
        let all: Vec<Atom> = rates
            .iter()
            .chain(&us)
            .chain(&qs)
            .chain(&rs)
            .copied()
            .collect();
        let (mut m, mut cm, mut k, mut f) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (i, e) in eqs.iter().enumerate() {
            let which = if n == 1 {
                String::new()
            } else {
                format!("equation {}: ", i + 1)
            };
            let (row, rest) = linear(e, &all)
                .map_err(|msg| c.cx.at(c.base, c.args[0].span, format!("{which}{msg}")))?;
            if !rest.is_zero() {
                return c.err(
                    c.args[0].span,
                    format!(
                        "{which}the term {rest} holds none of the state's symbols nor an input: the \
                         equations must vanish at the operating point (list an applied load as an input)"
                    ),
                );
            }
            m.push(row[..n].to_vec());
            cm.push(row[n..2 * n].to_vec());
            k.push(row[2 * n..3 * n].to_vec());
            f.push(row[3 * n..].to_vec());
        }
        let det = determinant(&m);
        if det.is_zero() {
            return c.err(
                c.args[2].span,
                "the coefficients of the speeds' rates (M) are singular: the equations do not determine them",
            );
        }
        let inverse = det
            .inverse_divisor()
            .or_else(|| sum_inverse(&det, &c.cx.positive).and_then(Result::ok));
        Ok(System {
            n,
            kq,
            ku,
            m,
            c: cm,
            k,
            f,
            inverse,
        })
    }

    /// M⁻¹ X (by Cramer's rule, column by column) where M can be divided
    /// by; X itself otherwise (E then holds M).
    fn divided(&self, x: &[Vec<Poly>]) -> Vec<Vec<Poly>> {
        let Some(inv) = &self.inverse else {
            return x.to_vec();
        };
        let cols = x.first().map_or(0, Vec::len);
        let mut out = vec![vec![Poly::zero(); cols]; self.n];
        for col in 0..cols {
            for (j, row_j) in out.iter_mut().enumerate() {
                let mj: Vec<Vec<Poly>> = self
                    .m
                    .iter()
                    .zip(x)
                    .map(|(row, xi)| {
                        let mut r = row.clone();
                        r[j] = xi[col].clone();
                        r
                    })
                    .collect();
                row_j[col] = &determinant(&mj) * inv;
            }
        }
        out
    }
}

/// `p` as Σ aᵢ vᵢ + rest: the coefficients of the symbols `vars` (each to
/// the first power, none multiplied together), and the terms free of them;
/// an error when `p` is not linear in them with constant coefficients.
fn linear(p: &Poly, vars: &[Atom]) -> Result<(Vec<Poly>, Poly), String> {
    let mut rest = Vec::new();
    for (mono, a) in p.terms() {
        let present: Vec<(Atom, i32)> = vars
            .iter()
            .map(|&v| (v, mono.exponent(v)))
            .filter(|&(_, e)| e != 0)
            .collect();
        match present.as_slice() {
            [] => rest.push((mono.clone(), a.clone())),
            [(_, 1)] => {}
            [(v, e)] => {
                return Err(format!(
                    "`{v}` occurs to the power {e}: the equations are not linear in it"
                ));
            }
            [(v, _), (w, _), ..] => {
                return Err(format!(
                    "`{v}` and `{w}` occur multiplied together: the equations are not linear in the state"
                ));
            }
        }
        if let Some((x, _)) = mono
            .factors()
            .iter()
            .find(|(x, _)| !vars.contains(x) && x.is_time_dependent())
        {
            return Err(format!(
                "`{x}` is a function of time that is neither in the state nor an input: linearize about an \
                 operating point that gives it a value, or list it"
            ));
        }
    }
    let coefficients = vars.iter().map(|&v| coefficient(p, v)).collect();
    Ok((coefficients, Poly::from_terms(rest)))
}
