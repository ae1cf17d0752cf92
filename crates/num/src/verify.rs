//! # Derived equations against particle sums
//!
//! A system of particles at fixed relative positions is a rigid body, so a
//! derived result must agree with the direct particle sum to round-off.
//! For each supported derivation this module draws random bodies (clouds,
//! coarsely discretised posed primitives and composites), expresses them in
//! the axes the derivation assumes (principal axes for `euler-principal`,
//! random body axes otherwise, z along the fixed axis for `fixed-axis`),
//! binds the derivation's symbols from the particle sums of *the same
//! particles* (moments and products of inertia as integrals, `I_xy = ∫xy dm`:
//! the tensor holds them with a minus sign), evaluates the derived step with
//! a compiled [`Tape`] and compares with the direct sum (Σ m r × a, Σ m r × v,
//! Σ ½ m v², the inertia about P).
//!
//! The error of a comparison is `|derived − direct| / scale`, where the
//! scale is the sum of the magnitudes of the derived terms with every
//! symbol replaced by a bound on its size (inertia components by
//! `Σ m |r|²`) plus the magnitude of the direct value; it passes below
//! [`TOLERANCE_ULPS`] units of round-off.

use std::collections::HashMap;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::{Derivation, Value};
use hdot_sym::poly::Poly;
use nalgebra::{Rotation3, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::body::{Body, Composite, Part, Pose, Primitive};
use crate::cloud::ParticleCloud;
use crate::discretize::{Discretization, DiscretizedBody, DiscretizedComposite};
use crate::error::BodyError;
use crate::eval::Tape;
use crate::sums::{self, Motion};

/// Pass threshold, in units of `f64::EPSILON` relative to the scale.
pub const TOLERANCE_ULPS: f64 = 256.0;

/// The derivations with a numeric check, by file stem.
pub const SUPPORTED: &[&str] = &[
    "angular-momentum",
    "euler-general",
    "euler-principal",
    "fixed-axis",
    "kinetic-energy",
    "parallel-axis",
];

/// Why a check could not run.
#[derive(Debug, thiserror::Error)]
pub enum VerifyError {
    /// The derivation has no step of that name.
    #[error("{derivation}: no step named {step}")]
    MissingStep {
        /// Derivation name.
        derivation: String,
        /// Step name.
        step: String,
    },
    /// A step's value is not of the shape the check expects.
    #[error("{derivation}: step {step} is not {expected}")]
    WrongShape {
        /// Derivation name.
        derivation: String,
        /// Step name.
        step: String,
        /// What was expected.
        expected: &'static str,
    },
    /// The derived result uses a symbol the check does not bind.
    #[error("{derivation}: step {step} uses {symbol}, which the check does not bind")]
    Unbound {
        /// Derivation name.
        derivation: String,
        /// Step name.
        step: String,
        /// The symbol as printed.
        symbol: String,
    },
    /// A random body was invalid (a bug in the sampler).
    #[error(transparent)]
    Body(#[from] BodyError),
}

/// A random instantaneous state: angular velocity and acceleration, the
/// velocity of G, the derivation's body axes, and an offset (G − O or
/// G − P) in those axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// ω (body axes).
    pub omega: Vector3<f64>,
    /// α (body axes).
    pub alpha: Vector3<f64>,
    /// v̄ (body axes).
    pub v: Vector3<f64>,
    /// Body axes in world coordinates (columns), unless the derivation
    /// fixes them (principal axes).
    pub axes: Rotation3<f64>,
    /// G − O (or G − P), body axes.
    pub offset: Vector3<f64>,
}

/// One derived value against its particle sum.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// `step[component]`.
    pub quantity: String,
    /// The derived result, evaluated.
    pub derived: f64,
    /// The direct particle sum.
    pub direct: f64,
    /// The magnitudes involved.
    pub scale: f64,
}

impl Comparison {
    /// `|derived − direct| / scale` (0 when both vanish).
    pub fn relative_error(&self) -> f64 {
        let d = (self.derived - self.direct).abs();
        if d == 0.0 { 0.0 } else { d / self.scale }
    }

    /// Whether the error is within [`TOLERANCE_ULPS`].
    pub fn passes(&self) -> bool {
        self.relative_error() <= TOLERANCE_ULPS * f64::EPSILON
    }
}

/// The result of verifying one derivation on many bodies.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Bodies tried.
    pub bodies: usize,
    /// The largest relative error.
    pub max_error: f64,
    /// The comparison with the largest error.
    pub worst: Option<Comparison>,
    /// Whether every comparison passed.
    pub passed: bool,
}

/// Whether `name` has a numeric check.
pub fn is_supported(name: &str) -> bool {
    SUPPORTED.contains(&name)
}

/// Verifies `d` on `bodies` random bodies and states drawn from a ChaCha
/// generator seeded with `seed`; `tick` is called after each body.
/// `None` when the derivation has no numeric check.
pub fn verify(
    d: &Derivation,
    bodies: usize,
    seed: u64,
    tick: &mut dyn FnMut(),
) -> Option<Result<Outcome, VerifyError>> {
    if !is_supported(&d.name) {
        return None;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Outcome {
        bodies: 0,
        max_error: 0.0,
        worst: None,
        passed: true,
    };
    for _ in 0..bodies {
        let state_and_body = random_body(&mut rng).map(|c| (c, random_state(&mut rng)));
        let run = state_and_body
            .map_err(VerifyError::from)
            .and_then(|(cloud, state)| check(d, &cloud, &state).expect("supported"));
        let comparisons = match run {
            Ok(c) => c,
            Err(e) => return Some(Err(e)),
        };
        for c in comparisons {
            let e = c.relative_error();
            out.passed &= c.passes();
            if out.worst.is_none() || e > out.max_error {
                out.max_error = e;
                out.worst = Some(c);
            }
        }
        out.bodies += 1;
        tick();
    }
    Some(Ok(out))
}

/// A random body in world coordinates, as particles: a cloud of 5–40
/// particles, a coarsely discretised posed primitive, or a composite of two
/// or three parts.
pub fn random_body(rng: &mut impl Rng) -> Result<ParticleCloud, BodyError> {
    let disc = Discretization::gauss(2, 2);
    match rng.gen_range(0..3) {
        0 => random_cloud(rng),
        1 => {
            let b = random_posed(rng)?;
            ParticleCloud::collect_from(&DiscretizedBody::new(&b, &disc))
        }
        _ => {
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

fn random_posed(rng: &mut impl Rng) -> Result<Body, BodyError> {
    let mut d = || rng.gen_range(0.1..3.0);
    let (a, b, c) = (d(), d(), d());
    let shape = match rng.gen_range(0..10) {
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
    };
    let mass = rng.gen_range(0.1..10.0);
    let pose = Pose {
        position: random_vector(rng, 3.0),
        rotation: UnitQuaternion::from_rotation_matrix(&random_rotation(rng)),
    };
    Body::try_new(shape, mass, pose)
}

/// A random state: ω, α, v̄ of size up to 5, random axes, an offset up to 3.
pub fn random_state(rng: &mut impl Rng) -> State {
    State {
        omega: random_vector(rng, 5.0),
        alpha: random_vector(rng, 5.0),
        v: random_vector(rng, 5.0),
        axes: random_rotation(rng),
        offset: random_vector(rng, 3.0),
    }
}

fn random_vector(rng: &mut impl Rng, s: f64) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
    )
}

fn random_rotation(rng: &mut impl Rng) -> Rotation3<f64> {
    let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0f64) + 1e-3,
    ));
    q.to_rotation_matrix()
}

/// The particles of `cloud` in the axes `axes` (columns, world) with
/// origin `origin` (world): `Rᵀ (p − origin)`.
fn in_axes(
    cloud: &ParticleCloud,
    origin: &Vector3<f64>,
    axes: &Rotation3<f64>,
) -> Result<ParticleCloud, BodyError> {
    let inv = axes.inverse();
    ParticleCloud::try_from_particles((0..cloud.len()).map(|i| {
        let (p, m) = cloud.particle(i);
        (inv * (p - origin), m)
    }))
}

/// Values of the derivation's symbols by (name, derivative order), and
/// bounds on their magnitudes.
#[derive(Default)]
struct Binding {
    value: HashMap<(&'static str, u32), f64>,
    size: HashMap<(&'static str, u32), f64>,
}

impl Binding {
    fn set(&mut self, name: &'static str, order: u32, value: f64, size: f64) {
        self.value.insert((name, order), value);
        self.size.insert((name, order), size);
    }

    fn vector(&mut self, names: [&'static str; 3], order: u32, v: &Vector3<f64>) {
        for (name, x) in names.into_iter().zip(v.iter()) {
            self.set(name, order, *x, v.norm());
        }
    }

    fn inertia(&mut self, i: &crate::Inertia) {
        let size = 0.5 * i.trace();
        let [ix, iy, iz] = i.moments();
        let [ixy, iyz, izx] = i.products();
        for (n, v) in [
            ("I_x", ix),
            ("I_y", iy),
            ("I_z", iz),
            ("I_xy", ixy),
            ("I_yz", iyz),
            ("I_zx", izx),
        ] {
            self.set(n, 0, v, size);
        }
    }
}

/// The components of a step, flattened (vectors x, y, z; matrices by rows).
fn components<'a>(d: &'a Derivation, step: &str) -> Result<Vec<&'a Poly>, VerifyError> {
    let s = d
        .steps
        .iter()
        .find(|s| s.name == step)
        .ok_or_else(|| VerifyError::MissingStep {
            derivation: d.name.clone(),
            step: step.into(),
        })?;
    Ok(match &s.value {
        Value::Scalar(p) => vec![p],
        Value::Vector(v, _) => v.0.iter().collect(),
        Value::Matrix(m) => m.0.iter().flatten().collect(),
    })
}

/// Evaluates `step` under `b` and compares component `k` with `direct[k]`.
fn compare(
    d: &Derivation,
    step: &str,
    b: &Binding,
    direct: &[f64],
) -> Result<Vec<Comparison>, VerifyError> {
    let polys: Vec<Poly> = components(d, step)?.into_iter().cloned().collect();
    if polys.len() != direct.len() {
        return Err(VerifyError::WrongShape {
            derivation: d.name.clone(),
            step: step.into(),
            expected: if direct.len() == 1 {
                "a scalar"
            } else {
                "a vector"
            },
        });
    }
    let tape = Tape::compile(&polys);
    let lookup = |map: &HashMap<(&'static str, u32), f64>, a: Atom| -> Option<f64> {
        match a.kind() {
            AtomKind::Var { name, order, .. } => map.get(&(name, order)).copied().or_else(|| {
                // An abbreviation (e.g. α := ω′): evaluate its definition.
                let ab = d.abbreviations.iter().find(|ab| ab.atom == a)?;
                let mut ok = true;
                let v = ab.definition.eval(&mut |x| match x.kind() {
                    AtomKind::Var { name, order, .. } => {
                        map.get(&(name, order)).copied().unwrap_or_else(|| {
                            ok = false;
                            0.0
                        })
                    }
                    _ => {
                        ok = false;
                        0.0
                    }
                });
                ok.then_some(v)
            }),
            _ => None,
        }
    };
    let mut values = Vec::with_capacity(tape.atoms().len());
    let mut sizes = Vec::with_capacity(tape.atoms().len());
    for &a in tape.atoms() {
        let unbound = || VerifyError::Unbound {
            derivation: d.name.clone(),
            step: step.into(),
            symbol: a.name().to_string(),
        };
        values.push(lookup(&b.value, a).ok_or_else(unbound)?);
        sizes.push(lookup(&b.size, a).ok_or_else(unbound)?.abs());
    }
    let mut derived = vec![0.0; polys.len()];
    let mut scale = vec![0.0; polys.len()];
    tape.eval(&values, &mut derived);
    tape.eval_abs(&sizes, &mut scale);
    let axes = ["x", "y", "z"];
    Ok((0..polys.len())
        .map(|k| Comparison {
            quantity: if polys.len() == 1 {
                step.to_string()
            } else {
                format!("{step}.{}", axes[k])
            },
            derived: derived[k],
            direct: direct[k],
            scale: scale[k] + direct[k].abs() + f64::MIN_POSITIVE,
        })
        .collect())
}

const OMEGA: [&str; 3] = ["omega_x", "omega_y", "omega_z"];
const VEL: [&str; 3] = ["v_x", "v_y", "v_z"];
const BAR: [&str; 3] = ["xbar", "ybar", "zbar"];

/// Runs the check of `d` on one body (world coordinates) and state.
/// `None` when the derivation has no numeric check.
pub fn check(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Option<Result<Vec<Comparison>, VerifyError>> {
    let f: fn(&Derivation, &ParticleCloud, &State) -> Result<Vec<Comparison>, VerifyError> =
        match d.name.as_str() {
            "euler-principal" => euler_principal,
            "euler-general" => euler_general,
            "angular-momentum" => angular_momentum,
            "fixed-axis" => fixed_axis,
            "kinetic-energy" => kinetic_energy,
            "parallel-axis" => parallel_axis,
            _ => return None,
        };
    Some(f(d, cloud, state))
}

/// The cloud in body axes through G, its centre (≈ 0) and mass properties.
fn about_g(
    cloud: &ParticleCloud,
    axes: &Rotation3<f64>,
) -> Result<(ParticleCloud, crate::MassProperties), VerifyError> {
    let g = cloud.mass_properties().center;
    let c = in_axes(cloud, &g, axes)?;
    let mp = c.mass_properties();
    Ok((c, mp))
}

fn euler(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
    axes: &Rotation3<f64>,
    principal: bool,
    steps: &[&str],
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, axes)?;
    let motion = Motion {
        omega: state.omega,
        alpha: state.alpha,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &motion, mp.center, mp.center);
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.vector(OMEGA, 0, &state.omega);
    b.vector(OMEGA, 1, &state.alpha);
    // With principal axes, the products left by the eigensolver (~1e-13 of
    // the moments) are removed from the direct sum: the derivation assumes
    // they vanish, and their effect is above round-off.
    let mut direct = k.hdot_g;
    if principal {
        let mut off = *mp.inertia_g.matrix();
        off.fill_diagonal(0.0);
        direct -= off * state.alpha + state.omega.cross(&(off * state.omega));
    }
    let mut out = Vec::new();
    for s in steps {
        out.extend(compare(d, s, &b, direct.as_slice())?);
    }
    Ok(out)
}

fn euler_principal(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    // True eigenvectors (no snapping of nearly repeated moments to a
    // canonical basis), so that the neglected products are round-off.
    let axes = cloud
        .mass_properties()
        .inertia_g
        .principal_with_tol(0.0)
        .axes;
    euler(d, cloud, state, &axes, true, &["M", "M_transport"])
}

fn euler_general(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    euler(d, cloud, state, &state.axes, false, &["M"])
}

fn angular_momentum(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let motion = Motion {
        omega: state.omega,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &motion, mp.center, mp.center);
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.vector(OMEGA, 0, &state.omega);
    let mut out = compare(d, "H", &b, k.h_g.as_slice())?;
    out.extend(compare(d, "T_rot", &b, &[k.kinetic_energy])?);
    Ok(out)
}

fn fixed_axis(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    // O = G − offset (world offset = axes · offset); axes Oxyz, z the axis.
    let g = cloud.mass_properties().center;
    let o = g - state.axes * state.offset;
    let c = in_axes(cloud, &o, &state.axes)?;
    let mp = c.mass_properties();
    let (w, wdot) = (state.omega.z, state.alpha.z);
    let origin = Vector3::zeros();
    let motion = Motion::about_fixed_point(
        origin,
        mp.center,
        Vector3::new(0.0, 0.0, w),
        Vector3::new(0.0, 0.0, wdot),
    );
    let k = sums::kinetics(&c, &motion, mp.center, origin);
    let mut b = Binding::default();
    b.inertia(&mp.inertia_about(&origin));
    b.set("omega", 0, w, w.abs());
    b.set("omega", 1, wdot, wdot.abs());
    compare(d, "M", &b, k.moment_o.as_slice())
}

fn kinetic_energy(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.set("m", 0, mp.mass, mp.mass);
    b.vector(OMEGA, 0, &state.omega);
    b.vector(VEL, 0, &state.v);
    b.vector(BAR, 0, &state.offset);
    let free = Motion {
        omega: state.omega,
        v_g: state.v,
        ..Motion::default()
    };
    let k = sums::kinetics(&c, &free, mp.center, mp.center);
    let mut out = compare(d, "T", &b, &[k.kinetic_energy])?;
    // Fixed point O with G − O = offset: v̄ = ω × r̄.
    let o = mp.center - state.offset;
    let pinned = Motion::about_fixed_point(o, mp.center, state.omega, state.alpha);
    let k = sums::kinetics(&c, &pinned, mp.center, o);
    out.extend(compare(d, "T_O", &b, &[k.kinetic_energy])?);
    Ok(out)
}

fn parallel_axis(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Result<Vec<Comparison>, VerifyError> {
    let (c, mp) = about_g(cloud, &state.axes)?;
    let p = mp.center - state.offset;
    let ip = sums::moments(&c, p).inertia();
    let mut b = Binding::default();
    b.inertia(&mp.inertia_g);
    b.set("m", 0, mp.mass, mp.mass);
    b.vector(BAR, 0, &state.offset);
    b.vector(OMEGA, 0, &state.omega);
    let [ix, iy, iz] = ip.moments();
    let [ixy, iyz, izx] = ip.products();
    let mut out = Vec::new();
    for (s, v) in [
        ("Ix_P", ix),
        ("Iy_P", iy),
        ("Iz_P", iz),
        ("Ixy_P", ixy),
        ("Iyz_P", iyz),
        ("Izx_P", izx),
    ] {
        out.extend(compare(d, s, &b, &[v])?);
    }
    Ok(out)
}
