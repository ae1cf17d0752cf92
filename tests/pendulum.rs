//! The double pendulum of two rods that the tests of where bodies are
//! (`tests/sim/positions.rs`) and of the simulation page
//! (`tests/cli/page_places.rs`) share: a derivation and its scene.

/// A double pendulum of two rods written for the tests: rod 1 (frame A)
/// hangs from the fixed point O, rod 2 (frame B, turned by q2 from A)
/// from rod 1's end P; Y is up. Kane's equations in mass-matrix form
/// (steps `M`, `f`).
pub const DOUBLE_PENDULUM: &str = concat!(
    r#"
title = "A double pendulum of two rods, written for the tests of the bodies' places"
source = "hdot tests"
summary = "Rod 1 hangs from O, rod 2 from rod 1's end P; q1 from the downward vertical, q2 relative to rod 1."
gravity = "[0, -g, 0] in N"

[symbols]
constants = ["m1", "m2", "l1", "l2", "I1", "I2", "g"]
time = ["q1", "q2"]
speeds = ["u1", "u2"]

[kinematics]
q1 = "u1"
q2 = "u2"

"#,
    crate::frame!("A", "N", "z(q1)"),
    crate::frame!("B", "A", "z(q2)"),
    crate::fixed_point!("O"),
    crate::point!("P", "O", "[0, -l1, 0] in A"),
    crate::double_pendulum_rods!(),
    r#"
[[step]]
name = "K"
label = "0"
value = "kane([u1, u2])"

[[step]]
name = "M"
value = "mass_matrix(K, [u1', u2'])"

[[step]]
name = "f"
value = "forcing(K, [u1', u2'])"
"#
);

/// The double pendulum's scene, beside the derivation as
/// `double-pendulum.toml`: two rods of 1 m and 0.8 m, given by their
/// tables in their frames' axes from their reference points.
pub const DOUBLE_PENDULUM_SCENE: &str = r#"
name = "double pendulum of two rods"
kind = "derived"
t_end = 2.0
g = [0.0, -9.81, 0.0]

[derivation]
file = "double-pendulum.toml"
mass_matrix = "M"
forcing = "f"
frame = "B"

[[body]]
of = "rod1"
shape = "rod"
length = 1.0
mass = 1.0
position = [0.0, -0.5, 0.0]
rotation = { x_axis = [0.0, 1.0, 0.0] }

[[body]]
of = "rod2"
shape = "rod"
length = 0.8
mass = 0.5
position = [0.0, -0.4, 0.0]
rotation = { x_axis = [0.0, 1.0, 0.0] }

[initial]
coordinates = { q1 = 1.0, q2 = 0.5 }
speeds = { u1 = 0.0, u2 = 0.0 }
"#;
