//! Gyroscopes: an axisymmetric rotor carried by a chain of rotations,
//! against Σ m r × v and Σ m r × R̈ q over its particles (see
//! [`super::motion`]: the particles' accelerations come from `R̈`, never
//! from ω, α or the transport theorem).
//!
//! A rotor is any random body made axisymmetric about its z axis by
//! `fold ≥ 3` copies turned by 2π/fold (so `I_x = I_y` and the products
//! with z vanish to round-off); its G sits on the axis at the height
//! `offset.z` above the fixed point O.

use hdot_sym::derivation::Derivation;
use nalgebra::{Rotation3, Vector3};

use super::bodies::axisymmetric;
use super::motion::{Attitude, path_sums};
use super::rigid::about_g;
use super::{Binding, Comparison, State, VerifyError, compare};
use crate::cloud::ParticleCloud;
use crate::sums;

const ANGLES: [&str; 3] = ["phi", "theta", "psi"];

/// The rotor: the cloud about its G (world axes), raised by `h` along z
/// and made axisymmetric about z. Returns it (coordinates about O) with
/// its inertia about O.
fn rotor(
    cloud: &ParticleCloud,
    h: f64,
    fold: usize,
) -> Result<(ParticleCloud, crate::Inertia), VerifyError> {
    let (c, _) = about_g(cloud, &Rotation3::identity())?;
    let raised = super::bodies::map_particles(&c, |p, m| [(p + Vector3::new(0.0, 0.0, h), m)])?;
    let r = axisymmetric(&raised, fold)?;
    let i = sums::moments(&r, Vector3::zeros()).inertia();
    Ok((r, i))
}

/// Binds the transverse and axial moments of an axisymmetric body under
/// the derivation's names, sized by `Σ m |r|²`.
fn bind_axisymmetric(
    b: &mut Binding,
    i: &crate::Inertia,
    transverse: &'static str,
    axial: &'static str,
) {
    let [ix, iy, iz] = i.moments();
    let size = 0.5 * i.trace();
    b.set(transverse, 0, 0.5 * (ix + iy), size);
    b.set(axial, 0, iz, size);
}

/// The frames of the gyroscope: F = R_z(φ) R_y(θ) (axes Oxyz) and the
/// rotor R = F R_z(ψ), with the given angles, rates and accelerations.
fn eulerian(q: Vector3<f64>, qd: Vector3<f64>, qdd: Vector3<f64>) -> (Attitude, Attitude) {
    let f = Attitude::about(2, q.x, qd.x, qdd.x).then(&Attitude::about(1, q.y, qd.y, qdd.y));
    let r = f.then(&Attitude::about(2, q.z, qd.z, qdd.z));
    (f, r)
}

fn bind_angles(b: &mut Binding, q: Vector3<f64>, qd: Vector3<f64>, qdd: Vector3<f64>) {
    b.vector(ANGLES, 0, &q);
    b.vector(ANGLES, 1, &qd);
    b.vector(ANGLES, 2, &qdd);
}

/// `gyroscope`: `Omega` and `omega` against the angular velocities of the
/// rotation chains (`Rᵀ Ṙ` of F; `Ṙ Rᵀ` of the rotor, in F); `H`, `M`,
/// `M_transport` against Σ m r × v and Σ m r × R̈ q about O, in F.
pub fn gyroscope(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (body, i) = rotor(cloud, state.offset.z, state.fold)?;
    let (q, qd, qdd) = (state.angles, state.omega, state.alpha);
    let (f, r) = eulerian(q, qd, qdd);
    let s = path_sums(&body, &r);
    let mut b = Binding::default();
    bind_axisymmetric(&mut b, &i, "Ip", "I");
    bind_angles(&mut b, q, qd, qdd);
    let mut out = compare(d, "Omega", &b, f.omega_own().as_slice())?;
    out.extend(compare(
        d,
        "omega",
        &b,
        f.to_own(&r.omega_world()).as_slice(),
    )?);
    out.extend(compare(d, "H", &b, f.to_own(&s.h_o).as_slice())?);
    let m = f.to_own(&s.moment_o);
    out.extend(compare(d, "M", &b, m.as_slice())?);
    out.extend(compare(d, "M_transport", &b, m.as_slice())?);
    Ok(out)
}

/// `steady-precession`: the rotor with θ̇ = φ̈ = ψ̈ = 0: `H`, `M` and
/// `M_steady` against Σ m r × v and Σ m r × R̈ q in F; `M_right_angle`
/// the same with θ = π/2.
pub fn steady_precession(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (body, i) = rotor(cloud, state.offset.z, state.fold)?;
    let qd = Vector3::new(state.omega.x, 0.0, state.omega.z);
    let qdd = Vector3::zeros();
    let mut out = Vec::new();
    for (q, steps) in [
        (state.angles, &["H", "M", "M_steady"][..]),
        (
            Vector3::new(state.angles.x, std::f64::consts::FRAC_PI_2, state.angles.z),
            &["M_right_angle"][..],
        ),
    ] {
        let (f, r) = eulerian(q, qd, qdd);
        let s = path_sums(&body, &r);
        let mut b = Binding::default();
        bind_axisymmetric(&mut b, &i, "Ip", "I");
        bind_angles(&mut b, q, qd, qdd);
        for step in steps {
            let direct = if *step == "H" { s.h_o } else { s.moment_o };
            out.extend(compare(d, step, &b, f.to_own(&direct).as_slice())?);
        }
    }
    Ok(out)
}

/// `gyroscope-axisymmetric-frame`: a frame F turning as
/// `R_z R_y R_x` (`angles`, `omega`, `alpha`) carries an axisymmetric body
/// (about G) that spins in it about axis 3 by β (`spin`). The symbols are
/// read off the chains: ω_i the body's ω in F, Ω_3 F's own, ω̇_i the time
/// derivatives of ω's components in F. `H` and `Q` are compared with
/// Σ m r × v and Σ m r × R̈ q in F; `Q_euler` with the same in body axes
/// (F = the body).
pub fn axisymmetric_frame(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (body, i) = rotor(cloud, 0.0, state.fold)?;
    let (q, qd, qdd) = (state.angles, state.omega, state.alpha);
    let f = Attitude::about(2, q.x, qd.x, qdd.x)
        .then(&Attitude::about(1, q.y, qd.y, qdd.y))
        .then(&Attitude::about(0, q.z, qd.z, qdd.z));
    let r = f.then(&Attitude::about(
        2,
        state.spin.x,
        state.spin.y,
        state.spin.z,
    ));
    let s = path_sums(&body, &r);
    let bind = |frame: &Attitude| {
        let mut b = Binding::default();
        bind_axisymmetric(&mut b, &i, "A", "C");
        let (w, a) = (r.omega_world(), r.alpha_world());
        // d/dt (Fᵀ ω) = Ḟᵀ ω + Fᵀ α.
        let w_f = frame.to_own(&w);
        let w_f_rate = frame.rd.transpose() * w + frame.r.transpose() * a;
        let names = ["omega_1", "omega_2", "omega_3"];
        b.vector(names, 0, &w_f);
        b.vector(names, 1, &w_f_rate);
        let big = frame.omega_own();
        b.set("Omega_3", 0, big.z, big.norm());
        b
    };
    let b = bind(&f);
    let mut out = compare(d, "H", &b, f.to_own(&s.h_o).as_slice())?;
    out.extend(compare(d, "Q", &b, f.to_own(&s.moment_o).as_slice())?);
    let b = bind(&r);
    out.extend(compare(d, "Q_euler", &b, r.to_own(&s.moment_o).as_slice())?);
    Ok(out)
}
