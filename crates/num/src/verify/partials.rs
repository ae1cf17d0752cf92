//! Kane's partial velocities measured at a drawn state, never taken from
//! the engine: the model is built at the drawn speeds and again with one
//! independent speed raised by one — the dependent speeds solved again
//! from the constraint rows and the coordinates' rates again from the
//! kinematic equations ([`super::speeds`]) — and, the velocities being
//! linear in the speeds, each particle's, point's and frame's partial
//! velocity for that speed is the difference of the two (exact up to
//! rounding). These are the constrained partial velocities: the dependent
//! speeds move with the independent one as the constraints require.
//! Their sums over a body's particles (`Σ m δv`, `Σ m a · δv`) are formed
//! from the body's particle sums (the particles are `r = r_P + R q`).
//! The models are made once per state and speed in a draw ([`KaneCache`]).

use std::cell::RefCell;
use std::rc::Rc;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::{Bodies, FrameMotion, PointKind};
use hdot_sym::poly::Poly;
use nalgebra::Vector3;
use rustc_hash::FxHashMap;

use super::placed::PartialVelocity;
use super::speeds::Speeds;
use super::world::{World, vee};
use super::{VerifyError, declaration};
use crate::bind::{Values, nth};

/// The orders of the models partial velocities are read from: positions
/// and velocities ([`Partials::between`] reads no acceleration).
const PARTIAL_ORDERS: usize = 2;

/// Kane's partial velocities for one speed at one state: of each body
/// ([`PartialVelocity`]), of each point and of each frame (N's axes), with
/// their magnitudes — the model with the speed raised by one less the
/// model at the drawn speeds, both consistent with the constraints.
pub(crate) struct Partials {
    bodies: Vec<PartialVelocity>,
    points: FxHashMap<String, (Vector3<f64>, f64)>,
    frames: Vec<(Vector3<f64>, f64)>,
}

/// The models at the drawn speeds, made once per world: every generalized
/// active and inertia force a world measures (two per speed) shares it.
#[derive(Default)]
pub(crate) struct KaneWorlds<'d> {
    /// The partial velocities of the world's state in the draw's
    /// [`KaneCache`], found once per world (not once per speed).
    state: Option<State>,
    /// The values with the dependent speeds and the coordinates' rates
    /// filled in, and the model at them.
    base: Option<(Values, Rc<World<'d>>)>,
}

/// Each speed's [`Partials`] by the state they were measured at, kept by
/// a draw for all the worlds built with it: the worlds of one draw differ
/// mostly in what partial velocities do not read (the unit rates a mass
/// matrix is measured at, the steps `kane`, `mass_matrix`, `forcing` and a
/// power balance all measure at the drawn state), so each state's models
/// are made once per draw, not once per world (the nonlinear bicycle made
/// 108 models per draw for 9 distinct ones). A clone starts empty (a
/// draw changed for a step's conditions is another draw).
///
/// The state partial velocities are a function of is every bound atom
/// with the bits of its value and size when the models' positions and
/// velocities, or the drawing of the dependent speeds and the
/// coordinates' rates, can read it ([`velocity_reads`]), the others by
/// their presence only ([`Values::same_state`]); the states are found by
/// their [`Values::state_fingerprint`] (no sort of the values per world).
#[derive(Default)]
pub(crate) struct KaneCache(RefCell<FxHashMap<u64, Vec<(Values, State)>>>);

/// The partial velocities of one state, shared by the cache and the
/// worlds at that state.
type State = Rc<RefCell<BySpeed>>;

/// The partial velocities of one state, by speed.
type BySpeed = Vec<(Atom, Rc<Partials>)>;

impl Clone for KaneCache {
    fn clone(&self) -> KaneCache {
        KaneCache::default()
    }
}

impl std::fmt::Debug for KaneCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "KaneCache({} states)", self.0.borrow().len())
    }
}

/// The atoms [`Values::get`] reads for `a`: a sine or cosine its angle, a
/// sum of constants its terms' atoms.
fn read_atoms(a: Atom, out: &mut Vec<Atom>) {
    match a.kind() {
        AtomKind::Var { .. } => out.push(a),
        AtomKind::Sin(q) | AtomKind::Cos(q) => out.push(q),
        AtomKind::Sum { sum, .. } => {
            for b in sum.atoms() {
                read_atoms(b, out);
            }
        }
    }
}

/// The atoms a model's positions and velocities (the orders partial
/// velocities read) are computed from — the frames' angles and their
/// rates, the hinge axes, the Euler parameters' direction cosines and
/// their rates, the angular velocities, the points' offsets and their
/// rates — and those the dependent speeds and the coordinates' rates are
/// drawn from ([`Speeds::reads`]), with the speeds; sorted. Read once per
/// check.
pub(crate) fn velocity_reads(d: &Derivation, speeds: &Speeds) -> Vec<Atom> {
    let mut polys: Vec<Poly> = Vec::new();
    let mut atoms: Vec<Atom> = speeds.reads();
    atoms.extend(d.speeds().iter().copied());
    for (i, motion) in d.physics.frames.iter().enumerate() {
        let angle = match motion {
            FrameMotion::Inertial => None,
            FrameMotion::Rotation { angle, .. } => Some(*angle),
            FrameMotion::Hinge { axis, angle, .. } => {
                polys.extend(axis.0.iter().cloned());
                Some(*angle)
            }
            FrameMotion::Quaternion { .. } => {
                let (_, c) = d.frames[i].parent.as_ref().expect("a turned frame");
                for p in c.0.iter().flatten() {
                    polys.push(p.dt());
                    polys.push(p.clone());
                }
                None
            }
            FrameMotion::AngularVelocity => {
                polys.extend(d.frames[i].omega.0.iter().cloned());
                None
            }
        };
        if let Some(q) = angle {
            atoms.push(q);
            if q.is_time_dependent() {
                atoms.push(nth(q, 1));
            }
        }
    }
    for p in &d.physics.points {
        match &p.kind {
            PointKind::Fixed(v, _) => polys.extend(v.0.iter().cloned()),
            PointKind::From { at, .. } => {
                for c in &at.0 {
                    polys.push(c.dt());
                    polys.push(c.clone());
                }
            }
            PointKind::Free => {}
        }
    }
    atoms.extend(polys.iter().flat_map(Poly::atoms));
    let mut out = Vec::new();
    for a in atoms {
        read_atoms(a, &mut out);
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The partial velocities for speed `u` at the state of `w`, made once
/// per state and draw ([`KaneCache`]).
///
/// # Errors
/// A file without kinematic equations, a dependent speed named (its
/// partial velocities are not those of Kane's equations), or constraints
/// whose dependent speeds cannot be solved at the state.
pub(crate) fn partials(w: &World<'_>, u: Atom) -> Result<Rc<Partials>, VerifyError> {
    let d = w.d;
    let consistent = w.draw.consistent();
    let Some(speeds) = &consistent.speeds else {
        return Err(declaration(
            d,
            "a generalized active or inertia force needs the kinematic equations ([kinematics])"
                .into(),
        ));
    };
    if speeds.dependent.contains(&u) {
        return Err(declaration(
            d,
            format!(
                "`{u}` is a dependent speed of the `kane` step: Kane's generalized forces are taken for the \
                 independent speeds"
            ),
        ));
    }
    let known = w.kane.borrow().state.clone();
    let state = match known {
        Some(s) => s,
        None => {
            let reads = consistent.velocity_reads();
            let mut cache = w.draw.kane_cache().0.borrow_mut();
            let states = cache.entry(w.values.state_fingerprint(reads)).or_default();
            let s = match states.iter().find(|(v, _)| v.same_state(&w.values, reads)) {
                Some((_, s)) => s.clone(),
                None => {
                    let s = State::default();
                    states.push((w.values.clone(), s.clone()));
                    s
                }
            };
            w.kane.borrow_mut().state = Some(s.clone());
            s
        }
    };
    if let Some((_, p)) = state.borrow().iter().find(|(v, _)| *v == u) {
        return Ok(p.clone());
    }
    let unbound = || {
        declaration(
            d,
            "a symbol of the kinematic equations or of the constraints has no value".into(),
        )
    };
    let known = w.kane.borrow().base.clone();
    let (base, base_world) = match known {
        Some(b) => b,
        None => {
            let mut base = w.values.clone();
            speeds.fill(d, &mut base, 1)?.ok_or_else(unbound)?;
            let world = Rc::new(World::build_to(d, w.draw, &base, &[], PARTIAL_ORDERS)?);
            w.kane.borrow_mut().base = Some((base.clone(), world.clone()));
            (base, world)
        }
    };
    let (x, _) = base.get(u).ok_or_else(unbound)?;
    let mut raised = base.with(u, x + 1.0);
    speeds.fill(d, &mut raised, 1)?.ok_or_else(unbound)?;
    let raised = World::build_to(d, w.draw, &raised, &[], PARTIAL_ORDERS)?;
    let p = Rc::new(Partials::between(&raised, &base_world));
    state.borrow_mut().push((u, p.clone()));
    Ok(p)
}

/// The range of [`World::placed`]`(b)` among `n` bodies.
fn range(b: Bodies, n: usize) -> std::ops::Range<usize> {
    match b {
        Bodies::One(i) => i..i + 1,
        Bodies::System => 0..n,
    }
}

impl Partials {
    /// The model `raised` less the model `base`.
    fn between(raised: &World<'_>, base: &World<'_>) -> Partials {
        let omega = |w: &World<'_>, f: usize| {
            let r = &w.frames[f];
            (vee(&(r[1] * r[0].transpose())), r[1].norm())
        };
        Partials {
            bodies: raised
                .bodies
                .iter()
                .zip(&base.bodies)
                .map(|(r, q)| PartialVelocity::of(r, q))
                .collect(),
            points: base
                .points
                .iter()
                .map(|(name, q)| {
                    let p = &raised.points[name];
                    (name.clone(), (p.r[1] - q.r[1], p.mag[1] + q.mag[1]))
                })
                .collect(),
            frames: (0..base.frames.len())
                .map(|f| {
                    let ((p, ps), (q, qs)) = (omega(raised, f), omega(base, f));
                    (p - q, ps + qs)
                })
                .collect(),
        }
    }

    /// `Σ m δv` over the particles of `b` (δv each particle's partial
    /// velocity) and the sum of their magnitudes, from each body's
    /// particle sums in `w` ([`super::placed::Placed::partial_momentum`]).
    pub(crate) fn momentum(&self, w: &World<'_>, b: Bodies) -> (Vector3<f64>, f64) {
        let own = &self.bodies[range(b, self.bodies.len())];
        w.placed(b)
            .iter()
            .zip(own)
            .fold((Vector3::zeros(), 0.0), |(v, m), (q, p)| {
                let (bv, bm) = q.partial_momentum(p);
                (v + bv, m + bm)
            })
    }

    /// `Σ m a · δv` over the particles of `b`, a their accelerations in
    /// `w` (the model at the same instant), and the sum of the magnitudes
    /// of its terms ([`super::placed::Placed::partial_power`]).
    pub(crate) fn inertia(&self, w: &World<'_>, b: Bodies) -> (f64, f64) {
        let own = &self.bodies[range(b, self.bodies.len())];
        w.placed(b)
            .iter()
            .zip(own)
            .fold((0.0, 0.0), |(v, m), (q, p)| {
                let (bv, bm) = q.partial_power::<2>(p);
                (v + bv, m + bm)
            })
    }

    /// The partial velocity of point `name` and its magnitude.
    pub(crate) fn point(&self, name: &str) -> (Vector3<f64>, f64) {
        self.points[name]
    }

    /// The partial angular velocity of frame `f` (N's axes) and its
    /// magnitude.
    pub(crate) fn frame(&self, f: usize) -> (Vector3<f64>, f64) {
        self.frames[f]
    }
}
