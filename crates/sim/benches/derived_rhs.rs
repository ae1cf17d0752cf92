//! One evaluation of the heavy top's right-hand side: the equations
//! `derivations/heavy-top.toml` derived (Eulerian angles, compiled with the
//! tape evaluator; the solved accelerations, and the mass-matrix form with
//! its 3 × 3 solve) against the hand-written models of the same top in
//! Eulerian angles and with a quaternion attitude, at the same physical
//! state (the bundled scene `docs/examples/sim-derived-heavy-top.toml`
//! moved to θ = 0.7 with all rates non-zero). Results in
//! `docs/performance.md`.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use hdot_sim::System;
use hdot_sim::nalgebra::Vector3;
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::systems::derived::DerivedSystem;
use hdot_sim::systems::euler_angles::quaternion_from_angles;
use hdot_sim::systems::free::pack;
use hdot_sim::systems::{EulerAngleBody, FreeBody, Gravity};

fn scene(mass_matrix: bool) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs/examples/sim-derived-heavy-top.toml");
    let mut text = std::fs::read_to_string(&path).expect("bundled scene");
    if mass_matrix {
        text = text.replace(
            "accelerations = \"accelerations\"",
            "mass_matrix = \"mass_matrix\"\nforcing = \"forcing\"\ncoordinates = [\"phi\", \"theta\", \"psi\"]",
        );
    }
    Scene::parse(&text, &path).expect("scene")
}

fn bench(c: &mut Criterion) {
    let (phi, theta, psi) = (0.3, 0.7, 0.2);
    let (phi_d, theta_d, psi_d) = (1.5, -0.8, 60.0);
    let y = [phi, theta, psi, phi_d, theta_d, psi_d];
    let mut g = c.benchmark_group("heavy top rhs");
    for (name, mm) in [
        ("derived, solved accelerations", false),
        ("derived, mass-matrix form", true),
    ] {
        let s = scene(mm);
        let SceneKind::Derived(ds) = &s.kind else {
            unreachable!("a derived scene")
        };
        let sys = DerivedSystem::<6>(&ds.model);
        g.bench_function(name, |b| b.iter(|| sys.rhs(0.0, black_box(&y))));
    }
    // The same state for the hand-written models: ω in body axes.
    let (m, l, grav) = (0.5, 0.05, 9.81);
    let (i_axis, i_trans) = (0.0004, 0.0014666666666666667);
    let w = Vector3::new(
        -phi_d * theta.sin() * psi.cos() + theta_d * psi.sin(),
        phi_d * theta.sin() * psi.sin() + theta_d * psi.cos(),
        psi_d + phi_d * theta.cos(),
    );
    let euler = EulerAngleBody {
        moments: [i_trans, i_trans, i_axis],
        weight_arm: m * grav * l,
    };
    let ye = [phi, theta, psi, w.x, w.y, w.z];
    g.bench_function("hand-written, Eulerian angles", |b| {
        b.iter(|| euler.rhs(0.0, black_box(&ye)))
    });
    let quat = FreeBody {
        moments: [i_trans, i_trans, i_axis],
        gravity: Some(Gravity {
            weight_arm: m * grav * l,
        }),
    };
    let yq = pack(&quaternion_from_angles(phi, theta, psi), &w);
    g.bench_function("hand-written, quaternion", |b| {
        b.iter(|| quat.rhs(0.0, black_box(&yq)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
