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
//! The heavy top is also tied to `derivations/gyroscope.toml`, whose moment
//! equations are in the axes Oxyz of the Eulerian angles (frame F follows
//! precession and nutation, not spin) and in φ̈, θ̈, ψ̈. At a random angle
//! state the body's ω and the map from (φ̈, θ̈, ψ̈) to the body's ω̇ come from
//! differentiating R = R_z(φ) R_y(θ) R_z(ψ) numerically by the product rule
//! (`hdot_num::verify::motion::Attitude`, no ω formula); the angle
//! accelerations that produce the hand-written right-hand side's ω̇ are
//! solved for, and the derived ΣM_O at them must equal the hand-written
//! gravity torque, turned from the body axes into F by ψ.

use std::path::Path;

use hdot_num::eval::Tape;
use hdot_num::verify::motion::Attitude;
use hdot_sim::System;
use hdot_sim::nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use hdot_sim::systems::free::{EulerEquations, pack};
use hdot_sim::systems::{FreeBody, Gravity, PrecessionAngle};
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

/// `derivations/gyroscope.toml`'s step `M` (ΣM_O in the axes Oxyz),
/// compiled once per test binary.
fn gyroscope_moments() -> &'static Tape {
    static T: std::sync::OnceLock<Tape> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../derivations/gyroscope.toml");
        let d = derivation::load(&path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        let step = d.steps.iter().find(|s| s.name == "M").expect("step M");
        match &step.value {
            Value::Vector(v, _) => Tape::compile(&v.0),
            _ => panic!("step M is not a vector"),
        }
    })
}

/// The inputs of [`gyroscope_moments`]: `I` (axial) and `Ip` (transverse)
/// moments about O, and each angle's value, rate and acceleration; with
/// `abs`, magnitudes (sin and cos bounded by 1) for the scale.
fn gyroscope_inputs(
    tape: &Tape,
    axial: f64,
    transverse: f64,
    angles: [[f64; 3]; 3],
    abs: bool,
) -> Vec<f64> {
    let f = |x: f64| if abs { x.abs() } else { x };
    let angle = |name: &str| match name {
        "phi" => angles[0],
        "theta" => angles[1],
        "psi" => angles[2],
        _ => panic!("unexpected angle {name}"),
    };
    tape.atoms()
        .iter()
        .map(|a| match a.kind() {
            AtomKind::Var { name: "I", .. } => axial,
            AtomKind::Var { name: "Ip", .. } => transverse,
            AtomKind::Var { name, order, .. } => f(angle(name)[order as usize]),
            AtomKind::Sin(q) => f(angle(q.name())[0].sin()),
            AtomKind::Cos(q) => f(angle(q.name())[0].cos()),
            AtomKind::Sum { .. } => unreachable!("the heavy top divides by no sum"),
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(7), ..ProptestConfig::default() })]

    #[test]
    fn heavy_top_agrees_with_the_derived_gyroscope_equations(
        transverse in 0.5f64..3.0,
        axial in 0.2f64..2.0,
        phi in -3.0f64..3.0,
        theta in 0.2f64..2.9,
        psi in -3.0f64..3.0,
        rates in prop::array::uniform3(-5.0f64..5.0),
        weight_arm in 0.0f64..5.0,
    ) {
        // R = R_z(φ) R_y(θ) R_z(ψ), with given angle accelerations.
        let chain = |acc: [f64; 3]| {
            Attitude::about(2, phi, rates[0], acc[0])
                .then(&Attitude::about(1, theta, rates[1], acc[1]))
                .then(&Attitude::about(2, psi, rates[2], acc[2]))
        };
        let at_rest = chain([0.0; 3]);
        let w = at_rest.omega_own();
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(at_rest.r));

        // The hand-written heavy top (moments about O, symmetry axis z).
        let top = FreeBody {
            moments: [transverse, transverse, axial],
            gravity: Some(Gravity { weight_arm }),
        };
        let y = pack(&q, &w);
        let f = top.rhs(0.0, &y);
        let wd = Vector3::new(f[4], f[5], f[6]);

        // The body's ω̇ is affine in (φ̈, θ̈, ψ̈): solve for the angle
        // accelerations that give the hand-written ω̇ (regular for
        // 0 < θ < π).
        let base = at_rest.omega_own_rate();
        let mut map = Matrix3::zeros();
        for j in 0..3 {
            let mut e = [0.0; 3];
            e[j] = 1.0;
            map.set_column(j, &(chain(e).omega_own_rate() - base));
        }
        let acc = map.lu().solve(&(wd - base)).expect("θ away from 0 and π");

        let tape = gyroscope_moments();
        let angles = [
            [phi, rates[0], acc[0]],
            [theta, rates[1], acc[1]],
            [psi, rates[2], acc[2]],
        ];
        let mut derived = [0.0; 3];
        tape.eval(&gyroscope_inputs(tape, axial, transverse, angles, false), &mut derived);
        let mut scale = [0.0; 3];
        tape.eval_abs(&gyroscope_inputs(tape, axial, transverse, angles, true), &mut scale);

        // The hand-written torque, from the body axes into F (the body is
        // F turned by ψ about z).
        let tau = Rotation3::from_axis_angle(&Vector3::z_axis(), psi) * Vector3::from(top.torque(&y));
        for k in 0..3 {
            let s = scale[k] + tau[k].abs();
            prop_assert!(
                (derived[k] - tau[k]).abs() <= 256.0 * f64::EPSILON * s.max(f64::MIN_POSITIVE),
                "component {k}: derived ΣM {} vs hand-written torque {} (scale {s:e})",
                derived[k],
                tau[k]
            );
        }
    }
}
