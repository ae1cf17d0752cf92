//! Generalized speeds and kinematic differential equations: `[symbols]
//! speeds` (u₁, u₂, … functions of time), the `[kinematics]` table giving
//! each coordinate's rate q̇ = f(q, u), the replacement of coordinates'
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
/// coordinates, speeds and constants.
pub(crate) fn declare(cx: &mut Context<'_>, raw: &RawFile) -> R<()> {
    let speeds: Vec<Atom> = raw
        .symbols
        .speeds
        .iter()
        .map(|s| Atom::time(s.get_ref(), 0))
        .collect();
    cx.speeds.speeds = speeds.clone();
    let Some(table) = &raw.kinematics else {
        return Ok(());
    };
    let mut entries: Vec<(&Spanned<String>, &Spanned<String>)> = table.iter().collect();
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
    let mut kinematics = Vec::with_capacity(entries.len());
    for (k, v) in entries {
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
        kinematics.push((q, f));
    }
    cx.speeds.kinematics = kinematics;
    Ok(())
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
