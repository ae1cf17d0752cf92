//! The rate of a body's energy measured on its particles: Σ m v · (a − g),
//! the rate of its kinetic energy Σ ½ m v² plus the weight's potential
//! energy −Σ m g · r about a fixed point (with no `gravity`, g = 0). The
//! power balance of Kane's equations, dE/dt = Σ u_r K_r, is compared with
//! it (`energy_rate(system) - u_1*(…) - …`).

use hdot_sym::derivation::physics::{Arg, Bodies};

use super::quantities::{Measured, Out};
use super::world::World;

/// `energy_rate(body)`: Σ m v · (a − g), and the magnitudes it sums,
/// Σ m |v| (|a| + |g|).
pub(super) fn energy_rate(w: &World<'_>, a: &[Arg]) -> Out {
    let Arg::Body(b) = &a[0] else {
        unreachable!("validated by hdot-sym")
    };
    let b: Bodies = *b;
    let g = w.gravity;
    let (mut e, mut s) = (0.0, 0.0);
    for p in w.particles(b) {
        e += p.m * p.r[1].dot(&(p.r[2] - g));
        s += p.m * p.mag[1] * (p.mag[2] + g.norm());
    }
    Ok((Measured::Scalar(e), s))
}
