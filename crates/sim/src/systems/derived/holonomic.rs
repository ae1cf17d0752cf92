//! Configuration (holonomic) constraints f(q) = 0 of a first-order model,
//! with their dependent coordinates q_d: solved by Newton's method at the
//! initial state from the scene's guess (the Jacobian ∂f/∂q_d compiled
//! from the derivation), monitored along the run (max |f(q)|), and — by
//! default — kept by projecting q_d back onto f = 0 after every step.
//!
//! The integrator carries q_d with the rate the derivation gives it (a
//! dependent speed the constraint's rate ḟ = 0 determines: implicit
//! differentiation), so f stays zero up to the integration error; the
//! projection removes that drift, coordinate by coordinate (the
//! independent coordinates and the speeds are left as the step made
//! them, so the velocity constraints keep holding).

use std::cell::Cell;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::poly::Poly;
use nalgebra::DMatrix;

use super::build::step;
use super::compile::{Compiled, Resolver, Source};
use super::small_solve::solve_small;
use super::{DerivedModel, HolonomicSpec, MAX_DOF, at, err};
use crate::SimError;

/// The largest number of Newton iterations, at the start and per step.
const MAX_NEWTON: usize = 50;

/// The compiled constraints of a model.
#[derive(Debug)]
pub(super) struct Holonomic {
    /// The steps holding f, as the scene names them.
    pub(super) steps: Vec<String>,
    /// The index of each dependent coordinate in the state.
    pub(super) dependent: Vec<usize>,
    /// One tape: f (m values), then ∂f/∂q_d (m × m, row-major), then
    /// ∂f/∂q (m × n, every coordinate).
    pub(super) tape: Compiled,
    /// Whether q_d is projected back onto f = 0 after each step.
    pub(super) project: bool,
    /// What the run met since the last reset.
    pub(super) monitor: Cell<ConstraintMonitor>,
}

/// What the constraints met along a run: the largest |f(q)| after each
/// step (after the projection, when there is one) and the largest
/// correction the projection made to a dependent coordinate.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ConstraintMonitor {
    /// max over the accepted steps of max_i |f_i(q)|.
    pub max_residual: f64,
    /// max over the accepted steps of max_i |Δq_d,i| (0 without projection).
    pub max_correction: f64,
}

/// Why Newton's method found no q_d with f(q) = 0.
#[derive(Debug, Clone, PartialEq)]
pub enum NewtonFailure {
    /// ∂f/∂q_d is singular at the iterate.
    Singular {
        /// The dependent coordinates' values there.
        at: Vec<f64>,
    },
    /// The iteration did not converge (or left the finite numbers).
    NoConvergence {
        /// The largest |f| at the last iterate.
        residual: f64,
    },
}

/// Compiles the constraints `spec` names: each step's components are f,
/// free of the speeds and rates; as many as the dependent coordinates,
/// which must be coordinates of the state.
pub(super) fn compile(
    d: &Derivation,
    spec: &HolonomicSpec,
    cx: &Resolver<'_>,
) -> Result<Holonomic, SimError> {
    let speeds = d.speeds();
    let mut f: Vec<Poly> = Vec::new();
    for name in &spec.steps {
        let s = step(d, name).map_err(|e| at("derivation.holonomic", e))?;
        for p in s.values() {
            let p = d.unfold(p);
            if let Some(a) = p.atoms().into_iter().find(|a| moves(*a, speeds)) {
                return Err(at(
                    "derivation.holonomic",
                    err(format!(
                        "{}: step `{name}` has `{a}`: a configuration constraint f(q) = 0 is in the \
                         coordinates (and constants) only",
                        d.path
                    )),
                ));
            }
            f.push(p);
        }
    }
    let mut dependent = Vec::new();
    let mut qd = Vec::new();
    for name in &spec.dependent {
        let q = Atom::time(name, 0);
        let Some(i) = cx.coordinates.iter().position(|&c| c == q) else {
            return Err(at(
                "derivation.dependent_coordinates",
                err(format!(
                    "{}: `{name}` is not a coordinate of the state ({})",
                    d.path,
                    cx.coordinates
                        .iter()
                        .map(|c| c.name())
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            ));
        };
        if dependent.contains(&i) {
            return Err(at(
                "derivation.dependent_coordinates",
                err(format!("`{name}` is listed twice")),
            ));
        }
        dependent.push(i);
        qd.push(q);
    }
    let m = f.len();
    if m == 0 || m != qd.len() || m > MAX_DOF {
        return Err(at(
            "derivation.dependent_coordinates",
            err(format!(
                "{}: {m} configuration constraint(s) in step(s) {} and {} dependent coordinate(s): \
                 give one dependent coordinate per constraint (at most {MAX_DOF})",
                d.path,
                spec.steps
                    .iter()
                    .map(|s| format!("`{s}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                qd.len()
            )),
        ));
    }
    // f, then ∂f/∂q_d, then ∂f/∂q (every coordinate: the scale against
    // which ∂f/∂q_d is singular).
    let mut outputs = f.clone();
    for fi in &f {
        for &q in &qd {
            outputs.push(fi.partial(q));
        }
    }
    for fi in &f {
        for &q in cx.coordinates {
            outputs.push(fi.partial(q));
        }
    }
    let tape = cx
        .compile(&outputs)
        .map_err(|e| at("derivation.holonomic", e))?;
    if tape.sources.iter().any(|s| {
        matches!(
            s,
            Source::Input(_) | Source::SinInput(_) | Source::CosInput(_)
        )
    }) {
        return Err(at(
            "derivation.holonomic",
            err(format!(
                "{}: the constraints in step(s) {} depend on an applied input (a function of t): \
                 only constraints f(q) = 0 in the coordinates are kept",
                d.path,
                spec.steps.join(", ")
            )),
        ));
    }
    Ok(Holonomic {
        steps: spec.steps.clone(),
        dependent,
        tape,
        project: spec.project,
        monitor: Cell::new(ConstraintMonitor::default()),
    })
}

/// Whether `a` is a speed or a rate (what a configuration constraint must
/// not have).
fn moves(a: Atom, speeds: &[Atom]) -> bool {
    match a.kind() {
        AtomKind::Var {
            order, time: true, ..
        } => order > 0 || speeds.contains(&a),
        AtomKind::Var { .. } | AtomKind::Sin(_) | AtomKind::Cos(_) | AtomKind::Sum { .. } => false,
    }
}

/// # Configuration constraints
impl DerivedModel {
    /// The steps of the configuration constraints and their dependent
    /// coordinates' names, when the scene declares any.
    pub fn holonomic(&self) -> Option<(Vec<String>, Vec<String>)> {
        self.holonomic.as_ref().map(|h| {
            (
                h.steps.clone(),
                h.dependent
                    .iter()
                    .map(|&i| self.coordinates[i].name().to_string())
                    .collect(),
            )
        })
    }

    /// Whether the dependent coordinates are projected onto f = 0 after
    /// each step.
    pub fn projects(&self) -> bool {
        self.holonomic.as_ref().is_some_and(|h| h.project)
    }

    /// The values of the constraints f(q) at `(t, y)` (empty without).
    pub fn constraint_residual(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let Some(h) = &self.holonomic else {
            return Vec::new();
        };
        let m = h.dependent.len();
        let mut out = vec![0.0; h.tape.tape.outputs()];
        self.eval(&h.tape, t, y, &mut out);
        out.truncate(m);
        out
    }

    /// Newton's method on the dependent coordinates of `y` (the others
    /// held) until f(q) = 0 to round-off: the number of iterations, and
    /// the largest correction made to a dependent coordinate. With
    /// `strict`, ∂f/∂q_d is singular when its smallest singular value is
    /// below 1e-12 of the largest of ∂f/∂q (q_d cannot be solved for
    /// there, though the pivot is not exactly zero); otherwise only an
    /// exactly zero pivot is.
    pub fn solve_constraints(
        &self,
        t: f64,
        y: &mut [f64],
        strict: bool,
    ) -> Result<(usize, f64), NewtonFailure> {
        let Some(h) = &self.holonomic else {
            return Ok((0, 0.0));
        };
        let m = h.dependent.len();
        let n = self.coordinates.len();
        let mut buf = [0.0; MAX_DOF + MAX_DOF * MAX_DOF + 2 * MAX_DOF * MAX_DOF];
        let mut mf = [0.0; MAX_DOF * MAX_DOF + MAX_DOF];
        let mut dq = [0.0; MAX_DOF];
        let start: Vec<f64> = h.dependent.iter().map(|&i| y[i]).collect();
        let mut last = f64::INFINITY;
        for k in 0..=MAX_NEWTON {
            let out = &mut buf[..m + m * m + m * n];
            self.eval(&h.tape, t, y, out);
            let residual = out[..m].iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            if !residual.is_finite() {
                break;
            }
            if residual == 0.0 {
                return Ok((k, correction(h, y, &start)));
            }
            // Converged: the step is at the round-off of the coordinates.
            if k > 0 && last <= 4.0 * f64::EPSILON {
                return Ok((k, correction(h, y, &start)));
            }
            if k == MAX_NEWTON {
                return Err(NewtonFailure::NoConvergence { residual });
            }
            if strict && singular(m, n, &out[m..]) {
                return Err(NewtonFailure::Singular {
                    at: h.dependent.iter().map(|&i| y[i]).collect(),
                });
            }
            mf[..m * m].copy_from_slice(&out[m..m + m * m]);
            mf[m * m..m * m + m].copy_from_slice(&out[..m]);
            let regular = solve_small(m, &mf[..m * m + m], &mut dq[..m]).is_some()
                && dq[..m].iter().all(|v| v.is_finite());
            if !regular {
                return Err(NewtonFailure::Singular {
                    at: h.dependent.iter().map(|&i| y[i]).collect(),
                });
            }
            last = 0.0;
            for (j, &i) in h.dependent.iter().enumerate() {
                y[i] -= dq[j];
                last = last.max(dq[j].abs() / y[i].abs().max(1.0));
            }
        }
        let out = &mut buf[..m + m * m + m * n];
        self.eval(&h.tape, t, y, out);
        Err(NewtonFailure::NoConvergence {
            residual: out[..m].iter().fold(0.0_f64, |a, v| a.max(v.abs())),
        })
    }

    /// The constraints' rate ḟ = (∂f/∂q) q̇ at `y` with its speeds
    /// replaced by `speeds` (the state's own independent speeds held
    /// elsewhere): the largest |ḟ_i| and the scale Σ_j |∂f_i/∂q_j q̇_j| it
    /// is measured against; `None` when the rates cannot be evaluated.
    /// It vanishes when the dependent speeds come from the constraints'
    /// rates (implicit differentiation), whatever the speeds.
    pub fn constraint_rate(&self, t: f64, y: &[f64], speeds: &[f64]) -> Option<(f64, f64)> {
        let h = self.holonomic.as_ref()?;
        let (m, n) = (h.dependent.len(), self.coordinates.len());
        let mut z = y.to_vec();
        z[n..n + speeds.len()].copy_from_slice(speeds);
        // A multiplier form's dependent speeds from its velocity constraints.
        self.solve_dependent_speeds(t, &mut z)?;
        let mut dz = vec![0.0; z.len()];
        self.rates(t, &z, &mut dz)?;
        let mut out = vec![0.0; h.tape.tape.outputs()];
        self.eval(&h.tape, t, &z, &mut out);
        let jac = &out[m + m * m..];
        let (mut rate, mut scale) = (0.0_f64, 0.0_f64);
        for i in 0..m {
            let terms = (0..n).map(|j| jac[i * n + j] * dz[j]);
            rate = rate.max(terms.clone().sum::<f64>().abs());
            scale = scale.max(terms.map(f64::abs).sum::<f64>());
        }
        Some((rate, scale))
    }

    /// Starts a new record of the constraints' residual and corrections.
    pub fn reset_constraint_monitor(&self) {
        if let Some(h) = &self.holonomic {
            h.monitor.set(ConstraintMonitor::default());
        }
    }

    /// What the constraints met since the last reset (`None` without
    /// constraints).
    pub fn constraint_monitor(&self) -> Option<ConstraintMonitor> {
        self.holonomic.as_ref().map(|h| h.monitor.get())
    }

    /// After an accepted step: projects q_d onto f = 0 (when asked) and
    /// records the residual and the correction. Returns whether `y`
    /// changed. A projection that fails leaves `y` as the step made it
    /// (the residual recorded says how far off it is).
    pub(super) fn keep_constraints(&self, t: f64, y: &mut [f64]) -> bool {
        let Some(h) = &self.holonomic else {
            return false;
        };
        let mut rec = h.monitor.get();
        let mut changed = false;
        if h.project {
            let before: Vec<f64> = h.dependent.iter().map(|&i| y[i]).collect();
            match self.solve_constraints(t, y, false) {
                Ok((_, c)) => {
                    rec.max_correction = rec.max_correction.max(c);
                    changed = c > 0.0;
                }
                Err(_) => {
                    for (&i, v) in h.dependent.iter().zip(before) {
                        y[i] = v;
                    }
                }
            }
        }
        let r = self
            .constraint_residual(t, y)
            .iter()
            .fold(0.0_f64, |a, v| a.max(v.abs()));
        rec.max_residual = rec.max_residual.max(r);
        h.monitor.set(rec);
        changed
    }
}

/// The largest change of a dependent coordinate from `start`.
fn correction(h: &Holonomic, y: &[f64], start: &[f64]) -> f64 {
    h.dependent
        .iter()
        .zip(start)
        .fold(0.0_f64, |a, (&i, s)| a.max((y[i] - s).abs()))
}

/// Whether ∂f/∂q_d (`jac`'s first m × m entries) is singular against
/// ∂f/∂q (the m × n entries after them).
fn singular(m: usize, n: usize, jac: &[f64]) -> bool {
    let jd = DMatrix::from_row_slice(m, m, &jac[..m * m]).singular_values();
    let ja = DMatrix::from_row_slice(m, n, &jac[m * m..m * m + m * n]).singular_values();
    let (lo, hi) = (jd.min(), ja.max());
    lo.is_nan() || hi.is_nan() || lo <= 1e-12 * hi
}
