//! Derived equations against particle sums, on random bodies and states
//! (the `hdot verify` checks as properties).

use std::path::Path;

use hdot_num::verify::{Comparison, check};
use hdot_sym::derivation::Derivation;
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
    eulers_principal_moments_equal_sum_of_r_cross_m_a,
    "euler-principal"
);
law!(
    eulers_general_moments_equal_sum_of_r_cross_m_a,
    "euler-general"
);
law!(
    h_equals_sum_of_r_cross_m_v_and_t_rot_half_m_v2,
    "angular-momentum"
);
law!(fixed_axis_moments_equal_sum_about_o, "fixed-axis");
law!(kinetic_energy_equals_sum_of_half_m_v2, "kinetic-energy");
law!(parallel_axis_equals_inertia_about_p, "parallel-axis");

#[test]
fn verify_is_seeded_and_skips_derivations_without_binding() {
    let d = derivation("euler-general");
    let a = hdot_num::verify::verify(&d, 5, 7, &mut || {})
        .unwrap()
        .unwrap();
    let b = hdot_num::verify::verify(&d, 5, 7, &mut || {})
        .unwrap()
        .unwrap();
    assert_eq!(a, b);
    assert!(a.passed && a.bodies == 5);
    assert!(hdot_num::verify::verify(&derivation("dalembert"), 5, 7, &mut || {}).is_none());
}
