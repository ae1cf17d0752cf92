//! The tape evaluator against `Poly::eval` (the slow reference).

use hdot_num::eval::Tape;
use hdot_sym::{Atom, Poly, Symbols};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const CONSTANTS: [&str; 3] = ["a", "b", "c"];
const TIME: [&str; 3] = ["x", "y", "z"];

fn poly(text: &str) -> Poly {
    Symbols::parse_decl(&CONSTANTS, &TIME)
        .poly(text)
        .unwrap_or_else(|e| panic!("{text}: {e:?}"))
}

/// Whether `tape` (compiled from `polys`, perhaps with constants folded)
/// evaluates every output to `Poly::eval` at the values `value` gives,
/// within 64 ulps of the reference's own Σ |terms|; else which output
/// differs and by how much.
fn agrees_with_reference(
    tape: &Tape,
    polys: &[Poly],
    value: &mut dyn FnMut(Atom) -> f64,
) -> Result<(), String> {
    let inputs: Vec<f64> = tape.atoms().iter().map(|&a| value(a)).collect();
    let mut out = vec![0.0; polys.len()];
    tape.eval(&inputs, &mut out);
    let full = Tape::compile(polys);
    let all: Vec<f64> = full.atoms().iter().map(|&a| value(a)).collect();
    let mut scale = vec![0.0; polys.len()];
    full.eval_abs(&all, &mut scale);
    for (k, p) in polys.iter().enumerate() {
        let reference = p.eval(&mut |a| value(a));
        let tol = 64.0 * f64::EPSILON * scale[k];
        if (out[k] - reference).abs() > tol {
            return Err(format!("output {k}: {} vs {reference} (tol {tol})", out[k]));
        }
    }
    Ok(())
}

/// A random expression: sums of products of powers, derivatives and
/// divisions by constants, with rational coefficients.
fn expression(rng: &mut impl Rng) -> String {
    let leaves = ["a", "b", "c", "x", "y", "z", "x'", "y''", "2", "3/7"];
    let mut terms = Vec::new();
    for _ in 0..rng.gen_range(1..6) {
        let mut f = Vec::new();
        for _ in 0..rng.gen_range(1..4) {
            let leaf = leaves[rng.gen_range(0..leaves.len())];
            f.push(if rng.gen_bool(0.3) {
                format!("{leaf}^{}", rng.gen_range(2..4))
            } else {
                leaf.to_string()
            });
        }
        let mut t = f.join("*");
        if rng.gen_bool(0.2) {
            t = format!("{t}/{}", CONSTANTS[rng.gen_range(0..3)]);
        }
        if rng.gen_bool(0.2) {
            t = format!("({t} - {})^2", leaves[rng.gen_range(0..leaves.len())]);
        }
        terms.push(t);
    }
    terms.join(" + ")
}

/// Evaluates `polys` both ways at `point(atom)` and checks the tape agrees
/// within a tolerance scaled by Σ |terms|.
fn agree(polys: &[Poly], point: &mut dyn FnMut(Atom) -> f64) -> Result<(), String> {
    let tape = Tape::compile(polys);
    let inputs: Vec<f64> = tape.atoms().iter().map(|&a| point(a)).collect();
    let mut out = vec![0.0; polys.len()];
    let mut scale = vec![0.0; polys.len()];
    tape.eval(&inputs, &mut out);
    tape.eval_abs(&inputs, &mut scale);
    for (k, p) in polys.iter().enumerate() {
        let value = |a: Atom| inputs[tape.atoms().iter().position(|&b| b == a).unwrap()];
        let reference = p.eval(&mut |a| value(a));
        let tol = 64.0 * f64::EPSILON * scale[k];
        if (out[k] - reference).abs() > tol {
            return Err(format!(
                "output {k}: tape {} vs reference {reference} (tol {tol})",
                out[k]
            ));
        }
    }
    Ok(())
}

#[test]
fn the_tape_agrees_with_poly_eval_on_random_expressions() {
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    for _ in 0..200 {
        let polys: Vec<Poly> = (0..rng.gen_range(1..4))
            .map(|_| poly(&expression(&mut rng)))
            .collect();
        let mut values = std::collections::HashMap::new();
        let mut point = |a: Atom| {
            *values.entry(a).or_insert_with(|| {
                rng.gen_range(0.5..2.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 }
            })
        };
        agree(&polys, &mut point).unwrap();
    }
}

#[test]
fn shared_powers_and_prefixes_are_computed_once() {
    // x²y, x²y z, x² : one power, one product x²·y, one product ·z.
    let p = poly("x^2*y + x^2*y*z + x^2");
    let tape = Tape::compile(std::slice::from_ref(&p));
    assert_eq!(tape.atoms().len(), 3);
    assert!(tape.len() <= 3, "{} instructions", tape.len());
}

/// Constants given values at compile time are folded into the
/// coefficients: they are no inputs, and the outputs agree with the
/// reference evaluated with the same values.
#[test]
fn known_constants_are_folded_into_coefficients() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let known = |a: Atom| match a.name() {
        "a" => Some(1.7),
        "b" => Some(-0.6),
        "c" => Some(2.3),
        _ => None,
    };
    for _ in 0..100 {
        let polys: Vec<Poly> = (0..rng.gen_range(1..4))
            .map(|_| poly(&expression(&mut rng)))
            .collect();
        let tape = Tape::compile_with(&polys, &mut |a| known(a));
        assert!(tape.atoms().iter().all(|&a| known(a).is_none()));
        let mut values = std::collections::HashMap::new();
        let mut value = |a: Atom| {
            known(a).unwrap_or_else(|| *values.entry(a).or_insert_with(|| rng.gen_range(-2.0..2.0)))
        };
        if let Err(m) = agrees_with_reference(&tape, &polys, &mut value) {
            panic!("{m}");
        }
    }
}

/// Monomials with more factors than a term multiplies in a register
/// (long products of distinct atoms, powers and reciprocals) store a
/// prefix and still evaluate to the reference.
#[test]
fn long_monomials_agree_with_the_reference() {
    let polys = [
        poly("a*b*c*x*y*z*x'"),
        poly("b^3*x*y^2*z*x'/a^2 - 3/5*x*y*z*a*b + c"),
        poly("(a + x)^3*(b - y)^2*z/c"),
    ];
    let mut i = 0;
    let mut point = |_: Atom| {
        i += 1;
        0.3 + 0.17 * f64::from(i)
    };
    agree(&polys, &mut point).unwrap();
}

#[test]
fn constants_and_zero_compile() {
    let tape = Tape::compile(&[poly("0"), poly("5/2")]);
    assert!(tape.atoms().is_empty());
    let mut out = [1.0, 0.0];
    tape.eval(&[], &mut out);
    assert_eq!(out, [0.0, 2.5]);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(0), ..ProptestConfig::default() })]

    /// Tape = Poly::eval for any expression and point.
    #[test]
    fn tape_equals_reference(seed in any::<u64>(), xs in prop::collection::vec(-3.0..3.0f64, 9)) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let p = poly(&expression(&mut rng));
        let mut i = 0;
        let mut seen = std::collections::HashMap::new();
        let mut point = |a: Atom| *seen.entry(a).or_insert_with(|| { i += 1; let v: f64 = xs[i % xs.len()]; if v.abs() < 0.1 { 0.5 } else { v } });
        prop_assert!(agree(&[p], &mut point).is_ok());
    }

    /// Tape = Poly::eval for systems of several outputs sharing atoms,
    /// prefixes and powers, with long products, some atoms folded as known
    /// constants: the tolerance scaled by Σ |terms| at the same point.
    #[test]
    fn systems_with_folded_constants_equal_the_reference(
        seed in any::<u64>(),
        xs in prop::collection::vec(-3.0..3.0f64, 9),
        known in prop::collection::vec(any::<bool>(), 3),
        outputs in 1usize..5,
    ) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let polys: Vec<Poly> = (0..outputs)
            .map(|_| {
                let long = (0..rng.gen_range(4..8))
                    .map(|_| ["a", "b", "c", "x", "y", "z", "x'"][rng.gen_range(0..7)])
                    .collect::<Vec<_>>()
                    .join("*");
                poly(&format!("{} + {long}", expression(&mut rng)))
            })
            .collect();
        let value = |a: Atom| {
            let k = CONSTANTS.iter().chain(&TIME).position(|&n| n == a.name()).unwrap_or(8)
                + 3 * a.order() as usize;
            let v = xs[k % xs.len()];
            if v.abs() < 0.1 { 0.5 } else { v }
        };
        let fixed = |a: Atom| CONSTANTS.iter().position(|&n| n == a.name()).is_some_and(|k| known[k]);
        let tape = Tape::compile_with(&polys, &mut |a| fixed(a).then(|| value(a)));
        prop_assert!(tape.atoms().iter().all(|&a| !fixed(a)));
        let r = agrees_with_reference(&tape, &polys, &mut |a| value(a));
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(1), ..ProptestConfig::default() })]

    /// Outputs whose terms share factors (a monomial with positive and
    /// negative powers times a random sum, times a difference, and plus a
    /// term lacking the factor) are evaluated with the common factors taken
    /// out of the sum and multiplied once: they still equal the reference
    /// within the tolerance scaled by Σ |terms|, folded constants or not.
    #[test]
    fn common_factors_taken_out_keep_the_reference(
        seed in any::<u64>(),
        xs in prop::collection::vec(-3.0..3.0f64, 9),
        fold in any::<bool>(),
    ) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let leaves = ["a", "b", "x", "y", "z", "x'", "sin(y)", "cos(y)"];
        let common = (0..rng.gen_range(1..4))
            .map(|_| {
                let leaf = leaves[rng.gen_range(0..leaves.len())];
                match rng.gen_range(0..3) {
                    0 => format!("{leaf}^{}", rng.gen_range(2..4)),
                    // Division by constants, sin and cos only.
                    1 => format!("1/{}", ["a", "b", "sin(y)", "cos(y)"][rng.gen_range(0..4)]),
                    _ => leaf.to_string(),
                }
            })
            .collect::<Vec<_>>()
            .join("*");
        let sum = expression(&mut rng);
        let polys = [
            poly(&format!("({common})*({sum})")),
            poly(&format!("({common})*({sum}) + 1")),
            poly(&format!("({common})*({sum})*(x - y)")),
        ];
        let value = |a: Atom| {
            let k = leaves.iter().position(|&n| n == a.to_string()).unwrap_or(8);
            let v = xs[k % xs.len()];
            if v.abs() < 0.1 { 0.5 } else { v }
        };
        let tape = if fold {
            Tape::compile_with(&polys, &mut |a| (a.name() == "a").then(|| value(a)))
        } else {
            Tape::compile(&polys)
        };
        let r = agrees_with_reference(&tape, &polys, &mut |a| value(a));
        prop_assert!(r.is_ok(), "{}: {}", polys[0], r.unwrap_err());
    }
}

/// A factor common to the terms of several outputs is multiplied once
/// per output after its sum, and computed once: `x·y/sin z` of the four
/// terms of two outputs costs its two products and one reciprocal, not
/// products per term.
#[test]
fn a_common_factor_is_taken_out_of_the_sums() {
    let polys = [
        poly("x*y*x'/sin(z) + 2*x*y*y'/sin(z)"),
        poly("3*x*y/sin(z) - x*y*x'*y'/sin(z)"),
    ];
    let tape = Tape::compile(&polys);
    // 1/sin z, x·y, x·y·(1/sin z), in some order.
    assert_eq!(tape.len(), 3, "{} instructions", tape.len());
    let inputs: Vec<f64> = tape
        .atoms()
        .iter()
        .map(|a| match a.to_string().as_str() {
            "x" => 1.5,
            "y" => -0.25,
            "sin(z)" => 4.0,
            "x'" => 0.5,
            _ => 3.0,
        })
        .collect();
    let mut out = [0.0; 2];
    tape.eval(&inputs, &mut out);
    let c = 1.5 * -0.25 / 4.0;
    assert!((out[0] - c * (0.5 + 2.0 * 3.0)).abs() <= 4.0 * f64::EPSILON * c.abs() * 6.5);
    assert!((out[1] - c * (3.0 - 0.5 * 3.0)).abs() <= 4.0 * f64::EPSILON * c.abs() * 4.5);
}

/// The inputs gathered from a state by the tape's plan (components, one
/// `sin_cos` per angle, the rest given by a closure) give the bits the
/// same inputs passed in full give; an output equal to an earlier one is
/// copied from it, and a zero output is zero.
#[test]
fn planned_inputs_give_the_outputs_of_explicit_inputs() {
    use hdot_num::eval::Input;
    let polys = [
        poly("x*sin(y) + cos(y)*z' - 3*x^2*z'/sin(y)"),
        poly("0"),
        poly("x*sin(y) + cos(y)*z' - 3*x^2*z'/sin(y)"),
        poly("a*x + 2*cos(y)^2"),
    ];
    let mut tape = Tape::compile(&polys);
    let state: [f64; 3] = [0.7, 1.3, -0.4];
    let a_value = -1.9;
    let source = |a: Atom| match a.to_string().as_str() {
        "x" => Input::Component(0),
        "sin(y)" => Input::Sin(1),
        "cos(y)" => Input::Cos(1),
        "z'" => Input::Component(2),
        _ => Input::Given,
    };
    tape.plan_inputs(source);
    let (s, c) = state[1].sin_cos();
    let inputs: Vec<f64> = tape
        .atoms()
        .iter()
        .map(|&a| match source(a) {
            Input::Component(i) => state[i],
            Input::Sin(_) => s,
            Input::Cos(_) => c,
            Input::Given => a_value,
        })
        .collect();
    let mut want = [0.0; 4];
    tape.eval(&inputs, &mut want);
    let mut got = [f64::NAN; 4];
    let atoms = tape.atoms().to_vec();
    tape.eval_at(
        &state,
        |slots| {
            for (k, &a) in atoms.iter().enumerate() {
                if source(a) == Input::Given {
                    slots[k] = a_value;
                }
            }
        },
        &mut got,
    );
    assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits));
    assert_eq!(got[1], 0.0);
    assert_eq!(got[2].to_bits(), got[0].to_bits());
    let reference = polys[3].eval(&mut |a| match a.to_string().as_str() {
        "x" => state[0],
        "cos(y)" => c,
        "a" => a_value,
        other => panic!("no atom {other} in a*x + 2*cos(y)^2"),
    });
    assert!((got[3] - reference).abs() <= 8.0 * f64::EPSILON * reference.abs());
}

/// A tape of more slots than fit on the stack is evaluated in a buffer
/// kept per thread, with the same bits.
#[test]
fn a_tape_larger_than_the_stack_buffer_evaluates_alike() {
    let text = (1..=5000)
        .map(|k| format!("x^{k}"))
        .collect::<Vec<_>>()
        .join(" + ");
    let mut tape = Tape::compile(&[poly(&text)]);
    assert!(tape.slots() > 4096, "{} slots", tape.slots());
    tape.plan_inputs(|_| hdot_num::eval::Input::Component(0));
    let x: f64 = 1.0001;
    let (mut want, mut got) = ([0.0], [0.0]);
    tape.eval(&[x], &mut want);
    tape.eval_at(&[x], |_| {}, &mut got);
    assert_eq!(got[0].to_bits(), want[0].to_bits());
    let exact: f64 = (1..=5000).map(|k| x.powi(k)).sum();
    assert!((got[0] - exact).abs() <= 1e-9 * exact);
}

/// Outputs of one to three terms are evaluated two at a time, one in each
/// lane of a vector register; `eval_abs` evaluates them one at a time.
/// With every coefficient and input positive the magnitudes are the
/// values, the same operations on the same numbers: the bits must agree.
#[test]
fn outputs_evaluated_in_pairs_have_the_bits_of_one_at_a_time() {
    let leaves = ["a", "b", "x", "y", "z", "x'", "y''", "2", "3/7"];
    let mut rng = ChaCha8Rng::seed_from_u64(25);
    for _ in 0..200 {
        let polys: Vec<Poly> = (0..rng.gen_range(2..9))
            .map(|_| {
                let terms: Vec<String> = (0..rng.gen_range(1..4))
                    .map(|_| {
                        let factors: Vec<&str> = (0..rng.gen_range(1..4))
                            .map(|_| leaves[rng.gen_range(0..leaves.len())])
                            .collect();
                        let t = factors.join("*");
                        if rng.gen_bool(0.3) {
                            format!("{t}/{}", CONSTANTS[rng.gen_range(0..3)])
                        } else {
                            t
                        }
                    })
                    .collect();
                poly(&terms.join(" + "))
            })
            .collect();
        let tape = Tape::compile(&polys);
        let inputs: Vec<f64> = tape
            .atoms()
            .iter()
            .map(|_| rng.gen_range(0.5..2.0))
            .collect();
        let (mut out, mut abs) = (vec![0.0; polys.len()], vec![0.0; polys.len()]);
        tape.eval(&inputs, &mut out);
        tape.eval_abs(&inputs, &mut abs);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&out), bits(&abs), "{polys:?}");
    }
}
