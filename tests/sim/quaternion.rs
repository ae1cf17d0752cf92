//! Euler parameters in a simulation (systems/derived/unit_norm.rs and
//! derivations/torque-free-quaternion.toml): the torque-free body with
//! products of inertia run in quaternion attitude ends where the same
//! body run in 3-1-3 angles ends (tests/sim/quaternion/, attitudes and
//! rates compared), the norm is kept with its drift reported, and the
//! body started at the angles' singular attitude θ = 0 runs (and is
//! refused in angles).

use std::path::PathBuf;

use hdot_sim::run::{self, Output, Report, Request};
use hdot_sim::scene::Scene;
use hdot_sim::{Method, SimError, Step};
use hdot_tests::repo_root;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

fn scene_path() -> PathBuf {
    repo_root().join("tests/sim/quaternion/sim-torque-free.toml")
}

/// The test's scene on the derivation `file`, started at `start` (an
/// inline table of coordinates).
fn scene(file: &str, start: &str) -> Result<Scene, SimError> {
    let text = std::fs::read_to_string(scene_path()).expect("the test's scene");
    let text = text.replace("FILE", file).replace("START", start);
    Scene::parse(&text, &scene_path())
}

fn run_scene(scene: &Scene, tol: f64) -> Report {
    let req = Request {
        method: Some(Method::Dop853),
        step: Some(Step::Tolerance(tol)),
        ..Request::default()
    };
    let plan = run::plan(scene, &req).expect("plan");
    run::run(scene, &plan, &mut Output::default()).expect("run")
}

/// The Euler parameters (scalar part first) of the attitude the 3-1-3
/// angles give, through nalgebra's rotations and quaternions.
fn euler_parameters(psi: f64, theta: f64, phi: f64) -> [f64; 4] {
    let r = Rotation3::from_axis_angle(&Vector3::z_axis(), psi)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), theta)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), phi);
    let q = UnitQuaternion::from_rotation_matrix(&r);
    [q.w, q.i, q.j, q.k]
}

fn start_e(e: [f64; 4]) -> String {
    format!(
        "{{ e_0 = {:?}, e_1 = {:?}, e_2 = {:?}, e_3 = {:?} }}",
        e[0], e[1], e[2], e[3]
    )
}

fn attitude(r: &Report) -> Matrix3<f64> {
    let a = r.frame.as_ref().expect("the scene reports B").attitude;
    Matrix3::from_fn(|i, j| a[i][j])
}

#[test]
fn quaternion_attitude_matches_the_3_1_3_angles() {
    let (psi, theta, phi) = (0.3, 1.0, -0.4);
    let tol = 1e-12;
    let angles = run_scene(
        &scene(
            "torque-free-angles.toml",
            &format!("{{ psi = {psi:?}, theta = {theta:?}, phi = {phi:?} }}"),
        )
        .expect("the angles' scene"),
        tol,
    );
    let quaternion = run_scene(
        &scene(
            "torque-free-quaternion",
            &start_e(euler_parameters(psi, theta, phi)),
        )
        .expect("the quaternion scene"),
        tol,
    );
    assert_eq!(
        quaternion.state_names,
        ["e_0", "e_1", "e_2", "e_3", "u_1", "u_2", "u_3"]
    );
    // Both integrate one motion to the tolerance: over T = 10 s the
    // global error is a few hundred times the per-step tolerance.
    let bound = 1e4 * tol;
    let (a, b) = (attitude(&angles), attitude(&quaternion));
    assert!(
        (a - b).abs().max() < bound,
        "attitudes differ by {:e}:\n{a}\n{b}",
        (a - b).abs().max()
    );
    let u = |r: &Report| Vector3::from_column_slice(&r.final_state[r.final_state.len() - 3..]);
    let (ua, ub) = (u(&angles), u(&quaternion));
    assert!((ua - ub).norm() < bound * ua.norm(), "rates {ua} and {ub}");
    // The norm is kept: reported, and the state ends on the unit sphere.
    let n = quaternion
        .unit_norms
        .as_ref()
        .expect("the norm's drift is reported");
    assert_eq!(
        n.parameters,
        [["e_0", "e_1", "e_2", "e_3"].map(String::from)]
    );
    assert!(n.max_drift < bound, "the norm drifted by {:e}", n.max_drift);
    let e = &quaternion.final_state[..4];
    let norm = e.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((norm - 1.0).abs() < 8.0 * f64::EPSILON, "|e| = {norm}");
    assert!(angles.unit_norms.is_none(), "angles have no norm to keep");
}

#[test]
fn a_body_started_upright_runs_in_euler_parameters() {
    let tol = 1e-12;
    // θ = 0: the 3-1-3 kinematic equations divide by sin θ.
    let refused = scene(
        "torque-free-angles.toml",
        "{ psi = 0.0, theta = 0.0, phi = 0.0 }",
    )
    .and_then(|s| {
        let req = Request {
            method: Some(Method::Dop853),
            step: Some(Step::Tolerance(tol)),
            ..Request::default()
        };
        let plan = run::plan(&s, &req)?;
        run::run(&s, &plan, &mut Output::default())
    });
    assert!(refused.is_err(), "the angles are singular at θ = 0");
    let r = run_scene(
        &scene("torque-free-quaternion", &start_e([1.0, 0.0, 0.0, 0.0]))
            .expect("the quaternion scene"),
        tol,
    );
    let names: Vec<&str> = r.drifts.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["T", "H2", "H_N"]);
    for d in &r.drifts {
        assert!(
            d.relative < 1e3 * tol,
            "{} drifts by {:e}",
            d.name,
            d.relative
        );
    }
    let a = attitude(&r);
    assert!(
        (a.transpose() * a - Matrix3::identity()).abs().max() < 16.0 * f64::EPSILON,
        "the attitude stays a rotation:\n{a}"
    );
    // The body turned: far from where it started.
    assert!((a - Matrix3::identity()).abs().max() > 0.1);
}

#[test]
fn euler_parameters_off_the_unit_sphere_are_refused_at_the_start() {
    let e = scene("torque-free-quaternion", &start_e([1.0, 1.0, 0.0, 0.0]))
        .expect_err("a norm of √2")
        .to_string();
    assert!(
        e.contains("initial.coordinates")
            && e.contains("unit norm")
            && e.contains("e_0, e_1, e_2, e_3"),
        "{e}"
    );
}
