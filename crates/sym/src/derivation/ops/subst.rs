//! `subst(x, a = e, theta' = 0, theta = pi/2, …)`: substitution.

use super::{Call, Op};
use crate::atom::{Atom, AtomKind};
use crate::derivation::context::R;
use crate::derivation::value::Value;
use crate::parse::{Ast, AstKind};
use crate::poly::Poly;
use crate::rational::Rational;
use crate::subst::mentions_symbol;
use crate::symbols::Decl;

pub(crate) const SUBST: Op = Op {
    names: &["subst"],
    signature: "subst(x, a = e, theta' = 0, theta = pi/2)",
    doc: "substitution, rules applied left to right (see *Substitution* below)",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    let Some((_, rules)) = c.args.split_first() else {
        return c.err(
            c.span,
            "subst(x, name = value, …) needs an expression and at least one rule",
        );
    };
    let mut v = c.value(0)?;
    if rules.is_empty() {
        return c.err(c.span, "subst(x, name = value, …) needs at least one rule");
    }
    for r in rules {
        let AstKind::Assign {
            name,
            primes,
            name_span,
            value,
        } = &r.kind
        else {
            return c.err(r.span, "expected a rule `name = value`");
        };
        let Some(decl) = c.cx.symbols.get(name) else {
            return c.err(
                *name_span,
                format!("cannot substitute for `{name}`: it is not a declared symbol"),
            );
        };
        let target =
            c.cx.symbols
                .atom(name, *primes, *name_span)
                .map_err(|e| c.cx.at(c.base, e.span, e.message))?;
        let time = !matches!(decl, Decl::Constant);
        if let Some(turns) = quarter_turns(value) {
            if *primes > 0 {
                return c.err(value.span, "a multiple of pi is an angle, not a rate");
            }
            let mut failed = false;
            v = v.map(&mut |p| {
                p.subst_quarter_turns(target, turns).unwrap_or_else(|| {
                    failed = true;
                    p.clone()
                })
            });
            if failed {
                return c.err(
                    *name_span,
                    format!(
                        "`{name}` occurs outside sin/cos, so it cannot be set to a multiple of pi (pi is no number \
                         of the algebra): take the coefficients first (`subst(jacobian(x, […]), {name} = …)`), or \
                         give the operating point as `q = pi` to `kane` or `linearize` directly, whose result is \
                         then in the deviation from pi"
                    ),
                );
            }
            // A sin or cos that becomes 0 cannot leave a denominator.
            if v.components().iter().any(|p| mentions_symbol(p, target)) {
                return c.err(
                    value.span,
                    format!(
                        "this value makes sin({name}) or cos({name}) zero where it divides; \
                         multiply through before substituting"
                    ),
                );
            }
            continue;
        }
        let val = c.cx.scalar(value, c.base)?;
        if !time {
            let mut stuck = false;
            v = v.map(&mut |p| {
                let q = p.subst(&mut |a| (a == target).then(|| val.clone()));
                stuck |= q.contains(target);
                q
            });
            if stuck {
                return c.err(
                    value.span,
                    format!(
                        "`{name}` occurs in a denominator, and this value cannot be divided by; multiply through first"
                    ),
                );
            }
            continue;
        }
        // A rate or angle: the symbol's derivatives of order ≥ `primes`
        // follow by differentiating the value. An angle set to another
        // angle symbol carries its sin/cos over; an angle set to 0 (a
        // multiple of pi/2 written without pi) has sin 0 and cos 1.
        let angle = val.as_atom().filter(|a| a.is_angle());
        let zero = val.is_zero();
        let mut failed = false;
        v = v.map(&mut |p| {
            p.subst(&mut |a| match a.kind() {
                AtomKind::Var { .. } if a.base() == target.base() && a.order() >= *primes => {
                    Some(val.dt_n(a.order() - primes))
                }
                AtomKind::Sin(q) | AtomKind::Cos(q) if q == target && *primes == 0 => match angle {
                    Some(w) => {
                        let is_sin = matches!(a.kind(), AtomKind::Sin(_));
                        Some(Poly::atom(
                            if is_sin { Atom::sin(w) } else { Atom::cos(w) }.expect("angle"),
                        ))
                    }
                    None if zero => Some(if matches!(a.kind(), AtomKind::Sin(_)) {
                        Poly::zero()
                    } else {
                        Poly::one()
                    }),
                    None => {
                        failed = true;
                        None
                    }
                },
                _ => None,
            })
        });
        // A sin that becomes 0 cannot leave a denominator (the substitution
        // keeps it there, see `Poly::subst`).
        if zero && !failed && v.components().iter().any(|p| mentions_symbol(p, target)) {
            return c.err(
                value.span,
                format!(
                    "this value makes `{name}` or sin({name}) zero where it divides; \
                     multiply through before substituting"
                ),
            );
        }
        if failed {
            return c.err(
                value.span,
                format!("`{name}` occurs inside sin/cos: substitute another angle symbol or a multiple of pi/2"),
            );
        }
    }
    Ok(v)
}

/// `pi`, `pi/2`, `k*pi/2`, `k*pi`, `0` as a number of quarter turns.
pub(crate) fn quarter_turns(ast: &Ast) -> Option<i64> {
    fn walk(a: &Ast) -> Option<(Rational, bool)> {
        match &a.kind {
            AstKind::Name { name, primes: 0 } if name == "pi" => Some((Rational::ONE, true)),
            AstKind::Num(r) => Some((r.clone(), false)),
            AstKind::Neg(x) => walk(x).map(|(r, p)| (-r, p)),
            AstKind::Mul(items) => {
                let mut acc = Rational::ONE;
                let mut has_pi = false;
                for it in items {
                    let (r, p) = match &it.kind {
                        AstKind::Recip(d) => {
                            let (r, p) = walk(d)?;
                            if p {
                                return None;
                            }
                            (r.recip()?, false)
                        }
                        _ => walk(it)?,
                    };
                    if p && has_pi {
                        return None;
                    }
                    has_pi |= p;
                    acc = &acc * &r;
                }
                Some((acc, has_pi))
            }
            _ => None,
        }
    }
    let (r, has_pi) = walk(ast)?;
    if !has_pi {
        return None;
    }
    let q = &r * &Rational::int(2);
    if !q.is_integer() {
        return None;
    }
    q.parts().0.parse().ok()
}
