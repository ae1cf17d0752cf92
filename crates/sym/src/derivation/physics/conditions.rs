//! A step's meaning and its conditions: `means` with `given` (rules on
//! the motion, points at rest, inequalities selecting a class of bodies)
//! and `symmetry`; the rules of `[motion] given` are read here too.

use std::collections::BTreeMap;

use toml::Spanned;

use super::check::{no_step_names, unknown};
use super::means::{check_shape, meaning};
use super::{Physics, PointKind, Rule, RuleValue, StepMeaning};
use crate::atom::Atom;
use crate::derivation::context::{Context, R};
use crate::derivation::raw::{RawAbbrev, RawStep};
use crate::derivation::value::Value;
use crate::parse::AstKind;
use crate::poly::Poly;
use crate::symbols::Decl;

/// Reads a step's `means` and `given` and checks the meaning's shape
/// against the step's value.
pub(crate) fn step_meaning(
    cx: &Context<'_>,
    ph: &Physics,
    s: &RawStep,
    value: &Value,
) -> R<Option<StepMeaning>> {
    conditioned(
        cx,
        ph,
        s.means.as_ref(),
        &s.given,
        s.symmetry.as_ref(),
        value,
    )
}

/// Reads an abbreviation's `means` and `given`: its definition, a scalar,
/// is verified like a step's value.
pub(crate) fn abbreviation_meaning(
    cx: &Context<'_>,
    ph: &Physics,
    a: &RawAbbrev,
    value: &Value,
) -> R<Option<StepMeaning>> {
    conditioned(cx, ph, a.means.as_ref(), &a.given, None, value)
}

/// A meaning with its conditions: `given` (rules, points at rest,
/// inequalities) and `symmetry`.
fn conditioned(
    cx: &Context<'_>,
    ph: &Physics,
    means: Option<&Spanned<String>>,
    given_raw: &[Spanned<String>],
    symmetry_raw: Option<&Spanned<BTreeMap<String, Spanned<String>>>>,
    value: &Value,
) -> R<Option<StepMeaning>> {
    let Some(means) = means else {
        if let Some(g) = given_raw.first() {
            let n = g.get_ref().len();
            return Err(cx.diag_string(
                g,
                0,
                n,
                "`given` is the condition of a step's `means`; this step has none",
            ));
        }
        if let Some(t) = symmetry_raw {
            let span = t.span();
            return Err(cx.diag(
                span.start,
                span.end,
                "`symmetry` is the condition of a step's `means`; this step has none",
            ));
        }
        return Ok(None);
    };
    let meaning = meaning(cx, ph, means)?;
    check_shape(cx, means, &meaning, value)?;
    let mut given = Vec::new();
    let mut at_rest = Vec::new();
    let mut bounds = Vec::new();
    for r in given_raw {
        if r.get_ref().contains(['<', '>']) {
            bounds.push(bound(cx, r)?);
            continue;
        }
        match point_at_rest(cx, ph, r)? {
            Some(p) => at_rest.push(p),
            None => given.push(rule(cx, ph, r)?),
        }
    }
    let mut conditions = Vec::new();
    if !given_raw.is_empty() {
        let items: Vec<String> = given_raw
            .iter()
            .map(|g| format!("{:?}", g.get_ref()))
            .collect();
        conditions.push(format!("given = [{}]", items.join(", ")));
    }
    if let Some(t) = symmetry_raw {
        let items: Vec<String> = t
            .get_ref()
            .iter()
            .map(|(k, v)| format!("{k} = {:?}", v.get_ref()))
            .collect();
        conditions.push(format!("symmetry = {{{}}}", items.join(", ")));
    }
    let mut symmetry = Vec::new();
    for (name, sym) in symmetry_raw.iter().flat_map(|t| t.get_ref()) {
        let table = symmetry_raw.expect("present");
        let Some(i) = ph.bodies.iter().position(|b| &b.name == name) else {
            let known: Vec<String> = ph.bodies.iter().map(|b| b.name.clone()).collect();
            let span = table.span();
            return Err(cx.diag(span.start, span.end, unknown("body", name, &known)));
        };
        symmetry.push((
            i,
            super::bodies::symmetry(cx, sym, &cx.frames[ph.bodies[i].frame].axes)?,
        ));
    }
    Ok(Some(StepMeaning {
        meaning,
        text: means.get_ref().clone(),
        given,
        at_rest,
        symmetry,
        bounds,
        conditions: conditions.join(", "),
    }))
}

/// Parses an inequality `a > b` or `a < b` of the file's symbols into
/// `a − b` (or `b − a`), positive.
fn bound(cx: &Context<'_>, s: &Spanned<String>) -> R<(Poly, String)> {
    let text = s.get_ref();
    let base = cx.content_start(s);
    let bad = |msg: &str| cx.diag_string(s, 0, text.len(), msg);
    let Some(i) = text.find(['<', '>']) else {
        return Err(bad("expected an inequality `a > b`"));
    };
    if text[i + 1..].contains(['<', '>', '=']) || text[..i].contains('=') {
        return Err(bad(
            "a class of bodies is given by strict inequalities, one per item: `A > B`, `B > C`",
        ));
    }
    let side = |from: usize, to: usize| -> R<Poly> {
        let ast = cx.parse_at(&text[from..to], base + from)?;
        no_step_names(cx, &ast, base + from)?;
        Ok(cx.unfold(&cx.scalar(&ast, base + from)?))
    };
    let (lhs, rhs) = (side(0, i)?, side(i + 1, text.len())?);
    if lhs
        .atoms()
        .into_iter()
        .chain(rhs.atoms())
        .any(Atom::is_time_dependent)
    {
        return Err(bad(
            "an inequality selects a class of bodies: it is written in constants (the moments A, B, C), not functions of time",
        ));
    }
    let p = if text.as_bytes()[i] == b'>' {
        &lhs - &rhs
    } else {
        &rhs - &lhs
    };
    Ok((p, text.clone()))
}

/// `P' = 0` (`P'' = 0`, …) for a point P that the verifier moves freely:
/// the point's velocity (acceleration, …) vanishes. `None` when the
/// condition is not about a point.
fn point_at_rest(
    cx: &Context<'_>,
    ph: &Physics,
    s: &Spanned<String>,
) -> R<Option<(String, usize)>> {
    let Some((lhs, rhs)) = s.get_ref().split_once('=') else {
        return Ok(None);
    };
    let name = lhs.trim().trim_end_matches('\'');
    let order = lhs.trim().len() - name.len();
    let declared = ph.points.iter().find(|p| p.name == name);
    let centre = ph.bodies.iter().find(|b| b.centre.as_deref() == Some(name));
    if declared.is_none() && centre.is_none() {
        return Ok(None);
    }
    let n = s.get_ref().len();
    if order == 0 || rhs.trim() != "0" {
        return Err(cx.diag_string(
            s,
            0,
            n,
            format!("a condition on point {name} is `{name}' = 0` (at rest) or `{name}'' = 0` (no acceleration)"),
        ));
    }
    let free = match (declared, centre) {
        (Some(p), _) => p.kind == PointKind::Free,
        (None, Some(b)) => b.about_centre(),
        (None, None) => false,
    };
    if !free {
        return Err(cx.diag_string(
            s,
            0,
            n,
            format!("point {name} moves as its declaration says; only a point that moves freely (a `[[point]]` without `fixed` or `from`, or the centre of a body about its centre) can be set at rest"),
        ));
    }
    Ok(Some((name.to_owned(), order)))
}

/// Parses a rule `q = e`, `q' = e`, `q = pi/2`, or a constant's value
/// `s = 0` (a special case: a constant the bodies and knowns do not bind).
pub(super) fn rule(cx: &Context<'_>, ph: &Physics, s: &Spanned<String>) -> R<Rule> {
    // Parsed as the argument of a call, where `name = value` is allowed.
    let base = cx.content_start(s);
    let wrapped = format!("f({})", s.get_ref());
    let shifted = base.wrapping_sub(2);
    let ast = crate::parse::parse(&wrapped).map_err(|e| cx.at(shifted, e.span, e.message))?;
    let bad = || {
        cx.diag_string(
            s,
            0,
            s.get_ref().len(),
            "a condition is written `q = e`, `q' = e` or `q = pi/2`, q a time symbol",
        )
    };
    let AstKind::Call { args, .. } = &ast.kind else {
        return Err(bad());
    };
    let [arg] = args.as_slice() else {
        return Err(bad());
    };
    let AstKind::Assign {
        name,
        primes,
        name_span,
        value,
    } = &arg.kind
    else {
        return Err(bad());
    };
    let target = match cx.symbols.get(name) {
        Some(Decl::Time) => Atom::time(name, *primes),
        Some(Decl::Constant) if *primes == 0 => {
            let c = Atom::constant(name);
            if let Some(by) = bound_by(ph, c) {
                return Err(cx.at(
                    shifted,
                    *name_span,
                    format!(
                        "`{name}` is measured on the particles ({by}): a condition cannot fix it"
                    ),
                ));
            }
            c
        }
        Some(Decl::Constant) => {
            return Err(cx.at(
                shifted,
                *name_span,
                format!("`{name}` is a constant: it has no rates (write `{name} = e`)"),
            ));
        }
        _ => {
            return Err(cx.at(
                shifted,
                *name_span,
                format!("`{name}` is neither a time symbol nor a constant: a condition sets a coordinate, a rate or a constant"),
            ));
        }
    };
    let value = match crate::derivation::ops::quarter_turns(value) {
        Some(t) if *primes == 0 => RuleValue::QuarterTurns(t),
        Some(_) => {
            return Err(cx.at(
                shifted,
                value.span,
                "a multiple of pi is an angle, not a rate",
            ));
        }
        None => {
            no_step_names(cx, value, shifted)?;
            let p = cx.scalar(value, shifted)?;
            if p.atoms()
                .iter()
                .any(|a| *a == target || a.base() == target.base() && a.order() >= *primes)
            {
                return Err(cx.at(
                    shifted,
                    value.span,
                    format!("the value of `{name}` cannot depend on it"),
                ));
            }
            RuleValue::Expr(cx.unfold(&p))
        }
    };
    Ok(Rule {
        target,
        value,
        text: s.get_ref().clone(),
    })
}

/// What binds the constant `c` from the particles, when something does:
/// a body's mass, mass centre or inertia, or a `[[known]]`.
fn bound_by(ph: &Physics, c: Atom) -> Option<String> {
    for b in &ph.bodies {
        let polys = b
            .mass
            .iter()
            .chain(b.mass_centre.iter().flat_map(|v| v.0.iter()))
            .chain(b.inertia.0.iter().flatten());
        for p in polys {
            if p.atoms().contains(&c) {
                return Some(format!("body `{}`", b.name));
            }
        }
    }
    ph.knowns
        .iter()
        .find(|k| k.value.components().iter().any(|p| p.atoms().contains(&c)))
        .map(|k| format!("the known `{}`", k.text))
}
