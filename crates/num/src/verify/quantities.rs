//! The measurable quantities: a registry of self-describing entries, one
//! per [`Quantity`] of `hdot_sym::derivation::physics`, each with its
//! particle sum and the magnitudes its round-off is relative to, its
//! call and its documentation (the quantity table of
//! `docs/derivation-format.md` is generated from it: [`super::means`]).

use hdot_sym::derivation::physics::{Arg, Bodies, Quantity};
use nalgebra::{Matrix3, Vector3};

use hdot_sym::derivation::Load;

use super::VerifyError;
use super::partials::partials;
use super::reactions::{acts_on, load_vector};
use super::world::{World, vee};

/// A measured value: in N's axes for a vector, in the named frame's axes
/// for a matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Measured {
    /// A scalar.
    Scalar(f64),
    /// A vector, N's axes.
    Vector(Vector3<f64>),
    /// A matrix, in the axes of the frame its quantity names.
    Matrix(Matrix3<f64>),
}

/// One entry of the registry.
pub struct Measure {
    /// The quantity.
    pub quantity: Quantity,
    /// How it is written in `means`, with its arguments named, for the
    /// docs: `position(point, from)`.
    pub call: &'static str,
    /// How it is measured on the particles, for the docs table
    /// (Markdown).
    pub doc: &'static str,
    /// What it is compared with, for reports.
    pub measured_as: &'static str,
    /// The particle sum (or point kinematics) and its scale.
    pub compute: fn(&World<'_>, &[Arg]) -> Out,
}

/// Every measurable quantity, in the order of the docs table.
pub static REGISTRY: &[Measure] = &[
    Measure {
        quantity: Quantity::Mass,
        call: "mass(body)",
        doc: "Σ m",
        measured_as: "Σ m",
        compute: mass,
    },
    Measure {
        quantity: Quantity::Position,
        call: "position(point, from)",
        doc: "r_point − r_from",
        measured_as: "r_P − r_Q",
        compute: position,
    },
    Measure {
        quantity: Quantity::Velocity,
        call: "velocity(point)",
        doc: "ṙ of the point",
        measured_as: "ṙ of the point",
        compute: velocity,
    },
    Measure {
        quantity: Quantity::Acceleration,
        call: "acceleration(point)",
        doc: "r̈ of the point",
        measured_as: "r̈ of the point",
        compute: acceleration,
    },
    Measure {
        quantity: Quantity::AngularVelocity,
        call: "angular_velocity(frame)",
        doc: "ω of the frame relative to N, read from Ṙ Rᵀ",
        measured_as: "the axial vector of Ṙ Rᵀ",
        compute: angular_velocity,
    },
    Measure {
        quantity: Quantity::AngularAcceleration,
        call: "angular_acceleration(frame)",
        doc: "α of the frame relative to N, read from d(Ṙ Rᵀ)/dt",
        measured_as: "the axial vector of d(Ṙ Rᵀ)/dt",
        compute: angular_acceleration,
    },
    Measure {
        quantity: Quantity::Momentum,
        call: "momentum(body)",
        doc: "Σ m v",
        measured_as: "Σ m v",
        compute: momentum,
    },
    Measure {
        quantity: Quantity::Force,
        call: "force(body)",
        doc: "Σ m a (the resultant force the motion requires)",
        measured_as: "Σ m a",
        compute: force,
    },
    Measure {
        quantity: Quantity::AngularMomentum,
        call: "angular_momentum(body, point)",
        doc: "Σ m (r − r_point) × v",
        measured_as: "Σ m (r − r_P) × v",
        compute: angular_momentum,
    },
    Measure {
        quantity: Quantity::Moment,
        call: "moment(body, point)",
        doc: "Σ m (r − r_point) × a (the resultant moment the motion requires)",
        measured_as: "Σ m (r − r_P) × a",
        compute: moment,
    },
    Measure {
        quantity: Quantity::KineticEnergy,
        call: "kinetic_energy(body)",
        doc: "Σ ½ m v²",
        measured_as: "Σ ½ m v²",
        compute: kinetic_energy,
    },
    Measure {
        quantity: Quantity::Inertia,
        call: "inertia(body, point, frame)",
        doc: "Σ m (\\|ρ\\|² E − ρ ρᵀ), ρ = r − r_point, in the frame's axes",
        measured_as: "Σ m (|ρ|² E − ρ ρᵀ) in the frame's axes",
        compute: inertia,
    },
    Measure {
        quantity: Quantity::Weight,
        call: "weight(body)",
        doc: "Σ m g (needs `gravity`)",
        measured_as: "Σ m g",
        compute: weight,
    },
    Measure {
        quantity: Quantity::WeightMoment,
        call: "weight_moment(body, point)",
        doc: "Σ (r − r_point) × m g",
        measured_as: "Σ (r − r_P) × m g",
        compute: weight_moment,
    },
    Measure {
        quantity: Quantity::PotentialEnergy,
        call: "potential_energy(body, point)",
        doc: "−Σ m g · (r − r_point)",
        measured_as: "−Σ m g · (r − r_P)",
        compute: potential_energy,
    },
    Measure {
        quantity: Quantity::EnergyRate,
        call: "energy_rate(body)",
        doc: "Σ m v · (a − g): the rate of `kinetic_energy(body)` plus `potential_energy(body, O)` about a fixed point O (g = 0 without `gravity`); `energy_rate(system) - u_1*K_1 - …`, with K_r Kane's −(F_r + F_r*) measured as below, is the power balance dE/dt − Σ u_r K_r",
        measured_as: "Σ m v · (a − g)",
        compute: super::power::energy_rate,
    },
    Measure {
        quantity: Quantity::GeneralizedForce,
        call: "generalized_force(body, q)",
        doc: "Σ m a · ∂r/∂q (the left side of Lagrange's equation for q); ∂r/∂q moves the coordinates `[motion]`'s rules tie to q with it (*Conditions*, below)",
        measured_as: "Σ m a · ∂r/∂q",
        compute: generalized_force,
    },
    Measure {
        quantity: Quantity::GeneralizedMomentum,
        call: "generalized_momentum(body, q)",
        doc: "Σ m v · ∂r/∂q (= ∂T/∂q̇)",
        measured_as: "Σ m v · ∂r/∂q",
        compute: generalized_momentum,
    },
    Measure {
        quantity: Quantity::GeneralizedWeight,
        call: "generalized_weight(body, q)",
        doc: "Σ m g · ∂r/∂q (= −∂V/∂q)",
        measured_as: "Σ m g · ∂r/∂q",
        compute: generalized_weight,
    },
    Measure {
        quantity: Quantity::KineticEnergyPartial,
        call: "kinetic_energy_partial(body, q)",
        doc: "∂T/∂q with the other coordinates and every rate held: T = Σ ½ m v² measured at nine values of q spaced evenly around the circle, differentiated as the trigonometric polynomial through them (exact for an angle, which enters through sin and cos); for a coordinate that enters the points' places or a frame's angular velocity as itself (a length), central differences at q ± ½, q ± 1, Richardson-extrapolated (exact for T of degree ≤ 4 in q)",
        measured_as: "∂(Σ ½ m v²)/∂q from T at neighbouring q",
        compute: kinetic_energy_partial,
    },
    Measure {
        quantity: Quantity::GeneralizedActiveForce,
        call: "generalized_active_force(body, u)",
        doc: "Kane's F_r for the independent speed u = u_r: Σ m g · v_r over the particles plus v_r · F of each `[[load]]` force at its point and ω_r · T of each torque on its frame (on the body's points and frame, or every load for `system`); v_r and ω_r are the *constrained* partial velocities — the velocities at the drawn state less those with u_r raised by one, the dependent speeds solved again from the `kane` step's constraint rows and the coordinates' rates from `[kinematics]` (the velocities are linear in the speeds, so the difference is exact up to rounding)",
        measured_as: "Σ m g · v_r + Σ v_r · F + Σ ω_r · T",
        compute: generalized_active_force,
    },
    Measure {
        quantity: Quantity::GeneralizedInertiaForce,
        call: "generalized_inertia_force(body, u)",
        doc: "Kane's F_r* for the independent speed u = u_r: −Σ m a · v_r over the particles, v_r the constrained partial velocities as above; a `kane` step is −(F_r + F_r*) for each of its speeds",
        measured_as: "−Σ m a · v_r",
        compute: generalized_inertia_force,
    },
    Measure {
        quantity: Quantity::PointVelocity,
        call: "point_velocity(body, point)",
        doc: "ṙ of the body's own (material) point at the point's place: ṙ_O + Ṙ q with q = Rᵀ (r_P − r_O) fixed in the body (a rolling disk's point at the contact C, whose velocity is zero, while C itself moves along the floor)",
        measured_as: "ṙ_O + Ṙ q of the body's point q = Rᵀ (r_P − r_O)",
        compute: point_velocity,
    },
    Measure {
        quantity: Quantity::PointAcceleration,
        call: "point_acceleration(body, point)",
        doc: "r̈ of the body's own (material) point at the point's place: r̈_O + R̈ q with q = Rᵀ (r_P − r_O) fixed in the body",
        measured_as: "r̈_O + R̈ q of the body's point q = Rᵀ (r_P − r_O)",
        compute: point_acceleration,
    },
    Measure {
        quantity: Quantity::VelocityAfterImpulse,
        call: "velocity_after_impulse(body, point, F)",
        doc: "v̄ of the body, at rest before, just after an impulse F (a vector expression, `[F_x, F_y, F_z] in N`) at the point: the rigid velocity field v = v̄ + ω × (r − r_G) of the particles that satisfies Σ m v = F and Σ m (r − r_G) × v = (r_point − r_G) × F; v̄ = F/Σ m (`derivations/impulse-momentum.toml`)",
        measured_as: "v̄ solving Σ m v = F̂, Σ m (r − r_G) × v = (r_P − r_G) × F̂ over the particles",
        compute: velocity_after_impulse,
    },
    Measure {
        quantity: Quantity::AngularVelocityAfterImpulse,
        call: "angular_velocity_after_impulse(body, point, F)",
        doc: "ω of the body, at rest before, just after an impulse F at the point (the same rigid velocity field): the 3 × 3 system about G whose columns are the particle sums Σ m ρ × (e_j × ρ), solved by LU",
        measured_as: "ω solving Σ m v = F̂, Σ m (r − r_G) × v = (r_P − r_G) × F̂ over the particles",
        compute: angular_velocity_after_impulse,
    },
    Measure {
        quantity: Quantity::Reaction,
        call: "reaction(support)",
        doc: "the force a declared `[[support]]` exerts on its body: Σ m a less the weight (Σ m g) and the `[[load]]`s on the body, and Σ (r − r_O) × m a less their moments, distributed over the supports that hold the body by solving their equilibrium for the components each carries (SVD); a set the six equations do not determine (statically indeterminate), or one that cannot hold what the motion requires, is an error",
        measured_as: "the supports' equilibrium with Σ m a − Σ m g and Σ (r − r_O) × m (a − g)",
        compute: reaction,
    },
    Measure {
        quantity: Quantity::ReactionCouple,
        call: "reaction_couple(support)",
        doc: "the couple a clamp or a drive exerts on its body, from the same solve (a drive's about its axis: `along(reaction_couple(motor), [0, 0, 1] in N)`)",
        measured_as: "the supports' equilibrium with Σ m a − Σ m g and Σ (r − r_O) × m (a − g)",
        compute: reaction_couple,
    },
];

/// The registry entry of `q`.
pub fn measure(q: Quantity) -> &'static Measure {
    REGISTRY
        .iter()
        .find(|m| m.quantity == q)
        .expect("every quantity is measurable")
}

/// A measured value and the magnitudes its round-off is relative to.
pub type Out = Result<(Measured, f64), VerifyError>;

fn bodies(a: &Arg) -> Bodies {
    match a {
        Arg::Body(b) => *b,
        _ => unreachable!("validated by hdot-sym"),
    }
}

fn point<'w>(w: &'w World<'_>, a: &Arg) -> &'w super::world::PointJet {
    match a {
        Arg::Point(p) => &w.points[p],
        _ => unreachable!("validated by hdot-sym"),
    }
}

fn frame(a: &Arg) -> usize {
    match a {
        Arg::Frame(f) => *f,
        _ => unreachable!("validated by hdot-sym"),
    }
}

fn mass(w: &World<'_>, a: &[Arg]) -> Out {
    let m: f64 = w.particles(bodies(&a[0])).map(|p| p.m).sum();
    Ok((Measured::Scalar(m), m))
}

fn position(w: &World<'_>, a: &[Arg]) -> Out {
    let (p, q) = (point(w, &a[0]), point(w, &a[1]));
    Ok((Measured::Vector(p.r[0] - q.r[0]), p.mag[0] + q.mag[0]))
}

fn velocity(w: &World<'_>, a: &[Arg]) -> Out {
    let p = point(w, &a[0]);
    Ok((Measured::Vector(p.r[1]), p.mag[1]))
}

fn acceleration(w: &World<'_>, a: &[Arg]) -> Out {
    let p = point(w, &a[0]);
    Ok((Measured::Vector(p.r[2]), p.mag[2]))
}

fn angular_velocity(w: &World<'_>, a: &[Arg]) -> Out {
    let r = &w.frames[frame(&a[0])];
    Ok((
        Measured::Vector(vee(&(r[1] * r[0].transpose()))),
        r[1].norm(),
    ))
}

fn angular_acceleration(w: &World<'_>, a: &[Arg]) -> Out {
    let r = &w.frames[frame(&a[0])];
    let s = r[2] * r[0].transpose() + r[1] * r[1].transpose();
    Ok((Measured::Vector(vee(&s)), r[2].norm() + r[1].norm_squared()))
}

/// Σ over the particles of `f(particle) → (vector, magnitude)`.
fn sum_vec(
    w: &World<'_>,
    b: Bodies,
    f: impl Fn(&super::world::Particle<'_>) -> (Vector3<f64>, f64),
) -> (Vector3<f64>, f64) {
    w.particles(b).fold((Vector3::zeros(), 0.0), |(s, m), p| {
        let (v, mag) = f(&p);
        (s + v, m + mag)
    })
}

fn sum_scalar(
    w: &World<'_>,
    b: Bodies,
    f: impl Fn(&super::world::Particle<'_>) -> (f64, f64),
) -> (f64, f64) {
    w.particles(b).fold((0.0, 0.0), |(s, m), p| {
        let (v, mag) = f(&p);
        (s + v, m + mag)
    })
}

fn momentum(w: &World<'_>, a: &[Arg]) -> Out {
    let (v, s) = sum_vec(w, bodies(&a[0]), |p| (p.r[1] * p.m, p.m * p.mag[1]));
    Ok((Measured::Vector(v), s))
}

fn force(w: &World<'_>, a: &[Arg]) -> Out {
    let (v, s) = sum_vec(w, bodies(&a[0]), |p| (p.r[2] * p.m, p.m * p.mag[2]));
    Ok((Measured::Vector(v), s))
}

/// `Σ m (r − r_O) × r⁽ᴼᴿᴰᴱᴿ⁾`: the particles' sum regrouped by their
/// moments ([`super::world::Placed::moment_about`]; a linearisation
/// measures the moment on tens of thousands of worlds).
fn about<const ORDER: usize>(w: &World<'_>, a: &[Arg]) -> Out {
    let (v, s) = w.moment_about::<ORDER>(bodies(&a[0]), point(w, &a[1]));
    Ok((Measured::Vector(v), s))
}

fn angular_momentum(w: &World<'_>, a: &[Arg]) -> Out {
    about::<1>(w, a)
}

fn moment(w: &World<'_>, a: &[Arg]) -> Out {
    about::<2>(w, a)
}

fn kinetic_energy(w: &World<'_>, a: &[Arg]) -> Out {
    let (t, s) = sum_scalar(w, bodies(&a[0]), |p| {
        (
            0.5 * p.m * p.r[1].norm_squared(),
            0.5 * p.m * p.mag[1] * p.mag[1],
        )
    });
    Ok((Measured::Scalar(t), s))
}

fn inertia(w: &World<'_>, a: &[Arg]) -> Out {
    let o = point(w, &a[1]);
    let f = frame(&a[2]);
    let rt = w.frames[f][0].transpose();
    let mut i = Matrix3::zeros();
    let mut s = 0.0;
    for p in w.particles(bodies(&a[0])) {
        let rho = rt * (p.r[0] - o.r[0]);
        i += p.m * (Matrix3::identity() * rho.norm_squared() - rho * rho.transpose());
        s += p.m * (p.mag[0] + o.mag[0]).powi(2);
    }
    Ok((Measured::Matrix(i), s))
}

fn weight(w: &World<'_>, a: &[Arg]) -> Out {
    let g = w.gravity;
    let (v, s) = sum_vec(w, bodies(&a[0]), |p| (g * p.m, p.m * g.norm()));
    Ok((Measured::Vector(v), s))
}

fn weight_moment(w: &World<'_>, a: &[Arg]) -> Out {
    let (g, o) = (w.gravity, point(w, &a[1]));
    let (v, s) = sum_vec(w, bodies(&a[0]), |p| {
        (
            (p.r[0] - o.r[0]).cross(&g) * p.m,
            p.m * (p.mag[0] + o.mag[0]) * g.norm(),
        )
    });
    Ok((Measured::Vector(v), s))
}

fn potential_energy(w: &World<'_>, a: &[Arg]) -> Out {
    let (g, o) = (w.gravity, point(w, &a[1]));
    let (v, s) = sum_scalar(w, bodies(&a[0]), |p| {
        (
            -p.m * g.dot(&(p.r[0] - o.r[0])),
            p.m * (p.mag[0] + o.mag[0]) * g.norm(),
        )
    });
    Ok((Measured::Scalar(v), s))
}

/// The index of the coordinate in `a` among the world's coordinates.
fn coordinate(w: &World<'_>, a: &Arg) -> usize {
    match a {
        Arg::Coordinate(q) => w
            .coordinates
            .iter()
            .position(|c| c == q)
            .expect("the world carries ∂r/∂q for every coordinate of the meaning"),
        _ => unreachable!("validated by hdot-sym"),
    }
}

fn generalized_force(w: &World<'_>, a: &[Arg]) -> Out {
    let k = coordinate(w, &a[1]);
    let (v, s) = sum_scalar(w, bodies(&a[0]), |p| {
        (p.m * p.r[2].dot(&p.dr(k)), p.m * p.mag[2] * p.dr(k).norm())
    });
    Ok((Measured::Scalar(v), s))
}

fn generalized_momentum(w: &World<'_>, a: &[Arg]) -> Out {
    let k = coordinate(w, &a[1]);
    let (v, s) = sum_scalar(w, bodies(&a[0]), |p| {
        (p.m * p.r[1].dot(&p.dr(k)), p.m * p.mag[1] * p.dr(k).norm())
    });
    Ok((Measured::Scalar(v), s))
}

fn generalized_weight(w: &World<'_>, a: &[Arg]) -> Out {
    let (g, k) = (w.gravity, coordinate(w, &a[1]));
    let (v, s) = sum_scalar(w, bodies(&a[0]), |p| {
        (p.m * g.dot(&p.dr(k)), p.m * g.norm() * p.dr(k).norm())
    });
    Ok((Measured::Scalar(v), s))
}

/// ∂T/∂q with the rates held, from T measured at other values of q (the
/// same draw): for an angle, T is a trigonometric polynomial in q of low
/// degree (each frame's rotation enters the velocities once, T twice), so
/// the derivative of its interpolant through nine equally spaced values
/// is exact; for a coordinate that enters as itself, T is a polynomial
/// and Richardson-extrapolated central differences are exact to degree 4.
fn kinetic_energy_partial(w: &World<'_>, a: &[Arg]) -> Out {
    let Arg::Coordinate(q) = a[1] else {
        unreachable!("validated by hdot-sym")
    };
    let (q0, _) = w
        .values
        .get(q)
        .ok_or_else(|| VerifyError::unbound(w.d, "kinetic_energy_partial", q))?;
    let t = |x: f64| -> Result<(f64, f64), VerifyError> {
        let wx = w.at(&w.values.with(q, x))?;
        match kinetic_energy(&wx, &a[..1])? {
            (Measured::Scalar(v), s) => Ok((v, s)),
            _ => unreachable!("a scalar"),
        }
    };
    let (mut v, mut s) = (0.0, 0.0);
    if enters_as_itself(w, q) {
        for (h, c) in [(0.5, 4.0 / 3.0), (1.0, -1.0 / 6.0)] {
            let (p, ps) = t(q0 + h)?;
            let (m, ms) = t(q0 - h)?;
            v += c * (p - m);
            s += c.abs() * (ps + ms);
        }
    } else {
        const M: usize = 9;
        let h = std::f64::consts::TAU / M as f64;
        for j in 1..M {
            let sign = if j % 2 == 0 { -1.0 } else { 1.0 };
            let c = sign * 0.5 / (j as f64 * h / 2.0).sin();
            let (x, xs) = t(q0 + j as f64 * h)?;
            v += c * x;
            s += c.abs() * xs;
        }
    }
    Ok((Measured::Scalar(v), s))
}

/// Whether the coordinate `q` enters the model as itself (a length in a
/// point's place, a rate in a frame's angular velocity), not only through
/// the sine and cosine of a frame's rotation.
fn enters_as_itself(w: &World<'_>, q: hdot_sym::atom::Atom) -> bool {
    use hdot_sym::derivation::physics::PointKind;
    let ph = &w.d.physics;
    let polys = ph
        .points
        .iter()
        .flat_map(|p| match &p.kind {
            PointKind::From { at, .. } | PointKind::Fixed(at, _) => at.0.iter().collect(),
            PointKind::Free => Vec::new(),
        })
        .chain(w.d.frames.iter().flat_map(|f| f.omega.0.iter()));
    polys.map(|p| w.d.unfold(p)).any(|p| p.atoms().contains(&q))
}

/// The speed argument `a` of a Kane quantity.
fn speed(a: &Arg) -> hdot_sym::atom::Atom {
    match a {
        Arg::Speed(u) => *u,
        _ => unreachable!("validated by hdot-sym"),
    }
}

fn generalized_active_force(w: &World<'_>, a: &[Arg]) -> Out {
    let (b, pv) = (bodies(&a[0]), partials(w, speed(&a[1]))?);
    let g = w.gravity;
    // Σ m g · δv = g · Σ m δv over the particles.
    let (momentum, mag) = pv.momentum(w, b);
    let (mut v, mut s) = (g.dot(&momentum), g.norm() * mag);
    for load in w.d.loads.iter().filter(|l| acts_on(w.d, l, b)) {
        let (f, size, (vr, mag)) = match load {
            Load::Force {
                point,
                force,
                frame,
            } => {
                let (f, size) = load_vector(w, force, *frame)?;
                (f, size, pv.point(point))
            }
            Load::Torque {
                on,
                torque,
                in_frame,
            } => {
                let (t, size) = load_vector(w, torque, *in_frame)?;
                (t, size, pv.frame(*on))
            }
        };
        v += f.dot(&vr);
        s += size * mag;
    }
    Ok((Measured::Scalar(v), s))
}

fn generalized_inertia_force(w: &World<'_>, a: &[Arg]) -> Out {
    let (b, pv) = (bodies(&a[0]), partials(w, speed(&a[1]))?);
    let (v, s) = pv.inertia(w, b);
    Ok((Measured::Scalar(-v), s))
}

/// The material point of one body at a point's place: `r = r_O + R q`
/// with q fixed in the body, differentiated as the particles are.
fn material(w: &World<'_>, a: &[Arg], order: usize) -> Out {
    let Bodies::One(i) = bodies(&a[0]) else {
        return Err(VerifyError::Declaration {
            derivation: w.d.name.clone(),
            message: "the point of a body is the point of one body, not of `system`".into(),
        });
    };
    let b = &w.d.physics.bodies[i];
    let (o, p) = (&w.points[&b.point], point(w, &a[1]));
    let r = &w.frames[b.frame];
    let q = r[0].transpose() * (p.r[0] - o.r[0]);
    let mag = (p.mag[0] + o.mag[0]) * r[order].norm();
    Ok((
        Measured::Vector(o.r[order] + r[order] * q),
        o.mag[order] + mag,
    ))
}

fn point_velocity(w: &World<'_>, a: &[Arg]) -> Out {
    material(w, a, 1)
}

fn point_acceleration(w: &World<'_>, a: &[Arg]) -> Out {
    material(w, a, 2)
}

/// The velocities a body at rest takes under an impulse F̂ at a point P:
/// particle velocities `v = v̄ + ω × (r − r_G)` (rigid) with
/// `Σ m v = F̂` and `Σ m (r − r_G) × v = (r_P − r_G) × F̂` (momenta after =
/// impulses, about G taken from the particles). About G the two balances
/// separate (`Σ m (r − r_G) = 0`), so they are solved separately: `v̄` is
/// F̂ over the particles' mass, and ω solves the 3 × 3 system whose
/// columns are the particle momenta `Σ m ρ × (e_j × ρ)` of a unit ω — sums
/// over the particles, no inertia formula — by LU. (Solved as one 6 × 6
/// system, the round-off of `Σ m ρ` coupled a large ω of a thin body into
/// v̄.) Returns (v̄, ω) in N's axes with their magnitudes (ω's scaled by
/// the condition of the inertia it is divided by).
fn after_impulse(w: &World<'_>, a: &[Arg]) -> Result<[(Vector3<f64>, f64); 2], VerifyError> {
    let Bodies::One(_) = bodies(&a[0]) else {
        return Err(VerifyError::Declaration {
            derivation: w.d.name.clone(),
            message: "the response to an impulse is that of one body, not of `system`".into(),
        });
    };
    let ps = w.particles(bodies(&a[0]));
    let p = point(w, &a[1]).r[0];
    let Arg::Vector(f, frame) = &a[2] else {
        unreachable!("validated by hdot-sym")
    };
    let fi =
        w.d.frames
            .iter()
            .position(|x| &x.name == frame)
            .expect("validated by hdot-sym");
    let mut local = Vector3::zeros();
    for (k, c) in f.0.iter().enumerate() {
        local[k] = w
            .values
            .eval(c)
            .map_err(|e| VerifyError::from(e).in_step(w.d, "impulse"))?
            .0;
    }
    let fhat = w.frames[fi][0] * local;
    let m: f64 = ps.clone().map(|q| q.m).sum();
    let g = ps.clone().map(|q| q.r[0] * q.m).sum::<Vector3<f64>>() / m;
    let mut sys = Matrix3::zeros();
    for q in ps {
        let rho = q.r[0] - g;
        for j in 0..3 {
            // ω = e_j: v = e_j × ρ, angular momentum m ρ × v.
            let u = Vector3::ith(j, 1.0).cross(&rho);
            let ang = rho.cross(&u) * q.m;
            for k in 0..3 {
                sys[(k, j)] += ang[k];
            }
        }
    }
    let h = (p - g).cross(&fhat);
    let omega = sys.lu().solve(&h).ok_or_else(|| VerifyError::Singular {
        derivation: w.d.name.clone(),
        what: "the impulse–momentum system of the particles",
    })?;
    let v = fhat / m;
    // ω is the impulse's moment divided by the particle inertia J. Its
    // round-off: J's entries to round-off of the largest (a thin body's
    // small moment, and ω along it, carry the condition number ‖J‖ ‖J⁻¹‖
    // times it), and the moment arm r_P − r_G to round-off of |r_P| + |r_G|
    // (times ‖J⁻¹‖ |F̂|). The scale says so (Frobenius norms).
    let inverse = sys.try_inverse().unwrap_or_else(Matrix3::zeros);
    let omega_scale = omega.norm() * sys.norm() * inverse.norm()
        + inverse.norm() * (p.norm() + g.norm()) * fhat.norm();
    Ok([(v, v.norm() + fhat.norm() / m), (omega, omega_scale)])
}

fn support(a: &[Arg]) -> usize {
    match a {
        [Arg::Support(s)] => *s,
        _ => unreachable!("validated by hdot-sym"),
    }
}

fn reaction(w: &World<'_>, a: &[Arg]) -> Out {
    let r = super::reactions::reaction(w, support(a))?;
    Ok((Measured::Vector(r.force), r.scale))
}

fn reaction_couple(w: &World<'_>, a: &[Arg]) -> Out {
    let r = super::reactions::reaction(w, support(a))?;
    Ok((Measured::Vector(r.couple), r.scale))
}

fn velocity_after_impulse(w: &World<'_>, a: &[Arg]) -> Out {
    let [(v, s), _] = after_impulse(w, a)?;
    Ok((Measured::Vector(v), s))
}

fn angular_velocity_after_impulse(w: &World<'_>, a: &[Arg]) -> Out {
    let [_, (omega, s)] = after_impulse(w, a)?;
    Ok((Measured::Vector(omega), s))
}
