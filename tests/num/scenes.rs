//! Bundled worked problems against their textbook answers, each derived
//! here by hand from the formulas of docs/equations.md; and the rank checks.

use std::path::{Path, PathBuf};

use hdot_num::scene::{DynamicsReport, Scene};
use hdot_num::solve::SolveError;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/examples")
        .join(name)
}

fn solve(name: &str) -> (Scene, DynamicsReport) {
    let scene = Scene::from_path(&example(name)).unwrap();
    let r = scene.dynamics();
    assert!(r.unsolved.is_none(), "{name}: {:?}", r.unsolved);
    assert!(
        r.particle_check < 1e-12,
        "{name}: particle check {:e}",
        r.particle_check
    );
    (scene, r)
}

fn assert_close(name: &str, got: f64, want: f64, scale: f64) {
    let tol = 1e3 * f64::EPSILON * scale;
    assert!(
        (got - want).abs() <= tol,
        "{name}: got {got}, want {want} (tol {tol:e})"
    );
}

#[test]
fn rolling_disk_floor_and_pivot_reactions() {
    let (scene, r) = solve("rolling-disk.toml");
    let (m, g, rad, l, w1) = (4.0, 9.81, 0.3, 0.6, 3.0);
    assert_eq!(scene.body.mass_properties().mass, m);
    // Ḣ_O about z = (m r²/4 + m L²) α_z − ω1 ω2 (m L² − m r²/4) = m r L ω1² / 2
    // ΣM_z = (N − m g) L  ⇒  N = m g + m r ω1² / 2
    let n = m * g + m * rad * w1 * w1 / 2.0;
    let scale = m * g + m * l * w1 * w1;
    assert_close("N", r.unknowns["N"], n, scale);
    // ΣF = m ā, ā = −L ω1² i
    assert_close("O_x", r.unknowns["O_x"], -m * l * w1 * w1, scale);
    assert_close("O_y", r.unknowns["O_y"], m * g - n, scale);
    assert_close("O_z", r.unknowns["O_z"], 0.0, scale);
}

#[test]
fn rod_on_axle_wire_tension_and_pin_reaction() {
    let (scene, r) = solve("rod-on-axle.toml");
    let (m, g, l, w) = (18.0, 9.81, 2.4, 15.0);
    let b = scene.forces[0].point;
    let beta = b.x.atan2(b.y); // from the vertical
    // H_A = (m L²/3)(E − e eᵀ) ω, Ḣ_A = ω × H_A = (m L² ω²/3) sin β cos β k
    // ΣM_A,z = T L cos β − m g (L/2) sin β
    let t = m * g / 2.0 * beta.tan() + m * l * w * w * beta.sin() / 3.0;
    let scale = m * l * w * w;
    assert_close("T", r.unknowns["T"], t, scale);
    // ΣF = m ā, ā = −ω² (L/2) sin β i
    assert_close(
        "A_x",
        r.unknowns["A_x"],
        t - m * w * w * l / 2.0 * beta.sin(),
        scale,
    );
    assert_close("A_y", r.unknowns["A_y"], m * g, scale);
    assert_close("A_z", r.unknowns["A_z"], 0.0, scale);
}

#[test]
fn struck_plate_velocities_after_impact() {
    let (_, r) = solve("struck-plate.toml");
    let (m, a, b, j): (f64, f64, f64, f64) = (6.0, 0.6, 0.4, -12.0);
    let (rx, ry) = (a / 2.0, -b / 2.0);
    // m v̄ = F Δt ; H_G = I_G ω = r_D × F Δt, I_x = m b²/12, I_y = m a²/12
    let scale = j.abs() / m * (1.0 + 1.0 / a.min(b));
    assert_close("v_z", r.unknowns["v_z"], j / m, scale);
    assert_close("v_x", r.unknowns["v_x"], 0.0, scale);
    assert_close("v_y", r.unknowns["v_y"], 0.0, scale);
    assert_close(
        "omega_x",
        r.unknowns["omega_x"],
        ry * j / (m * b * b / 12.0),
        scale,
    );
    assert_close(
        "omega_y",
        r.unknowns["omega_y"],
        -rx * j / (m * a * a / 12.0),
        scale,
    );
    assert_close("omega_z", r.unknowns["omega_z"], 0.0, scale);
    assert_close("J_A", r.unknowns["J_A"], 0.0, j.abs());
    assert_close("J_B", r.unknowns["J_B"], 0.0, j.abs());
    assert_close(
        "T after",
        r.kinetics.kinetic_energy,
        0.5 * m * (j / m).powi(2)
            + 0.5 * (m * b * b / 12.0) * (ry * j / (m * b * b / 12.0)).powi(2)
            + 0.5 * (m * a * a / 12.0) * (rx * j / (m * a * a / 12.0)).powi(2),
        1e3,
    );
}

#[test]
fn unbalanced_shaft_bearing_reactions() {
    let (_, r) = solve("unbalanced-shaft.toml");
    let g = 9.81;
    let (ms, mb, rb, lz) = (8.0, 0.5, 0.03, 1.2);
    let balls = [(0.1, 0.3), (-0.1, 0.9)];
    let (w, alpha) = (60.0, 5.0);
    let m = ms + 2.0 * mb;
    // products and moment about A (balls only; the slender shaft lies on z)
    let ixz: f64 = balls.iter().map(|(x, z)| mb * x * z).sum();
    let iyz = 0.0;
    let iz: f64 = balls
        .iter()
        .map(|(x, _)| 0.4 * mb * rb * rb + mb * x * x)
        .sum();
    let xg: f64 = balls.iter().map(|(x, _)| mb * x).sum::<f64>() / m;
    let zg = (ms * 0.6 + balls.iter().map(|(_, z)| mb * z).sum::<f64>()) / m;
    // fixed-axis equations about A (reference §6)
    //   ΣM_x = −L B_y + z̄ m g = −I_xz α + I_yz ω²
    //   ΣM_y =  L B_x         = −I_yz α − I_xz ω²
    //   ΣM_z = M − x̄ m g      =  I_z α
    let by = (zg * m * g + ixz * alpha - iyz * w * w) / lz;
    let bx = (-iyz * alpha - ixz * w * w) / lz;
    let mz = iz * alpha + xg * m * g;
    let scale = m * g + ixz.abs() * w * w;
    assert_close("B_x", r.unknowns["B_x"], bx, scale);
    assert_close("B_y", r.unknowns["B_y"], by, scale);
    assert_close("M_z", r.unknowns["M_z"], mz, scale);
    // ā = 0 (G on the axis): A = −W − B
    assert_close("A_x", r.unknowns["A_x"], -bx, scale);
    assert_close("A_y", r.unknowns["A_y"], m * g - by, scale);
    assert_close("A_z", r.unknowns["A_z"], 0.0, scale);
}

const ROD: &str = r#"
g = [0.0, -9.81, 0.0]
[[body]]
shape = "rod"
length = 2.0
mass = 3.0
position = [1.0, 0.0, 0.0]
[motion]
fixed_point = [0.0, 0.0, 0.0]
omega = [0.0, 2.0, 0.0]
"#;

#[test]
fn underdetermined_unknowns_are_reported_not_solved() {
    // two collinear pins on the x axis cannot share the x loads
    let text = format!(
        "{ROD}\n[[force]]\nname = \"P\"\npoint = [0.0, 0.0, 0.0]\nunknown = [\"x\", \"y\", \"z\"]\n\
         [[force]]\nname = \"Q\"\npoint = [2.0, 0.0, 0.0]\nunknown = [\"x\", \"y\", \"z\"]\n"
    );
    let s = Scene::from_str_at(Path::new("u.toml"), &text).unwrap();
    let r = s.dynamics();
    assert!(r.unknowns.is_empty());
    match r.unsolved {
        Some(SolveError::Underdetermined {
            rank,
            unknowns,
            ref free,
        }) => {
            assert_eq!((rank, unknowns), (5, 6));
            assert_eq!(free, &["P_x".to_string(), "Q_x".to_string()]);
        }
        other => panic!("expected underdetermined, got {other:?}"),
    }
}

#[test]
fn inconsistent_unknowns_are_reported_not_solved() {
    // a single vertical force cannot supply the centripetal force
    let text = format!(
        "{ROD}\n[[force]]\nname = \"N\"\npoint = [1.0, 0.0, 0.0]\ndirection = [0.0, 1.0, 0.0]\n"
    );
    let s = Scene::from_str_at(Path::new("i.toml"), &text).unwrap();
    let r = s.dynamics();
    assert!(
        matches!(r.unsolved, Some(SolveError::Inconsistent { .. })),
        "{:?}",
        r.unsolved
    );
    assert!(r.unknowns.is_empty());
}

#[test]
fn scene_errors_name_file_line_and_field() {
    // table: text => (line of the key, field, message fragment)
    let cases: &[(&str, usize, &str, &str)] = &[
        (
            "[[body]]\nshape = \"disk\"\nradius = 1.0\nmass = -2.0\n",
            4,
            "body[0].mass",
            "positive",
        ),
        (
            "[[body]]\nshape = \"disk\"\nmass = 2.0\n",
            1,
            "body[0].radius",
            "missing",
        ),
        (
            "\n[[body]]\nshape = \"blob\"\nmass = 2.0\n",
            2,
            "body[0].shape",
            "unknown shape",
        ),
        (
            "[[body]]\nshape = \"sphere\"\nradius = nan\nmass = 2.0\n",
            3,
            "body[0].radius",
            "not finite",
        ),
        (
            "[[body]]\nshape = \"sphere\"\nradius = 1.0\nweight = 2.0\n",
            4,
            "body[0].weight",
            "g",
        ),
        (
            "[[body]]\nshape = \"sphere\"\nradius = 1.0\nmass = 1.0\nposition = [0.0, inf, 0.0]\n",
            5,
            "body[0].position",
            "not finite",
        ),
        ("x = 1\n[[body]]\n", 1, "-", "unknown field"),
        (
            "[[body]]\nshape = \"rod\"\nlength = 1.0\nmass = 1.0\n\n[[force]]\nname = \"F\"\npoint = [0.0, 0.0, 0.0]\n",
            6,
            "force[0].value",
            "give a value",
        ),
        ("", 0, "body", "no body"),
        (
            "[[body]]\nshape = \"disk\"\nradius = 1.0\nmass = 1.0\nrotation = { axis = [0.0, 0.0, 0.0], angle_deg = 3.0 }\n",
            5,
            "body[0].rotation.axis",
            "zero",
        ),
    ];
    for (text, line, field, msg) in cases {
        let e = Scene::from_str_at(Path::new("s.toml"), text).unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (*line, *field), "{text:?}: {e}");
        assert!(e.message.contains(msg), "{text:?}: {e}");
        assert!(e.to_string().starts_with("s.toml:"), "{e}");
    }
}

#[test]
fn scene_with_a_csv_cloud_and_a_bad_cloud() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("c.csv"), "x,y,z,m\n1,0,0,2\n-1,0,0,2\n").unwrap();
    let scene_path = dir.path().join("s.toml");
    let text = "[[cloud]]\nfile = \"c.csv\"\n";
    let s = Scene::from_str_at(&scene_path, text).unwrap();
    let r = s.inertia();
    assert_eq!(r.props.mass, 4.0);
    assert_eq!(r.props.inertia_g.moments(), [0.0, 4.0, 4.0]);
    std::fs::write(dir.path().join("c.csv"), "x,y,z,m\n1,0,0,2\n-1,0,0\n").unwrap();
    let e = Scene::from_str_at(&scene_path, text).unwrap_err();
    assert_eq!((e.line, e.field.as_str()), (1, "cloud[0].file"));
    assert!(e.message.contains("c.csv:3: field `m`"), "{e}");
}

/// Issue 21: a CSV cloud whose total mass overflows panicked in `hdot
/// inertia` and `hdot dynamics`; it is an error naming the CSV file.
#[test]
fn a_cloud_whose_total_mass_overflows_is_an_error_naming_the_csv() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("big.csv"), "0,0,0,1.7e308\n1,0,0,1.7e308\n").unwrap();
    let scene_path = dir.path().join("s.toml");
    let e = Scene::from_str_at(&scene_path, "[[cloud]]\nfile = \"big.csv\"\n").unwrap_err();
    assert_eq!((e.line, e.field.as_str()), (1, "cloud[0].file"));
    assert!(
        e.message.contains("big.csv") && e.message.contains("mass is not finite"),
        "{e}"
    );
    // Finite masses whose second moments overflow: the same, naming the
    // inertia.
    std::fs::write(dir.path().join("big.csv"), "1e200,0,0,1\n-1e200,0,0,1\n").unwrap();
    let e = Scene::from_str_at(&scene_path, "[[cloud]]\nfile = \"big.csv\"\n").unwrap_err();
    assert!(
        e.message.contains("big.csv") && e.message.contains("inertia is not finite"),
        "{e}"
    );
}

/// Issue 21: an overflow of a cloud's sums named its field `-` at "line
/// 0" (`big.csv:0`, `s.toml:0: body: …`): it names the CSV's line and
/// column, or the scene's table that takes the bodies' sums past the
/// largest number, at its line.
#[test]
fn an_overflow_names_the_csv_line_and_column_or_the_scene_table() {
    let dir = tempfile::tempdir().unwrap();
    let scene_path = dir.path().join("s.toml");
    let csv = dir.path().join("big.csv");
    for (rows, line, column, what) in [
        // Masses summing past the largest number: the second particle's m.
        ("0,0,0,1.7e308\n1,0,0,1.7e308\n", 2, "m", "mass"),
        // A header and a comment counted: the line in the file.
        ("x,y,z,m\n# far\n0,0,0,1\n0,3e200,0,1\n", 4, "y", "inertia"),
        ("1,0,0,1\n0,0,-2e160,1e100\n", 2, "z", "inertia"),
    ] {
        std::fs::write(&csv, rows).unwrap();
        let e = Scene::from_str_at(&scene_path, "[[cloud]]\nfile = \"big.csv\"\n").unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (1, "cloud[0].file"), "{e}");
        let want = format!(
            "{}:{line}: field `{column}`: the particles' {what} is not finite",
            csv.display()
        );
        assert!(e.message.contains(&want), "`{e}` lacks `{want}`");
    }
    // Two clouds whose masses sum past the largest number: the second
    // `[[cloud]]` table, at its line.
    std::fs::write(dir.path().join("one.csv"), "0,0,0,1e308\n").unwrap();
    let text = "[[body]]\nshape = \"point\"\nmass = 1.0\n\n[[cloud]]\nfile = \"one.csv\"\n\n[[cloud]]\nfile = \"one.csv\"\n";
    let e = Scene::from_str_at(&scene_path, text).unwrap_err();
    let msg = e.to_string();
    let want = format!("{}:8: cloud[1]: ", scene_path.display());
    assert!(msg.starts_with(&want), "`{msg}` lacks `{want}`");
    assert!(msg.contains("overflow"), "{msg}");
}

/// Issue 21: a body of 1 mg and 1 mm printed its inertia tensor as zeros;
/// the text report prints significant digits however small the body.
#[test]
fn small_bodies_print_significant_digits() {
    let text = "[[body]]\nshape = \"sphere\"\nmass = 1e-6\nradius = 1e-3\n";
    let s = Scene::from_str_at(Path::new("small.toml"), text).unwrap();
    let r = hdot_num::report::Report::inertia(&s);
    // I = (2/5) m r², printed with 6 significant digits.
    let i = 0.4 * 1e-6 * 1e-6;
    let printed = r.text(6);
    assert!(
        printed.contains(&hdot_num::report::fmt_num_at(i, i, 6)),
        "{printed}"
    );
    // Off-diagonal entries, exactly zero, still print as 0.
    assert!(printed.contains(" 0 "), "{printed}");
    let text = "[[body]]\nshape = \"sphere\"\nmass = 1e-13\nradius = 1.0\n";
    let s = Scene::from_str_at(Path::new("small.toml"), text).unwrap();
    let printed = hdot_num::report::Report::inertia(&s).text(6);
    let fmt = |x: f64| hdot_num::report::fmt_num_at(x, x, 6);
    assert!(
        printed.contains(&format!("mass              {}", fmt(1e-13))),
        "{printed}"
    );
    assert!(printed.contains(&fmt(0.4e-13)), "{printed}");
    assert!(fmt(0.4e-13) != "0");
}

/// Issue 25: a scene of N `[[body]]` tables took time ∝ N² (the line of
/// each table counted from the start of the file). A large scene loads,
/// its mass the sum of its bodies'.
#[test]
fn a_scene_of_many_bodies_loads() {
    let n = 20_000;
    let mut text = String::new();
    for k in 0..n {
        text.push_str(&format!(
            "[[body]]\nshape = \"sphere\"\nmass = 1.0\nradius = 0.1\nposition = [{k}.0, 0.0, 0.0]\n"
        ));
    }
    let s = Scene::from_str_at(Path::new("many.toml"), &text).unwrap();
    let p = s.body.mass_properties();
    assert!((p.mass - n as f64).abs() <= 1e-12 * n as f64);
    let centre = (n - 1) as f64 / 2.0;
    assert!((p.center.x - centre).abs() <= 1e-9 * centre);
}

/// Rates whose moments leave f64's range (ω = 1e200 rad/s on a shaft) are
/// named at their field and line, not reported as a resultant moment that
/// is "not a finite number" (issue 21 item 8, a hostile trial).
#[test]
fn rates_beyond_range_are_named_at_their_line() {
    let text = std::fs::read_to_string(example("unbalanced-shaft.toml")).unwrap();
    for (from, to, field) in [
        (
            "omega = [0.0, 0.0, 60.0]",
            "omega = [0.0, 0.0, 1e200]",
            "motion.omega",
        ),
        (
            "alpha = [0.0, 0.0, 5.0]",
            "alpha = [0.0, 0.0, 1e305]",
            "motion.alpha",
        ),
    ] {
        assert!(text.contains(from), "the example changed: {from}");
        let bad = text.replace(from, to);
        let line = bad.lines().position(|l| l == to).unwrap() + 1;
        let e = Scene::from_str_at(Path::new("s.toml"), &bad).expect_err(to);
        assert_eq!((e.line, e.field.as_str()), (line, field), "{e}");
        assert!(e.message.contains("beyond the range of f64"), "{e}");
    }
}
