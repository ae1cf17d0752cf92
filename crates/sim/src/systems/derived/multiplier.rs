//! The multiplier form of a first-order model: Kane's equations in every
//! speed before the constraints, M u̇ − f = A_cᵀ λ, with the velocity
//! constraints A_c u = 0 and their rates A_c u̇ + b = 0. Each evaluation
//! solves the augmented linear system
//! [[M, −A_cᵀ], [A_c, 0]] [u̇; λ] = [f; −b] (an LU factorisation); the
//! dependent speeds the scene names are solved from A_c u = 0 at the start
//! and after every step (the independent ones held), so the velocity
//! constraints keep holding to round-off.
//!
//! A speed the mass matrix does not list (one that moves no body, like the
//! bicycle's χ̇) has a zero row and column in M: its rate comes from the
//! constraints alone.

use std::cell::Cell;

use hdot_sym::atom::Atom;
use hdot_sym::derivation::{Derivation, Value};
use hdot_sym::poly::Poly;
use nalgebra::{DMatrix, DVector};

use super::build::{bracket_names, mass_matrix_and_forcing, step, step_unknowns};
use super::compile::Compiled;
use super::{DerivedModel, Form, at, err};
use crate::SimError;

/// Where the outputs of a multiplier form's tape go.
#[derive(Debug, Clone)]
pub(super) struct Layout {
    /// The state index (among the speeds) of each column of M.
    pub(super) mass: Vec<usize>,
    /// The number of velocity constraints (rows of A_c).
    pub(super) rows: usize,
    /// The state index (among the speeds) of each dependent speed.
    pub(super) dependent: Vec<usize>,
    /// What the velocity constraints met since the last reset.
    pub(super) monitor: Cell<VelocityMonitor>,
}

/// What the velocity constraints A_c u = 0 met along a run: the largest
/// |A_c u| after each step's solve of the dependent speeds, and the
/// largest change that solve made to a dependent speed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct VelocityMonitor {
    /// max over the start and the accepted steps of max_i |(A_c u)_i|.
    pub max_residual: f64,
    /// max over the accepted steps of max_i |Δu_d,i|.
    pub max_correction: f64,
}

/// The steps of a multiplier form, as the scene names them.
#[derive(Debug, Clone, PartialEq)]
pub struct MultiplierSpec {
    /// The step `mass_matrix(eqs, [u1', …])` (a subset of the speeds).
    pub mass_matrix: String,
    /// The step `forcing(eqs, [u1', …])`.
    pub forcing: String,
    /// The step `jacobian(constraints, [u1, u2, …])`: A_c, its columns
    /// every speed (the state's order).
    pub constraint_matrix: String,
    /// The step holding b, the constraints' rates with u̇ = 0.
    pub constraint_bias: String,
    /// The speeds solved from A_c u = 0, one per constraint.
    pub dependent_speeds: Vec<String>,
}

/// The speeds (the columns of A_c, in order), the tape's outputs
/// M, f, A_c (row-major) and b, and their layout.
pub(super) fn outputs(
    d: &Derivation,
    spec: &MultiplierSpec,
) -> Result<(Vec<Atom>, Vec<Poly>, Layout), SimError> {
    let field = "derivation.constraint_matrix";
    let declared = d.speeds();
    let columns = jacobian_columns(d, &spec.constraint_matrix)
        .filter(|c| !c.is_empty() && c.iter().all(|u| declared.contains(u)))
        .ok_or_else(|| {
            at(
                field,
                err(format!(
                    "{}: step `{}` is not written jacobian(constraints, [u1, u2, …]) in the generalized \
                     speeds: the multiplier form takes the state's speeds from its brackets",
                    d.path, spec.constraint_matrix
                )),
            )
        })?;
    let n = columns.len();
    let unknowns = step_unknowns(d, &spec.mass_matrix).unwrap_or_default();
    let mass: Vec<usize> = unknowns
        .iter()
        .filter(|(_, primes)| *primes == 1)
        .filter_map(|(name, _)| columns.iter().position(|u| *u == Atom::time(name, 0)))
        .collect();
    if mass.is_empty() || mass.len() != unknowns.len() {
        return Err(at(
            "derivation.mass_matrix",
            err(format!(
                "{}: step `{}` must be written mass_matrix(eqs, [u1', …]) in rates of the speeds of \
                 `{}` ({})",
                d.path,
                spec.mass_matrix,
                spec.constraint_matrix,
                columns
                    .iter()
                    .map(|u| u.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        ));
    }
    let mf = mass_matrix_and_forcing(d, &spec.mass_matrix, &spec.forcing, mass.len())
        .map_err(|e| at("derivation.mass_matrix", e))?;
    let a = step(d, &spec.constraint_matrix).map_err(|e| at(field, e))?;
    let Value::Array(rows) = &a.value else {
        return Err(at(
            field,
            err(format!(
                "{}: step `{}` is {}, not a constraint matrix (rows × {n} speeds)",
                d.path,
                spec.constraint_matrix,
                a.value.describe()
            )),
        ));
    };
    if rows.is_empty() || rows.len() >= n || rows.iter().any(|r| r.len() != n) {
        return Err(at(
            field,
            err(format!(
                "{}: step `{}` has {} row(s) of {} column(s); a constraint matrix has fewer rows than \
                 its {n} speeds, each row of {n}",
                d.path,
                spec.constraint_matrix,
                rows.len(),
                rows.first().map_or(0, Vec::len)
            )),
        ));
    }
    let m = rows.len();
    let bfield = "derivation.constraint_bias";
    let b = step(d, &spec.constraint_bias).map_err(|e| at(bfield, e))?;
    let bias: Vec<Poly> = match &b.value {
        Value::List { items, .. } if items.len() == m => items.clone(),
        Value::Vector(v, _) if m == 3 => v.0.to_vec(),
        Value::Scalar(p) if m == 1 => vec![p.clone()],
        v => {
            return Err(at(
                bfield,
                err(format!(
                    "{}: step `{}` is {}, not the constraints' {m} bias terms (A_c u̇ + b = 0)",
                    d.path,
                    spec.constraint_bias,
                    v.describe()
                )),
            ));
        }
    };
    let dfield = "derivation.dependent_speeds";
    let mut dependent = Vec::new();
    for name in &spec.dependent_speeds {
        let Some(i) = columns.iter().position(|u| u.name() == name) else {
            return Err(at(
                dfield,
                err(format!(
                    "{}: `{name}` is not a speed of `{}`",
                    d.path, spec.constraint_matrix
                )),
            ));
        };
        if dependent.contains(&i) {
            return Err(at(dfield, err(format!("`{name}` is listed twice"))));
        }
        dependent.push(i);
    }
    if dependent.len() != m {
        return Err(at(
            dfield,
            err(format!(
                "{}: {} dependent speed(s) for {m} velocity constraint(s): give one per constraint",
                d.path,
                dependent.len()
            )),
        ));
    }
    let outputs: Vec<Poly> = mf
        .into_iter()
        .chain(rows.iter().flatten().cloned())
        .chain(bias)
        .map(|p| d.unfold(&p))
        .collect();
    Ok((
        columns,
        outputs,
        Layout {
            mass,
            rows: m,
            dependent,
            monitor: Cell::default(),
        },
    ))
}

/// The speeds in the brackets of a step `jacobian(x, [u1, u2, …])`.
fn jacobian_columns(d: &Derivation, name: &str) -> Option<Vec<Atom>> {
    let names = bracket_names(d, name, &["jacobian"])?;
    names
        .into_iter()
        .map(|(n, p)| (p == 0).then(|| Atom::time(&n, 0)))
        .collect()
}

/// The augmented system at a state: its matrix, right-hand side and the
/// coordinates' rates q̇.
struct Augmented {
    matrix: DMatrix<f64>,
    rhs: DVector<f64>,
    qdot: Vec<f64>,
}

/// # Multiplier form
impl DerivedModel {
    fn multiplier(&self) -> Option<(&Compiled, &Layout)> {
        match &self.form {
            Form::Multiplier(c, l) => Some((c, l)),
            _ => None,
        }
    }

    /// The augmented matrix [[M, −A_cᵀ], [A_c, 0]], [f; −b] and q̇ at `(t, y)`.
    fn augmented(&self, c: &Compiled, l: &Layout, t: f64, y: &[f64]) -> Augmented {
        let (nq, n, m, k) = (
            self.coordinates.len(),
            self.speeds.len(),
            l.rows,
            l.mass.len(),
        );
        let mut out = vec![0.0; c.tape.outputs()];
        self.eval(c, t, y, &mut out);
        let size = n + m;
        let mut matrix = DMatrix::zeros(size, size);
        let mut rhs = DVector::zeros(size);
        for (i, &ci) in l.mass.iter().enumerate() {
            for (j, &cj) in l.mass.iter().enumerate() {
                matrix[(ci, cj)] = out[i * k + j];
            }
            rhs[ci] = out[k * k + i];
        }
        let a = &out[k * k + k..k * k + k + m * n];
        let b = &out[k * k + k + m * n..k * k + k + m * n + m];
        for r in 0..m {
            for j in 0..n {
                matrix[(n + r, j)] = a[r * n + j];
                matrix[(j, n + r)] = -a[r * n + j];
            }
            rhs[n + r] = -b[r];
        }
        let qdot = out[k * k + k + m * n + m..k * k + k + m * n + m + nq].to_vec();
        Augmented { matrix, rhs, qdot }
    }

    /// The rates `(q̇, u̇)` of a multiplier form; `None` when the augmented
    /// matrix cannot be factorised.
    pub(super) fn multiplier_rates(
        &self,
        c: &Compiled,
        l: &Layout,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
    ) -> Option<()> {
        let (nq, n) = (self.coordinates.len(), self.speeds.len());
        let s = self.augmented(c, l, t, y);
        let sol = s.matrix.lu().solve(&s.rhs)?;
        if !sol.iter().all(|v| v.is_finite()) {
            return None;
        }
        dy[..nq].copy_from_slice(&s.qdot);
        dy[nq..nq + n].copy_from_slice(&sol.as_slice()[..n]);
        Some(())
    }

    /// Why the augmented matrix is singular at `(t, y)` (reciprocal
    /// condition below 1e-13), if it is.
    pub(super) fn multiplier_singularity(&self, t: f64, y: &[f64]) -> Option<String> {
        let (c, l) = self.multiplier()?;
        let sv = self.augmented(c, l, t, y).matrix.singular_values();
        let (lo, hi) = (sv.min(), sv.max());
        (lo.is_nan() || lo <= 1e-13 * hi).then(|| {
            format!(
                "the augmented matrix [[M, -A_c^T], [A_c, 0]] is singular (singular values from \
                 {lo:.3e} to {hi:.3e}): the constraints are dependent, or M is singular on the \
                 motions they allow"
            )
        })
    }

    /// The names of the dependent speeds of a multiplier form (empty
    /// otherwise).
    pub fn dependent_speeds(&self) -> Vec<String> {
        self.multiplier().map_or_else(Vec::new, |(_, l)| {
            l.dependent
                .iter()
                .map(|&i| self.speeds[i].name().to_string())
                .collect()
        })
    }

    /// The velocity constraints A_c u at `(t, y)` (empty without a
    /// multiplier form).
    pub fn velocity_residual(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let Some((c, l)) = self.multiplier() else {
            return Vec::new();
        };
        let (nq, n) = (self.coordinates.len(), self.speeds.len());
        let s = self.augmented(c, l, t, y);
        (0..l.rows)
            .map(|r| (0..n).map(|j| s.matrix[(n + r, j)] * y[nq + j]).sum())
            .collect()
    }

    /// Starts a new record of the velocity constraints' residual, with
    /// the residual of the initial state `y0`.
    pub fn reset_velocity_monitor(&self, y0: &[f64]) {
        if let Some((_, l)) = self.multiplier() {
            l.monitor.set(VelocityMonitor {
                max_residual: max_abs(&self.velocity_residual(0.0, y0)),
                max_correction: 0.0,
            });
        }
    }

    /// What the velocity constraints met since the last reset (`None`
    /// without a multiplier form).
    pub fn velocity_monitor(&self) -> Option<VelocityMonitor> {
        self.multiplier().map(|(_, l)| l.monitor.get())
    }

    /// After an accepted step: the dependent speeds solved from A_c u = 0
    /// and what that met recorded. Returns whether `y` changed.
    pub(super) fn keep_velocity_constraints(&self, t: f64, y: &mut [f64]) -> bool {
        let Some((_, l)) = self.multiplier() else {
            return false;
        };
        let change = self.solve_dependent_speeds(t, y);
        let mut rec = l.monitor.get();
        rec.max_correction = rec.max_correction.max(change.unwrap_or(0.0));
        rec.max_residual = rec.max_residual.max(max_abs(&self.velocity_residual(t, y)));
        l.monitor.set(rec);
        change.is_some_and(|c| c > 0.0)
    }

    /// Solves A_c u = 0 for the dependent speeds of `y`, the independent
    /// ones held: the largest change made, or `None` when A_c restricted
    /// to the dependent speeds is singular (`y` unchanged). Without a
    /// multiplier form, `Some(0.0)`.
    pub fn solve_dependent_speeds(&self, t: f64, y: &mut [f64]) -> Option<f64> {
        let Some((c, l)) = self.multiplier() else {
            return Some(0.0);
        };
        let (nq, n, m) = (self.coordinates.len(), self.speeds.len(), l.rows);
        let s = self.augmented(c, l, t, y);
        let a = |r: usize, j: usize| s.matrix[(n + r, j)];
        let ad = DMatrix::from_fn(m, m, |r, j| a(r, l.dependent[j]));
        let rhs = DVector::from_fn(m, |r, _| {
            -(0..n)
                .filter(|j| !l.dependent.contains(j))
                .map(|j| a(r, j) * y[nq + j])
                .sum::<f64>()
        });
        let sv = ad.clone().singular_values();
        if sv.min().is_nan() || sv.min() <= 1e-12 * sv.max() {
            return None;
        }
        let ud = ad.lu().solve(&rhs)?;
        if !ud.iter().all(|v| v.is_finite()) {
            return None;
        }
        let mut change = 0.0_f64;
        for (j, &i) in l.dependent.iter().enumerate() {
            change = change.max((y[nq + i] - ud[j]).abs());
            y[nq + i] = ud[j];
        }
        Some(change)
    }
}

/// The largest magnitude of `v` (NaN kept: a NaN residual is reported).
fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |a, x| {
        if a.is_nan() || x.is_nan() {
            f64::NAN
        } else {
            a.max(x.abs())
        }
    })
}
