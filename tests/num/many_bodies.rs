//! A scene of many bodies (issue 21, item 10): its mass properties and
//! kinetics agree with the sums of its bodies' closed forms, and the
//! particle sums over its discretised copy visit every particle once, in
//! order, across leaves that straddle the parts.

use std::fmt::Write as _;

use hdot_num::nalgebra::{Matrix3, Vector3};
use hdot_num::scene::{CHECK_DISCRETIZATION, Scene};
use hdot_num::{DiscretizedBody, DiscretizedComposite, Part, ParticleCloud};

/// Body k of the scene: mass, radius and centre, varied so that no two
/// neighbours share a leaf boundary in the same way.
fn sphere(k: usize) -> (f64, f64, Vector3<f64>) {
    let m = 1.0 + (k % 7) as f64 * 0.25;
    let r = 0.01 + (k % 5) as f64 * 0.002;
    let t = k as f64;
    (
        m,
        r,
        Vector3::new(0.1 * t, (0.37 * t).sin(), (0.23 * t).cos() - 0.5),
    )
}

const BODIES: usize = 301;
const OMEGA: [f64; 3] = [0.3, -1.2, 0.7];

/// A scene file of `BODIES` spheres turning about the origin at `OMEGA`.
fn scene_text() -> String {
    let mut s = String::from("name = \"many spheres\"\n\n");
    for k in 0..BODIES {
        let (m, r, p) = sphere(k);
        writeln!(
            s,
            "[[body]]\nshape = \"sphere\"\nmass = {m:?}\nradius = {r:?}\nposition = [{:?}, {:?}, {:?}]\n",
            p.x, p.y, p.z
        )
        .unwrap();
    }
    writeln!(
        s,
        "[motion]\nfixed_point = [0.0, 0.0, 0.0]\nomega = [{:?}, {:?}, {:?}]",
        OMEGA[0], OMEGA[1], OMEGA[2]
    )
    .unwrap();
    s
}

fn load() -> Scene {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("many-spheres.toml");
    std::fs::write(&path, scene_text()).unwrap();
    Scene::from_path(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn many_bodies_sum_to_the_scene() {
    let scene = load();
    let r = scene.dynamics();
    // Σ over the bodies: mass and inertia about O (a solid sphere's
    // 2/5 m r², shifted by m (|p|² 1 − p pᵀ)).
    let (mut mass, mut i_o) = (0.0, Matrix3::zeros());
    for k in 0..BODIES {
        let (m, rad, p) = sphere(k);
        mass += m;
        i_o += Matrix3::identity() * (0.4 * m * rad * rad + m * p.norm_squared())
            - m * p * p.transpose();
    }
    let got_m = r.inertia.props.mass;
    assert!(
        (got_m - mass).abs() <= 1e3 * f64::EPSILON * mass,
        "{got_m} vs {mass}"
    );
    let scale = i_o.trace();
    let diff = (r.inertia.inertia_o.matrix() - i_o).abs().max();
    assert!(
        diff <= 1e3 * f64::EPSILON * scale,
        "I_O differs by {diff:e}"
    );
    // T = ½ ωᵀ I_O ω about the fixed point.
    let w = Vector3::from(OMEGA);
    let t = 0.5 * w.dot(&(i_o * w));
    let got_t = r.kinetics.kinetic_energy;
    assert!(
        (got_t - t).abs() <= 1e3 * f64::EPSILON * t,
        "T = {got_t}, want {t}"
    );
    // The particle sums over all the bodies agree with the rigid formulas.
    assert!(
        r.particle_check < 1e-12,
        "particle check {:e}",
        r.particle_check
    );
}

#[test]
fn a_composite_yields_its_parts_particles_in_order() {
    let scene = load();
    let all = ParticleCloud::collect_from(&DiscretizedComposite::new(
        &scene.body,
        &CHECK_DISCRETIZATION,
    ))
    .unwrap();
    let mut want: [Vec<f64>; 4] = Default::default();
    for part in scene.body.parts() {
        let Part::Solid(b) = part else {
            panic!("a sphere is a solid");
        };
        let c =
            ParticleCloud::collect_from(&DiscretizedBody::new(b, &CHECK_DISCRETIZATION)).unwrap();
        let (x, y, z, m) = c.arrays();
        for (w, a) in want.iter_mut().zip([x, y, z, m]) {
            w.extend_from_slice(a);
        }
    }
    let (x, y, z, m) = all.arrays();
    for (k, (got, w)) in [x, y, z, m].iter().zip(&want).enumerate() {
        // bitwise: the same particles in the same order
        assert!(*got == w.as_slice(), "coordinate {k} differs");
    }
}
