//! Scenes that are strict about their input and raise no false alarms
//! (issue 13): wrong vector lengths, duplicates and non-finite values are
//! errors at the key's line; overflowing masses are refused; zero
//! resultants pass the particle-sum check; huge or tiny directions are
//! normalised without overflow.

use std::path::Path;

use hdot_num::scene::Scene;

const PRISM: &str =
    "name = \"p\"\n[[body]]\nshape = \"prism\"\na = 1.0\nb = 2.0\nc = 3.0\nmass = 2.0\n";

fn error_of(text: &str) -> hdot_num::scene::SceneError {
    Scene::from_str_at(Path::new("s.toml"), text).unwrap_err()
}

#[test]
fn bad_vectors_and_values_are_errors_at_the_line_of_their_key() {
    for (text, line, field, fragment) in [
        (
            format!("{PRISM}position = [0.0, 0.0, 0.0, 1.0]\n"),
            8,
            "body[0].position",
            "3 components, not 4",
        ),
        (
            format!("{PRISM}position = [0.0, 1.0]\n"),
            8,
            "body[0].position",
            "not 2",
        ),
        (
            format!("name = \"p\"\n\n\n\ng = [0.0, nan, 0.0]\n{}", &PRISM[11..]),
            5,
            "g",
            "not finite",
        ),
        (
            format!("{PRISM}[motion]\nomega = [0.0, 0.0, inf]\n"),
            9,
            "motion.omega",
            "not finite",
        ),
        (
            format!("{PRISM}rotation = {{ x_axis = [1.0, 0.0, 0.0, 0.0] }}\n"),
            8,
            "body[0].rotation.x_axis",
            "3 components",
        ),
        (
            format!(
                "{PRISM}[motion]\nomega = [0.0, 0.0, 1.0]\n[[force]]\nname = \"A\"\npoint = [0.0, 0.0, 0.0]\nunknown = [\"x\",\n  \"x\"]\n"
            ),
            14,
            "force[0].unknown",
            "listed twice",
        ),
        (
            format!(
                "{PRISM}[motion]\nomega = [0.0, 0.0, 1.0]\n[[force]]\nname = \"A\"\npoint = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n[[force]]\nname = \"A\"\npoint = [1.0, 0.0, 0.0]\ndirection = [0.0, 1.0, 0.0]\n"
            ),
            15,
            "force[1].name",
            "a second unknown named \"A\"",
        ),
        (
            "[[body]]\nshape = \"sphere\"\nradius = 1.0\nmass = 1e308\n[[body]]\nshape = \"sphere\"\nradius = 1.0\nmass = 1.7e308\n".to_string(),
            5,
            "body[1]",
            "overflow",
        ),
    ] {
        let e = error_of(&text);
        assert_eq!((e.line, e.field.as_str()), (line, field), "{e}\n{text}");
        assert!(e.message.contains(fragment), "{e}");
    }
}

#[test]
fn dimensions_that_overflow_the_inertia_are_refused() {
    let e = error_of(&PRISM.replace("a = 1.0", "a = 1e200"));
    assert!(e.message.contains("overflow"), "{e}");
    let e = error_of(&format!("{PRISM}position = [1e200, 0.0, 0.0]\n"));
    assert!(e.to_string().contains("overflow"), "{e}");
}

#[test]
fn a_prism_spinning_steadily_about_a_principal_axis_passes_the_particle_check() {
    for omega in ["[0.0, 0.0, 1.0]", "[0.0, 3.0, 0.0]", "[1e3, 0.0, 0.0]"] {
        let s = Scene::from_str_at(
            Path::new("s.toml"),
            &format!("{PRISM}[motion]\nomega = {omega}\n"),
        )
        .unwrap();
        let d = s.dynamics();
        assert!(d.kinetics.force.norm() < 1e-9, "{omega}");
        assert!(d.particle_check < 1e-9, "{omega}: {}", d.particle_check);
    }
}

#[test]
fn huge_and_tiny_directions_are_normalised_without_overflow() {
    let base = |x_axis: &str, dir: &str| {
        format!(
            "{PRISM}rotation = {{ x_axis = {x_axis} }}\n[motion]\nomega = [0.0, 0.0, 1.0]\n[[force]]\nname = \"F\"\npoint = [0.0, 0.0, 0.0]\ndirection = {dir}\n[[force]]\nname = \"R\"\npoint = [0.0, 0.0, 0.0]\nunknown = [\"y\", \"z\"]\n[[couple]]\nname = \"C\"\nunknown = [\"x\", \"y\", \"z\"]\n"
        )
    };
    let reference = Scene::from_str_at(
        Path::new("s.toml"),
        &base("[1.0, 1.0, 0.0]", "[1.0, 0.0, 0.0]"),
    )
    .unwrap()
    .dynamics();
    assert!(reference.unsolved.is_none(), "{:?}", reference.unsolved);
    for (x_axis, dir) in [
        ("[1e160, 1e160, 0.0]", "[1e200, 0.0, 0.0]"),
        ("[1e-200, 1e-200, 0.0]", "[1e-300, 0.0, 0.0]"),
    ] {
        let s = Scene::from_str_at(Path::new("s.toml"), &base(x_axis, dir)).unwrap();
        let d = s.dynamics();
        assert!(d.unsolved.is_none(), "{x_axis} {dir}: {:?}", d.unsolved);
        let (a, b) = (
            d.inertia.props.inertia_g.matrix(),
            reference.inertia.props.inertia_g.matrix(),
        );
        assert!((a - b).norm() <= 1e-12 * b.norm(), "{x_axis}: {a} vs {b}");
        for (k, v) in &reference.unknowns {
            let w = d.unknowns[k];
            assert!((v - w).abs() <= 1e-9 * (1.0 + v.abs()), "{k}: {v} vs {w}");
        }
    }
}
