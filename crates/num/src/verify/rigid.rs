//! The rigid-body helpers of the remaining name-keyed check
//! (`principal-axis-stability`).

use nalgebra::Rotation3;

use super::VerifyError;
use super::bodies::{in_axes, mirrored};
use crate::cloud::ParticleCloud;

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
