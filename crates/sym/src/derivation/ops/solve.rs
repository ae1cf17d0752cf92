//! `solve(eq, x)` and `solve(eqs, [x, y, …])`: linear equations solved
//! exactly, dividing only by what the canonical form can divide by (and by
//! a sum of constants known not to be zero: φ̈ = M_a/(I′ + I L²/r²)); and
//! `solve(eq, x^k)`, an equation in which x occurs only as x^k (the
//! conical pendulum's φ̇²) solved for that power.

use super::mass_matrix::system;
use super::sign::sign_of;
use super::{Call, Op};
use crate::atom::{Atom, AtomKind};
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::expr::Expr;
use crate::parse::{Ast, AstKind};
use crate::poly::{Exp, Monomial, Poly};
use crate::rational::Rational;
use crate::vector::Vec3;

pub(crate) const SOLVE: Op = Op {
    names: &["solve"],
    signature: "solve(eq, x), solve(eqs, [x, y, …])",
    doc: "the values of the unknowns that make the equations (a scalar, a vector or a `list`) zero, when they occur \
          linearly and the coefficient matrix's determinant can be divided by (numbers, constants, sin and cos, \
          and a sum of constants whose terms all have one sign for the constants declared `positive`, such as \
          I′ + I L²/r²: \
          otherwise use `mass_matrix`/`forcing`); a factor common to all terms of an equation is divided out first, \
          and a determinant holding a power of the coefficients' own sums is divided by each once, so a \
          solution reads (m g r sin β + T)/(I + m r²), not over (I + m r²)² expanded. \
          A vector equation in three unknowns gives a vector; otherwise one unknown gives a scalar and several a \
          list labelled by the unknowns (θ̈ = …). `solve(eq, x^k)` solves one equation in which x occurs only as \
          x^k for that power (φ̇² = 3 g/(2 L cos θ))",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    if let Some(AstKind::Pow(base, k)) = c.args.get(1).map(|a| &a.kind) {
        return solve_power(c, base, *k);
    }
    let super::mass_matrix::System {
        m,
        f,
        unknowns,
        listed,
        value: v,
    } = system(c)?;
    let mut m = m;
    let mut f = f;
    divide_common(&mut m, &mut f);
    let x = solve_known(&m, &f, &c.cx.positive)
        .map_err(|msg| c.cx.at(c.base, c.args[0].span, advise(msg, &unknowns)))?;
    Ok(match v {
        Value::Vector(_, frame)
            if unknowns.len() == 3 && unknowns.iter().all(|u| u.order() == 0) =>
        {
            Value::Vector(Vec3(x.try_into().expect("three")), frame)
        }
        _ if !listed => Value::Scalar(x.into_iter().next().expect("one unknown")),
        _ => Value::List {
            items: x,
            labels: unknowns,
        },
    })
}

/// `solve(eq, x^k)`: one scalar equation in which the symbol x occurs only
/// as x^k, solved for x^k as for an unknown of its own.
fn solve_power(c: &Call<'_, '_>, base: &Ast, k: u32) -> R<Value> {
    c.arity(2)?;
    let u = c.cx.symbol_arg(base, c.base)?;
    let at = c.args[1].span;
    if k < 2 {
        return c.err(
            at,
            format!("solve for `{u}` itself, not for a power {k} of it"),
        );
    }
    let v = c.value(0)?;
    let Value::Scalar(eq) = &v else {
        return c.err(
            c.args[0].span,
            format!(
                "solving for a power `{u}^{k}` needs one scalar equation, found {}",
                v.describe()
            ),
        );
    };
    let eq = c.cx.unfold(eq);
    let k = Exp::try_from(k).unwrap_or(Exp::MAX);
    let (mut coefficient, mut rest) = (Vec::new(), Vec::new());
    for (m, a) in eq.terms() {
        match m.exponent(u) {
            0 => rest.push((m.clone(), a.clone())),
            e if e == k => coefficient.push((m.without(u, k), a.clone())),
            e => {
                return c.err(
                    at,
                    format!(
                        "`{u}` occurs to the power {e} in the equation: solving for `{u}^{k}` needs `{u}` only as \
                         `{u}^{k}` (an equation linear in `{u}^{k}`)"
                    ),
                );
            }
        }
    }
    if coefficient.is_empty() {
        return c.err(at, format!("`{u}^{k}` does not occur in the equation"));
    }
    let mut m = vec![vec![Poly::from_terms(coefficient)]];
    let mut f = vec![-&Poly::from_terms(rest)];
    divide_common(&mut m, &mut f);
    let x = solve_known(&m, &f, &c.cx.positive)
        .map_err(|msg| c.cx.at(c.base, c.args[0].span, advise(msg, &[u])))?;
    Ok(Value::Scalar(x.into_iter().next().expect("one unknown")))
}

/// Divides each equation `m[i] · x = f[i]` by the monomial common to all
/// its terms (such as sin θ or θ̇), assumed not zero: it cannot change the
/// solution.
fn divide_common(m: &mut [Vec<Poly>], f: &mut [Poly]) {
    for (row, fi) in m.iter_mut().zip(f.iter_mut()) {
        let terms: Vec<&Monomial> = row
            .iter()
            .chain(std::iter::once(&*fi))
            .flat_map(|p| p.terms().iter().map(|t| &t.0))
            .collect();
        let Some(first) = terms.first() else { continue };
        let g = terms.iter().skip(1).fold((*first).clone(), |g, t| g.gcd(t));
        if !g.is_one() {
            let inv = Poly::term(g.recip(), Rational::ONE);
            for p in row.iter_mut().chain(std::iter::once(fi)) {
                *p = &*p * &inv;
            }
        }
    }
}

/// `M x = f` by Cramer's rule, when `det M` can be divided by.
pub(crate) fn solve_system(m: &[Vec<Poly>], f: &[Poly]) -> Result<Vec<Poly>, String> {
    solve_known(m, f, &[])
}

/// The inverse of `det` when it is a divisor times a sum of constants
/// whose terms all have one sign for the `positive` constants (so that it
/// cannot be zero): `1/(I′ + I L²/r²)` is `r²/(I′ r² + I L²)`. `Err` with
/// the reason when it is such a sum whose sign is not known.
pub(crate) fn sum_inverse(det: &Poly, positive: &[Atom]) -> Option<Result<Poly, String>> {
    let (k, s) = det.sum_factor()?;
    let k_inv = k.inverse_divisor()?;
    Some(match sign_of(&s, positive) {
        Some(_) => Ok(&k_inv * &Poly::recip_sum(&s)),
        None => Err(format!(
            "{} could be zero: a sum of constants is divided by only when every term has one sign for the \
             constants declared positive (`[symbols] positive = [...]`; even powers count as positive)",
            factored(&s)
        )),
    })
}

/// The inverse of `det = k · s` with `s` split into the sums of constants
/// that the coefficient matrix's own entries hold (`I + m r²` of a diagonal
/// `diag(I + m r², I + m r², I)`, whose determinant's sum is
/// `I² + 2 m I r² + m² r⁴`), each known not to be zero for the `positive`
/// constants: the canonical form then cancels each factor against the
/// numerators that hold it, so a solution reads `(m g r sin β + T)/(I + m r²)`
/// as a textbook writes it. `None` when no entry's sum divides `s`, or a
/// factor's sign is not known (the caller then divides by `s` whole).
fn factored_inverse(det: &Poly, m: &[Vec<Poly>], positive: &[Atom]) -> Option<Poly> {
    let (k, mut s) = det.sum_factor()?;
    let mut candidates: Vec<Poly> = Vec::new();
    for e in m.iter().flatten() {
        if let Some((_, c)) = e.sum_factor()
            && c != s
            && !candidates.contains(&c)
        {
            candidates.push(c);
        }
    }
    let mut inv = k.inverse_divisor()?;
    let mut split = false;
    for c in &candidates {
        while let Some(q) = s.div_sum(c) {
            sign_of(c, positive)?;
            inv = &inv * &Poly::recip_sum(c);
            s = q;
            split = true;
        }
    }
    if !split {
        return None;
    }
    // What is left: a number times a monomial, or one more sum.
    let rest = match s.inverse_divisor() {
        Some(r) => r,
        None => {
            let (k, rest) = s.sum_factor()?;
            sign_of(&rest, positive)?;
            &k.inverse_divisor()? * &Poly::recip_sum(&rest)
        }
    };
    Some(&inv * &rest)
}

/// [`solve_system`], dividing also by a sum of constants that is known not
/// to be zero for the `positive` constants ([`sum_inverse`]).
fn solve_known(m: &[Vec<Poly>], f: &[Poly], positive: &[Atom]) -> Result<Vec<Poly>, String> {
    let n = m.len();
    if n > 16 {
        return Err(format!("{n} unknowns: at most 16 can be solved for"));
    }
    let det = determinant(m);
    if det.is_zero() {
        return Err(
            "the equations do not determine the unknowns: their coefficient matrix is singular"
                .into(),
        );
    }
    let what = if n == 1 {
        "the coefficient"
    } else {
        "the determinant of the coefficients"
    };
    let inv = match det.inverse_divisor() {
        Some(inv) => inv,
        None => match factored_inverse(&det, m, positive)
            .map(Ok)
            .or_else(|| sum_inverse(&det, positive))
        {
            Some(Ok(inv)) => inv,
            Some(Err(why)) => {
                return Err(format!(
                    "{what} is {}, which cannot be divided by: {why}",
                    factored(&det)
                ));
            }
            None => {
                return Err(format!(
                    "{what} is {}, which cannot be divided by ({}){}",
                    factored(&det),
                    crate::poly::DIVISOR_RULE,
                    vanishing(&det)
                ));
            }
        },
    };
    Ok((0..n)
        .map(|j| {
            let mj: Vec<Vec<Poly>> = m
                .iter()
                .zip(f)
                .map(|(row, fi)| {
                    let mut r = row.clone();
                    r[j] = fi.clone();
                    r
                })
                .collect();
            &determinant(&mj) * &inv
        })
        .collect())
}

/// Why a determinant cannot be divided by: it holds a function of time
/// outside sin and cos (a speed, a rate, a coordinate), which can be zero
/// along the motion, or else it is a sum holding sines and cosines of the
/// coordinates, whose sign the engine does not decide. Empty when neither
/// says more than the rule.
pub(crate) fn vanishing(det: &Poly) -> String {
    let time: Vec<String> = det
        .atoms()
        .into_iter()
        .filter(|a| matches!(a.kind(), AtomKind::Var { time: true, .. }))
        .map(|a| format!("`{a}`"))
        .collect();
    if !time.is_empty() {
        return format!(
            ": {} {} a function of time that can be zero along the motion, so it is never divided by",
            time.join(", "),
            if time.len() == 1 { "is" } else { "are" }
        );
    }
    let trig = det
        .atoms()
        .into_iter()
        .any(|a| matches!(a.kind(), AtomKind::Sin(q) | AtomKind::Cos(q) if q.is_time_dependent()));
    if trig {
        return ": it is a sum holding sines and cosines of the coordinates, which the exact engine does not \
                divide by (it does not decide whether such a sum vanishes at some configuration)"
            .into();
    }
    String::new()
}

/// The error `msg` of [`solve_known`] with what to write
/// instead: for accelerations (every unknown a rate), the mass-matrix
/// form, which a simulation solves numerically; for other unknowns (a
/// steady-motion condition solved for a speed), another unknown.
fn advise(msg: String, unknowns: &[Atom]) -> String {
    if !msg.contains("cannot be divided by (") {
        return msg;
    }
    if unknowns.iter().all(|u| u.order() > 0) {
        return format!(
            "{msg}; write the equations in mass-matrix form with mass_matrix(…) and forcing(…) instead: \
             `hdot simulate` solves them numerically at each step"
        );
    }
    let unknown: Vec<String> = unknowns.iter().map(|u| format!("`{u}`")).collect();
    let unknown = unknown.join(", ");
    format!(
        "{msg}; solving for {unknown} would divide by it: solve for an unknown whose coefficient holds no \
         function of time (in a steady-motion condition, a constant such as a load or `g`), or keep the \
         equation as it stands"
    )
}

/// `p` for an error message, factored where it can be: the monomial common
/// to all terms first, then binomial factors `x ± y` of two atoms, each
/// found by exact division in `x` (`A_3*J*(A_1 + J_t)*(A_2 + J_t)` rather
/// than the expanded sum).
pub(crate) fn factored(p: &Poly) -> String {
    let Some((first, _)) = p.terms().first() else {
        return "0".into();
    };
    let common = p.terms().iter().fold(first.clone(), |g, (m, _)| g.gcd(m));
    let mut rest = p * &Poly::term(common.recip(), Rational::ONE);
    let mut factors: Vec<Poly> = Vec::new();
    // A bounded search: at most a few hundred terms and atoms, each
    // candidate one synthetic division.
    'search: while rest.len() > 1 && rest.len() <= 256 {
        let atoms = rest.atoms();
        for &x in &atoms {
            for &y in &atoms {
                for sign in [Rational::ONE, -Rational::ONE] {
                    if x == y {
                        continue;
                    }
                    let s = Poly::term(Monomial::atom(y, 1), sign.clone());
                    if let Some(q) = rest.div_binomial(x, &s) {
                        factors.push(&Poly::atom(x) + &s);
                        rest = q;
                        continue 'search;
                    }
                }
            }
        }
        break;
    }
    // A binomial that would print with a leading minus (`-B + J`) is
    // turned round (`B - J`), its sign moved to the coefficient.
    let mut coefficient = Poly::one();
    for f in &mut factors {
        if Expr::from_poly(f).to_string().starts_with('-') {
            *f = f.scale(&-Rational::ONE);
            coefficient = coefficient.scale(&-Rational::ONE);
        }
    }
    if rest.len() > 1 {
        factors.push(rest);
    } else {
        // A single term left (a number, or ±1): into the monomial part.
        coefficient = &coefficient * &rest;
    }
    let m = &coefficient * &Poly::term(common, Rational::ONE);
    match m.as_constant() {
        Some(c) if c == Rational::ONE => join(&factors),
        Some(c) if c == -Rational::ONE && !factors.is_empty() => format!("-{}", join(&factors)),
        _ => {
            factors.insert(0, m);
            join(&factors)
        }
    }
}

fn join(factors: &[Poly]) -> String {
    if factors.is_empty() {
        return "1".into();
    }
    factors
        .iter()
        .map(|f| {
            let e = Expr::from_poly(f);
            if f.len() > 1 && factors.len() > 1 {
                format!("({e})")
            } else {
                e.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("*")
}

/// The determinant by Laplace expansion along the rows, memoised on the
/// set of columns left (2ⁿ minors).
pub(crate) fn determinant(m: &[Vec<Poly>]) -> Poly {
    let n = m.len();
    let mut memo: std::collections::HashMap<u32, Poly> = std::collections::HashMap::new();
    fn minor(
        m: &[Vec<Poly>],
        row: usize,
        cols: u32,
        memo: &mut std::collections::HashMap<u32, Poly>,
    ) -> Poly {
        if row == m.len() {
            return Poly::one();
        }
        if let Some(p) = memo.get(&cols) {
            return p.clone();
        }
        let mut acc = Poly::zero();
        let mut sign = 1;
        for j in 0..m.len() {
            if cols & (1 << j) == 0 {
                continue;
            }
            if !m[row][j].is_zero() {
                let sub = minor(m, row + 1, cols & !(1 << j), memo);
                let t = &m[row][j] * &sub;
                acc = if sign > 0 { &acc + &t } else { &acc - &t };
            }
            sign = -sign;
        }
        memo.insert(cols, acc.clone());
        acc
    }
    minor(m, 0, (1u32 << n) - 1, &mut memo)
}
