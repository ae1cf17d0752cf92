//! The inertia invariant, parallel axes and principal axes.

use hdot_num::{Inertia, InertiaError, MassProperties};
use nalgebra::{Matrix3, Rotation3, Vector3};
use proptest::prelude::*;

use crate::strategies::{particle_cloud, rigid_body, rotation, vector3};

#[test]
fn impossible_tensors_are_rejected_and_flat_ones_accepted() {
    // table: (Ix, Iy, Iz, Ixy, Iyz, Izx) => accepted?
    let cases: &[([f64; 6], bool)] = &[
        ([1.0, 3.0, 5.0, 0.0, 0.0, 0.0], false), // positive definite, impossible
        ([1.0, 3.0, 4.0, 0.0, 0.0, 0.0], true),  // flat body, exactly on the inequality
        ([0.0, 1.0, 1.0, 0.0, 0.0, 0.0], true),  // rod
        ([1.0, 1.0, 1.0, 2.0, 0.0, 0.0], false), // not PSD
        ([2.0, 2.0, 2.0, 0.5, 0.3, -0.2], true),
    ];
    for (c, ok) in cases {
        let r = Inertia::from_components(c[0], c[1], c[2], c[3], c[4], c[5]);
        assert_eq!(r.is_ok(), *ok, "{c:?}: {r:?}");
    }
    assert!(matches!(
        Inertia::diagonal(1.0, 3.0, 5.0),
        Err(InertiaError::Triangle { .. })
    ));
}

#[test]
fn flat_body_from_a_rotated_plate_is_accepted() {
    // the rotated tensor of a plate carries round-off; the relative
    // tolerance must still accept it
    let plate = Inertia::diagonal(0.49 / 12.0, 0.09 / 12.0, 0.58 / 12.0).unwrap();
    let r = Rotation3::from_euler_angles(0.4, 1.2, -2.0);
    let m = *plate.rotated(&r).matrix();
    assert!(Inertia::try_new(m).is_ok());
}

#[test]
fn repeated_moments_give_the_canonical_basis() {
    // axisymmetric about a tilted axis: the symmetry axis is found, the
    // plane basis does not depend on round-off
    let r = Rotation3::from_euler_angles(0.3, 0.2, 0.1);
    let disk = Inertia::diagonal(1.0, 1.0, 2.0).unwrap().rotated(&r);
    let p = disk.principal();
    assert_eq!(p.multiplicity, [2, 2, 1]);
    let axis = r * Vector3::z();
    assert!((p.axes.matrix().column(2) - axis).norm() < 1e-12);
    let mut perturbed = *disk.matrix();
    perturbed[(0, 0)] *= 1.0 + 4.0 * f64::EPSILON;
    let q = Inertia::try_new(perturbed).unwrap().principal();
    assert!((q.axes.matrix() - p.axes.matrix()).norm() < 1e-9);
    // sphere: the world axes
    let s = Inertia::diagonal(0.4, 0.4, 0.4 * (1.0 + 1e-13))
        .unwrap()
        .principal();
    assert_eq!(s.multiplicity, [3, 3, 3]);
    assert_eq!(*s.axes.matrix(), Matrix3::identity());
}

proptest! {
    #![proptest_config(hdot_tests::proptest_config(64))]

    /// Parallel axes: the tensor about any point from the tensor about G
    /// equals the direct particle sum about that point.
    #[test]
    fn parallel_axis_matches_particle_sum(cloud in particle_cloud(), p in vector3(3.0)) {
        let props = cloud.mass_properties();
        let direct = hdot_num::sums::moments(&cloud, p).inertia();
        let shifted = props.inertia_about(&p);
        let scale = direct.trace() + props.mass * (props.center - p).norm_squared();
        prop_assert!((direct.matrix() - shifted.matrix()).norm() <= 1e3 * f64::EPSILON * scale);
    }

    /// Any body's tensor satisfies the invariant; principal axes
    /// diagonalise it into ascending moments.
    #[test]
    fn principal_axes_diagonalise(body in rigid_body(), r in rotation()) {
        let props = body.mass_properties();
        prop_assert!(Inertia::try_new(*props.inertia_g.matrix()).is_ok());
        let p = props.principal();
        let d = props.inertia_g.in_axes(&p.axes);
        let scale = props.inertia_g.trace();
        let diag = Matrix3::from_diagonal(&p.moments);
        prop_assert!((d.matrix() - diag).norm() <= 1e-8 * scale);
        prop_assert!(p.moments[0] <= p.moments[1] && p.moments[1] <= p.moments[2]);
        prop_assert!((p.axes.matrix().determinant() - 1.0).abs() < 1e-12);
        // rotating into other axes and back is the identity
        let r = r.to_rotation_matrix();
        let back = props.inertia_g.in_axes(&r).rotated(&r);
        prop_assert!((back.matrix() - props.inertia_g.matrix()).norm() <= 1e2 * f64::EPSILON * scale);
    }

    /// Combining parts equals the particle sum of their union.
    #[test]
    fn composite_equals_union(a in particle_cloud(), b in particle_cloud()) {
        let ab = MassProperties::combine(&[a.mass_properties(), b.mass_properties()]).unwrap();
        let (ax, ay, az, am) = a.arrays();
        let (bx, by, bz, bm) = b.arrays();
        let u = hdot_num::ParticleCloud::try_from_arrays(
            [ax, bx].concat(), [ay, by].concat(), [az, bz].concat(), [am, bm].concat()).unwrap();
        let up = u.mass_properties();
        let scale = up.inertia_g.trace() + up.mass;
        prop_assert!((ab.mass - up.mass).abs() <= 64.0 * f64::EPSILON * up.mass);
        prop_assert!((ab.center - up.center).norm() <= 1e3 * f64::EPSILON * (1.0 + up.center.norm()));
        prop_assert!((ab.inertia_g.matrix() - up.inertia_g.matrix()).norm() <= 1e3 * f64::EPSILON * scale);
    }
}
