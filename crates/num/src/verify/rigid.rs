//! The impulse–momentum solve against the direct sums of
//! [`crate::sums::kinetics`] over the same particles, and the rigid-body
//! helpers the remaining name-keyed checks share.

use hdot_sym::derivation::Derivation;
use nalgebra::{Matrix6, Rotation3, Vector6};

use super::bodies::{in_axes, mirrored};
use super::{Binding, Comparison, State, VerifyError, compare};
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
