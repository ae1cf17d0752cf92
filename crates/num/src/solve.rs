//! Linear solve of named unknowns with rank detection (faer SVD).
//!
//! Worked problems reduce to `A x = b`: six balance equations (force and
//! moment, or linear and angular impulse–momentum) plus any kinematic
//! constraints, in a handful of unknowns. The solve never "succeeds by
//! accident":
//! - columns and rows are scaled to unit norm (unknowns of different units),
//!   then the singular values decide the rank with a relative tolerance;
//! - rank below the number of unknowns → [`SolveError::Underdetermined`],
//!   naming the unknowns that the equations do not fix;
//! - a residual above round-off → [`SolveError::Inconsistent`]: no value of
//!   the unknowns satisfies all the equations.

/// Relative tolerance on singular values (relative to the largest).
pub const RANK_RTOL: f64 = 1e-10;

/// Why the unknowns cannot be solved for.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// Fewer independent equations than unknowns.
    #[error(
        "underdetermined: rank {rank} < {unknowns} unknowns; not fixed by the equations: {}",
        free.join(", ")
    )]
    Underdetermined {
        /// Numerical rank of the system.
        rank: usize,
        /// Number of unknowns.
        unknowns: usize,
        /// Unknowns involved in the null space.
        free: Vec<String>,
    },
    /// The equations contradict each other.
    #[error(
        "inconsistent: no values of the unknowns satisfy every equation (largest relative residual {residual:e} in equation `{equation}`)"
    )]
    Inconsistent {
        /// Largest scaled residual.
        residual: f64,
        /// The equation with the largest residual.
        equation: String,
    },
    /// The SVD did not converge.
    #[error("the singular value decomposition did not converge")]
    NoConvergence,
}

/// `A x = b` with named unknowns and equations.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LinearSystem {
    /// Names of the unknowns (columns).
    pub unknowns: Vec<String>,
    /// Names of the equations (rows).
    pub equations: Vec<String>,
    /// Row-major coefficients, one `Vec` per equation.
    pub a: Vec<Vec<f64>>,
    /// Right-hand sides.
    pub b: Vec<f64>,
    /// Magnitude of the terms that make up each equation (for the
    /// consistency tolerance); `|b|` when not given.
    pub scales: Vec<f64>,
}

impl LinearSystem {
    /// Adds an equation `Σ coeffs[k] x_k = rhs`.
    pub fn push(&mut self, name: impl Into<String>, coeffs: Vec<f64>, rhs: f64) {
        self.push_scaled(name, coeffs, rhs, rhs.abs());
    }

    /// Adds an equation and the magnitude `scale` of the terms summed into
    /// its right-hand side (a right-hand side that is the round-off of
    /// cancelling terms is then recognised as zero).
    pub fn push_scaled(&mut self, name: impl Into<String>, coeffs: Vec<f64>, rhs: f64, scale: f64) {
        self.equations.push(name.into());
        self.a.push(coeffs);
        self.b.push(rhs);
        self.scales.push(scale.abs());
    }

    /// Solves with rank detection (see the module docs).
    ///
    /// # Example
    /// ```
    /// use hdot_num::solve::{LinearSystem, SolveError};
    /// let mut s = LinearSystem { unknowns: vec!["a".into(), "b".into()], ..Default::default() };
    /// s.push("sum", vec![1.0, 1.0], 3.0);
    /// assert!(matches!(s.solve(), Err(SolveError::Underdetermined { .. })));
    /// s.push("diff", vec![1.0, -1.0], 1.0);
    /// assert_eq!(s.solve().unwrap().len(), 2);
    /// s.push("twice", vec![2.0, 2.0], 7.0);
    /// assert!(matches!(s.solve(), Err(SolveError::Inconsistent { .. })));
    /// ```
    pub fn solve(&self) -> Result<Vec<f64>, SolveError> {
        let n = self.unknowns.len();
        if n == 0 {
            return Ok(Vec::new());
        }
        let m = self.equations.len();
        if m == 0 {
            return Err(SolveError::Underdetermined {
                rank: 0,
                unknowns: n,
                free: self.unknowns.clone(),
            });
        }
        // Column scaling (units of the unknowns), then row scaling.
        let col: Vec<f64> = (0..n)
            .map(|j| {
                let s = (0..m).map(|i| self.a[i][j].powi(2)).sum::<f64>().sqrt();
                if s > 0.0 { s } else { 1.0 }
            })
            .collect();
        let row: Vec<f64> = (0..m)
            .map(|i| {
                let s = (0..n)
                    .map(|j| (self.a[i][j] / col[j]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                if s > 0.0 { s } else { 1.0 }
            })
            .collect();
        let a = faer::Mat::<f64>::from_fn(m, n, |i, j| self.a[i][j] / col[j] / row[i]);
        let b: Vec<f64> = (0..m).map(|i| self.b[i] / row[i]).collect();
        let svd = a.svd().map_err(|_| SolveError::NoConvergence)?;
        let s = svd.S().column_vector();
        let (u, v) = (svd.U(), svd.V());
        let k = m.min(n);
        let smax = if k > 0 { s[0] } else { 0.0 };
        let rank = (0..k).filter(|&i| s[i] > RANK_RTOL * smax).count();
        if rank < n {
            // Null space: columns rank..n of V.
            let free = (0..n)
                .filter(|&j| (rank..n).any(|c| v[(j, c)].abs() > 1e-8))
                .map(|j| self.unknowns[j].clone())
                .collect();
            return Err(SolveError::Underdetermined {
                rank,
                unknowns: n,
                free,
            });
        }
        // y = V Σ⁺ Uᵀ b
        let mut y = vec![0.0; n];
        for c in 0..rank {
            let ub: f64 = (0..m).map(|i| u[(i, c)] * b[i]).sum();
            let coef = ub / s[c];
            for (j, yj) in y.iter_mut().enumerate() {
                *yj += v[(j, c)] * coef;
            }
        }
        // Residual in the original units, against the magnitude of the
        // terms of each equation.
        let x: Vec<f64> = (0..n).map(|j| y[j] / col[j]).collect();
        let ynorm = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        let (mut worst, mut at) = (0.0f64, 0usize);
        for i in 0..m {
            // typical size of each unknown: |y| / col_j (unit-consistent)
            let terms: f64 = (0..n)
                .map(|j| self.a[i][j].abs() * (x[j].abs() + ynorm / col[j]))
                .sum();
            let r = self.b[i] - (0..n).map(|j| self.a[i][j] * x[j]).sum::<f64>();
            let scale = terms + self.b[i].abs() + self.scales.get(i).copied().unwrap_or(0.0);
            let rel = if scale > 0.0 { r.abs() / scale } else { 0.0 };
            if rel > worst {
                worst = rel;
                at = i;
            }
        }
        if worst > 1e-9 {
            return Err(SolveError::Inconsistent {
                residual: worst,
                equation: self.equations[at].clone(),
            });
        }
        Ok(x)
    }
}
