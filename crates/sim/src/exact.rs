//! Motions known in closed form: the torque-free body (permanent rotation,
//! axisymmetric steady precession of §9, asymmetric body through Jacobi
//! elliptic functions), and the heavy top in steady precession (§7).
//!
//! For the asymmetric body, ω(t) is closed form (`cn`, `sn`, `dn`); the
//! attitude is closed form up to the angle φ of rotation about the fixed
//! `H`, whose rate depends on `dn²` only and which is therefore the integral
//! of a smooth periodic function. That integral is evaluated by quadrature
//! (composite 20-point Gauss–Legendre, 16 panels per period, whole periods
//! counted once), not by integrating the attitude kinematics: the result is
//! at round-off level and costs no step-size choice.

use std::sync::OnceLock;

use nalgebra::{Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};

use crate::SimError;
use crate::dd::Dd;
use crate::elliptic::Jacobi;
use crate::systems::euler_angles::quaternion_from_angles;
use crate::systems::free::pack;

/// The exact torque-free motion from a given initial state.
#[derive(Debug, Clone)]
pub enum TorqueFree {
    /// Spin about a principal axis (or any axis of a sphere): ω constant.
    Permanent {
        /// Initial attitude.
        q0: UnitQuaternion<f64>,
        /// The constant body angular velocity.
        omega: Vector3<f64>,
    },
    /// Axisymmetric body: steady precession about `H` (§9).
    Axisymmetric(Axisymmetric),
    /// Asymmetric body: Jacobi elliptic functions.
    Elliptic(Box<Elliptic>),
}

/// Axisymmetric torque-free body: `R(t) = Rot(Ĥ, |H| t / I') R₀ Rot(e_s, σ t)`
/// with `σ = H_s (I' − I) / (I I')`.
#[derive(Debug, Clone)]
pub struct Axisymmetric {
    moments: [f64; 3],
    axis: usize,
    q0: UnitQuaternion<f64>,
    h_space: Vector3<f64>,
    /// Precession rate `φ̇ = |H| / I'`.
    pub precession_rate: f64,
    /// Spin rate relative to the precessing frame, `ψ̇ = H cos θ (I' − I)/(I I')`.
    pub spin_rate: f64,
    /// Nutation angle between `H` and the symmetry axis (constant).
    pub nutation: f64,
}

/// Asymmetric torque-free body, see the module docs.
#[derive(Debug, Clone)]
pub struct Elliptic {
    moments: [f64; 3],
    /// Labels: `lab[0]` the extreme axis carrying cn, `lab[1]` the
    /// intermediate axis carrying sn, `lab[2]` the axis `H` circulates about.
    lab: [usize; 3],
    amp: [f64; 3],
    lambda: f64,
    /// Parameter `m = k²`.
    pub m: f64,
    /// Complementary parameter `1 − m` (0 on the separatrix), computed from
    /// the components, not as a difference.
    pub mc: f64,
    jacobi: Jacobi,
    u0: f64,
    /// Period `2K` of the φ̇ integrand in u (∞ on the separatrix).
    period: f64,
    /// Panels of `[0, 2K]` chosen from the integrand (start, ∫ up to start).
    panels: Vec<(f64, f64)>,
    /// `G(2K)`: the φ-integral over one period.
    period_integral: f64,
    g_u0: f64,
    l: f64,
    /// Constant rotation `R₀ P R_zf(0)ᵀ` and the axis permutation `P`.
    c_rot: UnitQuaternion<f64>,
    perm: UnitQuaternion<f64>,
}

/// `L² − 2E I_j = Σ_i I_i (I_i − I_j) ω_i²` in double-double: the term
/// `i = j` vanishes, the differences of moments and the products are exact,
/// so the sign and the leading digits are right however close the motion
/// is to the separatrix (`j` intermediate) or to a permanent rotation.
pub fn momentum_energy_gap(moments: [f64; 3], w: &Vector3<f64>, j: usize) -> Dd {
    let mut s = Dd::ZERO;
    for i in 0..3 {
        if i == j {
            continue;
        }
        let d = Dd::diff(moments[i], moments[j]);
        s = s + d.scale(moments[i]) * Dd::prod(w[i], w[i]);
    }
    s
}

fn gauss_legendre_20() -> &'static ([f64; 20], [f64; 20]) {
    static NODES: OnceLock<([f64; 20], [f64; 20])> = OnceLock::new();
    NODES.get_or_init(|| {
        let n = 20;
        let mut x = [0.0; 20];
        let mut w = [0.0; 20];
        for i in 0..n {
            let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                // Legendre recurrence for P_n(z) and its derivative.
                let (mut p0, mut p1) = (1.0, z);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                if dz.abs() <= 1e-16 {
                    break;
                }
            }
            x[i] = z;
            w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
        (x, w)
    })
}

/// `R_Z(φ) R_X(θ) R_Z(ψ)`, whose third column is the direction of the
/// body momentum `hp` given in the cyclic body frame `(p, q, c)`: θ is the
/// angle between H and the c axis, ψ its azimuth, φ the angle turned about
/// H. θ by `atan2` (accurate near 0 and π, where `acos` loses digits).
pub(crate) fn invariable_frame(hp: &Vector3<f64>, phi: f64) -> UnitQuaternion<f64> {
    let theta = hp.x.hypot(hp.y).atan2(hp.z);
    let psi = hp.x.atan2(hp.y);
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), theta)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), psi)
}

/// The permutation taking the coordinates of a cyclic relabelling
/// `(p, q, c)` of the body axes to body coordinates (a rotation).
pub(crate) fn cyclic_perm(c: usize) -> UnitQuaternion<f64> {
    let p = (c + 1) % 3;
    let q = (c + 2) % 3;
    let mut m = Matrix3::zeros();
    m[(p, 0)] = 1.0;
    m[(q, 1)] = 1.0;
    m[(c, 2)] = 1.0;
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
}

/// # Construction
impl TorqueFree {
    /// The exact motion for principal moments `moments` from attitude `q0`
    /// and body angular velocity `w0`. Picks the permanent rotation, the
    /// axisymmetric or the elliptic form, whichever applies.
    pub fn new(
        moments: [f64; 3],
        q0: UnitQuaternion<f64>,
        w0: Vector3<f64>,
    ) -> Result<Self, SimError> {
        let i = unit_scale(moments);
        // Permanent rotation: ω ∥ H exactly (ω along a principal axis, or a
        // sphere). A spin merely close to an axis is not permanent: near the
        // intermediate axis it flips, so the elliptic form takes it.
        let nonzero = (0..3).filter(|&k| w0[k] != 0.0).count();
        if nonzero <= 1 || (i[0] == i[1] && i[1] == i[2]) {
            return Ok(TorqueFree::Permanent { q0, omega: w0 });
        }
        // Only exactly equal moments make the body axisymmetric: nearly
        // equal ones are an elliptic motion with m → 0, which the elliptic
        // form evaluates to round-off (treating them as equal would err by
        // the relative difference of the moments times |ω| t).
        let close = |a: f64, b: f64| a.total_cmp(&b).is_eq();
        let axis = if close(i[0], i[1]) {
            Some(2)
        } else if close(i[1], i[2]) {
            Some(0)
        } else if close(i[0], i[2]) {
            Some(1)
        } else {
            None
        };
        if let Some(s) = axis {
            return Ok(TorqueFree::Axisymmetric(Axisymmetric::new(i, s, q0, w0)));
        }
        Ok(TorqueFree::Elliptic(Box::new(Elliptic::new(i, q0, w0)?)))
    }

    /// Forces the elliptic form (for an asymmetric body: what `new` gives).
    pub fn elliptic(
        moments: [f64; 3],
        q0: UnitQuaternion<f64>,
        w0: Vector3<f64>,
    ) -> Result<Elliptic, SimError> {
        Elliptic::new(moments, q0, w0)
    }
}

/// The moments scaled by a power of two (exactly) into a range where
/// their products of three stay finite, when they are not there already:
/// the torque-free motion depends on their ratios only.
fn unit_scale(moments: [f64; 3]) -> [f64; 3] {
    let imax = moments[0].max(moments[1]).max(moments[2]);
    if !(imax.is_finite() && imax > 0.0) || (1e-50..=1e50).contains(&imax) {
        return moments;
    }
    let s = 2f64.powi(-(imax.log2().round() as i32));
    moments.map(|m| m * s)
}

/// # Evaluation
impl TorqueFree {
    /// The state `[q, ω]` at time `t`.
    pub fn state(&self, t: f64) -> [f64; 7] {
        match self {
            TorqueFree::Permanent { q0, omega } => {
                let n = omega.norm();
                let q = if n == 0.0 {
                    *q0
                } else {
                    q0 * UnitQuaternion::from_axis_angle(&Unit::new_unchecked(omega / n), n * t)
                };
                pack(&q, omega)
            }
            TorqueFree::Axisymmetric(a) => a.state(t),
            TorqueFree::Elliptic(e) => e.state(t),
        }
    }

    /// Name of the closed form used.
    pub fn form(&self) -> &'static str {
        match self {
            TorqueFree::Permanent { .. } => "permanent rotation about a principal axis",
            TorqueFree::Axisymmetric(_) => "steady precession (axisymmetric, trigonometric)",
            TorqueFree::Elliptic(_) => "Jacobi elliptic functions (asymmetric)",
        }
    }
}

impl Axisymmetric {
    fn new(moments: [f64; 3], axis: usize, q0: UnitQuaternion<f64>, w0: Vector3<f64>) -> Self {
        let i_axial = moments[axis];
        let i_trans = moments[(axis + 1) % 3];
        let h_body = Vector3::new(moments[0] * w0.x, moments[1] * w0.y, moments[2] * w0.z);
        let l = h_body.norm();
        let h_space = q0 * h_body;
        let hs = h_body[axis];
        Axisymmetric {
            moments,
            axis,
            q0,
            h_space,
            precession_rate: l / i_trans,
            spin_rate: hs * (i_trans - i_axial) / (i_axial * i_trans),
            nutation: (hs / l).clamp(-1.0, 1.0).acos(),
        }
    }

    fn state(&self, t: f64) -> [f64; 7] {
        let l = self.h_space.norm();
        let hhat = Unit::new_unchecked(self.h_space / l);
        let e = Vector3::ith_axis(self.axis);
        let q = UnitQuaternion::from_axis_angle(&hhat, self.precession_rate * t)
            * self.q0
            * UnitQuaternion::from_axis_angle(&e, self.spin_rate * t);
        let m = q.inverse() * self.h_space;
        let w = Vector3::new(
            m.x / self.moments[0],
            m.y / self.moments[1],
            m.z / self.moments[2],
        );
        pack(&q, &w)
    }
}

impl Elliptic {
    fn new(moments: [f64; 3], q0: UnitQuaternion<f64>, w0: Vector3<f64>) -> Result<Self, SimError> {
        let i = moments;
        let l2: f64 = (0..3).map(|k| (i[k] * w0[k]).powi(2)).sum();
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&a, &b| i[a].total_cmp(&i[b]));
        let (lo, mid, hi) = (idx[0], idx[1], idx[2]);
        if i[lo] == i[hi] || i[mid] == i[lo] || i[mid] == i[hi] {
            return Err(SimError::BadInertia {
                moments: i,
                message: "the elliptic solution needs three distinct moments".into(),
            });
        }
        // H circulates about the largest axis if L² > 2E I_mid, else the
        // smallest; the sign of L² − 2E I_mid comes from the components.
        let d_mid = momentum_energy_gap(i, &w0, mid);
        let (c, e) = if d_mid.hi >= 0.0 { (hi, lo) } else { (lo, hi) };
        let lab = [e, mid, c];
        let parity = if (e + 1) % 3 == mid { 1.0 } else { -1.0 };
        let (i1, i2, i3) = (i[e], i[mid], i[c]);
        // D_j = L² − 2E I_j; D_1 and −D_3 have the sign of I_3 − I_1.
        let d1 = momentum_energy_gap(i, &w0, e);
        let d3 = momentum_energy_gap(i, &w0, c);
        let (i31, i32) = (Dd::diff(i3, i1).to_f64(), Dd::diff(i3, i2).to_f64());
        let a1 = (-(d3.to_f64()) / (i1 * i31)).max(0.0).sqrt();
        let a3 = (d1.to_f64() / (i3 * i31)).max(0.0).sqrt() * w0[c].signum();
        let lambda = (i32 * d1.to_f64() / (i1 * i2 * i3)).max(0.0).sqrt();
        // m = (I₂−I₁)(−D₃) / ((I₃−I₂) D₁), 1 − m = (I₃−I₁) D₂ / ((I₃−I₂) D₁):
        // both ratios of accurately known quantities.
        let den = Dd::diff(i3, i2) * d1;
        let m = ((Dd::diff(i2, i1) * (-d3)) / den).to_f64().clamp(0.0, 1.0);
        let mc = ((Dd::diff(i3, i1) * d_mid) / den).to_f64().clamp(0.0, 1.0);
        // On the separatrix cn = dn > 0: the branch is chosen by a₁'s sign.
        let a1 = if mc == 0.0 { a1 * w0[e].signum() } else { a1 };
        let a2 = parity * i31 * a3 * a1 / (lambda * i2);
        let jacobi = Jacobi::new(m, mc);
        // u₀ from the initial (sn, cn, dn), each a ratio of a component to
        // its amplitude; see `Jacobi::arg`.
        let ratio = |w: f64, a: f64| {
            if a == 0.0 {
                0.0
            } else {
                (w / a).clamp(-1.0, 1.0)
            }
        };
        let (sn0, cn0, dn0) = (ratio(w0[mid], a2), ratio(w0[e], a1), ratio(w0[c], a3).abs());
        let u0 = jacobi.arg(sn0, cn0, dn0);
        let mut s = Elliptic {
            moments,
            lab,
            amp: [a1, a2, a3],
            lambda,
            m,
            mc,
            jacobi,
            u0,
            period: 2.0 * jacobi.k,
            panels: vec![],
            period_integral: 0.0,
            g_u0: 0.0,
            l: l2.sqrt(),
            c_rot: UnitQuaternion::identity(),
            perm: cyclic_perm(c),
        };
        if s.period.is_finite() {
            s.build_panels();
        }
        s.g_u0 = s.g(u0);
        // R(t) = C R_zf(t) Pᵀ with C = R₀ P R_zf(0)ᵀ.
        let zf0 = s.frame_rotation(&s.momentum_body(0.0), 0.0);
        s.c_rot = q0 * s.perm * zf0.inverse();
        Ok(s)
    }

    /// Angular velocity (body components) at time t.
    pub fn omega(&self, t: f64) -> Vector3<f64> {
        let u = self.u0 + self.lambda * t;
        let (sn, cn, dn) = self.jacobi.eval(u);
        let mut w = Vector3::zeros();
        w[self.lab[0]] = self.amp[0] * cn;
        w[self.lab[1]] = self.amp[1] * sn;
        w[self.lab[2]] = self.amp[2] * dn;
        w
    }

    fn momentum_body(&self, t: f64) -> Vector3<f64> {
        let w = self.omega(t);
        Vector3::new(
            self.moments[0] * w.x,
            self.moments[1] * w.y,
            self.moments[2] * w.z,
        )
    }

    /// The two constants of `φ̇ = L/I₂ + C cn² / (A cn² + B sn²)`:
    /// `(A, B, C)` with `A = I₁² a₁²`, `B = I₂² a₂²`,
    /// `C = L I₁ (I₂ − I₁) a₁² / I₂`. (From `φ̇ = L (2E − I₃ω₃²)/(L² − I₃²ω₃²)`
    /// with both differences written as the sums of the other two axes.)
    fn rate_constants(&self) -> (f64, f64, f64) {
        let (i1, i2) = (self.moments[self.lab[0]], self.moments[self.lab[1]]);
        let (a1, a2) = (self.amp[0], self.amp[1]);
        (
            i1 * i1 * a1 * a1,
            i2 * i2 * a2 * a2,
            self.l * i1 * Dd::diff(i2, i1).to_f64() * a1 * a1 / i2,
        )
    }

    /// φ̇ as a function of the elliptic argument u (depends on cn², sn²).
    fn phi_rate(&self, u: f64) -> f64 {
        let (sn, cn, _) = self.jacobi.eval(u);
        let (a, b, c) = self.rate_constants();
        let i2 = self.moments[self.lab[1]];
        let den = a * cn * cn + b * sn * sn;
        self.l / i2 + if den == 0.0 { 0.0 } else { c * cn * cn / den }
    }

    fn gl(&self, a: f64, b: f64) -> f64 {
        let (x, w) = gauss_legendre_20();
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = 0.0;
        for j in 0..20 {
            s += w[j] * self.phi_rate(mid + half * x[j]);
        }
        half * s
    }

    /// Splits `[0, 2K]` into panels on which 20-point Gauss–Legendre
    /// agrees with its two halves to round-off: the panels crowd where
    /// the integrand turns fast (the flips near the separatrix) and stay
    /// wide where it is flat (the slow passage near the intermediate axis).
    fn build_panels(&mut self) {
        let scale = self.l / self.moments[self.lab[0]].min(self.moments[self.lab[1]]);
        let mut out = vec![];
        let first = 16;
        let width = self.period / first as f64;
        let mut stack: Vec<(f64, f64, u32)> = (0..first)
            .rev()
            .map(|p| (p as f64 * width, (p + 1) as f64 * width, 0))
            .collect();
        while let Some((a, b, depth)) = stack.pop() {
            let whole = self.gl(a, b);
            let m = 0.5 * (a + b);
            let halves = self.gl(a, m) + self.gl(m, b);
            if (whole - halves).abs() <= 2.0 * f64::EPSILON * scale * (b - a) || depth >= 40 {
                out.push((a, b, halves));
            } else {
                stack.push((m, b, depth + 1));
                stack.push((a, m, depth + 1));
            }
        }
        let mut cum = 0.0;
        self.panels = out
            .iter()
            .map(|&(a, _, v)| {
                let start = (a, cum);
                cum += v;
                start
            })
            .collect();
        self.period_integral = cum;
    }

    /// `∫₀^r φ̇(v) dv` for `0 ≤ r ≤ 2K`.
    fn g_partial(&self, r: f64) -> f64 {
        let p = self.panels.partition_point(|&(a, _)| a <= r).max(1) - 1;
        let (a, cum) = self.panels[p];
        cum + self.gl(a, r)
    }

    /// `G(u) = ∫₀^u φ̇(v) dv` for every real u.
    fn g(&self, u: f64) -> f64 {
        if !self.period.is_finite() {
            return self.g_separatrix(u);
        }
        let j = (u / self.period).floor();
        let r = u - j * self.period;
        j * self.period_integral + self.g_partial(r)
    }

    /// On the separatrix `cn = dn = sech u`, `sn = tanh u` and with
    /// `τ = tanh u` the integral is elementary:
    /// `∫ sech² / (A sech² + B tanh²) du = ∫ dτ / (A − (A − B) τ²)`.
    fn g_separatrix(&self, u: f64) -> f64 {
        let (a, b, c) = self.rate_constants();
        let i2 = self.moments[self.lab[1]];
        let tau = u.tanh();
        let part = if a > b {
            let kappa = ((a - b) / a).sqrt();
            (kappa * tau).atanh() / (a * kappa)
        } else if a < b {
            let kappa = ((b - a) / a).sqrt();
            (kappa * tau).atan() / (a * kappa)
        } else {
            tau / a
        };
        self.l / i2 * u + c * part
    }

    /// `R_zf` of [`invariable_frame`] from the body momentum `h` (body
    /// axes) and φ.
    ///
    /// The components are permuted by index, not by rotating with `P`:
    /// the quaternion product would add round-off of `ε |H|` to the two
    /// small components when `H` is near the `c` axis, and the azimuth ψ
    /// would then be wrong by `ε / θ`.
    fn frame_rotation(&self, h: &Vector3<f64>, phi: f64) -> UnitQuaternion<f64> {
        let c = self.lab[2];
        let hp = Vector3::new(h[(c + 1) % 3], h[(c + 2) % 3], h[c]);
        invariable_frame(&hp, phi)
    }

    /// The angle turned about `H` since t = 0.
    pub fn phi(&self, t: f64) -> f64 {
        (self.g(self.u0 + self.lambda * t) - self.g_u0) / self.lambda
    }

    /// The state `[q, ω]` at time t.
    pub fn state(&self, t: f64) -> [f64; 7] {
        let w = self.omega(t);
        let h = Vector3::new(
            self.moments[0] * w.x,
            self.moments[1] * w.y,
            self.moments[2] * w.z,
        );
        let zf = self.frame_rotation(&h, self.phi(t));
        let q = self.c_rot * zf * self.perm.inverse();
        pack(&q, &w)
    }
}

/// A heavy symmetric top in steady precession (§7): θ, φ̇ and ψ̇ constant,
/// `W l = (I ω_z − I' φ̇ cos θ) φ̇` (θ ≠ 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyTop {
    /// Initial precession angle.
    pub phi0: f64,
    /// Nutation angle.
    pub theta: f64,
    /// Initial spin angle.
    pub psi0: f64,
    /// Precession rate φ̇.
    pub phi_dot: f64,
    /// Spin rate ψ̇.
    pub psi_dot: f64,
    /// Axial component of ω, `ω_z = ψ̇ + φ̇ cos θ`.
    pub omega_z: f64,
}

impl SteadyTop {
    /// The slow precession rate for given nutation θ and axial spin ω_z, from
    /// `I' cos θ φ̇² − I ω_z φ̇ + W l = 0`; `None` if the spin is too slow
    /// for steady precession.
    pub fn slow_precession_rate(
        i_axial: f64,
        i_trans: f64,
        weight_arm: f64,
        theta: f64,
        omega_z: f64,
    ) -> Option<f64> {
        let a = i_trans * theta.cos();
        let b = -i_axial * omega_z;
        let c = weight_arm;
        if a.abs() <= 1e-15 * (b.abs() + c.abs()) {
            return Some(-c / b);
        }
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            return None;
        }
        // Root of smaller magnitude, computed without cancellation.
        let qq = -0.5 * (b + b.signum() * disc.sqrt());
        Some(c / qq)
    }

    /// Residual of §7's relation `W l − (I ω_z − I' φ̇ cos θ) φ̇`, relative to `W l`.
    pub fn residual(&self, i_axial: f64, i_trans: f64, weight_arm: f64) -> f64 {
        let rhs =
            (i_axial * self.omega_z - i_trans * self.phi_dot * self.theta.cos()) * self.phi_dot;
        (weight_arm - rhs).abs() / weight_arm.abs().max(f64::MIN_POSITIVE)
    }

    /// The state `[q, ω]` at time t.
    pub fn state(&self, t: f64) -> [f64; 7] {
        let psi = self.psi0 + self.psi_dot * t;
        let q = quaternion_from_angles(self.phi0 + self.phi_dot * t, self.theta, psi);
        let (s, c) = psi.sin_cos();
        // ω in the §7 frame: (−φ̇ sin θ, 0, ω_z); body: R_z(−ψ) of it.
        let wx = -self.phi_dot * self.theta.sin();
        let w = Vector3::new(c * wx, -s * wx, self.omega_z);
        pack(&q, &w)
    }
}
