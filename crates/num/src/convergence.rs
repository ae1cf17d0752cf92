//! Convergence of discretised mass properties, the cheapest discretisation
//! meeting a tolerance, and the charts of error against cost.
//!
//! The error of a discretisation is the relative Frobenius error of its
//! inertia tensor about G against the analytic tensor,
//! `‖I_h − I‖_F / ‖I‖_F`. The midpoint grid converges like `h²`
//! (`h ∝ 1/cells`); Gauss–Legendre with `k` points per cell like `h^{2k}`
//! on smooth integrands, and is exact on boxes for `k ≥ 2`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::body::{Body, Pose, Primitive};
use crate::chart::{ChartError, Series, loglog_chart_into};
use crate::discretize::{Discretization, DiscretizedBody, Method, particle_count};
use crate::fsio::Batch;
use crate::sums::{ParticleSource, mass_properties};

/// One discretisation and how well it did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvergencePoint {
    /// The discretisation.
    pub disc: Discretization,
    /// Number of particles.
    pub particles: usize,
    /// Relative Frobenius error of the inertia about G.
    pub error: f64,
    /// Wall-clock seconds of the sums (mass properties, two passes; best
    /// of several runs).
    pub seconds: f64,
}

/// The methods compared by default: midpoint, 2- and 3-point
/// Gauss–Legendre.
pub const METHODS: [Method; 3] = [
    Method::Midpoint,
    Method::GaussLegendre(2),
    Method::GaussLegendre(3),
];

/// Relative error of `disc` on a unit-mass `shape`.
pub fn error_of(shape: &Primitive, disc: &Discretization) -> ConvergencePoint {
    let body = Body::try_new(*shape, 1.0, Pose::identity()).expect("caller passes a valid shape");
    let exact = body.mass_properties();
    let src = DiscretizedBody::new(&body, disc);
    // best of a few runs (at least 3, until 20 ms are spent), so that the
    // time axis is not dominated by warm-up at small sizes
    let mut seconds = f64::INFINITY;
    let mut spent = 0.0;
    let mut runs = 0;
    let mut p = None;
    while runs < 3 || (spent < 0.02 && runs < 50) {
        let t = Instant::now();
        p = Some(mass_properties(&src).expect("non-empty discretisation"));
        let dt = t.elapsed().as_secs_f64();
        seconds = seconds.min(dt);
        spent += dt;
        runs += 1;
    }
    let p = p.expect("ran at least once");
    let error =
        (p.inertia_g.matrix() - exact.inertia_g.matrix()).norm() / exact.inertia_g.matrix().norm();
    ConvergencePoint {
        disc: *disc,
        particles: src.len(),
        error,
        seconds,
    }
}

/// Cells tried by the sweeps: 1, 2, 3, 4, 6, 8, 12, 16, … (×√2 roughly).
pub fn cell_ladder() -> impl Iterator<Item = usize> {
    (0..).map(|k: u32| {
        let base = 1usize << (k / 2);
        if k.is_multiple_of(2) {
            base
        } else {
            base + base / 2
        }
    })
}

/// Errors of `method` on `shape` for growing resolution, up to
/// `max_particles`, stopping once the error reaches round-off.
pub fn sweep(shape: &Primitive, method: Method, max_particles: usize) -> Vec<ConvergencePoint> {
    let mut out = Vec::new();
    for cells in cell_ladder().step_by(2) {
        let disc = Discretization { method, cells };
        if particle_count(shape, &disc) > max_particles {
            break;
        }
        let p = error_of(shape, &disc);
        let done = p.error < 1e-14;
        out.push(p);
        if done {
            break;
        }
    }
    out
}

/// Observed order of convergence between successive points of a sweep,
/// `log(e₁/e₂) / log(n₂/n₁)` with `n` the cells per parameter; `None`
/// where an error is at round-off.
pub fn observed_orders(points: &[ConvergencePoint]) -> Vec<Option<f64>> {
    points
        .windows(2)
        .map(|w| {
            let (a, b) = (&w[0], &w[1]);
            if a.error < 1e-13 || b.error < 1e-13 {
                None
            } else {
                Some((a.error / b.error).ln() / (b.disc.cells as f64 / a.disc.cells as f64).ln())
            }
        })
        .collect()
}

/// The discretisation with the fewest particles whose error is at most
/// `tol`, over `methods` and the rungs of [`cell_ladder`], within
/// `max_particles`.
///
/// # Example
/// ```
/// use hdot_num::{Primitive, convergence::{cheapest_meeting, METHODS}};
/// let p = cheapest_meeting(&Primitive::Prism { a: 1.0, b: 2.0, c: 3.0 }, 1e-12, &METHODS, 1_000_000).unwrap();
/// // Gauss–Legendre with 2 points in one cell is exact on a box: 8 particles
/// assert_eq!(p.particles, 8);
/// ```
pub fn cheapest_meeting(
    shape: &Primitive,
    tol: f64,
    methods: &[Method],
    max_particles: usize,
) -> Option<ConvergencePoint> {
    let mut best: Option<ConvergencePoint> = None;
    for &method in methods {
        for cells in cell_ladder() {
            let disc = Discretization { method, cells };
            let n = particle_count(shape, &disc);
            if n > max_particles || best.is_some_and(|b| n >= b.particles) {
                break;
            }
            let p = error_of(shape, &disc);
            if p.error <= tol {
                best = Some(p);
                break;
            }
        }
    }
    best
}

/// The primitives with the dimensions used for the bundled charts.
pub fn bundled_primitives() -> Vec<Primitive> {
    vec![
        Primitive::Rod { length: 2.0 },
        Primitive::Plate { a: 1.2, b: 0.8 },
        Primitive::Prism {
            a: 1.2,
            b: 0.8,
            c: 0.5,
        },
        Primitive::Disk { radius: 0.7 },
        Primitive::Cylinder {
            radius: 0.4,
            length: 1.5,
        },
        Primitive::HollowCylinder {
            inner: 0.3,
            outer: 0.5,
            length: 1.0,
        },
        Primitive::Ring { radius: 0.9 },
        Primitive::Sphere { radius: 0.6 },
        Primitive::SphericalShell { radius: 0.6 },
        Primitive::Cone {
            radius: 0.5,
            height: 1.2,
        },
    ]
}

/// Sweeps of every method on one primitive.
#[derive(Debug, Clone)]
pub struct PrimitiveSweeps {
    /// The primitive.
    pub shape: Primitive,
    /// One sweep per method.
    pub sweeps: Vec<(Method, Vec<ConvergencePoint>)>,
}

/// Writes `<dir>/<shape>-error-vs-particles.{svg,png}` and
/// `<dir>/<shape>-error-vs-time.{svg,png}`; returns the stems written.
pub fn write_charts(dir: &Path, s: &PrimitiveSweeps) -> Result<Vec<PathBuf>, ChartError> {
    let mut batch = Batch::new();
    let stems = stage_charts(&mut batch, dir, s)?;
    batch.commit().map_err(|source| ChartError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    Ok(stems)
}

/// As [`write_charts`], but stages the files in `batch` (to appear with
/// the other files of the command, or not at all).
pub fn stage_charts(
    batch: &mut Batch,
    dir: &Path,
    s: &PrimitiveSweeps,
) -> Result<Vec<PathBuf>, ChartError> {
    let name = s.shape.name().replace('_', "-");
    let series = |f: &dyn Fn(&ConvergencePoint) -> f64| -> Vec<Series> {
        s.sweeps
            .iter()
            .map(|(m, pts)| {
                Series::new(m.to_string(), pts.iter().map(|p| (f(p), p.error)).collect())
            })
            .collect()
    };
    let a = dir.join(format!("{name}-error-vs-particles"));
    loglog_chart_into(
        batch,
        &a,
        &format!("{}: relative error of the inertia tensor", s.shape.name()),
        "particles",
        "relative error ‖I_h − I‖ / ‖I‖",
        &series(&|p| p.particles as f64),
    )?;
    let b = dir.join(format!("{name}-error-vs-time"));
    loglog_chart_into(
        batch,
        &b,
        &format!("{}: relative error against time", s.shape.name()),
        "seconds (mass properties by particle sums)",
        "relative error ‖I_h − I‖ / ‖I‖",
        &series(&|p| p.seconds.max(1e-9)),
    )?;
    Ok(vec![a, b])
}
