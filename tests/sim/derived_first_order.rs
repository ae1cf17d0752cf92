//! First-order derived scenes (systems/derived/first_order.rs): the
//! gyrostat in its body rates, integrated with its attitude, against an
//! independent integration of Euler's equations with the rotation matrix
//! integrated directly; every method that applies; bad scenes refused
//! naming their field.

use std::path::PathBuf;

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::{Method, SimError, Step};
use hdot_tests::repo_root;
use nalgebra::{Matrix3, Vector3};

fn example(name: &str) -> PathBuf {
    repo_root().join("docs/examples").join(name)
}

fn run_scene(scene: &Scene, req: Request) -> run::Report {
    let plan = run::plan(scene, &req).expect("plan");
    run::run(scene, &plan, &mut Output::default()).expect("run")
}

/// The scene run by DOP853 at tolerance `tol`.
fn run_dop853(scene: &Scene, tol: f64) -> run::Report {
    run_scene(
        scene,
        Request {
            method: Some(Method::Dop853),
            step: Some(Step::Tolerance(tol)),
            ..Request::default()
        },
    )
}

/// The gyrostat's constants and start, as the bundled scene gives them.
const MOMENTS: [f64; 3] = [0.6, 0.8, 1.0];
const ROTOR: f64 = 0.3;

fn hat(w: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -w.z, w.y, w.z, 0.0, -w.x, -w.y, w.x, 0.0)
}

/// Euler's equations of the gyrostat, I ω̇ = −ω × (I ω + h e₃), and the
/// attitude Ṙ = R [ω]× (R's columns the body axes in N), integrated by
/// the classical Runge–Kutta method at a fixed step: no Euler angles, no
/// derivation.
fn reference(
    r0: Matrix3<f64>,
    w0: Vector3<f64>,
    t_end: f64,
    steps: usize,
) -> (Matrix3<f64>, Vector3<f64>) {
    let i = Vector3::from(MOMENTS);
    let f = |r: &Matrix3<f64>, w: &Vector3<f64>| {
        let h = i.component_mul(w) + Vector3::new(0.0, 0.0, ROTOR);
        (r * hat(w), (-w.cross(&h)).component_div(&i))
    };
    let dt = t_end / steps as f64;
    let (mut r, mut w) = (r0, w0);
    for _ in 0..steps {
        let (r1, w1) = f(&r, &w);
        let (r2, w2) = f(&(r + r1 * (dt / 2.0)), &(w + w1 * (dt / 2.0)));
        let (r3, w3) = f(&(r + r2 * (dt / 2.0)), &(w + w2 * (dt / 2.0)));
        let (r4, w4) = f(&(r + r3 * dt), &(w + w3 * dt));
        r += (r1 + r2 * 2.0 + r3 * 2.0 + r4) * (dt / 6.0);
        w += (w1 + w2 * 2.0 + w3 * 2.0 + w4) * (dt / 6.0);
    }
    (r, w)
}

fn elementary(axis: usize, a: f64) -> Matrix3<f64> {
    nalgebra::Rotation3::from_axis_angle(&Vector3::ith_axis(axis), a).into_inner()
}

/// The gyrostat in body rates runs with its attitude: the attitude of B
/// stays orthonormal, T and |H|² are reported with small drifts, H in N
/// (the attitude times H in B) keeps its components, and the attitude
/// and rates at T agree with an independent integration of Euler's
/// equations and Ṙ = R [ω]×, within a bound scaled to the tolerance.
#[test]
fn gyrostat_in_body_rates_runs_with_its_attitude() {
    let scene = Scene::from_file(&example("sim-gyrostat.toml")).expect("gyrostat scene");
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    assert!(ds.model.is_first_order());
    assert_eq!(
        ds.state_names(),
        ["psi", "theta", "phi", "u_1", "u_2", "u_3"]
    );
    let tol = 1e-12;
    let t_end = scene.t_end;
    let report = run_dop853(&scene, tol);
    let names: Vec<&str> = report.drifts.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["T", "H2"]);
    for d in &report.drifts {
        assert!(
            d.relative < 1e3 * tol,
            "{} drifts by {:e}",
            d.name,
            d.relative
        );
    }
    let frame = report.frame.expect("the scene names frame B");
    let r = Matrix3::from_fn(|i, j| frame.attitude[i][j]);
    let w = Vector3::from(frame.angular_velocity);
    assert!(
        (r.transpose() * r - Matrix3::identity()).abs().max() < 16.0 * f64::EPSILON,
        "the attitude is not orthonormal: {r}"
    );
    assert!((r.determinant() - 1.0).abs() < 16.0 * f64::EPSILON);
    // ω of B in its own axes is the state's speeds.
    let u = &report.final_state[3..6];
    assert!((w - Vector3::from_column_slice(u)).abs().max() < 1e-14 * w.norm());
    // H in N from the attitude: constant.
    let h_n = |r: &Matrix3<f64>, w: &Vector3<f64>| {
        r * (Vector3::from(MOMENTS).component_mul(w) + Vector3::new(0.0, 0.0, ROTOR))
    };
    let r0 = ds.model.attitude("B", 0.0, &ds.y0).expect("B at 0");
    let w0 = Vector3::from_column_slice(&ds.y0[3..6]);
    let (h0, h1) = (h_n(&r0, &w0), h_n(&r, &w));
    assert!(
        (h1 - h0).norm() < 1e3 * tol * h0.norm(),
        "H in N moved by {:e}",
        (h1 - h0).norm()
    );
    // The start: 3-1-3 angles (0, 1, 0) and the speeds as given.
    let expected0 = elementary(2, 0.0) * elementary(0, 1.0) * elementary(2, 0.0);
    assert!((r0 - expected0).abs().max() < 1e-15);
    // Against the independent integration (RK4 at 2·10⁴ steps: its own
    // error is of order (ω dt)⁴ ω T ≈ 1e-10 here).
    let (r_ref, w_ref) = reference(r0, w0, t_end, 20_000);
    let dr = (r - r_ref).abs().max();
    let dw = (w - w_ref).abs().max() / w_ref.norm();
    assert!(
        dr < 1e-8 && dw < 1e-8,
        "attitude differs by {dr:e}, ω by {dw:e}"
    );
}

/// Every method that applies integrates the first-order system; at a
/// fixed step each lands near the reference, closer for higher orders.
/// The splittings do not apply (they need the quaternion body's exact
/// sub-flows), and the plan says so.
#[test]
fn every_method_that_applies_integrates_the_gyrostat() {
    let scene = Scene::from_file(&example("sim-gyrostat.toml")).expect("gyrostat scene");
    for method in Method::ALL {
        let req = Request {
            method: Some(method),
            step: Some(Step::Fixed(1e-3)),
            t_end: Some(1.0),
            ..Request::default()
        };
        match method {
            Method::Split2 | Method::Split4 => {
                let Err(e) = run::plan(&scene, &req) else {
                    panic!("a splitting is refused")
                };
                assert!(e.to_string().contains("derived"), "{e}");
            }
            _ => {
                let r = run_scene(&scene, req);
                let err = r.error.expect("measured against the reference");
                let bound = match method {
                    Method::Euler => 1e-2,
                    Method::Midpoint => 1e-5,
                    _ => 1e-9,
                };
                assert!(err < bound, "{}: error {err:e}", method.name());
            }
        }
    }
}

fn parse(text: &str) -> Result<Scene, SimError> {
    Scene::parse(text, &repo_root().join("docs/examples/test.toml"))
}

const HEAD: &str = r#"
name = "gyrostat"
kind = "derived"
t_end = 1.0
[constants]
I1 = 0.6
I2 = 0.8
I3 = 1.0
h = 0.3
"#;

fn refused(derivation: &str, initial: &str) -> String {
    let text =
        format!("{HEAD}[derivation]\nfile = \"gyrostat\"\n{derivation}\n[initial]\n{initial}\n");
    match parse(&text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Bad first-order scenes: each is refused naming the field.
#[test]
fn bad_first_order_scenes_name_their_field() {
    let start = "coordinates = { psi = 0.0, theta = 1.0, phi = 0.0 }\nspeeds = { u_1 = 0.3, u_2 = 0.2, u_3 = 2.0 }";
    // Rates of the coordinates for a state in speeds.
    let e = refused(
        "rates = \"rates\"",
        "coordinates = { psi = 0.0, theta = 1.0, phi = 0.0 }\nrates = { psi = 0.0, theta = 0.0, phi = 2.0 }",
    );
    assert!(
        e.contains("initial.rates") && e.contains("initial.speeds"),
        "{e}"
    );
    // A speed missing.
    let e = refused(
        "rates = \"rates\"",
        "coordinates = { psi = 0.0, theta = 1.0, phi = 0.0 }\nspeeds = { u_1 = 0.3, u_2 = 0.2 }",
    );
    assert!(e.contains("`initial`") && e.contains("u_3"), "{e}");
    // A step that is not the speeds' rates.
    let e = refused("rates = \"omega\"", start);
    assert!(e.contains("derivation.rates") && e.contains("omega"), "{e}");
    // Dependent speeds with second-order equations.
    let e = refused("accelerations = \"rates\"\ndependent = \"rates\"", start);
    assert!(e.contains("derivation.dependent"), "{e}");
    // The equations break down where they divide by sin θ.
    let e = refused(
        "rates = \"rates\"",
        "coordinates = { psi = 0.0, theta = 0.0, phi = 0.0 }\nspeeds = { u_1 = 0.3, u_2 = 0.2, u_3 = 2.0 }",
    );
    assert!(e.contains("`initial`") && e.contains("sin(theta)"), "{e}");
}

/// The disk rolling on the plane: the no-slip constraints hold along the
/// run (the contact's x, y move as the dependent speeds say), and the
/// energy is reported with a small drift.
#[test]
fn rolling_disk_runs_with_its_contact_and_energy() {
    let scene =
        Scene::from_file(&example("sim-disk-rolling-on-plane.toml")).expect("rolling disk scene");
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    assert_eq!(
        ds.state_names(),
        // The derived attitude gives the angles in the order the chain
        // turns them from N: yaw, lean, spin.
        ["x", "y", "psi", "theta", "phi", "u_1", "u_2", "u_3"]
    );
    let tol = 1e-12;
    let report = run_dop853(&scene, tol);
    let names: Vec<&str> = report.drifts.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["E"]);
    assert!(
        report.drifts[0].relative < 1e3 * tol,
        "E drifts by {:e}",
        report.drifts[0].relative
    );
    // The contact moved: about r |u₂| T along its path.
    let y = &report.final_state;
    let travelled = y[0].hypot(y[1]);
    assert!(travelled > 0.1, "the contact stayed at {travelled}");
    // The disk's material point at C has zero velocity: with G − C = r
    // along L's z, v_C = (ẋ, ẏ, 0) + ω_L × r e_z − ω_D × r e_z = 0, from
    // the attitudes and angular velocities of L and D and the state's
    // rate, at the start and at T.
    let m = &ds.model;
    let r = 0.3;
    for (t, y) in [(0.0, &ds.y0[..]), (scene.t_end, &y[..])] {
        let mut dy = [0.0; 8];
        m.rates(t, y, &mut dy).expect("rates");
        let in_n = |f: &str| {
            let a = m.attitude(f, t, y).expect("attitude");
            (a, a * m.angular_velocity(f, t, y).expect("ω"))
        };
        let ((l, w_l), (d, w_d)) = (in_n("L"), in_n("D"));
        assert!((d.transpose() * d - Matrix3::identity()).abs().max() < 16.0 * f64::EPSILON);
        let gc = l.column(2) * r;
        let v_c = Vector3::new(dy[0], dy[1], 0.0) + w_l.cross(&gc) - w_d.cross(&gc);
        let scale = w_d.norm() * r;
        assert!(v_c.norm() < 1e-14 * scale, "v_C = {v_c} at t = {t}");
    }
    assert!(report.frame.is_some(), "the scene names frame D");
}

/// Steady rolling, the derived condition (step `steady`: the lean
/// equation with u₁ = 0 must vanish), stays steady: from a lean θ₀ and
/// spin u₂ with u₃ solved from the condition, θ and the speeds keep their
/// values over the run.
#[test]
fn steady_rolling_stays_steady() {
    use hdot_num::eval::Tape;
    let path = repo_root().join("derivations/disk-rolling-on-plane.toml");
    let d = hdot_sym::derivation::load(&path).expect("the rolling disk derives");
    let steady = d
        .steps
        .iter()
        .find(|s| s.name == "steady")
        .expect("step steady");
    let p = d.unfold(steady.values()[0]);
    let (m, r, g) = (2.0, 0.3, 9.81);
    let (theta0, u2): (f64, f64) = (0.2, -10.0);
    let value = |u3: f64| {
        let tape = Tape::compile_with(std::slice::from_ref(&p), &mut |a| {
            let name = a.to_string();
            Some(match name.as_str() {
                "m" => m,
                "r" => r,
                "g" => g,
                "I" => m * r * r / 2.0,
                "J" => m * r * r / 4.0,
                "u_2" => u2,
                "u_3" => u3,
                "sin(theta)" => theta0.sin(),
                "cos(theta)" => theta0.cos(),
                "theta" => theta0,
                _ => return None,
            })
        });
        assert!(tape.atoms().is_empty(), "unbound atoms {:?}", tape.atoms());
        let mut out = [0.0];
        tape.eval(&[], &mut out);
        out[0]
    };
    // The root near the turn of a disk rolling straight on: scan, then bisect.
    let (mut a, mut b) = (0.0, 0.0);
    let step = 0.01;
    let mut found = false;
    for k in 0..1000 {
        let (x0, x1) = (k as f64 * step, (k + 1) as f64 * step);
        if value(x0).signum() != value(x1).signum() {
            (a, b) = (x0, x1);
            found = true;
            break;
        }
    }
    assert!(found, "no steady turning rate u_3 in [0, 10]");
    for _ in 0..100 {
        let c = (a + b) / 2.0;
        if value(a).signum() == value(c).signum() {
            a = c;
        } else {
            b = c;
        }
    }
    let u3 = (a + b) / 2.0;
    let text = std::fs::read_to_string(example("sim-disk-rolling-on-plane.toml")).unwrap();
    let text = text.replace(
        "speeds = { u_1 = 0.5, u_2 = -10.0, u_3 = 1.0 }",
        &format!("speeds = {{ u_1 = 0.0, u_2 = {u2:?}, u_3 = {u3:?} }}"),
    );
    let scene = Scene::parse(&text, &example("steady.toml")).expect("steady scene");
    let tol = 1e-12;
    let report = run_dop853(&scene, tol);
    let y = &report.final_state;
    let scale = u2.abs();
    let lean = report
        .state_names
        .iter()
        .position(|n| n == "theta")
        .expect("θ is in the state");
    assert!(
        (y[lean] - theta0).abs() < 1e3 * tol,
        "θ moved to {}",
        y[lean]
    );
    assert!(y[5].abs() < 1e3 * tol * scale, "u_1 = {}", y[5]);
    assert!((y[6] - u2).abs() < 1e3 * tol * scale, "u_2 = {}", y[6]);
    assert!((y[7] - u3).abs() < 1e3 * tol * scale, "u_3 = {}", y[7]);
}

/// A frame whose angle a `[motion]` rule ties to the coordinates is
/// reported: the disk on its pivoted axle (rolling-disk.toml) spins by ψ,
/// which the rolling rule ψ' = −(L/r) φ' gives, so ψ is carried in the
/// state and the disk's frame D = A x(ψ), A = N z(φ), has its attitude
/// and ω — which agree with the rule integrated by hand, ψ = −(L/r) φ.
#[test]
fn a_frame_turned_by_a_motion_rule_is_reported() {
    let text = std::fs::read_to_string(example("sim-rolling-disk.toml")).unwrap();
    let text = text.replace(
        "coordinates = [\"phi\"]",
        "coordinates = [\"phi\"]\nframe = \"D\"",
    );
    let scene = Scene::parse(&text, &example("rolling-disk-frame.toml")).expect("scene");
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    assert_eq!(ds.state_names(), ["phi", "phi'", "psi"]);
    let tol = 1e-12;
    let report = run_dop853(&scene, tol);
    let y = &report.final_state;
    let (phi, dphi, psi) = (y[0], y[1], y[2]);
    // L = 0.3 m (bound from the body table), r = 0.1 m.
    let ratio = 0.3 / 0.1;
    assert!(phi.abs() > 0.1, "the axle turned by {phi}");
    assert!(
        (psi + ratio * phi).abs() < 1e3 * tol * psi.abs(),
        "ψ = {psi}, −(L/r) φ = {}",
        -ratio * phi
    );
    let frame = report.frame.expect("frame D reported");
    assert_eq!(frame.frame, "D");
    let r = Matrix3::from_fn(|i, j| frame.attitude[i][j]);
    let expected = elementary(2, phi) * elementary(0, psi);
    assert!((r - expected).abs().max() < 1e-12, "{r} vs {expected}");
    // ω of D in its axes: ψ' along x plus φ' about N's z seen from D.
    let w = Vector3::from(frame.angular_velocity);
    let w_expected = elementary(0, psi).transpose() * Vector3::new(0.0, 0.0, dphi)
        + Vector3::new(-ratio * dphi, 0.0, 0.0);
    assert!(
        (w - w_expected).norm() < 1e-12 * w_expected.norm(),
        "{w} vs {w_expected}"
    );
}
