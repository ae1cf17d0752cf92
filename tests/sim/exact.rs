use hdot_sim::exact::{SteadyTop, TorqueFree};
use hdot_sim::nalgebra::{UnitQuaternion, Vector3};
use hdot_sim::systems::free::{pack, state_distance};
use hdot_sim::systems::{FreeBody, Gravity};
use hdot_sim::{Limits, Method, Step, integrate};
use proptest::prelude::*;

use crate::strategies::{angular_velocity, asymmetric_moments};

/// The asymmetric body of issue 5: I = (0.6, 0.8, 1.0), H = (1.8, 0.4, −0.9).
pub fn issue_body() -> ([f64; 3], UnitQuaternion<f64>, Vector3<f64>) {
    let i = [0.6, 0.8, 1.0];
    let h = [1.8, 0.4, -0.9];
    (
        i,
        UnitQuaternion::identity(),
        Vector3::new(h[0] / i[0], h[1] / i[1], h[2] / i[2]),
    )
}

fn dop853(i: [f64; 3], y0: [f64; 7], t: f64, tol: f64) -> [f64; 7] {
    let body = FreeBody {
        moments: i,
        gravity: None,
    };
    integrate(
        &body,
        Method::Dop853,
        Step::Tolerance(tol),
        0.0,
        y0,
        t,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap()
    .0
}

#[test]
fn elliptic_solution_matches_tight_dop853_on_the_issue_body() {
    let (i, q0, w0) = issue_body();
    let exact = TorqueFree::new(i, q0, w0).unwrap();
    assert!(matches!(exact, TorqueFree::Elliptic(_)));
    let y0 = pack(&q0, &w0);
    assert!(state_distance(&exact.state(0.0), &y0) <= 16.0 * f64::EPSILON * 4.0);
    let t = 10.0;
    let d = state_distance(&exact.state(t), &dop853(i, y0, t, 1e-13));
    // DOP853 at 1e-13 over 10 time units: global error well under 1e-10 · |y|.
    assert!(d <= 1e-10 * 4.0, "distance {d:e}");
}

#[test]
fn elliptic_solution_conserves_spatial_momentum_and_energy() {
    let (i, q0, w0) = issue_body();
    let exact = TorqueFree::new(i, q0, w0).unwrap();
    let body = FreeBody {
        moments: i,
        gravity: None,
    };
    let y0 = exact.state(0.0);
    let h0 = q0 * Vector3::from(body.momentum(&y0));
    let e0 = body.energy(&y0);
    for k in 0..50 {
        let t = 0.37 * k as f64 + 0.1;
        let y = exact.state(t);
        let q = hdot_sim::systems::free::attitude(&y);
        let h = q * Vector3::from(body.momentum(&y));
        assert!(
            (h - h0).norm() <= 64.0 * f64::EPSILON * h0.norm() * (1.0 + t),
            "t = {t}: {:e}",
            (h - h0).norm()
        );
        assert!((body.energy(&y) - e0).abs() <= 16.0 * f64::EPSILON * e0);
    }
}

#[test]
fn axisymmetric_closed_form_matches_dop853_elongated_and_flattened() {
    for i in [[1.0, 1.0, 0.4], [1.0, 1.0, 1.8]] {
        let w0 = Vector3::new(0.7, -0.3, 2.0);
        let q0 = UnitQuaternion::from_euler_angles(0.3, -0.2, 1.0);
        let exact = TorqueFree::new(i, q0, w0).unwrap();
        let TorqueFree::Axisymmetric(a) = &exact else {
            panic!("expected the axisymmetric form")
        };
        // §9: direct precession (same sense) when I < I', retrograde when I > I'.
        assert_eq!(
            a.spin_rate.signum() == a.precession_rate.signum() * w0.z.signum(),
            i[2] < i[0]
        );
        let y0 = pack(&q0, &w0);
        let d = state_distance(&exact.state(5.0), &dop853(i, y0, 5.0, 1e-13));
        assert!(d <= 1e-10 * 3.0, "I = {i:?}: {d:e}");
    }
}

#[test]
fn steady_top_is_a_solution_of_the_heavy_top_equations() {
    // Gyroscope: I = 0.02 axial, I' = 0.015 about O, W l = 0.5, θ = 60°, ω_z = 100.
    let (ia, it, wl, theta, wz) = (0.02, 0.015, 0.5, 1.0471975511965976, 100.0);
    let phi_dot = SteadyTop::slow_precession_rate(ia, it, wl, theta, wz).unwrap();
    let top = SteadyTop {
        phi0: 0.0,
        theta,
        psi0: 0.0,
        phi_dot,
        psi_dot: wz - phi_dot * theta.cos(),
        omega_z: wz,
    };
    assert!(top.residual(ia, it, wl) <= 8.0 * f64::EPSILON);
    let body = FreeBody {
        moments: [it, it, ia],
        gravity: Some(Gravity { weight_arm: wl }),
    };
    let t = 2.0;
    let y = integrate(
        &body,
        Method::Dop853,
        Step::Tolerance(1e-13),
        0.0,
        top.state(0.0),
        t,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap()
    .0;
    let d = state_distance(&y, &top.state(t));
    assert!(d <= 1e-9 * wz, "distance {d:e}");
}

proptest! {
    #![proptest_config(hdot_tests::proptest_config(24))]
    #[test]
    fn elliptic_matches_dop853_for_random_bodies(i in asymmetric_moments(), w in angular_velocity()) {
        let w0 = Vector3::from(w);
        let q0 = UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3);
        let exact = TorqueFree::new(i, q0, w0).unwrap();
        let scale = 1.0 + w0.norm();
        let t = 3.0;
        let d = state_distance(&exact.state(t), &dop853(i, pack(&q0, &w0), t, 1e-13));
        prop_assert!(d <= 1e-10 * scale * scale, "distance {:e}", d);
    }
}
