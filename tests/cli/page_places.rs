//! Where `hdot simulate --html` draws each body (issue 24): a derived
//! scene's bodies at their reference points, not at the origin — the
//! double pendulum's second rod hangs from the first rod's tip, the disk
//! rolls along its path with the view following it — and every scene
//! upright: the view's turn takes up (against gravity) to the canvas' up,
//! so the bicycle, whose Z points down, stands on its wheels. Read from the
//! page's data.

use hdot_tests::pendulum::{DOUBLE_PENDULUM, DOUBLE_PENDULUM_SCENE};
use nalgebra::{Matrix3, Vector3};
use serde_json::Value;

use super::html::view_data;
use super::{hdot, text};

/// The page of `scene` (a path from the repository's root, or in a
/// temporary folder) as its view's data.
fn page_data(scene: &str, dir: &std::path::Path) -> Value {
    let page = dir.join("page.html");
    let out = hdot(&["simulate", scene, "--html", page.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    view_data(&std::fs::read_to_string(&page).unwrap())
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// Point `i` of a track of 3 numbers per frame.
fn point(track: &[f64], i: usize) -> Vector3<f64> {
    Vector3::new(track[3 * i], track[3 * i + 1], track[3 * i + 2])
}

/// Rotation `i` of a track of 9 numbers (row-major) per frame.
fn rotation(track: &[f64], i: usize) -> Matrix3<f64> {
    Matrix3::from_row_slice(&track[9 * i..9 * i + 9])
}

/// The page writes 6 significant digits: a drawn value holds to this,
/// relative to its scale.
const DIGITS: f64 = 1e-5;

#[test]
fn the_second_rod_hangs_from_the_first_rods_tip() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("double-pendulum.toml"), DOUBLE_PENDULUM).unwrap();
    let scene = dir.path().join("sim-double-pendulum.toml");
    std::fs::write(&scene, DOUBLE_PENDULUM_SCENE).unwrap();
    let d = page_data(scene.to_str().unwrap(), dir.path());
    let groups = d["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 2);
    let (rod1, rod2) = (&groups[0], &groups[1]);
    assert_eq!(
        (rod1["frame"].as_str(), rod2["frame"].as_str()),
        (Some("A"), Some("B"))
    );
    let rot1 = numbers(&rod1["rot"]);
    let (pos1, pos2) = (numbers(&rod1["pos"]), numbers(&rod2["pos"]));
    let frames = d["t"].as_array().unwrap().len();
    // Rod 1 hangs from O at the origin; rod 2 from rod 1's tip, l1 = 1 m
    // along −y of rod 1's frame as the page turns it.
    let l1 = 1.0;
    let mut swing = 0.0f64;
    for i in 0..frames {
        assert_eq!(point(&pos1, i), Vector3::zeros());
        let tip = rotation(&rot1, i) * Vector3::new(0.0, -l1, 0.0);
        let p = point(&pos2, i);
        assert!(
            (p - tip).norm() < 4.0 * DIGITS * l1,
            "frame {i}: {p} against {tip}"
        );
        swing = swing.max((p - point(&pos2, 0)).norm());
    }
    assert!(swing > 0.5 * l1, "rod 2's pivot moved by {swing} only");
    // Y is up: the view takes +Y to the canvas' up, and holds the origin.
    let view = Matrix3::from_row_slice(&numbers(&d["view"]));
    assert!((view * Vector3::y() - Vector3::z()).norm() < DIGITS);
    assert!(d["centre"].is_null());
}

#[test]
fn the_rolling_disk_moves_along_its_path() {
    let dir = tempfile::tempdir().unwrap();
    let d = page_data("docs/examples/sim-disk-rolling-on-plane.toml", dir.path());
    let groups = d["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 1);
    let pos = numbers(&groups[0]["pos"]);
    let frames = d["t"].as_array().unwrap().len();
    // G rides r cos θ above the floor, and travels about r |u₂| T = 15 m.
    let r = 0.3;
    let mut travelled = 0.0;
    for i in 0..frames {
        let z = point(&pos, i).z;
        assert!(
            z > 0.0 && z <= r * (1.0 + DIGITS),
            "frame {i}: G at height {z}"
        );
        if i > 0 {
            travelled += (point(&pos, i) - point(&pos, i - 1)).norm();
        }
    }
    assert!(travelled > 10.0, "the disk travelled {travelled} m");
    // The view follows it: its centre is the disk's place.
    let centre = numbers(&d["centre"]);
    for i in [0, frames / 2, frames - 1] {
        assert!((point(&centre, i) - point(&pos, i)).norm() < DIGITS * travelled);
    }
    let scale = d["scale"].as_f64().unwrap();
    assert!(scale < 4.0 * r, "the view shows {scale} m about the disk");
}

#[test]
fn the_bicycle_stands_upright() {
    let dir = tempfile::tempdir().unwrap();
    let d = page_data("docs/examples/sim-bicycle-nonlinear.toml", dir.path());
    // Its N has Z down: gravity along +Z, and the view turns +Z to the
    // canvas' down.
    let g = numbers(&d["g"]);
    assert!((Vector3::new(g[0], g[1], g[2]) - Vector3::z()).norm() < DIGITS);
    let view = Matrix3::from_row_slice(&numbers(&d["view"]));
    assert!((view * Vector3::z() + Vector3::z()).norm() < DIGITS);
    // The wheels' centres are drawn above the ground (Z = 0 in N), at
    // their radii, all along the run.
    let groups = d["groups"].as_array().unwrap();
    let frames = d["t"].as_array().unwrap().len();
    for (k, radius) in [(0, 0.3), (3, 0.35)] {
        let pos = numbers(&groups[k]["pos"]);
        for i in 0..frames {
            let up = (view * point(&pos, i)).z;
            assert!(
                (up - radius).abs() < 1e-3 * radius,
                "group {k}, frame {i}: {up}"
            );
        }
    }
}
