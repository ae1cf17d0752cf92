//! One evaluation of the heavy top's right-hand side: the equations
//! `derivations/heavy-top.toml` derived (Eulerian angles, compiled with the
//! tape evaluator; the solved accelerations, and the mass-matrix form with
//! its 3 × 3 solve) against the hand-written models of the same top in
//! Eulerian angles and with a quaternion attitude, at the same physical
//! state (the bundled scene `docs/examples/sim-derived-heavy-top.toml`
//! moved to θ = 0.7 with all rates non-zero). Results in
//! `docs/performance.md`.
//!
//! Two modes: criterion (`cargo bench -p hdot-sim --bench derived_rhs`),
//! and a plain loop of one line for a CPU-time measure that a loaded
//! machine does not distort (`HDOT_RHS_LOOP=<line>` with the bench binary
//! under `perf stat -e task-clock`; `HDOT_RHS_LOOP=list` names the lines,
//! `HDOT_RHS_COUNT` changes the number of evaluations, 2 × 10⁷).

use std::hint::black_box;
use std::path::Path;
use std::rc::Rc;

use criterion::Criterion;
use hdot_sim::System;
use hdot_sim::nalgebra::Vector3;
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::systems::derived::{DerivedModel, DerivedSystem};
use hdot_sim::systems::euler_angles::quaternion_from_angles;
use hdot_sim::systems::free::pack;
use hdot_sim::systems::{EulerAngleBody, FreeBody, Gravity};

/// Evaluations per line in the CPU-time loop.
const LOOP: usize = 20_000_000;

fn model(mass_matrix: bool) -> Rc<DerivedModel> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs/examples/sim-derived-heavy-top.toml");
    let mut text = std::fs::read_to_string(&path).expect("bundled scene");
    if mass_matrix {
        text = text.replace(
            "accelerations = \"accelerations\"",
            "mass_matrix = \"mass_matrix\"\nforcing = \"forcing\"\ncoordinates = [\"phi\", \"theta\", \"psi\"]",
        );
    }
    let SceneKind::Derived(ds) = Scene::parse(&text, &path).expect("scene").kind else {
        unreachable!("a derived scene")
    };
    ds.model
}

/// Where the lines go: criterion's group, or the one line looped.
enum Mode<'c> {
    Criterion(criterion::BenchmarkGroup<'c, criterion::measurement::WallTime>),
    Loop { line: String, found: bool },
}

impl Mode<'_> {
    /// Measures one line (monomorphised: no call through a pointer that
    /// the models' own calls do not pay).
    fn line<R>(&mut self, name: &str, f: impl Fn() -> R) {
        match self {
            Mode::Criterion(g) => {
                g.bench_function(name, |b| b.iter(&f));
            }
            Mode::Loop { line, found } => {
                if line == name {
                    *found = true;
                    let count = std::env::var("HDOT_RHS_COUNT")
                        .ok()
                        .and_then(|c| c.parse().ok())
                        .unwrap_or(LOOP);
                    for _ in 0..count {
                        black_box(f());
                    }
                } else if line == "list" {
                    eprintln!("{name}");
                }
            }
        }
    }
}

fn lines(mode: &mut Mode<'_>) {
    let (phi, theta, psi) = (0.3, 0.7, 0.2);
    let (phi_d, theta_d, psi_d) = (1.5, -0.8, 60.0);
    let y = [phi, theta, psi, phi_d, theta_d, psi_d];
    for (name, mm) in [
        ("derived, solved accelerations", false),
        ("derived, mass-matrix form", true),
    ] {
        let m = model(mm);
        let sys = DerivedSystem::<6>(&m);
        mode.line(name, || sys.rhs(0.0, black_box(&y)));
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
    mode.line("hand-written, Eulerian angles", || {
        euler.rhs(0.0, black_box(&ye))
    });
    let quat = FreeBody {
        moments: [i_trans, i_trans, i_axis],
        gravity: Some(Gravity {
            weight_arm: m * grav * l,
        }),
    };
    let yq = pack(&quaternion_from_angles(phi, theta, psi), &w);
    mode.line("hand-written, quaternion", || quat.rhs(0.0, black_box(&yq)));
}

fn main() {
    if let Ok(line) = std::env::var("HDOT_RHS_LOOP") {
        let mut mode = Mode::Loop { line, found: false };
        lines(&mut mode);
        if let Mode::Loop { line, found: false } = mode
            && line != "list"
        {
            eprintln!("HDOT_RHS_LOOP: no line `{line}` (HDOT_RHS_LOOP=list names them)");
            std::process::exit(2);
        }
        return;
    }
    let mut c = Criterion::default().configure_from_args();
    {
        let mut mode = Mode::Criterion(c.benchmark_group("heavy top rhs"));
        lines(&mut mode);
        if let Mode::Criterion(g) = mode {
            g.finish();
        }
    }
    c.final_summary();
}
