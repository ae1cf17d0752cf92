//! Particle-sum throughput.
//!
//! - `stored`: the deterministic moment sums (mass, first and second
//!   moments: 10 accumulators per particle) over a stored SoA cloud,
//!   against a plain streaming sum over the same four arrays in the same
//!   run (same thread pool, same memory): the ratio of their rates is the
//!   figure of merit (target ≥ 70 %).
//! - `lazy`: particles/s for discretised bodies generated on the fly
//!   (moments, and the full kinetic sums).
//!
//! Run: `cargo bench -p hdot-num --bench particle_sums`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use hdot_num::nalgebra::Vector3;
use hdot_num::sums::{Motion, kinetics, moments};
use hdot_num::{
    Body, Discretization, DiscretizedBody, ParticleCloud, ParticleSource, Pose, Primitive,
};
use rayon::prelude::*;
use std::hint::black_box;

/// Particles in the stored cloud: 4 × 8 B × 4 M = 128 MB, well beyond cache.
const N: usize = 4_000_000;

fn cloud() -> ParticleCloud {
    // deterministic pseudo-random positions (xorshift), positive masses
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut v = [
        Vec::with_capacity(N),
        Vec::with_capacity(N),
        Vec::with_capacity(N),
        Vec::with_capacity(N),
    ];
    for _ in 0..N {
        v[0].push(next() - 0.5);
        v[1].push(next() - 0.5);
        v[2].push(next() - 0.5);
        v[3].push(0.5 + next());
    }
    let [x, y, z, m] = v;
    ParticleCloud::try_from_arrays(x, y, z, m).expect("valid cloud")
}

/// The baseline: sum every number of the four arrays, in parallel chunks.
fn streaming_sum(c: &ParticleCloud) -> f64 {
    let (x, y, z, m) = c.arrays();
    const CH: usize = 1 << 16;
    x.par_chunks(CH)
        .zip(y.par_chunks(CH))
        .zip(z.par_chunks(CH))
        .zip(m.par_chunks(CH))
        .map(|(((x, y), z), m)| {
            let mut acc = [0.0f64; 4];
            for i in 0..x.len() {
                acc[i % 4] += x[i] + y[i] + z[i] + m[i];
            }
            acc.iter().sum::<f64>()
        })
        .sum()
}

fn stored(c: &mut Criterion) {
    let cl = cloud();
    let mut g = c.benchmark_group("stored");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(20);
    g.bench_function("streaming_sum", |b| {
        b.iter(|| black_box(streaming_sum(black_box(&cl))))
    });
    g.bench_function("moments", |b| {
        b.iter(|| black_box(moments(black_box(&cl), Vector3::zeros())))
    });
    g.finish();
}

fn lazy(c: &mut Criterion) {
    let mut g = c.benchmark_group("lazy");
    g.sample_size(10);
    let cases = [
        (
            Primitive::Prism {
                a: 1.0,
                b: 2.0,
                c: 3.0,
            },
            Discretization::midpoint(128),
        ),
        (
            Primitive::Cylinder {
                radius: 0.5,
                length: 2.0,
            },
            Discretization::gauss(64, 2),
        ),
        (
            Primitive::Sphere { radius: 0.5 },
            Discretization::midpoint(128),
        ),
    ];
    for (shape, disc) in cases {
        let body =
            Body::try_new(shape, 2.0, Pose::translation(Vector3::new(0.1, 0.2, 0.3))).unwrap();
        let src = DiscretizedBody::new(&body, &disc);
        g.throughput(Throughput::Elements(src.len() as u64));
        g.bench_with_input(BenchmarkId::new("moments", shape.name()), &src, |b, src| {
            b.iter(|| black_box(moments(src, Vector3::zeros())))
        });
        let motion = Motion {
            omega: Vector3::new(1.0, 2.0, 3.0),
            alpha: Vector3::new(0.3, -0.2, 0.1),
            v_g: Vector3::new(0.5, 0.0, 0.0),
            a_g: Vector3::zeros(),
        };
        g.bench_with_input(
            BenchmarkId::new("kinetics", shape.name()),
            &src,
            |b, src| {
                b.iter(|| {
                    black_box(kinetics(
                        src,
                        &motion,
                        Vector3::new(0.1, 0.2, 0.3),
                        Vector3::zeros(),
                    ))
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, stored, lazy);
criterion_main!(benches);
