//! The linearized Kane equations of the bicycle measured on the particles
//! (issue 24, item 7; verify/linearized.rs): the `kane` step about upright
//! straight running and the matrices taken from it (`forward`, `M`, `C`,
//! `Kq`, and `C_1`, `K_0`, `K_2` with constants given values) against the
//! Jacobian of the generalized forces measured on the four bodies'
//! particles at the operating point. A perturbed entry must fail.

use hdot_num::verify::{Options, check};
use hdot_sym::Rational;
use hdot_sym::derivation::Value;

use super::load;

const BICYCLE: &str = include_str!("../../derivations/bicycle.toml");

/// The matrices of the benchmark's lean and steer equations.
const MATRICES: [&str; 8] = ["K", "forward", "M", "C", "Kq", "C_1", "K_0", "K_2"];

fn options() -> Options {
    Options { draws: 3, seed: 24 }
}

#[test]
fn the_linearized_bicycle_agrees_with_the_particles() {
    let r = check(&load(BICYCLE), &options()).unwrap_or_else(|e| panic!("{e}"));
    for m in MATRICES {
        let s = r
            .steps
            .iter()
            .find(|s| s.step == m)
            .unwrap_or_else(|| panic!("{m} is not compared: {:?}", r.not_compared));
        assert!(s.passed, "{m}: {:?}", s.worst);
        let w = s
            .worst
            .as_ref()
            .unwrap_or_else(|| panic!("{m}: no comparison made"));
        // `--steps` states the bound the worst comparison was held to,
        // and it holds the difference.
        let (_, bound) = s
            .against
            .split_once("|derived − measured| ≤ ")
            .unwrap_or_else(|| panic!("{m} states no tolerance: {}", s.against));
        let bound: f64 = bound
            .split(' ')
            .next()
            .and_then(|b| b.parse().ok())
            .expect("a number");
        assert!(
            bound > 0.0 && (w.derived - w.direct).abs() <= bound,
            "{m}: {w:?} beyond {bound}"
        );
    }
    for m in MATRICES {
        assert!(
            !r.not_compared
                .iter()
                .any(|n| n == m || n.starts_with(&format!("{m} ("))),
            "{m} listed as not compared: {:?}",
            r.not_compared
        );
    }
}

/// `step`'s entry (1, 2) times 1 + 1/`relative` (nonzero in each of the
/// benchmark's matrices), or K's first equation so.
fn perturbed(step: &str, relative: i64) -> hdot_sym::derivation::Derivation {
    let mut d = load(BICYCLE);
    let s = d
        .steps
        .iter_mut()
        .find(|s| s.name == step)
        .expect("the step");
    let factor = Rational::new(relative + 1, relative).expect("a ratio");
    match &mut s.value {
        Value::Array(rows) => rows[0][1] = rows[0][1].scale(&factor),
        Value::List { items, .. } => items[0] = items[0].scale(&factor),
        v => panic!("{step}: {v:?}"),
    }
    d
}

#[test]
fn a_perturbed_entry_of_a_linearized_matrix_fails() {
    for step in ["M", "C", "Kq", "K_0", "K_2"] {
        let d = perturbed(step, 10_000);
        let r = check(&d, &Options { draws: 1, seed: 24 }).unwrap_or_else(|e| panic!("{e}"));
        let failed = r.failed();
        assert_eq!(failed, [step], "{step}");
        let worst = r.worst().expect("a comparison");
        assert!(
            worst.quantity.starts_with(&format!("{step}.12")),
            "{worst:?}"
        );
    }
}

#[test]
fn a_perturbed_linearized_kane_equation_fails() {
    let d = perturbed("K", 10_000);
    let r = check(&d, &options()).unwrap_or_else(|e| panic!("{e}"));
    let k = r.steps.iter().find(|s| s.step == "K").expect("K compared");
    assert!(!k.passed, "{:?}", k.worst);
}
