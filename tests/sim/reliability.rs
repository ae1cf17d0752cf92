//! Issue 21's simulation reproducers: each a scene or run that crashed,
//! gave a wrong answer or blamed the wrong input, and what it must do.

use std::path::Path;

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::Scene;
use hdot_sim::{Limits, Method, SimError, Step, integrate};

fn scene(text: &str) -> Result<Scene, SimError> {
    Scene::parse(text, Path::new("reliability.toml"))
}

/// Plans and runs a scene with the default choice.
fn simulate(s: &Scene, req: &Request) -> Result<run::Report, SimError> {
    let plan = run::plan(s, req)?;
    run::run(s, &plan, &mut Output::default())
}

/// Item 1: moments of 1e200 overflowed the elliptic closed form's
/// parameter to NaN, and the ascending Landen recursion never ended (a
/// stack overflow, whatever the method). A rate whose square underflows is
/// refused with a located error; moments of 1e200 with a rate f64 can
/// square run, by every method.
#[test]
fn huge_moments_do_not_overflow_the_stack() {
    let text = |h: &str| {
        format!(
            "name = \"big\"\nkind = \"free\"\nt_end = 1.0\n[[body]]\nprincipal_moments = [1e200, 2e200, 2.5e200]\n\
             mass = 1.0\n[initial]\nangular_momentum = {h}\n"
        )
    };
    // The reproducer: |ω| ~ 1e-200, whose square underflows, is refused
    // naming the field and its line.
    let err = scene(&text("[1.0, 0.2, 0.3]")).unwrap_err().to_string();
    assert!(
        err.contains("reliability.toml")
            && err.contains("initial.angular_momentum")
            && err.contains("line 8"),
        "{err}"
    );
    // Moments of 1e200 with |ω| ~ 1e-50: runs.
    let tiny = scene(&text("[1e150, 0.2e150, 0.3e150]")).unwrap();
    for method in [None, Some(Method::Rk4), Some(Method::Dop853)] {
        let req = Request {
            method,
            ..Request::default()
        };
        match simulate(&tiny, &req) {
            Ok(r) => assert!(r.final_state.iter().all(|v| v.is_finite())),
            Err(e) if method.is_none() => panic!("the default choice must run: {e}"),
            Err(e) => assert!(e.to_string().contains("reliability.toml"), "{e}"),
        }
    }
}

const SHAFT: &str = r#"
name = "shaft"
kind = "fixed-axis"
t_end = 2.0
[[body]]
shape = "disk"
mass = 2.0
radius = 0.1
[shaft]
bearings = [-0.1, 0.1]
[motor]
stall_torque = STALL
no_load_speed = 300.0
[initial]
rate = 10.0
"#;

/// Item 6: with a negative stall torque the motor law's ω coefficient is
/// negative, and the closed form took the constant-torque branch (17 off
/// DOP853). It must agree with a tight integration.
#[test]
fn fixed_axis_closed_form_with_a_negative_stall_torque() {
    // The last: a stiff friction (time constant I_z/c = 1e-4 s), whose
    // closed form's error estimate integrated with steps of a turn's time
    // and failed "unstable at this step size" (a hostile trial).
    let stiff = "bearings = [-0.1, 0.1]\nfriction = 100.0";
    for (stall, friction) in [("-0.5", ""), ("0.5", ""), ("0.5", stiff)] {
        let text = SHAFT.replace("STALL", stall);
        let text = match friction {
            "" => text,
            f => text.replace("bearings = [-0.1, 0.1]", f),
        };
        let s = scene(&text).unwrap();
        let closed = simulate(&s, &Request::default()).unwrap();
        assert_eq!(closed.plan.method, None, "a closed form");
        let tight = simulate(
            &s,
            &Request {
                method: Some(Method::Dop853),
                step: Some(Step::Tolerance(1e-13)),
                ..Request::default()
            },
        )
        .unwrap();
        for (x, y) in closed.final_state.iter().zip(&tight.final_state) {
            assert!(
                (x - y).abs() <= 1e-9 * (1.0 + y.abs()),
                "stall {stall}: closed {x} vs dop853 {y}"
            );
        }
    }
}

/// Item 10: an adaptive method over a valid, very short run (T = 1e-15)
/// reported "step size underflow".
#[test]
fn adaptive_methods_run_a_very_short_interval() {
    let s = scene(&SHAFT.replace("STALL", "0.5")).unwrap();
    for method in [Method::Dopri5, Method::Dop853] {
        let r = simulate(
            &s,
            &Request {
                method: Some(method),
                t_end: Some(1e-15),
                ..Request::default()
            },
        )
        .unwrap_or_else(|e| panic!("{method}: {e}"));
        assert!(r.error.is_some_and(|e| e <= 1e-12), "{method}");
    }
    // The integrator alone, on a short interval far from t = 0 as well.
    let shaft = match &s.kind {
        hdot_sim::scene::SceneKind::FixedAxis { shaft, .. } => *shaft,
        _ => unreachable!(),
    };
    let (y, _) = integrate(
        &shaft,
        Method::Dop853,
        Step::Tolerance(1e-8),
        0.0,
        [0.0, 10.0],
        1e-15,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap();
    assert!((y[0] - 1e-14).abs() <= 1e-28, "{y:?}");
}

/// Item 8: NaN, infinite or huge initial values name their field and the
/// file's line, not the end time.
#[test]
fn bad_initial_values_name_their_field_and_line() {
    let top = |initial: &str| {
        format!(
            "name = \"top\"\nkind = \"heavy-top\"\nt_end = 1.0\ng = [0.0, 0.0, -9.81]\n[[body]]\n\
             shape = \"disk\"\nmass = 1.0\nradius = 0.1\n[top]\nfixed_point = [0.0, 0.0, -0.1]\n\
             [initial]\n{initial}\n"
        )
    };
    let cases = [
        (
            top("steady_precession = { theta = 0.5, spin = nan }"),
            "initial.steady_precession.spin",
            "line 12",
        ),
        (
            SHAFT.replace("STALL", "0.5").replace("rate = 10.0", "rate = 1e308"),
            "initial.rate",
            "line 15",
        ),
        (
            "name = \"b\"\nkind = \"free\"\nt_end = 1.0\n[[body]]\nprincipal_moments = [1e-300, 2e-300, 2.5e-300]\n\
             mass = 1.0\n[initial]\nangular_momentum = [1.0, 0.2, 0.3]\n"
                .to_string(),
            "initial.angular_momentum",
            "line 8",
        ),
    ];
    for (text, field, line) in cases {
        let err = match scene(&text) {
            Err(e) => e,
            Ok(s) => simulate(&s, &Request::default()).expect_err(field),
        };
        let msg = err.to_string();
        assert!(msg.contains("reliability.toml"), "{msg}");
        assert!(msg.contains(field), "{field}: {msg}");
        assert!(msg.contains(line), "{field} at {line}: {msg}");
        assert!(!msg.contains("end time"), "blames the end time: {msg}");
    }
}

/// A body whose moments overflow once squared (a mass of 1e300) is
/// blamed, not the angular velocity that multiplies them.
#[test]
fn moments_beyond_range_blame_the_body() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/examples");
    let text = std::fs::read_to_string(root.join("sim-heavy-top.toml")).unwrap();
    let mass = text
        .lines()
        .find(|l| l.starts_with("mass = "))
        .expect("the example gives a mass");
    let text = text.replacen(mass, "mass = 1e300", 1);
    let msg = scene(&text).expect_err("must be refused").to_string();
    assert!(msg.contains("field `body`"), "{msg}");
    assert!(msg.contains("principal moments"), "{msg}");
    assert!(!msg.contains("angular_velocity"), "{msg}");
    // A pivot so far away that m |OG|² overflows: the pivot, at its line,
    // not the body's moments (NaN); a gravity beyond range: g, not its
    // direction (the message asked for the form it refused).
    let original = std::fs::read_to_string(root.join("sim-heavy-top.toml")).unwrap();
    for (from, to, field, says) in [
        (
            "fixed_point = [0.0, 0.0, -0.05]",
            "fixed_point = [0.0, 0.0, -1e300]",
            "field `top.fixed_point`: line 17:",
            "m |OG|²",
        ),
        (
            "g = [0.0, 0.0, -9.81]",
            "g = [0.0, 0.0, -1e308]",
            "field `g`: line 8:",
            "beyond the range",
        ),
    ] {
        assert!(original.contains(from), "the example changed: {from}");
        let msg = scene(&original.replace(from, to))
            .expect_err(to)
            .to_string();
        assert!(msg.contains(field) && msg.contains(says), "{to}: {msg}");
        assert!(
            !msg.contains("NaN") && !msg.contains("give g"),
            "{to}: {msg}"
        );
    }
}

/// The 1-based line of the first line of `text` containing `needle`.
fn line_with(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .expect("the needle is in the text")
        + 1
}

/// Item 8's leftovers: a value that is not finite in `[initial]` of a
/// fixed-axis, free or derived scene is named at its field and line.
#[test]
fn initial_values_that_are_not_finite_are_located() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/examples");
    let read = |name: &str| std::fs::read_to_string(root.join(name)).unwrap();
    let cases = [
        (
            read("sim-shaft-unbalanced.toml").replace("angle = 0.0", "angle = inf"),
            "angle = inf",
            "field `initial.angle`",
        ),
        (
            read("sim-shaft-unbalanced.toml").replace("rate = 0.0", "rate = nan"),
            "rate = nan",
            "field `initial.rate`",
        ),
        (
            read("sim-heavy-top.toml").replace(
                "angular_velocity = [0.0, 0.0, 60.0]",
                "angular_velocity = [0.0, nan, 60.0]",
            ),
            "angular_velocity = [0.0, nan",
            "field `initial.angular_velocity`",
        ),
        // Finite but beyond f64 once squared: the rates' own line.
        (
            read("sim-heavy-top.toml").replace(
                "angular_velocity = [0.0, 0.0, 60.0]",
                "angular_velocity = [0.0, 0.0, 1e300]",
            ),
            "angular_velocity = [0.0, 0.0, 1e300]",
            "field `initial.angular_velocity`",
        ),
        // The shaft's friction at its own field, not the motor's.
        (
            SHAFT.replace("STALL", "0.5").replace(
                "bearings = [-0.1, 0.1]",
                "bearings = [-0.1, 0.1]\nfriction = nan",
            ),
            "friction = nan",
            "field `shaft.friction`",
        ),
        (
            SHAFT.replace("STALL", "inf"),
            "stall_torque = inf",
            "field `motor.stall_torque`",
        ),
    ];
    for (text, needle, field) in cases {
        assert!(text.contains(needle), "the example changed: {needle}");
        let msg = scene(&text).expect_err("must be refused").to_string();
        let at = format!("{field}: line {}: ", line_with(&text, needle));
        assert!(msg.contains(&at), "`{msg}` lacks `{at}`");
    }
}

/// The numbers of a report line after `label`, as printed (separated by
/// commas, spaces, brackets and parentheses; words and units skipped).
fn printed_numbers(text: &str, label: &str) -> Vec<f64> {
    let line = text
        .lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no `{label}` line in\n{text}"));
    line[label.len()..]
        .split([',', ' ', '[', ']', '(', ')', '='])
        .filter_map(|w| w.parse::<f64>().ok())
        .collect()
}

/// `printed` is `values` to within `rel` of the largest of them: each
/// number kept its significant digits, however small the group.
fn assert_printed(printed: &[f64], values: &[f64], rel: f64) {
    assert_eq!(printed.len(), values.len(), "{printed:?} for {values:?}");
    let scale = values.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    assert!(scale > 0.0, "{values:?}");
    for (p, v) in printed.iter().zip(values) {
        assert!(
            (p - v).abs() <= rel * scale,
            "{p:e} printed for {v:e} ({printed:?})"
        );
    }
}

/// Item 7: the simulate text report printed fixed decimals — a free body
/// turning at |ω| ~ 1e-13 rad/s printed its state as `[1.000000000000,
/// 0.000000000000, …]`, a 1 mg shaft its reactions as `0.000000`. Each
/// group (attitude, rates, forces, moments) keeps its significant digits.
#[test]
fn small_values_print_significant_digits_in_the_report() {
    let slow = scene(
        "name = \"slow free body\"\nkind = \"free\"\nt_end = 1.0\n[[body]]\n\
         principal_moments = [0.6, 0.8, 1.0]\nmass = 1.0\n[initial]\n\
         attitude = [1.0, 0.0, 0.0, 0.0]\nangular_momentum = [1e-13, 2e-14, 3e-14]\n",
    )
    .expect("scene");
    let r = simulate(&slow, &Request::default()).expect("run");
    let printed = printed_numbers(&r.to_string(), "state at T:");
    let y = &r.final_state;
    assert_eq!(printed.len(), 7, "{r}");
    // 12 significant digits: within 1e-11 of each group's largest — the
    // quaternion's scalar part, its vector part (a rotation of ~1e-13 rad:
    // components ~1e-13 beside a scalar part of 1) and the rates.
    assert_printed(&printed[..1], &y[..1], 1e-11);
    assert_printed(&printed[1..4], &y[1..4], 1e-11);
    assert_printed(&printed[4..], &y[4..], 1e-11);
    assert!(printed[1..].iter().all(|w| *w != 0.0), "{r}");

    // A shaft of 1 mg with a 1 µg point off its axis, turning at 1e-3
    // rad/s: its bearing reactions are of order 1e-18 N.
    let shaft = scene(
        "name = \"tiny shaft\"\nkind = \"fixed-axis\"\nt_end = 1.0\n[shaft]\n\
         bearings = [-0.15, 0.15]\nfriction = 0.0\n[[body]]\nshape = \"disk\"\nmass = 1e-6\n\
         radius = 1e-3\n[[body]]\nshape = \"point\"\nmass = 1e-9\nposition = [1e-3, 0.0, 1e-3]\n\
         [initial]\nangle = 0.0\nrate = 1e-3\n[motor]\nstall_torque = 0.0\nno_load_speed = 300.0\n",
    )
    .expect("scene");
    let r = simulate(&shaft, &Request::default()).expect("run");
    let reactions = r.reactions.expect("reactions");
    let printed = printed_numbers(&r.to_string(), "reactions:");
    assert_eq!(printed.len(), 7, "{r}");
    // 6 significant digits: within 1e-5 of the forces' and the moments'
    // largest.
    assert_printed(&printed[..4], &reactions[..4], 1e-5);
    assert!(printed[..4].iter().any(|f| *f != 0.0), "{r}");
    if reactions[4..].iter().any(|m| *m != 0.0) {
        assert_printed(&printed[4..], &reactions[4..], 1e-5);
    }
}
