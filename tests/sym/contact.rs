//! Rolling contacts (`[[contact]]`): the disk rolling on a plane written
//! with a declared contact gives the bundled file's Kane's equations; the
//! same disk with an auxiliary angle χ for its contact direction (a
//! configuration constraint keeps the rim's lowest point) gives them too
//! where that constraint holds, and to first order about upright rolling;
//! the nonlinear bicycle's linearized lean and steer matrices are the
//! linear bicycle's; bad declarations are located errors.

use hdot_sym::derivation::{Derivation, Value, load, load_str};
use hdot_tests::{WHIPPLE_EIGENVALUES, repo_root};
use hdot_tests::{disk_frames, fixed_point, point};

fn step<'d>(d: &'d Derivation, name: &str) -> &'d Value {
    &d.steps
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("{}: no step {name}", d.name))
        .value
}

fn bundled(path: &str) -> Derivation {
    load(&repo_root().join(path)).unwrap_or_else(|e| panic!("{e}"))
}

/// The rolling disk (yaw ψ, lean θ, spin φ; the wheel's place (x, y) on
/// the ground) declared with a `[[contact]]`; `SPEEDS`, `KINEMATICS`,
/// `CONTACT` and `STEPS` are spliced in.
const DISK: &str = concat!(
    r#"
title = "a disk rolling on a plane, its contact declared"
source = "written for the test"
gravity = "[0, 0, -g] in N"
[symbols]
constants = ["m", "g", "r", "I", "J", "Omega"]
time = ["x", "y", "psi", "theta", "phi"TIME]
speeds = ["u_1", "u_2", "u_3", "u_4", "u_5"SPEEDS]
[kinematics]
x = "u_4"
y = "u_5"
theta = "u_1"
psi = "u_3/cos(theta)"
phi = "u_2 - u_3*sin(theta)/cos(theta)"
KINEMATICS
"#,
    disk_frames!(),
    fixed_point!("O"),
    point!("P", "O", "[x, y, 0] in N"),
    point!("G", "P", "[0, 0, r] in L"),
    r#"[[body]]
name = "disk"
frame = "D"
point = "G"
mass = "m"
mass_centre = "[0, 0, 0] in D"
inertia = "principal(J, I, J)"
symmetry = "axisymmetric y"
[[contact]]
name = "C"
wheel = "disk"
axle = "y"
down = "-z"
radius = "r"
CONTACT
STEPS
"#,
);

fn disk(time: &str, speeds: &str, kinematics: &str, contact: &str, steps: &str) -> Derivation {
    let text = DISK
        .replace("TIME", time)
        .replace("SPEEDS", speeds)
        .replace("KINEMATICS", kinematics)
        .replace("CONTACT", contact)
        .replace("STEPS", steps);
    load_str("disk.toml", &text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_declared_contact_gives_the_bundled_rolling_disk() {
    let want = bundled("derivations/disk-rolling-on-plane.toml");
    for plane in ["", "plane = \"A\""] {
        let d = disk(
            "",
            "",
            "",
            plane,
            r#"
[[step]]
name = "height"
value = "contact_height(C)"
expect = "0"
[[step]]
name = "tangent"
value = "contact_tangent(C)"
expect = "0"
[[step]]
name = "v_z"
value = "contact_velocity(C).z"
expect = "0"
[[step]]
name = "K"
value = "kane([u_1, u_2, u_3], contact_constraints(C), [u_4, u_5])"
"#,
        );
        assert!(d.all_hold(), "{plane}: {:?}", d.failures());
        assert_eq!(step(&d, "K"), step(&want, "K"), "{plane}");
    }
    // Without the plane frame the constraints are written in N's x and y,
    // with A's they are the bundled file's own.
    let d = disk(
        "",
        "",
        "",
        "plane = \"A\"",
        "[[step]]\nname = \"no_slip\"\nvalue = \"rolling_constraints(C)\"\n",
    );
    assert_eq!(step(&d, "no_slip"), step(&want, "no_slip"));
}

/// The contact's direction in the wheel's plane as g = cos χ (−z_L) +
/// sin χ (−x_L) with χ kept by the tangent constraint sin χ cos θ = 0:
/// where it holds (χ = 0) the equations are the bundled disk's, and to
/// first order about upright rolling the linearized ones too.
#[test]
fn an_auxiliary_angle_keeps_the_lowest_point() {
    let want = bundled("derivations/disk-rolling-on-plane.toml");
    let d = disk(
        ", \"chi\"",
        ", \"u_6\"",
        "chi = \"u_6\"",
        "angle = \"chi\"\nplane = \"A\"",
        r#"
[[step]]
name = "tangent"
value = "contact_tangent(C)"
expect = "sin(chi)*cos(theta)"
[[step]]
name = "height"
value = "contact_height(C)"
expect = "r*cos(theta)*(1 - cos(chi))"
[[step]]
name = "rc"
value = "rolling_constraints(C)"
[[step]]
name = "K"
value = "kane([u_1, u_2, u_3], list(rc.1, rc.2, tangent), [u_4, u_5, u_6], [chi])"
[[step]]
name = "K_0"
value = "subst(K, chi = 0*pi)"
[[step]]
name = "KL"
value = "kane([u_1, u_2, u_3], list(rc.1, rc.2, tangent), [u_4, u_5, u_6], [chi], theta = 0, chi = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
"#,
    );
    assert!(d.all_hold(), "{:?}", d.failures());
    assert_eq!(step(&d, "K_0"), step(&want, "K"));
    // χ is not vacuous: away from χ = 0 the equations differ.
    assert_ne!(step(&d, "K"), step(&want, "K"));
    let linear = load_str(
        "disk.toml",
        &(std::fs::read_to_string(repo_root().join("derivations/disk-rolling-on-plane.toml"))
            .unwrap()
            .replace("\"I\", \"J\"]", "\"I\", \"J\", \"Omega\"]")
            + r#"
[[step]]
name = "KL"
value = "kane([u_1, u_2, u_3], no_slip, [u_4, u_5], theta = 0, u_1 = 0, u_2 = Omega, u_3 = 0)"
"#),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(step(&d, "KL"), step(&linear, "KL"));
}

/// Bad declarations: each a located error naming what is wrong.
#[test]
fn bad_contacts_are_located_errors() {
    let cases: [(&str, &str, &str); 6] = [
        (
            "wheel = \"disk\"",
            "wheel = \"wheel\"",
            "`wheel` is not a declared body",
        ),
        ("radius = \"r\"", "radius = \"0\"", "radius is zero"),
        ("radius = \"r\"", "radius = \"r*theta\"", "varies in time"),
        (
            "axle = \"y\"",
            "axle = \"w\"",
            "`axle` is an axis of frame L",
        ),
        ("down = \"-z\"", "down = \"y\"", "square to the axle"),
        (
            "name = \"C\"\nwheel",
            "name = \"G\"\nwheel",
            "already a point",
        ),
    ];
    for (from, to, fragment) in cases {
        let text = DISK
            .replace("TIME", "")
            .replace("SPEEDS", "")
            .replace("KINEMATICS", "")
            .replace("CONTACT", "")
            .replace("STEPS", "");
        assert!(text.contains(from), "{from}");
        let text = text.replacen(from, to, 1);
        let err = load_str("disk.toml", &text).expect_err(to);
        assert!(err.message.contains(fragment), "{to}: {}", err.message);
        let first = to.lines().next().unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let line = 1 + lines.iter().rposition(|l| *l == first).unwrap();
        assert_eq!(err.line, line, "{to}: {err}");
        assert!(err.to_string().contains("--> disk.toml:"), "{err}");
    }
    // A centre that is not a declared point, a direction that needs an
    // auxiliary angle, and a name that is not a contact.
    let base = DISK
        .replace("TIME", "")
        .replace("SPEEDS", "")
        .replace("KINEMATICS", "");
    let more = [
        ("centre = \"Z\"", "", "`Z` is not a declared point"),
        ("angle = \"r\"", "", "declare it under [symbols] time"),
        ("frame = \"D\"\ndown = \"z\"", "", "auxiliary angle"),
        ("down = \"z\"", "", "the rim's highest point"),
        (
            "",
            "[[step]]\nname = \"h\"\nvalue = \"contact_height(G)\"",
            "expected a declared contact",
        ),
    ];
    for (contact, steps, fragment) in more {
        let text = base.replace("CONTACT", contact).replace("STEPS", steps);
        let text = if contact.contains("down") {
            text.replacen("down = \"-z\"\n", "", 1)
        } else {
            text
        };
        let err = load_str("disk.toml", &text).expect_err(contact);
        assert!(
            err.message.contains(fragment),
            "{contact}{steps}: {}",
            err.message
        );
        let first = if contact.is_empty() {
            "value = \"contact_height(G)\""
        } else {
            contact.lines().last().unwrap()
        };
        let lines: Vec<&str> = text.lines().collect();
        let line = 1 + lines.iter().rposition(|l| *l == first).unwrap();
        assert_eq!(err.line, line, "{contact}{steps}: {err}");
    }
}

/// The nonlinear bicycle (both contacts declared, the front one with an
/// auxiliary angle) linearized about upright running: its lean and steer
/// matrices are those of the linear bicycle, which tests/sim/bicycle.rs
/// checks against the benchmark's published values.
#[test]
fn the_nonlinear_bicycle_linearizes_to_the_benchmark_matrices() {
    let exact = bundled("derivations/bicycle-nonlinear.toml");
    let linear = bundled("derivations/bicycle.toml");
    assert!(exact.all_hold(), "{:?}", exact.failures());
    for m in ["M", "C_1", "K_0", "K_2"] {
        assert_eq!(step(&exact, m), step(&linear, m), "{m}");
    }
    // The front contact's constraints are exact: its tangent constraint
    // holds χ, the height the pitch, and neither is the squared form.
    for (s, atom) in [("tangent", "chi"), ("ground", "theta")] {
        let Value::Scalar(p) = step(&exact, s) else {
            panic!("{s}: a scalar")
        };
        assert!(p.atoms().iter().any(|a| a.name() == atom), "{s}: {p}");
    }
    // The nonlinear equations before the constraints: 8 × 8 in the rates
    // of the speeds that move a body, and the power balance (checked by
    // the file's `expect`) is not vacuous.
    let Value::Array(m) = step(&exact, "M_all") else {
        panic!("M_all: an array")
    };
    assert_eq!((m.len(), m[0].len()), (8, 8));
    let Value::Array(a) = step(&exact, "A_c") else {
        panic!("A_c: an array")
    };
    assert_eq!((a.len(), a[0].len()), (6, 9));
    let power = exact.steps.iter().find(|s| s.name == "power").unwrap();
    assert_eq!(power.checks.len(), 1);
    let Value::Scalar(e) = step(&exact, "E") else {
        panic!("E: a scalar")
    };
    assert!(e.terms().len() > 50, "{e}");
}

/// The nonlinear bicycle's equations in multiplier form — M u̇ − f = A_cᵀ λ,
/// A_c u̇ + b = 0 and the kinematic equations — at the benchmark's
/// parameters (docs/examples/stability-bicycle.toml), linearized by
/// central differences about upright running: their eigenvalues away from
/// zero (the ignorable coordinates and the constraints' invariants give
/// zeros) are the benchmark's at 0 and 5 m/s (Table 2's digits, as in
/// tests/sim/bicycle.rs), so the nonlinear equations are those of the
/// bicycle, not only their linearization.
#[test]
fn the_nonlinear_bicycle_in_multiplier_form_has_the_benchmark_eigenvalues() {
    use hdot_sim::nalgebra::{Complex, DMatrix, DVector};
    use hdot_sym::{Atom, AtomKind};
    let d = bundled("derivations/bicycle-nonlinear.toml");
    let scene: toml::Table = toml::from_str(
        &std::fs::read_to_string(repo_root().join("docs/examples/stability-bicycle.toml")).unwrap(),
    )
    .unwrap();
    let constants = scene["constants"].as_table().unwrap();
    let names: Vec<&str> = d
        .kinematic_equations()
        .iter()
        .map(|(q, _)| q.name())
        .chain(d.speeds().iter().map(|u| u.name()))
        .collect();
    assert_eq!(names.len(), 18);
    let polys = |s: &str| -> Vec<hdot_sym::Poly> {
        step(&d, s)
            .components()
            .into_iter()
            .map(|p| d.unfold(p))
            .collect()
    };
    let (m_all, f_all, a_c, b) = (
        polys("M_all"),
        polys("f_all"),
        polys("A_c"),
        polys("A_c_rate"),
    );
    let kin: Vec<hdot_sym::Poly> = d
        .kinematic_equations()
        .iter()
        .map(|(_, f)| f.clone())
        .collect();
    let (n, k) = (9, 6);
    let eval = |p: &hdot_sym::Poly, x: &[f64]| -> f64 {
        fn value(a: Atom, x: &[f64], names: &[&str], c: &toml::Table) -> f64 {
            match a.kind() {
                AtomKind::Sin(q) => value(q, x, names, c).sin(),
                AtomKind::Cos(q) => value(q, x, names, c).cos(),
                AtomKind::Var {
                    name, time: false, ..
                } => c[name].as_float().unwrap(),
                AtomKind::Var { name, order: 0, .. } => {
                    x[names.iter().position(|s| *s == name).unwrap()]
                }
                _ => panic!("a rate in the equations: {a}"),
            }
        }
        p.eval(&mut |a| value(a, x, &names, constants))
    };
    // ẋ = (q̇, u̇): u̇ and λ from [M A_cᵀ; A_c 0] [u̇; λ] = [f; −b].
    let rhs = |x: &[f64]| -> Vec<f64> {
        let mut sys = DMatrix::zeros(n + k, n + k);
        let mut r = DVector::zeros(n + k);
        for i in 0..8 {
            for j in 0..8 {
                sys[(i, j)] = eval(&m_all[8 * i + j], x);
            }
            r[i] = eval(&f_all[i], x);
        }
        for i in 0..k {
            for j in 0..n {
                let a = eval(&a_c[n * i + j], x);
                sys[(n + i, j)] = a;
                sys[(j, n + i)] = a;
            }
            r[n + i] = -eval(&b[i], x);
        }
        let s = sys
            .lu()
            .solve(&r)
            .expect("the constrained system is regular");
        kin.iter()
            .map(|f| eval(f, x))
            .chain(s.iter().take(n).copied())
            .collect()
    };
    for &(v, table) in &WHIPPLE_EIGENVALUES {
        let want: Vec<Complex<f64>> = table.iter().map(|&(re, im)| Complex::new(re, im)).collect();
        // Upright straight running: every angle 0, the rear wheel turning
        // at −v/r_R, the dependent speeds from A_c u = 0.
        let mut x = vec![0.0; 18];
        x[9 + 5] = -v / constants["r_R"].as_float().unwrap();
        let dep = [0, 1, 2, 4, 7, 8];
        let mut ad = DMatrix::zeros(k, k);
        let mut rhs0 = DVector::zeros(k);
        for i in 0..k {
            for (c, &j) in dep.iter().enumerate() {
                ad[(i, c)] = eval(&a_c[n * i + j], &x);
            }
            rhs0[i] = -eval(&a_c[n * i + 5], &x) * x[9 + 5];
        }
        let ud = ad.lu().solve(&rhs0).expect("the dependent speeds");
        for (c, &j) in dep.iter().enumerate() {
            x[9 + j] = ud[c];
        }
        let still = rhs(&x);
        let scale = v.max(1.0);
        for (i, r) in still.iter().enumerate().skip(9) {
            assert!(
                r.abs() <= 1e-9 * scale,
                "v = {v}: u̇ {i} = {r} in steady running"
            );
        }
        let h = 1e-6;
        let mut jac = DMatrix::zeros(18, 18);
        for j in 0..18 {
            let (mut up, mut dn) = (x.clone(), x.clone());
            up[j] += h;
            dn[j] -= h;
            let (fu, fd) = (rhs(&up), rhs(&dn));
            for i in 0..18 {
                jac[(i, j)] = (fu[i] - fd[i]) / (2.0 * h);
            }
        }
        let ev = jac.complex_eigenvalues();
        for z in &want {
            let nearest = ev.iter().map(|e| (e - z).norm()).fold(f64::MAX, f64::min);
            assert!(nearest <= 1e-6 * z.norm(), "v = {v}: {z} not among {ev:?}");
        }
        // Every other eigenvalue is (numerically) zero.
        let away = ev.iter().filter(|e| e.norm() > 1e-3).count();
        assert_eq!(away, want.len(), "v = {v}: {ev:?}");
    }
}
