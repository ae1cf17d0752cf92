//! The solve of a symmetric mass matrix, `M q̈ = f`, by LDLᵀ on the
//! structure known when compiled: which entries of M are structurally
//! zero (no terms), and so which entries of L can be non-zero (with the
//! fill of the elimination). A matrix that is not symmetric as compiled,
//! or a pivot that is not positive at a state, is solved by the general
//! elimination with partial pivoting of `small_solve.rs` instead.
//!
//! Why: a mass matrix is symmetric and, where the coordinates are
//! regular, positive definite; there LDLᵀ without pivoting is backward
//! stable, needs no comparisons or row swaps, and skips every product
//! with a structural zero. The heavy top's M has four zeros: the nutation
//! row is apart from the others, and the chain of dependent operations
//! (the latency of an evaluation) is two divisions long instead of three.

use hdot_sym::poly::Poly;

use super::MAX_DOF;
use super::small_solve::solve_small;

/// How `M q̈ = f` is solved, planned when the model is compiled.
#[derive(Debug, Clone)]
pub(super) struct MassSolve {
    n: usize,
    /// The entries of L that can be non-zero, when M is symmetric as
    /// compiled (`None`: solved by the general elimination).
    ldl: Option<Pattern>,
}

/// `lower[i][j]` (j < i): the entry L_ij of the factor can be non-zero
/// (M_ij has terms, or the elimination of an earlier column fills it);
/// `bits`: the same entries of the first three rows, bit `3 i + j`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pattern {
    lower: [[bool; MAX_DOF]; MAX_DOF],
    bits: u32,
}

/// Which entries of L can be non-zero, as [`ldl_fixed`] reads them: a
/// [`Pattern`] read per entry, or (n ≤ 3) one fixed in the type, [`Bits`],
/// for which every test of the pattern is folded away when compiled.
trait Lower: Copy {
    fn at(self, i: usize, j: usize) -> bool;
}

impl Lower for &Pattern {
    #[inline(always)]
    fn at(self, i: usize, j: usize) -> bool {
        self.lower[i][j]
    }
}

/// A pattern of at most three rows as the bits of [`Pattern::bits`].
#[derive(Clone, Copy)]
struct Bits<const B: u32>;

impl<const B: u32> Lower for Bits<B> {
    #[inline(always)]
    fn at(self, i: usize, j: usize) -> bool {
        B >> (3 * i + j) & 1 == 1
    }
}

/// # Planning
impl MassSolve {
    /// The solve of the `n × n` matrix whose entries (row-major) are
    /// `m[..n * n]`: LDLᵀ on its structure when every M_ji is the same
    /// polynomial as M_ij, the general elimination otherwise.
    pub(super) fn plan(n: usize, m: &[Poly]) -> MassSolve {
        let symmetric = n <= MAX_DOF
            && m.len() >= n * n
            && (0..n).all(|i| (0..i).all(|j| m[i * n + j] == m[j * n + i]));
        let ldl = symmetric.then(|| Pattern::of(n, |i, j| !m[i * n + j].is_zero()));
        MassSolve { n, ldl }
    }

    /// The general elimination, whatever the matrix.
    #[cfg(test)]
    fn general(n: usize) -> MassSolve {
        MassSolve { n, ldl: None }
    }
}

impl Pattern {
    /// The symbolic factorisation: L_ij (j < i) can be non-zero when
    /// `entry(i, j)` can, or when L_ik and L_jk can for some k < j.
    fn of(n: usize, entry: impl Fn(usize, usize) -> bool) -> Pattern {
        let mut lower = [[false; MAX_DOF]; MAX_DOF];
        let mut bits = 0;
        for j in 0..n {
            for i in j + 1..n {
                lower[i][j] = entry(i, j) || (0..j).any(|k| lower[i][k] && lower[j][k]);
                if i < 3 && lower[i][j] {
                    bits |= 1 << (3 * i + j);
                }
            }
        }
        Pattern { lower, bits }
    }
}

/// # Solving
impl MassSolve {
    /// Solves `M q̈ = f` with `mf` = M (row-major, `n × n`) followed by f,
    /// leaving q̈ in `x`; `None` when M is singular (a zero pivot of the
    /// general elimination). LDLᵀ when planned and every pivot is
    /// positive; otherwise the general elimination with partial pivoting.
    /// For n ≤ 3 the pattern selects an instance of the factorisation with
    /// the pattern in its type (no test of it per entry: the heavy top's
    /// solve spent ~35 of its ~110 instructions in such tests). Always
    /// inlined: a right-hand side that inlines the tape's dispatch is too
    /// large for LLVM to inline this by itself, and the call with its own
    /// frame was ~30 of the heavy top's instructions per evaluation.
    #[inline(always)]
    pub(super) fn solve(&self, mf: &[f64], x: &mut [f64]) -> Option<()> {
        // Bits 3, 6 and 7: L_10, L_20 and L_21 (filled when both others are).
        let done = match &self.ldl {
            None => None,
            Some(p) => match (self.n, p.bits) {
                (1, _) => ldl_fixed::<1, _>(Bits::<0>, mf, x),
                (2, 0) => ldl_fixed::<2, _>(Bits::<0>, mf, x),
                (2, _) => ldl_fixed::<2, _>(Bits::<8>, mf, x),
                (3, 0) => ldl_fixed::<3, _>(Bits::<0>, mf, x),
                (3, 8) => ldl_fixed::<3, _>(Bits::<8>, mf, x),
                (3, 64) => ldl_fixed::<3, _>(Bits::<64>, mf, x),
                (3, 128) => ldl_fixed::<3, _>(Bits::<128>, mf, x),
                (3, 136) => ldl_fixed::<3, _>(Bits::<136>, mf, x),
                (3, 192) => ldl_fixed::<3, _>(Bits::<192>, mf, x),
                (3, 200) => ldl_fixed::<3, _>(Bits::<200>, mf, x),
                (3, _) => ldl_fixed::<3, _>(p, mf, x),
                (4, _) => ldl_fixed::<4, _>(p, mf, x),
                (5, _) => ldl_fixed::<5, _>(p, mf, x),
                (6, _) => ldl_fixed::<6, _>(p, mf, x),
                _ => None,
            },
        };
        done.or_else(|| solve_small(self.n, mf, x))
    }
}

/// LDLᵀ of the symmetric `M` (its lower triangle read) on the pattern
/// `p`, then the forward, diagonal and backward solves; `None` (and `x`
/// untouched) when a pivot is not positive. One division per pivot; an
/// entry outside the pattern is an exact zero, and skipping it gives the
/// same bits as the dense loops.
// Index loops read as the factorisation is written (rows i, j and k).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn ldl_fixed<const N: usize, L: Lower>(p: L, mf: &[f64], x: &mut [f64]) -> Option<()> {
    let (m, f) = (&mf[..N * N], &mf[N * N..N * N + N]);
    // c[i][j] = L_ij d_j, l[i][j] = L_ij (j < i), r[j] = 1 / d_j.
    let mut c = [[0.0; N]; N];
    let mut l = [[0.0; N]; N];
    let mut r = [0.0; N];
    for j in 0..N {
        let mut d = m[j * N + j];
        for k in 0..j {
            if p.at(j, k) {
                d -= l[j][k] * c[j][k];
            }
        }
        // A NaN pivot too: the general elimination decides.
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        r[j] = 1.0 / d;
        for i in j + 1..N {
            if p.at(i, j) {
                let mut s = m[i * N + j];
                for k in 0..j {
                    if p.at(i, k) && p.at(j, k) {
                        s -= l[i][k] * c[j][k];
                    }
                }
                c[i][j] = s;
                l[i][j] = s * r[j];
            }
        }
    }
    let mut z = [0.0; N];
    for i in 0..N {
        let mut s = f[i];
        for k in 0..i {
            if p.at(i, k) {
                s -= l[i][k] * z[k];
            }
        }
        z[i] = s;
    }
    let mut y = [0.0; N];
    for i in (0..N).rev() {
        let mut s = z[i] * r[i];
        for k in i + 1..N {
            if p.at(k, i) {
                s -= l[k][i] * y[k];
            }
        }
        y[i] = s;
    }
    x[..N].copy_from_slice(&y);
    Some(())
}

#[cfg(test)]
mod tests {
    use nalgebra::DMatrix;

    use super::*;

    /// A seeded generator of numbers in [−1, 1).
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// The entries `(i, j)` of an `n × n` pattern drawn from `bits`,
    /// symmetric, the diagonal always present.
    fn pattern_of(n: usize, bits: u64) -> Pattern {
        Pattern::of(n, |i, j| bits >> (i * n + j) & 1 == 1)
    }

    /// LDLᵀ on a structure agrees with the general elimination on
    /// seeded symmetric positive definite matrices of every size, with
    /// every structure of zeros drawn at random: both are backward stable,
    /// so they differ by at most the condition number times the round-off
    /// of the solution's size (the algebra differs: no pivoting, other
    /// order of operations).
    #[test]
    fn ldl_on_a_structure_agrees_with_the_general_elimination() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let mut bits = uniform(0x2545_f491_4f6c_dd1d);
        for n in 1..=MAX_DOF {
            for _ in 0..300 {
                let drawn = (bits().to_bits() >> 3) & ((1u64 << (n * n)) - 1);
                let p = pattern_of(n, drawn);
                // A diagonally dominant symmetric matrix (so positive
                // definite) with exactly the drawn zeros below its diagonal.
                let mut m = DMatrix::<f64>::zeros(n, n);
                for i in 0..n {
                    for j in 0..i {
                        if drawn >> (i * n + j) & 1 == 1 {
                            let v = next();
                            m[(i, j)] = v;
                            m[(j, i)] = v;
                        }
                    }
                }
                for i in 0..n {
                    let off: f64 = (0..n).filter(|&j| j != i).map(|j| m[(i, j)].abs()).sum();
                    m[(i, i)] = off + 0.01 + next().abs();
                }
                let mut mf: Vec<f64> = m.transpose().iter().copied().collect();
                mf.extend((0..n).map(|_| next()));
                let ldl = MassSolve { n, ldl: Some(p) };
                let mut x = vec![0.0; n];
                ldl_fixed_dyn(n, &p, &mf, &mut x).expect("positive pivots");
                let mut want = vec![0.0; n];
                MassSolve::general(n)
                    .solve(&mf, &mut want)
                    .expect("regular");
                let mut via = vec![0.0; n];
                ldl.solve(&mf, &mut via).expect("regular");
                assert_eq!(x, via, "the plan takes the LDLᵀ path");
                let sv = m.singular_values();
                let cond = sv.max() / sv.min();
                let big = want.iter().fold(1.0f64, |a, v| a.max(v.abs()));
                let scale = cond * big * f64::EPSILON * 64.0;
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
    }

    fn ldl_fixed_dyn(n: usize, p: &Pattern, mf: &[f64], x: &mut [f64]) -> Option<()> {
        match n {
            1 => ldl_fixed::<1, _>(p, mf, x),
            2 => ldl_fixed::<2, _>(p, mf, x),
            3 => ldl_fixed::<3, _>(p, mf, x),
            4 => ldl_fixed::<4, _>(p, mf, x),
            5 => ldl_fixed::<5, _>(p, mf, x),
            _ => ldl_fixed::<6, _>(p, mf, x),
        }
    }

    /// Skipping the pattern's zeros gives the same bits as the dense
    /// factorisation of the same matrix.
    #[test]
    fn the_structure_only_skips_exact_zeros() {
        // The heavy top's M: rows φ, θ, ψ with M_φθ = M_θψ = 0.
        let mf = [
            0.0012, 0.0, 0.0003, 0.0, 0.0015, 0.0, 0.0003, 0.0, 0.0004, 0.7, -0.2, 0.05,
        ];
        let sparse = Pattern::of(3, |i, j| (i, j) == (2, 0));
        assert!(!sparse.lower[1][0]);
        assert!(!sparse.lower[2][1], "no fill");
        let dense = Pattern::of(3, |_, _| true);
        let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
        ldl_fixed::<3, _>(&sparse, &mf, &mut a).unwrap();
        ldl_fixed::<3, _>(&dense, &mf, &mut b).unwrap();
        assert_eq!(a, b);
        // Fill: L_21 from L_10 and L_20.
        let fill = Pattern::of(3, |i, j| j == 0 && i > 0);
        assert!(fill.lower[2][1]);
    }

    /// A pivot that is not positive (an indefinite or singular M) goes to
    /// the general elimination: the same answer, and the same `None` for a
    /// singular matrix.
    #[test]
    fn a_pivot_not_positive_falls_back_to_the_general_elimination() {
        let full = MassSolve {
            n: 2,
            ldl: Some(Pattern::of(2, |_, _| true)),
        };
        // Indefinite: [[0, 1], [1, 0]] x = [3, 5].
        let mut x = [0.0; 2];
        full.solve(&[0.0, 1.0, 1.0, 0.0, 3.0, 5.0], &mut x).unwrap();
        assert_eq!(x, [5.0, 3.0]);
        assert!(
            full.solve(&[1.0, 2.0, 2.0, 4.0, 1.0, 1.0], &mut x)
                .is_none()
        );
        let nan = [f64::NAN, 0.0, 0.0, 1.0, 1.0, 1.0];
        let mut y = [0.0; 2];
        assert_eq!(
            full.solve(&nan, &mut x).is_some(),
            MassSolve::general(2).solve(&nan, &mut y).is_some()
        );
        assert!(x[0].is_nan() && y[0].is_nan());
    }

    /// A matrix not symmetric as compiled gets no LDLᵀ plan.
    #[test]
    fn only_a_symmetric_matrix_is_planned_for_ldl() {
        use hdot_sym::Rational;
        let c = |v: i64| Poly::constant(Rational::int(v));
        let sym = [c(2), c(1), c(1), c(3)];
        assert!(MassSolve::plan(2, &sym).ldl.is_some());
        let unsym = [c(2), c(1), c(0), c(3)];
        assert!(MassSolve::plan(2, &unsym).ldl.is_none());
        let zeros = [c(2), c(0), c(0), c(3)];
        let p = MassSolve::plan(2, &zeros).ldl.unwrap();
        assert!(!p.lower[1][0]);
    }
}
