//! A drawn configuration that meets a `kane` step's configuration
//! constraints f(q) = 0 (the front wheel of a bicycle touching the
//! ground): the dependent coordinates solved by Newton's method from the
//! drawn values of the others, in a bounded number of iterations; where no
//! root is found near the draw, the other symbols the constraints hold are
//! drawn again, a bounded number of times, and then the step is named in
//! the error.

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::poly::Poly;
use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::speeds::Configuration;
use super::{TOLERANCE_ULPS, VerifyError, declaration};
use crate::bind::Values;

/// Newton iterations from one starting configuration.
pub(crate) const ITERATIONS: usize = 60;

/// Configurations drawn before no root is declared.
pub(crate) const TRIES: usize = 64;

/// The symbols `rows` hold that a redraw may change: constants and
/// coordinates (an angle under sine or cosine included), less the
/// dependent coordinates and those `fixed` (bound by a declaration).
fn free_symbols(c: &Configuration, fixed: &[Atom]) -> Vec<Atom> {
    let mut out: Vec<Atom> = Vec::new();
    for a in c.rows.iter().flat_map(Poly::atoms) {
        let a = match a.kind() {
            AtomKind::Sin(q) | AtomKind::Cos(q) => q,
            AtomKind::Var { order: 0, .. } => a,
            _ => continue,
        };
        if !out.contains(&a) && !c.dependent.contains(&a) && !fixed.contains(&a) {
            out.push(a);
        }
    }
    out
}

/// Newton's method on the constraints in the dependent coordinates from
/// their values in `values`; true when every constraint vanishes to
/// round-off of its terms' magnitudes.
pub(crate) fn newton(c: &Configuration, values: &mut Values) -> Result<bool, VerifyError> {
    let n = c.dependent.len();
    // `c.prepared`: the rows, then the Jacobian row by row.
    let (p, rows) = (&c.prepared, c.rows.len());
    for _ in 0..ITERATIONS {
        let at = p.resolve(values);
        let mut f = DVector::zeros(n);
        let mut met = true;
        for i in 0..rows {
            let (v, s) = p.eval(i, &at)?;
            f[i] = v;
            met &= v.abs() <= TOLERANCE_ULPS * f64::EPSILON * s.max(f64::MIN_POSITIVE);
        }
        if met {
            return Ok(true);
        }
        let mut j = DMatrix::zeros(n, n);
        for (i, row) in c.jacobian.iter().enumerate() {
            for k in 0..row.len() {
                j[(i, k)] = p.eval(rows + i * row.len() + k, &at)?.0;
            }
        }
        let Some(step) = j.lu().solve(&f) else {
            return Ok(false);
        };
        if !step.iter().all(|x| x.is_finite()) {
            return Ok(false);
        }
        for (q, dq) in c.dependent.iter().zip(step.iter()) {
            let x = values.get(*q).map_or(0.0, |v| v.0) - dq;
            values.set(*q, x, x);
        }
    }
    Ok(false)
}

/// Solves `c`'s dependent coordinates at the drawn `values`; where no
/// root is found, draws the other symbols of the constraints (except
/// those in `fixed`) and the starting values again, at most [`TRIES`]
/// times.
///
/// # Errors
/// A configuration constraint without a solution near any of the drawn
/// configurations, naming the `kane` step; a symbol of the constraints
/// without a value.
pub(crate) fn meet(
    d: &Derivation,
    c: &Configuration,
    values: &mut Values,
    fixed: &[Atom],
    rng: &mut ChaCha8Rng,
) -> Result<(), VerifyError> {
    if c.rows.is_empty() || c.dependent.is_empty() {
        return Ok(());
    }
    if c.rows.len() != c.dependent.len() {
        return Err(declaration(
            d,
            format!(
                "step `{}`: {} configuration constraint(s) but {} dependent coordinate(s) to solve them for",
                c.step,
                c.rows.len(),
                c.dependent.len()
            ),
        ));
    }
    let free = free_symbols(c, fixed);
    for _ in 0..TRIES {
        let mut v = values.clone();
        if newton(c, &mut v).map_err(|e| e.in_step(d, &c.step))? {
            *values = v;
            return Ok(());
        }
        for &a in free.iter().chain(&c.dependent) {
            let x = if a.is_time_dependent() {
                rng.gen_range(-2.0..2.0)
            } else {
                rng.gen_range(0.5..2.0)
            };
            values.set(a, x, x);
        }
    }
    let names = |v: &[Atom]| {
        v.iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    Err(declaration(
        d,
        format!(
            "step `{}`: the configuration constraints have no solution for {} near any of {TRIES} drawn \
             configurations (Newton's method, {ITERATIONS} iterations from each)",
            c.step,
            names(&c.dependent)
        ),
    ))
}
