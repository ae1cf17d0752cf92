//! Kinetics of a rigid body at an instant, against the direct sums of
//! [`crate::sums::kinetics`] over the same particles: Euler's equations,
//! angular momentum (about G and about another point), kinetic energy, the
//! parallel-axis theorem, d'Alembert's principle, plane motion, and the
//! impulse–momentum solve.

use hdot_sym::derivation::Derivation;
use nalgebra::{Matrix6, Rotation3, Vector3, Vector6};

use super::bodies::{in_axes, mirrored};
use super::{BAR, Binding, Comparison, OMEGA, State, VEL, VerifyError, compare, compare_scaled};
use crate::cloud::ParticleCloud;
use crate::sums::{self, Motion};

/// The cloud in body axes through G, its centre (≈ 0) and mass properties.
pub(crate) fn about_g(
    cloud: &ParticleCloud,
    axes: &Rotation3<f64>,
) -> Result<(ParticleCloud, crate::MassProperties), VerifyError> {
    let g = cloud.mass_properties().center;
    let c = in_axes(cloud, &g, axes)?;
    let mp = c.mass_properties();
    Ok((c, mp))
}

/// A body whose coordinate axes are principal by symmetry: the cloud in
/// `axes` about G, mirrored in the three coordinate planes.
pub(crate) fn principal_body(
    cloud: &ParticleCloud,
    axes: &Rotation3<f64>,
) -> Result<(ParticleCloud, crate::MassProperties), VerifyError> {
    let (c, _) = about_g(cloud, axes)?;
    let c = mirrored(&c, [true; 3])?;
    let mp = c.mass_properties();
    Ok((c, mp))
}

/// The 9 entries of `i`'s tensor (with the minus signs), by rows.
fn tensor(i: &crate::Inertia) -> Vec<f64> {
    i.matrix().transpose().as_slice().to_vec()
}

/// The inertia tensor about `center` (with the minus signs), by rows,
/// measured as a linear map: column k is the particles' angular momentum
/// Σ m r × (e_k × r) for a unit angular velocity about axis k. Independent
/// of the moments and products the binding reads from [`crate::Inertia`].
fn tensor_from_momenta(c: &ParticleCloud, center: Vector3<f64>) -> Vec<f64> {
    let columns = [Vector3::x(), Vector3::y(), Vector3::z()].map(|e| {
        let unit = Motion {
            omega: e,
            ..Motion::default()
        };
        sums::kinetics(c, &unit, center, center).h_g
    });
    (0..3)
        .flat_map(|row| columns.iter().map(move |col| col[row]))
        .collect()
}

/// Euler's moment equations on `c` (body axes through G, with its mass
/// properties `mp`) against Σ m r × a, and then `I_G` (against
/// [`tensor_from_momenta`]) and `H` (against Σ m r × v) on the same sums.
fn euler(
    d: &Derivation,
    c: &ParticleCloud,
    mp: &crate::MassProperties,
    state: &State,
    steps: &[&str],
) -> Result<(Vec<Comparison>, Binding, Motion), VerifyError> {
    let motion = Motion {
        omega: state.omega,
        alpha: state.alpha,
        ..Motion::default()
    };
    let k = sums::kinetics(c, &motion, mp.center, mp.center);
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.vector(OMEGA, 0, &state.omega);
    b.vector(OMEGA, 1, &state.alpha);
    let mut out = Vec::new();
    for s in steps {
        out.extend(compare(d, s, &b, k.hdot_g.as_slice())?);
    }
    out.extend(compare(d, "I_G", &b, &tensor_from_momenta(c, mp.center))?);
    out.extend(compare(d, "H", &b, k.h_g.as_slice())?);
    Ok((out, b, motion))
}

/// `euler-principal`: `M`, `M_transport` against Σ m r × a on a body whose
/// coordinate axes are principal by symmetry (mirrored in the three
/// coordinate planes), so that the products the derivation drops vanish to
/// round-off. (Eigenvectors of a general body would leave products of
/// ~1e-13 of the moments, whose effect on Σ m r × a is above round-off.)
pub fn euler_principal(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = principal_body(cloud, &state.axes)?;
    Ok(euler(d, &c, &mp, state, &["M", "M_transport"])?.0)
}

/// `euler-general`: `M` against Σ m r × a in random body axes.
pub fn euler_general(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let (mut out, mut b, motion) = euler(d, &c, &mp, state, &["M"])?;
    // M_principal on a body principal by symmetry.
    let (c, mp) = principal_body(cloud, &state.axes)?;
    let k = sums::kinetics(&c, &motion, mp.center, mp.center);
    b.inertia(&mp.inertia_g);
    out.extend(compare(d, "M_principal", &b, k.hdot_g.as_slice())?);
    Ok(out)
}

/// `angular-momentum`: `H`, `T_rot` against Σ m r × v, Σ ½ m v².
pub fn angular_momentum(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let motion = Motion {
        omega: state.omega,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &motion, mp.center, mp.center);
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.vector(OMEGA, 0, &state.omega);
    let mut out = compare(d, "H", &b, k.h_g.as_slice())?;
    out.extend(compare(d, "T_rot", &b, &[k.kinetic_energy])?);
    // ω along x.
    let along_x = Motion {
        omega: Vector3::new(state.omega.x, 0.0, 0.0),
        ..Motion::default()
    };
    let kx = sums::kinetics(&c, &along_x, mp.center, mp.center);
    out.extend(compare(d, "H_along_x", &b, kx.h_g.as_slice())?);
    // A body principal by symmetry.
    let (c, mp) = principal_body(cloud, &state.axes)?;
    let k = sums::kinetics(&c, &motion, mp.center, mp.center);
    b.inertia(&mp.inertia_g);
    out.extend(compare(d, "H_principal", &b, k.h_g.as_slice())?);
    Ok(out)
}

/// `fixed-axis`: `M` against Σ m r × a about O on the axis (body z).
pub fn fixed_axis(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    // O = G − offset (world offset = axes · offset); axes Oxyz, z the axis.
    let g = cloud.mass_properties().center;
    let o = g - state.axes * state.offset;
    let c = in_axes(cloud, &o, &state.axes)?;
    let mp = c.mass_properties();
    let (w, wdot) = (state.omega.z, state.alpha.z);
    let origin = Vector3::zeros();
    let motion = Motion::about_fixed_point(
        origin,
        mp.center,
        Vector3::new(0.0, 0.0, w),
        Vector3::new(0.0, 0.0, wdot),
    );
    let k = sums::kinetics(&c, &motion, mp.center, origin);
    let mut b = Binding::default();
    b.inertia(&sums::moments(&c, origin).inertia());
    b.set("omega", 0, w, w.abs());
    b.set("omega", 1, wdot, wdot.abs());
    let mut out = compare(d, "M", &b, k.moment_o.as_slice())?;
    // About the fixed point O: "centre" O in the kernel, each particle
    // moving as ω × (p − O).
    let spin = Motion {
        omega: motion.omega,
        alpha: motion.alpha,
        ..Motion::default()
    };
    let ko = sums::kinetics(&c, &spin, origin, origin);
    out.extend(compare(d, "H", &b, ko.h_g.as_slice())?);
    let steady = Motion {
        omega: motion.omega,
        ..Motion::default()
    };
    let ks = sums::kinetics(&c, &steady, origin, origin);
    out.extend(compare(d, "M_steady", &b, ks.hdot_g.as_slice())?);
    // A body symmetric about the xy plane through O (mirrored in it).
    let sym = mirrored(&c, [false, false, true])?;
    let ksym = sums::kinetics(&sym, &spin, origin, origin);
    let mut bs = Binding::default();
    let i_sym = sums::moments(&sym, origin).inertia();
    bs.inertia(&i_sym);
    bs.set("omega", 0, w, w.abs());
    bs.set("omega", 1, wdot, wdot.abs());
    // The ω² terms cancel in x and y (mirror pairs) and vanish in z
    // particle by particle; the derived form has none of them.
    let cancelled = 0.5 * i_sym.trace() * (wdot.abs() + w * w);
    out.extend(compare_scaled(
        d,
        "M_symmetric",
        &bs,
        ksym.hdot_g.as_slice(),
        &[cancelled; 3],
    )?);
    Ok(out)
}

/// `kinetic-energy`: `T` (free motion) and `T_O` (about a fixed point)
/// against Σ ½ m v².
pub fn kinetic_energy(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.set("m", 0, mp.mass, mp.mass);
    b.vector(OMEGA, 0, &state.omega);
    b.vector(VEL, 0, &state.v);
    b.vector(BAR, 0, &state.offset);
    let free = Motion {
        omega: state.omega,
        v_g: state.v,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &free, mp.center, mp.center);
    let mut out = compare(d, "T", &b, &[k.kinetic_energy])?;
    out.extend(compare(d, "H_G", &b, k.h_g.as_slice())?);
    // A body principal by symmetry.
    let (cp, mpp) = principal_body(cloud, &state.axes)?;
    let kp = sums::kinetics(&cp, &free, mpp.center, mpp.center);
    let mut bp = Binding::default();
    bp.inertia(&mpp.inertia_g);
    bp.set("m", 0, mpp.mass, mpp.mass);
    bp.vector(OMEGA, 0, &state.omega);
    bp.vector(VEL, 0, &state.v);
    out.extend(compare(d, "T_principal", &bp, &[kp.kinetic_energy])?);
    // Fixed point O with G − O = offset: v̄ = ω × r̄.
    let o = mp.center - state.offset;
    let pinned = Motion::about_fixed_point(o, mp.center, state.omega, state.alpha);
    let k = sums::kinetics(&c, &pinned, mp.center, o);
    out.extend(compare(d, "T_O", &b, &[k.kinetic_energy])?);
    Ok(out)
}

/// `parallel-axis`: `Ix_P` … `Izx_P` against the particle inertia about P.
pub fn parallel_axis(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let p = mp.center - state.offset;
    let ip = sums::moments(&c, p).inertia();
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.set("m", 0, mp.mass, mp.mass);
    b.vector(BAR, 0, &state.offset);
    b.vector(OMEGA, 0, &state.omega);
    let [ix, iy, iz] = ip.moments();
    let [ixy, iyz, izx] = ip.products();
    let mut out = compare(d, "I_P", &b, &tensor(&ip))?;
    // H_point = H_P − H_G for the body turning about P (particle sums
    // about P and about G; their magnitudes join the scale).
    let spin = Motion {
        omega: state.omega,
        ..Motion::default()
    };
    let h_p = sums::kinetics(&c, &spin, p, p).h_g;
    let h_g = sums::kinetics(&c, &spin, mp.center, mp.center).h_g;
    let mag = h_p.abs() + h_g.abs();
    out.extend(compare_scaled(
        d,
        "H_point",
        &b,
        (h_p - h_g).as_slice(),
        mag.as_slice(),
    )?);
    for (s, v) in [
        ("Ix_P", ix),
        ("Iy_P", iy),
        ("Iz_P", iz),
        ("Ixy_P", ixy),
        ("Iyz_P", iyz),
        ("Izx_P", izx),
    ] {
        out.extend(compare(d, s, &b, &[v])?);
    }
    Ok(out)
}

/// `angular-momentum-about-point`: `H_G` against Σ m r′ × v′;
/// `H_O_general` against Σ m r × v about O for a free motion (ω, v̄);
/// `vbar` and `H_O` against Σ m v / m and Σ m r × v with every particle
/// moving as `ω × (p − O)` (O fixed; no G in the direct sums).
pub fn angular_momentum_about_point(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let o = mp.center - state.offset;
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.scalar("m", 0, mp.mass);
    b.vector(BAR, 0, &state.offset);
    b.vector(OMEGA, 0, &state.omega);
    b.vector(VEL, 0, &state.v);
    let free = Motion {
        omega: state.omega,
        v_g: state.v,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &free, mp.center, o);
    let mut out = compare(d, "H_G", &b, k.h_g.as_slice())?;
    out.extend(compare(d, "H_O_general", &b, k.h_o.as_slice())?);
    // About the fixed point: "centre" O in the kernel, so that each
    // particle's velocity is ω × (p − O) and h_g is Σ m (p − O) × v.
    let spin = Motion {
        omega: state.omega,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &spin, o, o);
    out.extend(compare(d, "vbar", &b, (k.momentum / k.mass).as_slice())?);
    out.extend(compare(d, "H_O", &b, k.h_g.as_slice())?);
    Ok(out)
}

/// `dalembert`: `F` and `M_O` against Σ m a and Σ m r × a about a fixed O
/// (world axes) for a free motion (ω, α, v̄, ā), with `h′` bound from the
/// particle sum Σ m r′ × a; `Hdot_G` against Σ m r′ × a in the axes of a
/// principal body (the cloud mirrored in three planes).
pub fn dalembert(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let mp = cloud.mass_properties();
    let o = mp.center - state.axes * state.offset;
    let motion = Motion {
        omega: state.omega,
        alpha: state.alpha,
        v_g: state.v,
        a_g: state.a,
    };
    let k = sums::kinetics(cloud, &motion, mp.center, o);
    let mut b = Binding::default();
    b.scalar("m", 0, mp.mass);
    let xyz = ["x", "y", "z"];
    b.vector(xyz, 0, &(mp.center - o));
    b.vector(xyz, 1, &state.v);
    b.vector(xyz, 2, &state.a);
    b.vector(["h_x", "h_y", "h_z"], 0, &k.h_g);
    b.vector(["h_x", "h_y", "h_z"], 1, &k.hdot_g);
    // The direct sums cancel r̄ × Σ m a′ and Σ m r′ × ā (Σ m r′ = 0); their
    // magnitudes, bounded with Σ m |r′| ≤ √(m Σ m |r′|²), join the scale.
    let spread = (mp.mass * 0.5 * mp.inertia_g.trace()).sqrt();
    let turn = state.alpha.norm() + state.omega.norm_squared();
    let f_mag = spread * turn;
    let m_mag = spread * ((mp.center - o).norm() * turn + state.a.norm());
    let mut out = compare_scaled(d, "F", &b, k.force.as_slice(), &[f_mag; 3])?;
    out.extend(compare_scaled(
        d,
        "M_O",
        &b,
        k.moment_o.as_slice(),
        &[m_mag; 3],
    )?);

    let (c, mp) = principal_body(cloud, &state.axes)?;
    let spin = Motion {
        omega: state.omega,
        alpha: state.alpha,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &spin, mp.center, mp.center);
    b.inertia(&mp.inertia_g);
    b.vector(OMEGA, 0, &state.omega);
    b.vector(OMEGA, 1, &state.alpha);
    out.extend(compare(d, "Hdot_G", &b, k.hdot_g.as_slice())?);
    Ok(out)
}

/// `plane-motion`: `H` against Σ m r′ × v′ with ω = ω k (any body); then
/// the body mirrored in its xy plane through G: `H_lamina` and
/// `M_lamina` against Σ m r′ × v′ and Σ m r′ × a with α = ω̇ k.
pub fn plane_motion(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (w, wdot) = (state.omega.z, state.alpha.z);
    let motion = Motion {
        omega: Vector3::new(0.0, 0.0, w),
        alpha: Vector3::new(0.0, 0.0, wdot),
        ..Motion::default()
    };
    let (c, mp) = about_g(cloud, &state.axes)?;
    let k = sums::kinetics(&c, &motion, mp.center, mp.center);
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.set("omega", 0, w, w.abs());
    b.set("omega", 1, wdot, wdot.abs());
    let mut out = compare(d, "H", &b, k.h_g.as_slice())?;

    let lamina = mirrored(&c, [false, false, true])?;
    let mp = lamina.mass_properties();
    let k = sums::kinetics(&lamina, &motion, mp.center, mp.center);
    b.inertia(&mp.inertia_g);
    out.extend(compare(d, "H_lamina", &b, k.h_g.as_slice())?);
    // The ω² terms of the direct sum cancel in x and y (mirror pairs) and
    // vanish in z particle by particle (the derived form has none): their
    // magnitude, Σ m |r′|² ω², joins the scale.
    let cancelled = 0.5 * mp.inertia_g.trace() * (wdot.abs() + w * w);
    out.extend(compare_scaled(
        d,
        "M_lamina",
        &b,
        k.hdot_g.as_slice(),
        &[cancelled; 3],
    )?);
    Ok(out)
}

/// `impulse-momentum`: `v` and `omega` against the numeric solution of
/// the impulse–momentum equations of the particles, `Σ m v_i = F̂` and
/// `Σ m r′_i × v_i = r_P × F̂` with `v_i = v̄ + ω × r′_i`: a 6 × 6 system
/// whose columns are the particle momenta of unit velocities (no inertia
/// formula), solved by LU. The body is principal by symmetry (the cloud
/// mirrored in three planes), as the derivation assumes.
pub fn impulse_momentum(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = principal_body(cloud, &state.axes)?;
    let (fhat, r_p) = (state.v, state.offset);
    let mut a = Matrix6::zeros();
    for j in 0..6 {
        let mut motion = Motion::default();
        if j < 3 {
            motion.v_g[j] = 1.0;
        } else {
            motion.omega[j - 3] = 1.0;
        }
        let k = sums::kinetics(&c, &motion, mp.center, mp.center);
        let col = Vector6::new(
            k.momentum.x,
            k.momentum.y,
            k.momentum.z,
            k.h_g.x,
            k.h_g.y,
            k.h_g.z,
        );
        a.set_column(j, &col);
    }
    let h = r_p.cross(&fhat);
    let rhs = Vector6::new(fhat.x, fhat.y, fhat.z, h.x, h.y, h.z);
    let x = a.lu().solve(&rhs).ok_or_else(|| VerifyError::Singular {
        derivation: d.name.clone(),
        what: "the impulse–momentum system",
    })?;
    let mut b = Binding::default();
    b.scalar("m", 0, mp.mass);
    let [ix, iy, iz] = mp.inertia_g.moments();
    // Divided by: sized by their own values (a bound on 1/I from below
    // would not be one).
    b.scalar("I_x", 0, ix);
    b.scalar("I_y", 0, iy);
    b.scalar("I_z", 0, iz);
    b.vector(["F_x", "F_y", "F_z"], 0, &fhat);
    b.vector(["x_P", "y_P", "z_P"], 0, &r_p);
    let mut out = compare(d, "v", &b, &[x[0], x[1], x[2]])?;
    out.extend(compare(d, "omega", &b, &[x[3], x[4], x[5]])?);
    Ok(out)
}
