//! Torque-free motion: the stability of spin about a principal axis.
//!
//! Here the derived steps are consequences of the equations of motion
//! (a solve, a linearisation, a sign), so the direct side is numeric
//! linear algebra on the particle inertia: the Jacobian of Euler's equations built from central differences of
//! particle sums (exact for a quadratic) and its eigenvalues. Nothing on
//! the direct side uses the textbook formula being checked.

use hdot_sym::derivation::Derivation;
use nalgebra::{Matrix3, Vector3};

use super::bodies::map_particles;
use super::rigid::principal_body;
use super::{Binding, Comparison, State, VerifyError, compare, compare_scaled};
use crate::cloud::ParticleCloud;
use crate::sums::{self, Motion};

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
