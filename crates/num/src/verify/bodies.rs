//! Random bodies and states, and the symmetries the derivations assume
//! (made exact to round-off by copying particles, not by choosing shapes).

use std::f64::consts::PI;

use nalgebra::{Rotation3, UnitQuaternion, Vector3};
use rand::Rng;

use crate::body::{Body, Composite, Part, Pose, Primitive};
use crate::cloud::ParticleCloud;
use crate::discretize::{Discretization, DiscretizedBody, DiscretizedComposite};
use crate::error::BodyError;

/// A random body in world coordinates, as particles: a cloud of 5–40
/// particles, a coarsely discretised posed primitive, a composite of two
/// or three parts, or a stack of coaxial primitives along the world z axis.
pub fn random_body(rng: &mut impl Rng) -> Result<ParticleCloud, BodyError> {
    let disc = Discretization::gauss(2, 2);
    match rng.gen_range(0..4) {
        0 => random_cloud(rng),
        1 => {
            let b = random_posed(rng)?;
            ParticleCloud::collect_from(&DiscretizedBody::new(&b, &disc))
        }
        2 => {
            let n = rng.gen_range(2..=3);
            let mut parts = Vec::with_capacity(n);
            for _ in 0..n {
                parts.push(if rng.gen_bool(0.25) {
                    Part::Cloud(random_cloud(rng)?)
                } else {
                    Part::Solid(random_posed(rng)?)
                });
            }
            let c = Composite::try_new(parts)?;
            ParticleCloud::collect_from(&DiscretizedComposite::new(&c, &disc))
        }
        _ => {
            let c = random_stack(rng)?;
            ParticleCloud::collect_from(&DiscretizedComposite::new(&c, &disc))
        }
    }
}

/// A cloud of 5–40 particles within 2 of the origin, masses in (0.1, 5).
pub fn random_cloud(rng: &mut impl Rng) -> Result<ParticleCloud, BodyError> {
    let n = rng.gen_range(5..=40);
    let ps: Vec<_> = (0..n)
        .map(|_| (random_vector(rng, 2.0), rng.gen_range(0.1..5.0)))
        .collect();
    ParticleCloud::try_from_particles(ps)
}

fn random_shape(rng: &mut impl Rng, kind: usize) -> Primitive {
    let mut d = || rng.gen_range(0.1..3.0);
    let (a, b, c) = (d(), d(), d());
    match kind {
        0 => Primitive::Rod { length: a },
        1 => Primitive::Plate { a, b },
        2 => Primitive::Prism { a, b, c },
        3 => Primitive::Disk { radius: a },
        4 => Primitive::Cylinder {
            radius: a,
            length: b,
        },
        5 => Primitive::HollowCylinder {
            inner: a.min(b) * 0.5,
            outer: a.max(b),
            length: c,
        },
        6 => Primitive::Ring { radius: a },
        7 => Primitive::Sphere { radius: a },
        8 => Primitive::SphericalShell { radius: a },
        _ => Primitive::Cone {
            radius: a,
            height: b,
        },
    }
}

fn random_posed(rng: &mut impl Rng) -> Result<Body, BodyError> {
    let kind = rng.gen_range(0..10);
    let shape = random_shape(rng, kind);
    let mass = rng.gen_range(0.1..10.0);
    let pose = Pose {
        position: random_vector(rng, 3.0),
        rotation: UnitQuaternion::from_rotation_matrix(&random_rotation(rng)),
    };
    Body::try_new(shape, mass, pose)
}

/// One to three primitives with an axis of symmetry (disk, cylinder, tube,
/// ring, sphere, shell, cone), on the world z axis at random heights,
/// turned about it by random angles (a rotor).
fn random_stack(rng: &mut impl Rng) -> Result<Composite, BodyError> {
    let n = rng.gen_range(1..=3);
    let mut parts = Vec::with_capacity(n);
    for _ in 0..n {
        let kind = rng.gen_range(3..10);
        let shape = random_shape(rng, kind);
        let mass = rng.gen_range(0.1..10.0);
        let pose = Pose {
            position: Vector3::new(0.0, 0.0, rng.gen_range(-3.0..3.0)),
            rotation: UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rng.gen_range(-PI..PI)),
        };
        parts.push(Part::Solid(Body::try_new(shape, mass, pose)?));
    }
    Composite::try_new(parts)
}

fn random_vector(rng: &mut impl Rng, s: f64) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
    )
}

pub(crate) fn random_rotation(rng: &mut impl Rng) -> Rotation3<f64> {
    let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0f64) + 1e-3,
    ));
    q.to_rotation_matrix()
}

/// Applies `f` to every particle: `(position, mass) → particles`.
pub(crate) fn map_particles<I>(
    cloud: &ParticleCloud,
    mut f: impl FnMut(Vector3<f64>, f64) -> I,
) -> Result<ParticleCloud, BodyError>
where
    I: IntoIterator<Item = (Vector3<f64>, f64)>,
{
    ParticleCloud::try_from_particles((0..cloud.len()).flat_map(|i| {
        let (p, m) = cloud.particle(i);
        f(p, m)
    }))
}

/// `fold` (≥ 3) copies of `cloud` turned by 2πk/fold about the z axis
/// through the origin, each with 1/fold of the mass: the moments about
/// any transverse axis through a point of z are equal, and the products
/// with z vanish, to round-off.
pub(crate) fn axisymmetric(cloud: &ParticleCloud, fold: usize) -> Result<ParticleCloud, BodyError> {
    let fold = fold.max(3);
    let turns: Vec<Rotation3<f64>> = (0..fold)
        .map(|k| Rotation3::from_axis_angle(&Vector3::z_axis(), 2.0 * PI * k as f64 / fold as f64))
        .collect();
    let share = 1.0 / fold as f64;
    map_particles(cloud, |p, m| turns.iter().map(move |r| (r * p, m * share)))
}

/// `cloud` with its mirror images in the planes whose normals are the
/// axes flagged in `normals`, each copy with its share of the mass. All
/// three planes: a body whose coordinate axes are principal (products
/// vanish to round-off); only z: a body symmetric about the xy plane.
pub(crate) fn mirrored(
    cloud: &ParticleCloud,
    normals: [bool; 3],
) -> Result<ParticleCloud, BodyError> {
    let mut signs = vec![Vector3::new(1.0, 1.0, 1.0)];
    for (k, &on) in normals.iter().enumerate() {
        if on {
            let flipped: Vec<_> = signs
                .iter()
                .map(|s| {
                    let mut s = *s;
                    s[k] = -s[k];
                    s
                })
                .collect();
            signs.extend(flipped);
        }
    }
    let share = 1.0 / signs.len() as f64;
    map_particles(cloud, |p, m| {
        signs
            .iter()
            .map(move |s| (p.component_mul(s), m * share))
            .collect::<Vec<_>>()
    })
}
