//! `linearize(x)`: first order in the symbols declared small; and
//! `linearize(x, q = q0, u = u0, …)`: first order about an operating point.

use super::{Call, Op};
use crate::atom::AtomKind;
use crate::derivation::context::R;
use crate::derivation::operating::OperatingPoint;
use crate::derivation::value::Value;
use crate::parse::AstKind;
use crate::poly::Poly;

pub(crate) const LINEARIZE: Op = Op {
    names: &["linearize"],
    signature: "linearize(x), linearize(x, e_1), linearize(x, q = q0, u = u0, …)",
    doc: "keep terms of first order in the symbols declared `small` (an undeclared one is an error); a small angle \
          counts as first order under sin and cos (sin ε → ε, cos ε → 1). With `name = value` arguments, the \
          first-order Taylor polynomial about that operating point, f(x₀) + Σ ∂f/∂x(x₀) (x − x₀), in the listed \
          coordinates, speeds and rates (values in constants; a rate of a listed symbol is 0 there unless listed; \
          symbols not listed are held as they are). An angle may be given a multiple of pi/2 (`q1 = pi`, the \
          inverted pendulum): its sine and cosine are exact there and the result is in its deviation from that \
          value (q1 stands for q1 − π), which must occur only under sin and cos",
    eval,
};

/// First order in the declared small symbols (a term with two or more
/// small factors, counting derivatives, is dropped).
fn eval(c: &Call<'_, '_>) -> R<Value> {
    if c.args.is_empty() {
        return c.err(c.span, "linearize(x) needs an expression");
    }
    if c.args[1..]
        .iter()
        .any(|a| matches!(a.kind, AstKind::Assign { .. }))
    {
        return about(c);
    }
    let mut small = Vec::new();
    for (i, a) in c.args.iter().enumerate().skip(1) {
        let s = c.symbol(i)?;
        if !c.cx.small.contains(&s) {
            return c.err(
                a.span,
                format!(
                    "`{}` is not declared small; list it under [symbols] small = [...]",
                    s.name()
                ),
            );
        }
        small.push(s);
    }
    if c.args.len() == 1 {
        if c.cx.small.is_empty() {
            return c.err(
                c.span,
                "no symbol is declared small: add [symbols] small = [...]",
            );
        }
        small = c.cx.small.clone();
    }
    let v = c.value(0)?;
    Ok(v.map(&mut |p| {
        // A small angle: sin ε = ε + O(ε³) and cos ε = 1 + O(ε²), whose
        // remainders are dropped with the other higher-order terms.
        let p = p.subst(&mut |a| match a.kind() {
            AtomKind::Sin(q) if small.contains(&q) => Some(Poly::atom(q)),
            AtomKind::Cos(q) if small.contains(&q) => Some(Poly::one()),
            _ => None,
        });
        Poly::from_terms(p.terms().iter().filter_map(|(m, c)| {
            let order: i32 = m
                .factors()
                .iter()
                .filter(|(a, _)| small.contains(&a.base()))
                .map(|f| f.1)
                .sum();
            (order <= 1).then(|| (m.clone(), c.clone()))
        }))
    }))
}

/// `linearize(x, q = q0, …)`: the Taylor polynomial of first order about
/// the operating point.
fn about(c: &Call<'_, '_>) -> R<Value> {
    let op = OperatingPoint::read(c, &c.args[1..])?;
    let v = c.value(0)?;
    if let Some(a) = v
        .components()
        .into_iter()
        .find_map(|p| op.outside_trig(&c.cx.unfold(p)))
    {
        return c.err(c.args[0].span, outside_trig_message(a));
    }
    let mut failed = None;
    let out = v.map(&mut |p| {
        let p = c.cx.unfold(p);
        op.first_order(&p, &|_| true).unwrap_or_else(|a| {
            failed.get_or_insert(a);
            p
        })
    });
    match failed {
        Some(a) => c.err(
            c.span,
            format!(
                "`{a}` cannot be expanded about its operating value: give an angle the value 0, a multiple of pi/2 \
                 (under sin and cos only) or a constant symbol, and divide by no sine or cosine that vanishes there"
            ),
        ),
        None => Ok(out),
    }
}

/// The error for an angle given a multiple of π/2 that occurs outside sin
/// and cos in what is expanded (`linearize`, `kane`).
pub(crate) fn outside_trig_message(a: crate::atom::Atom) -> String {
    format!(
        "`{a}` occurs outside sin and cos, so its operating value cannot be a multiple of pi (pi is no number of \
         the algebra): write it under sin and cos, or give the operating point as a constant symbol (`{a} = beta`) \
         and substitute after taking coefficients"
    )
}
