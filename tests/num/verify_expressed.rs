//! verify/expressed.rs: a step expressing a constant vector of one frame
//! in another's axes (the bicycle's `a_z`, the front axle's vertical
//! component) measured from the drawn rotation matrices: the engine's
//! `express` against them; a wrong value fails.

use super::{load, verified};
use hdot_num::verify::{Options, check};
use hdot_sym::Rational;
use hdot_sym::derivation::Value;

const BICYCLE: &str = include_str!("../../derivations/bicycle.toml");

const OPTS: Options = Options { draws: 4, seed: 24 };

#[test]
fn the_front_axle_s_vertical_component_agrees_with_the_rotations() {
    let (compared, failed) = verified(BICYCLE, &OPTS);
    assert!(compared.iter().any(|s| s == "a_z"), "{compared:?}");
    assert!(failed.is_empty(), "{failed:?}");
}

#[test]
fn a_wrong_value_of_the_axle_s_component_fails() {
    // The formula is what is measured (the frames it names); a value that
    // is not what it says — here 1/1000 off — fails.
    let mut d = load(BICYCLE);
    let s = d.steps.iter_mut().find(|s| s.name == "a_z").expect("a_z");
    let factor = Rational::new(1001, 1000).expect("a ratio");
    let Value::Scalar(p) = &mut s.value else {
        panic!("a_z is a scalar")
    };
    *p = p.scale(&factor);
    let r = check(&d, &OPTS).unwrap_or_else(|e| panic!("{e}"));
    let failed = r.failed();
    assert_eq!(failed, ["a_z"]);
}
