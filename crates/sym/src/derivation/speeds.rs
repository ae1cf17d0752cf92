//! Generalized speeds and kinematic differential equations: `[symbols]
//! speeds` (u₁, u₂, … functions of time), the `[kinematics]` table giving
//! each coordinate's rate q̇ = f(q, u) (typed, or derived for a frame's
//! angles by `attitude.rs`), the replacement of coordinates'
//! rates by those equations, and a step's speed rates u̇ read in the
//! speeds' order (what a first-order simulation integrates).

use toml::Spanned;

use super::context::{Context, R};
use super::raw::RawFile;
use crate::atom::Atom;
use crate::poly::Poly;
use crate::symbols::Decl;

/// Reads `[kinematics]` (the speeds themselves are declared with the other
/// symbols): each key a declared coordinate, each value its rate in the
/// coordinates, speeds and constants; or a table whose speeds are a
/// frame's angular velocity, its angles' rates derived (`attitude.rs`).
pub(crate) fn declare(cx: &mut Context<'_>, raw: &RawFile) -> R<()> {
    let speeds: Vec<Atom> = raw
        .symbols
        .speeds
        .iter()
        .map(|s| Atom::time(s.get_ref(), 0))
        .collect();
    cx.speeds.speeds = speeds.clone();
    cx.speeds.unit_norms = cx.frames.iter().filter_map(|f| f.quaternion).collect();
    let Some(table) = &raw.kinematics else {
        return Ok(());
    };
    let mut entries: Vec<(&Spanned<String>, &Spanned<toml::Value>)> = table.iter().collect();
    entries.sort_by_key(|(k, _)| k.span().start);
    if speeds.is_empty()
        && let Some((k, _)) = entries.first()
    {
        let sp = k.span();
        return Err(cx.diag(
            sp.start,
            sp.end,
            "[kinematics] gives coordinates' rates in generalized speeds: declare them with [symbols] speeds = [\"u1\", …]",
        ));
    }
    let mut kinematics: Vec<(Atom, Poly)> = Vec::with_capacity(entries.len());
    for (k, v) in entries {
        let sp = v.span();
        let given = match v.get_ref() {
            toml::Value::String(text) => {
                vec![typed(
                    cx,
                    k,
                    &Spanned::new(sp.clone(), text.clone()),
                    &speeds,
                )?]
            }
            toml::Value::Table(_) => super::attitude::derive(cx, k, v, &speeds)?,
            _ => {
                return Err(cx.diag(
                    sp.start,
                    sp.end,
                    format!(
                        "[kinematics] `{}`: a coordinate's rate (a string such as \"u_1\") or a derived attitude \
                         {{ frame = \"B\", speeds = [\"u_1\", \"u_2\", \"u_3\"] }}",
                        k.get_ref()
                    ),
                ));
            }
        };
        for (q, f) in given {
            if kinematics.iter().any(|(c, _)| *c == q) {
                return Err(cx.diag(
                    sp.start,
                    sp.end,
                    format!("[kinematics] gives the rate of `{q}` twice"),
                ));
            }
            kinematics.push((q, f));
        }
    }
    cx.speeds.kinematics = kinematics;
    Ok(())
}

/// A typed entry `q = "f(q, u)"`: the coordinate and its rate.
fn typed(
    cx: &Context<'_>,
    k: &Spanned<String>,
    v: &Spanned<String>,
    speeds: &[Atom],
) -> R<(Atom, Poly)> {
    let name = k.get_ref();
    let sp = k.span();
    let q = match cx.symbols.get(name) {
        Some(Decl::Time) if !speeds.contains(&Atom::time(name, 0)) => Atom::time(name, 0),
        Some(Decl::Time) => {
            return Err(cx.diag(
                sp.start,
                sp.end,
                format!("[kinematics] `{name}` is a speed: the table gives coordinates' rates (q' = f(q, u))"),
            ));
        }
        _ => {
            return Err(cx.diag(
                sp.start,
                sp.end,
                format!(
                    "[kinematics] `{name}` is not a coordinate: declare it under [symbols] time"
                ),
            ));
        }
    };
    let f = cx.unfold(&cx.scalar_in(v)?);
    if let Some(a) = f.atoms().into_iter().find(|a| a.order() > 0) {
        return Err(cx.diag_string(
            v,
            0,
            v.get_ref().len(),
            format!(
                "[kinematics] `{name}`: the rate is written in coordinates, speeds and constants, not in rates such as `{a}`"
            ),
        ));
    }
    Ok((q, f))
}

/// The values of the step called `step` that give the speeds' rates, in
/// the speeds' order: a list solved for `[u1', u2', …]` (any order of the
/// unknowns), abbreviations unfolded. An error message says what the step
/// is instead.
pub(crate) fn speed_rates(d: &super::Derivation, step: &str) -> Result<Vec<Poly>, String> {
    let speeds = &d.speeds.speeds;
    if speeds.is_empty() {
        return Err(format!(
            "{} declares no generalized speeds ([symbols] speeds = [\"u1\", …])",
            d.path
        ));
    }
    let Some(s) = d.steps.iter().find(|s| s.name == step) else {
        return Err(format!("{}: no step called `{step}`", d.path));
    };
    let want: Vec<String> = speeds.iter().map(|u| format!("{u}'")).collect();
    let bad = || {
        format!(
            "{}: step `{step}` is {}, not the speeds' rates solved for (write it as solve(eqs, [{}]))",
            d.path,
            s.value.describe(),
            want.join(", ")
        )
    };
    let super::Value::List { items, labels } = &s.value else {
        return Err(bad());
    };
    if labels.len() != speeds.len() {
        return Err(bad());
    }
    speeds
        .iter()
        .map(|u| {
            let du = u.derivative().expect("a speed is a function of time");
            labels
                .iter()
                .position(|l| *l == du)
                .map(|k| d.unfold(&items[k]))
                .ok_or_else(bad)
        })
        .collect()
}
