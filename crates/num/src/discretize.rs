//! Lazy discretisation of primitives into particles.
//!
//! Each primitive is a product of up to three parameter intervals (e.g.
//! r, θ, z for a cylinder) mapped to space; its density factor (the
//! Jacobian, e.g. `r`) is a product of one factor per parameter. Each
//! interval is cut into `cells` equal cells, with one node per cell
//! ([`Method::Midpoint`]) or `k` Gauss–Legendre nodes per cell
//! ([`Method::GaussLegendre`]); the particle at nodes `(i, j, l)` has mass
//! `m · w₁ᵢ · w₂ⱼ · w₃ₗ`, the 1-D weights (rule weight × density factor)
//! normalised to sum 1, so that a discretised body has exactly the mass
//! of the body. Parameters a primitive does not use (a plate's thickness)
//! have a single node.
//!
//! Only the 1-D node tables are stored (`O(N^{1/3})` numbers); particles
//! are generated on demand, block by block, by [`ParticleSource::visit`].
//! Summing 10⁸ particles therefore needs memory for one block per thread.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Vector3};

use crate::body::{Body, Composite, Part, Primitive};
use crate::cloud::ParticleCloud;
use crate::sums::{Block, LEAF, ParticleSource};

/// Quadrature per cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// One node at the centre of each cell (error O(h²)).
    Midpoint,
    /// `k` Gauss–Legendre nodes per cell (exact for polynomials of degree
    /// `2k − 1`; `k = 2` is exact for the quadratic integrands of inertia
    /// on boxes).
    GaussLegendre(usize),
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Method::Midpoint => write!(f, "midpoint"),
            Method::GaussLegendre(k) => write!(f, "gauss-legendre-{k}"),
        }
    }
}

/// A method and a number of cells per parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Discretization {
    /// Quadrature per cell.
    pub method: Method,
    /// Cells along each parameter (at least 1).
    pub cells: usize,
}

impl Discretization {
    /// Midpoint grid with `cells` cells per parameter.
    pub fn midpoint(cells: usize) -> Self {
        Self {
            method: Method::Midpoint,
            cells,
        }
    }
    /// `k`-point Gauss–Legendre per cell.
    pub fn gauss(cells: usize, k: usize) -> Self {
        Self {
            method: Method::GaussLegendre(k),
            cells,
        }
    }
    fn nodes_per_cell(&self) -> usize {
        match self.method {
            Method::Midpoint => 1,
            Method::GaussLegendre(k) => k.max(1),
        }
    }
}

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton on the Legendre
/// recurrence; accurate to round-off for k ≤ 64).
///
/// # Example
/// ```
/// let (x, w) = hdot_num::discretize::gauss_legendre(2);
/// assert!((x[1] - 1.0 / 3f64.sqrt()).abs() < 4.0 * f64::EPSILON);
/// assert!((w[0] + w[1] - 2.0).abs() < 4.0 * f64::EPSILON);
/// ```
pub fn gauss_legendre(k: usize) -> (Vec<f64>, Vec<f64>) {
    let k = k.max(1);
    let mut x = vec![0.0; k];
    let mut w = vec![0.0; k];
    for i in 0..k.div_ceil(2) {
        let mut z = (PI * (i as f64 + 0.75) / (k as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for j in 2..=k {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * z * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            let pk = if k == 1 { z } else { p1 };
            let pkm1 = if k == 1 { 1.0 } else { p0 };
            dp = k as f64 * (z * pk - pkm1) / (z * z - 1.0);
            let dz = pk / dp;
            z -= dz;
            if dz.abs() <= 1e-16 {
                break;
            }
        }
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        x[i] = -z;
        x[k - 1 - i] = z;
        w[i] = wi;
        w[k - 1 - i] = wi;
    }
    if k % 2 == 1 {
        x[k / 2] = 0.0;
    }
    (x, w)
}

/// Density factor of a parameter.
#[derive(Debug, Clone, Copy)]
enum Density {
    One,
    /// ∝ t (polar radius).
    Linear,
    /// ∝ t² (spherical radius).
    Square,
    /// ∝ sin t (polar angle).
    Sin,
    /// ∝ (c − t)² (cone cross-section at height t, apex at c).
    ConeSection(f64),
}

impl Density {
    fn at(self, t: f64) -> f64 {
        match self {
            Density::One => 1.0,
            Density::Linear => t,
            Density::Square => t * t,
            Density::Sin => t.sin(),
            Density::ConeSection(c) => (c - t) * (c - t),
        }
    }
}

/// A 1-D rule: nodes, their cosines and sines, normalised weights.
#[derive(Debug, Clone)]
struct Axis {
    t: Vec<f64>,
    cos: Vec<f64>,
    sin: Vec<f64>,
    w: Vec<f64>,
}

impl Axis {
    fn new(lo: f64, hi: f64, d: Density, disc: &Discretization, active: bool) -> Self {
        let (t, raw): (Vec<f64>, Vec<f64>) = if !active {
            (vec![lo], vec![1.0])
        } else {
            let n = disc.cells.max(1);
            let h = (hi - lo) / n as f64;
            let (gx, gw) = match disc.method {
                Method::Midpoint => (vec![0.0], vec![2.0]),
                Method::GaussLegendre(k) => gauss_legendre(k),
            };
            let mut t = Vec::with_capacity(n * gx.len());
            let mut w = Vec::with_capacity(n * gx.len());
            for c in 0..n {
                let mid = lo + (c as f64 + 0.5) * h;
                for (x, wx) in gx.iter().zip(&gw) {
                    let ti = mid + 0.5 * h * x;
                    t.push(ti);
                    w.push(0.5 * h * wx * d.at(ti));
                }
            }
            (t, w)
        };
        let total: f64 = pairwise(&raw);
        let w = raw.iter().map(|v| v / total).collect();
        Self {
            cos: t.iter().map(|v| v.cos()).collect(),
            sin: t.iter().map(|v| v.sin()).collect(),
            t,
            w,
        }
    }
    fn len(&self) -> usize {
        self.t.len()
    }
}

fn pairwise(v: &[f64]) -> f64 {
    if v.len() <= 8 {
        v.iter().sum()
    } else {
        let (a, b) = v.split_at(v.len() / 2);
        pairwise(a) + pairwise(b)
    }
}

/// How the three parameters map to a local point.
#[derive(Debug, Clone, Copy)]
enum Map {
    /// (u, v, w) → (u, v, w).
    Cartesian,
    /// (r, θ, z) → (r cos θ, r sin θ, z).
    Cylindrical,
    /// (r, θ polar, φ) → (r sin θ cos φ, r sin θ sin φ, r cos θ).
    Spherical,
    /// (s, θ, z) → (s ρ(z) cos θ, s ρ(z) sin θ, z), ρ = k (apex − z).
    Cone { apex: f64, k: f64 },
}

/// A posed primitive discretised lazily. Implements [`ParticleSource`].
#[derive(Debug, Clone)]
pub struct DiscretizedBody {
    mass: f64,
    rot: Matrix3<f64>,
    pos: Vector3<f64>,
    map: Map,
    axes: [Axis; 3],
}

impl DiscretizedBody {
    /// Discretises `body`.
    pub fn new(body: &Body, disc: &Discretization) -> Self {
        let d = disc;
        let (map, axes) = match *body.shape() {
            Primitive::Rod { length: l } => (
                Map::Cartesian,
                [
                    Axis::new(-l / 2.0, l / 2.0, Density::One, d, true),
                    Axis::new(0.0, 0.0, Density::One, d, false),
                    Axis::new(0.0, 0.0, Density::One, d, false),
                ],
            ),
            Primitive::Plate { a, b } => (
                Map::Cartesian,
                [
                    Axis::new(-a / 2.0, a / 2.0, Density::One, d, true),
                    Axis::new(-b / 2.0, b / 2.0, Density::One, d, true),
                    Axis::new(0.0, 0.0, Density::One, d, false),
                ],
            ),
            Primitive::Prism { a, b, c } => (
                Map::Cartesian,
                [
                    Axis::new(-a / 2.0, a / 2.0, Density::One, d, true),
                    Axis::new(-b / 2.0, b / 2.0, Density::One, d, true),
                    Axis::new(-c / 2.0, c / 2.0, Density::One, d, true),
                ],
            ),
            Primitive::Disk { radius } => (
                Map::Cylindrical,
                [
                    Axis::new(0.0, radius, Density::Linear, d, true),
                    Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                    Axis::new(0.0, 0.0, Density::One, d, false),
                ],
            ),
            Primitive::Cylinder { radius, length } => (
                Map::Cylindrical,
                [
                    Axis::new(0.0, radius, Density::Linear, d, true),
                    Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                    Axis::new(-length / 2.0, length / 2.0, Density::One, d, true),
                ],
            ),
            Primitive::HollowCylinder {
                inner,
                outer,
                length,
            } => (
                Map::Cylindrical,
                [
                    Axis::new(inner, outer, Density::Linear, d, outer > inner),
                    Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                    Axis::new(-length / 2.0, length / 2.0, Density::One, d, true),
                ],
            ),
            Primitive::Ring { radius } => (
                Map::Cylindrical,
                [
                    Axis::new(radius, radius, Density::One, d, false),
                    Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                    Axis::new(0.0, 0.0, Density::One, d, false),
                ],
            ),
            Primitive::Sphere { radius } => (
                Map::Spherical,
                [
                    Axis::new(0.0, radius, Density::Square, d, true),
                    Axis::new(0.0, PI, Density::Sin, d, true),
                    Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                ],
            ),
            Primitive::SphericalShell { radius } => (
                Map::Spherical,
                [
                    Axis::new(radius, radius, Density::One, d, false),
                    Axis::new(0.0, PI, Density::Sin, d, true),
                    Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                ],
            ),
            Primitive::Cone { radius, height } => {
                let apex = 0.75 * height;
                (
                    Map::Cone {
                        apex,
                        k: radius / height,
                    },
                    [
                        Axis::new(0.0, 1.0, Density::Linear, d, true),
                        Axis::new(0.0, 2.0 * PI, Density::One, d, true),
                        Axis::new(-0.25 * height, apex, Density::ConeSection(apex), d, true),
                    ],
                )
            }
        };
        Self {
            mass: body.mass(),
            rot: *body.pose().rotation_matrix().matrix(),
            pos: body.pose().position,
            map,
            axes,
        }
    }

    #[inline]
    fn local(&self, i: usize, j: usize, l: usize) -> Vector3<f64> {
        let [a, b, c] = &self.axes;
        match self.map {
            Map::Cartesian => Vector3::new(a.t[i], b.t[j], c.t[l]),
            Map::Cylindrical => Vector3::new(a.t[i] * b.cos[j], a.t[i] * b.sin[j], c.t[l]),
            Map::Spherical => {
                let rs = a.t[i] * b.sin[j];
                Vector3::new(rs * c.cos[l], rs * c.sin[l], a.t[i] * b.cos[j])
            }
            Map::Cone { apex, k } => {
                let rho = a.t[i] * k * (apex - c.t[l]);
                Vector3::new(rho * b.cos[j], rho * b.sin[j], c.t[l])
            }
        }
    }
}

impl ParticleSource for DiscretizedBody {
    fn len(&self) -> usize {
        self.axes.iter().map(Axis::len).product()
    }

    fn visit(&self, lo: usize, hi: usize, f: &mut dyn FnMut(Block<'_>)) {
        let mut bx = [0.0; LEAF];
        let mut by = [0.0; LEAF];
        let mut bz = [0.0; LEAF];
        let mut bm = [0.0; LEAF];
        let (n2, n3) = (self.axes[1].len(), self.axes[2].len());
        let mut start = lo;
        while start < hi {
            let end = (start + LEAF).min(hi);
            for (k, p) in (start..end).enumerate() {
                let i = p / (n2 * n3);
                let j = (p / n3) % n2;
                let l = p % n3;
                let w = self.pos + self.rot * self.local(i, j, l);
                bx[k] = w.x;
                by[k] = w.y;
                bz[k] = w.z;
                bm[k] = self.mass * self.axes[0].w[i] * self.axes[1].w[j] * self.axes[2].w[l];
            }
            let n = end - start;
            f(Block {
                x: &bx[..n],
                y: &by[..n],
                z: &bz[..n],
                m: &bm[..n],
            });
            start = end;
        }
    }
}

/// One part of a discretised composite.
#[derive(Debug, Clone)]
enum SourcePart<'a> {
    Body(Box<DiscretizedBody>),
    Cloud(&'a ParticleCloud),
}

impl SourcePart<'_> {
    fn as_source(&self) -> &dyn ParticleSource {
        match self {
            SourcePart::Body(b) => b.as_ref(),
            SourcePart::Cloud(c) => *c,
        }
    }
}

/// A composite discretised lazily: the parts' particles one after the
/// other (clouds as stored).
#[derive(Debug, Clone)]
pub struct DiscretizedComposite<'a> {
    parts: Vec<SourcePart<'a>>,
    offsets: Vec<usize>,
}

impl<'a> DiscretizedComposite<'a> {
    /// Discretises every primitive of `c` with `disc`.
    pub fn new(c: &'a Composite, disc: &Discretization) -> Self {
        let parts: Vec<SourcePart<'a>> = c
            .parts()
            .iter()
            .map(|p| match p {
                Part::Solid(b) => SourcePart::Body(Box::new(DiscretizedBody::new(b, disc))),
                Part::Cloud(c) => SourcePart::Cloud(c),
            })
            .collect();
        let mut offsets = vec![0];
        for p in &parts {
            offsets.push(offsets.last().copied().unwrap_or(0) + p.as_source().len());
        }
        Self { parts, offsets }
    }
}

impl ParticleSource for DiscretizedComposite<'_> {
    fn len(&self) -> usize {
        self.offsets.last().copied().unwrap_or(0)
    }
    /// Only the parts that overlap `lo..hi` are visited, found by a binary
    /// search of the offsets: a leaf costs O(log parts + its particles), so
    /// a sum over a composite of many parts is linear in its size (a scan
    /// of every part per leaf made it quadratic in the number of parts).
    fn visit(&self, lo: usize, hi: usize, f: &mut dyn FnMut(Block<'_>)) {
        // first part whose end lies beyond `lo`
        let first = self.offsets[1..].partition_point(|&end| end <= lo);
        for (k, p) in self.parts.iter().enumerate().skip(first) {
            let (a, b) = (self.offsets[k], self.offsets[k + 1]);
            if a >= hi {
                break;
            }
            let (s, e) = (lo.max(a), hi.min(b));
            if s < e {
                p.as_source().visit(s - a, e - a, f);
            }
        }
    }
}

/// Number of particles a discretisation of `shape` produces.
pub fn particle_count(shape: &Primitive, disc: &Discretization) -> usize {
    let per = disc.cells.max(1) * disc.nodes_per_cell();
    let dims = match shape {
        Primitive::Rod { .. } | Primitive::Ring { .. } => 1,
        Primitive::Plate { .. } | Primitive::Disk { .. } | Primitive::SphericalShell { .. } => 2,
        Primitive::HollowCylinder { inner, outer, .. } if inner == outer => 2,
        _ => 3,
    };
    per.pow(dims)
}
