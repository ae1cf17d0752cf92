//! Derived equations against particle sums, on random bodies and states
//! (the `hdot verify` checks as properties), and the same checks failing
//! when the derived result is perturbed.

use std::path::Path;

use hdot_num::verify::{
    COVERAGE, Comparison, Options, SUPPORTED, check as declared, check_named as check,
};
use hdot_sym::atom::AtomKind;
use hdot_sym::derivation::Derivation;
use hdot_sym::poly::Poly;
use proptest::prelude::*;

use crate::strategies::{verify_body, verify_state};

fn derivation(name: &str) -> Derivation {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../derivations/{name}.toml"));
    hdot_sym::derivation::load(&p).unwrap_or_else(|e| panic!("{e}"))
}

fn all_pass(cs: &[Comparison]) -> Result<(), TestCaseError> {
    for c in cs {
        prop_assert!(c.passes(), "{c:?}: relative error {:e}", c.relative_error());
    }
    Ok(())
}

/// One property per derivation, named after the law it checks.
macro_rules! law {
    ($test:ident, $name:literal) => {
        proptest! {
            #![proptest_config(ProptestConfig { cases: 16, rng_seed: proptest::test_runner::RngSeed::Fixed(0), ..ProptestConfig::default() })]
            #[test]
            fn $test(body in verify_body(), state in verify_state()) {
                let d = derivation($name);
                let cs = check(&d, &body, &state).expect("supported").expect("binds");
                prop_assert!(!cs.is_empty());
                all_pass(&cs)?;
            }
        }
    };
}

law!(
    stability_coefficient_matches_the_jacobians_eigenvalues,
    "principal-axis-stability"
);

/// `d` with the terms of `step` that contain the symbol `name` (of
/// derivative order `order`, or inside sin/cos) negated; `name = "*"`
/// negates the whole step.
fn mutated(d: &Derivation, step: &str, name: &str, order: u32) -> Derivation {
    let mut d = d.clone();
    let s = d
        .steps
        .iter_mut()
        .find(|s| s.name == step)
        .unwrap_or_else(|| panic!("{} has no step {step}", d.name));
    let hit = |a: hdot_sym::atom::Atom| {
        let a = match a.kind() {
            AtomKind::Sin(x) | AtomKind::Cos(x) => x,
            _ => a,
        };
        name == "*" || (a.name() == name && a.order() == order)
    };
    let mut changed = false;
    s.value = s.value.map(&mut |p: &Poly| {
        Poly::from_terms(p.terms().iter().map(|(m, c)| {
            if m.factors().iter().any(|(a, _)| hit(*a)) || (name == "*") {
                changed = true;
                (m.clone(), -c.clone())
            } else {
                (m.clone(), c.clone())
            }
        }))
    });
    assert!(changed, "{step} has no term with {name}");
    d
}

/// One perturbation per binding: the step, and the symbol whose terms
/// get the wrong sign (`*`: the whole step).
const PERTURBATIONS: &[(&str, &str, &str, u32)] = &[("principal-axis-stability", "k_1", "A", 0)];

/// Bundled files verified from their declarations: the step, and the
/// symbol whose terms get the wrong sign (`*`: the whole step).
const DECLARED_PERTURBATIONS: &[(&str, &str, &str, u32)] = &[
    ("euler-general", "M", "I_xy", 0),
    ("euler-general", "M_principal", "I_x", 0),
    ("euler-general", "I_G", "I_yz", 0),
    ("angular-momentum", "H", "I_xy", 0),
    ("angular-momentum", "H_along_x", "I_zx", 0),
    ("angular-momentum", "H_principal", "I_y", 0),
    ("angular-momentum", "T_rot", "I_zx", 0),
    ("angular-momentum-about-point", "H_O", "m", 0),
    ("angular-momentum-about-point", "H_O_general", "m", 0),
    ("angular-momentum-about-point", "vbar", "*", 0),
    ("dalembert", "F", "*", 0),
    ("dalembert", "M_O", "m", 0),
    ("dalembert", "Hdot_G", "I_x", 0),
    ("fixed-axis", "M", "I_yz", 0),
    ("fixed-axis", "M_symmetric", "I_z", 0),
    ("fixed-axis", "M_steady", "I_zx", 0),
    ("kinetic-energy", "T", "I_zx", 0),
    ("kinetic-energy", "T_principal", "m", 0),
    ("kinetic-energy", "T_O", "m", 0),
    ("parallel-axis", "I_P", "m", 0),
    ("parallel-axis", "H_point", "*", 0),
    ("plane-motion", "H", "I_zx", 0),
    ("plane-motion", "H_lamina", "I_z", 0),
    ("plane-motion", "M_lamina", "I_z", 0),
    ("impulse-momentum", "omega", "F_x", 0),
    ("impulse-momentum", "v", "m", 0),
];

/// The declared checks fail when one group of terms of a step gets the
/// wrong sign, naming that step.
#[test]
fn declared_checks_fail_when_the_derived_result_is_perturbed() {
    for &(name, step, symbol, order) in DECLARED_PERTURBATIONS {
        let d = mutated(&derivation(name), step, symbol, order);
        let r = declared(&d, &Options { draws: 8, seed: 3 }).expect("binds");
        let s = r.steps.iter().find(|s| s.step == step).expect("compared");
        assert!(!s.passed, "{name}: {step} with −{symbol} still passes");
        assert!(
            r.steps.iter().filter(|t| t.step != step).all(|t| t.passed),
            "{name}: only {step} was perturbed"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, rng_seed: proptest::test_runner::RngSeed::Fixed(1), ..ProptestConfig::default() })]
    /// Every binding can fail: a wrong sign on one group of terms (a
    /// product of inertia, the Coriolis term, the transverse moment…)
    /// makes some comparison fail on every random body.
    #[test]
    fn every_check_fails_when_the_derived_result_is_perturbed(body in verify_body(), state in verify_state()) {
        for &(name, step, symbol, order) in PERTURBATIONS {
            let d = mutated(&derivation(name), step, symbol, order);
            let cs = check(&d, &body, &state).expect("supported").expect("binds");
            let worst = cs.iter().map(Comparison::relative_error).fold(0.0, f64::max);
            prop_assert!(
                cs.iter().any(|c| !c.passes()),
                "{name}: {step} with −{symbol} still passes (worst {worst:e})"
            );
        }
    }

    /// The verdict steps (constants ±1) fail when negated: the direct side
    /// is the sign computed from the particle body, not a restatement.
    #[test]
    fn verdicts_fail_when_negated(body in verify_body(), state in verify_state()) {
        for (name, step) in [
            ("principal-axis-stability", "sign_largest"),
            ("principal-axis-stability", "sign_intermediate"),
            ("principal-axis-stability", "sign_smallest"),
        ] {
            let d = mutated(&derivation(name), step, "*", 0);
            let cs = check(&d, &body, &state).expect("supported").expect("binds");
            let c = cs.iter().find(|c| c.quantity == step).expect("compared");
            prop_assert!(!c.passes(), "{name}: −{step} passes: {c:?}");
        }
    }
}

/// The lamina form H = I_z ω k, applied to a body that is not symmetric
/// about its xy plane, fails: the check sees the missing products.
#[test]
fn lamina_form_fails_on_an_unsymmetric_body() {
    let d = derivation("plane-motion");
    let mut d2 = d.clone();
    // H := H_lamina, compared on the general body.
    let lamina = d.steps.iter().find(|s| s.name == "H_lamina").unwrap();
    let h = d2.steps.iter_mut().find(|s| s.name == "H").unwrap();
    h.value = lamina.value.clone();
    let r = declared(&d2, &Options { draws: 20, seed: 3 }).unwrap();
    let h = r.steps.iter().find(|s| s.step == "H").unwrap();
    assert!(!h.passed && h.worst.as_ref().unwrap().quantity.starts_with("H."));
    assert!(r.steps.iter().filter(|s| s.step != "H").all(|s| s.passed));
}

#[test]
fn verify_is_seeded_and_covers_every_bundled_derivation() {
    let d = derivation("euler-general");
    let o = Options { draws: 5, seed: 7 };
    let a = declared(&d, &o).unwrap();
    assert_eq!(a, declared(&d, &o).unwrap());
    assert!(a.passed() && a.draws == 5);
    // Every bundled derivation declares its meanings, or (until it does)
    // has a binding and a coverage entry.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../derivations");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n != hdot_sym::course::MANIFEST_FILE)
        })
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .filter(|n| derivation(n).steps.iter().all(|s| s.meaning.is_none()))
        .collect();
    names.sort();
    assert_eq!(names, SUPPORTED);
    let mut covered: Vec<&str> = COVERAGE.iter().map(|c| c.derivation).collect();
    covered.sort();
    assert_eq!(covered, SUPPORTED);
    assert_eq!(PERTURBATIONS.len(), SUPPORTED.len());
    // A derivation the checks do not know has no binding.
    let mut other = derivation("principal-axis-stability");
    other.name = "not-a-bundled-derivation".into();
    assert!(hdot_num::verify::verify(&other, 5, 7, &mut || {}).is_none());
}

/// Every step of every derivation is either compared, compared with
/// kinematics, or listed as not compared (with a reason).
#[test]
fn coverage_names_every_step() {
    for c in COVERAGE {
        let d = derivation(c.derivation);
        let listed: Vec<&str> = c
            .compared
            .iter()
            .chain(c.kinematic)
            .chain(c.not_compared)
            .flat_map(|(steps, _)| steps.split(", "))
            .collect();
        for s in &d.steps {
            let named = listed.iter().any(|l| {
                *l == s.name
                    || l.strip_suffix('*')
                        .is_some_and(|prefix| s.name.starts_with(prefix))
            });
            assert!(
                named,
                "{}: step {} is not in the coverage",
                c.derivation, s.name
            );
        }
        for l in &listed {
            let prefix = l.strip_suffix('*').unwrap_or(l);
            assert!(
                d.steps.iter().any(|s| s.name.starts_with(prefix)),
                "{}: the coverage names {l}, which is not a step",
                c.derivation
            );
        }
    }
}
