//! Accuracy and cost targets of issue 5 on the torque-free body
//! I = (0.6, 0.8, 1.0), H = (1.8, 0.4, −0.9), identity attitude, T = 100.
//! Counts and errors, not times: the timing comparison with ode_solvers is
//! the criterion benchmark `benches/dop853.rs`.
//!
//! Errors are [`state_error`]: the attitude as a rotation angle, ω as a norm,
//! combined as `√(angle² + |Δω|²)`, always on the full attitude and ω
//! against the exact elliptic solution, whatever state the integrator used.

use hdot_sim::exact::TorqueFree;
use hdot_sim::nalgebra::{UnitQuaternion, Vector3};
use hdot_sim::systems::free::{EulerEquations, pack, state_error};
use hdot_sim::systems::{FreeBody, PrecessionAngle};
use hdot_sim::{Limits, Method, Stats, Step, System, integrate};

const T: f64 = 100.0;
const I: [f64; 3] = [0.6, 0.8, 1.0];

fn start() -> (UnitQuaternion<f64>, Vector3<f64>) {
    (
        UnitQuaternion::identity(),
        Vector3::new(1.8 / 0.6, 0.4 / 0.8, -0.9 / 1.0),
    )
}

fn exact_at_t() -> [f64; 7] {
    let (q0, w0) = start();
    TorqueFree::new(I, q0, w0).unwrap().state(T)
}

fn dop853<const N: usize, S: System<N>>(sys: &S, y0: [f64; N], tol: f64) -> ([f64; N], Stats) {
    integrate(
        sys,
        Method::Dop853,
        Step::Tolerance(tol),
        0.0,
        y0,
        T,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap()
}

fn quaternion_form() -> (FreeBody, [f64; 7]) {
    let (q0, w0) = start();
    let body = FreeBody {
        moments: I,
        gravity: None,
    };
    (body, pack(&q0, &w0))
}

fn precession_form() -> (PrecessionAngle, [f64; 4]) {
    let (q0, w0) = start();
    PrecessionAngle::new(I, &q0, &w0).unwrap()
}

/// Tolerance at which DOP853 on the precession-angle model meets the
/// 2e-9 target within 4,500 evaluations.
pub const TARGET_TOL: f64 = 1e-10;

#[test]
fn exact_solution_and_tight_dop853_agree_at_t_100() {
    let (b, y0) = quaternion_form();
    let (y, _) = dop853(&b, y0, 1e-14);
    let e = state_error(&y, &exact_at_t());
    assert!(e.combined() <= 1e-11, "quaternion form: {e:?}");

    let (p, z0) = precession_form();
    let (z, _) = dop853(&p, z0, 1e-14);
    let e = state_error(&p.full_state(&z), &exact_at_t());
    assert!(e.combined() <= 1e-11, "precession-angle form: {e:?}");
}

/// The target on the full attitude and ω: met by the precession-angle model
/// (ω and one angle about the invariable H, ω projected onto E and |H|).
#[test]
fn dop853_reaches_2e_9_at_t_100_within_4500_evaluations() {
    let (p, z0) = precession_form();
    let (z, stats) = dop853(&p, z0, TARGET_TOL);
    let e = state_error(&p.full_state(&z), &exact_at_t());
    assert!(e.combined() <= 2e-9, "error {e:?}");
    assert!(
        stats.evaluations <= 4500,
        "{} evaluations",
        stats.evaluations
    );
}

/// Euler's equations alone (ω, 3 components) meet it too, on ω.
#[test]
fn euler_equations_reach_2e_9_within_4500_evaluations() {
    let (_, w0) = start();
    let (w, stats) = dop853(&EulerEquations { moments: I }, w0.into(), TARGET_TOL);
    let we = exact_at_t();
    let d = (0..3)
        .map(|k| (w[k] - we[k + 4]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(d <= 2e-9, "error {d:e}");
    assert!(stats.evaluations <= 4500, "{}", stats.evaluations);
}

/// Why the quaternion form misses the target: at about the same cost
/// (within 10 % of the evaluations) its error is an order of magnitude
/// larger than the projected precession-angle form's, and projecting onto
/// the invariants is what brings the error down (the same form without it,
/// at the same tolerance, gives several times the error). The claim is the
/// ratio at equal cost, not the particular numbers (those are in
/// docs/performance.md).
#[test]
fn the_quaternion_form_and_the_unprojected_form_miss_it() {
    let (p, z0) = precession_form();
    let (z, best) = dop853(&p, z0, TARGET_TOL);
    let projected = state_error(&p.full_state(&z), &exact_at_t()).combined();

    let (b, y0) = quaternion_form();
    let (y, s) = dop853(&b, y0, 3e-10);
    let quaternion = state_error(&y, &exact_at_t()).combined();
    let cost = s.evaluations as f64 / best.evaluations as f64;
    assert!((0.9..=1.1).contains(&cost), "{s:?} against {best:?}");
    assert!(
        quaternion > 10.0 * projected,
        "quaternion {quaternion:e}, projected {projected:e}"
    );

    let mut unprojected = p;
    unprojected.projection = false;
    let (z, s) = dop853(&unprojected, z0, TARGET_TOL);
    let e = state_error(&unprojected.full_state(&z), &exact_at_t()).combined();
    let cost = s.evaluations as f64 / best.evaluations as f64;
    assert!((0.9..=1.1).contains(&cost), "{s:?} against {best:?}");
    assert!(
        e > 5.0 * projected,
        "unprojected {e:e}, projected {projected:e}"
    );
}

#[test]
#[ignore = "exploration: prints error and cost against tolerance"]
fn print_dop853_sweep() {
    let ye = exact_at_t();
    let (b, y0) = quaternion_form();
    let (p, z0) = precession_form();
    let mut q = p;
    q.projection = false;
    for k in 16..=28 {
        let tol = 10f64.powf(-k as f64 / 2.0);
        let (y, s) = dop853(&b, y0, tol);
        let e = state_error(&y, &ye);
        println!(
            "quaternion          tol {tol:.2e}: evals {:5}, angle {:.3e}, |Δω| {:.3e}",
            s.evaluations, e.attitude, e.omega
        );
        for (name, sys) in [("precession-angle", &p), ("  without projection", &q)] {
            let (z, s) = dop853(sys, z0, tol);
            let e = state_error(&sys.full_state(&z), &ye);
            println!(
                "{name:<20}tol {tol:.2e}: evals {:5}, angle {:.3e}, |Δω| {:.3e}",
                s.evaluations, e.attitude, e.omega
            );
        }
    }
}
