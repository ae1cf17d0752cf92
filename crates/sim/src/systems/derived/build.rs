//! Building a [`DerivedModel`] from a derivation and a scene's spec: the
//! steps that hold the equations, the divisors that can vanish, the
//! conserved steps and the frames whose attitude can be evaluated.

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::{Derivation, Step, Value};
use hdot_sym::poly::Poly;
use hdot_sym::vector::Mat3;
use nalgebra::Vector3;

use super::compile::{Resolver, Source};
use super::symmetric_solve::MassSolve;
use super::{
    Conserved, DIVISOR_BOUND, DerivedModel, DerivedSpec, Divisor, EquationsSpec, Form,
    FrameAttitude, FrameChain, MAX_DOF, MAX_STATE, SpeedRates, TimeFunction, at, carried,
    energy_reason, err, first_order, holonomic, in_steps,
};
use crate::SimError;

/// # Construction
impl DerivedModel {
    /// Compiles the equations `spec` names in `d`.
    pub fn new(d: &Derivation, spec: &DerivedSpec) -> Result<DerivedModel, SimError> {
        // The field that names the equations, and their steps.
        let (field, steps) = match &spec.equations {
            EquationsSpec::Explicit { step } => ("derivation.accelerations", vec![step.as_str()]),
            EquationsSpec::MassMatrix {
                mass_matrix,
                forcing,
                ..
            }
            | EquationsSpec::FirstOrder {
                rates:
                    SpeedRates::MassMatrix {
                        mass_matrix,
                        forcing,
                    },
                ..
            } => (
                "derivation.mass_matrix",
                vec![mass_matrix.as_str(), forcing.as_str()],
            ),
            EquationsSpec::FirstOrder {
                rates: SpeedRates::Explicit { step },
                ..
            } => ("derivation.rates", vec![step.as_str()]),
            EquationsSpec::FirstOrder {
                rates: SpeedRates::Multiplier(m),
                ..
            } => (
                "derivation.constraint_matrix",
                vec![
                    m.mass_matrix.as_str(),
                    m.forcing.as_str(),
                    m.constraint_matrix.as_str(),
                    m.constraint_bias.as_str(),
                ],
            ),
        };
        let (coordinates, speeds, mut replace, outputs, layout) = match &spec.equations {
            EquationsSpec::FirstOrder {
                rates, dependent, ..
            } => {
                let e = first_order::equations(d, rates, dependent.as_deref())?;
                (e.coordinates, e.speeds, e.replace, e.outputs, e.layout)
            }
            e => {
                let (q, out) = equations(d, e).map_err(|e| at(field, e))?;
                (q, Vec::new(), Vec::new(), out, None)
            }
        };
        if layout.is_some() && !spec.inputs.is_empty() {
            return Err(at(
                field,
                err(format!(
                    "{}: a multiplier form with applied inputs is not simulated (its constraints are \
                     kept after each step, where the time is not known): remove the scene's [inputs]",
                    d.path
                )),
            ));
        }
        let n = coordinates.len();
        if n == 0 || (speeds.is_empty() && n > MAX_DOF) {
            let field = match &spec.equations {
                EquationsSpec::MassMatrix { .. } => "derivation.coordinates",
                _ => field,
            };
            return Err(at(
                field,
                err(format!(
                    "{}: {n} coordinates; a derived model has 1 to {MAX_DOF}",
                    d.path
                )),
            ));
        }
        let inputs: Vec<(String, TimeFunction)> = spec
            .inputs
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        // Angles a [motion] rule's rate ties to the state, carried after
        // it; their rates replace theirs wherever they occur.
        let input_names: Vec<&str> = inputs.iter().map(|(k, _)| k.as_str()).collect();
        let carried = carried::carried_angles(d, &coordinates, &speeds, &input_names);
        let carried_base = if speeds.is_empty() {
            2 * n
        } else {
            n + speeds.len()
        };
        let carried_rates: Vec<Poly> = {
            let cx = Resolver {
                d,
                spec,
                coordinates: &coordinates,
                speeds: &speeds,
                replace: &replace,
                carried: &[],
                carried_base,
                inputs: &inputs,
            };
            carried.iter().map(|(_, rate)| cx.replaced(rate)).collect()
        };
        if carried_base + carried.len() > MAX_STATE {
            return Err(at(
                field,
                err(format!(
                    "{}: a state of {} components with the angles its [motion] rules carry; a derived \
                     model has at most {}",
                    d.path,
                    carried_base + carried.len(),
                    MAX_STATE
                )),
            ));
        }
        replace.extend(
            carried
                .iter()
                .zip(&carried_rates)
                .map(|((a, _), v)| (a.derivative().expect("a time symbol"), v.clone())),
        );
        let carried: Vec<Atom> = carried.into_iter().map(|(a, _)| a).collect();
        let cx = Resolver {
            d,
            spec,
            coordinates: &coordinates,
            speeds: &speeds,
            replace: &replace,
            carried: &carried,
            carried_base,
            inputs: &inputs,
        };
        let polys = unfold(d, &outputs);
        let replaced: Vec<Poly> = polys.iter().map(|p| cx.replaced(p)).collect();
        let (divisors, singular) = divisors(&replaced, spec, &coordinates);
        let compiled = cx.compile(&polys).map_err(|e| in_steps(&steps, e))?;
        let form = match &spec.equations {
            EquationsSpec::Explicit { .. }
            | EquationsSpec::FirstOrder {
                rates: SpeedRates::Explicit { .. },
                ..
            } => Form::Explicit(compiled),
            _ => match layout {
                Some(l) => Form::Multiplier(compiled, l),
                None => {
                    // M is over the speeds' rates in a first-order model.
                    let m = if speeds.is_empty() { n } else { speeds.len() };
                    Form::MassMatrix(compiled, MassSolve::plan(m, &replaced))
                }
            },
        };
        let conserved = conserved(d, spec, &cx)?;
        let holonomic = match &spec.equations {
            EquationsSpec::FirstOrder {
                holonomic: Some(h), ..
            } => Some(holonomic::compile(d, h, &cx)?),
            _ => None,
        };
        let frames = frames(d, &cx);
        let (placements, gravity) = super::positions::compile(d, &cx);
        let carried_rates = if carried.is_empty() {
            None
        } else {
            Some(cx.compile(&carried_rates).map_err(|e| at(field, e))?)
        };
        let unit_norms = super::unit_norm::UnitNorms::of(d, &coordinates);
        let mut model = DerivedModel {
            coordinates,
            speeds,
            carried,
            carried_rates,
            plain_state: 0,
            form,
            inputs,
            divisors,
            singular,
            conserved,
            holonomic,
            unit_norms,
            frames,
            placements,
            gravity,
        };
        model.plain_state = model.plain_state_of();
        Ok(model)
    }
}

/// The polynomials with the derivation's abbreviations expanded.
fn unfold(d: &Derivation, v: &[Poly]) -> Vec<Poly> {
    v.iter().map(|p| d.unfold(p)).collect()
}

/// The step called `name`, or an error listing the steps.
pub(super) fn step<'d>(d: &'d Derivation, name: &str) -> Result<&'d Step, SimError> {
    d.steps.iter().find(|s| s.name == name).ok_or_else(|| {
        err(format!(
            "{}: no step named `{name}` (steps: {})",
            d.path,
            d.steps
                .iter()
                .map(|s| s.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ))
    })
}

/// The coordinates and the outputs of one tape: q̈, or M (row-major) then
/// f (one tape, so that the two share their inputs, sines and products).
fn equations(d: &Derivation, spec: &EquationsSpec) -> Result<(Vec<Atom>, Vec<Poly>), SimError> {
    let step = |name: &str| step(d, name);
    Ok(match spec {
        EquationsSpec::Explicit { step: name } => {
            let s = step(name)?;
            let Value::List { items, labels } = &s.value else {
                return Err(err(format!(
                    "{}: step `{name}` is {}, not accelerations solved for (write it as solve(eqs, [q1'', q2'', …]), \
                         or name a mass_matrix and forcing step)",
                    d.path,
                    s.value.describe()
                )));
            };
            if labels.len() != items.len()
                || labels
                    .iter()
                    .any(|a| a.order() != 2 || !a.is_time_dependent())
            {
                return Err(err(format!(
                    "{}: step `{name}` must be solved for second derivatives of time symbols ([q1'', q2'', …])",
                    d.path
                )));
            }
            (labels.iter().map(|a| a.base()).collect(), items.clone())
        }
        EquationsSpec::MassMatrix {
            mass_matrix,
            forcing,
            coordinates,
        } => {
            let mf = mass_matrix_and_forcing(d, mass_matrix, forcing, coordinates.len())?;
            let coords = coordinates
                .iter()
                .map(|c| match d.symbols.get(c) {
                    Some(hdot_sym::Decl::Time) => Ok(Atom::time(c, 0)),
                    _ => Err(at(
                        "derivation.coordinates",
                        err(format!(
                            "{}: `{c}` is not a time symbol of the derivation",
                            d.path
                        )),
                    )),
                })
                .collect::<Result<Vec<_>, _>>()?;
            (coords, mf)
        }
        EquationsSpec::FirstOrder { .. } => {
            unreachable!("a first-order form is read by first_order.rs")
        }
    })
}

/// The entries of an n × n mass matrix (step `mass_matrix`, row-major)
/// followed by the n items of the forcing (step `forcing`): the outputs
/// of one tape, so that the two share their inputs, sines and products.
pub(super) fn mass_matrix_and_forcing(
    d: &Derivation,
    mass_matrix: &str,
    forcing: &str,
    n: usize,
) -> Result<Vec<Poly>, SimError> {
    let sm = step(d, mass_matrix)?;
    let sf = step(d, forcing).map_err(|e| at("derivation.forcing", e))?;
    let m = match &sm.value {
        Value::Array(rows) if rows.len() == n && rows.iter().all(|r| r.len() == n) => {
            rows.iter().flatten().cloned().collect::<Vec<_>>()
        }
        Value::Matrix(m) if n == 3 => m.0.iter().flatten().cloned().collect(),
        v => {
            return Err(err(format!(
                "{}: step `{mass_matrix}` is {}, not an {n}×{n} mass matrix",
                d.path,
                v.describe()
            )));
        }
    };
    let f = match &sf.value {
        Value::List { items, .. } if items.len() == n => items.clone(),
        Value::Vector(v, _) if n == 3 => v.0.to_vec(),
        v => {
            return Err(at(
                "derivation.forcing",
                err(format!(
                    "{}: step `{forcing}` is {}, not a forcing list of {n}",
                    d.path,
                    v.describe()
                )),
            ));
        }
    };
    Ok(m.into_iter().chain(f).collect())
}

/// The sines and cosines of coordinates the equations divide by, and the
/// constants whose value makes them singular whatever the state.
fn divisors(
    polys: &[Poly],
    spec: &DerivedSpec,
    coordinates: &[Atom],
) -> (Vec<Divisor>, Vec<(String, String)>) {
    let mut divisors = Vec::new();
    let mut singular = Vec::new();
    for p in polys {
        for (m, _) in p.terms() {
            for &(a, e) in m.factors() {
                if e >= 0 {
                    continue;
                }
                // A constant the equations divide by: zero (or an
                // angle whose sine or cosine is below the divisor
                // bound) makes them singular whatever the state.
                if let AtomKind::Var { time: false, .. } = a.kind()
                    && spec.constants.get(a.name()) == Some(&0.0)
                    && !singular.iter().any(|(n, _)| n == a.name())
                {
                    singular.push((
                        a.name().to_string(),
                        format!("the equations divide by the constant `{a}`, and it is 0"),
                    ));
                }
                let (q, sin) = match a.kind() {
                    AtomKind::Sin(q) => (q, true),
                    AtomKind::Cos(q) => (q, false),
                    _ => continue,
                };
                if !q.is_time_dependent()
                    && let Some(&v) = spec.constants.get(q.name())
                    && !singular.iter().any(|(n, _)| n == q.name())
                {
                    let (f, value) = if sin {
                        ("sin", v.sin())
                    } else {
                        ("cos", v.cos())
                    };
                    if value.abs() < DIVISOR_BOUND {
                        singular.push((
                                q.name().to_string(),
                                format!(
                                    "the equations divide by {f}({q}), and with the constant `{q}` = {v} it is {value:.3e}: \
                                     they are singular for every state (choose another value of `{q}`, or derive the \
                                     equations for this case)"
                                ),
                            ));
                    }
                }
                if let Some(i) = coordinates.iter().position(|&c| c == q) {
                    let dv = Divisor { coordinate: i, sin };
                    if !divisors.contains(&dv) {
                        divisors.push(dv);
                    }
                }
            }
        }
    }
    (divisors, singular)
}

/// The steps whose values are reported as drifts: those the derivation
/// marks `conserved = true`, then those the scene adds.
fn conserved(
    d: &Derivation,
    spec: &DerivedSpec,
    cx: &Resolver<'_>,
) -> Result<Vec<Conserved>, SimError> {
    let mut conserved = Vec::new();
    let mut names: Vec<&String> = d
        .steps
        .iter()
        .filter(|s| s.conserved)
        .map(|s| &s.name)
        .collect();
    for name in &spec.conserved {
        if !names.contains(&name) {
            names.push(name);
        }
    }
    for name in names {
        let s = step(d, name).map_err(|e| at("derivation.conserved", e))?;
        let polys = unfold(d, &s.values().into_iter().cloned().collect::<Vec<_>>());
        conserved.push(Conserved {
            name: name.clone(),
            energy: energy_reason(s),
            compiled: cx.compile(&polys).map_err(|e| in_steps(&[name], e))?,
        });
    }
    Ok(conserved)
}

/// The derivation's frames, each with its motion or why its attitude
/// cannot be evaluated. A frame's attitude is evaluated when it is a
/// function of the coordinates and inputs (a chain of rotations), or when
/// the frame is given by a constant angular velocity (turned by
/// exp(t [ω]×) from N, with which it coincides at t = 0).
fn frames(d: &Derivation, cx: &Resolver<'_>) -> Vec<(String, Result<FrameChain, String>)> {
    d
            .frames
            .iter()
            .map(|f| {
                let omega: Vec<Poly> = f.omega.0.iter().map(|p| d.unfold(p)).collect();
                let chain = (|| {
                    let omega = cx.compile(&omega).map_err(|e| e.to_string())?;
                    let attitude = match &f.parent {
                        Some((p, r)) => FrameAttitude::Rotation {
                            parent: d.frames.iter().position(|g| &g.name == p),
                            rotation: Box::new(
                                cx.compile(&r.0.iter().flatten().cloned().collect::<Vec<_>>())
                                    .map_err(|e| e.to_string())?,
                            ),
                        },
                        None if f.omega.0.iter().all(|p| p.is_zero()) => FrameAttitude::Rotation {
                            parent: None,
                            rotation: Box::new(
                                cx.compile(&Mat3::identity().0.iter().flatten().cloned().collect::<Vec<_>>())
                                    .map_err(|e| e.to_string())?,
                            ),
                        },
                        None if omega.sources.iter().all(|s| matches!(s, Source::Value(_))) => {
                            let mut w = [0.0; 3];
                            let mut buf = vec![0.0; omega.tape.slots()];
                            omega.tape.eval_slots(&mut buf, &mut w, false);
                            FrameAttitude::Spin(Vector3::from(w))
                        }
                        None => {
                            return Err(format!(
                                "it is given by its angular velocity, which is not constant ({}), not by a rotation: \
                                 its attitude is not a function of the coordinates",
                                f.omega.0.iter().map(|p| p.to_string()).collect::<Vec<_>>().join(", ")
                            ));
                        }
                    };
                    Ok(FrameChain { attitude, omega })
                })();
                (f.name.clone(), chain)
            })
            .collect()
}

/// The coordinates a step `mass_matrix(eqs, [q1'', q2'', …])` (or
/// `forcing(…)`) was written for, in the order of its columns: `None`
/// when the step's formula is not such a call with second derivatives in
/// brackets.
pub fn step_coordinates(d: &Derivation, step: &str) -> Option<Vec<String>> {
    let unknowns = step_unknowns(d, step)?;
    unknowns
        .into_iter()
        .map(|(name, primes)| (primes == 2).then_some(name))
        .collect()
}

/// The unknowns of a step `mass_matrix(eqs, [x1', x2'', …])` (or
/// `forcing(…)`): each name and its number of primes, in the order of the
/// columns; `None` when the step's formula is not such a call with its
/// unknowns in brackets.
pub(super) fn step_unknowns(d: &Derivation, step: &str) -> Option<Vec<(String, u32)>> {
    let names = bracket_names(d, step, &["mass_matrix", "forcing"])?;
    names
        .into_iter()
        .map(|(n, p)| (p > 0).then_some((n, p)))
        .collect()
}

/// The names in the bracket of a step written `f(x, [a, b', …])` with `f`
/// one of `funcs`: each name with its number of primes, in order; `None`
/// when the step's formula is not such a call or an item is not a name.
pub(super) fn bracket_names(
    d: &Derivation,
    step: &str,
    funcs: &[&str],
) -> Option<Vec<(String, u32)>> {
    use hdot_sym::parse::{AstKind, parse};
    let s = d.steps.iter().find(|s| s.name == step)?;
    let ast = parse(&s.formula).ok()?;
    let AstKind::Call { func, args } = &ast.kind else {
        return None;
    };
    if !funcs.contains(&func.as_str()) || args.len() != 2 {
        return None;
    }
    let AstKind::Vector { items, frame: None } = &args[1].kind else {
        return None;
    };
    items
        .iter()
        .map(|a| match &a.kind {
            AstKind::Name { name, primes } => Some((name.clone(), *primes)),
            _ => None,
        })
        .collect()
}

/// Whether a step `mass_matrix(eqs, [u1', …])` is written for the rates
/// of generalized speeds (a first-order mass-matrix form).
pub fn in_speed_rates(d: &Derivation, step: &str) -> bool {
    let speeds = d.speeds();
    step_unknowns(d, step).is_some_and(|u| {
        !u.is_empty()
            && u.iter()
                .all(|(name, primes)| *primes == 1 && speeds.contains(&Atom::time(name, 0)))
    })
}
