//! Particle sums: determinism and the rigid-body laws.

use hdot_num::sums::{kinetics, mass_properties, moments, rigid_kinetics};
use hdot_num::{Body, Discretization, DiscretizedBody, Motion, Pose, Primitive};
use nalgebra::Vector3;
use proptest::prelude::*;

use crate::strategies::{angular_velocity, particle_cloud, rigid_body, vector3};

#[test]
fn sums_are_bitwise_identical_for_any_thread_count() {
    let body = Body::try_new(
        Primitive::Cone {
            radius: 0.5,
            height: 1.1,
        },
        3.0,
        Pose::translation(Vector3::new(0.3, 0.1, -0.2)),
    )
    .unwrap();
    let src = DiscretizedBody::new(&body, &Discretization::gauss(25, 2)); // 125 000 particles
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| moments(&src, Vector3::zeros()))
    };
    let one = run(1);
    for t in [2, 3, 7] {
        let m = run(t);
        assert_eq!(m.mass.to_bits(), one.mass.to_bits());
        for k in 0..6 {
            assert_eq!(
                m.second[k].to_bits(),
                one.second[k].to_bits(),
                "threads {t}"
            );
        }
    }
}

/// Relative difference of two vectors, scaled by a magnitude.
fn close(a: Vector3<f64>, b: Vector3<f64>, scale: f64) -> bool {
    (a - b).norm() <= 1e4 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
}

proptest! {
    #![proptest_config(hdot_tests::proptest_config(64))]

    /// H_G = I_G ω, H_O = r̄ × m v̄ + H_G, T, ΣF = m ā and
    /// Ḣ_G = I α + ω × (I ω) equal the direct particle sums.
    #[test]
    fn rigid_formulas_equal_particle_sums(
        cloud in particle_cloud(),
        omega in angular_velocity(),
        alpha in angular_velocity(),
        v in vector3(3.0),
        a in vector3(3.0),
        o in vector3(3.0),
    ) {
        let props = mass_properties(&cloud).unwrap();
        let motion = Motion { omega, alpha, v_g: v, a_g: a };
        let sums = kinetics(&cloud, &motion, props.center, o);
        let rigid = rigid_kinetics(&props, &motion, o);
        let l = 1.0 + (props.center - o).norm() + (props.inertia_g.trace() / props.mass).sqrt();
        let w = 1.0 + omega.norm();
        let s_h = props.mass * l * (v.norm() + w * l);
        let s_a = props.mass * l * (a.norm() + (alpha.norm() + w * w) * l);
        prop_assert!(close(sums.h_g, rigid.h_g, s_h));
        prop_assert!(close(sums.h_o, rigid.h_o, s_h));
        prop_assert!(close(sums.force, rigid.force, s_a));
        prop_assert!(close(sums.hdot_g, rigid.hdot_g, s_a));
        prop_assert!(close(sums.moment_o, rigid.moment_o, s_a));
        let t_scale = props.mass * (v.norm() + w * l).powi(2);
        prop_assert!((sums.kinetic_energy - rigid.kinetic_energy).abs() <= 1e4 * f64::EPSILON * t_scale);
    }

    /// Discretised primitives: the same laws hold to round-off, because a
    /// set of particles *is* a rigid body.
    #[test]
    fn rigid_formulas_hold_for_discretised_bodies(
        body in rigid_body(),
        omega in angular_velocity(),
        alpha in angular_velocity(),
    ) {
        let src = DiscretizedBody::new(&body, &Discretization::midpoint(6));
        let props = mass_properties(&src).unwrap();
        let o = body.pose().position + Vector3::new(0.5, -0.3, 0.2);
        let motion = Motion::about_fixed_point(o, props.center, omega, alpha);
        let sums = kinetics(&src, &motion, props.center, o);
        let rigid = rigid_kinetics(&props, &motion, o);
        let l = 1.0 + (props.inertia_g.trace() / props.mass).sqrt() + 1.0;
        let w = 1.0 + omega.norm();
        let s_a = props.mass * l * l * (alpha.norm() + w * w);
        prop_assert!(close(sums.moment_o, rigid.moment_o, s_a));
        prop_assert!(close(sums.hdot_g, rigid.hdot_g, s_a));
    }
}
