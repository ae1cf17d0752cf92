//! Named proptest strategies for the numeric tests.

use hdot_num::{Body, ParticleCloud, Pose, Primitive};
use nalgebra::{UnitQuaternion, Vector3};
use proptest::prelude::*;

/// A finite 3-vector with components in `[-s, s]`.
pub fn vector3(s: f64) -> impl Strategy<Value = Vector3<f64>> {
    (-s..s, -s..s, -s..s).prop_map(|(x, y, z)| Vector3::new(x, y, z))
}

/// A random attitude (uniform enough for testing).
pub fn rotation() -> impl Strategy<Value = UnitQuaternion<f64>> {
    (vector3(1.0), -3.1..3.1f64).prop_map(|(axis, angle)| {
        if axis.norm() < 1e-3 {
            UnitQuaternion::identity()
        } else {
            UnitQuaternion::from_scaled_axis(axis.normalize() * angle)
        }
    })
}

/// A pose within a few units of the origin.
pub fn pose() -> impl Strategy<Value = Pose> {
    (vector3(3.0), rotation()).prop_map(|(position, rotation)| Pose { position, rotation })
}

/// An angular velocity (or acceleration) of moderate size.
pub fn angular_velocity() -> impl Strategy<Value = Vector3<f64>> {
    vector3(5.0)
}

/// A cloud of 1 to 40 particles with masses in (0.1, 5).
pub fn particle_cloud() -> impl Strategy<Value = ParticleCloud> {
    prop::collection::vec((vector3(2.0), 0.1..5.0f64), 1..40)
        .prop_map(|ps| ParticleCloud::try_from_particles(ps).expect("valid by construction"))
}

/// Any primitive with dimensions in (0.1, 3).
pub fn primitive() -> impl Strategy<Value = Primitive> {
    let d = || 0.1..3.0f64;
    prop_oneof![
        d().prop_map(|length| Primitive::Rod { length }),
        (d(), d()).prop_map(|(a, b)| Primitive::Plate { a, b }),
        (d(), d(), d()).prop_map(|(a, b, c)| Primitive::Prism { a, b, c }),
        d().prop_map(|radius| Primitive::Disk { radius }),
        (d(), d()).prop_map(|(radius, length)| Primitive::Cylinder { radius, length }),
        (0.0..1.0f64, d(), d()).prop_map(|(f, outer, length)| Primitive::HollowCylinder {
            inner: f * outer,
            outer,
            length
        }),
        d().prop_map(|radius| Primitive::Ring { radius }),
        d().prop_map(|radius| Primitive::Sphere { radius }),
        d().prop_map(|radius| Primitive::SphericalShell { radius }),
        (d(), d()).prop_map(|(radius, height)| Primitive::Cone { radius, height }),
    ]
}

/// A posed primitive with mass in (0.1, 10).
pub fn rigid_body() -> impl Strategy<Value = Body> {
    (primitive(), 0.1..10.0f64, pose())
        .prop_map(|(s, m, p)| Body::try_new(s, m, p).expect("valid by construction"))
}
