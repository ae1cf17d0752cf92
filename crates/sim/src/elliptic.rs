//! Jacobi elliptic functions and complete/incomplete elliptic integrals of
//! the first kind, written here (no dependency) to round-off accuracy.
//!
//! Parameter convention: `m = k²` (the "parameter"), as in Abramowitz &
//! Stegun ch. 16–17.
//!
//! * [`ellip_k`], [`ellip_k_c`]: `K(m) = π / (2 AGM(1, √(1−m)))`.
//! * [`Jacobi`] (and [`sncndn`]): sn, cn, dn by the descending Landen
//!   transformation driven by the arithmetic–geometric mean (A&S 16.4) for
//!   `m ≤ 1/2` and the ascending one (A&S 16.14) above, carrying `1 − m`
//!   separately so that parameters within 1e-300 of 1 keep their digits.
//! * [`ellip_f`]: `F(φ | m)` through Carlson's symmetric integral `R_F`
//!   (duplication theorem), extended to every real φ by quasi-periodicity.
//!
//! # Example
//! ```
//! use hdot_sim::elliptic::{ellip_k, sncndn};
//! let m = 0.5;
//! let (sn, cn, dn) = sncndn(ellip_k(m), m);
//! assert!((sn - 1.0).abs() < 4.0 * f64::EPSILON);
//! assert!(cn.abs() < 8.0 * f64::EPSILON);
//! assert!((dn - (1.0 - m).sqrt()).abs() < 4.0 * f64::EPSILON);
//! ```

use std::f64::consts::FRAC_PI_2;

/// Largest number of AGM iterations (convergence is quadratic: 6–8 suffice).
const MAX_AGM: usize = 40;

/// Arithmetic–geometric mean of `a` and `b` (both ≥ 0).
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..MAX_AGM {
        if (a - b).abs() <= 2.0 * f64::EPSILON * a {
            break;
        }
        let an = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = an;
    }
    0.5 * (a + b)
}

/// Complete elliptic integral of the first kind `K(m)`, `0 ≤ m < 1`.
/// Returns `+∞` at `m = 1`. Near `m = 1` prefer [`ellip_k_c`], which takes
/// the complementary parameter `1 − m` itself.
pub fn ellip_k(m: f64) -> f64 {
    debug_assert!((0.0..=1.0).contains(&m), "parameter m = {m} outside [0, 1]");
    ellip_k_c(1.0 - m)
}

/// `K` from the complementary parameter `m_c = 1 − m` (accurate for every
/// `m_c`, including the tiny values `1 − m` cannot carry): `π / (2 AGM(1, √m_c))`.
pub fn ellip_k_c(mc: f64) -> f64 {
    if mc <= 0.0 {
        return f64::INFINITY;
    }
    FRAC_PI_2 / agm(1.0, mc.sqrt())
}

/// Jacobi elliptic functions `(sn, cn, dn)(u | m)` for `0 ≤ m ≤ 1`. Near
/// `m = 1` use [`Jacobi`] with the complementary parameter.
pub fn sncndn(u: f64, m: f64) -> (f64, f64, f64) {
    debug_assert!((0.0..=1.0).contains(&m), "parameter m = {m} outside [0, 1]");
    Jacobi::new(m, 1.0 - m).eval(u)
}

/// The Jacobi elliptic functions for one parameter, given as the pair
/// `(m, m_c = 1 − m)` so that both can be carried to full relative
/// accuracy (the distance of a torque-free motion from its separatrix lives
/// in `m_c`, which may be far below the spacing of doubles near 1).
///
/// * `m ≤ 1/2`: descending Landen transformation driven by the AGM (A&S
///   16.4); every ratio `c_n / a_n` is at most 0.18, so the `asin` steps are
///   well conditioned.
/// * `m > 1/2`: `u` is reduced to `[0, K/2]` by the half- and quarter-period
///   relations (A&S 16.8: `sn(K − s) = cd s`, `cn(K − s) = k' sd s`,
///   `dn(K − s) = k' nd s`), then the ascending Landen (Gauss)
///   transformation (A&S 16.14) drives `m_c` to below 1e-12 (it squares
///   roughly every step) where the first-order hyperbolic forms (A&S 16.15)
///   are exact to round-off. Every step multiplies, divides or adds
///   positive numbers (the one difference `dn² − √μ₁` is at least half its
///   first term on `[0, K/4]`), so relative accuracy is kept.
/// * `m_c = 0`: the separatrix, `sn = tanh`, `cn = dn = sech`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobi {
    /// Parameter `m`.
    pub m: f64,
    /// Complementary parameter `1 − m`.
    pub mc: f64,
    /// Quarter period `K` (∞ on the separatrix).
    pub k: f64,
}

impl Jacobi {
    /// The functions of parameter `m`, `m_c = 1 − m` (both in `[0, 1]`;
    /// `m_c` is trusted where it is small, `m` where it is small).
    pub fn new(m: f64, mc: f64) -> Jacobi {
        Jacobi {
            m,
            mc,
            k: ellip_k_c(mc),
        }
    }

    /// `(sn, cn, dn)(u)`.
    pub fn eval(&self, u: f64) -> (f64, f64, f64) {
        let (m, mc) = (self.m, self.mc);
        if mc <= 0.0 {
            let sech = 1.0 / u.cosh();
            return (u.tanh(), sech, sech);
        }
        if m < f64::EPSILON {
            // The series in m would start at m·(u − sin u cos u)/4: below round-off.
            let (s, c) = u.sin_cos();
            return (s, c, 1.0);
        }
        if m <= 0.5 {
            return descending(u, m, mc);
        }
        let k = self.k;
        // u = 2K n + r, |r| ≤ K: sn, cn change sign with n, dn does not.
        let n = (u / (2.0 * k)).round();
        let r = u - 2.0 * k * n;
        let flip = if n.rem_euclid(2.0) == 1.0 { -1.0 } else { 1.0 };
        let sgn = if r < 0.0 { -1.0 } else { 1.0 };
        let r = r.abs();
        let (sn, cn, dn) = if r <= 0.5 * k {
            ascending(r, m, mc)
        } else {
            let (s, c, d) = ascending(k - r, m, mc);
            let kp = mc.sqrt();
            (c / d, kp * s / d, kp / d)
        };
        (flip * sgn * sn, flip * cn, dn)
    }

    /// The argument `u ∈ [−2K, 2K]` with the given `(sn, cn, dn)` (which
    /// must satisfy the identities), from Carlson's `R_F`:
    /// `F(φ|m) = sin φ R_F(cos² φ, dn², 1)`; the squares come straight from
    /// the values, so `u` is as accurate as they are even where
    /// `dF/dφ = 1/dn` is large.
    pub fn arg(&self, sn: f64, cn: f64, dn: f64) -> f64 {
        let f = sn * carlson_rf(cn * cn, dn * dn, 1.0);
        if cn >= 0.0 {
            f
        } else {
            sn.signum() * 2.0 * self.k - f
        }
    }
}

fn descending(u: f64, m: f64, mc: f64) -> (f64, f64, f64) {
    // Descending Landen: a_n, c_n of the AGM sequence starting at (1, √(1−m)).
    let mut a = [0.0_f64; MAX_AGM + 1];
    let mut c = [0.0_f64; MAX_AGM + 1];
    a[0] = 1.0;
    let mut b = mc.sqrt();
    c[0] = m.sqrt();
    let mut n = 0;
    while n < MAX_AGM && c[n].abs() > f64::EPSILON * a[n] {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    // φ_N = 2^N a_N u, then back: φ_{n−1} = (φ_n + asin(c_n/a_n sin φ_n)) / 2.
    let mut phi = f64::powi(2.0, n as i32) * a[n] * u;
    for j in (1..=n).rev() {
        phi = 0.5 * (phi + (c[j] / a[j] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    // dn² = 1 − m sn² = (1 − m) + m cn²: two non-negative terms, no cancellation.
    let dn = (mc + m * cn * cn).sqrt();
    (sn, cn, dn)
}

/// `(sn, cn, dn)(v | m)` for `0 ≤ v ≤ K(m)/2`, `m ≥ 1/2`, by the ascending
/// Landen transformation; see [`Jacobi`].
fn ascending(v: f64, m: f64, mc: f64) -> (f64, f64, f64) {
    if mc.is_nan() || m.is_nan() {
        // Not a parameter: no transformation would reach m_c < 1e-12.
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    if mc < 1e-12 {
        // A&S 16.15: first order in m_c; the next term is O(m_c² e^{4v}),
        // below round-off for v ≤ K/2 (e^{2v} ≤ 4/√m_c).
        let (sh, ch) = (v.sinh(), v.cosh());
        let (th, sech) = (sh / ch, 1.0 / ch);
        let q = 0.25 * mc;
        return (
            th + q * (sh * ch - v) * sech * sech,
            sech - q * (sh * ch - v) * th * sech,
            sech + q * (sh * ch + v) * th * sech,
        );
    }
    let k = m.sqrt();
    // √μ₁ = (1 − k)/(1 + k) with 1 − k = m_c/(1 + k): no cancellation.
    let s1 = mc / ((1.0 + k) * (1.0 + k));
    let mu1 = s1 * s1;
    let mu = 4.0 * k / ((1.0 + k) * (1.0 + k));
    let (s, c, d) = ascending(v / (1.0 + s1), mu, mu1);
    (
        (1.0 + s1) * s * c / d,
        (1.0 + s1) / mu * (d * d - s1) / d,
        (1.0 - s1) / mu * (d * d + s1) / d,
    )
}

/// Carlson's symmetric elliptic integral of the first kind
/// `R_F(x, y, z)`, `x, y, z ≥ 0`, at most one of them zero.
pub fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    // Duplication until the arguments agree to ~1e-3; the fifth-order
    // series then leaves an error of order (1e-3)^6.
    for _ in 0..100 {
        let a = (x + y + z) / 3.0;
        let dx = 1.0 - x / a;
        let dy = 1.0 - y / a;
        let dz = 1.0 - z / a;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / a.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
    (x * y * z).powf(-1.0 / 6.0)
}

/// Incomplete elliptic integral of the first kind `F(φ | m)` for every real
/// φ and `0 ≤ m < 1`; it inverts the amplitude: `sn(F(φ|m) | m) = sin φ`.
pub fn ellip_f(phi: f64, m: f64) -> f64 {
    ellip_f_c(phi, 1.0 - m)
}

/// [`ellip_f`] with the complementary parameter `m_c = 1 − m` given
/// (`1 − m sin² φ = cos² φ + m_c sin² φ`, two non-negative terms).
pub fn ellip_f_c(phi: f64, mc: f64) -> f64 {
    // φ = jπ + r with |r| ≤ π/2; F(jπ + r) = 2jK + F(r).
    let j = (phi / std::f64::consts::PI).round();
    let r = phi - j * std::f64::consts::PI;
    let (s, c) = r.sin_cos();
    let fr = s * carlson_rf(c * c, c * c + mc * s * s, 1.0);
    if j == 0.0 {
        fr
    } else {
        2.0 * j * ellip_k_c(mc) + fr
    }
}
