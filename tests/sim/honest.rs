//! Issue 11, items 2 and 5: every report's error is a measurement or an
//! estimate (never an assumed 0), closed forms are checked, and non-finite
//! inputs and results never pass.

use std::path::Path;

use hdot_sim::SimError;
use hdot_sim::run::{self, Model, Output, Request};
use hdot_sim::scene::Scene;

fn scene(body: &str, initial: &str, t_end: f64) -> Scene {
    let text = format!(
        "name = \"test\"\nkind = \"free\"\nt_end = {t_end:e}\n[[body]]\n{body}\n[initial]\n{initial}\n"
    );
    Scene::parse(&text, Path::new("test.toml")).unwrap()
}

fn run_default(s: &Scene, req: Request) -> run::Report {
    let plan = run::plan(s, &req).unwrap();
    run::run(s, &plan, &mut Output::default()).unwrap()
}

#[test]
fn a_closed_form_reports_an_estimate_and_check_agrees_with_it() {
    let s = scene(
        "principal_moments = [0.6, 0.8, 1.0]\nmass = 1.0",
        "angular_velocity = [3.0, 0.5, -0.9]",
        50.0,
    );
    let r = run_default(
        &s,
        Request {
            check: true,
            ..Request::default()
        },
    );
    assert_eq!(r.plan.model, Model::named("elliptic").unwrap());
    let e = r
        .error
        .expect("a closed-form run reports an error estimate");
    assert!(r.error_basis.starts_with("estimated"), "{}", r.error_basis);
    assert!(e > 0.0 && e < 1e-9, "estimate {e:e}");
    let c = r.check.clone().expect("--check compares with DOP853");
    // DOP853 at tol 1e-13 over 50 time units is good to ~1e-10 here.
    assert!(c.difference < 1e-9, "check {:e}", c.difference);
    let text = r.to_string();
    assert!(!text.contains("this is the reference"), "{text}");
    assert!(
        text.contains("error at T:") && text.contains("check:"),
        "{text}"
    );
}

#[test]
fn the_estimate_sees_a_wrong_closed_form() {
    use hdot_sim::exact::TorqueFree;
    use hdot_sim::nalgebra::{UnitQuaternion, Vector3};
    use hdot_sim::systems::FreeBody;
    use hdot_sim::systems::free::{pack, state_distance};
    let i = [0.6, 0.8, 1.0];
    let (q0, w0) = (UnitQuaternion::identity(), Vector3::new(3.0, 0.5, -0.9));
    let body = FreeBody {
        moments: i,
        gravity: None,
    };
    let y0 = pack(&q0, &w0);
    let estimate = |moments: [f64; 3]| {
        let exact = TorqueFree::new(moments, q0, w0).unwrap();
        run::closed_form_estimate(
            &body,
            &|t| exact.state(t),
            &y0,
            20.0,
            1.0 / w0.norm(),
            16,
            state_distance,
        )
        .unwrap()
    };
    let right = estimate(i);
    // The closed form of a body whose moment differs by 1e-7: it starts
    // right and drifts; the estimate must see it, and bound the truth.
    let wrong_i = [0.6, 0.8, 1.0 + 1e-7];
    let wrong = estimate(wrong_i);
    let truth = state_distance(
        &TorqueFree::new(wrong_i, q0, w0).unwrap().state(20.0),
        &TorqueFree::new(i, q0, w0).unwrap().state(20.0),
    );
    assert!(right < 1e-11, "right closed form: {right:e}");
    assert!(
        wrong > 1e3 * right && wrong >= 0.3 * truth,
        "estimate {wrong:e}, truth {truth:e}"
    );
}

#[test]
fn a_spin_1e_12_off_the_intermediate_axis_gets_a_finite_flipping_exact_run() {
    // Issue 11: this prism got a NaN attitude and an unchanged ω at T = 1000.
    let s = scene(
        "shape = \"prism\"\nmass = 1.0\na = 0.3\nb = 0.2\nc = 0.1",
        "angular_velocity = [1e-12, 10.0, 0.0]",
        1000.0,
    );
    let r = run_default(&s, Request::default());
    assert_eq!(
        r.plan.model,
        Model::named("elliptic").unwrap(),
        "{}",
        r.plan.reason
    );
    assert!(
        r.final_state.iter().all(|v| v.is_finite()),
        "{:?}",
        r.final_state
    );
    assert!(r.error.unwrap() < 1e-8, "{:?}", r.error);
    // It flips: ω₂ changes sign somewhere in [0, 20].
    let mut signs = vec![];
    for k in 0..400 {
        let (y, _) = run::reference_state(&s, 0.05 * k as f64).unwrap();
        signs.push(y[5] > 0.0);
    }
    assert!(signs.contains(&false), "never flipped");
}

#[test]
fn overflowing_momentum_is_refused_naming_the_field() {
    let text = "name = \"big\"\nkind = \"free\"\nt_end = 1.0\n[[body]]\nprincipal_moments = [1.0, 2.0, 3.0]\nmass = 1.0\n\
                [initial]\nangular_momentum = [1e200, 1.0, 1.0]\n";
    let err = Scene::parse(text, Path::new("big.toml")).unwrap_err();
    assert!(
        matches!(&err, SimError::BadField { field, .. } if field == "initial.angular_momentum"),
        "{err:?}"
    );
    let text = text.replace("angular_momentum = [1e200", "angular_velocity = [1e160");
    let err = Scene::parse(&text, Path::new("big.toml")).unwrap_err();
    assert!(
        err.to_string().contains("initial.angular_velocity"),
        "{err}"
    );
}

#[test]
fn end_times_beyond_f64_resolution_are_refused() {
    let s = scene(
        "principal_moments = [1.0, 2.0, 3.0]\nmass = 1.0",
        "angular_velocity = [1e-6, 1.0, 1e-6]",
        10.0,
    );
    for t in [f64::INFINITY, f64::NAN, -1.0] {
        let req = Request {
            t_end: Some(t),
            ..Request::default()
        };
        assert!(
            matches!(run::plan(&s, &req), Err(SimError::BadEndTime(_))),
            "{t}"
        );
    }
    let req = Request {
        t_end: Some(1e308),
        ..Request::default()
    };
    let err = run::plan(&s, &req).unwrap_err();
    assert!(matches!(err, SimError::EndTimeTooLong { .. }), "{err:?}");
    assert!(run::check_end_time(&s, 1e15).is_ok());
}
