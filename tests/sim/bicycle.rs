//! The Whipple bicycle: derivations/bicycle.toml through the stability
//! scene docs/examples/stability-bicycle.toml against the published
//! benchmark (Meijaard, Papadopoulos, Ruina & Schwab, Proc. R. Soc. A 463
//! (2007)): M, C₁, K₀ and K₂ (§5 / appendix A), the eigenvalues at 0 and
//! 5 m/s and the weave and capsize speeds (Table 2). The published numbers
//! are expectations here only; the derivation derives the matrices.

use hdot_sim::nalgebra::Complex;
use hdot_sim::stability::{Edge, StabilityScene, spectrum, sweep};
use hdot_tests::{WHIPPLE_EIGENVALUES, repo_root};

const G: f64 = 9.81;

fn scene() -> StabilityScene {
    StabilityScene::from_file(&repo_root().join("docs/examples/stability-bicycle.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// M, C and K (row-major, 2 × 2 each) at speed `v`.
fn matrices(s: &StabilityScene, v: f64) -> [[f64; 4]; 3] {
    let mut out = vec![0.0; 12];
    s.matrices.eval(v, &mut Vec::new(), &mut out);
    std::array::from_fn(|k| std::array::from_fn(|i| out[4 * k + i]))
}

/// Each entry within 1e-12 of the matrix's largest published entry.
fn assert_close(name: &str, got: [f64; 4], want: [f64; 4]) {
    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= 1e-12 * scale,
            "{name}[{}][{}] = {g:e}, published {w:e}",
            i / 2,
            i % 2
        );
    }
}

#[test]
fn the_bicycle_matrices_are_the_benchmark() {
    let s = scene();
    assert_eq!(s.matrices.dof(), 2);
    let [m0, c0, k0] = matrices(&s, 0.0);
    let [m1, c1, k1] = matrices(&s, 1.0);
    let [_, c2, k2] = matrices(&s, 2.0);
    assert_eq!(m0, m1, "M does not depend on the speed");
    assert!(c0.iter().all(|x| *x == 0.0), "C vanishes at rest: {c0:?}");
    for i in 0..4 {
        // C = v C₁ and K = g K₀ + v² K₂ exactly in form: check the shape.
        assert!((c2[i] - 2.0 * c1[i]).abs() <= 1e-12 * c1[i].abs().max(1.0));
        let k2v = k2[i] - k0[i];
        assert!((k2v - 4.0 * (k1[i] - k0[i])).abs() <= 1e-10 * k2v.abs().max(1.0));
    }
    assert_close(
        "M",
        m0,
        [
            80.81722,
            2.31941332208709,
            2.31941332208709,
            0.29784188199686,
        ],
    );
    assert_close(
        "C1",
        c1,
        [0.0, 33.86641391492494, -0.85035641456978, 1.68540397397560],
    );
    assert_close(
        "K0",
        k0.map(|x| x / G),
        [
            -80.95,
            -2.59951685249872,
            -2.59951685249872,
            -0.80329488458618,
        ],
    );
    let k2: [f64; 4] = std::array::from_fn(|i| k1[i] - k0[i]);
    assert_close("K2", k2, [0.0, 76.59734589573222, 0.0, 2.65431523794604]);
}

/// The eigenvalues at rest and at 5 m/s, Table 2's digits.
#[test]
fn the_bicycle_eigenvalues_are_the_benchmark() {
    let s = scene();
    for &(v, table) in &WHIPPLE_EIGENVALUES {
        let want: Vec<Complex<f64>> = table.iter().map(|&(re, im)| Complex::new(re, im)).collect();
        let (ev, _) = spectrum(&s.matrices, v, &mut Vec::new()).unwrap();
        for z in &want {
            let nearest = ev.iter().map(|e| (e - z).norm()).fold(f64::MAX, f64::min);
            // The published values carry 14 to 15 significant digits.
            assert!(
                nearest <= 1e-11 * z.norm().max(1.0),
                "v = {v}: {z} not among {ev:?}"
            );
        }
    }
}

/// Self-stable from the weave speed to the capsize speed (Table 2:
/// 4.292382536341 and 6.024262015388 m/s), found by the sweep to 1e-8.
#[test]
fn the_bicycle_is_self_stable_between_weave_and_capsize() {
    let s = scene();
    let out = sweep(&s, &mut |_, _| {}).unwrap();
    assert_eq!(out.stable.len(), 1, "{:?}", out.stable);
    let iv = out.stable[0];
    let (weave, capsize) = (4.29238253634111, 6.02426201538837);
    assert!(
        (iv.lo - weave).abs() <= 1e-8 * weave,
        "weave speed {}",
        iv.lo
    );
    assert!(
        (iv.hi - capsize).abs() <= 1e-8 * capsize,
        "capsize speed {}",
        iv.hi
    );
    assert!(matches!(iv.lo_edge, Edge::Boundary { .. }));
    assert!(matches!(iv.hi_edge, Edge::Boundary { .. }));
}

/// Lean and steer (φ, δ) of the linearized equations M q̈ + v C₁ q̇ +
/// (g K₀ + v² K₂) q = 0 at speed `v` from q = 0, q̇ = (φ̇₀, 0), at time
/// `t_end` (classical Runge–Kutta, 2 × 10⁴ steps per second: error far below
/// the comparison's tolerance).
fn linear_lean_steer(s: &StabilityScene, v: f64, lean_rate: f64, t_end: f64) -> [f64; 2] {
    let [m, c, k] = matrices(s, v);
    let det = m[0] * m[3] - m[1] * m[2];
    let accel = |x: [f64; 4]| -> [f64; 4] {
        let (q, qd) = ([x[0], x[1]], [x[2], x[3]]);
        let r = [
            -(c[0] * qd[0] + c[1] * qd[1] + k[0] * q[0] + k[1] * q[1]),
            -(c[2] * qd[0] + c[3] * qd[1] + k[2] * q[0] + k[3] * q[1]),
        ];
        [
            qd[0],
            qd[1],
            (m[3] * r[0] - m[1] * r[1]) / det,
            (m[0] * r[1] - m[2] * r[0]) / det,
        ]
    };
    let n = (t_end * 2e4).round() as usize;
    let h = t_end / n as f64;
    let mut x = [0.0, 0.0, lean_rate, 0.0];
    let add = |x: [f64; 4], d: [f64; 4], a: f64| std::array::from_fn(|i| x[i] + a * d[i]);
    for _ in 0..n {
        let k1 = accel(x);
        let k2 = accel(add(x, k1, h / 2.0));
        let k3 = accel(add(x, k2, h / 2.0));
        let k4 = accel(add(x, k3, h));
        x = std::array::from_fn(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    [x[0], x[1]]
}

/// The bundled scene of the nonlinear bicycle.
const NONLINEAR: &str = "docs/examples/sim-bicycle-nonlinear.toml";

/// The nonlinear scene's four `[[body]]` tables bind the derivation's mass
/// properties to the benchmark's (Table 1), as the linear scene gives them
/// under `[constants]`: every constant of the linear scene is the nonlinear
/// scene's, given or bound, to round-off.
#[test]
fn the_nonlinear_bicycle_s_bodies_are_the_benchmark_s() {
    use hdot_sim::scene::Scene;
    let s = Scene::from_file(&repo_root().join(NONLINEAR)).unwrap_or_else(|e| panic!("{e}"));
    let bound = &s.derivation().expect("a derived scene").spec.constants;
    let text =
        std::fs::read_to_string(repo_root().join("docs/examples/stability-bicycle.toml")).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    let linear = table["constants"].as_table().expect("[constants]");
    // Every mass property of the four bodies, and the geometry besides.
    assert!(linear.len() >= 26, "{} constants", linear.len());
    let text = std::fs::read_to_string(repo_root().join(NONLINEAR)).unwrap();
    for (name, want) in linear {
        let want = want.as_float().unwrap();
        let got = *bound
            .get(name)
            .unwrap_or_else(|| panic!("`{name}` is neither given nor bound"));
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{name}: bound {got:e}, the benchmark's {want:e}"
        );
        // The masses and inertias come from the tables, not constants.
        if name.starts_with("m_") || name.starts_with("I_") {
            assert!(
                !text.contains(&format!("\n{name} =")),
                "{name} given as a constant"
            );
        }
    }
}

/// The nonlinear scene's text with each `from` replaced by its `to`, read:
/// the error's text, which must name the scene and `where` (the table's
/// line and field).
fn refused(edits: &[(&str, &str)], want: &[&str]) {
    use hdot_sim::scene::Scene;
    let path = repo_root().join(NONLINEAR);
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "the scene has no `{from}`");
        text = text.replace(from, to);
    }
    let e = Scene::parse(&text, &path).expect_err("refused").to_string();
    assert!(e.contains("sim-bicycle-nonlinear.toml"), "{e}");
    for w in want {
        assert!(e.contains(w), "`{w}` not in: {e}");
    }
}

/// Bad body tables of the bicycle's scene, each refused at its table: a
/// body with no table whose symbols are no constants either, an `of` the
/// derivation does not declare, a table without `of`, an inertia tensor
/// that is not 3 × 3 or not a body's, and two ways of giving one part.
#[test]
fn bad_bicycle_body_tables_are_refused_at_their_table() {
    let front_wheel = "[[body]]\nof = \"front_wheel\"\n";
    refused(
        &[(front_wheel, "[[body]]\n")],
        &["body[3]", "several bodies", "of = "],
    );
    let wheel = "principal_moments = [0.1405, 0.28, 0.1405]\nmass = 3.0\n";
    refused(
        &[(front_wheel, ""), (wheel, "")],
        &[
            "body[0].of",
            "`front_wheel`",
            "I_Fxx, I_Fyy, m_F",
            "[constants]",
        ],
    );
    refused(
        &[("of = \"front_wheel\"", "of = \"front_whee\"")],
        &["body[3].of", "no body `front_whee`", "`front_wheel`"],
    );
    let tensor = "inertia = [[9.2, 0.0, 2.4], [0.0, 11.0, 0.0], [2.4, 0.0, 2.8]]";
    refused(
        &[(tensor, "inertia = [[9.2, 0.0, 2.4], [0.0, 11.0, 0.0]]")],
        &["body[1].inertia", "3 rows of 3"],
    );
    refused(
        &[(
            tensor,
            "inertia = [[9.2, 0.0, 2.4], [0.0, 11.0, 0.0], [2.4, 0.0, 20.8]]",
        )],
        &["body[1].inertia"],
    );
    refused(
        &[(
            tensor,
            &format!("{tensor}\nshape = \"sphere\"\nradius = 0.3"),
        )],
        &["body[1].inertia", "not several"],
    );
}

/// The nonlinear bicycle (docs/examples/sim-bicycle-nonlinear.toml: the
/// multiplier form of derivations in derivations/
/// bicycle-nonlinear.toml, both contacts exact) simulated from upright
/// straight running with a small lean rate follows its linearization: at
/// 5 m/s, inside the self-stable range, the lean decays; at 2 m/s, below the
/// weave speed, it grows — and lean and steer agree with the linear
/// equations' solution to the size of the neglected second-order terms.
#[test]
fn the_nonlinear_bicycle_decays_at_5_and_grows_at_2_m_per_s() {
    use hdot_sim::Step;
    use hdot_sim::run::{self, Output, Request};
    use hdot_sim::scene::Scene;
    let linear = scene();
    let path = repo_root().join(NONLINEAR);
    let text = std::fs::read_to_string(&path).unwrap();
    // A lean rate small enough that the second-order terms (relative size
    // ~ the lean-steer amplitude, below 1e-4 here) stay under the tolerance.
    let lean_rate = 1e-5;
    for (v, t_end, grows) in [(5.0, 5.0, false), (2.0, 3.0, true)] {
        let mut edited = text.clone();
        for (from, to) in [
            ("u_4 = 0.01", format!("u_4 = {lean_rate:e}")),
            ("u_6 = -16.666666666666668", format!("u_6 = {:e}", -v / 0.3)),
            ("t_end = 5.0", format!("t_end = {t_end:e}")),
        ] {
            assert!(edited.contains(from), "the scene sets `{from}`");
            edited = edited.replace(from, &to);
        }
        let s = Scene::parse(&edited, &path).unwrap_or_else(|e| panic!("{e}"));
        let req = Request {
            step: Some(Step::Tolerance(1e-11)),
            ..Request::default()
        };
        let plan = run::plan(&s, &req).unwrap_or_else(|e| panic!("{e}"));
        let r = run::run(&s, &plan, &mut Output::default()).unwrap_or_else(|e| panic!("{e}"));
        let at = |name: &str| {
            let i = r.state_names.iter().position(|n| n == name).unwrap();
            r.final_state[i]
        };
        let got = [at("phi"), at("delta")];
        let want = linear_lean_steer(&linear, v, lean_rate, t_end);
        let scale = want[0].abs().max(want[1].abs());
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= 1e-3 * scale,
                "v = {v}: nonlinear {got:?}, linear {want:?}"
            );
        }
        let lean = at("u_4").abs().max(at("phi").abs());
        if grows {
            assert!(
                lean > 10.0 * lean_rate,
                "v = {v}: lean {lean:e} did not grow"
            );
        } else {
            assert!(
                lean < 0.1 * lean_rate,
                "v = {v}: lean {lean:e} did not decay"
            );
        }
        assert!(
            r.drifts.iter().any(|d| d.name == "E"),
            "the energy's drift is reported"
        );
        let drift = r.drifts.iter().map(|d| d.relative).fold(0.0, f64::max);
        assert!(drift < 1e-8, "v = {v}: energy drift {drift:e}");
        // The velocity constraints: held to round-off after each step's
        // solve of the dependent speeds, which corrected a drift the
        // steps left (of the order of the tolerance, not zero).
        let vc = r
            .velocity_constraints
            .as_ref()
            .expect("max |A_c u| reported");
        assert_eq!(vc.dependent, ["u_1", "u_2", "u_3", "u_5", "u_8", "u_9"]);
        assert!(
            vc.max_residual <= 1e-13 * v,
            "v = {v}: max |A_c u| = {:e}",
            vc.max_residual
        );
        assert!(
            vc.max_correction > 0.0 && vc.max_correction <= 1e-8 * v,
            "v = {v}: largest correction {:e}",
            vc.max_correction
        );
        let text = r.to_string();
        assert!(
            text.contains("max |A_c u| = ") && text.contains("max |f(q)| = "),
            "{text}"
        );
    }
}
