//! A body at one instant: its particles (placed in its own axes once per
//! draw) and the motion that carries them, read as `r = r_P + R q`; the
//! particle sums a moment about a point is formed from ([`CloudMoments`]);
//! the particles of consecutive bodies as one iterator.

use nalgebra::{Matrix3, Vector3};

use super::jet::{MatJet, PointJet};
use crate::ParticleCloud;

/// One particle at the instant, placed as it is read: `r = r_P + R q`
/// from its body's [`Placed`] and its position `q` in the body.
#[derive(Clone, Copy, Debug)]
pub struct Particle<'w> {
    /// Mass.
    pub m: f64,
    /// Position, velocity, acceleration (N's axes).
    pub r: [Vector3<f64>; 3],
    /// Magnitudes of the terms of each.
    pub mag: [f64; 3],
    /// Position in the body (its axes, about its reference point).
    q: Vector3<f64>,
    body: &'w Placed<'w>,
}

impl Particle<'_> {
    /// The virtual displacement `δr` for the world's `k`th coordinate
    /// (see [`World::build`](super::world::World::build)).
    pub fn dr(&self, k: usize) -> Vector3<f64> {
        self.body.dr[k]
            .iter()
            .fold(Vector3::zeros(), |s, (c, dref, partial)| {
                s + *c * (dref + partial * self.q)
            })
    }
}

/// One term `c · (∂r_P/∂x + ∂R/∂x q)` of a particle's virtual
/// displacement: `c` the coordinate x's share ([`displacement`](super::world::displacement)), the
/// reference point's and the attitude's partials in x.
pub(super) type DisplacementTerm = (f64, Vector3<f64>, Matrix3<f64>);

/// A body at the instant: its particles (placed once, in its own axes, by
/// the draw) and the motion that carries them — the reference point's jet
/// and the frame's attitude jet. A world is built for every value a
/// linearisation or a sign measures (tens of thousands per file), so the
/// particles are not placed in N's axes until a quantity reads them.
#[derive(Debug)]
pub struct Placed<'d> {
    pub(super) cloud: &'d ParticleCloud,
    /// Its particle sums (made once per draw).
    pub(super) moments: &'d CloudMoments,
    /// The reference point's jet.
    pub(super) reference: PointJet,
    /// The frame's attitude jet.
    pub(super) frame: MatJet,
    /// Frobenius norms of the attitude jet's first three orders.
    pub(super) norms: [f64; 3],
    /// For each of the world's coordinates, the terms its displacement
    /// sums.
    pub(super) dr: Vec<Vec<DisplacementTerm>>,
}

/// A body's partial velocity for one speed ([`super::partials`]):
/// `δv = δv_P + δṘ q` of each particle, the body in the model with the
/// speed raised less the body in the model at the drawn speeds (two models
/// of one instant and one draw), and the magnitudes of δv, `e + f |q|`:
/// the reference point's and the attitude's summed over the two models.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PartialVelocity {
    dv: Vector3<f64>,
    dr: Matrix3<f64>,
    e: f64,
    f: f64,
}

impl PartialVelocity {
    /// The body `raised` less the body `base`.
    pub(crate) fn of(raised: &Placed<'_>, base: &Placed<'_>) -> PartialVelocity {
        PartialVelocity {
            dv: raised.reference.r[1] - base.reference.r[1],
            dr: raised.frame[1] - base.frame[1],
            e: raised.reference.mag[1] + base.reference.mag[1],
            f: raised.norms[1] + base.norms[1],
        }
    }
}

impl<'d> Placed<'d> {
    /// The number of particles.
    pub fn len(&self) -> usize {
        self.cloud.len()
    }

    /// Whether the body has no particles (never: a cloud is non-empty).
    pub fn is_empty(&self) -> bool {
        self.cloud.len() == 0
    }

    /// `Σ m (r − r_O) × r⁽ᴼᴿᴰᴱᴿ⁾` over the body's particles (the
    /// moment about O of their momenta, ORDER 1, or of their mass times
    /// acceleration, ORDER 2) and the sum of the magnitudes of its terms
    /// `Σ m (|r|ₘ + |r_O|ₘ) |r⁽ᴼᴿᴰᴱᴿ⁾|ₘ`, each particle's magnitudes
    /// those of [`Particle::mag`]. With `r = r_P + R q` and
    /// `r⁽ⁿ⁾ = r_P⁽ⁿ⁾ + R⁽ⁿ⁾ q`, `d = r_P − r_O`:
    /// `Σ m (d + R q) × (a + A q) = M d × a + d × A S + R S × a + Σ m (R q) × (A q)`,
    /// the last term read off `K = R J Aᵀ` (`J = Σ m q qᵀ`) as
    /// `(K_yz − K_zy, K_zx − K_xz, K_xy − K_yx)` — the particles' own sum,
    /// regrouped ([`CloudMoments`]).
    pub fn moment_about<const ORDER: usize>(&self, o: &PointJet) -> (Vector3<f64>, f64) {
        let s = self.moments;
        let d = self.reference.r[0] - o.r[0];
        let a = self.reference.r[ORDER];
        let (r, am) = (&self.frame[0], &self.frame[ORDER]);
        let k = r * s.second * am.transpose();
        let own = Vector3::new(
            k[(1, 2)] - k[(2, 1)],
            k[(2, 0)] - k[(0, 2)],
            k[(0, 1)] - k[(1, 0)],
        );
        let v = d.cross(&a) * s.mass + d.cross(&(am * s.first)) + (r * s.first).cross(&a) + own;
        let (c0, n0) = (self.reference.mag[0] + o.mag[0], self.norms[0]);
        let (cn, nn) = (self.reference.mag[ORDER], self.norms[ORDER]);
        let mag = c0 * cn * s.mass + (c0 * nn + n0 * cn) * s.distance[0] + n0 * nn * s.distance[1];
        (v, mag)
    }

    /// `Σ m δv` over the body's particles, `δv = v⁺ − v` each particle's
    /// partial velocity ([`PartialVelocity`]), and `Σ m |δv|ₘ` with each
    /// particle's magnitudes those of [`Particle::mag`] summed over the two
    /// models. With `δv = δv_P + δṘ q` the sum is `M δv_P + δṘ S`
    /// ([`CloudMoments`]).
    pub(crate) fn partial_momentum(&self, p: &PartialVelocity) -> (Vector3<f64>, f64) {
        let s = self.moments;
        (
            p.dv * s.mass + p.dr * s.first,
            p.e * s.mass + p.f * s.distance[0],
        )
    }

    /// `Σ m r⁽ᴼᴿᴰᴱᴿ⁾ · δv` over the body's particles, `r⁽ᴼᴿᴰᴱᴿ⁾` in this
    /// model and `δv` as in [`Placed::partial_momentum`], and the sum of
    /// the magnitudes of its terms `Σ m |r⁽ᴼᴿᴰᴱᴿ⁾|ₘ |δv|ₘ`. With
    /// `r⁽ᴼᴿᴰᴱᴿ⁾ = a + A q` and `δv = b + B q`:
    /// `M a·b + a·(B S) + b·(A S) + Σ m (A q)·(B q)`, the last term
    /// `Σ_ij (A J)_ij B_ij` (`J = Σ m q qᵀ`) — the particles' own sum,
    /// regrouped.
    pub(crate) fn partial_power<const ORDER: usize>(&self, p: &PartialVelocity) -> (f64, f64) {
        let s = self.moments;
        let (a, am) = (self.reference.r[ORDER], &self.frame[ORDER]);
        let (b, bm) = (p.dv, p.dr);
        let own = (am * s.second).component_mul(&bm).sum();
        let v = a.dot(&b) * s.mass + a.dot(&(bm * s.first)) + b.dot(&(am * s.first)) + own;
        let (c, d) = (self.reference.mag[ORDER], self.norms[ORDER]);
        let (e, f) = (p.e, p.f);
        let mag = c * e * s.mass + (c * f + d * e) * s.distance[0] + d * f * s.distance[1];
        (v, mag)
    }

    /// The particles, placed at the instant.
    pub fn particles(&self) -> Particles<'_> {
        Particles {
            bodies: std::slice::from_ref(self),
            next: 0,
        }
    }

    /// Particle `k`, placed at the instant.
    #[inline(always)]
    fn particle(&self, k: usize) -> Particle<'_> {
        let (q, m) = self.cloud.particle(k);
        let (reference, rj, norms) = (&self.reference, &self.frame, &self.norms);
        let size = q.norm();
        Particle {
            m,
            r: std::array::from_fn(|n| reference.r[n] + rj[n] * q),
            mag: std::array::from_fn(|n| reference.mag[n] + norms[n] * size),
            q,
            body: self,
        }
    }
}

/// The sums over a body's particles (its own axes, about its reference
/// point) that a moment about a point is formed from: Σ m, Σ m q,
/// Σ m q qᵀ, and the sums of the particles' distances Σ m |q|, Σ m |q|².
/// A rigid body's particles are `r = r_P + R q`, so a sum bilinear in
/// them (`Σ m (r − r_O) × r⁽ⁿ⁾`) is a function of these five sums and
/// the motion: made once per draw, a moment on each of a linearisation's
/// thousands of worlds is a few dozen products instead of a pass over the
/// particles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CloudMoments {
    mass: f64,
    first: Vector3<f64>,
    second: Matrix3<f64>,
    /// Σ m |q|, Σ m |q|².
    distance: [f64; 2],
}

impl CloudMoments {
    /// The sums over `cloud`'s particles.
    pub(crate) fn of(cloud: &ParticleCloud) -> CloudMoments {
        let mut s = CloudMoments {
            mass: 0.0,
            first: Vector3::zeros(),
            second: Matrix3::zeros(),
            distance: [0.0; 2],
        };
        for k in 0..cloud.len() {
            let (q, m) = cloud.particle(k);
            let mq = q * m;
            s.mass += m;
            s.first += mq;
            s.second += mq * q.transpose();
            s.distance[0] += m * q.norm();
            s.distance[1] += m * q.norm_squared();
        }
        s
    }
}

/// The particles of consecutive bodies, each placed as it is read.
#[derive(Clone, Debug)]
pub struct Particles<'w> {
    pub(super) bodies: &'w [Placed<'w>],
    /// The next particle of `bodies[0]`.
    pub(super) next: usize,
}

impl<'w> Iterator for Particles<'w> {
    type Item = Particle<'w>;

    #[inline]
    fn next(&mut self) -> Option<Particle<'w>> {
        loop {
            let (b, rest) = self.bodies.split_first()?;
            if self.next < b.len() {
                self.next += 1;
                return Some(b.particle(self.next - 1));
            }
            self.bodies = rest;
            self.next = 0;
        }
    }

    #[inline]
    fn fold<A, F: FnMut(A, Particle<'w>) -> A>(self, init: A, mut f: F) -> A {
        let mut acc = init;
        let mut from = self.next;
        for b in self.bodies {
            for k in from..b.len() {
                acc = f(acc, b.particle(k));
            }
            from = 0;
        }
        acc
    }
}
