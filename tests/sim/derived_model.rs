//! Integrating what a derivation derived (`hdot_sim::systems::derived`):
//! the heavy top in Eulerian angles, solved for its accelerations by the
//! engine, against the built-in quaternion heavy top; the mass-matrix form
//! against the explicit form; singularities and bad input.

use std::collections::BTreeMap;

use hdot_sim::nalgebra::Vector3;
use hdot_sim::systems::derived::{
    DerivedModel, DerivedSpec, DerivedSystem, EquationsSpec, TimeFunction,
};
use hdot_sim::systems::euler_angles::quaternion_from_angles;
use hdot_sim::systems::free::{attitude, omega, pack};
use hdot_sim::systems::{FreeBody, Gravity};
use hdot_sim::{Limits, Method, SimError, Step, integrate};
use hdot_sym::derivation::{Derivation, load_str};

/// A heavy top written for this test: moments about O from the transport
/// theorem, the weight's moment, accelerations solved by the engine, and
/// the mass-matrix form of Lagrange's equations from T and V.
const TOP: &str = r#"
title = "heavy top"
source = "test"
[symbols]
constants = ["I", "Ip", "m", "g", "l"]
time = ["phi", "theta", "psi"]
[[frame]]
name = "P"
parent = "N"
rotation = "z(phi)"
[[frame]]
name = "F"
parent = "P"
rotation = "y(theta)"
[[frame]]
name = "R"
parent = "F"
rotation = "z(psi)"
[[step]]
name = "H"
value = "principal(Ip, Ip, I) * express(angvel(R), F)"
[[step]]
name = "M"
value = "dt_rel(H) + cross(angvel(F), H)"
[[step]]
name = "W"
value = "cross([0, 0, l] in F, express([0, 0, -m*g] in N, F))"
[[step]]
name = "acc"
value = "solve(M - W, [phi'', theta'', psi''])"
[[step]]
name = "T"
value = "dot(express(angvel(R), F), H)/2"
[[step]]
name = "V"
value = "m*g*l*cos(theta)"
[[step]]
name = "E"
value = "T + V"
[[step]]
name = "L"
value = "lagrange(T, V, [phi, theta, psi])"
[[step]]
name = "Mass"
value = "mass_matrix(L, [phi'', theta'', psi''])"
[[step]]
name = "f"
value = "forcing(L, [phi'', theta'', psi''])"
"#;

const I: f64 = 4.0e-4;
const IP: f64 = 2.5e-4;
const M: f64 = 0.5;
const G: f64 = 9.81;
const L: f64 = 0.05;

fn derivation() -> Derivation {
    load_str("top.toml", TOP)
        .map_err(|e| e.to_string())
        .unwrap()
}

fn spec(equations: EquationsSpec) -> DerivedSpec {
    let constants: BTreeMap<String, f64> = [("I", I), ("Ip", IP), ("m", M), ("g", G), ("l", L)]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
    DerivedSpec {
        equations,
        constants,
        inputs: BTreeMap::new(),
        conserved: vec!["E".into()],
    }
}

fn explicit() -> EquationsSpec {
    EquationsSpec::Explicit { step: "acc".into() }
}

fn mass_matrix() -> EquationsSpec {
    EquationsSpec::MassMatrix {
        mass_matrix: "Mass".into(),
        forcing: "f".into(),
        coordinates: vec!["phi".into(), "theta".into(), "psi".into()],
    }
}

/// Integrates a derived model to `t_end` with DOP853 at `tol`.
fn run(model: &DerivedModel, y0: [f64; 6], t_end: f64, tol: f64) -> [f64; 6] {
    integrate(
        &DerivedSystem::<6>(model),
        Method::Dop853,
        Step::Tolerance(tol),
        0.0,
        y0,
        t_end,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap()
    .0
}

fn initial() -> ([f64; 6], BTreeMap<String, f64>) {
    let y0 = [0.3, 0.6, -0.2, 0.5, -1.0, 80.0];
    let names = ["phi", "theta", "psi", "phi'", "theta'", "psi'"];
    (
        y0,
        names
            .iter()
            .zip(y0)
            .map(|(n, v)| (n.to_string(), v))
            .collect(),
    )
}

#[test]
fn derived_heavy_top_agrees_with_the_built_in_quaternion_top() {
    let d = derivation();
    let model = DerivedModel::new(&d, &spec(explicit())).unwrap();
    let (y0, named) = initial();
    assert_eq!(model.initial_state(&named).unwrap(), y0.to_vec());
    let t_end = 0.5;
    let tol = 1e-12;
    let y = run(&model, y0, t_end, tol);

    // The built-in top: same body, attitude and ω from the derivation's
    // own frames at t = 0.
    let r0 = model.attitude("R", 0.0, &y0).unwrap();
    let q0 = quaternion_from_angles(y0[0], y0[1], y0[2]);
    assert!(
        (r0 - q0.to_rotation_matrix().into_inner()).norm() < 1e-15,
        "z-y-z convention"
    );
    let w0 = model.angular_velocity("R", 0.0, &y0).unwrap();
    let top = FreeBody {
        moments: [IP, IP, I],
        gravity: Some(Gravity {
            weight_arm: M * G * L,
        }),
    };
    let z0 = pack(&q0, &Vector3::new(w0[0], w0[1], w0[2]));
    let (z, _) = integrate(
        &top,
        Method::Dop853,
        Step::Tolerance(tol),
        0.0,
        z0,
        t_end,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap();

    let r_derived = model.attitude("R", t_end, &y).unwrap();
    let r_builtin = attitude(&z).to_rotation_matrix().into_inner();
    let w_derived = model.angular_velocity("R", t_end, &y).unwrap();
    let w_builtin = omega(&z);
    let w_scale = w_builtin.norm();
    // Both runs are within their tolerance of the truth; the error grows
    // with the spin's phase (|ω| T ≈ 40 rad).
    let bound = 100.0 * tol * w_scale * t_end;
    assert!(
        (r_derived - r_builtin).norm() < bound,
        "attitude {:.3e}",
        (r_derived - r_builtin).norm()
    );
    assert!(
        (w_derived - w_builtin).norm() < bound * w_scale,
        "ω {:.3e} (|ω| {w_scale})",
        (w_derived - w_builtin).norm()
    );
    // And the derived run is not trivially the initial state.
    assert!((r_derived - r0).norm() > 0.1);
}

#[test]
fn mass_matrix_form_integrates_like_the_explicit_form_and_conserves_energy() {
    let d = derivation();
    let a = DerivedModel::new(&d, &spec(explicit())).unwrap();
    let b = DerivedModel::new(&d, &spec(mass_matrix())).unwrap();
    let (y0, _) = initial();
    let ya = run(&a, y0, 0.3, 1e-12);
    let yb = run(&b, y0, 0.3, 1e-12);
    for k in 0..6 {
        let scale = 1.0 + y0[k].abs() + ya[k].abs();
        assert!(
            (ya[k] - yb[k]).abs() < 1e-8 * scale,
            "component {k}: {} vs {}",
            ya[k],
            yb[k]
        );
    }
    let e = &a.conserved()[0];
    let (e0, e1) = (
        a.conserved_value(e, 0.0, &y0)[0],
        a.conserved_value(e, 0.3, &ya)[0],
    );
    assert!(
        (e1 - e0).abs() < 1e-9 * e0.abs(),
        "energy drift {}",
        (e1 - e0) / e0
    );
}

/// One evaluation: the mass-matrix form (M and f compiled together, the
/// small stack solve) gives the explicit form's accelerations at states
/// drawn over the whole range of the angles and rates (seeded), within the
/// round-off of the larger of the two sides.
#[test]
fn the_mass_matrix_solve_gives_the_explicit_accelerations_at_every_state() {
    let d = derivation();
    let a = DerivedModel::new(&d, &spec(explicit())).unwrap();
    let b = DerivedModel::new(&d, &spec(mass_matrix())).unwrap();
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move |lo: f64, hi: f64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..500 {
        let y = [
            next(-3.0, 3.0),
            next(0.05, 3.09),
            next(-3.0, 3.0),
            next(-20.0, 20.0),
            next(-20.0, 20.0),
            next(-200.0, 200.0),
        ];
        let (mut qa, mut qb) = ([0.0; 3], [0.0; 3]);
        a.accelerations(0.0, &y, &mut qa).unwrap();
        b.accelerations(0.0, &y, &mut qb).unwrap();
        // The explicit form divides by sin θ: its terms grow like
        // |rates|² / sin θ, and so does the round-off of both.
        let scale = (1.0 + y[3..].iter().map(|v| v * v).sum::<f64>()) / y[1].sin();
        for k in 0..3 {
            assert!(
                (qa[k] - qb[k]).abs() <= 1e-11 * scale,
                "q̈[{k}] at {y:?}: {} vs {}",
                qa[k],
                qb[k]
            );
        }
    }
}

/// A mass matrix that is singular at a state: the evaluation says so
/// (`None`, the integrator's NaN) and the check names it, no panic.
#[test]
fn a_singular_mass_matrix_is_no_acceleration() {
    // Two coordinates whose kinetic energy (q̇₁ + cos q₂ q̇₂)²/2 + c q̇₂²
    // has M = [[1, cos q₂], [cos q₂, cos² q₂ + 2 c]]: singular where c = 0.
    let text = r#"
title = "degenerate"
source = "test"
[symbols]
constants = ["c"]
time = ["a", "b"]
[[step]]
name = "T"
value = "(a' + cos(b)*b')^2/2 + c*b'^2"
[[step]]
name = "L"
value = "lagrange(T, 0, [a, b])"
[[step]]
name = "Mass"
value = "mass_matrix(L, [a'', b''])"
[[step]]
name = "f"
value = "forcing(L, [a'', b''])"
"#;
    let d = load_str("degenerate.toml", text)
        .map_err(|e| e.to_string())
        .unwrap();
    let spec = |c: f64| DerivedSpec {
        equations: EquationsSpec::MassMatrix {
            mass_matrix: "Mass".into(),
            forcing: "f".into(),
            coordinates: vec!["a".into(), "b".into()],
        },
        constants: [("c".to_string(), c)].into_iter().collect(),
        inputs: BTreeMap::new(),
        conserved: vec![],
    };
    let y = [0.1, 0.0, 0.5, 0.7];
    let regular = DerivedModel::new(&d, &spec(0.25)).unwrap();
    let mut q = [0.0; 2];
    assert!(regular.accelerations(0.0, &y, &mut q).is_some());
    assert!(q.iter().all(|v| v.is_finite()), "{q:?}");
    let singular = DerivedModel::new(&d, &spec(0.0)).unwrap();
    assert!(singular.accelerations(0.0, &y, &mut q).is_none());
    let why = singular
        .singularity(0.0, &y)
        .expect("a singular mass matrix");
    assert!(why.contains("mass matrix is singular"), "{why}");
}

#[test]
fn an_applied_torque_given_as_a_function_of_time_drives_the_spin() {
    // A rotor on a fixed axis: I ψ̈ = M(t).
    let text = r#"
title = "rotor"
source = "test"
[symbols]
constants = ["I"]
time = ["psi", "M_z"]
[[step]]
name = "acc"
value = "solve(I*psi'' - M_z, [psi''])"
"#;
    let d = load_str("rotor.toml", text)
        .map_err(|e| e.to_string())
        .unwrap();
    let mut s = spec(explicit());
    s.constants = [("I".to_string(), 2.0), ("M_0".to_string(), 3.0)]
        .into_iter()
        .collect();
    s.inputs.insert(
        "M_z".into(),
        TimeFunction::parse("M_0*cos(t)", &s.constants).unwrap(),
    );
    s.conserved.clear();
    let model = DerivedModel::new(&d, &s).unwrap();
    let (y, _) = integrate(
        &DerivedSystem::<2>(&model),
        Method::Dop853,
        Step::Tolerance(1e-12),
        0.0,
        [0.0, 0.0],
        2.0,
        Limits::default(),
        |_, _| Ok(()),
    )
    .unwrap();
    // ψ = (M_0/I)(1 − cos t)
    let want = 1.5 * (1.0 - 2f64.cos());
    assert!((y[0] - want).abs() < 1e-10, "{} vs {want}", y[0]);
}

#[test]
fn the_coordinate_singularity_is_reported_not_integrated() {
    let d = derivation();
    let model = DerivedModel::new(&d, &spec(explicit())).unwrap();
    // θ = 0 exactly: the solved φ̈ and ψ̈ divide by sin θ.
    let r = integrate(
        &DerivedSystem::<6>(&model),
        Method::Rk4,
        Step::Fixed(1e-3),
        0.0,
        [0.0, 0.0, 0.0, 0.0, 0.0, 50.0],
        0.1,
        Limits::default(),
        |_, _| Ok(()),
    );
    match r {
        Err(SimError::CoordinateSingularity { why, .. }) => {
            assert!(why.contains("sin(theta)"), "{why}")
        }
        other => panic!("expected a singularity, got {other:?}"),
    }
}

#[test]
fn bad_specifications_are_errors_naming_what_is_wrong() {
    let d = derivation();
    let mut s = spec(explicit());
    s.constants.remove("Ip");
    assert!(
        DerivedModel::new(&d, &s)
            .unwrap_err()
            .to_string()
            .contains("`Ip` has no value")
    );
    let s = spec(EquationsSpec::Explicit { step: "M".into() });
    assert!(
        DerivedModel::new(&d, &s)
            .unwrap_err()
            .to_string()
            .contains("not accelerations")
    );
    let s = spec(EquationsSpec::Explicit {
        step: "nope".into(),
    });
    assert!(
        DerivedModel::new(&d, &s)
            .unwrap_err()
            .to_string()
            .contains("no step named `nope`")
    );
    let model = DerivedModel::new(&d, &spec(explicit())).unwrap();
    let (_, mut named) = initial();
    named.remove("theta'");
    assert!(
        model
            .initial_state(&named)
            .unwrap_err()
            .to_string()
            .contains("`theta'` is missing")
    );
    named.insert("theta'".into(), f64::NAN);
    assert!(
        model
            .initial_state(&named)
            .unwrap_err()
            .to_string()
            .contains("not finite")
    );
}
