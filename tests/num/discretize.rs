//! Discretised primitives against their analytic mass properties.

use hdot_num::discretize::particle_count;
use hdot_num::sums::mass_properties;
use hdot_num::{Body, Discretization, DiscretizedBody, ParticleSource, Pose, Primitive};
use nalgebra::{Matrix3, Vector3};

pub fn all_primitives() -> Vec<Primitive> {
    vec![
        Primitive::Rod { length: 2.0 },
        Primitive::Plate { a: 1.2, b: 0.8 },
        Primitive::Prism {
            a: 1.2,
            b: 0.8,
            c: 0.5,
        },
        Primitive::Disk { radius: 0.7 },
        Primitive::Cylinder {
            radius: 0.4,
            length: 1.5,
        },
        Primitive::HollowCylinder {
            inner: 0.3,
            outer: 0.5,
            length: 1.0,
        },
        Primitive::HollowCylinder {
            inner: 0.5,
            outer: 0.5,
            length: 1.0,
        },
        Primitive::Ring { radius: 0.9 },
        Primitive::Sphere { radius: 0.6 },
        Primitive::SphericalShell { radius: 0.6 },
        Primitive::Cone {
            radius: 0.5,
            height: 1.2,
        },
    ]
}

fn rel_err(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).norm() / b.norm()
}

#[test]
fn gauss_legendre_converges_to_the_table_for_every_primitive() {
    for shape in all_primitives() {
        let body = Body::try_new(shape, 2.5, Pose::identity()).unwrap();
        let exact = body.mass_properties();
        let d = Discretization::gauss(12, 3);
        let src = DiscretizedBody::new(&body, &d);
        assert_eq!(src.len(), particle_count(&shape, &d), "{shape:?}");
        let p = mass_properties(&src).unwrap();
        let scale = exact.inertia_g.trace();
        assert!(
            (p.mass - 2.5).abs() <= 64.0 * f64::EPSILON * 2.5,
            "{shape:?}"
        );
        assert!(
            p.center.norm() <= 1e-12 * scale.sqrt(),
            "{shape:?} centre {}",
            p.center
        );
        let e = rel_err(p.inertia_g.matrix(), exact.inertia_g.matrix());
        assert!(e < 1e-7, "{shape:?}: relative error {e:e}");
    }
}

#[test]
fn midpoint_error_falls_like_h_squared() {
    for shape in all_primitives() {
        let body = Body::try_new(shape, 1.0, Pose::identity()).unwrap();
        let exact = body.mass_properties();
        let err = |n| {
            let p = mass_properties(&DiscretizedBody::new(&body, &Discretization::midpoint(n)))
                .unwrap();
            rel_err(p.inertia_g.matrix(), exact.inertia_g.matrix())
        };
        let (e1, e2) = (err(10), err(20));
        if e1 < 1e-12 {
            // Rings and shells: the uniform rule is exact for these
            // trigonometric integrands; nothing to converge.
            assert!(e2 < 1e-12, "{shape:?}");
            continue;
        }
        let order = (e1 / e2).log2();
        assert!(
            order > 1.8,
            "{shape:?}: errors {e1:e} {e2:e}, observed order {order}"
        );
    }
}

#[test]
fn posed_discretisation_matches_rotated_analytic_tensor() {
    let pose = Pose::new(
        Vector3::new(1.0, -2.0, 0.5),
        nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1),
    );
    for shape in all_primitives() {
        let body = Body::try_new(shape, 3.0, pose).unwrap();
        let exact = body.mass_properties();
        let p =
            mass_properties(&DiscretizedBody::new(&body, &Discretization::gauss(10, 3))).unwrap();
        assert!((p.center - exact.center).norm() < 1e-9, "{shape:?}");
        let e = rel_err(p.inertia_g.matrix(), exact.inertia_g.matrix());
        assert!(e < 1e-7, "{shape:?}: {e:e}");
    }
}

/// The midpoint grid on a box has a closed-form error: with n cells of
/// width h = a/n along x, Σ m x² = m (a²/12)(1 − 1/n²).
#[test]
fn box_midpoint_error_has_its_closed_form() {
    let (a, b, c, m) = (1.3, 0.7, 0.4, 2.0);
    let body = Body::try_new(Primitive::Prism { a, b, c }, m, Pose::identity()).unwrap();
    for n in [1usize, 2, 3, 7, 16] {
        let src = DiscretizedBody::new(&body, &Discretization::midpoint(n));
        let mo = hdot_num::sums::moments(&src, Vector3::zeros());
        let nf = n as f64;
        for (k, side) in [a, b, c].into_iter().enumerate() {
            let expected = m * side * side / 12.0 * (1.0 - 1.0 / (nf * nf));
            let tol = 64.0 * f64::EPSILON * m * side * side;
            assert!(
                (mo.second[k] - expected).abs() <= tol,
                "n = {n}, axis {k}: {} vs {expected}",
                mo.second[k]
            );
        }
    }
    // and Gauss–Legendre with 2 points per cell is exact on boxes
    let src = DiscretizedBody::new(&body, &Discretization::gauss(1, 2));
    let mo = hdot_num::sums::moments(&src, Vector3::zeros());
    let tol = 64.0 * f64::EPSILON * m * a * a;
    assert!((mo.second[0] - m * a * a / 12.0).abs() <= tol);
}
