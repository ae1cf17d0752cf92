//! The eigenvalue sweep of a stability scene: the spectrum of the state
//! matrix at each value of the parameter, ordered so that each column
//! follows one eigenvalue, and the intervals of stability with their ends
//! refined by bisection.

use nalgebra::{Complex, DMatrix};

use super::scene::{LinearMatrices, StabilityScene};
use crate::SimError;

/// The margin of "no real part positive": a real part counts as zero when
/// it is at most `MARGIN` times the Frobenius norm of A (the round-off of
/// the Schur form is a few ε‖A‖, and near a double eigenvalue of a
/// conservative system √ε‖A‖).
pub const MARGIN: f64 = 1e-9;

/// The margin of "every real part negative": each real part is below
/// `−STRICT_MARGIN` times the Frobenius norm of A. Round-off alone (a few
/// hundred ε‖A‖ at most for the conjugate pairs of a conservative system,
/// whose real parts sum to the trace) never passes it, and a boundary
/// where a real part crosses zero at a rate s moves by only
/// `STRICT_MARGIN ‖A‖ / s`.
pub const STRICT_MARGIN: f64 = 1e-12;

/// Bisection stops when an end is known to within this fraction of the
/// sweep's scale `max(|from|, |to|, to − from)`.
pub const BISECTION_REL: f64 = 1e-13;

/// The most bisection steps per boundary (each halves the bracket).
const MAX_BISECTIONS: usize = 200;

/// One end of an [`Interval`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Edge {
    /// The end of the sweep: the interval may go on beyond it.
    SweepEnd,
    /// A boundary found between two values of the grid and refined by
    /// bisection: the true boundary is within `half_width` of the value.
    Boundary {
        /// Half the width of the last bracket.
        half_width: f64,
    },
}

/// An interval of the parameter in which a condition holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Its lower end (a refined boundary, or the sweep's start).
    pub lo: f64,
    /// What the lower end is.
    pub lo_edge: Edge,
    /// Its upper end.
    pub hi: f64,
    /// What the upper end is.
    pub hi_edge: Edge,
}

/// The result of a sweep.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The parameter's name.
    pub parameter: String,
    /// The parameter's values.
    pub values: Vec<f64>,
    /// The eigenvalues at each value, in the same order along the sweep
    /// (column k follows one eigenvalue).
    pub eigenvalues: Vec<Vec<Complex<f64>>>,
    /// Where every real part is negative (below −[`STRICT_MARGIN`] ‖A‖):
    /// asymptotically stable.
    pub stable: Vec<Interval>,
    /// Where no real part is positive (within [`MARGIN`] ‖A‖): stable
    /// or marginally stable.
    pub not_unstable: Vec<Interval>,
}

/// The eigenvalues of A at `p` (in no particular order) and the Frobenius
/// norm of A; an error when A cannot be formed or the Schur iteration
/// does not converge.
pub fn spectrum(
    m: &LinearMatrices,
    p: f64,
    scratch: &mut Vec<f64>,
) -> Result<(Vec<Complex<f64>>, f64), String> {
    let a = m.state_matrix(p, scratch)?;
    let norm = a.norm();
    if !norm.is_finite() {
        return Err(format!(
            "the state matrix's eigenvalues are not finite (‖A‖ = {norm:e}): rescale the units"
        ));
    }
    let (a, zeros) = deflate_exact_zeros(a);
    let mut out = vec![Complex::new(0.0, 0.0); zeros];
    if a.nrows() > 0 {
        // faer's real Schur form (Hessenberg reduction, then Francis steps
        // with aggressive early deflation): nalgebra's iteration can fail
        // to deflate the purely imaginary pairs of a conservative system.
        let f = faer::Mat::<f64>::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)]);
        let ev = f
            .eigenvalues()
            .map_err(|e| format!("the eigenvalue iteration did not converge ({e:?})"))?;
        if ev.iter().any(|z| !(z.re.is_finite() && z.im.is_finite())) {
            return Err(format!(
                "the state matrix's eigenvalues are not finite (‖A‖ = {norm:e}): rescale the \
                 units"
            ));
        }
        out.extend(ev.iter().map(|z| Complex::new(z.re, z.im)));
    }
    Ok((out, norm))
}

/// `a` with every row and column removed whose entries are all exactly
/// zero, one index at a time, and how many were removed: each is an exact
/// zero eigenvalue (expand det(A − λI) along that column or row). A cyclic
/// coordinate — absent from K, so its column of A is zero — is the common
/// case: its zero eigenvalue, often double with its rate's conserved
/// momentum, would otherwise come out of the Schur form as a pair
/// ±√ε‖A‖ either side of zero (a Jordan block), more than the margin
/// allows, and "not unstable" would break into fragments.
fn deflate_exact_zeros(mut a: DMatrix<f64>) -> (DMatrix<f64>, usize) {
    let mut zeros = 0;
    loop {
        let n = a.nrows();
        let Some(j) =
            (0..n).find(|&j| (0..n).all(|i| a[(i, j)] == 0.0) || (0..n).all(|i| a[(j, i)] == 0.0))
        else {
            return (a, zeros);
        };
        a = a.remove_row(j).remove_column(j);
        zeros += 1;
    }
}

/// The largest real part of `ev` (−∞ for none).
pub fn max_real_part(ev: &[Complex<f64>]) -> f64 {
    ev.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max)
}

/// Sweeps the scene's parameter: the eigenvalues at each value, ordered
/// continuously, and the stability intervals. `progress(done, total)` is
/// called now and then.
pub fn sweep(
    scene: &StabilityScene,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Sweep, SimError> {
    let m = &scene.matrices;
    let values = scene.values();
    let at = |p: f64, why: String| SimError::BadField {
        file: scene.file.clone(),
        field: "sweep".into(),
        message: format!(
            "at {} = {}: {why}",
            scene.parameter,
            crate::run::significant(&[p], 12)[0]
        ),
    };
    let mut scratch = Vec::new();
    let mut eigenvalues: Vec<Vec<Complex<f64>>> = Vec::with_capacity(values.len());
    let mut stable = Vec::with_capacity(values.len());
    let mut not_unstable = Vec::with_capacity(values.len());
    let every = (values.len() / 100).max(1);
    for (k, &p) in values.iter().enumerate() {
        let (ev, norm) = spectrum(m, p, &mut scratch).map_err(|why| at(p, why))?;
        let ev = match eigenvalues.len() {
            0 => first_order(ev),
            1 => follow(&eigenvalues[0], &eigenvalues[0], ev),
            n => follow(&eigenvalues[n - 1], &eigenvalues[n - 2], ev),
        };
        let r = max_real_part(&ev);
        stable.push(r < -STRICT_MARGIN * norm);
        not_unstable.push(r <= MARGIN * norm);
        eigenvalues.push(ev);
        if k % every == 0 {
            progress(k, values.len());
        }
    }
    progress(values.len(), values.len());
    let scale = scene
        .from
        .abs()
        .max(scene.to.abs())
        .max(scene.to - scene.from);
    let refine = |strict: bool, flags: &[bool]| -> Result<Vec<Interval>, SimError> {
        let mut scratch = Vec::new();
        let mut holds = |p: f64| -> Result<bool, SimError> {
            let (ev, norm) = spectrum(m, p, &mut scratch).map_err(|why| at(p, why))?;
            let r = max_real_part(&ev);
            Ok(if strict {
                r < -STRICT_MARGIN * norm
            } else {
                r <= MARGIN * norm
            })
        };
        intervals(&values, flags, scale, &mut holds)
    };
    Ok(Sweep {
        parameter: scene.parameter.clone(),
        stable: refine(true, &stable)?,
        not_unstable: refine(false, &not_unstable)?,
        values,
        eigenvalues,
    })
}

/// The order at the first value: by real part, largest first, then by
/// imaginary part, largest first.
fn first_order(mut ev: Vec<Complex<f64>>) -> Vec<Complex<f64>> {
    ev.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
    ev
}

/// `ev` reordered so that entry k continues column k: each new eigenvalue
/// is matched to the prediction `2 last − before` (a straight line through
/// the two previous values), nearest pairs first.
fn follow(
    last: &[Complex<f64>],
    before: &[Complex<f64>],
    ev: Vec<Complex<f64>>,
) -> Vec<Complex<f64>> {
    let n = ev.len();
    let predicted: Vec<Complex<f64>> = last.iter().zip(before).map(|(l, b)| l * 2.0 - b).collect();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::with_capacity(n * n);
    for (i, p) in predicted.iter().enumerate() {
        for (j, z) in ev.iter().enumerate() {
            pairs.push(((p - z).norm(), i, j));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut out = vec![Complex::new(f64::NAN, f64::NAN); n];
    let (mut column_done, mut taken) = (vec![false; n], vec![false; n]);
    for (_, i, j) in pairs {
        if !column_done[i] && !taken[j] {
            out[i] = ev[j];
            column_done[i] = true;
            taken[j] = true;
        }
    }
    out
}

/// The maximal runs of `flags` that hold, with each end inside the sweep
/// refined by bisection of `holds` between the two grid values around it.
fn intervals(
    values: &[f64],
    flags: &[bool],
    scale: f64,
    holds: &mut dyn FnMut(f64) -> Result<bool, SimError>,
) -> Result<Vec<Interval>, SimError> {
    let mut out = Vec::new();
    let mut k = 0;
    while k < flags.len() {
        if !flags[k] {
            k += 1;
            continue;
        }
        let start = k;
        while k + 1 < flags.len() && flags[k + 1] {
            k += 1;
        }
        let (lo, lo_edge) = if start == 0 {
            (values[0], Edge::SweepEnd)
        } else {
            bisect(values[start - 1], values[start], scale, holds)?
        };
        let (hi, hi_edge) = if k + 1 == flags.len() {
            (values[k], Edge::SweepEnd)
        } else {
            bisect(values[k], values[k + 1], scale, holds)?
        };
        out.push(Interval {
            lo,
            lo_edge,
            hi,
            hi_edge,
        });
        k += 1;
    }
    Ok(out)
}

/// The boundary between `a` and `b`, where `holds` differs, by bisection
/// to `BISECTION_REL · scale` (or until the bracket cannot be halved in
/// f64): its midpoint and half-width.
fn bisect(
    mut a: f64,
    mut b: f64,
    scale: f64,
    holds: &mut dyn FnMut(f64) -> Result<bool, SimError>,
) -> Result<(f64, Edge), SimError> {
    let at_a = holds(a)?;
    for _ in 0..MAX_BISECTIONS {
        if b - a <= BISECTION_REL * scale {
            break;
        }
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        if holds(mid)? == at_a {
            a = mid;
        } else {
            b = mid;
        }
    }
    Ok((
        0.5 * (a + b),
        Edge::Boundary {
            half_width: 0.5 * (b - a),
        },
    ))
}

/// The sweep as CSV: a header (the parameter, then `re_1, im_1, re_2,
/// im_2, …`) and one line per value, numbers in the shortest form that
/// reads back exactly.
pub fn csv(s: &Sweep) -> String {
    let n = s.eigenvalues.first().map_or(0, Vec::len);
    let mut out = s.parameter.clone();
    for k in 1..=n {
        out.push_str(&format!(",re_{k},im_{k}"));
    }
    out.push('\n');
    for (p, ev) in s.values.iter().zip(&s.eigenvalues) {
        out.push_str(&format!("{p:?}"));
        for z in ev {
            out.push_str(&format!(",{:?},{:?}", z.re, z.im));
        }
        out.push('\n');
    }
    out
}

/// The state matrix of a scene at `p` (for tests and reports).
pub fn state_matrix(scene: &StabilityScene, p: f64) -> Result<DMatrix<f64>, String> {
    scene.matrices.state_matrix(p, &mut Vec::new())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two eigenvalues whose paths cross are followed through the
    /// crossing, not swapped at it.
    #[test]
    fn following_keeps_crossing_paths_apart() {
        let z = |re: f64| Complex::new(re, 0.0);
        // Column 0 rises fast (−2, −0.5, then 1), column 1 falls slowly
        // (0.5, 0.4, then 0.3): they cross between the last two values,
        // and the nearest to each last value would swap them.
        let before = [z(-2.0), z(0.5)];
        let last = [z(-0.5), z(0.4)];
        let now = vec![z(0.3), z(1.0)];
        assert_eq!(follow(&last, &before, now), vec![z(1.0), z(0.3)]);
    }

    /// A cyclic coordinate's zero column and the zero row of a rate that
    /// nothing drives are removed as exact zero eigenvalues; what is left
    /// keeps its spectrum.
    #[test]
    fn exact_zero_rows_and_columns_are_exact_zero_eigenvalues() {
        // State (θ, ψ, θ̇, ψ̇) of an upright rolling hoop: ψ is cyclic
        // (column 1 zero), ψ̈ = −a θ̇.
        let (k, c, d) = (2.0, 3.0, 0.5);
        let a = DMatrix::from_row_slice(
            4,
            4,
            &[
                0.0, 0.0, 1.0, 0.0, //
                0.0, 0.0, 0.0, 1.0, //
                k, 0.0, 0.0, c, //
                0.0, 0.0, -d, 0.0,
            ],
        );
        let (rest, zeros) = deflate_exact_zeros(a);
        assert_eq!(zeros, 1);
        assert_eq!(rest.nrows(), 3);
        // λ (λ² − k + c d) = 0 on what is left.
        let ev = rest.complex_eigenvalues();
        let mut re: Vec<f64> = ev.iter().map(|z| z.re).collect();
        re.sort_by(f64::total_cmp);
        let w = (k - c * d).sqrt();
        assert!((re[0] + w).abs() < 1e-12 && re[1].abs() < 1e-12 && (re[2] - w).abs() < 1e-12);
    }

    /// A boundary between two grid values is found to the bisection's
    /// precision, on both sides of the change.
    #[test]
    fn bisection_finds_a_boundary_to_its_tolerance() {
        let edge = std::f64::consts::PI;
        for (lo, hi) in [(3.0, 3.5), (2.0, 4.0)] {
            let mut below = |p: f64| Ok(p < edge);
            let (b, e) = bisect(lo, hi, 4.0, &mut below).unwrap();
            let Edge::Boundary { half_width } = e else {
                panic!("a boundary")
            };
            assert!(half_width <= BISECTION_REL * 4.0);
            assert!((b - edge).abs() <= half_width + f64::EPSILON * edge);
        }
    }

    /// The runs of a flag vector become intervals with sweep ends where
    /// they reach the grid's ends.
    #[test]
    fn runs_become_intervals() {
        let values: Vec<f64> = (0..=10).map(f64::from).collect();
        let mut holds = |p: f64| Ok(!(2.5..7.25).contains(&p));
        let flags: Vec<bool> = values.iter().map(|&p| !(2.5..7.25).contains(&p)).collect();
        let iv = intervals(&values, &flags, 10.0, &mut holds).unwrap();
        assert_eq!(iv.len(), 2);
        assert_eq!((iv[0].lo, iv[0].lo_edge), (0.0, Edge::SweepEnd));
        assert!((iv[0].hi - 2.5).abs() < 1e-11);
        assert!((iv[1].lo - 7.25).abs() < 1e-11);
        assert_eq!((iv[1].hi, iv[1].hi_edge), (10.0, Edge::SweepEnd));
    }
}
