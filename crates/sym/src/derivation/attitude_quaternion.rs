//! The kinematic equations of Euler parameters, derived: a frame's
//! angular velocity (three rows, linear in the parameters' rates ė) set
//! equal to the speeds, and the rate of each unit norm e·ė = 0 as a
//! further row, solved for the rates by Cramer's rule with every
//! determinant reduced modulo the norms (`quaternion.rs`). On the unit
//! sphere the determinant is a number, and the result is the textbook's
//! ė = ½ E(e)ᵀ ω — derived from the direction cosine matrix, not typed.

use super::context::Context;
use super::quaternion::{norm_rate, reduce_all};
use crate::atom::Atom;
use crate::poly::Poly;
use crate::vector::Vec3;

/// The rates of `rates` (the coordinates of frame `frame`'s chain, the
/// Euler parameters of `norms` among them) given by `omega` = `us` and
/// the norms' rates; `entry` names the `[kinematics]` entry for messages.
pub(crate) fn derive(
    cx: &Context<'_>,
    (entry, frame): (&str, &str),
    omega: &Vec3,
    us: &[Atom],
    rates: &[Atom],
    norms: &[[Atom; 4]],
) -> Result<Vec<(Atom, Poly)>, String> {
    let mut eqs: Vec<Poly> = omega
        .0
        .iter()
        .zip(us)
        .map(|(w, &u)| reduce_all(&(&cx.unfold(w) - &Poly::atom(u)), norms))
        .collect();
    eqs.extend(norms.iter().map(norm_rate));
    let listed = || {
        rates
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    if eqs.len() != rates.len() {
        return Err(format!(
            "[kinematics] `{entry}`: {frame}'s angular velocity and the unit norm of its Euler parameters give {} \
             equations in the rates of {} coordinates ({}): a frame turned by Euler parameters takes no other \
             angle on its chain of rotations from N",
            eqs.len(),
            rates.len(),
            listed()
        ));
    }
    let (m, f) = super::ops::linear_system(&eqs, rates)
        .map_err(|msg| format!("[kinematics] `{entry}`: {msg}"))?;
    let det = reduce_all(&super::ops::determinant(&m), norms);
    let inverse = det
        .as_constant()
        .and_then(|d| d.recip())
        .ok_or_else(|| {
            format!(
                "[kinematics] `{entry}`: {frame}'s angular velocity does not give the rates of {} on the unit \
                 sphere (the determinant of the rows, reduced by the norm, is {det}, not a non-zero number)",
                listed()
            )
        })?;
    let values = (0..rates.len()).map(|j| {
        let replaced: Vec<Vec<Poly>> = m
            .iter()
            .zip(&f)
            .map(|(row, fi)| {
                let mut row = row.clone();
                row[j] = fi.clone();
                row
            })
            .collect();
        reduce_all(&super::ops::determinant(&replaced), norms).scale(&inverse)
    });
    Ok(rates.iter().map(|r| r.base()).zip(values).collect())
}
