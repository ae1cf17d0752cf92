//! Scene files (numeric and simulation), the simulation planner, and CSV
//! particle clouds.

use std::path::Path;

use hdot_num::ParticleCloud;
use hdot_num::report::Report;
use proptest::prelude::*;

fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-1e3f64..1e3).prop_map(|x| format!("{x:?}")),
        prop::sample::select(vec![
            "0.0", "1.0", "-1.0", "1e308", "-1e308", "1e-308", "5e-324", "1e200", "1e-200", "nan",
            "inf", "-inf", "2", "0", "\"x\"",
        ])
        .prop_map(str::to_owned),
    ]
}

fn vector() -> impl Strategy<Value = String> {
    prop::collection::vec(number(), 0..5).prop_map(|v| format!("[{}]", v.join(", ")))
}

fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        number(),
        vector(),
        vector(),
        prop::sample::select(vec![
            "\"rod\"",
            "\"prism\"",
            "\"sphere\"",
            "\"disk\"",
            "\"cone\"",
            "\"free\"",
            "\"heavy-top\"",
            "\"fixed-axis\"",
            "[\"x\", \"x\"]",
            "[\"y\", \"z\"]",
            "{ x_axis = [1e160, 1e160, 0.0] }",
            "{ axis = [0.0, 0.0, 1.0], angle_deg = 30.0 }",
            "{ euler_deg = [1.0, 2.0] }",
            "{ euler_angles = [1.0, 2.0] }",
            "\"point\"",
            "[0.0, 0.0, -9.81]",
            "\"T\"",
        ])
        .prop_map(str::to_owned),
    ]
}

/// A scene as a sequence of table headers and `key = value` lines drawn
/// from the keys of both scene formats.
fn scene() -> impl Strategy<Value = String> {
    let line = prop_oneof![
        prop::sample::select(vec![
            "[[body]]",
            "[motion]",
            "[impulse]",
            "[[force]]",
            "[[couple]]",
            "[[constraint]]",
            "[body]",
            "[initial]",
            "[shaft]",
            "[motor]",
            "[top]",
        ])
        .prop_map(str::to_owned),
        (
            prop::sample::select(vec![
                "name",
                "shape",
                "mass",
                "weight",
                "length",
                "a",
                "b",
                "c",
                "radius",
                "height",
                "position",
                "rotation",
                "omega",
                "alpha",
                "v_g",
                "a_g",
                "fixed_point",
                "g",
                "reference",
                "point",
                "direction",
                "value",
                "unknown",
                "v_before",
                "omega_before",
                "kind",
                "t_end",
                "principal_moments",
                "attitude",
                "angular_momentum",
                "angle",
                "rate",
                "spin",
                "bearings",
                "fixed_point",
            ]),
            value(),
        )
            .prop_map(|(k, v)| format!("{k} = {v}")),
    ];
    prop::collection::vec(line, 0..24).prop_map(|l| l.join("\n"))
}

/// A valid prism scene with one value replaced.
fn near_valid_scene() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec!["A", "B", "C", "D", "E", "F"]),
        value(),
    )
        .prop_map(|(slot, v)| {
            let t = "name = \"p\"\ng = A\n[[body]]\nshape = \"prism\"\na = 1.0\nb = 2.0\nc = 3.0\nmass = B\nposition = C\nrotation = { x_axis = D }\n[motion]\nomega = E\n[[force]]\nname = \"F\"\npoint = [0.0, 0.0, 0.0]\ndirection = F\n[[couple]]\nname = \"C\"\nunknown = [\"x\", \"y\", \"z\"]\n";
            let defaults = [
                ("A", "[0.0, -9.81, 0.0]"),
                ("B", "2.0"),
                ("C", "[0.0, 0.0, 0.0]"),
                ("D", "[1.0, 1.0, 0.0]"),
                ("E", "[0.0, 0.0, 1.0]"),
                ("F", "[0.0, 1.0, 0.0]"),
            ];
            let mut s = t.replace(slot, &v);
            for (k, d) in defaults {
                s = s.replace(&format!("= {k}\n"), &format!("= {d}\n"));
                s = s.replace(&format!("= {k} }}"), &format!("= {d} }}"));
            }
            s
        })
}

proptest! {
    #![proptest_config(crate::config())]

    /// The numeric scene parser and everything `hdot dynamics` computes
    /// from an accepted scene: no panic, and an error names a field.
    #[test]
    fn numeric_scenes_never_panic(text in prop_oneof![scene(), near_valid_scene()]) {
        match hdot_num::scene::Scene::from_str_at(Path::new("f.toml"), &text) {
            Ok(s) => {
                let r = Report::dynamics(&s);
                // A non-finite report is refused by the CLI, never printed.
                let _ = r.non_finite();
            }
            Err(e) => prop_assert!(!e.field.is_empty(), "{e}"),
        }
    }

    /// The simulation scene parser: accepted or refused, never a panic.
    #[test]
    fn simulation_scenes_never_panic(text in scene()) {
        let _ = hdot_sim::scene::Scene::parse(&text, Path::new("f.toml"));
    }

    /// CSV particle clouds: random fields, lines and bytes.
    #[test]
    fn csv_clouds_never_panic(
        rows in prop::collection::vec(prop::collection::vec(number(), 0..6), 0..12),
        header in any::<bool>(),
        noise in "\\PC{0,40}",
    ) {
        let mut text = if header { "x,y,z,m\n".to_string() } else { String::new() };
        for r in &rows {
            text.push_str(&r.join(","));
            text.push('\n');
        }
        let _ = ParticleCloud::from_csv_str(Path::new("c.csv"), &text);
        text.push_str(&noise);
        if let Err(e) = ParticleCloud::from_csv_str(Path::new("c.csv"), &text) {
            prop_assert!(e.to_string().starts_with("c.csv:"), "{e}");
        }
    }
}

/// The simulation planner: every bundled simulation scene with random
/// models, methods, steps and end times (absurd ones included).
fn request() -> impl Strategy<Value = hdot_sim::run::Request> {
    use hdot_sim::run::{Model, Request};
    use hdot_sim::{Method, Step};
    let models = vec![
        "fixed-axis",
        "steady-precession",
        "elliptic",
        "precession-angle",
        "rigid-body",
        "euler-angles",
    ];
    let methods = vec![
        "euler", "rk4", "dopri5", "dop853", "midpoint", "split2", "split4",
    ];
    let number = prop::sample::select(vec![
        1e-3,
        0.1,
        -1.0,
        0.0,
        1e308,
        1e-300,
        f64::NAN,
        f64::INFINITY,
    ]);
    (
        prop::option::of(prop::sample::select(models)),
        prop::option::of(prop::sample::select(methods)),
        prop::option::of((any::<bool>(), number.clone())),
        prop::option::of(number),
    )
        .prop_map(|(model, method, step, t_end)| Request {
            model: model.and_then(|m| m.parse::<Model>().ok()),
            method: method.and_then(|m| m.parse::<Method>().ok()),
            step: step.map(|(fixed, x)| {
                if fixed {
                    Step::Fixed(x)
                } else {
                    Step::Tolerance(x)
                }
            }),
            t_end,
            check: false,
        })
}

proptest! {
    #![proptest_config(crate::config())]

    #[test]
    fn the_simulation_planner_never_panics(which in 0usize..16, req in request()) {
        let dir = hdot_tests::repo_root().join("docs/examples");
        let mut scenes: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with("sim-"))
            .collect();
        scenes.sort();
        let path = &scenes[which % scenes.len()];
        let scene = hdot_sim::scene::Scene::from_file(path).unwrap();
        let _ = hdot_sim::run::plan(&scene, &req);
    }
}
