//! Torque-free motion: the axisymmetric body under no force, and the
//! stability of spin about a principal axis.
//!
//! Here the derived steps are consequences of the equations of motion
//! (a solve, a linearisation, a sign), so the direct side is numeric
//! linear algebra on the particle inertia: ω solved from `I ω = H` with
//! the particle tensor (LU), ω decomposed along Z and the symmetry axis,
//! the Jacobian of Euler's equations built from central differences of
//! particle sums (exact for a quadratic) and its eigenvalues. Nothing on
//! the direct side uses the textbook formula being checked.

use hdot_sym::derivation::Derivation;
use nalgebra::{Matrix3, Vector3};

use super::bodies::{axisymmetric, map_particles};
use super::motion::Attitude;
use super::rigid::{about_g, principal_body};
use super::{Binding, Comparison, State, VerifyError, compare, compare_scaled};
use crate::cloud::ParticleCloud;
use crate::sums::{self, Motion};

/// `torque-free-axisymmetric`. The body (axisymmetric about z, G at the
/// origin) is set at `F = R_z(φ) R_y(θ)`, turned by ψ about its axis, with
/// `H_G = h Z`, `h = 1 + |v|`, θ in (0.1, π − 0.1). In F's axes, ω is
/// solved from the particle tensor, `I ω = Fᵀ h Z` (LU). Compared:
/// `H` with Σ m r × (ω × r); `omega` with the solved ω; `tan_gamma`
/// (which reads 0 = −ω_x I′ cos θ − ω_z I sin θ) with
/// `|ω| (sin γ I′ cos θ − cos γ I sin θ)`, γ the angle between the solved ω
/// and z; `precession` and `spin` with the components of ω along Z and z
/// (ω = φ̇ Z + ψ̇ k, by cross products); `kinematics` with ω of the chain
/// `F R_z(ψ)` for random φ̇, ψ̇ (θ̇ = 0); `elongated` and `flattened` with
/// the sign of φ̇ ψ̇ so obtained for the body stretched to
/// `Σ m z² = (1 + stretch) Σ m x²`, and squeezed to the inverse ratio,
/// with θ in (0.1, π/2 − 0.1).
pub fn torque_free_axisymmetric(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, _) = about_g(cloud, &nalgebra::Rotation3::identity())?;
    let body = axisymmetric(&c, state.fold)?;
    let (phi, psi) = (state.angles.x, state.angles.z);
    let u = state.angles.y.abs() / std::f64::consts::PI;
    let theta = 0.1 + u * (std::f64::consts::PI - 0.2);
    let h = 1.0 + state.v.norm();
    let sol = precession_of(d, &body, phi, theta, psi, h)?;

    let mut b = Binding::default();
    b.scalar("I", 0, sol.i);
    b.scalar("Ip", 0, sol.ip);
    b.scalar("H_G", 0, h);
    b.scalar("theta", 0, theta);
    let mut out = compare(d, "H", &b, sol.h.as_slice())?;
    out.extend(compare(d, "omega", &b, sol.omega.as_slice())?);
    let w = sol.omega.norm();
    let gamma = sol.omega.xy().norm().atan2(sol.omega.z);
    let residual = w * (gamma.sin() * sol.ip * theta.cos() - gamma.cos() * sol.i * theta.sin());
    out.extend(compare_scaled(
        d,
        "tan_gamma",
        &b,
        &[residual],
        &[w * (sol.ip + sol.i)],
    )?);
    out.extend(compare_scaled(
        d,
        "precession",
        &b,
        &[sol.phi_dot],
        &[sol.cond],
    )?);
    out.extend(compare_scaled(d, "spin", &b, &[sol.psi_dot], &[sol.cond])?);

    // Kinematics: random rates, θ constant.
    let rates = Vector3::new(state.omega.x, 0.0, state.omega.z);
    let f = Attitude::about(2, phi, rates.x, 0.0).then(&Attitude::about(1, theta, 0.0, 0.0));
    let r = f.then(&Attitude::about(2, psi, rates.z, 0.0));
    b.vector(["phi", "theta", "psi"], 1, &rates);
    out.extend(compare(
        d,
        "kinematics",
        &b,
        f.to_own(&r.omega_world()).as_slice(),
    )?);

    // The verdicts, on a stretched and a squeezed copy, 0 < θ < 90°.
    let theta = 0.1 + u * (std::f64::consts::FRAC_PI_2 - 0.2);
    for (step, ratio) in [
        ("elongated", 1.0 + state.stretch),
        ("flattened", 1.0 / (1.0 + state.stretch)),
    ] {
        let shaped = reshaped(&body, ratio)?;
        let sol = precession_of(d, &shaped, phi, theta, psi, h)?;
        let sign = (sol.phi_dot * sol.psi_dot).signum();
        out.extend(compare(d, step, &b, &[sign])?);
    }
    Ok(out)
}

/// What the torque-free body does, from particle sums and numerics only.
struct Precession {
    i: f64,
    ip: f64,
    /// Σ m r × (ω × r) in F.
    h: Vector3<f64>,
    /// ω solved from I ω = H, in F.
    omega: Vector3<f64>,
    phi_dot: f64,
    psi_dot: f64,
    /// |ω| / sin θ: the magnitude of the terms of the decomposition.
    cond: f64,
}

fn precession_of(
    d: &Derivation,
    body: &ParticleCloud,
    phi: f64,
    theta: f64,
    psi: f64,
    h: f64,
) -> Result<Precession, VerifyError> {
    let spun = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), psi);
    let in_f = map_particles(body, |p, m| [(spun * p, m)])?;
    let tensor = sums::moments(&in_f, Vector3::zeros()).inertia();
    let [ix, iy, iz] = tensor.moments();
    let f = Attitude::about(2, phi, 0.0, 0.0).then(&Attitude::about(1, theta, 0.0, 0.0));
    let z_f = f.to_own(&Vector3::z());
    let omega = tensor
        .matrix()
        .lu()
        .solve(&(z_f * h))
        .ok_or_else(|| VerifyError::Singular {
            derivation: d.name.clone(),
            what: "the particle inertia",
        })?;
    let motion = Motion {
        omega,
        ..Motion::default()
    };
    let hh = sums::kinetics(&in_f, &motion, Vector3::zeros(), Vector3::zeros()).h_g;
    // ω = a Z + b k: ω × k = a Z × k, ω × Z = b k × Z.
    let k = Vector3::z();
    let (zk, kz) = (z_f.cross(&k), k.cross(&z_f));
    let a = omega.cross(&k).dot(&zk) / zk.norm_squared();
    let bb = omega.cross(&z_f).dot(&kz) / kz.norm_squared();
    Ok(Precession {
        i: iz,
        ip: 0.5 * (ix + iy),
        h: hh,
        omega,
        phi_dot: a,
        psi_dot: bb,
        cond: omega.norm() / zk.norm(),
    })
}

/// The axisymmetric `body` (G at the origin) with `Σ m z² = ratio Σ m x²`:
/// z scaled down, or the body split in two halves moved apart along z.
fn reshaped(body: &ParticleCloud, ratio: f64) -> Result<ParticleCloud, VerifyError> {
    let mo = sums::moments(body, Vector3::zeros());
    let [xx, _, zz, ..] = mo.second;
    let target = ratio * xx;
    if zz > target {
        let s = (target / zz).sqrt();
        Ok(map_particles(body, |p, m| {
            [(Vector3::new(p.x, p.y, s * p.z), m)]
        })?)
    } else {
        let c = ((target - zz) / mo.mass).sqrt();
        let up = Vector3::new(0.0, 0.0, c);
        Ok(map_particles(body, |p, m| {
            [(p + up, 0.5 * m), (p - up, 0.5 * m)]
        })?)
    }
}

/// `principal-axis-stability`. The body is principal by symmetry (the
/// cloud mirrored in three planes), made triaxial (pairs of point masses
/// on the axes keep the second moments Σ m x², Σ m y², Σ m z² at least a
/// tenth of their sum apart), and relabelled cyclically so that axis 1 is
/// principal axis `axis`. It spins at Ω (|Ω| ≥ 0.5, from `omega.x`),
/// disturbed by ε = `v`, ε̇ = `alpha`. Compared: `M` with Σ m r × a for
/// ω = (Ω + ε₁, ε₂, ε₃), α = ε̇; `L` with the central difference
/// `[M(ω₀ + ε, ε̇) − M(ω₀ − ε, −ε̇)] / 2` of particle sums (exact for a
/// quadratic in ω); `eps3_rate` and `eps2_acc` with `(J ε)₃` and
/// `(J² ε)₂`, J = −I⁻¹ ∂(Σ m r × a)/∂ω at α = 0 (central differences,
/// the particle tensor, LU); `k_1` with −λ²/Ω², λ the eigenvalue of J of
/// largest modulus (Schur); `sign_largest`, `sign_intermediate`,
/// `sign_smallest` with the sign of −λ² for spin about the axis of the
/// largest, middle and smallest moment.
pub fn principal_axis_stability(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, _) = principal_body(cloud, &state.axes)?;
    let c = triaxial(&c)?;
    let omega0 = state.omega.x.signum() * (0.5 + state.omega.x.abs());
    let (eps, eps_dot) = (state.v, state.alpha);
    let body = relabelled(&c, state.axis)?;
    let mp = body.mass_properties();
    let [a, bm, cm] = mp.inertia_g.moments();
    let mut b = Binding::default();
    b.scalar("A", 0, a);
    b.scalar("B", 0, bm);
    b.scalar("C", 0, cm);
    b.scalar("Omega", 0, omega0);
    let names = ["epsilon_1", "epsilon_2", "epsilon_3"];
    b.vector(names, 0, &eps);
    b.vector(names, 1, &eps_dot);
    let spin = Vector3::new(omega0, 0.0, 0.0);
    let moment = |w: Vector3<f64>, al: Vector3<f64>| {
        let m = Motion {
            omega: w,
            alpha: al,
            ..Motion::default()
        };
        sums::kinetics(&body, &m, mp.center, mp.center).hdot_g
    };
    let mut out = compare(d, "M", &b, moment(spin + eps, eps_dot).as_slice())?;
    let (plus, minus) = (moment(spin + eps, eps_dot), moment(spin - eps, -eps_dot));
    let lin = (plus - minus) / 2.0;
    let mag = (plus.abs() + minus.abs()) / 2.0;
    out.extend(compare_scaled(d, "L", &b, lin.as_slice(), mag.as_slice())?);

    let j = jacobian(d, &body, omega0)?;
    let (je, jje) = (j * eps, j * (j * eps));
    let ja = j.abs();
    let (je_mag, jje_mag) = (ja * eps.abs(), ja * (ja * eps.abs()));
    out.extend(compare_scaled(d, "eps3_rate", &b, &[je.z], &[je_mag.z])?);
    out.extend(compare_scaled(d, "eps2_acc", &b, &[jje.y], &[jje_mag.y])?);
    let lambda2 = largest_eigenvalue_squared(d, &j)?;
    let tr_mag: f64 = (0..3)
        .flat_map(|r| (0..3).map(move |s| (r, s)))
        .map(|(r, s)| (j[(r, s)] * j[(s, r)]).abs())
        .sum();
    let w2 = omega0 * omega0;
    out.extend(compare_scaled(
        d,
        "k_1",
        &b,
        &[-lambda2 / w2],
        &[tr_mag / w2],
    )?);

    // The verdicts: spin about the largest, middle, smallest moment.
    let moments = c.mass_properties().inertia_g.moments();
    let mut order = [0, 1, 2];
    order.sort_by(|&p, &q| moments[q].total_cmp(&moments[p]));
    for (step, axis) in [
        ("sign_largest", order[0]),
        ("sign_intermediate", order[1]),
        ("sign_smallest", order[2]),
    ] {
        let body = relabelled(&c, axis)?;
        let j = jacobian(d, &body, omega0)?;
        let sign = (-largest_eigenvalue_squared(d, &j)?).signum();
        out.extend(compare(d, step, &b, &[sign])?);
    }
    Ok(out)
}

/// `J = −I⁻¹ D`, `D` the derivative of Σ m r × a (α = 0) with respect to
/// ω at `(Ω, 0, 0)`, by central differences with unit steps (exact: the
/// sum is quadratic in ω); `I` the particle tensor.
fn jacobian(
    d: &Derivation,
    body: &ParticleCloud,
    omega0: f64,
) -> Result<Matrix3<f64>, VerifyError> {
    let mp = body.mass_properties();
    let spin = Vector3::new(omega0, 0.0, 0.0);
    let moment = |w: Vector3<f64>| {
        let m = Motion {
            omega: w,
            ..Motion::default()
        };
        sums::kinetics(body, &m, mp.center, mp.center).hdot_g
    };
    let mut dm = Matrix3::zeros();
    for k in 0..3 {
        let e = Vector3::ith(k, 1.0);
        dm.set_column(k, &((moment(spin + e) - moment(spin - e)) / 2.0));
    }
    mp.inertia_g
        .matrix()
        .lu()
        .solve(&(-dm))
        .ok_or_else(|| VerifyError::Singular {
            derivation: d.name.clone(),
            what: "the particle inertia",
        })
}

/// λ² for the eigenvalue λ of `j` of largest modulus (real part: λ² > 0
/// for a growing pair ±λ, < 0 for an oscillating pair ±iω).
fn largest_eigenvalue_squared(d: &Derivation, j: &Matrix3<f64>) -> Result<f64, VerifyError> {
    let schur = nalgebra::linalg::Schur::try_new(*j, f64::EPSILON, 10_000).ok_or_else(|| {
        VerifyError::Singular {
            derivation: d.name.clone(),
            what: "the Schur decomposition of the Jacobian",
        }
    })?;
    let ev = schur.complex_eigenvalues();
    let top = ev
        .iter()
        .max_by(|p, q| p.norm().total_cmp(&q.norm()))
        .copied()
        .unwrap_or_default();
    Ok((top * top).re)
}

/// `cloud` (principal axes, G at the origin) with pairs of point masses at
/// ±e_k added so that the second moments Σ m x_k² are at least a tenth of
/// their sum apart: three distinct principal moments.
fn triaxial(cloud: &ParticleCloud) -> Result<ParticleCloud, VerifyError> {
    let s = sums::moments(cloud, Vector3::zeros()).second;
    let mut idx = [0, 1, 2];
    idx.sort_by(|&p, &q| s[p].total_cmp(&s[q]));
    let gap = 0.1 * (s[0] + s[1] + s[2]);
    let mid = s[idx[1]].max(s[idx[0]] + gap);
    let high = s[idx[2]].max(mid + gap);
    let mut add = [0.0; 3];
    add[idx[1]] = mid - s[idx[1]];
    add[idx[2]] = high - s[idx[2]];
    let mut ps: Vec<_> = (0..cloud.len()).map(|i| cloud.particle(i)).collect();
    for (k, &extra) in add.iter().enumerate() {
        if extra > 0.0 {
            let e = Vector3::ith(k, 1.0);
            ps.push((e, 0.5 * extra));
            ps.push((-e, 0.5 * extra));
        }
    }
    Ok(ParticleCloud::try_from_particles(ps)?)
}

/// Cyclic relabelling of the axes so that axis `k` becomes axis 1 (x).
fn relabelled(cloud: &ParticleCloud, k: usize) -> Result<ParticleCloud, VerifyError> {
    Ok(map_particles(cloud, |p, m| {
        [(Vector3::new(p[k % 3], p[(k + 1) % 3], p[(k + 2) % 3]), m)]
    })?)
}
