//! The reactions of declared supports, measured on the particles: the
//! resultant force and moment the drawn motion requires (Σ m a and
//! Σ (r − r_O) × m a, particle sums) less the weight (Σ m g and its
//! moment) and the `[[load]]`s on the body, distributed over the supports that hold the body by solving
//! their equilibrium — six equations in the components each support
//! carries (a radial bearing two forces across its axis, a thrust bearing
//! three, a ball three, a clamp three forces and three couples, a floor
//! its normal force or, with friction, three, a drive the couple about
//! its axis) — by a singular value decomposition. A set of supports whose
//! reactions the six equations do not determine (statically
//! indeterminate) and a set that cannot carry what the motion requires
//! (a direction no support holds) are errors that say so; no formula of
//! the file enters.

use hdot_sym::derivation::physics::{Bodies, SupportKind};
use hdot_sym::derivation::{Derivation, Load};
use hdot_sym::vector::Vec3;
use nalgebra::{DMatrix, DVector, Vector3};

use super::means::frame_index;
use super::world::World;
use super::{TOLERANCE_ULPS, VerifyError, declaration};

/// What one support exerts on its body.
pub(crate) struct Reaction {
    /// The force (N's axes).
    pub force: Vector3<f64>,
    /// The couple (N's axes).
    pub couple: Vector3<f64>,
    /// The magnitudes the round-off of both is relative to.
    pub scale: f64,
}

/// One unknown reaction component: a unit direction (N's axes), the
/// support it belongs to, and whether it is a couple.
struct Component {
    support: usize,
    dir: Vector3<f64>,
    couple: bool,
}

/// Two unit vectors across the unit vector `n`.
fn across(n: &Vector3<f64>) -> [Vector3<f64>; 2] {
    let k = n.iamin();
    let e1 = n.cross(&Vector3::ith(k, 1.0)).normalize();
    [e1, n.cross(&e1)]
}

/// The unit axis of support `s` in N's axes.
fn axis(w: &World<'_>, s: usize) -> Result<Vector3<f64>, VerifyError> {
    let sup = &w.d.physics.supports[s];
    let (v, f) = sup.axis.as_ref().expect("validated by hdot-sym");
    let mut local = Vector3::zeros();
    for (k, c) in v.0.iter().enumerate() {
        local[k] = w.values.eval(c)?.0;
    }
    let n = w.frames[frame_index(w.d, f)][0] * local;
    if n.norm() == 0.0 {
        return Err(declaration(
            w.d,
            format!("the axis of support `{}` has zero length here", sup.name),
        ));
    }
    Ok(n.normalize())
}

/// The components the supports of body `b` carry.
fn components(w: &World<'_>, b: usize) -> Result<Vec<Component>, VerifyError> {
    let mut out = Vec::new();
    let frame = [Vector3::x(), Vector3::y(), Vector3::z()];
    for (s, sup) in w.d.physics.supports.iter().enumerate() {
        if sup.body != b {
            continue;
        }
        let force = |dir| Component {
            support: s,
            dir,
            couple: false,
        };
        let couple = |dir| Component {
            support: s,
            dir,
            couple: true,
        };
        match sup.kind {
            SupportKind::Bearing { axial } => {
                let n = axis(w, s)?;
                out.extend(across(&n).map(force));
                if axial {
                    out.push(force(n));
                }
            }
            SupportKind::Ball | SupportKind::Floor { friction: true } => {
                out.extend(frame.map(force));
            }
            SupportKind::Clamp => {
                out.extend(frame.map(force));
                out.extend(frame.map(couple));
            }
            SupportKind::Floor { friction: false } => out.push(force(axis(w, s)?)),
            SupportKind::Drive => out.push(couple(axis(w, s)?)),
        }
    }
    Ok(out)
}

/// Whether a declared `[[load]]` acts on `bodies`: a force at one of the
/// body's points (every point when the file has one body), a torque on its
/// frame; every load acts on the `system`.
pub(crate) fn acts_on(d: &Derivation, load: &Load, bodies: Bodies) -> bool {
    let Bodies::One(b) = bodies else {
        return true;
    };
    let body = &d.physics.bodies[b];
    match load {
        Load::Force { point, .. } => {
            d.physics.bodies.len() == 1
                || *point == body.point
                || Some(point) == body.centre.as_ref()
        }
        Load::Torque { on, .. } => *on == body.frame,
    }
}

/// A load's force or torque in N's axes at the world's instant (its
/// components in frame `frame`), and the magnitude of its terms.
pub(crate) fn load_vector(
    w: &World<'_>,
    v: &Vec3,
    frame: usize,
) -> Result<(Vector3<f64>, f64), VerifyError> {
    let (mut local, mut size) = (Vector3::zeros(), 0.0);
    for (k, c) in v.0.iter().enumerate() {
        let (x, s) = w.values.eval(&w.d.unfold(c))?;
        local[k] = x;
        size += s;
    }
    Ok((w.frames[frame][0] * local, size))
}

/// The reaction of support `s`, from the equilibrium of all supports of
/// its body.
pub(crate) fn reaction(w: &World<'_>, s: usize) -> Result<Reaction, VerifyError> {
    let d = w.d;
    let b = d.physics.supports[s].body;
    let ps: Vec<_> = w.particles(Bodies::One(b)).collect();
    let mass: f64 = ps.iter().map(|p| p.m).sum();
    // Moments about the particles' centroid: the arms stay small.
    let o = ps.iter().map(|p| p.r[0] * p.m).sum::<Vector3<f64>>() / mass;
    let o_mag = ps.iter().map(|p| p.m * p.mag[0]).sum::<f64>() / mass;
    let g = w.gravity;
    let (mut f, mut m) = (Vector3::zeros(), Vector3::zeros());
    let (mut sf, mut sm) = (0.0, 0.0);
    for p in &ps {
        let q = p.r[2] - g;
        let rho = p.r[0] - o;
        f += q * p.m;
        m += rho.cross(&q) * p.m;
        sf += p.m * (p.mag[2] + g.norm());
        sm += p.m * (p.mag[0] + o_mag) * (p.mag[2] + g.norm());
    }
    // The declared loads on the body: forces at its points (every point
    // when the file has one body), torques on its frame.
    for load in d.loads.iter().filter(|l| acts_on(d, l, Bodies::One(b))) {
        match load {
            Load::Force {
                point,
                force,
                frame,
            } => {
                let (fv, size) = load_vector(w, force, *frame)?;
                let at = &w.points[point];
                f -= fv;
                m -= (at.r[0] - o).cross(&fv);
                sf += size;
                sm += size * (at.mag[0] + o_mag);
            }
            Load::Torque {
                torque, in_frame, ..
            } => {
                let (tv, size) = load_vector(w, torque, *in_frame)?;
                m -= tv;
                sm += size;
            }
        }
    }
    let comps = components(w, b)?;
    let names = || -> String {
        d.physics
            .supports
            .iter()
            .filter(|x| x.body == b)
            .map(|x| x.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let body = &d.physics.bodies[b].name;
    let k = comps.len();
    let mut a = DMatrix::<f64>::zeros(6, k);
    let mut arm: f64 = 0.0;
    for (j, c) in comps.iter().enumerate() {
        let (top, bottom) = if c.couple {
            (Vector3::zeros(), c.dir)
        } else {
            let sup = &d.physics.supports[c.support];
            let at = &w.points[sup.point.as_deref().expect("a force acts at a point")];
            let r = at.r[0] - o;
            arm = arm.max(at.mag[0] + o_mag);
            (c.dir, r.cross(&c.dir))
        };
        for i in 0..3 {
            a[(i, j)] = top[i];
            a[(i + 3, j)] = bottom[i];
        }
    }
    let rhs = DVector::from_iterator(6, f.iter().chain(m.iter()).copied());
    let svd = a.clone().svd(true, true);
    let sv = &svd.singular_values;
    let (top, low) = (sv.max(), if k == 0 { 0.0 } else { sv.min() });
    if k == 0 || low <= 1e-9 * top {
        let rank = sv.iter().filter(|x| **x > 1e-9 * top).count();
        return Err(declaration(
            d,
            format!(
                "the supports of `{body}` ({}) are statically indeterminate: of their {k} reaction components only {rank} are determined by the six equations of the body's motion (a combination of them is in equilibrium by itself)",
                names()
            ),
        ));
    }
    let x = svd.solve(&rhs, 0.0).map_err(|_| VerifyError::Singular {
        derivation: d.name.clone(),
        what: "the equilibrium of the supports",
    })?;
    let residual = (&a * &x - &rhs).norm();
    let sb = sf + sm;
    let cond = top / low;
    let scale = (sb + top * x.norm() * (1.0 + arm)) / low;
    if residual > TOLERANCE_ULPS * f64::EPSILON * (sb + top * x.norm()) * cond * (1.0 + arm) {
        return Err(declaration(
            d,
            format!(
                "the supports of `{body}` ({}) cannot carry the force and moment the drawn motion requires (Σ m a less the weight, and its moment: {residual:.3e} is left over): a direction is held by none of them — declare the support that holds it (a thrust bearing, a drive about the shaft) or give the step the condition that removes it (`given = [\"phi'' = 0\"]`)",
                names()
            ),
        ));
    }
    let (mut force, mut couple) = (Vector3::zeros(), Vector3::zeros());
    for (c, xj) in comps.iter().zip(x.iter()) {
        if c.support != s {
            continue;
        }
        if c.couple {
            couple += c.dir * *xj;
        } else {
            force += c.dir * *xj;
        }
    }
    Ok(Reaction {
        force,
        couple,
        scale,
    })
}
