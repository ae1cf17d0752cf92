//! The linearisation about a steady state, measured on the particles.
//!
//! The disturbance is the file's small symbols (`[symbols] small`) with
//! all their derivatives. A meaning X measured at the drawn instant is a
//! function of them; scaling the disturbance by h makes it a function
//! X(h) of one number, and its first-order part is X′(0), measured by
//! Richardson-extrapolated central differences
//! `4/3 [X(½) − X(−½)] − 1/6 [X(1) − X(−1)]`: exact (to round-off) when X
//! is a polynomial of degree ≤ 4 in the disturbance — the moment, the
//! momenta and the energy of frames given by their angular velocity are
//! quadratic in it. (A small *angle* enters through sin and cos, which no
//! finite difference reproduces exactly: such a linearisation is compared
//! to the truncation error of the differences and fails.)
//!
//! - `linear(X)`: X at zero disturbance plus its first-order part.
//! - `coefficient(X, e)`: the first-order part of X in e alone, at e = 0.
//! - `rate(e⁽ⁿ⁾, X)`: the first-order part of X is `X₀ + P ε + Q ε̇`
//!   (columns of P and Q measured one small symbol or rate at a time);
//!   X = 0 gives `ε̇ = −Q⁻¹ (X₀ + P ε)` and, differentiating the linear
//!   system, `ε⁽ⁿ⁾ = J ε⁽ⁿ⁻¹⁾` with `J = −Q⁻¹ P`; at the drawn ε. (The
//!   system is of first order in the small symbols: X may contain their
//!   rates, not their accelerations.)

use hdot_sym::atom::Atom;
use nalgebra::{DMatrix, DVector};

use super::VerifyError;
use crate::bind::Values;

/// A meaning measured at given values: its components and the magnitudes
/// of the terms summed into them.
pub(crate) type Eval<'a> = dyn Fn(&Values) -> Result<(Vec<f64>, f64), VerifyError> + 'a;

/// The first-order part of `eval` along the family `at(h)` (h = 0 the
/// base), and its scale.
fn first_order(
    eval: &Eval<'_>,
    at: &dyn Fn(f64) -> Values,
) -> Result<(Vec<f64>, f64), VerifyError> {
    let mut out: Vec<f64> = Vec::new();
    let mut scale = 0.0;
    for (h, w) in [
        (0.5, 4.0 / 3.0),
        (-0.5, -4.0 / 3.0),
        (1.0, -1.0 / 6.0),
        (-1.0, 1.0 / 6.0),
    ] {
        let (x, s) = eval(&at(h))?;
        if out.is_empty() {
            out = vec![0.0; x.len()];
        }
        for (o, v) in out.iter_mut().zip(&x) {
            *o += w * v;
        }
        scale += f64::abs(w) * (s + x.iter().map(|v| v.abs()).fold(0.0, f64::max));
    }
    Ok((out, scale))
}

/// `linear(X)` at `values`.
pub(crate) fn linear(
    eval: &Eval<'_>,
    values: &Values,
    small: &[Atom],
) -> Result<(Vec<f64>, f64), VerifyError> {
    let (x0, s0) = eval(&values.scale_small(small, 0.0))?;
    let (x1, s1) = first_order(eval, &|h| values.scale_small(small, h))?;
    Ok((x0.iter().zip(&x1).map(|(a, b)| a + b).collect(), s0 + s1))
}

/// `coefficient(X, e)` at `values` (X scalar).
pub(crate) fn coefficient(
    eval: &Eval<'_>,
    values: &Values,
    e: Atom,
) -> Result<(f64, f64), VerifyError> {
    let (x, s) = first_order(eval, &|h| values.with(e, h))?;
    Ok((x[0], s))
}

/// `rate(e, X)` at `values`: `e` a derivative (order ≥ 1) of the small
/// symbol it names.
pub(crate) fn rate(
    eval: &Eval<'_>,
    values: &Values,
    small: &[Atom],
    e: Atom,
    derivation: &str,
) -> Result<(f64, f64), VerifyError> {
    let k = small.len();
    let zero = values.scale_small(small, 0.0);
    let (x0, s0) = eval(&zero)?;
    let (mut p, mut q) = (DMatrix::zeros(k, k), DMatrix::zeros(k, k));
    let mut scale = s0 + x0.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for (j, s) in small.iter().enumerate() {
        for (order, m) in [(0, &mut p), (1, &mut q)] {
            let a = Atom::time(s.name(), order);
            let (col, cs) = first_order(eval, &|h| zero.with(a, h))?;
            scale = scale.max(cs);
            for (i, c) in col.iter().enumerate() {
                m[(i, j)] = *c;
            }
        }
    }
    let eps = DVector::from_iterator(k, small.iter().map(|s| values.get(*s).map_or(0.0, |v| v.0)));
    let x0 = DVector::from_vec(x0);
    let qinv = q
        .clone()
        .try_inverse()
        .ok_or_else(|| VerifyError::Singular {
            derivation: derivation.into(),
            what: "the first-order part of X in the small symbols' rates (rate(e', X))",
        })?;
    let j = -&qinv * &p;
    let mut x = -&qinv * (&x0 + &p * &eps);
    let (qa, pa, ja) = (qinv.abs(), p.abs(), j.abs());
    // Magnitudes: the sums X is measured from, the terms of Q⁻¹ (X₀ + P ε)
    // and Q's own round-off.
    let ones = DVector::from_element(k, 1.0);
    let mut mag = &qa * (x0.abs() + &pa * eps.abs() + &ones * scale) + &qa * (q.abs() * x.abs());
    for _ in 1..e.order() {
        mag = &ja * (&mag + x.abs());
        x = &j * &x;
    }
    let i = small
        .iter()
        .position(|s| s.name() == e.name())
        .expect("validated: a small symbol");
    Ok((x[i], mag[i]))
}
