//! systems/derived/positions.rs: where each declared body is — its
//! reference point in N, summed along the chain of `at` vectors — against
//! the same place written by hand from the coordinates, at seeded random
//! states; a body with no declared place says why; the derivation's
//! gravity in N.

use hdot_sim::scene::{DerivedScene, Scene, SceneKind};
use hdot_tests::pendulum::{DOUBLE_PENDULUM, DOUBLE_PENDULUM_SCENE};
use hdot_tests::repo_root;
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn derived(scene: &Scene) -> &DerivedScene {
    match &scene.kind {
        SceneKind::Derived(ds) => ds,
        _ => panic!("a derived scene"),
    }
}

fn example(name: &str) -> Scene {
    Scene::from_file(&repo_root().join("docs/examples").join(name)).expect("scene")
}

/// `y0` with the coordinates named set to random angles (seeded).
fn random_state(ds: &DerivedScene, rng: &mut ChaCha8Rng, names: &[&str]) -> Vec<f64> {
    let mut y = ds.y0.clone();
    for (k, q) in ds.model.coordinates().iter().enumerate() {
        if names.contains(&q.name()) {
            y[k] = rng.gen_range(-3.0..3.0);
        }
    }
    y
}

fn value(ds: &DerivedScene, y: &[f64], name: &str) -> f64 {
    let k = ds
        .model
        .coordinates()
        .iter()
        .position(|q| q.name() == name)
        .expect("a coordinate");
    y[k]
}

/// The double pendulum's scene, its derivation written beside it in `dir`.
fn double_pendulum(dir: &tempfile::TempDir) -> Scene {
    std::fs::write(dir.path().join("double-pendulum.toml"), DOUBLE_PENDULUM).unwrap();
    Scene::parse(
        DOUBLE_PENDULUM_SCENE,
        &dir.path().join("sim-double-pendulum.toml"),
    )
    .expect("scene")
}

/// `got` within `tol` of `want` relative to `scale`.
fn assert_near(got: Vector3<f64>, want: Vector3<f64>, scale: f64, tol: f64) {
    assert!((got - want).norm() <= tol * scale, "{got} against {want}");
}

/// Rod 2 hangs from rod 1's end: P = l1 (sin q1, −cos q1, 0); rod 1 from
/// the fixed O at the origin.
#[test]
fn the_second_rod_is_placed_at_the_first_rods_end() {
    let dir = tempfile::tempdir().unwrap();
    let scene = double_pendulum(&dir);
    let ds = derived(&scene);
    assert_eq!(ds.model.bodies().collect::<Vec<_>>(), ["rod1", "rod2"]);
    let l1 = 1.0;
    let mut rng = ChaCha8Rng::seed_from_u64(24);
    for _ in 0..20 {
        let y = random_state(ds, &mut rng, &["q1", "q2"]);
        let q1 = value(ds, &y, "q1");
        let p = ds.model.position("rod2", 0.0, &y).expect("placed");
        assert_near(p, l1 * Vector3::new(q1.sin(), -q1.cos(), 0.0), l1, 1e-15);
        assert_eq!(
            ds.model.position("rod1", 0.0, &y).expect("placed"),
            Vector3::zeros()
        );
    }
    assert!(ds.model.position("rod3", 0.0, &ds.y0).is_err());
    // Y is up: gravity is −g Y.
    let g = ds.model.gravity(0.0, &ds.y0).expect("gravity");
    assert_near(g, Vector3::new(0.0, -9.81, 0.0), 9.81, 1e-15);
}

/// The rolling disk's centre G is r above the contact (x, y, 0) along the
/// lean frame's z: G = (x, y, 0) + R_z(ψ) R_x(θ) (0, 0, r).
#[test]
fn the_rolling_disk_is_placed_above_its_contact() {
    let scene = example("sim-disk-rolling-on-plane.toml");
    let ds = derived(&scene);
    let r = 0.3;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..20 {
        let mut y = random_state(ds, &mut rng, &["theta", "psi", "phi"]);
        y[0] = rng.gen_range(-5.0..5.0);
        y[1] = rng.gen_range(-5.0..5.0);
        let (x, yy) = (value(ds, &y, "x"), value(ds, &y, "y"));
        let (theta, psi) = (value(ds, &y, "theta"), value(ds, &y, "psi"));
        let want = Vector3::new(
            x + r * psi.sin() * theta.sin(),
            yy - r * psi.cos() * theta.sin(),
            r * theta.cos(),
        );
        let got = ds.model.position("disk", 0.0, &y).expect("placed");
        assert_near(got, want, 5.0, 1e-15);
    }
    let g = ds.model.gravity(0.0, &ds.y0).expect("gravity");
    assert_near(g, Vector3::new(0.0, 0.0, -9.81), 9.81, 1e-15);
}

/// The bicycle's N has Z down: gravity is +g Z, and the rear wheel's
/// centre, upright, is r_R above the ground (−r_R in Z) over the contact.
#[test]
fn the_bicycle_is_placed_with_z_down() {
    let scene = example("sim-bicycle-nonlinear.toml");
    let ds = derived(&scene);
    let g = ds.model.gravity(0.0, &ds.y0).expect("gravity");
    assert_near(g, Vector3::new(0.0, 0.0, 9.81), 9.81, 1e-15);
    // The pitch is solved from the configuration constraints (Newton's
    // tolerance): the places hold to that.
    let w_r = ds
        .model
        .position("rear_wheel", 0.0, &ds.y0)
        .expect("placed");
    assert_near(w_r, Vector3::new(0.0, 0.0, -0.3), 1.0, 1e-12);
    // The front wheel's centre, upright and unsteered, is the wheel base
    // (between the contacts) ahead and r_F above the ground.
    let w_f = ds
        .model
        .position("front_wheel", 0.0, &ds.y0)
        .expect("placed");
    assert_near(w_f, Vector3::new(1.02, 0.0, -0.35), 1.0, 1e-12);
}

/// A body about its own centre with no declared place (the gyrostat) is
/// not placed, and says why.
#[test]
fn a_body_with_no_declared_place_says_why() {
    let scene = example("sim-gyrostat.toml");
    let ds = derived(&scene);
    let body = ds.model.bodies().next().expect("a body").to_owned();
    let e = ds.model.position(&body, 0.0, &ds.y0).unwrap_err();
    assert!(e.contains(&body) && e.contains("not known"), "{e}");
}

/// Issue 24: the positions reach the simulate report (text and JSON) and
/// the `--output` stream, three columns per body named after it. The
/// double pendulum's streamed `rod2` — hung at rod 1's tip P — agrees at
/// every step with P = l1 (sin q1, −cos q1, 0) from the same row's q1, and
/// `rod1` stays at the fixed O.
#[test]
fn the_stream_and_the_report_carry_the_bodies_positions() {
    use hdot_sim::run::{self, Output, Request};
    let dir = tempfile::tempdir().unwrap();
    let scene = double_pendulum(&dir);
    let request = Request {
        method: Some(hdot_sim::Method::Rk4),
        step: Some(hdot_sim::Step::Fixed(1e-2)),
        ..Request::default()
    };
    let plan = run::plan(&scene, &request).expect("plan");
    let mut csv: Vec<u8> = Vec::new();
    let report = {
        let mut out = Output {
            stream: Some(&mut csv),
            ..Output::default()
        };
        run::run(&scene, &plan, &mut out).expect("run")
    };
    let header: Vec<String> = run::csv_header(&scene, plan.model)
        .split(',')
        .map(str::to_owned)
        .collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
    };
    // The state's columns first (as the trajectory has them), then the
    // bodies in declaration order.
    let state = run::stream_header(&scene, plan.model).split(',').count();
    assert_eq!(
        &header[state..],
        ["rod1.x", "rod1.y", "rod1.z", "rod2.x", "rod2.y", "rod2.z"]
    );
    let l1 = 1.0;
    let rows: Vec<Vec<f64>> = String::from_utf8(csv)
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect())
        .collect();
    assert!(rows.len() as u64 >= report.steps, "{} rows", rows.len());
    for row in &rows {
        assert_eq!(row.len(), header.len());
        let q1 = row[col("q1")];
        let got = Vector3::new(row[col("rod2.x")], row[col("rod2.y")], row[col("rod2.z")]);
        assert_near(got, l1 * Vector3::new(q1.sin(), -q1.cos(), 0.0), l1, 1e-15);
        for c in ["rod1.x", "rod1.y", "rod1.z"] {
            assert_eq!(row[col(c)], 0.0);
        }
    }
    // The report: the place at T, in the text and the JSON.
    let q1 = report.final_state[report
        .state_names
        .iter()
        .position(|n| n == "q1")
        .expect("q1")];
    let tip = report
        .positions
        .iter()
        .find(|p| p.body == "rod2")
        .and_then(|p| p.at)
        .expect("rod2 placed");
    assert_near(
        Vector3::from(tip),
        l1 * Vector3::new(q1.sin(), -q1.cos(), 0.0),
        l1,
        1e-15,
    );
    let text = report.to_string();
    let line = text
        .lines()
        .find(|l| l.starts_with("position:    rod2 at ("))
        .unwrap_or_else(|| panic!("no position line in\n{text}"));
    let printed: Vec<f64> = line
        .split(['(', ')', ','])
        .filter_map(|w| w.trim().parse().ok())
        .collect();
    assert_near(
        Vector3::from_iterator(printed),
        Vector3::from(tip),
        l1,
        1e-8,
    );
    let json: serde_json::Value = serde_json::to_value(&report).unwrap();
    let at = &json["positions"][1];
    assert_eq!(at["body"], "rod2");
    assert_eq!(at["at"][0].as_f64(), Some(tip[0]));
}
