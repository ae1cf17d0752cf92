//! Issue 11, item 3: the method choice for a heavy top is measured on the
//! scene (pilots), not read from a table. On heavy tops the choice was not
//! tuned on and on the bundled one, the requested error is met and the work
//! is within 3× of the cheapest setting that meets it in a sweep.

use std::path::Path;

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::Scene;
use hdot_sim::{Method, Step};

fn top(spin: f64, theta: f64, distance: f64, t_end: f64) -> Scene {
    let below = -distance;
    let text = format!(
        "name = \"top\"\nkind = \"heavy-top\"\nt_end = {t_end:e}\ng = [0.0, 0.0, -9.81]\n\
         [[body]]\nprincipal_moments = [0.002, 0.002, 0.003]\nmass = 0.6\n\
         [top]\nfixed_point = [0.0, 0.0, {below:e}]\n[initial]\neuler_angles = [0.0, {theta:e}, 0.0]\n\
         angular_velocity = [0.3, -0.2, {spin:e}]\n"
    );
    Scene::parse(&text, Path::new("top.toml")).unwrap()
}

fn run_with(s: &Scene, method: Method, step: Step) -> (f64, u64) {
    let req = Request {
        method: Some(method),
        step: Some(step),
        ..Request::default()
    };
    let plan = run::plan(s, &req).unwrap();
    // A setting too coarse to stay finite does not meet any request.
    match run::run(s, &plan, &mut Output::default()) {
        Ok(r) => (r.error.unwrap(), r.evaluations),
        Err(_) => (f64::INFINITY, u64::MAX),
    }
}

#[test]
fn pilot_choice_meets_the_request_within_3x_of_the_cheapest() {
    let bundled = Scene::from_file(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/examples/sim-heavy-top.toml"),
    )
    .unwrap();
    for (s, requested) in [
        (top(40.0, 0.6, 0.04, 4.0), 1e-6),
        (top(70.0, 1.2, 0.06, 3.0), 1e-8),
        // The bundled heavy top (the only bundled scene the choice
        // applies to: the others have closed forms).
        (bundled, 1e-8),
    ] {
        let req = Request {
            step: Some(Step::Tolerance(requested)),
            ..Request::default()
        };
        let plan = run::plan(&s, &req).unwrap();
        assert!(
            plan.reason.contains("measured on this scene"),
            "{}",
            plan.reason
        );
        let r = run::run(&s, &plan, &mut Output::default()).unwrap();
        let e = r.error.unwrap();
        assert!(
            e <= requested,
            "requested {requested:e}, got {e:e} ({})",
            plan.reason
        );
        // The sweep: dop853 and dopri5 at tol 10^(−3 − j/4), rk4 at T/2^k.
        let mut cheapest = u64::MAX;
        for m in [Method::Dop853, Method::Dopri5] {
            for j in 0..=40 {
                let (err, n) = run_with(&s, m, Step::Tolerance(10f64.powf(-3.0 - j as f64 / 4.0)));
                if err <= requested {
                    cheapest = cheapest.min(n);
                    break;
                }
            }
        }
        for k in 6..=18 {
            let (err, n) = run_with(&s, Method::Rk4, Step::Fixed(s.t_end / 2f64.powi(k)));
            if err <= requested {
                cheapest = cheapest.min(n);
                break;
            }
        }
        assert!(
            r.evaluations <= 3 * cheapest,
            "{} evaluations, cheapest in the sweep {cheapest} ({})",
            r.evaluations,
            plan.reason
        );
    }
}
