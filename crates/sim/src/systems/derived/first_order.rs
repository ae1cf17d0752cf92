//! The first-order form of derived equations: a state `y = (q, u)` of the
//! coordinates (in the order of the derivation's `[kinematics]`) and the
//! independent generalized speeds, integrated as q̇ = f(q, u) (the
//! kinematic equations) and u̇ = g(q, u) (a step solved for the speeds'
//! rates, or a mass-matrix form M(q) u̇ = f(q, u) in them). Dependent
//! speeds — those a step `solve(constraints, [u4, u5])` gives in the
//! others — are replaced by their values wherever they occur, so the
//! constraints hold along the whole run, and a coordinate's rate anywhere
//! (a frame's ω, a conserved step) by its kinematic equation.

use hdot_sym::atom::Atom;
use hdot_sym::derivation::{Derivation, Value};
use hdot_sym::poly::Poly;

use super::build::{mass_matrix_and_forcing, step, step_unknowns};
use super::{DerivedModel, Form, MAX_DOF, MAX_STATE, SpeedRates, at, err, multiplier};
use crate::SimError;

/// What a first-order model compiles: its state's coordinates and
/// speeds, the atoms replaced before compiling, and the outputs of the
/// equations' tape (`[q̇…, u̇…]` explicit, or `[M…, f…, q̇…]`).
pub(super) struct FirstOrderEquations {
    pub(super) coordinates: Vec<Atom>,
    pub(super) speeds: Vec<Atom>,
    pub(super) replace: Vec<(Atom, Poly)>,
    pub(super) outputs: Vec<Poly>,
    /// Where a multiplier form's outputs go.
    pub(super) layout: Option<multiplier::Layout>,
}

/// Reads the kinematic equations, the dependent speeds and the speeds'
/// rates of `d`; errors are traced to the scene field that names the step.
pub(super) fn equations(
    d: &Derivation,
    rates: &SpeedRates,
    dependent: Option<&str>,
) -> Result<FirstOrderEquations, SimError> {
    let rates_field = match rates {
        SpeedRates::Explicit { .. } => "derivation.rates",
        SpeedRates::MassMatrix { .. } | SpeedRates::Multiplier(_) => "derivation.mass_matrix",
    };
    let declared = d.speeds();
    if declared.is_empty() {
        return Err(at(
            rates_field,
            err(format!(
                "{}: declares no generalized speeds ([symbols] speeds = [\"u1\", …]): a first-order model \
                 integrates q' = f(q, u) and u' = g(q, u)",
                d.path
            )),
        ));
    }
    let kinematics = d.kinematic_equations();
    if kinematics.is_empty() {
        return Err(at(
            rates_field,
            err(format!(
                "{}: has no [kinematics] table (each coordinate's rate in the speeds, q' = f(q, u)): \
                 a first-order model integrates the coordinates by it",
                d.path
            )),
        ));
    }
    let dependent = match dependent {
        Some(name) => dependent_speeds(d, name).map_err(|e| at("derivation.dependent", e))?,
        None => Vec::new(),
    };
    let (speeds, rate_outputs, layout) = match rates {
        SpeedRates::Multiplier(spec) => {
            let (speeds, outputs, layout) = multiplier::outputs(d, spec)?;
            (speeds, outputs, Some(layout))
        }
        _ => {
            let (speeds, outputs) =
                speed_rates(d, rates, &dependent).map_err(|e| at(rates_field, e))?;
            (speeds, outputs, None)
        }
    };
    // Every declared speed is in the state or given by the constraints.
    if let Some(u) = declared
        .iter()
        .find(|u| !speeds.contains(u) && !dependent.iter().any(|(x, _)| x == *u))
    {
        let field = if dependent.is_empty() {
            rates_field
        } else {
            "derivation.dependent"
        };
        return Err(at(
            field,
            err(format!(
                "{}: the speed `{u}` is neither solved for by the rates' step nor a dependent speed \
                 (name a step `solve(constraints, [{u}, …])` as `dependent`)",
                d.path
            )),
        ));
    }
    // q' → f(q, u) with the dependent speeds replaced, and the dependent
    // speeds themselves: one pass, each value free of the atoms replaced.
    let dep = |p: &Poly| {
        p.subst(&mut |a| {
            dependent
                .iter()
                .find(|(x, _)| *x == a)
                .map(|(_, v)| v.clone())
        })
    };
    let coordinates: Vec<Atom> = kinematics.iter().map(|(q, _)| *q).collect();
    let qdot: Vec<Poly> = kinematics.iter().map(|(_, f)| dep(&d.unfold(f))).collect();
    let mut replace: Vec<(Atom, Poly)> = coordinates
        .iter()
        .zip(&qdot)
        .map(|(q, f)| {
            (
                q.derivative().expect("a coordinate is a function of time"),
                f.clone(),
            )
        })
        .collect();
    replace.extend(dependent.iter().cloned());
    let (nq, nu) = (coordinates.len(), speeds.len());
    // A multiplier form solves its system in the heap; the others on the
    // stack, up to MAX_DOF speeds.
    let most = if layout.is_some() { MAX_STATE } else { MAX_DOF };
    if nu > most || nq + nu > MAX_STATE {
        return Err(at(
            rates_field,
            err(format!(
                "{}: {nq} coordinates and {nu} speeds in the state; a first-order derived model of this \
                 form has at most {most} speeds and {MAX_STATE} components in all",
                d.path,
            )),
        ));
    }
    let outputs = match rates {
        SpeedRates::Explicit { .. } => qdot.into_iter().chain(rate_outputs).collect(),
        SpeedRates::MassMatrix { .. } | SpeedRates::Multiplier(_) => {
            rate_outputs.into_iter().chain(qdot).collect()
        }
    };
    Ok(FirstOrderEquations {
        coordinates,
        speeds,
        replace,
        outputs,
        layout,
    })
}

/// The dependent speeds of step `name` (`solve(constraints, [u4, u5])`),
/// each with its value in the coordinates and the other speeds.
fn dependent_speeds(d: &Derivation, name: &str) -> Result<Vec<(Atom, Poly)>, SimError> {
    let s = step(d, name)?;
    let speeds = d.speeds();
    let bad = || {
        err(format!(
            "{}: step `{name}` is {}, not dependent speeds solved for (write it as \
             solve(constraints, [u4, u5, …]) with generalized speeds in the brackets)",
            d.path,
            s.value.describe()
        ))
    };
    let Value::List { items, labels } = &s.value else {
        return Err(bad());
    };
    if labels.len() != items.len()
        || labels.is_empty()
        || labels.iter().any(|u| !speeds.contains(u))
    {
        return Err(bad());
    }
    let out: Vec<(Atom, Poly)> = labels
        .iter()
        .zip(items)
        .map(|(u, v)| (*u, d.unfold(v)))
        .collect();
    for (u, v) in &out {
        if let Some(a) = v.atoms().into_iter().find(|a| labels.contains(&a.base())) {
            return Err(err(format!(
                "{}: step `{name}` gives `{u}` in terms of the dependent speed `{a}`: each must be \
                 solved in the coordinates and the independent speeds",
                d.path
            )));
        }
    }
    Ok(out)
}

/// The independent speeds, in the order the rates' step solves for them,
/// and that step's outputs: the rates u̇ (explicit), or M (row-major) then
/// f. The dependent speeds are not among them.
fn speed_rates(
    d: &Derivation,
    rates: &SpeedRates,
    dependent: &[(Atom, Poly)],
) -> Result<(Vec<Atom>, Vec<Poly>), SimError> {
    let declared = d.speeds();
    let check = |name: &str, unknowns: &[Atom]| -> Result<Vec<Atom>, SimError> {
        let speeds: Vec<Atom> = unknowns.iter().map(|a| a.base()).collect();
        let want: Vec<String> = declared
            .iter()
            .filter(|u| !dependent.iter().any(|(x, _)| x == *u))
            .map(|u| format!("{u}'"))
            .collect();
        let bad = unknowns.iter().find(|a| {
            a.order() != 1
                || !declared.contains(&a.base())
                || dependent.iter().any(|(x, _)| *x == a.base())
        });
        if unknowns.is_empty() || bad.is_some() {
            return Err(err(format!(
                "{}: step `{name}` must be solved for the independent speeds' rates [{}]{}",
                d.path,
                want.join(", "),
                bad.map_or(String::new(), |a| format!(", not for `{a}`"))
            )));
        }
        Ok(speeds)
    };
    match rates {
        SpeedRates::Explicit { step: name } => {
            let s = step(d, name)?;
            let Value::List { items, labels } = &s.value else {
                return Err(err(format!(
                    "{}: step `{name}` is {}, not the speeds' rates solved for (write it as \
                     solve(eqs, [u1', u2', …]), or name a mass_matrix and forcing step)",
                    d.path,
                    s.value.describe()
                )));
            };
            if labels.len() != items.len() {
                return Err(err(format!(
                    "{}: step `{name}` is an unlabelled list, not the speeds' rates solved for \
                     (write it as solve(eqs, [u1', u2', …]))",
                    d.path
                )));
            }
            let speeds = check(name, labels)?;
            Ok((speeds, items.iter().map(|p| d.unfold(p)).collect()))
        }
        SpeedRates::MassMatrix {
            mass_matrix,
            forcing,
        } => {
            let unknowns = step_unknowns(d, mass_matrix).ok_or_else(|| {
                err(format!(
                    "{}: step `{mass_matrix}` is not written mass_matrix(eqs, [u1', u2', …]): a first-order \
                     mass-matrix form takes its speeds from the brackets",
                    d.path
                ))
            })?;
            let unknowns: Vec<Atom> = unknowns
                .iter()
                .map(|(name, primes)| Atom::time(name, *primes))
                .collect();
            let speeds = check(mass_matrix, &unknowns)?;
            let mf = mass_matrix_and_forcing(d, mass_matrix, forcing, speeds.len())?;
            Ok((speeds, mf.iter().map(|p| d.unfold(p)).collect()))
        }
        SpeedRates::Multiplier(_) => unreachable!("read by multiplier::outputs"),
    }
}

/// # First-order evaluation
impl DerivedModel {
    /// The rates `(q̇, u̇)` of a first-order state `y = (q, u)`; `None`
    /// when the mass matrix cannot be factorised there.
    pub(super) fn first_order_rates(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Option<()> {
        let (nq, nu) = (self.coordinates.len(), self.speeds.len());
        match &self.form {
            Form::Explicit(c) => {
                self.eval(c, t, y, &mut dy[..nq + nu]);
                Some(())
            }
            Form::MassMatrix(c, solve) => {
                // M, f and q̇ on the stack: no allocation.
                let mut buf = [0.0; MAX_DOF * MAX_DOF + 3 * MAX_DOF];
                let out = &mut buf[..nu * nu + nu + nq];
                self.eval(c, t, y, out);
                dy[..nq].copy_from_slice(&out[nu * nu + nu..]);
                solve.solve(&out[..nu * nu + nu], &mut dy[nq..nq + nu])
            }
            Form::Multiplier(c, l) => self.multiplier_rates(c, l, t, y, dy),
        }
    }
}
