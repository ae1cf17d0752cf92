//! The simulation's hand-written right-hand sides against the equations
//! `hdot-sym` derives. `derivations/euler-principal.toml` derives
//! `ΣM = (Ḣ)_B + ω × H` for body-fixed principal axes; its step `M` is
//! compiled with [`Tape`], symbols bound by name and derivative order
//! (`I_x`, `omega_x`, `omega_x'`), and solved for `ω̇` with `ΣM = τ`
//! (the step is linear in `ω̇`: its coefficients are read off by evaluating
//! at `ω̇ = 0` and at the unit vectors). At seeded random states
//! (proptest) the hand-written [`FreeBody`], [`EulerEquations`] and
//! [`PrecessionAngle`] right-hand sides must agree to round-off, relative
//! to the magnitudes of the terms (`Tape::eval_abs`).
//!
//! `derivations/gyroscope.toml` is not used: its moment equations are in
//! the Eulerian-angle frame of an axisymmetric rotor (frame F does not
//! spin), in φ̈, θ̈, ψ̈; tying them to the body-frame ω̇ needs the derivative
//! of the angle kinematics, which this test does not build. The heavy top's
//! torque enters through the same `ΣM = τ` solve below, with τ from
//! `FreeBody::torque`.

use std::path::Path;

use hdot_num::eval::Tape;
use hdot_sim::System;
use hdot_sim::models::free::{EulerEquations, pack};
use hdot_sim::models::{FreeBody, Gravity, PrecessionAngle};
use hdot_sim::nalgebra::{Matrix3, UnitQuaternion, Vector3};
use hdot_sym::atom::AtomKind;
use hdot_sym::derivation::{self, Value};
use hdot_sym::poly::Poly;
use proptest::prelude::*;

use crate::strategies::{angular_velocity, asymmetric_moments};

/// The derived moment equations, compiled.
struct Derived {
    tape: Tape,
}

impl Derived {
    /// Loaded and compiled once per test binary.
    fn get() -> &'static Derived {
        static D: std::sync::OnceLock<Derived> = std::sync::OnceLock::new();
        D.get_or_init(Derived::load)
    }

    fn load() -> Derived {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../derivations/euler-principal.toml");
        let d = derivation::load(&path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        let step = d.steps.iter().find(|s| s.name == "M").expect("step M");
        let polys: Vec<Poly> = match &step.value {
            Value::Vector(v, _) => v.0.to_vec(),
            _ => panic!("step M is not a vector"),
        };
        Derived {
            tape: Tape::compile(&polys),
        }
    }

    /// Inputs bound by (name, order); panics on a symbol the test does not know.
    fn inputs(&self, i: [f64; 3], w: [f64; 3], wd: [f64; 3], abs: bool) -> Vec<f64> {
        let f = |x: f64| if abs { x.abs() } else { x };
        self.tape
            .atoms()
            .iter()
            .map(|a| match a.kind() {
                AtomKind::Var { name, order, .. } => {
                    let k = match name.chars().last() {
                        Some('x') => 0,
                        Some('y') => 1,
                        Some('z') => 2,
                        _ => panic!("unexpected symbol {name}"),
                    };
                    match (name.split('_').next(), order) {
                        (Some("I"), 0) => f(i[k]),
                        (Some("omega"), 0) => f(w[k]),
                        (Some("omega"), 1) => f(wd[k]),
                        _ => panic!("unexpected symbol {name} of order {order}"),
                    }
                }
                _ => panic!("unexpected atom {}", a.name()),
            })
            .collect()
    }

    fn eval(&self, i: [f64; 3], w: [f64; 3], wd: [f64; 3]) -> [f64; 3] {
        let mut out = [0.0; 3];
        self.tape.eval(&self.inputs(i, w, wd, false), &mut out);
        out
    }

    /// ω̇ from `M(ω̇) = τ` (M is affine in ω̇), and the scale of the terms.
    fn angular_acceleration(&self, i: [f64; 3], w: [f64; 3], tau: [f64; 3]) -> ([f64; 3], f64) {
        let m0 = self.eval(i, w, [0.0; 3]);
        let mut a = Matrix3::zeros();
        for j in 0..3 {
            let mut e = [0.0; 3];
            e[j] = 1.0;
            let mj = self.eval(i, w, e);
            for k in 0..3 {
                a[(k, j)] = mj[k] - m0[k];
            }
        }
        let rhs = Vector3::new(tau[0] - m0[0], tau[1] - m0[1], tau[2] - m0[2]);
        let wd = a.lu().solve(&rhs).expect("positive moments: invertible");
        let mut scale = [0.0; 3];
        self.tape
            .eval_abs(&self.inputs(i, w, [0.0; 3], true), &mut scale);
        let s = (0..3)
            .map(|k| (scale[k] + tau[k].abs()) / i[k])
            .fold(0.0, f64::max);
        ([wd.x, wd.y, wd.z], s)
    }
}

fn close(hand: [f64; 3], derived: [f64; 3], scale: f64) -> Result<(), TestCaseError> {
    for k in 0..3 {
        prop_assert!(
            (hand[k] - derived[k]).abs() <= 64.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE),
            "component {k}: hand-written {} vs derived {} (scale {scale:e})",
            hand[k],
            derived[k]
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(5), ..ProptestConfig::default() })]

    #[test]
    fn hand_written_euler_equations_agree_with_the_derived_ones(
        i in asymmetric_moments(),
        w in angular_velocity(),
        q in prop::array::uniform4(-1.0f64..1.0),
        weight_arm in 0.0f64..5.0,
    ) {
        let derived = Derived::get();
        let q = UnitQuaternion::from_quaternion(
            hdot_sim::nalgebra::Quaternion::new(q[0] + 2.0, q[1], q[2], q[3]),
        );
        let wv = Vector3::from(w);

        // Torque-free: FreeBody, EulerEquations, PrecessionAngle.
        let (wd, scale) = derived.angular_acceleration(i, w, [0.0; 3]);
        let body = FreeBody { moments: i, gravity: None };
        let f = body.rhs(0.0, &pack(&q, &wv));
        close([f[4], f[5], f[6]], wd, scale)?;
        close(EulerEquations { moments: i }.rhs(0.0, &w), wd, scale)?;
        let (p, z) = PrecessionAngle::new(i, &q, &wv).expect("ω ≠ 0");
        let g = p.rhs(0.0, &z);
        close([g[0], g[1], g[2]], wd, scale)?;

        // Heavy top (moments about O): ΣM = τ with the gravity torque.
        let top = FreeBody { moments: i, gravity: Some(Gravity { weight_arm }) };
        let y = pack(&q, &wv);
        let tau = top.torque(&y);
        let (wd, scale) = derived.angular_acceleration(i, w, tau);
        let f = top.rhs(0.0, &y);
        close([f[4], f[5], f[6]], wd, scale)?;
    }
}

/// Without proptest: the binding names every atom of the derived step.
#[test]
fn the_derived_step_uses_only_moments_and_angular_velocity() {
    let d = Derived::get();
    assert_eq!(d.tape.outputs(), 3);
    assert_eq!(d.tape.atoms().len(), 9, "I, ω, ω̇ for x, y, z");
    d.inputs([1.0; 3], [1.0; 3], [1.0; 3], false);
}
