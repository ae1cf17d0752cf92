//! Our DOP853 against the `ode_solvers` crate's Dop853 at equal error, on the
//! torque-free body of issue 5 (I = (0.6, 0.8, 1.0), H = (1.8, 0.4, −0.9),
//! T = 100), both solvers given the same right-hand side: Euler's equations
//! (ω, 3 components); the precession-angle model (ω and the angle about H,
//! 4 components) with our projection onto the invariants against ode_solvers
//! (which cannot project), and without projection on both sides; the
//! quaternion form (7 components).
//!
//! `ode_solvers` runs with sparse output (its dense output has known bugs);
//! we read its last stored state. Each solver's tolerance is chosen so that
//! its error at T, measured against the exact elliptic solution (attitude as
//! a rotation angle and |Δω|, combined; ω alone for Euler's equations), matches
//! ours at the target tolerance (ode_solvers' tolerance scanned in steps of
//! 10^(1/8); the first one at or below our error is used). The matched
//! errors and evaluation counts are printed before the timings.

use criterion::{Criterion, black_box, criterion_group, criterion_main};
use hdot_sim::exact::TorqueFree;
use hdot_sim::nalgebra::{UnitQuaternion, Vector3};
use hdot_sim::systems::free::{EulerEquations, pack, state_error};
use hdot_sim::systems::{FreeBody, PrecessionAngle};
use hdot_sim::{Limits, Method, Step, System, integrate};
use ode_solvers::{Dop853, OutputType, SVector};

const T: f64 = 100.0;
const MOMENTS: [f64; 3] = [0.6, 0.8, 1.0];

struct Theirs<const N: usize, S>(S);

impl<const N: usize, S: System<N>> ode_solvers::System<f64, SVector<f64, N>> for Theirs<N, S> {
    fn system(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        let mut a = [0.0; N];
        a.copy_from_slice(y.as_slice());
        let d = self.0.rhs(t, &a);
        dy.copy_from_slice(&d);
    }
}

fn theirs<const N: usize, S: System<N> + Copy>(sys: S, y0: [f64; N], tol: f64) -> ([f64; N], u32) {
    let mut stepper = Dop853::new(
        Theirs(sys),
        0.0,
        T,
        T,
        SVector::<f64, N>::from(y0),
        tol,
        tol,
    );
    stepper.set_output(OutputType::Sparse);
    let stats = stepper.integrate().expect("ode_solvers integrates");
    let last = stepper.y_out().last().expect("a stored state");
    let mut y = [0.0; N];
    y.copy_from_slice(last.as_slice());
    (y, stats.num_eval)
}

fn ours<const N: usize, S: System<N>>(sys: &S, y0: [f64; N], tol: f64) -> ([f64; N], u64) {
    let (y, s) = integrate(
        sys,
        Method::Dop853,
        Step::Tolerance(tol),
        0.0,
        y0,
        T,
        Limits::default(),
        |_, _| Ok(()),
    )
    .expect("integrates");
    (y, s.evaluations)
}

/// ode_solvers' tolerance whose error first reaches `target`.
fn matching_tol<const N: usize, S: System<N> + Copy>(
    sys: S,
    y0: [f64; N],
    err: &impl Fn(&[f64; N]) -> f64,
    target: f64,
) -> f64 {
    let mut tol: f64 = 1e-6;
    while tol > 1e-15 {
        let (y, _) = theirs(sys, y0, tol);
        if err(&y) <= target {
            return tol;
        }
        tol /= 10f64.powf(0.125);
    }
    tol
}

/// Times ours (`mine`, at `our_tol`) against ode_solvers (`their`, the same
/// right-hand side, at the tolerance giving the same error or less).
#[allow(clippy::too_many_arguments)]
fn compare<const N: usize, S: System<N> + Copy>(
    c: &mut Criterion,
    name: &str,
    mine: S,
    their: S,
    y0: [f64; N],
    our_tol: f64,
    err: impl Fn(&[f64; N]) -> f64,
) {
    let (y, evals) = ours(&mine, y0, our_tol);
    let e_ours = err(&y);
    let their_tol = matching_tol(their, y0, &err, e_ours);
    let (y2, evals2) = theirs(their, y0, their_tol);
    eprintln!(
        "{name}: ours tol {our_tol:e} error {e_ours:.3e} evaluations {evals}; \
         ode_solvers tol {their_tol:.3e} error {:.3e} evaluations {evals2}",
        err(&y2)
    );
    let mut g = c.benchmark_group(name);
    g.bench_function("hdot-sim dop853", |b| {
        b.iter(|| ours(&mine, black_box(y0), our_tol))
    });
    g.bench_function("ode_solvers Dop853", |b| {
        b.iter(|| theirs(their, black_box(y0), their_tol))
    });
    g.finish();
}

fn bench(c: &mut Criterion) {
    let w0 = Vector3::new(1.8 / 0.6, 0.4 / 0.8, -0.9 / 1.0);
    let q0 = UnitQuaternion::identity();
    let exact = TorqueFree::new(MOMENTS, q0, w0).unwrap().state(T);

    // ω alone: the error is |Δω|.
    let euler = EulerEquations { moments: MOMENTS };
    compare(c, "euler-equations", euler, euler, w0.into(), 1e-10, |w| {
        (0..3)
            .map(|k| (w[k] - exact[k + 4]).powi(2))
            .sum::<f64>()
            .sqrt()
    });

    // The rest: the error is state_error(..).combined() on the full attitude
    // and ω (rotation angle, |Δω|) against the exact elliptic solution.
    let full = |y: &[f64; 7]| state_error(y, &exact).combined();

    // The claimed configuration: the precession-angle model with projection
    // (ours) against ode_solvers on the same right-hand side (it cannot
    // project) at equal error.
    let (projected, z0) = PrecessionAngle::new(MOMENTS, &q0, &w0).unwrap();
    let mut plain = projected;
    plain.projection = false;
    let on_full = |z: &[f64; 4]| full(&plain.full_state(z));
    compare(c, "precession-angle", projected, plain, z0, 1e-10, on_full);

    // Like for like: the same model, neither solver projecting.
    compare(
        c,
        "precession-angle-unprojected",
        plain,
        plain,
        z0,
        1e-10,
        on_full,
    );

    // The quaternion form (7 components).
    let body = FreeBody {
        moments: MOMENTS,
        gravity: None,
    };
    compare(
        c,
        "quaternion-form",
        body,
        body,
        pack(&q0, &w0),
        3e-11,
        full,
    );
}
criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = bench
}
criterion_main!(benches);
