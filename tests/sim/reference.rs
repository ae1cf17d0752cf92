//! A high-precision reference for the torque-free body, independent of the
//! closed form: Taylor series of order 40 of Euler's equations and the
//! quaternion kinematics in double-double arithmetic (about 32 digits),
//! coefficients by the usual recurrences for products of series
//! (Jorba & Zou, *A software package for the numerical integration of ODEs
//! by means of high-order Taylor methods*, 2005), step from the decay of the
//! last coefficients so that the truncation stays below 1e-30.

use hdot_sim::dd::Dd;

const ORDER: usize = 40;

/// Quaternion `[w, x, y, z]` and body ω in double-double.
#[derive(Clone, Copy)]
pub struct DdState {
    pub q: [Dd; 4],
    pub w: [Dd; 3],
}

impl DdState {
    pub fn new(q: [f64; 4], w: [f64; 3]) -> Self {
        DdState {
            q: q.map(Dd::from_f64),
            w: w.map(Dd::from_f64),
        }
    }

    /// `[q, ω]` rounded to f64.
    pub fn to_f64(self) -> [f64; 7] {
        let mut y = [0.0; 7];
        for (dst, src) in y.iter_mut().zip(self.q.iter().chain(self.w.iter())) {
            *dst = src.to_f64();
        }
        y
    }
}

/// Integrates `I ω̇ = (I ω) × ω`, `q̇ = ½ q ⊗ (0, ω)` from `y0` over `[0, t]`.
pub fn torque_free(moments: [f64; 3], y0: DdState, t: f64) -> DdState {
    let i = moments;
    // c_k = (I_{k+1} − I_{k+2}) / I_k, the difference exact.
    let c: [Dd; 3] =
        std::array::from_fn(|k| Dd::diff(i[(k + 1) % 3], i[(k + 2) % 3]) / Dd::from_f64(i[k]));
    let mut y = y0;
    let mut time = Dd::ZERO;
    let t_end = Dd::from_f64(t);
    let mut wc = vec![[Dd::ZERO; 3]; ORDER + 1];
    let mut qc = vec![[Dd::ZERO; 4]; ORDER + 1];
    loop {
        let left = (t_end - time).to_f64();
        if left <= 0.0 {
            return y;
        }
        wc[0] = y.w;
        qc[0] = y.q;
        for k in 0..ORDER {
            let inv = Dd::ONE / Dd::from_f64((k + 1) as f64);
            let mut wn = [Dd::ZERO; 3];
            for (a, wn_a) in wn.iter_mut().enumerate() {
                let (b, d) = ((a + 1) % 3, (a + 2) % 3);
                let mut s = Dd::ZERO;
                for j in 0..=k {
                    s = s + wc[j][b] * wc[k - j][d];
                }
                *wn_a = c[a] * s * inv;
            }
            let mut qn = [Dd::ZERO; 4];
            for j in 0..=k {
                let p = qc[j];
                let v = wc[k - j];
                // p ⊗ (0, v) = (−p⃗·v, p₀ v + p⃗ × v)
                qn[0] = qn[0] - (p[1] * v[0] + p[2] * v[1] + p[3] * v[2]);
                qn[1] = qn[1] + p[0] * v[0] + (p[2] * v[2] - p[3] * v[1]);
                qn[2] = qn[2] + p[0] * v[1] + (p[3] * v[0] - p[1] * v[2]);
                qn[3] = qn[3] + p[0] * v[2] + (p[1] * v[1] - p[2] * v[0]);
            }
            let half = inv * Dd::from_f64(0.5);
            wc[k + 1] = wn;
            qc[k + 1] = qn.map(|x| x * half);
        }
        // Radius of convergence from the last two orders; truncation
        // (h/ρ)^ORDER ≤ 1e-31 relative.
        let norm = |k: usize| {
            let w = wc[k].iter().map(|x| x.hi.abs()).fold(0.0, f64::max);
            let q = qc[k].iter().map(|x| x.hi.abs()).fold(0.0, f64::max);
            w.max(q)
        };
        let scale = norm(0).max(1e-300);
        let rho = [ORDER - 1, ORDER]
            .iter()
            .map(|&k| (scale / norm(k).max(1e-300)).powf(1.0 / k as f64))
            .fold(f64::INFINITY, f64::min);
        let h = (0.17 * rho).min(left);
        let hd = if h == left {
            t_end - time
        } else {
            Dd::from_f64(h)
        };
        // Horner.
        let mut w = wc[ORDER];
        let mut q = qc[ORDER];
        for k in (0..ORDER).rev() {
            for a in 0..3 {
                w[a] = w[a] * hd + wc[k][a];
            }
            for a in 0..4 {
                q[a] = q[a] * hd + qc[k][a];
            }
        }
        y = DdState { q, w };
        time = time + hd;
    }
}

/// Rotation angle between the attitudes plus `|Δω| / |ω|`: the error
/// measure of the exact solution.
pub fn attitude_rate_error(a: &[f64; 7], b: &[f64; 7]) -> f64 {
    use hdot_sim::nalgebra::{Quaternion, UnitQuaternion, Vector3};
    let qa = UnitQuaternion::from_quaternion(Quaternion::new(a[0], a[1], a[2], a[3]));
    let qb = UnitQuaternion::from_quaternion(Quaternion::new(b[0], b[1], b[2], b[3]));
    // 2 atan2(|v|, |w|): `angle()` goes through acos, √ε near zero.
    let d = qa.rotation_to(&qb);
    let angle = 2.0 * d.imag().norm().atan2(d.scalar().abs());
    let wa = Vector3::new(a[4], a[5], a[6]);
    let wb = Vector3::new(b[4], b[5], b[6]);
    angle + (wa - wb).norm() / wb.norm().max(f64::MIN_POSITIVE)
}
