//! The small dense solve of the mass-matrix form, `M q̈ = f` for n ≤
//! [`MAX_DOF`](super::MAX_DOF), on the stack.

/// Solves `M q̈ = f` with `mf` = M (row-major, `n × n`) followed by f,
/// leaving q̈ in `x`; `None` when a pivot is exactly zero (M singular).
/// Gaussian elimination with partial pivoting on fixed-size arrays on the
/// stack, one instance per n ≤ [`MAX_DOF`](super::MAX_DOF) (unrolled, no allocation: a
/// general LU allocates its matrix per evaluation).
pub(super) fn solve_small(n: usize, mf: &[f64], x: &mut [f64]) -> Option<()> {
    match n {
        1 => solve_fixed::<1>(mf, x),
        2 => solve_fixed::<2>(mf, x),
        3 => solve_fixed::<3>(mf, x),
        4 => solve_fixed::<4>(mf, x),
        5 => solve_fixed::<5>(mf, x),
        6 => solve_fixed::<6>(mf, x),
        _ => None,
    }
}

// Index loops read as the elimination is written (rows i and k of one array).
#[allow(clippy::needless_range_loop)]
fn solve_fixed<const N: usize>(mf: &[f64], x: &mut [f64]) -> Option<()> {
    let mut a = [[0.0; N]; N];
    for (i, row) in a.iter_mut().enumerate() {
        row.copy_from_slice(&mf[i * N..(i + 1) * N]);
    }
    let mut b = [0.0; N];
    b.copy_from_slice(&mf[N * N..N * N + N]);
    let mut inv = [0.0; N];
    for k in 0..N {
        // Partial pivoting by compare-and-swap with each row below (row k
        // ends with the largest |a[·][k]|): fixed indices only, so the
        // unrolled matrix can stay in registers.
        for i in k + 1..N {
            if a[i][k].abs() > a[k][k].abs() {
                let (top, rest) = a.split_at_mut(i);
                std::mem::swap(&mut top[k], &mut rest[0]);
                b.swap(i, k);
            }
        }
        if a[k][k] == 0.0 {
            return None;
        }
        inv[k] = 1.0 / a[k][k];
        for i in k + 1..N {
            let l = a[i][k] * inv[k];
            for j in k + 1..N {
                a[i][j] -= l * a[k][j];
            }
            b[i] -= l * b[k];
        }
    }
    for k in (0..N).rev() {
        let mut s = b[k];
        for j in k + 1..N {
            s -= a[k][j] * b[j];
        }
        b[k] = s * inv[k];
    }
    x.copy_from_slice(&b);
    Some(())
}

#[cfg(test)]
mod tests {
    use nalgebra::DMatrix;

    use super::super::MAX_DOF;
    use super::*;

    /// The stack solve against nalgebra's LU for every size it takes, on
    /// seeded random matrices (and M x = f checked by its residual).
    #[test]
    fn the_small_solve_agrees_with_a_general_lu() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for n in 1..=MAX_DOF {
            for _ in 0..200 {
                let mf: Vec<f64> = (0..n * n + n).map(|_| next()).collect();
                let mut x = vec![0.0; n];
                solve_small(n, &mf, &mut x).expect("a random matrix is regular");
                let m = DMatrix::from_row_slice(n, n, &mf[..n * n]);
                let f = nalgebra::DVector::from_column_slice(&mf[n * n..]);
                let want = m.clone().lu().solve(&f).unwrap();
                // Both errors are bounded by the condition number times
                // the round-off of the solution's size.
                let sv = m.singular_values();
                let cond = sv.max() / sv.min();
                let scale = cond * (1.0 + want.amax()) * f64::EPSILON * 64.0;
                for i in 0..n {
                    assert!(
                        (x[i] - want[i]).abs() <= scale,
                        "n = {n}, x[{i}]: {} vs {} (scale {scale:.3e})",
                        x[i],
                        want[i]
                    );
                }
            }
        }
        // A zero pivot, wherever it appears, is a singular matrix.
        assert!(solve_small(2, &[1.0, 2.0, 2.0, 4.0, 1.0, 1.0], &mut [0.0; 2]).is_none());
        assert!(solve_small(1, &[0.0, 1.0], &mut [0.0; 1]).is_none());
        // Pivoting: a zero in the leading position is no singularity.
        let mut x = [0.0; 2];
        solve_small(2, &[0.0, 1.0, 1.0, 0.0, 3.0, 5.0], &mut x).unwrap();
        assert_eq!(x, [5.0, 3.0]);
    }
}
