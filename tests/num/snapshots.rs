//! Snapshots of what is meant to be read: the text of `hdot inertia` and
//! `hdot dynamics` on the bundled scenes.

use std::path::Path;

use hdot_num::report::Report;
use hdot_num::scene::Scene;

const SCENES: [&str; 4] = [
    "rolling-disk",
    "rod-on-axle",
    "struck-plate",
    "unbalanced-shaft",
];

fn scene(name: &str) -> Scene {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/examples")
        .join(format!("{name}.toml"));
    Scene::from_path(&p).unwrap()
}

#[test]
fn inertia_text() {
    for name in SCENES {
        insta::assert_snapshot!(
            format!("inertia@{name}"),
            Report::inertia(&scene(name)).text(6)
        );
    }
}

#[test]
fn dynamics_text() {
    for name in SCENES {
        insta::assert_snapshot!(
            format!("dynamics@{name}"),
            Report::dynamics(&scene(name)).text(6)
        );
    }
}

#[test]
fn dynamics_json_has_the_documented_keys() {
    let keys = [
        "mass",
        "center",
        "inertia_G",
        "inertia_O",
        "principal_moments",
        "principal_axes",
        "H_G",
        "H_O",
        "kinetic_energy",
        "resultant_force",
        "resultant_moment",
        "unknowns",
    ];
    let v = serde_json::to_value(Report::dynamics(&scene("rod-on-axle"))).unwrap();
    for k in keys {
        assert!(v.get(k).is_some(), "missing key {k}");
    }
    assert!(v["unknowns"]["T"].is_f64());
}
