//! Proptest strategies of random declared bodies (feature `proptest`), for
//! property tests of a derivation in a user's own crate.
//!
//! [`declared_bodies`] gives one particle cloud per `[[body]]` of a
//! derivation, each with that body's declared symmetry made exact by
//! copying particles (as `hdot verify` draws them: mirror images for
//! `principal` and `plane`, 3–6 turned copies for `axisymmetric`), in the
//! body's own axes about its reference point. Pass them to
//! [`super::check_bodies`], which draws the motions and binds the file's
//! symbols from the particle sums of exactly these particles:
//!
//! ```
//! use hdot_num::verify::{Options, check_bodies, strategy::declared_bodies};
//! use proptest::prelude::*;
//! use proptest::test_runner::{Config, TestRunner};
//!
//! let d = hdot_sym::derivation::load_str("spin.toml", r#"
//! title = "A spinning body"
//! source = "example"
//! [symbols]
//! constants = ["A", "B", "C"]
//! time = ["w_x", "w_y", "w_z"]
//! [[frame]]
//! name = "F"
//! angular_velocity = "[w_x, w_y, w_z]"
//! [[body]]
//! name = "body"
//! frame = "F"
//! point = "G"
//! inertia = "principal(A, B, C)"
//! symmetry = "principal"
//! [[step]]
//! name = "H"
//! value = "principal(A, B, C) * angvel(F)"
//! means = "angular_momentum(body, G)"
//! "#).unwrap();
//! let mut runner = TestRunner::new(Config { cases: 8, ..Config::default() });
//! runner
//!     .run(&(declared_bodies(&d), any::<u64>()), |(bodies, seed)| {
//!         let r = check_bodies(&d, &bodies, &Options { draws: 2, seed }).unwrap();
//!         prop_assert!(r.passed());
//!         Ok(())
//!     })
//!     .unwrap();
//! ```
//!
//! A body is either a cloud of 2–12 particles (which shrinks to fewer
//! particles and smaller coordinates) or one of the verifier's sampled
//! bodies (posed primitives, composites, coaxial stacks) picked by a seed.

use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::Symmetry;
use nalgebra::Vector3;
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::bodies::random_body;
use super::draw::{line_axes, on_axes, symmetric};
use crate::cloud::ParticleCloud;

/// A body with `symmetry` about the origin (its reference point).
pub fn body(symmetry: Symmetry) -> impl Strategy<Value = ParticleCloud> {
    let particle = (-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64, 0.1..5.0f64)
        .prop_map(|(x, y, z, m)| (Vector3::new(x, y, z), m));
    let cloud = prop::collection::vec(particle, 2..12)
        .prop_map(|ps| ParticleCloud::try_from_particles(ps).expect("finite positive masses"));
    let sampled = any::<u64>().prop_map(|seed| {
        random_body(&mut ChaCha8Rng::seed_from_u64(seed)).expect("the sampler makes valid bodies")
    });
    (prop_oneof![cloud, sampled], 3..=6usize).prop_map(move |(c, fold)| {
        symmetric(&c, symmetry, fold).expect("copies of a valid body are valid")
    })
}

/// One body per `[[body]]` of `d`, each with its declared symmetry (and
/// on the axis a moment of inertia declared zero requires: a slender
/// rod's `principal(Ip, Ip, 0)` is a line of particles along z).
pub fn declared_bodies(d: &Derivation) -> impl Strategy<Value = Vec<ParticleCloud>> {
    d.physics
        .bodies
        .iter()
        .map(|b| {
            let zero = line_axes(b);
            body(b.symmetry).prop_map(move |c| {
                on_axes(&c, zero).expect("a valid body moved onto its axis is valid")
            })
        })
        .collect::<Vec<_>>()
}
