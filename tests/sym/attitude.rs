//! Attitude kinematics derived, not typed: a `[kinematics]` entry
//! `{ frame = "B", speeds = […], axes = "…" }` gives the kinematic
//! equations of the angles that turn B from N. The bundled gyrostat and
//! rolling disk give the same equations (canonically) as the tables typed
//! by hand; a 3-1-3 sequence in space components and a 1-2-3 sequence in
//! body components give SymPy's inverses; bad entries are located errors.

use hdot_sym::derivation::{Derivation, load_str};
use hdot_tests::repo_root;

/// `text` with the body of its `[kinematics]` table (up to a blank line
/// or the next table) replaced by `table`.
fn with_kinematics(text: &str, table: &str) -> String {
    let mut out = String::new();
    let mut skipping = false;
    for line in text.lines() {
        if line.trim() == "[kinematics]" {
            out.push_str(line);
            out.push('\n');
            out.push_str(table);
            out.push('\n');
            skipping = true;
            continue;
        }
        if skipping && (line.trim().is_empty() || line.trim_start().starts_with('[')) {
            skipping = false;
        }
        if !skipping {
            out.push_str(line);
            out.push('\n');
        }
    }
    assert!(out.contains(table), "the file has a [kinematics] table");
    out
}

fn load(name: &str, text: &str) -> Derivation {
    load_str(name, text).unwrap_or_else(|e| panic!("{e}"))
}

/// The bundled file with its `[kinematics]` table `derived` and `typed`.
fn derived_and_typed(path: &str, derived: &str, typed: &str) -> (Derivation, Derivation) {
    let text = std::fs::read_to_string(repo_root().join(path)).unwrap();
    let a = with_kinematics(&text, derived);
    let b = with_kinematics(&text, typed);
    assert!(
        a == text || b == text,
        "the bundled file has one of the tables"
    );
    (load(path, &a), load(path, &b))
}

/// Both derivations give every coordinate the same rate (canonical
/// equality, whatever the order) and every step the same value.
fn assert_same(derived: &Derivation, typed: &Derivation) {
    assert!(derived.all_hold(), "{:?}", derived.failures());
    assert!(typed.all_hold(), "{:?}", typed.failures());
    let (a, b) = (derived.kinematic_equations(), typed.kinematic_equations());
    assert_eq!(a.len(), b.len());
    for (q, f) in b {
        let g = a
            .iter()
            .find(|(c, _)| c == q)
            .unwrap_or_else(|| panic!("no rate for {q}"));
        assert_eq!(&g.1, f, "the rate of {q}");
    }
    assert_eq!(derived.steps.len(), typed.steps.len());
    for (s, t) in derived.steps.iter().zip(&typed.steps) {
        assert_eq!(s.value, t.value, "step {}", s.name);
    }
}

#[test]
fn the_gyrostat_derived_kinematics_are_the_typed_ones() {
    let (derived, typed) = derived_and_typed(
        "derivations/gyrostat.toml",
        r#"attitude = { frame = "B", speeds = ["u_1", "u_2", "u_3"] }   # u = B's angular velocity in B's axes: ψ', θ', φ' derived"#,
        r#"psi = "(u_1*sin(phi) + u_2*cos(phi))/sin(theta)"
theta = "u_1*cos(phi) - u_2*sin(phi)"
phi = "u_3 - (u_1*sin(phi) + u_2*cos(phi))*cos(theta)/sin(theta)""#,
    );
    assert_same(&derived, &typed);
}

#[test]
fn the_rolling_disk_derived_kinematics_are_the_typed_ones() {
    let (derived, typed) = derived_and_typed(
        "derivations/disk-rolling-on-plane.toml",
        r#"x = "u_4"
y = "u_5"
disk = { frame = "D", speeds = ["u_1", "u_2", "u_3"], axes = "L" }"#,
        r#"x = "u_4"
y = "u_5"
theta = "u_1"
psi = "u_3/cos(theta)"
phi = "u_2 - u_3*sin(theta)/cos(theta)""#,
    );
    assert_same(&derived, &typed);
}

/// Frames A, E, B turned from N about `axes` (three axis names) by the
/// angles `q` (three names), speeds u_1, u_2, u_3, and `entry` as the
/// `[kinematics]` table.
fn sequence(axes: [&str; 3], q: [&str; 3], entry: &str) -> String {
    format!(
        r#"title = "t"
source = "t"
[symbols]
time = ["{q0}", "{q1}", "{q2}"]
speeds = ["u_1", "u_2", "u_3"]
[kinematics]
{entry}
[[frame]]
name = "A"
parent = "N"
rotation = "{a0}({q0})"
[[frame]]
name = "E"
parent = "A"
rotation = "{a1}({q1})"
[[frame]]
name = "B"
parent = "E"
rotation = "{a2}({q2})"
"#,
        q0 = q[0],
        q1 = q[1],
        q2 = q[2],
        a0 = axes[0],
        a1 = axes[1],
        a2 = axes[2],
    )
}

/// The derived rates equal `want` (coordinate, rate), in this order.
fn assert_rates(d: &Derivation, want: &[(&str, &str)]) {
    let got = d.kinematic_equations();
    let names: Vec<&str> = got.iter().map(|(q, _)| q.name()).collect();
    let want_names: Vec<&str> = want.iter().map(|(q, _)| *q).collect();
    assert_eq!(names, want_names, "the chain's order from N");
    for ((q, f), (_, w)) in got.iter().zip(want) {
        assert_eq!(*f, d.symbols.poly(w).unwrap(), "the rate of {q}");
    }
}

// The expected rates below were computed with SymPy 1.14: R = R_1(q_1)
// R_2(q_2) R_3(q_3) (hdot's `x(q)`, `y(q)`, `z(q)`: components in the turned
// frame to the parent's), ω from the skew matrix Rᵀ Ṙ (body components) or
// R Rᵀ Ṙ's axial vector (space components), `solve(ω - u, q̇)`, simplified;
// tan written as sin/cos.

#[test]
fn a_3_1_3_sequence_in_space_components_gives_sympys_inverse() {
    let text = sequence(
        ["z", "x", "z"],
        ["psi", "theta", "phi"],
        r#"attitude = { frame = "B", speeds = ["u_1", "u_2", "u_3"], axes = "N" }
[[step]]
name = "omega"
value = "in_speeds(express(angvel(B), N))"
expect = ["u_1", "u_2", "u_3"]"#,
    );
    let d = load("t.toml", &text);
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_rates(
        &d,
        &[
            (
                "psi",
                "u_3 - (u_1*sin(psi) - u_2*cos(psi))*cos(theta)/sin(theta)",
            ),
            ("theta", "u_1*cos(psi) + u_2*sin(psi)"),
            ("phi", "(u_1*sin(psi) - u_2*cos(psi))/sin(theta)"),
        ],
    );
}

#[test]
fn a_1_2_3_sequence_in_body_components_gives_sympys_inverse() {
    let text = sequence(
        ["x", "y", "z"],
        ["q_1", "q_2", "q_3"],
        r#"body = { frame = "B", speeds = ["u_1", "u_2", "u_3"] }
[[step]]
name = "omega"
value = "in_speeds(angvel(B))"
expect = ["u_1", "u_2", "u_3"]"#,
    );
    let d = load("t.toml", &text);
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_rates(
        &d,
        &[
            ("q_1", "(u_1*cos(q_3) - u_2*sin(q_3))/cos(q_2)"),
            ("q_2", "u_1*sin(q_3) + u_2*cos(q_3)"),
            (
                "q_3",
                "u_3 - (u_1*cos(q_3) - u_2*sin(q_3))*sin(q_2)/cos(q_2)",
            ),
        ],
    );
}

/// The error of a 3-1-3 file whose `[kinematics]` table is `entry`.
fn bad(entry: &str) -> hdot_sym::derivation::Diagnostic {
    load_str(
        "bad.toml",
        &sequence(["z", "x", "z"], ["psi", "theta", "phi"], entry),
    )
    .unwrap_err()
}

#[test]
fn bad_attitude_entries_are_located_errors() {
    let cases: [(&str, &str); 8] = [
        (
            r#"a = { frame = "C", speeds = ["u_1", "u_2", "u_3"] }"#,
            "unknown frame `C`",
        ),
        (
            r#"a = { frame = "B", speeds = ["u_1", "u_2"] }"#,
            "names 2 speeds",
        ),
        (
            r#"a = { frame = "B", speeds = ["u_1", "u_2", "w"] }"#,
            "`w` is not a declared speed",
        ),
        (
            r#"a = { frame = "B", speeds = ["u_1", "u_1", "u_2"] }"#,
            "names `u_1` twice",
        ),
        (
            r#"a = { frame = "A", speeds = ["u_1", "u_2", "u_3"] }"#,
            "the rates of 1 angles (psi')",
        ),
        (
            r#"a = { frame = "B", speeds = ["u_1", "u_2", "u_3"], axis = "N" }"#,
            "a derived attitude is",
        ),
        ("a = 3", "a coordinate's rate (a string"),
        (
            "a = { frame = \"B\", speeds = [\"u_1\", \"u_2\", \"u_3\"] }\ntheta = \"u_1\"",
            "gives the rate of `theta` twice",
        ),
    ];
    for (entry, words) in cases {
        let e = bad(entry);
        assert!(e.message.contains(words), "{entry}: {e}");
        let line = if words.contains("twice") && words.contains("theta") {
            8
        } else {
            7
        };
        assert_eq!(e.line, line, "{entry}: {e}");
        assert!(e.column > 1, "{entry}: the value is pointed at: {e}");
    }
}

/// A frame turned from N by Euler parameters, speeds u_1, u_2, u_3, and
/// `entry` as the `[kinematics]` table; `rotation` replaces the rotation.
fn quaternion_file(rotation: &str, entry: &str) -> String {
    format!(
        r#"title = "t"
source = "t"
[symbols]
constants = ["c"]
time = ["e_0", "e_1", "e_2", "e_3", "q"]
speeds = ["u_1", "u_2", "u_3"]
[kinematics]
{entry}
[[frame]]
name = "B"
parent = "N"
rotation = "{rotation}"
[[frame]]
name = "C"
parent = "B"
rotation = "z(q)"
[[step]]
name = "omega"
value = "in_speeds(angvel(B))"
expect = ["u_1", "u_2", "u_3"]
"#
    )
}

// Kane, Likins & Levinson, Spacecraft Dynamics (1983), (1.3.22)-(1.3.25):
// ė = ½ E(e)ᵀ ω with ω in the body's axes, e₀ the scalar part.
#[test]
fn euler_parameters_get_the_textbook_kinematic_equations() {
    let text = quaternion_file(
        "quaternion(e_0, e_1, e_2, e_3)",
        r#"body = { frame = "B", speeds = ["u_1", "u_2", "u_3"] }"#,
    );
    let d = load("t.toml", &text);
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_rates(
        &d,
        &[
            ("e_0", "-(e_1*u_1 + e_2*u_2 + e_3*u_3)/2"),
            ("e_1", "(e_0*u_1 - e_3*u_2 + e_2*u_3)/2"),
            ("e_2", "(e_3*u_1 + e_0*u_2 - e_1*u_3)/2"),
            ("e_3", "(-e_2*u_1 + e_1*u_2 + e_0*u_3)/2"),
        ],
    );
    // In N's axes the same rates come out with ω = C u.
    let text = quaternion_file(
        "quaternion(e_0, e_1, e_2, e_3)",
        r#"body = { frame = "B", speeds = ["u_1", "u_2", "u_3"], axes = "N" }"#,
    )
    .replace("in_speeds(angvel(B))", "in_speeds(express(angvel(B), N))");
    let d = load("t.toml", &text);
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_rates(
        &d,
        &[
            ("e_0", "-(e_1*u_1 + e_2*u_2 + e_3*u_3)/2"),
            ("e_1", "(e_0*u_1 + e_3*u_2 - e_2*u_3)/2"),
            ("e_2", "(-e_3*u_1 + e_0*u_2 + e_1*u_3)/2"),
            ("e_3", "(e_2*u_1 - e_1*u_2 + e_0*u_3)/2"),
        ],
    );
}

#[test]
fn bad_quaternion_rotations_are_located_errors() {
    let entry = r#"body = { frame = "B", speeds = ["u_1", "u_2", "u_3"] }"#;
    let cases: [(&str, &str, &str); 4] = [
        (
            "quaternion(e_0, e_1, e_2)",
            entry,
            "quaternion(e_0, e_1, e_2, e_3)",
        ),
        ("quaternion(e_0, e_1, e_2, c)", entry, "`c` is a constant"),
        (
            "quaternion(e_0, e_1, e_1, e_3)",
            entry,
            "`e_1` is named twice",
        ),
        (
            "quaternion(e_0, e_1, e_2, e_3)",
            r#"body = { frame = "C", speeds = ["u_1", "u_2", "u_3"] }"#,
            "give 4 equations in the rates of 5 coordinates",
        ),
    ];
    for (rotation, entry, words) in cases {
        let e = load_str("bad.toml", &quaternion_file(rotation, entry)).unwrap_err();
        assert!(e.message.contains(words), "{rotation} / {entry}: {e}");
        assert!(e.column > 1, "{rotation}: pointed at: {e}");
        let line = if words.contains("coordinates") { 8 } else { 12 };
        assert_eq!(e.line, line, "{rotation} / {entry}: {e}");
    }
}
