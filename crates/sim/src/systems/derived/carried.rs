//! Angles carried along the run: a time symbol that is not a coordinate,
//! a speed nor an input, that a frame's rotation turns by, and whose rate
//! a `[motion]` rule gives in the state (`psi' = -(L/r)*phi'`, a rolling
//! condition), is integrated with the state — its rate is the rule — so
//! the frame's attitude is a function of the state and can be reported.

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::RuleValue;
use hdot_sym::poly::Poly;

/// The angles to carry, each with its rate as the rule gives it (in
/// the derivation's symbols: coordinates' rates not yet replaced).
pub(super) fn carried_angles(
    d: &Derivation,
    coordinates: &[Atom],
    speeds: &[Atom],
    inputs: &[&str],
) -> Vec<(Atom, Poly)> {
    let turns_a_frame = |angle: Atom| {
        d.frames.iter().any(|f| {
            f.parent.as_ref().is_some_and(|(_, r)| {
                r.0.iter().flatten().any(|p| {
                    p.atoms().into_iter().any(|a| match a.kind() {
                        AtomKind::Sin(q) | AtomKind::Cos(q) => q == angle,
                        _ => a == angle,
                    })
                })
            })
        })
    };
    let mut out: Vec<(Atom, Poly)> = Vec::new();
    for rule in &d.physics.motion {
        let angle = rule.target.base();
        let RuleValue::Expr(rate) = &rule.value else {
            continue;
        };
        if rule.target.order() != 1
            || !angle.is_time_dependent()
            || coordinates.contains(&angle)
            || speeds.contains(&angle)
            || inputs.contains(&angle.name())
            || out.iter().any(|(a, _)| *a == angle)
            || !turns_a_frame(angle)
        {
            continue;
        }
        out.push((angle, d.unfold(rate)));
    }
    out
}
