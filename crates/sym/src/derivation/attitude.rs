//! Attitude kinematics derived, not typed: a `[kinematics]` entry
//! `name = { frame = "B", speeds = ["u_1", "u_2", "u_3"], axes = "L" }`
//! says that the three speeds are frame B's angular velocity in the
//! components of frame `axes` (B's own when omitted). B's angular
//! velocity, linear in the rates of the angles of its chain of rotations
//! from N, is set equal to the speeds and solved for those rates exactly
//! (Cramer's rule): each angle's kinematic equation q̇ = f(q, u), used as
//! a typed one would be. A chain holding a frame turned by Euler
//! parameters adds the rate of their unit norm as a row
//! (`attitude_quaternion.rs`).

use serde::Deserialize;
use toml::Spanned;

use super::context::{Context, R};
use crate::atom::Atom;
use crate::poly::Poly;

/// The inline table of a derived attitude entry.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAttitude {
    frame: String,
    speeds: Vec<String>,
    axes: Option<String>,
}

/// The kinematic equations of the angles that turn frame `frame` from N,
/// derived from the entry `key = value` (a TOML table), in the order the
/// chain of rotations turns them (from N outwards). `speeds` are the
/// file's declared speeds.
pub(crate) fn derive(
    cx: &Context<'_>,
    key: &Spanned<String>,
    value: &Spanned<toml::Value>,
    speeds: &[Atom],
) -> R<Vec<(Atom, Poly)>> {
    let sp = value.span();
    let here = |msg: String| cx.diag(sp.start, sp.end, msg);
    let name = key.get_ref();
    let raw: RawAttitude = value.get_ref().clone().try_into().map_err(|e| {
        here(format!(
            "[kinematics] `{name}`: a derived attitude is {{ frame = \"B\", speeds = [\"u_1\", \"u_2\", \"u_3\"], \
             axes = \"B\" }} (the speeds are B's angular velocity in the components of `axes`): {}",
            first_line(&e.to_string())
        ))
    })?;
    let frame_index = |f: &str| {
        cx.frame_index(f).ok_or_else(|| {
            let known: Vec<&str> = cx.frames.iter().map(|f| f.name.as_str()).collect();
            here(format!(
                "[kinematics] `{name}`: unknown frame `{f}` (one of {})",
                known.join(", ")
            ))
        })
    };
    let fi = frame_index(&raw.frame)?;
    let axes = raw.axes.as_deref().unwrap_or(&raw.frame);
    let ai = frame_index(axes)?;
    let us =
        attitude_speeds(&raw, speeds).map_err(|m| here(format!("[kinematics] `{name}`: {m}")))?;
    let omega = cx
        .along_chain(cx.frames[fi].omega.clone(), fi, ai)
        .ok_or_else(|| {
            here(format!(
                "[kinematics] `{name}`: the components are taken in `{axes}`, which is not on {}'s chain of \
                 rotations from N (name {} itself, one of its parents or a frame turned from it)",
                raw.frame, raw.frame
            ))
        })?;
    let rates = chain_rates(cx, fi);
    let norms = chain_norms(cx, fi);
    if !norms.is_empty() {
        return super::attitude_quaternion::derive(
            cx,
            (name, &raw.frame),
            &omega,
            &us,
            &rates,
            &norms,
        )
        .map_err(here);
    }
    if rates.len() != 3 {
        let listed: Vec<String> = rates.iter().map(ToString::to_string).collect();
        return Err(here(format!(
            "[kinematics] `{name}`: {}'s angular velocity holds the rates of {} angles ({}): three speeds give \
             the rates of three angles (a chain of three rotations from N)",
            raw.frame,
            rates.len(),
            if listed.is_empty() {
                "none".into()
            } else {
                listed.join(", ")
            }
        )));
    }
    let eqs: Vec<Poly> = omega
        .0
        .iter()
        .zip(&us)
        .map(|(w, &u)| &cx.unfold(w) - &Poly::atom(u))
        .collect();
    let (m, f) = super::ops::linear_system(&eqs, &rates)
        .map_err(|m| here(format!("[kinematics] `{name}`: {m}")))?;
    let values = super::ops::solve_system(&m, &f).map_err(|m| {
        here(format!(
            "[kinematics] `{name}`: {}'s angular velocity does not give the angles' rates: {m}",
            raw.frame
        ))
    })?;
    Ok(rates
        .iter()
        .zip(values)
        .map(|(r, v)| (r.base(), v))
        .collect())
}

/// The three speeds an entry names, each a declared speed, none twice.
fn attitude_speeds(raw: &RawAttitude, speeds: &[Atom]) -> Result<Vec<Atom>, String> {
    if raw.speeds.len() != 3 {
        return Err(format!(
            "`speeds` names {} speeds: an angular velocity has three components",
            raw.speeds.len()
        ));
    }
    let mut out: Vec<Atom> = Vec::with_capacity(3);
    for s in &raw.speeds {
        let u = speeds
            .iter()
            .copied()
            .find(|u| u.to_string() == *s)
            .ok_or_else(|| format!("`{s}` is not a declared speed ([symbols] speeds)"))?;
        if out.contains(&u) {
            return Err(format!("`speeds` names `{s}` twice"));
        }
        out.push(u);
    }
    Ok(out)
}

/// The rates of coordinates (first derivatives) in the angular velocities
/// of frame `i`'s chain, in the order the chain turns them from its root.
fn chain_rates(cx: &Context<'_>, mut i: usize) -> Vec<Atom> {
    let mut chain = vec![i];
    while let Some((p, _)) = &cx.frames[i].parent {
        i = cx.frame_index(p).expect("parent exists");
        chain.push(i);
    }
    let mut rates: Vec<Atom> = Vec::new();
    for &k in chain.iter().rev() {
        // Euler parameters in their declared order, the scalar part first.
        for e in cx.frames[k].quaternion.iter().flatten() {
            rates.push(e.derivative().expect("a function of time"));
        }
        for w in &cx.frames[k].omega.0 {
            for a in cx.unfold(w).atoms() {
                if a.order() == 1 && !rates.contains(&a) {
                    rates.push(a);
                }
            }
        }
    }
    rates
}

/// The Euler parameters of the quaternion frames on frame `i`'s chain.
fn chain_norms(cx: &Context<'_>, mut i: usize) -> Vec<[Atom; 4]> {
    let mut out: Vec<[Atom; 4]> = cx.frames[i].quaternion.into_iter().collect();
    while let Some((p, _)) = &cx.frames[i].parent {
        i = cx.frame_index(p).expect("parent exists");
        out.extend(cx.frames[i].quaternion);
    }
    out.reverse();
    out
}

/// The first line of a deserializer's message (the rest repeats the
/// entry's text).
fn first_line(s: &str) -> &str {
    s.lines().next().unwrap_or(s).trim()
}
