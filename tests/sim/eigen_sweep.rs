//! stability/: the eigenvalue sweep of linearised equations M q̈ + C q̇ +
//! K q = 0 — the sleeping top's threshold against its closed form, the
//! eigenvalues against theirs, strict stability of a damped oscillator,
//! columns that follow one eigenvalue, and located errors.

use std::path::PathBuf;

use hdot_sim::nalgebra::Complex;
use hdot_sim::stability::{Edge, StabilityScene, Sweep, sweep};
use hdot_tests::repo_root;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn examples() -> PathBuf {
    repo_root().join("docs/examples")
}

/// A stability scene over the sleeping top of docs/examples with these
/// constants and sweep.
fn top_scene(i: f64, ip: f64, m: f64, l: f64, to: f64, count: usize) -> String {
    format!(
        r#"name = "top"
kind = "stability"
[derivation]
file = "sleeping-top"
mass = "M"
damping = "C"
stiffness = "K"
[constants]
I = {i:?}
Ip = {ip:?}
m = {m:?}
g = 9.81
l = {l:?}
[sweep]
parameter = "omega"
from = 0.0
to = {to:?}
count = {count}
"#
    )
}

/// Parses scene text as if it were a file in docs/examples (so that its
/// derivation is found in docs/examples/derivations).
fn parse(text: &str) -> Result<StabilityScene, hdot_sim::SimError> {
    let file = examples().join("test-scene.toml");
    StabilityScene::parse_with(text, &file, &|name| {
        hdot_sim::scene::resolve_near(&file, name)
    })
}

fn run(text: &str) -> Sweep {
    let scene = parse(text).unwrap();
    sweep(&scene, &mut |_, _| {}).unwrap()
}

/// The threshold I² ω² = 4 I′ m g l, found by the sweep and its bisection,
/// against the closed form to 1e-8 (relative) on seeded random tops; no
/// real part is ever negative (the motion is conservative), and above the
/// threshold none is positive up to the sweep's end.
#[test]
fn the_sleeping_top_threshold_is_the_closed_form() {
    let mut rng = ChaCha8Rng::seed_from_u64(24);
    for _ in 0..5 {
        let (i, ip, m, l): (f64, f64, f64, f64) = (
            rng.gen_range(0.005..0.05),
            rng.gen_range(0.02..0.2),
            rng.gen_range(0.2..3.0),
            rng.gen_range(0.02..0.3),
        );
        let want = 2.0 * (ip * m * 9.81 * l).sqrt() / i;
        let s = run(&top_scene(i, ip, m, l, 3.0 * want, 301));
        assert!(s.stable.is_empty(), "{:?}", s.stable);
        assert_eq!(s.not_unstable.len(), 1, "{:?}", s.not_unstable);
        let iv = s.not_unstable[0];
        assert!(
            (iv.lo - want).abs() <= 1e-8 * want,
            "threshold {} against {want}",
            iv.lo
        );
        let Edge::Boundary { half_width } = iv.lo_edge else {
            panic!("a refined boundary");
        };
        assert!(half_width <= 1e-10 * want);
        assert_eq!((iv.hi, iv.hi_edge), (3.0 * want, Edge::SweepEnd));
    }
}

/// At every value the eigenvalues are the closed form's: below the
/// threshold λ = ±(Iω/2I′) i ± √(mgl/I′ − (Iω/2I′)²), above it
/// λ = i (±Iω ± √(I²ω² − 4I′mgl)) / 2I′.
#[test]
fn the_sleeping_top_eigenvalues_are_the_closed_form() {
    let (i, ip, m, g, l) = (0.02, 0.05, 1.5, 9.81, 0.1);
    let s = run(&top_scene(i, ip, m, l, 200.0, 101));
    for (&w, ev) in s.values.iter().zip(&s.eigenvalues) {
        let h = i * w / (2.0 * ip);
        let k = m * g * l / ip;
        let d = h * h - k;
        let mut want: Vec<Complex<f64>> = Vec::new();
        for s1 in [1.0, -1.0] {
            for s2 in [1.0, -1.0] {
                want.push(if d < 0.0 {
                    Complex::new(s2 * (-d).sqrt(), s1 * h)
                } else {
                    Complex::new(0.0, s1 * h + s2 * d.sqrt())
                });
            }
        }
        // The scale of the eigenvalues; near the double root the error of
        // a defective eigenvalue is √ε times it.
        let scale = h.abs() + k.sqrt();
        let tol = if d.abs() < 1e-3 * k {
            1e-6 * scale
        } else {
            1e-10 * scale
        };
        for z in &want {
            let nearest = ev.iter().map(|e| (e - z).norm()).fold(f64::MAX, f64::min);
            assert!(nearest <= tol, "omega = {w}: {z} not among {ev:?}");
        }
    }
}

/// A damped oscillator m ẍ + c ẋ + (k − v) x = 0 swept in v: every real
/// part is negative exactly for v < k (a real eigenvalue crossing zero),
/// found to 1e-8; swept in c from −1 to 1, stable for c > 0 (a complex
/// pair crossing the imaginary axis).
#[test]
fn a_damped_oscillator_is_stable_where_the_closed_form_says() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("oscillator.toml"),
        r#"title = "A damped oscillator"
source = "written for the test"
[symbols]
constants = ["m", "c", "k", "v"]
time = ["x"]
[[step]]
name = "eq"
value = "list(m*x'' + c*x' + (k - v)*x)"
[[step]]
name = "M"
value = "jacobian(eq, [x''])"
[[step]]
name = "C"
value = "jacobian(eq, [x'])"
[[step]]
name = "K"
value = "jacobian(eq, [x])"
"#,
    )
    .unwrap();
    let scene = |parameter: &str, constants: &str, from: f64, to: f64| {
        let file = dir.path().join("scene.toml");
        let text = format!(
            "name = \"oscillator\"\nkind = \"stability\"\n[derivation]\nfile = \"oscillator.toml\"\n\
             mass = \"M\"\ndamping = \"C\"\nstiffness = \"K\"\n[constants]\n{constants}\n\
             [sweep]\nparameter = \"{parameter}\"\nfrom = {from:?}\nto = {to:?}\ncount = 97\n"
        );
        let s =
            StabilityScene::parse_with(&text, &file, &|n| hdot_sim::scene::resolve_near(&file, n))
                .unwrap();
        sweep(&s, &mut |_, _| {}).unwrap()
    };
    let k = std::f64::consts::E;
    let s = scene("v", &format!("m = 0.7\nc = 0.3\nk = {k:?}"), 0.0, 5.0);
    assert_eq!(s.stable.len(), 1);
    let iv = s.stable[0];
    assert_eq!((iv.lo, iv.lo_edge), (0.0, Edge::SweepEnd));
    assert!((iv.hi - k).abs() <= 1e-8 * k, "{} against {k}", iv.hi);
    let s = scene("c", "m = 0.7\nk = 2.0\nv = 0.5", -1.0, 1.0);
    assert_eq!(s.stable.len(), 1);
    let iv = s.stable[0];
    assert!(iv.lo.abs() <= 1e-8, "{}", iv.lo);
    assert_eq!((iv.hi, iv.hi_edge), (1.0, Edge::SweepEnd));
    // Without damping the pair sits on the axis at c = 0: not unstable
    // there and for c > 0, unstable for c < 0.
    assert_eq!(s.not_unstable.len(), 1);
    assert!(s.not_unstable[0].lo.abs() <= 1e-8);
}

/// Columns follow eigenvalues: above the threshold each column keeps its
/// branch (the fast and slow precession, each sign), so the column with
/// the largest imaginary part is one column throughout.
#[test]
fn each_column_follows_one_eigenvalue() {
    let (i, ip, m, l): (f64, f64, f64, f64) = (0.02, 0.05, 1.5, 0.1);
    let want = 2.0 * (ip * m * 9.81 * l).sqrt() / i;
    let s = run(&top_scene(i, ip, m, l, 8.0 * want, 1000));
    let argmax = |ev: &Vec<Complex<f64>>, f: &dyn Fn(f64) -> f64| {
        (0..ev.len())
            .max_by(|&a, &b| f(ev[a].im).total_cmp(&f(ev[b].im)))
            .unwrap()
    };
    let above: Vec<&Vec<Complex<f64>>> = s
        .values
        .iter()
        .zip(&s.eigenvalues)
        .filter(|(w, _)| **w > 1.05 * want)
        .map(|(_, ev)| ev)
        .collect();
    assert!(above.len() > 800);
    for f in [&|x: f64| x, &|x: f64| -x] as [&dyn Fn(f64) -> f64; 2] {
        let first = argmax(above[0], f);
        assert!(above.iter().all(|ev| argmax(ev, f) == first));
    }
    // And each column changes little from one value to the next there.
    let step = s.values[1] - s.values[0];
    let slope = i / ip; // |dλ/dω| of the fast branch
    for w in above.windows(2) {
        for (a, b) in w[0].iter().zip(w[1]) {
            assert!((b - a).norm() <= 2.0 * slope * step);
        }
    }
}

/// The example scene runs: its threshold is the closed form of the
/// constants it gives.
#[test]
fn the_example_scene_finds_its_threshold() {
    let path = examples().join("stability-sleeping-top.toml");
    let scene = StabilityScene::from_file(&path).unwrap();
    let s = sweep(&scene, &mut |_, _| {}).unwrap();
    let want = 2.0 * (0.05f64 * 1.5 * 9.81 * 0.1).sqrt() / 0.02;
    assert!((s.not_unstable[0].lo - want).abs() <= 1e-8 * want);
    assert_eq!(s.eigenvalues.len(), scene.count);
}

/// Bad input names the field and its line; nothing panics.
#[test]
fn bad_scenes_name_the_field_and_line() {
    let good = top_scene(0.02, 0.05, 1.5, 0.1, 200.0, 100);
    let cases: Vec<(String, &str, &str)> = vec![
        (
            good.replace("parameter = \"omega\"", "parameter = \"theta\""),
            "sweep.parameter",
            "line 15",
        ),
        (
            good.replace("l = 0.1", "l = 0.1\nomega = 3.0"),
            "constants.omega",
            "swept parameter",
        ),
        (
            good.replace("l = 0.1\n", ""),
            "derivation.stiffness",
            "`l` has no value",
        ),
        (
            good.replace("mass = \"M\"", "mass = \"eqs\""),
            "derivation.mass",
            "not a square matrix",
        ),
        (
            good.replace("mass = \"M\"", "mass = \"Q\""),
            "derivation.mass",
            "no step named `Q`",
        ),
        (
            good.replace("count = 100", "count = 1"),
            "sweep.count",
            "line 18",
        ),
        (
            good.replace("to = 200.0", "to = -1.0"),
            "sweep.to",
            "greater than",
        ),
        (
            good.replace("kind = \"stability\"", "kind = \"derived\""),
            "kind",
            "line 2",
        ),
        (
            good.replace("Ip = 0.05", "Ip = nan"),
            "constants.Ip",
            "finite",
        ),
        (
            good.replace("Ip = 0.05", "Ip = 0.05\nq = 1.0"),
            "constants.q",
            "not a constant",
        ),
        (
            good.replace("file = \"sleeping-top\"", "file = \"missing\""),
            "derivation.file",
            "no derivation",
        ),
    ];
    for (text, field, says) in cases {
        let e = parse(&text).unwrap_err().to_string();
        assert!(
            e.contains(&format!("`{field}`")) && e.contains(says),
            "{field}: {e}"
        );
    }
    // A matrix that depends on the state is refused, naming the entry.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("d.toml"),
        "title = \"t\"\nsource = \"s\"\n[symbols]\nconstants = [\"k\"]\ntime = [\"x\"]\n\
         [[step]]\nname = \"K\"\nvalue = \"jacobian(list(k*x*x' + x''), [x])\"\n\
         [[step]]\nname = \"M\"\nvalue = \"jacobian(list(x''), [x''])\"\n",
    )
    .unwrap();
    let file = dir.path().join("s.toml");
    let text = "name = \"s\"\nkind = \"stability\"\n[derivation]\nfile = \"d.toml\"\nmass = \"M\"\n\
                stiffness = \"K\"\n[sweep]\nparameter = \"k\"\nfrom = 0.0\nto = 1.0\ncount = 3\n";
    let e = StabilityScene::parse_with(text, &file, &|n| hdot_sim::scene::resolve_near(&file, n))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`derivation.stiffness`") && e.contains("line 6") && e.contains("entry (1, 1)"),
        "{e}"
    );
    // A mass matrix singular at a value of the sweep: the error names it.
    let singular = good.replace("Ip = 0.05", "Ip = 0.0");
    let s = parse(&singular).unwrap();
    let e = sweep(&s, &mut |_, _| {}).unwrap_err().to_string();
    assert!(
        e.contains("`sweep`") && e.contains("omega = 0") && e.contains("singular"),
        "{e}"
    );
}

/// Whatever finite constants a scene gives — zero, tiny, huge, negative —
/// the sweep returns eigenvalues that are all finite, or an error naming
/// the value; it never panics.
#[test]
fn extreme_constants_give_finite_eigenvalues_or_an_error() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let pick = |rng: &mut ChaCha8Rng| -> f64 {
        let v = [0.0, 1e-300, 1e300, 1e-30, 1e30, 1.0, 0.3][rng.gen_range(0..7)];
        if rng.gen_bool(0.3) { -v } else { v }
    };
    for _ in 0..60 {
        let (i, ip, m, l) = (
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
        );
        let text = top_scene(i, ip, m, l, 1e3, 7);
        let Ok(scene) = parse(&text) else { continue };
        match sweep(&scene, &mut |_, _| {}) {
            Ok(s) => assert!(
                s.eigenvalues
                    .iter()
                    .flatten()
                    .all(|z| z.re.is_finite() && z.im.is_finite()),
                "{text}"
            ),
            Err(e) => assert!(e.to_string().contains("at omega = "), "{e}"),
        }
    }
}

/// A cyclic coordinate (the yaw of a hoop rolling upright, in no
/// equation) gives an exact zero eigenvalue, double with its conserved
/// momentum: "not unstable" is one interval on each side, |Ω| above the
/// closed form Ω² = m g r J / (I (I + m r²)) to 1e-8 — not fragments
/// broken wherever round-off split the double zero (a scene written for
/// this test).
#[test]
fn a_cyclic_coordinate_is_neutral_not_fragments() {
    let (m, r, i, j, g) = (1.0_f64, 0.5_f64, 0.25_f64, 0.125_f64, 9.81_f64);
    let text = format!(
        r#"name = "hoop"
kind = "stability"
[derivation]
file = "hoop-upright.toml"
mass = "ML"
damping = "CL"
stiffness = "KqL"
[constants]
m = {m:?}
r = {r:?}
I = {i:?}
J = {j:?}
g = {g:?}
[sweep]
parameter = "Omega"
from = -10.0
to = 10.0
count = 1001
"#
    );
    let file = hdot_tests::repo_root().join("tests/sim/cyclic/scene.toml");
    let scene = StabilityScene::parse_with(&text, &file, &|name| {
        hdot_sim::scene::resolve_near(&file, name)
    })
    .unwrap();
    let s = sweep(&scene, &mut |_, _| {}).unwrap();
    let edge = (m * g * r * j / (i * (i + m * r * r))).sqrt();
    assert_eq!(s.not_unstable.len(), 2, "{:?}", s.not_unstable);
    let (lo, hi) = (&s.not_unstable[0], &s.not_unstable[1]);
    assert_eq!((lo.lo_edge, hi.hi_edge), (Edge::SweepEnd, Edge::SweepEnd));
    assert!((lo.hi + edge).abs() < 1e-8 * edge, "{} vs {}", lo.hi, -edge);
    assert!((hi.lo - edge).abs() < 1e-8 * edge, "{} vs {edge}", hi.lo);
    // The exact zero is reported as exactly zero at every value.
    for ev in &s.eigenvalues {
        assert!(ev.iter().any(|z| z.re == 0.0 && z.im == 0.0));
    }
}
