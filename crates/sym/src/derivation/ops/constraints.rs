//! The constraints of `kane`: velocity constraints (linear in the speeds)
//! and configuration constraints f(q) = 0 (their rates join the velocity
//! constraints) solved for the dependent speeds — exactly, or to first
//! order about an operating point — and, about an operating point, the
//! dependent coordinates by implicit differentiation,
//! Δq_d = −(∂f/∂q_d)⁻¹ (∂f/∂q_i) Δq_i.

use super::Call;
use super::mass_matrix::linear_system;
use super::solve::solve_system;
use super::velocity::{Speedmap, linear_in_speeds};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::operating::OperatingPoint;
use crate::parse::AstKind;
use crate::poly::Poly;
use crate::vector::Vec3;

/// Kane's equations to first order about an operating point: the point,
/// and which symbols are coordinates (expanded in the velocities, whose
/// speeds are kept exact so that partial velocities can be read off).
pub(crate) struct Linear<'c, 'a, 'b> {
    pub c: &'c Call<'a, 'b>,
    pub op: OperatingPoint,
}

impl Linear<'_, '_, '_> {
    fn coordinate(&self, x: Atom) -> bool {
        x.order() == 0 && !self.c.cx.speeds.speeds.contains(&x)
    }

    fn fail(&self, a: Atom) -> crate::derivation::Diagnostic {
        let c = self.c;
        c.cx.at(
            c.base,
            c.span,
            format!(
                "`{a}` cannot be expanded about its operating value: give an angle the value 0, a multiple of pi/2 \
                 (under sin and cos only) or a constant symbol, and divide by no sine or cosine that vanishes there"
            ),
        )
    }

    /// `p` to first order in the coordinates (speeds held exact).
    pub fn positional(&self, p: &Poly) -> R<Poly> {
        self.op
            .first_order(p, &|x| self.coordinate(x))
            .map_err(|a| self.fail(a))
    }

    /// `p` to first order in every symbol with an operating value.
    pub fn full(&self, p: &Poly) -> R<Poly> {
        self.op.first_order(p, &|_| true).map_err(|a| self.fail(a))
    }

    /// `p` at the operating point's coordinates.
    fn at(&self, p: &Poly) -> R<Poly> {
        self.op
            .at(p, &|x| self.coordinate(x))
            .map_err(|a| self.fail(a))
    }

    /// A vector, component by component, through `f`.
    pub fn vec(&self, v: &Vec3, f: impl Fn(&Self, &Poly) -> R<Poly>) -> R<Vec3> {
        let [a, b, c] = &v.0;
        Ok(Vec3([f(self, a)?, f(self, b)?, f(self, c)?]))
    }
}

/// What the constraints give: the dependent speeds in the independent
/// ones, and (about an operating point) the dependent coordinates'
/// deviations in the others.
pub(crate) struct Eliminated {
    pub speeds: Vec<(Atom, Poly)>,
    pub coordinates: Vec<(Atom, Poly)>,
}

/// The constraints (argument 1) solved for the dependent speeds `deps`;
/// `qdeps` are the dependent coordinates of the configuration constraints
/// (argument 3, when given).
pub(crate) fn eliminate(
    c: &Call<'_, '_>,
    deps: &[Atom],
    qdeps: &[Atom],
    lin: Option<&Linear<'_, '_, '_>>,
) -> R<Eliminated> {
    let span = c.args[1].span;
    let v = c.value(1)?;
    let Some(eqs) = v.equations() else {
        return c.err(
            span,
            format!(
                "the constraints are a vector or a list that vanishes, found {}",
                v.describe()
            ),
        );
    };
    let plain = Speedmap::plain(c);
    let speeds = &c.cx.speeds.speeds;
    let at = |msg: String| c.cx.at(c.base, span, msg);
    let mut velocity: Vec<Poly> = Vec::with_capacity(eqs.len());
    let mut configuration: Vec<Poly> = Vec::new();
    for p in eqs.iter().map(|p| plain.poly(p)).filter(|p| !p.is_zero()) {
        if let Some(a) = p.atoms().into_iter().find(|a| a.order() > 0) {
            return Err(at(format!(
                "`{a}` occurs in the constraints: they are written in the coordinates and the speeds (give `{}` a kinematic equation)",
                a.base()
            )));
        }
        if p.atoms().iter().any(|a| speeds.contains(a)) {
            velocity.push(p);
        } else {
            // A configuration constraint f(q) = 0: its rate in the speeds.
            velocity.push(plain.poly(&p.dt()));
            configuration.push(p);
        }
    }
    if configuration.len() != qdeps.len() {
        let n = configuration.len();
        return Err(at(format!(
            "{n} configuration constraint{} (free of the speeds) for {} dependent coordinate{}: list one dependent \
             coordinate per configuration constraint, kane([u…], constraints, [dependent u…], [dependent q…])",
            if n == 1 { "" } else { "s" },
            qdeps.len(),
            if qdeps.len() == 1 { "" } else { "s" },
        )));
    }
    linear_in_speeds(c, &velocity, "a constraint").map_err(|e| at(e.message))?;
    if velocity.len() != deps.len() {
        return Err(at(format!(
            "{} independent constraint equation{} for {} dependent speed{}: give one dependent speed per constraint",
            velocity.len(),
            if velocity.len() == 1 { "" } else { "s" },
            deps.len(),
            if deps.len() == 1 { "" } else { "s" },
        )));
    }
    let Some(lin) = lin else {
        let (m, f) = linear_system(&velocity, deps).map_err(at)?;
        let x = solve_system(&m, &f).map_err(|e| {
            let every: Vec<String> = speeds.iter().map(|u| u.to_string()).collect();
            at(format!(
                "the dependent speeds cannot be eliminated: {e}; it vanishes wherever the constraints are \
                 singular. Keep the constraints in multiplier form instead: Kane's equations in every speed, \
                 `kane([{0}])`, with `mass_matrix(…)` and `forcing(…)`, the constraint matrix \
                 `jacobian(c, [{0}])` of the velocity constraints c (a configuration constraint f's are \
                 `in_speeds(dt(f))`) and its rate with the speeds' rates zero; `hdot simulate` solves the \
                 rates and the multipliers together (docs/multibody.md, *In multiplier form*)",
                every.join(", ")
            ))
        })?;
        return Ok(Eliminated {
            speeds: deps.iter().copied().zip(x).collect(),
            coordinates: Vec::new(),
        });
    };
    let velocity = velocity
        .iter()
        .map(|p| lin.positional(p))
        .collect::<R<Vec<_>>>()?;
    let (m, f) = linear_system(&velocity, deps).map_err(at)?;
    // M = M₀ + M₁ with M₀ at the operating point: u = M₀⁻¹ (f − M₁ M₀⁻¹ f)
    // to first order.
    let m0 = m
        .iter()
        .map(|row| row.iter().map(|p| lin.at(p)).collect::<R<Vec<_>>>())
        .collect::<R<Vec<_>>>()?;
    let singular = |e: String| {
        at(format!(
            "the dependent speeds cannot be eliminated at the operating point: {e}"
        ))
    };
    let x0 = solve_system(&m0, &f).map_err(singular)?;
    let f1: Vec<Poly> = f
        .iter()
        .zip(m.iter().zip(&m0))
        .map(|(fi, (row, row0))| {
            row.iter()
                .zip(row0)
                .zip(&x0)
                .fold(fi.clone(), |acc, ((mij, m0ij), xj)| {
                    &acc - &(&(mij - m0ij) * xj)
                })
        })
        .collect();
    let x = solve_system(&m0, &f1).map_err(singular)?;
    let x = x.iter().map(|p| lin.positional(p)).collect::<R<Vec<_>>>()?;
    let coordinates = implicit(c, lin, &configuration, qdeps)?;
    Ok(Eliminated {
        speeds: deps.iter().copied().zip(x).collect(),
        coordinates,
    })
}

/// The dependent coordinates' values to first order about the operating
/// point, from the configuration constraints expanded there.
fn implicit(
    c: &Call<'_, '_>,
    lin: &Linear<'_, '_, '_>,
    configuration: &[Poly],
    qdeps: &[Atom],
) -> R<Vec<(Atom, Poly)>> {
    if qdeps.is_empty() {
        return Ok(Vec::new());
    }
    let span = c.args[3].span;
    let at = |msg: String| c.cx.at(c.base, span, msg);
    for &q in qdeps {
        if lin.op.value(q).is_none() {
            return Err(at(format!(
                "the dependent coordinate `{q}` needs an operating value (`{q} = …`)"
            )));
        }
    }
    let mut expanded = Vec::with_capacity(configuration.len());
    for (i, f) in configuration.iter().enumerate() {
        let f0 = lin.op.at(f, &|_| true).map_err(|a| lin.fail(a))?;
        if !f0.is_zero() {
            return Err(at(format!(
                "configuration constraint {} is {} at the operating point, not 0: the operating point must satisfy it",
                i + 1,
                f0
            )));
        }
        expanded.push(lin.full(f)?);
    }
    let (m, rhs) = linear_system(&expanded, qdeps).map_err(at)?;
    let x = solve_system(&m, &rhs).map_err(|e| {
        at(format!(
            "the dependent coordinates cannot be found from the configuration constraints at the operating point \
             (∂f/∂q_d is singular there): {e}"
        ))
    })?;
    Ok(qdeps.iter().copied().zip(x).collect())
}

/// Argument `i`: declared coordinates (time symbols that are not speeds)
/// in brackets.
pub(crate) fn coordinates_arg(c: &Call<'_, '_>, i: usize) -> R<Vec<Atom>> {
    let (qs, _) = c.symbols(i)?;
    for (k, &q) in qs.iter().enumerate() {
        let span = match &c.args[i].kind {
            AstKind::Vector { items, .. } => items[k].span,
            _ => c.args[i].span,
        };
        if !q.is_time_dependent() || q.order() > 0 || c.cx.speeds.speeds.contains(&q) {
            return c.err(
                span,
                format!("`{q}` is not a coordinate (a time symbol that is not a speed)"),
            );
        }
    }
    Ok(qs)
}
