//! Jacobi elliptic functions and complete/incomplete elliptic integrals of
//! the first kind, written here (no dependency) to round-off accuracy.
//!
//! Parameter convention: `m = k²` (the "parameter"), as in Abramowitz &
//! Stegun ch. 16–17.
//!
//! * [`ellip_k`]: `K(m) = π / (2 AGM(1, √(1−m)))`.
//! * [`sncndn`]: sn, cn, dn by the descending Landen transformation driven by
//!   the arithmetic–geometric mean (A&S 16.4).
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
/// Returns `+∞` at `m = 1`.
pub fn ellip_k(m: f64) -> f64 {
    debug_assert!((0.0..=1.0).contains(&m), "parameter m = {m} outside [0, 1]");
    if m >= 1.0 {
        return f64::INFINITY;
    }
    FRAC_PI_2 / agm(1.0, (1.0 - m).sqrt())
}

/// Jacobi elliptic functions `(sn, cn, dn)(u | m)` for `0 ≤ m ≤ 1`.
pub fn sncndn(u: f64, m: f64) -> (f64, f64, f64) {
    debug_assert!((0.0..=1.0).contains(&m), "parameter m = {m} outside [0, 1]");
    if m < f64::EPSILON {
        // The series in m would start at m·(u − sin u cos u)/4: below round-off.
        let (s, c) = u.sin_cos();
        return (s, c, 1.0);
    }
    if m > 1.0 - f64::EPSILON {
        let sech = 1.0 / u.cosh();
        return (u.tanh(), sech, sech);
    }
    // Descending Landen: a_n, c_n of the AGM sequence starting at (1, √(1−m)).
    let mut a = [0.0_f64; MAX_AGM + 1];
    let mut c = [0.0_f64; MAX_AGM + 1];
    a[0] = 1.0;
    let mut b = (1.0 - m).sqrt();
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
    let dn = ((1.0 - m) + m * cn * cn).sqrt();
    (sn, cn, dn)
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
    // φ = jπ + r with |r| ≤ π/2; F(jπ + r) = 2jK + F(r).
    let j = (phi / std::f64::consts::PI).round();
    let r = phi - j * std::f64::consts::PI;
    let (s, c) = r.sin_cos();
    let fr = s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
    if j == 0.0 {
        fr
    } else {
        2.0 * j * ellip_k(m) + fr
    }
}
