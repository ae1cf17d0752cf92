//! The integrators: one driver, one function per method.
//!
//! | method | order | step | cost per step (evaluations) |
//! |---|---|---|---|
//! | `euler` | 1 | fixed | 1 |
//! | `rk4` | 4 | fixed | 4 |
//! | `dopri5` | 5(4) | adaptive (or fixed) | 6 (FSAL) |
//! | `dop853` | 8(5,3) | adaptive (or fixed) | 12 (11 on rejection) |
//! | `midpoint` | 2 | fixed, implicit | 1 + fixed-point iterations |
//! | `split2` | 2 | fixed, symplectic | sub-flows (5 free, 7 heavy top) |
//! | `split4` | 4 | fixed, symplectic | 3 × split2 |
//!
//! Adaptive steps follow Hairer's `dopri5.f`/`dop853.f`: error norm
//! `√(Σ (e_i / sc_i)² / N)` with `sc_i = atol + rtol max(|y_i|, |ŷ_i|)`,
//! safety factor 0.9, step ratio limits and Lund (PI) stabilisation
//! `β = 0.04` for dopri5 (none for dop853), initial step by `hinit`.

use std::fmt;
use std::str::FromStr;

use crate::tableau::*;
use crate::{SimError, System};

/// An integration method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Explicit (forward) Euler.
    Euler,
    /// Classical fourth-order Runge–Kutta.
    Rk4,
    /// Dormand–Prince 5(4).
    Dopri5,
    /// Dormand–Prince 8(5,3).
    Dop853,
    /// Implicit midpoint rule, fixed-point iteration to round-off.
    Midpoint,
    /// Strang splitting into exact sub-flows (second order, symplectic).
    Split2,
    /// Yoshida's fourth-order composition of `split2`.
    Split4,
}

/// # Names and properties
impl Method {
    /// Every method, in the order of the documentation.
    pub const ALL: [Method; 7] = [
        Method::Euler,
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
        Method::Midpoint,
        Method::Split2,
        Method::Split4,
    ];

    /// Command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Euler => "euler",
            Method::Rk4 => "rk4",
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
            Method::Midpoint => "midpoint",
            Method::Split2 => "split2",
            Method::Split4 => "split4",
        }
    }

    /// Classical order of convergence.
    pub fn order(self) -> u32 {
        match self {
            Method::Euler => 1,
            Method::Rk4 | Method::Split4 => 4,
            Method::Dopri5 => 5,
            Method::Dop853 => 8,
            Method::Midpoint | Method::Split2 => 2,
        }
    }

    /// Whether the method controls its step by a tolerance.
    pub fn is_adaptive(self) -> bool {
        matches!(self, Method::Dopri5 | Method::Dop853)
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = SimError;
    fn from_str(s: &str) -> Result<Self, SimError> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| SimError::UnknownName {
                what: "method",
                name: s.to_string(),
                expected: Method::ALL.map(Method::name).join(", "),
            })
    }
}

/// How the step is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step {
    /// Fixed step `h` (adjusted down so that it divides the interval).
    Fixed(f64),
    /// Adaptive, with `rtol = atol = tol`.
    Tolerance(f64),
}

impl Step {
    /// Rejects non-positive or non-finite values.
    pub fn validate(self) -> Result<Self, SimError> {
        match self {
            Step::Fixed(h) if !(h.is_finite() && h > 0.0) => Err(SimError::NonPositiveStep(h)),
            Step::Tolerance(t) if !(t.is_finite() && t > 0.0) => {
                Err(SimError::NonPositiveTolerance(t))
            }
            s => Ok(s),
        }
    }
}

/// Counters of one run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations (for the splittings: exact sub-flows).
    pub evaluations: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps (adaptive methods).
    pub rejected: u64,
}

/// Limits of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest number of steps (accepted + rejected).
    pub max_steps: u64,
}

impl Default for Limits {
    fn default() -> Self {
        // The run budget in force (docs/cli.md, `--max-steps`).
        Limits {
            max_steps: crate::budget::max_steps(),
        }
    }
}

/// Number of fixed steps of size about `h` over `span`: `⌈span/h⌉`, where a
/// quotient within `1e-9` of an integer counts as that integer.
pub fn fixed_step_count(span: f64, h: f64) -> u64 {
    let q = span / h;
    let r = q.round();
    let n = if (q - r).abs() <= 1e-9 * r.max(1.0) {
        r
    } else {
        q.ceil()
    };
    (n as u64).max(1)
}

/// Integrates `sys` from `(t0, y0)` to `t_end`, calling `observe` at `t0`
/// and after every accepted step; returns the final state and counters.
///
/// # Example
/// ```
/// use hdot_sim::{integrate, Method, Step, System, Limits};
/// struct Decay;
/// impl System<1> for Decay {
///     fn name(&self) -> &str { "decay" }
///     fn rhs(&self, _t: f64, y: &[f64; 1]) -> [f64; 1] { [-y[0]] }
/// }
/// let (y, stats) = integrate(&Decay, Method::Dop853, Step::Tolerance(1e-12),
///     0.0, [1.0], 1.0, Limits::default(), |_, _| Ok(())).unwrap();
/// assert!((y[0] - (-1.0f64).exp()).abs() < 1e-11);
/// assert!(stats.evaluations > 0);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn integrate<const N: usize, S, F>(
    sys: &S,
    method: Method,
    step: Step,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
    limits: Limits,
    mut observe: F,
) -> Result<([f64; N], Stats), SimError>
where
    S: System<N>,
    F: FnMut(f64, &[f64; N]) -> Result<(), SimError>,
{
    let step = step.validate()?;
    if !(t_end.is_finite() && t_end >= t0) {
        return Err(SimError::BadEndTime(t_end));
    }
    if y0.iter().any(|v| !v.is_finite()) {
        return Err(SimError::NonFinite { t: t0, step: 0 });
    }
    sys.check(t0, &y0)?;
    observe(t0, &y0)?;
    match (method, step) {
        (Method::Dopri5 | Method::Dop853, Step::Tolerance(tol)) => {
            adaptive(sys, method, tol, t0, y0, t_end, limits, observe)
        }
        (_, Step::Tolerance(_)) => Err(SimError::StepControl {
            method: method.name().into(),
            reason: "has a fixed step: give a step size (--dt), not a tolerance (--tol)".into(),
        }),
        (_, Step::Fixed(h)) => fixed(sys, method, h, t0, y0, t_end, limits, observe),
    }
}

#[inline]
fn finite_or<const N: usize>(y: &[f64; N], t: f64, step: u64) -> Result<(), SimError> {
    if y.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SimError::NonFinite { t, step })
    }
}

#[allow(clippy::too_many_arguments)]
fn fixed<const N: usize, S, F>(
    sys: &S,
    method: Method,
    h: f64,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
    limits: Limits,
    mut observe: F,
) -> Result<([f64; N], Stats), SimError>
where
    S: System<N>,
    F: FnMut(f64, &[f64; N]) -> Result<(), SimError>,
{
    let span = t_end - t0;
    let mut stats = Stats::default();
    if span == 0.0 {
        return Ok((y0, stats));
    }
    let n = fixed_step_count(span, h);
    if n > limits.max_steps {
        return Err(SimError::TooManySteps {
            max_steps: limits.max_steps,
            t: t0,
            t_end,
            accepted: 0,
            rejected: 0,
            run: String::new(),
        });
    }
    let h = span / n as f64;
    if matches!(method, Method::Split2 | Method::Split4) && sys.strang_step(t0, &y0, 0.0).is_none()
    {
        return Err(SimError::MethodNotApplicable {
            method: method.name().into(),
            model: sys.name().into(),
            reason: "it has no splitting into exactly solvable parts".into(),
        });
    }
    let mut y = y0;
    let mut k_prev: Option<[f64; N]> = None;
    for i in 0..n {
        let t = t0 + i as f64 * h;
        y = match method {
            Method::Euler => euler_step(sys, t, &y, h, &mut stats),
            Method::Rk4 => rk4_step(sys, t, &y, h, &mut stats),
            Method::Dopri5 => {
                let k1 = sys.rhs(t, &y);
                stats.evaluations += 1;
                dopri5_step(sys, t, &y, h, &k1, &mut stats).0
            }
            Method::Dop853 => {
                let k1 = sys.rhs(t, &y);
                stats.evaluations += 1;
                dop853_step(sys, t, &y, h, &k1, &mut stats).0
            }
            Method::Midpoint => midpoint_step(sys, t, &y, h, &mut k_prev, &mut stats)?,
            Method::Split2 => strang(sys, t, &y, h, &mut stats),
            Method::Split4 => {
                let g1 = 1.0 / (2.0 - 2f64.cbrt());
                let g2 = 1.0 - 2.0 * g1;
                let a = strang(sys, t, &y, g1 * h, &mut stats);
                let b = strang(sys, t + g1 * h, &a, g2 * h, &mut stats);
                strang(sys, t + (g1 + g2) * h, &b, g1 * h, &mut stats)
            }
        };
        stats.steps += 1;
        let t_new = if i + 1 == n { t_end } else { t + h };
        finite_or(&y, t_new, stats.steps)?;
        // Projection moves y by a little: the midpoint rule's previous slope
        // (k_prev) stays a good first guess and is kept.
        sys.project(&mut y);
        sys.check(t_new, &y)?;
        observe(t_new, &y)?;
    }
    Ok((y, stats))
}

#[inline]
fn strang<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    stats: &mut Stats,
) -> [f64; N] {
    let (z, flows) = sys
        .strang_step(t, y, h)
        .expect("checked before the loop: the model has a splitting");
    stats.evaluations += flows;
    z
}

#[inline]
fn euler_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    stats: &mut Stats,
) -> [f64; N] {
    let k = sys.rhs(t, y);
    stats.evaluations += 1;
    std::array::from_fn(|i| y[i] + h * k[i])
}

#[inline]
fn rk4_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    stats: &mut Stats,
) -> [f64; N] {
    let k1 = sys.rhs(t, y);
    let y2: [f64; N] = std::array::from_fn(|i| y[i] + 0.5 * h * k1[i]);
    let k2 = sys.rhs(t + 0.5 * h, &y2);
    let y3: [f64; N] = std::array::from_fn(|i| y[i] + 0.5 * h * k2[i]);
    let k3 = sys.rhs(t + 0.5 * h, &y3);
    let y4: [f64; N] = std::array::from_fn(|i| y[i] + h * k3[i]);
    let k4 = sys.rhs(t + h, &y4);
    stats.evaluations += 4;
    std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]))
}

/// Implicit midpoint `y₁ = y₀ + h f(t + h/2, (y₀ + y₁)/2)`, solved for the
/// stage slope `k` by fixed-point iteration until the update stops
/// shrinking at round-off level.
fn midpoint_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    k_prev: &mut Option<[f64; N]>,
    stats: &mut Stats,
) -> Result<[f64; N], SimError> {
    let mut k = match k_prev {
        Some(k) => *k,
        None => {
            stats.evaluations += 1;
            sys.rhs(t, y)
        }
    };
    let scale = y
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let mut prev = f64::INFINITY;
    let mut converged = false;
    for _ in 0..100 {
        let mid: [f64; N] = std::array::from_fn(|i| y[i] + 0.5 * h * k[i]);
        let k_new = sys.rhs(t + 0.5 * h, &mid);
        stats.evaluations += 1;
        let d = (0..N).fold(0.0_f64, |m, i| m.max((h * (k_new[i] - k[i])).abs()));
        k = k_new;
        if !d.is_finite() {
            break;
        }
        if d <= 2.0 * f64::EPSILON * scale {
            converged = true;
            break;
        }
        if d >= prev {
            // Stagnation: at round-off this is convergence, above it divergence.
            converged = d <= 1e3 * f64::EPSILON * scale;
            break;
        }
        prev = d;
    }
    if !converged {
        return Err(SimError::NotConverged { t, h });
    }
    *k_prev = Some(k);
    Ok(std::array::from_fn(|i| y[i] + h * k[i]))
}

/// One Dormand–Prince 5(4) step from `(t, y)` with `k1 = f(t, y)`.
/// Returns `ŷ`, `f(t + h, ŷ)` and the raw error vector `h Σ e_i k_i`.
#[inline]
fn dopri5_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    k1: &[f64; N],
    stats: &mut Stats,
) -> ([f64; N], [f64; N], [f64; N]) {
    let a = &DP5_A;
    let c = &DP5_C;
    let mut k = [[0.0; N]; 7];
    k[0] = *k1;
    for s in 1..6 {
        let ys: [f64; N] =
            std::array::from_fn(|i| y[i] + h * (0..s).map(|j| a[s - 1][j] * k[j][i]).sum::<f64>());
        k[s] = sys.rhs(t + c[s] * h, &ys);
    }
    let ynew: [f64; N] =
        std::array::from_fn(|i| y[i] + h * (0..6).map(|j| a[5][j] * k[j][i]).sum::<f64>());
    k[6] = sys.rhs(t + h, &ynew);
    stats.evaluations += 6;
    let err: [f64; N] =
        std::array::from_fn(|i| h * (0..7).map(|j| DP5_E[j] * k[j][i]).sum::<f64>());
    (ynew, k[6], err)
}

/// `y + h Σ c_j k_j` over the non-zero coefficients of one tableau row
/// (const-sized, so the loops unroll and no zero is multiplied).
#[inline(always)]
fn lin<const N: usize, const M: usize>(
    y: &[f64; N],
    h: f64,
    terms: [(f64, &[f64; N]); M],
) -> [f64; N] {
    std::array::from_fn(|i| {
        let mut acc = 0.0;
        for (c, k) in &terms {
            acc += c * k[i];
        }
        y[i] + h * acc
    })
}

/// One DOP853 step from `(t, y)` with `k1 = f(t, y)`. Returns `ŷ` and the
/// raw error vectors `(Σ e_j k_j, Σ b_j k_j − Σ b̂_j k_j)` of the fifth- and
/// third-order estimates (not yet multiplied by h); `f(t + h, ŷ)` is left
/// to the caller. The stages skip the zeros of the tableau (as `dop853.f`
/// does) and each sum is formed once.
#[inline]
fn dop853_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    k1: &[f64; N],
    stats: &mut Stats,
) -> ([f64; N], [f64; N], [f64; N]) {
    let a = &DP8_A;
    let c = &DP8_C;
    let k2 = sys.rhs(t + c[1] * h, &lin(y, h, [(a[0][0], k1)]));
    let k3 = sys.rhs(t + c[2] * h, &lin(y, h, [(a[1][0], k1), (a[1][1], &k2)]));
    let k4 = sys.rhs(t + c[3] * h, &lin(y, h, [(a[2][0], k1), (a[2][2], &k3)]));
    let k5 = sys.rhs(
        t + c[4] * h,
        &lin(y, h, [(a[3][0], k1), (a[3][2], &k3), (a[3][3], &k4)]),
    );
    let k6 = sys.rhs(
        t + c[5] * h,
        &lin(y, h, [(a[4][0], k1), (a[4][3], &k4), (a[4][4], &k5)]),
    );
    let k7 = sys.rhs(
        t + c[6] * h,
        &lin(
            y,
            h,
            [
                (a[5][0], k1),
                (a[5][3], &k4),
                (a[5][4], &k5),
                (a[5][5], &k6),
            ],
        ),
    );
    let k8 = sys.rhs(
        t + c[7] * h,
        &lin(
            y,
            h,
            [
                (a[6][0], k1),
                (a[6][3], &k4),
                (a[6][4], &k5),
                (a[6][5], &k6),
                (a[6][6], &k7),
            ],
        ),
    );
    let k9 = sys.rhs(
        t + c[8] * h,
        &lin(
            y,
            h,
            [
                (a[7][0], k1),
                (a[7][3], &k4),
                (a[7][4], &k5),
                (a[7][5], &k6),
                (a[7][6], &k7),
                (a[7][7], &k8),
            ],
        ),
    );
    let k10 = sys.rhs(
        t + c[9] * h,
        &lin(
            y,
            h,
            [
                (a[8][0], k1),
                (a[8][3], &k4),
                (a[8][4], &k5),
                (a[8][5], &k6),
                (a[8][6], &k7),
                (a[8][7], &k8),
                (a[8][8], &k9),
            ],
        ),
    );
    let k11 = sys.rhs(
        t + c[10] * h,
        &lin(
            y,
            h,
            [
                (a[9][0], k1),
                (a[9][3], &k4),
                (a[9][4], &k5),
                (a[9][5], &k6),
                (a[9][6], &k7),
                (a[9][7], &k8),
                (a[9][8], &k9),
                (a[9][9], &k10),
            ],
        ),
    );
    let k12 = sys.rhs(
        t + h,
        &lin(
            y,
            h,
            [
                (a[10][0], k1),
                (a[10][3], &k4),
                (a[10][4], &k5),
                (a[10][5], &k6),
                (a[10][6], &k7),
                (a[10][7], &k8),
                (a[10][8], &k9),
                (a[10][9], &k10),
                (a[10][10], &k11),
            ],
        ),
    );
    stats.evaluations += 11;
    let (b, e) = (&DP8_B, &DP8_E);
    let mut ynew = [0.0; N];
    let mut e5 = [0.0; N];
    let mut e3 = [0.0; N];
    for i in 0..N {
        // Stages 2–5 have zero weights in b and e.
        let bs = b[0] * k1[i]
            + b[5] * k6[i]
            + b[6] * k7[i]
            + b[7] * k8[i]
            + b[8] * k9[i]
            + b[9] * k10[i]
            + b[10] * k11[i]
            + b[11] * k12[i];
        e5[i] = e[0] * k1[i]
            + e[5] * k6[i]
            + e[6] * k7[i]
            + e[7] * k8[i]
            + e[8] * k9[i]
            + e[9] * k10[i]
            + e[10] * k11[i]
            + e[11] * k12[i];
        e3[i] = bs - DP8_BHH[0] * k1[i] - DP8_BHH[1] * k9[i] - DP8_BHH[2] * k12[i];
        ynew[i] = y[i] + h * bs;
    }
    (ynew, e5, e3)
}

/// DOP853's error norm (Hairer): a fifth-order estimate corrected by the
/// third-order one, `err = |h| e₅² / √(N (e₅² + 0.01 e₃²))` in scaled
/// squared norms, with `sc_i = tol (1 + max(|y_i|, |ŷ_i|))`.
#[inline]
fn dop853_error<const N: usize>(
    y: &[f64; N],
    ynew: &[f64; N],
    e5: &[f64; N],
    e3: &[f64; N],
    h: f64,
    tol: f64,
) -> f64 {
    let mut err = 0.0;
    let mut err2 = 0.0;
    for i in 0..N {
        let inv = 1.0 / (tol + tol * y[i].abs().max(ynew[i].abs()));
        err2 += (e3[i] * inv) * (e3[i] * inv);
        err += (e5[i] * inv) * (e5[i] * inv);
    }
    let mut deno = err + 0.01 * err2;
    if deno <= 0.0 {
        deno = 1.0;
    }
    h.abs() * err * (1.0 / (N as f64 * deno)).sqrt()
}

/// Hairer's `hinit`: a first step from the local behaviour of `f`.
#[allow(clippy::too_many_arguments)]
fn initial_step<const N: usize, S: System<N>>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    f0: &[f64; N],
    order: i32,
    tol: f64,
    hmax: f64,
    stats: &mut Stats,
) -> f64 {
    let sk: [f64; N] = std::array::from_fn(|i| tol + tol * y[i].abs());
    let dnf: f64 = (0..N).map(|i| (f0[i] / sk[i]).powi(2)).sum();
    let dny: f64 = (0..N).map(|i| (y[i] / sk[i]).powi(2)).sum();
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(hmax);
    let y1: [f64; N] = std::array::from_fn(|i| y[i] + h * f0[i]);
    let f1 = sys.rhs(t + h, &y1);
    stats.evaluations += 1;
    let der2 = (0..N)
        .map(|i| ((f1[i] - f0[i]) / sk[i]).powi(2))
        .sum::<f64>()
        .sqrt()
        / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / order as f64)
    };
    (100.0 * h).min(h1).min(hmax)
}

#[allow(clippy::too_many_arguments)]
fn adaptive<const N: usize, S, F>(
    sys: &S,
    method: Method,
    tol: f64,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
    limits: Limits,
    mut observe: F,
) -> Result<([f64; N], Stats), SimError>
where
    S: System<N>,
    F: FnMut(f64, &[f64; N]) -> Result<(), SimError>,
{
    let mut stats = Stats::default();
    if t_end == t0 {
        return Ok((y0, stats));
    }
    // (order of the estimate + 1 exponent, β, fac1, fac2, hinit order)
    let (expo, beta, fac1, fac2, iord) = match method {
        Method::Dopri5 => (0.2 - 0.04 * 0.75, 0.04, 0.2, 10.0, 5),
        _ => (1.0 / 8.0, 0.0, 0.333, 6.0, 8),
    };
    let safe = 0.9;
    let hmax = t_end - t0;
    let mut t = t0;
    let mut y = y0;
    let mut f = sys.rhs(t, &y);
    stats.evaluations += 1;
    let mut h = initial_step(sys, t, &y, &f, iord, tol, hmax, &mut stats);
    let mut facold: f64 = 1e-4;
    let mut last_rejected = false;
    loop {
        if stats.steps + stats.rejected >= limits.max_steps {
            return Err(SimError::TooManySteps {
                max_steps: limits.max_steps,
                t,
                t_end,
                accepted: stats.steps,
                rejected: stats.rejected,
                run: String::new(),
            });
        }
        let last = t + 1.01 * h >= t_end;
        if last {
            h = t_end - t;
        }
        // A step lost in t's round-off (on the run's own scale: a run of
        // 1e-15 takes steps of 1e-15).
        if h.abs() <= 10.0 * f64::EPSILON * t.abs().max(hmax.abs().min(1.0)) {
            return Err(SimError::StepSizeUnderflow { t, h });
        }
        let (ynew, fnew_opt, err) = match method {
            Method::Dopri5 => {
                let (ynew, fnew, e) = dopri5_step(sys, t, &y, h, &f, &mut stats);
                let mut s = 0.0;
                for i in 0..N {
                    let sk = tol + tol * y[i].abs().max(ynew[i].abs());
                    s += (e[i] / sk).powi(2);
                }
                (ynew, Some(fnew), (s / N as f64).sqrt())
            }
            _ => {
                let (ynew, e5, e3) = dop853_step(sys, t, &y, h, &f, &mut stats);
                let e = dop853_error(&y, &ynew, &e5, &e3, h, tol);
                (ynew, None, e)
            }
        };
        if !err.is_finite() {
            // Treat as a large error: shrink strongly.
            h *= 0.1;
            stats.rejected += 1;
            last_rejected = true;
            continue;
        }
        // err^(1/8) by three square roots (DOP853), else powf.
        let fac11 = if method == Method::Dop853 {
            err.sqrt().sqrt().sqrt()
        } else {
            err.powf(expo)
        };
        let pi = if beta == 0.0 { 1.0 } else { facold.powf(beta) };
        let fac = (fac11 / pi / safe).clamp(1.0 / fac2, 1.0 / fac1);
        let mut hnew = h / fac;
        if err <= 1.0 {
            facold = err.max(1e-4);
            t = if last { t_end } else { t + h };
            y = ynew;
            stats.steps += 1;
            finite_or(&y, t, stats.steps)?;
            let projected = sys.project(&mut y);
            f = match fnew_opt {
                Some(fnew) if !projected => fnew,
                _ => {
                    stats.evaluations += 1;
                    sys.rhs(t, &y)
                }
            };
            sys.check(t, &y)?;
            observe(t, &y)?;
            if last {
                return Ok((y, stats));
            }
            hnew = hnew.min(hmax);
            if last_rejected {
                hnew = hnew.min(h);
            }
            last_rejected = false;
            h = hnew;
        } else {
            h /= (1.0 / fac1).min(fac11 / safe);
            stats.rejected += 1;
            last_rejected = true;
        }
    }
}
