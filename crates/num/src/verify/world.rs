//! The motion of a declared model at one instant, computed independently
//! of the symbolic engine: attitudes of the frame chain as products of
//! elementary rotations differentiated by the product rule (never through
//! a derived ω, the transport theorem or `express`), points as jets
//! (position and three derivatives), particles as `r = r_P + R q`.

use std::cell::RefCell;
use std::rc::Rc;

use hdot_sym::atom::Atom;
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::{
    Bodies, FrameMotion, Meaning, PointKind, Quantity, Rule, RuleValue,
};
use hdot_sym::poly::Poly;
use hdot_sym::vector::Vec3;
use nalgebra::{Matrix3, Vector3};
use rustc_hash::FxHashMap;

use super::VerifyError;
use super::draw::Draw;
use super::jet::{BINOMIAL, fro, generator, hinge_jet_to, mat_mat_to, mat_vec_to, rotation_jet_to};
pub use super::jet::{
    MatJet, ORDERS, PointJet, VecJet, mat_mat, mat_t_vec, mat_vec, rotation_jet, vee,
};
use super::partials::KaneWorlds;
pub(crate) use super::placed::CloudMoments;
pub use super::placed::{Particle, Particles, Placed};
use super::prepared::Prepared;
use crate::bind::Values;

/// A meaning measured at other values of the symbols: its components (N's
/// axes for a vector) and the magnitudes of the terms summed into them.
pub(crate) type Measurement = (Vec<f64>, f64);

/// The measurements made by the worlds of one step (one draw, one set of
/// coordinates), by the bits of the values they were made at. The
/// first-order parts of a linearisation measure the same perturbed worlds
/// again and again: `rate` measures X at zero disturbance whatever the
/// disturbance it is given, so `coefficient(rate(e'', X), e)` would
/// measure the same 25 worlds four times. A measurement is a function of
/// the draw, the coordinates, the values and the meaning, so a repeat is
/// looked up, and its bits are those a new world would give.
/// Keyed by the values' fingerprint ([`Values::fingerprint`], no sort of
/// the values per lookup); each entry holds the values themselves, their
/// bits compared in full ([`Values::same_bits`]).
#[derive(Default)]
struct Memo(RefCell<FxHashMap<u64, Vec<MemoEntry>>>);

/// The values, the meaning, and what it measured.
type MemoEntry = (Values, Meaning, Measurement);

/// The model at one instant.
pub struct World<'d> {
    pub(crate) d: &'d Derivation,
    /// The bodies, free attitudes and free points it was built with.
    pub(crate) draw: &'d Draw,
    /// Attitude jets of the frames (parallel to the derivation's frames).
    pub frames: Vec<MatJet>,
    /// Point jets by name (declared points and body centres).
    pub points: FxHashMap<String, PointJet>,
    /// Each body with the motion that places its particles.
    pub bodies: Vec<Placed<'d>>,
    /// Gravity in N's axes.
    pub gravity: Vector3<f64>,
    /// The coordinate the particles' ∂r/∂q is being computed for.
    coordinate: Option<Atom>,
    /// The orders of the jets computed (the value and `orders − 1` rates;
    /// the higher ones not computed, zero but for a drawn free point's):
    /// [`ORDERS`], or 2 for the models partial velocities are read from
    /// ([`World::build_to`]).
    orders: usize,
    /// The coordinates the particles carry ∂r/∂q for.
    pub coordinates: Vec<Atom>,
    /// The symbols' values it was built from.
    pub values: Values,
    /// The measurements at other values made so far, shared with the
    /// worlds [`World::at`] builds from this one.
    memo: Rc<Memo>,
    /// The models Kane's partial velocities at this state are read from,
    /// made as they are first needed.
    pub(crate) kane: RefCell<KaneWorlds<'d>>,
}

/// The jet of a polynomial's value (`p, ṗ, p̈, p⃛`) under `values`, to
/// the first `orders` orders (the others zero).
pub(crate) fn poly_jet_to(
    p: &Poly,
    values: &Values,
    orders: usize,
) -> Result<[f64; ORDERS], VerifyError> {
    let rates = rates(p, ORDERS);
    let at = rates.prepared.resolve(values);
    let mut out = [0.0; ORDERS];
    for (k, o) in out.iter_mut().enumerate().take(orders) {
        *o = rates.prepared.eval(k, &at)?.0;
    }
    Ok(out)
}

/// The orders of the jets a measurement of `x` reads: Kane's equations —
/// generalized active and inertia forces, in lists, sums and multiples,
/// as a mass matrix or a forcing measures them at other accelerations —
/// read positions, velocities and accelerations (the partial velocities
/// come from models of their own); any other meaning is given every order.
fn orders_read(x: &Meaning) -> usize {
    fn kane(m: &Meaning) -> bool {
        match m {
            Meaning::Quantity(q, _) => matches!(
                q,
                Quantity::GeneralizedActiveForce | Quantity::GeneralizedInertiaForce
            ),
            Meaning::Sum(terms) => terms.iter().all(|(_, m)| kane(m)),
            Meaning::List(items) => items.iter().all(kane),
            Meaning::Scaled(_, m) => kane(m),
            _ => false,
        }
    }
    if kane(x) { 3 } else { ORDERS }
}

/// A polynomial and its first time derivatives ([`rates`]).
pub(crate) struct Rates {
    /// `p, ṗ, p̈, …`
    pub(crate) polys: Vec<Poly>,
    /// The same, prepared: a world reads each atom once for the whole jet
    /// ([`Prepared`], the bits of [`Values::eval`]).
    pub(crate) prepared: Prepared,
}

/// `p` and its time derivatives, at least `count` of them in all. A world
/// is built for every value a linearisation or a sign measures (hundreds
/// per body), and the `[motion]` rules are applied at every draw, step and
/// state measured, always from the same few polynomials of the file (Ω of
/// a frame, where a point sits, a rule's value): each is differentiated
/// once per thread and looked up by address afterwards, the hit confirmed
/// by equality (an address can be reused by another derivation's
/// polynomial once the first is dropped).
pub(crate) fn rates(p: &Poly, count: usize) -> Rc<Rates> {
    type Known = FxHashMap<usize, (Poly, Rc<Rates>)>;
    thread_local! {
        static KNOWN: RefCell<Known> = Default::default();
    }
    let key = p as *const Poly as usize;
    KNOWN.with(|k| {
        let mut k = k.borrow_mut();
        let mut d = match k.get(&key) {
            Some((q, d)) if q == p && d.polys.len() >= count => return d.clone(),
            Some((q, d)) if q == p => d.polys.clone(),
            _ => vec![p.clone()],
        };
        while d.len() < count {
            let next = d[d.len() - 1].dt();
            d.push(next);
        }
        let d = Rc::new(Rates {
            prepared: Prepared::new(&d),
            polys: d,
        });
        // Bounded: a long-running process verifying many files starts over.
        if k.len() >= 4096 {
            k.clear();
        }
        k.insert(key, (p.clone(), d.clone()));
        d
    })
}

fn vec_jet(v: &Vec3, values: &Values, orders: usize) -> Result<VecJet, VerifyError> {
    let c = [
        poly_jet_to(&v.0[0], values, orders)?,
        poly_jet_to(&v.0[1], values, orders)?,
        poly_jet_to(&v.0[2], values, orders)?,
    ];
    Ok(std::array::from_fn(|n| {
        Vector3::new(c[0][n], c[1][n], c[2][n])
    }))
}

/// The jet `q, q̇, q̈, q⃛` of a frame's angle (a constant angle, a fixed
/// tilt, has no rates).
fn angle_jet(
    d: &Derivation,
    values: &Values,
    angle: Atom,
    orders: usize,
) -> Result<[f64; ORDERS], VerifyError> {
    let mut q = [0.0; ORDERS];
    for (n, x) in q.iter_mut().enumerate().take(orders) {
        *x = match n {
            0 => values.get(angle).map(|(v, _)| v),
            _ if !angle.is_time_dependent() => Some(0.0),
            _ => values.time(angle, n as u32).map(|(v, _)| v),
        }
        .ok_or_else(|| VerifyError::unbound(d, "frame", angle))?;
    }
    Ok(q)
}

/// A frame turned from its parent (attitude jet `parent`, partial `∂R/∂q`
/// of the parent in the world's coordinate) by `(rot, g, moves)`: the
/// elementary rotation's jet, its generator, and whether its angle is the
/// coordinate. Its attitude jet and its own `∂R/∂q`.
fn turned(
    parent: &MatJet,
    parent_partial: &Matrix3<f64>,
    (rot, g, moves): (MatJet, Matrix3<f64>, bool),
    orders: usize,
) -> (MatJet, Matrix3<f64>) {
    let jet = mat_mat_to(parent, &rot, orders);
    let mut partial = parent_partial * rot[0];
    if moves {
        partial += parent[0] * rot[0] * g;
    }
    (jet, partial)
}

/// The point at the offset `a` (a jet, in the axes of a frame given by its
/// attitude jet and its `∂R/∂q`) from `base` (its jet and its `∂r/∂q`):
/// `r = r_base + R a` by the product rule, the magnitudes of the terms of
/// each order, and `∂r/∂q = ∂r_base/∂q + ∂R/∂q a (+ R ∂a/∂q)`, `da` the
/// offset's own partial when it depends on the coordinate.
fn offset(
    (base, base_partial): (&PointJet, Vector3<f64>),
    (rj, frame_partial): (&MatJet, &Matrix3<f64>),
    a: &VecJet,
    da: Option<Vector3<f64>>,
    orders: usize,
) -> (PointJet, Vector3<f64>) {
    let r = mat_vec_to(rj, a, orders);
    let mag = std::array::from_fn(|n| {
        if n >= orders {
            return 0.0;
        }
        base.mag[n]
            + (0..=n)
                .map(|k| BINOMIAL[n][k] * fro(&rj[k]) * a[n - k].norm())
                .sum::<f64>()
    });
    let mut partial = base_partial + frame_partial * a[0];
    if let Some(da) = da {
        partial += rj[0] * da;
    }
    let r = std::array::from_fn(|n| base.r[n] + r[n]);
    (PointJet { r, mag }, partial)
}

/// The virtual displacement of coordinate `q` as coefficients of the
/// coordinates' partials: q itself with 1, and every coordinate x that a
/// rule of `[motion]` ties to q with `∂x/∂q` by the chain rule through the
/// rules — for the rule `x⁽ⁿ⁾ = f` (of the lowest order n given for x),
/// `Σ_y ∂f/∂y⁽ⁿ⁾ · ∂y/∂q` over the coordinates y already displaced
/// (`psi' = -phi'/cos(gamma)` moves ψ by −1/cos γ per unit of φ). These
/// are the constrained partial velocities: Σ m a · δr is the generalized
/// force of q in the motions the rules allow. A rule for q itself is not
/// used (q is the independent coordinate named), and a coordinate no rule
/// ties to q stays fixed.
pub(crate) fn displacement(
    d: &Derivation,
    values: &Values,
    q: Atom,
) -> Result<Vec<(Atom, f64)>, VerifyError> {
    let q = q.base();
    let mut rules: Vec<&Rule> = Vec::new();
    for r in &d.physics.motion {
        let t = r.target.base();
        if t == q {
            continue;
        }
        match rules.iter_mut().find(|x| x.target.base() == t) {
            Some(x) if x.target.order() <= r.target.order() => {}
            Some(x) => *x = r,
            None => rules.push(r),
        }
    }
    let mut c: Vec<(Atom, f64)> = vec![(q, 1.0)];
    // A chain of rules is followed in as many passes as it has links.
    for _ in 0..=rules.len() {
        let mut changed = false;
        for r in &rules {
            let (t, n) = (r.target.base(), r.target.order());
            let v = match &r.value {
                RuleValue::QuarterTurns(_) => 0.0,
                RuleValue::Expr(f) => {
                    let mut v = 0.0;
                    for &(y, cy) in c.iter().filter(|(y, _)| *y != t) {
                        let dy = f.partial(Atom::time(y.name(), n));
                        if !dy.is_zero() {
                            v += cy
                                * values
                                    .eval(&dy)
                                    .map_err(|e| {
                                        VerifyError::from(e)
                                            .in_step(d, &format!("given {}", r.text))
                                    })?
                                    .0;
                        }
                    }
                    v
                }
            };
            match c.iter_mut().find(|(x, _)| *x == t) {
                Some(e) if e.1 == v => {}
                Some(e) => {
                    e.1 = v;
                    changed = true;
                }
                None if v == 0.0 => {}
                None => {
                    c.push((t, v));
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    Ok(c)
}

impl<'d> World<'d> {
    /// Builds the model at the instant `values` describe, with the free
    /// attitudes, free points and bodies of `draw`; each particle carries
    /// its virtual displacement `δr` for each of `coordinates`: ∂r/∂q,
    /// plus ∂r/∂x times ∂x/∂q for each coordinate x that `[motion]`'s rules
    /// tie to q ([`displacement`]).
    pub fn build(
        d: &'d Derivation,
        draw: &'d Draw,
        values: &Values,
        coordinates: &[Atom],
    ) -> Result<World<'d>, VerifyError> {
        World::build_to(d, draw, values, coordinates, ORDERS)
    }

    /// [`World::build`] with the jets to the first `orders` orders only
    /// (the higher ones not computed): 2 for a model only positions and
    /// velocities are read from (Kane's partial velocities), with the same
    /// bits in those as a full model's.
    pub(crate) fn build_to(
        d: &'d Derivation,
        draw: &'d Draw,
        values: &Values,
        coordinates: &[Atom],
        orders: usize,
    ) -> Result<World<'d>, VerifyError> {
        let displacements = coordinates
            .iter()
            .map(|q| displacement(d, values, *q))
            .collect::<Result<Vec<_>, _>>()?;
        // The coordinates whose partials are needed, each built once.
        let mut atoms: Vec<Atom> = Vec::new();
        for (x, _) in displacements.iter().flatten() {
            if !atoms.contains(x) {
                atoms.push(*x);
            }
        }
        let mut w = World::build_for(d, draw, values, atoms.first().copied(), orders)?;
        w.coordinates = coordinates.to_vec();
        if atoms.is_empty() {
            return Ok(w);
        }
        // ∂r_P/∂x and ∂R/∂x of each body for each of `atoms`.
        let of = |w: &World<'_>| -> Vec<(Vector3<f64>, Matrix3<f64>)> {
            w.bodies
                .iter()
                .map(|b| (b.dr[0][0].1, b.dr[0][0].2))
                .collect()
        };
        let mut partials: Vec<Vec<(Vector3<f64>, Matrix3<f64>)>> = vec![of(&w)];
        for x in atoms.iter().skip(1) {
            partials.push(of(&World::build_for(d, draw, values, Some(*x), orders)?));
        }
        for (bi, b) in w.bodies.iter_mut().enumerate() {
            b.dr = displacements
                .iter()
                .map(|disp| {
                    disp.iter()
                        .map(|(x, c)| {
                            let k = atoms.iter().position(|a| a == x).expect("collected");
                            let (dref, partial) = partials[k][bi];
                            (*c, dref, partial)
                        })
                        .collect()
                })
                .collect();
        }
        Ok(w)
    }

    fn build_for(
        d: &'d Derivation,
        draw: &'d Draw,
        values: &Values,
        coordinate: Option<Atom>,
        orders: usize,
    ) -> Result<World<'d>, VerifyError> {
        let ph = &d.physics;
        let mut frames: Vec<MatJet> = Vec::with_capacity(d.frames.len());
        // ∂R/∂q of each frame.
        let mut partials: Vec<Matrix3<f64>> = Vec::with_capacity(d.frames.len());
        for (i, motion) in ph.frames.iter().enumerate() {
            let (jet, partial) = match motion {
                FrameMotion::Inertial => (
                    [
                        Matrix3::identity(),
                        Matrix3::zeros(),
                        Matrix3::zeros(),
                        Matrix3::zeros(),
                    ],
                    Matrix3::zeros(),
                ),
                FrameMotion::Rotation {
                    parent,
                    axis,
                    angle,
                } => {
                    let q = angle_jet(d, values, *angle, orders)?;
                    let g = generator(*axis);
                    let turn = (
                        rotation_jet_to(*axis, q, orders),
                        g,
                        Some(angle.base()) == coordinate,
                    );
                    turned(&frames[*parent], &partials[*parent], turn, orders)
                }
                FrameMotion::Hinge {
                    parent,
                    axis,
                    angle,
                } => {
                    let q = angle_jet(d, values, *angle, orders)?;
                    // The axis is constant: its jet's value.
                    let k = vec_jet(axis, values, orders)?[0];
                    let turn = (
                        hinge_jet_to(k, q, orders),
                        k.cross_matrix(),
                        Some(angle.base()) == coordinate,
                    );
                    turned(&frames[*parent], &partials[*parent], turn, orders)
                }
                FrameMotion::Quaternion { parent, e } => {
                    let (_, c) = d.frames[i].parent.as_ref().expect("a turned frame");
                    let at = (&frames[*parent], &partials[*parent]);
                    super::quaternion::turned(at.0, at.1, c, e, coordinate, values, orders)?
                }
                FrameMotion::AngularVelocity => {
                    let w = vec_jet(&d.frames[i].omega, values, orders)?;
                    let wx: [Matrix3<f64>; ORDERS] = std::array::from_fn(|n| w[n].cross_matrix());
                    let r = draw.attitude(i);
                    let mut jet = [r, Matrix3::zeros(), Matrix3::zeros(), Matrix3::zeros()];
                    // Ṙ = R W, differentiated by the product rule.
                    for n in 1..orders {
                        jet[n] = (0..n)
                            .map(|k| BINOMIAL[n - 1][k] * jet[k] * wx[n - 1 - k])
                            .sum();
                    }
                    (jet, Matrix3::zeros())
                }
            };
            frames.push(jet);
            partials.push(partial);
        }
        let mut w = World {
            d,
            draw,
            frames,
            points: FxHashMap::default(),
            bodies: Vec::new(),
            gravity: Vector3::zeros(),
            coordinate,
            orders,
            coordinates: Vec::new(),
            values: values.clone(),
            memo: Rc::default(),
            kane: RefCell::default(),
        };
        if let Some((g, f)) = &ph.gravity {
            let fi = d.frames.iter().position(|x| &x.name == f).expect("frame");
            let g = vec_jet(g, values, orders)?[0];
            w.gravity = w.frames[fi][0] * g;
        }
        let mut point_partials: FxHashMap<String, Vector3<f64>> = FxHashMap::default();
        let names: Vec<String> = ph
            .points
            .iter()
            .map(|p| p.name.clone())
            .chain(ph.bodies.iter().filter_map(|b| b.centre.clone()))
            .collect();
        for n in &names {
            w.point(n, draw, values, &partials, &mut point_partials, 0)?;
        }
        for (bi, b) in ph.bodies.iter().enumerate() {
            let reference = w.point(&b.point, draw, values, &partials, &mut point_partials, 0)?;
            let dref = point_partials[&b.point];
            let rj = w.frames[b.frame];
            w.bodies.push(Placed {
                cloud: draw.body(bi),
                moments: draw.moments(bi),
                reference,
                frame: rj,
                norms: std::array::from_fn(|n| fro(&rj[n])),
                // Only a world built for a coordinate carries ∂r/∂q.
                dr: match coordinate {
                    Some(_) => vec![vec![(1.0, dref, partials[b.frame])]],
                    None => Vec::new(),
                },
            });
        }
        Ok(w)
    }

    /// The same model at the instant `values` describe (the same draw and
    /// coordinates).
    pub(crate) fn at(&self, values: &Values) -> Result<World<'d>, VerifyError> {
        self.at_to(values, ORDERS)
    }

    /// [`World::at`] with the jets to the first `orders` orders only.
    fn at_to(&self, values: &Values, orders: usize) -> Result<World<'d>, VerifyError> {
        let mut w = World::build_to(self.d, self.draw, values, &self.coordinates, orders)?;
        w.memo = self.memo.clone();
        Ok(w)
    }

    /// `x` measured by `measure` on the world [`World::at`] `values`, or
    /// the same measurement made before by a world of this step.
    pub(crate) fn measured_at(
        &self,
        values: &Values,
        x: &Meaning,
        measure: impl FnOnce(&World<'d>) -> Result<Measurement, VerifyError>,
    ) -> Result<Measurement, VerifyError> {
        let key = values.fingerprint();
        if let Some(found) = self.memo.0.borrow().get(&key).and_then(|e| {
            e.iter()
                .find(|(b, m, _)| m == x && b.same_bits(values))
                .map(|(_, _, measured)| measured.clone())
        }) {
            return Ok(found);
        }
        let measured = measure(&self.at_to(values, orders_read(x))?)?;
        self.memo.0.borrow_mut().entry(key).or_default().push((
            values.clone(),
            x.clone(),
            measured.clone(),
        ));
        Ok(measured)
    }

    /// The jet of point `name`, computed once.
    fn point(
        &mut self,
        name: &str,
        draw: &Draw,
        values: &Values,
        partials: &[Matrix3<f64>],
        dp: &mut FxHashMap<String, Vector3<f64>>,
        depth: usize,
    ) -> Result<PointJet, VerifyError> {
        if let Some(p) = self.points.get(name) {
            return Ok(*p);
        }
        if depth > 64 {
            return Err(VerifyError::Declaration {
                derivation: self.d.name.clone(),
                message: format!("point {name} is placed relative to itself"),
            });
        }
        let ph = &self.d.physics;
        let frame_of = |f: &str| {
            self.d
                .frames
                .iter()
                .position(|x| x.name == f)
                .expect("frame")
        };
        let (jet, partial) = if let Some(p) = ph.points.iter().find(|p| p.name == name) {
            match &p.kind {
                PointKind::Fixed(v, f) => {
                    let r = self.frames[frame_of(f)][0] * vec_jet(v, values, self.orders)?[0];
                    (
                        PointJet {
                            r: [r, Vector3::zeros(), Vector3::zeros(), Vector3::zeros()],
                            mag: [r.norm(), 0.0, 0.0, 0.0],
                        },
                        Vector3::zeros(),
                    )
                }
                PointKind::Free => (draw.point(name), Vector3::zeros()),
                PointKind::From { from, at, frame } => {
                    let base = self.point(from, draw, values, partials, dp, depth + 1)?;
                    let fi = frame_of(frame);
                    // The offset's own partial in the coordinate.
                    let da = self.coordinate.map(|q| {
                        Vector3::from_iterator(
                            at.0.iter()
                                .map(|c| values.eval(&c.partial(q)).map(|x| x.0).unwrap_or(0.0)),
                        )
                    });
                    let frame = (&self.frames[fi], &partials[fi]);
                    let a = vec_jet(at, values, self.orders)?;
                    offset((&base, dp[from]), frame, &a, da, self.orders)
                }
            }
        } else {
            let (bi, b) = ph
                .bodies
                .iter()
                .enumerate()
                .find(|(_, b)| b.centre.as_deref() == Some(name))
                .expect("points are validated");
            if b.about_centre() {
                (draw.point(name), Vector3::zeros())
            } else {
                let base = self.point(&b.point, draw, values, partials, dp, depth + 1)?;
                let c = draw.centre(bi);
                let zero = Vector3::zeros();
                let frame = (&self.frames[b.frame], &partials[b.frame]);
                offset(
                    (&base, dp[&b.point]),
                    frame,
                    &[c, zero, zero, zero],
                    None,
                    self.orders,
                )
            }
        };
        self.points.insert(name.to_owned(), jet);
        dp.insert(name.to_owned(), partial);
        Ok(jet)
    }

    /// The bodies `bodies` names, placed at the instant.
    pub(crate) fn placed(&self, bodies: Bodies) -> &[Placed<'d>] {
        let range = match bodies {
            Bodies::One(i) => i..i + 1,
            Bodies::System => 0..self.bodies.len(),
        };
        &self.bodies[range]
    }

    /// The particles of `bodies`, placed at the instant.
    pub fn particles(&self, bodies: Bodies) -> Particles<'_> {
        Particles {
            bodies: self.placed(bodies),
            next: 0,
        }
    }

    /// [`Placed::moment_about`] summed over `bodies`.
    pub fn moment_about<const ORDER: usize>(
        &self,
        bodies: Bodies,
        o: &PointJet,
    ) -> (Vector3<f64>, f64) {
        self.placed(bodies)
            .iter()
            .fold((Vector3::zeros(), 0.0), |(v, m), b| {
                let (bv, bm) = b.moment_about::<ORDER>(o);
                (v + bv, m + bm)
            })
    }
}
