//! Derived scenes that give their bodies as `[[body]]` tables
//! (scene/derived.rs): the derivation's body declarations bind its symbols
//! from the tables' mass properties, after checking the declared symmetry.
//! A problem written for the test — a compound pendulum (a rod with a disk
//! at its end) swinging about a horizontal axle — and each way a scene's
//! bodies can disagree with the derivation, refused naming the field.

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::{Method, SimError, Step};
use hdot_tests::repo_root;

/// A body pivoted at O on a horizontal axle y, swinging by θ; its axis z
/// points from O through G (G at l), it is axisymmetric about z with
/// moments I′ about the transverse axes through O and I about z.
/// Lagrange's equation with T = ½ I′ θ̇² and V = −m g l cos θ.
const PENDULUM: &str = r#"
title = "compound pendulum"
source = "written for the test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "l", "I", "Ip"]
time = ["theta"]
[[frame]]
name = "P"
parent = "N"
rotation = "y(theta)"
[[point]]
name = "O"
fixed = true
[[body]]
name = "pendulum"
frame = "P"
point = "O"
mass = "m"
mass_centre = "[0, 0, -l] in P"
inertia = "principal(Ip, Ip, I)"
symmetry = "axisymmetric z"
[[step]]
name = "w"
value = "express(angvel(P), P)"
[[step]]
name = "T_kin"
value = "dot(w, principal(Ip, Ip, I)*w)/2"
[[step]]
name = "V"
value = "m*g*dot(express([0, 0, -l] in P, N), [0, 0, 1] in N)"
[[step]]
name = "eq"
value = "lagrange(T_kin, V, theta)"
[[step]]
name = "acc"
value = "solve(list(eq), [theta''])"
[[step]]
name = "energy"
value = "T_kin + V"
conserved = true
"#;

/// A rod of 0.4 kg, 0.5 m long, hanging from O along −z, and a disk of
/// 1 kg, radius 0.05 m, in the xy-plane at its end.
const SCENE: &str = r#"
name = "compound pendulum"
kind = "derived"
t_end = 2.0
[derivation]
file = "pendulum.toml"
accelerations = "acc"
[[body]]
shape = "rod"
mass = 0.4
length = 0.5
position = [0.0, 0.0, -0.25]
rotation = { x_axis = [0.0, 0.0, 1.0] }
[[body]]
shape = "disk"
mass = 1.0
radius = 0.05
position = [0.0, 0.0, -0.5]
[constants]
g = 9.81
[initial]
coordinates = { theta = 0.4 }
rates = { theta = 0.0 }
"#;

fn pendulum(scene: &str, derivation: &str) -> Result<Scene, SimError> {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("pendulum.toml"), derivation).expect("write");
    Scene::parse(scene, &dir.path().join("scene.toml"))
}

fn constants(scene: &Scene) -> &std::collections::BTreeMap<String, f64> {
    let SceneKind::Derived(ds) = &scene.kind else {
        panic!("a derived scene")
    };
    &ds.spec.constants
}

/// The tables bind m, l, I′ and I as the textbook formulas give them
/// (rod: m L²/12 about its centre; disk: m r²/4 about a diameter, m r²/2
/// about its axis; parallel axes to O), and the run conserves the energy.
#[test]
fn a_composite_binds_the_declared_symbols() {
    let scene = pendulum(SCENE, PENDULUM).expect("scene");
    let c = constants(&scene);
    let (m1, len, m2, r): (f64, f64, f64, f64) = (0.4, 0.5, 1.0, 0.05);
    let m = m1 + m2;
    let l = (m1 * len / 2.0 + m2 * len) / m;
    let ip = m1 * len * len / 12.0 + m1 * (len / 2.0).powi(2) + m2 * r * r / 4.0 + m2 * len * len;
    let i = m2 * r * r / 2.0;
    for (name, want) in [("m", m), ("l", l), ("Ip", ip), ("I", i), ("g", 9.81)] {
        let got = c[name];
        assert!(
            (got - want).abs() <= 1e-13 * want,
            "{name}: bound {got}, textbook {want}"
        );
    }
    let req = Request {
        method: Some(Method::Dop853),
        step: Some(Step::Tolerance(1e-10)),
        ..Request::default()
    };
    let plan = run::plan(&scene, &req).expect("plan");
    let r = run::run(&scene, &plan, &mut Output::default()).expect("run");
    assert_eq!(r.drifts.len(), 1);
    assert!(r.drifts[0].relative < 1e-8, "{:e}", r.drifts[0].relative);
    assert!(r.final_state.iter().all(|v| v.is_finite()));
}

/// The scene's bodies and the same numbers given under `[constants]` are
/// one scene: same equations, same final state.
#[test]
fn bodies_and_constants_give_the_same_motion() {
    let a = pendulum(SCENE, PENDULUM).expect("scene");
    let c = constants(&a).clone();
    let mut text = SCENE.split("[[body]]").next().expect("head").to_string();
    text.push_str("[constants]\n");
    for (k, v) in &c {
        text.push_str(&format!("{k} = {v:e}\n"));
    }
    text.push_str("[initial]\ncoordinates = { theta = 0.4 }\nrates = { theta = 0.0 }\n");
    let b = pendulum(&text, PENDULUM).expect("scene with constants");
    let req = Request {
        method: Some(Method::Dop853),
        step: Some(Step::Tolerance(1e-10)),
        ..Request::default()
    };
    let run_it = |s: &Scene| {
        let plan = run::plan(s, &req).expect("plan");
        run::run(s, &plan, &mut Output::default()).expect("run")
    };
    let (ra, rb) = (run_it(&a), run_it(&b));
    assert_eq!(ra.final_state, rb.final_state);
}

macro_rules! refuses {
    ($($name:ident: $scene:expr, $derivation:expr => $($says:expr),+;)*) => {$(
        #[test]
        fn $name() {
            let err = pendulum(&$scene, $derivation).expect_err("must be refused");
            let msg = err.to_string();
            $(assert!(msg.contains($says), "message `{msg}` lacks `{}`", $says);)+
        }
    )*};
}

refuses! {
    // A prism for the disk: the body is not axisymmetric about z.
    not_axisymmetric: SCENE.replace(
        "shape = \"disk\"\nmass = 1.0\nradius = 0.05",
        "shape = \"prism\"\nmass = 1.0\na = 0.1\nb = 0.2\nc = 0.01",
    ), PENDULUM => "body[0]", "`pendulum`", "axisymmetric about its z axis", "but the body is not";
    // The disk off the axis: G is not on z.
    centre_off_the_axis: SCENE.replace("[0.0, 0.0, -0.5]", "[0.02, 0.0, -0.5]"), PENDULUM
        => "body[0]", "axisymmetric about its z axis", "G at";
    // A product of inertia the declared principal form rules out.
    declared_form_not_met: SCENE.replace(
        "symmetry = \"axisymmetric z\"", ""
    ).replace("position = [0.0, 0.0, -0.5]", "position = [0.0, 0.0, -0.5]\nrotation = { axis = [1.0, 0.0, 0.0], angle_deg = 30.0 }"),
    &PENDULUM.replace("symmetry = \"axisymmetric z\"", "symmetry = \"none\"")
        => "body[0]", "inertia entry (2, 2) of pendulum", "declared Ip";
    given_twice: SCENE.replace("g = 9.81", "g = 9.81\nl = 0.4"), PENDULUM
        => "constants.l", "also bound by the body `pendulum`";
    unknown_body: SCENE.replace("shape = \"rod\"", "of = \"bob\"\nshape = \"rod\""), PENDULUM
        => "body[0].of", "declares no body `bob`", "`pendulum`";
    body_without_declaration: SCENE, &PENDULUM.replace("[[body]]\nname = \"pendulum\"", "[[ignored]]\nname = \"pendulum\"")
        => "derivation.file";
    unknown_constant: SCENE.replace("g = 9.81", "g = 9.81\ngg = 1.0"), PENDULUM
        => "constants.gg", "not a constant";
    gravity_not_along_the_declared_one: SCENE.replace("kind = \"derived\"", "kind = \"derived\"\ng = [0.0, -9.81, 0.0]").replace("g = 9.81\n", ""), PENDULUM
        => "field `g`", "must point along it", "[0, 0, -g] in N";
    gravity_given_twice: SCENE.replace("kind = \"derived\"", "kind = \"derived\"\ng = [0.0, 0.0, -9.81]"), PENDULUM
        => "constants.g", "also bound by the scene's g";
    gravity_not_declared: SCENE.replace("kind = \"derived\"", "kind = \"derived\"\ng = [0.0, 0.0, -9.81]").replace("g = 9.81\n", ""),
        &PENDULUM.replace("gravity = \"[0, 0, -g] in N\"\n", "")
        => "field `g`", "declares no gravity";
}

/// A derivation that declares no body cannot take `[[body]]` tables.
#[test]
fn tables_without_a_declared_body_are_refused() {
    let d = PENDULUM.split("[[body]]").next().expect("head").to_string()
        + PENDULUM
            .split("[[step]]")
            .skip(1)
            .fold(String::new(), |s, x| s + "[[step]]" + x)
            .as_str();
    let err = pendulum(SCENE, &d).expect_err("refused").to_string();
    assert!(err.contains("declares no `[[body]]`"), "{err}");
}

/// Tables of a derivation with several bodies say which they make up.
#[test]
fn several_bodies_need_of() {
    let path = repo_root().join("docs/examples/sim-gimballed-gyroscope.toml");
    let text = std::fs::read_to_string(&path).expect("read");
    let without = text.replace("of = \"rotor\"\n", "");
    let err = Scene::parse(&without, &path)
        .expect_err("refused")
        .to_string();
    assert!(
        err.contains("several bodies") && err.contains("of = "),
        "{err}"
    );
    // `of` is refused outside a derived scene.
    let free = repo_root().join("docs/examples/sim-torque-free-asymmetric.toml");
    let text = std::fs::read_to_string(&free).expect("read");
    let with = text.replacen("[[body]]", "[[body]]\nof = \"x\"", 1);
    let err = Scene::parse(&with, &free).expect_err("refused").to_string();
    assert!(
        err.contains("body[0].of") && err.contains("only the bodies of a derived scene"),
        "{err}"
    );
}

/// The scene's gravity vector binds the derivation's g through its
/// `gravity` declaration, as the built-in scenes give gravity.
#[test]
fn the_gravity_vector_binds_g() {
    let text = SCENE
        .replace(
            "kind = \"derived\"",
            "kind = \"derived\"\ng = [0.0, 0.0, -9.75]",
        )
        .replace("[constants]\ng = 9.81\n", "");
    let scene = pendulum(&text, PENDULUM).expect("scene");
    assert_eq!(constants(&scene)["g"], 9.75);
}
