use hdot_sim::exact::TorqueFree;
use hdot_sim::systems::free::{pack, state_distance};
use hdot_sim::systems::{FreeBody, Gravity, Shaft};
use hdot_sim::{Limits, Method, SimError, Step, integrate};

use crate::exact::issue_body;

/// Least-squares slope of log(error) against log(h).
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let xs: Vec<f64> = points.iter().map(|p| p.0.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

fn run(method: Method, step: Step, t: f64) -> Result<([f64; 7], hdot_sim::Stats), SimError> {
    let (i, q0, w0) = issue_body();
    let body = FreeBody {
        moments: i,
        gravity: None,
    };
    integrate(
        &body,
        method,
        step,
        0.0,
        pack(&q0, &w0),
        t,
        Limits::default(),
        |_, _| Ok(()),
    )
}

/// Measured convergence slopes lie within ±0.2 of each method's order.
/// Step counts are chosen per method so that the error stays well above
/// round-off and inside the asymptotic range.
#[test]
fn convergence_slopes_match_the_orders() {
    let (i, q0, w0) = issue_body();
    let t = 1.0;
    let exact = TorqueFree::new(i, q0, w0).unwrap().state(t);
    let cases: [(Method, &[u64]); 7] = [
        (Method::Euler, &[400, 800, 1600, 3200]),
        (Method::Rk4, &[20, 40, 80, 160]),
        (Method::Dopri5, &[20, 30, 40, 60, 80]),
        (Method::Dop853, &[5, 6, 8, 10, 12]),
        (Method::Midpoint, &[20, 40, 80, 160]),
        (Method::Split2, &[20, 40, 80, 160]),
        (Method::Split4, &[10, 20, 40, 80]),
    ];
    for (method, ns) in cases {
        let pts: Vec<(f64, f64)> = ns
            .iter()
            .map(|&n| {
                let h = t / n as f64;
                let (y, _) = run(method, Step::Fixed(h), t).unwrap();
                (h, state_distance(&y, &exact))
            })
            .collect();
        let p = slope(&pts);
        let order = method.order() as f64;
        assert!(
            (p - order).abs() <= 0.2,
            "{method}: slope {p:.3}, order {order}, points {pts:?}"
        );
    }
}

#[test]
fn adaptive_methods_meet_their_tolerance_on_the_issue_body() {
    let (i, q0, w0) = issue_body();
    let t = 10.0;
    let exact = TorqueFree::new(i, q0, w0).unwrap().state(t);
    for method in [Method::Dopri5, Method::Dop853] {
        let mut last = f64::INFINITY;
        for tol in [1e-6, 1e-8, 1e-10] {
            let (y, stats) = run(method, Step::Tolerance(tol), t).unwrap();
            let err = state_distance(&y, &exact);
            // Global error: within two orders of the local tolerance over 10 time units,
            // and decreasing as the tolerance tightens.
            assert!(
                err <= 100.0 * tol * t,
                "{method} tol {tol:e}: error {err:e}"
            );
            assert!(err < last);
            assert!(stats.evaluations > 0 && stats.steps > 0);
            last = err;
        }
    }
}

#[test]
fn dop853_counts_twelve_evaluations_per_accepted_step() {
    let (_, stats) = run(Method::Dop853, Step::Tolerance(1e-9), 10.0).unwrap();
    // 1 initial + 1 for hinit + 12 per accepted step + 11 per rejected step.
    assert_eq!(
        stats.evaluations,
        2 + 12 * stats.steps + 11 * stats.rejected
    );
}

#[test]
fn implicit_midpoint_and_splittings_keep_quadratic_invariants() {
    let (i, q0, w0) = issue_body();
    let body = FreeBody {
        moments: i,
        gravity: None,
    };
    let y0 = pack(&q0, &w0);
    for method in [Method::Midpoint, Method::Split2, Method::Split4] {
        let (y, _) = run(method, Step::Fixed(0.05), 20.0).unwrap();
        let h0 = body.momentum_norm(&y0);
        // |H| is quadratic: the midpoint rule keeps it to the iteration's round-off,
        // the splittings (exact rotations) to round-off per sub-flow.
        assert!(
            (body.momentum_norm(&y) - h0).abs() <= 1e-12 * h0,
            "{method}"
        );
        let qn = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3]).sqrt();
        assert!((qn - 1.0).abs() <= 1e-12, "{method}: |q| = {qn}");
    }
}

#[test]
fn shaft_methods_converge_to_the_closed_form() {
    let shaft = Shaft {
        i_z: 0.0150,
        i_xz: 1e-4,
        i_yz: -2e-5,
        mass: 0.09,
        xbar: 0.004,
        ybar: 0.001,
        stall_torque: 0.5,
        no_load_speed: 300.0,
        friction: 1e-4,
        bearings: [-0.15, 0.15],
    };
    let y0 = [0.0, 0.0];
    let t = 2.0;
    let exact = shaft.exact(&y0, t);
    for method in hdot_sim::Method::ALL {
        let step = if method.is_adaptive() {
            Step::Tolerance(1e-10)
        } else {
            Step::Fixed(1e-3)
        };
        let (y, _) = integrate(
            &shaft,
            method,
            step,
            0.0,
            y0,
            t,
            Limits::default(),
            |_, _| Ok(()),
        )
        .unwrap();
        let scale = exact[0].abs() + exact[1].abs();
        // First order: h · |α| · T ≈ 1e-3 · 30 · 2; the others far below.
        let tol = if method == Method::Euler {
            1e-3 * scale
        } else {
            1e-6 * scale
        };
        assert!(
            (y[0] - exact[0]).abs() + (y[1] - exact[1]).abs() <= tol,
            "{method}: {y:?} vs {exact:?}"
        );
    }
}

#[test]
fn bearing_reactions_balance_the_effective_forces() {
    // §6 with the reactions: R_A + R_B = m ā and Σ z e_3 × R = (ΣM_x, ΣM_y).
    let shaft = Shaft {
        i_z: 0.02,
        i_xz: 3e-4,
        i_yz: -1e-4,
        mass: 0.1,
        xbar: 0.01,
        ybar: -0.02,
        stall_torque: 1.0,
        no_load_speed: f64::INFINITY,
        friction: 0.0,
        bearings: [-0.1, 0.25],
    };
    for w in [0.0, 10.0, 100.0] {
        let r = shaft.reactions(w);
        let [za, zb] = shaft.bearings;
        let fx = shaft.mass * (-r.alpha * shaft.ybar - w * w * shaft.xbar);
        let fy = shaft.mass * (r.alpha * shaft.xbar - w * w * shaft.ybar);
        let scale = 1.0 + fx.abs() + fy.abs() + r.moment_x.abs() + r.moment_y.abs();
        let tol = 16.0 * f64::EPSILON * scale;
        assert!((r.bearing_a[0] + r.bearing_b[0] - fx).abs() <= tol);
        assert!((r.bearing_a[1] + r.bearing_b[1] - fy).abs() <= tol);
        assert!((-(za * r.bearing_a[1] + zb * r.bearing_b[1]) - r.moment_x).abs() <= tol);
        assert!((za * r.bearing_a[0] + zb * r.bearing_b[0] - r.moment_y).abs() <= tol);
        // §6: ΣM_x = −I_xz α + I_yz ω², ΣM_y = −I_yz α − I_xz ω².
        assert!((r.moment_x - (-shaft.i_xz * r.alpha + shaft.i_yz * w * w)).abs() <= tol);
        assert!((r.moment_y - (-shaft.i_yz * r.alpha - shaft.i_xz * w * w)).abs() <= tol);
    }
}

#[test]
fn euler_angle_and_quaternion_models_agree_away_from_the_singularity() {
    use hdot_sim::systems::EulerAngleBody;
    use hdot_sim::systems::euler_angles::{quaternion_from_angles, to_quaternion_state};
    let moments = [0.03, 0.03, 0.01];
    let wl = 0.2;
    let q0 = quaternion_from_angles(0.2, 0.7, -0.4);
    let w0 = hdot_sim::nalgebra::Vector3::new(0.5, -0.3, 30.0);
    let quat = FreeBody {
        moments,
        gravity: Some(Gravity { weight_arm: wl }),
    };
    let euler = EulerAngleBody {
        moments,
        weight_arm: wl,
    };
    let t = 1.0;
    let step = Step::Tolerance(1e-12);
    let (yq, _) = integrate(
        &quat,
        Method::Dop853,
        step,
        0.0,
        pack(&q0, &w0),
        t,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap();
    let e0 = [0.2, 0.7, -0.4, w0.x, w0.y, w0.z];
    let (ye, _) = integrate(
        &euler,
        Method::Dop853,
        step,
        0.0,
        e0,
        t,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap();
    let d = state_distance(&yq, &to_quaternion_state(&ye));
    assert!(d <= 1e-8 * w0.norm(), "distance {d:e}");
    // And the gravity torque is W l sin θ about the line of nodes (§7 frame, ψ = 0).
    let tau = quat.torque(&pack(&quaternion_from_angles(0.0, 0.7, 0.0), &w0));
    assert!((tau[1] - wl * 0.7f64.sin()).abs() <= 4.0 * f64::EPSILON * wl);
    assert!(tau[0].abs() <= 4.0 * f64::EPSILON * wl);
}
