//! One draw of a verification: random bodies with the declared symmetry
//! (particles copied so that the symmetry is exact), their symbols bound
//! from the particles, random values of the other symbols, attitudes of
//! frames given by their angular velocity and motions of free points; the
//! `[motion]` rules and a step's `given` applied to the values; and the
//! draw a step's own conditions (`symmetry`, points at rest, inequalities
//! selecting a class of bodies) call for.

use std::rc::Rc;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::{
    Body, FrameMotion, PointKind, Rule, RuleValue, StepMeaning, Symmetry,
};
use hdot_sym::poly::Poly;
use hdot_sym::symbols::Decl;
use nalgebra::{Matrix3, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rustc_hash::FxHashMap;

use super::bodies::{axisymmetric, map_particles, mirrored, random_body, random_rotation};
use super::jet::{ORDERS, PointJet};
use super::partials::KaneCache;
use super::speeds::Consistent;
use super::world::{CloudMoments, rates};
use super::{VerifyError, declaration};
use crate::bind::{MeasuredBody, Values, bind_all, declared_equations, nth};
use crate::cloud::ParticleCloud;

/// Highest derivative order drawn for a time symbol.
pub(crate) const MAX_ORDER: u32 = 6;

/// What one draw fixes besides the symbols' values: the bodies (body axes,
/// about the reference point), their centres, free attitudes and free
/// points.
#[derive(Clone, Debug)]
pub struct Draw {
    /// Each body with its declared symmetry, about the point its inertia
    /// is about (G moved to the origin when that is the centre).
    bases: Vec<ParticleCloud>,
    /// The rotated copies an axisymmetric body is made of.
    folds: Vec<usize>,
    bodies: Vec<ParticleCloud>,
    /// The sums over each body's particles a moment is formed from.
    moments: Vec<CloudMoments>,
    centres: Vec<Vector3<f64>>,
    attitudes: FxHashMap<usize, Matrix3<f64>>,
    points: FxHashMap<String, PointJet>,
    /// The speeds and constraints the motion is drawn consistent with
    /// (read once per check).
    consistent: Rc<Consistent>,
    /// Whether the bodies were drawn (not given): drawn bodies are given
    /// the equal moments their declarations state ([`equal_moments`]).
    drawn: bool,
    /// The partial velocities measured in this draw, by state.
    kane: KaneCache,
}

impl Draw {
    /// The particles of body `i` (body axes, about its reference point).
    pub fn body(&self, i: usize) -> &ParticleCloud {
        &self.bodies[i]
    }

    /// The particle sums of body `i` ([`CloudMoments`]).
    pub(crate) fn moments(&self, i: usize) -> &CloudMoments {
        &self.moments[i]
    }

    /// G of body `i` from its reference point, body axes.
    pub fn centre(&self, i: usize) -> Vector3<f64> {
        self.centres[i]
    }

    /// The partial velocities measured in this draw ([`KaneCache`]).
    pub(crate) fn kane_cache(&self) -> &KaneCache {
        &self.kane
    }

    /// The speeds and constraints of the check ([`Consistent`]).
    pub(crate) fn consistent(&self) -> &Consistent {
        &self.consistent
    }

    pub(crate) fn attitude(&self, frame: usize) -> Matrix3<f64> {
        self.attitudes[&frame]
    }

    pub(crate) fn point(&self, name: &str) -> PointJet {
        self.points[name]
    }
}

/// A body with the declared symmetry about the origin (the reference
/// point): copies mirrored in planes or turned about an axis.
pub fn symmetric(
    cloud: &ParticleCloud,
    symmetry: Symmetry,
    fold: usize,
) -> Result<ParticleCloud, VerifyError> {
    Ok(match symmetry {
        Symmetry::None => cloud.clone(),
        Symmetry::Principal => mirrored(cloud, [true; 3])?,
        Symmetry::Plane(k) => {
            let mut n = [false; 3];
            n[k] = true;
            mirrored(cloud, n)?
        }
        Symmetry::Axisymmetric(k) => {
            // Axis k to z, the copies turned about z, and z back to axis k
            // (cyclic permutations, proper rotations): a cloud already on
            // axis k (a slender rod along x, [`on_axes`]) stays on it.
            let to_z = map_particles(cloud, |p, m| {
                let q = match k {
                    0 => Vector3::new(p.y, p.z, p.x),
                    1 => Vector3::new(p.z, p.x, p.y),
                    _ => p,
                };
                [(q, m)]
            })?;
            let c = axisymmetric(&to_z, fold)?;
            map_particles(&c, |p, m| {
                let q = match k {
                    0 => Vector3::new(p.z, p.x, p.y),
                    1 => Vector3::new(p.y, p.z, p.x),
                    _ => p,
                };
                [(q, m)]
            })?
        }
    })
}

fn random_vector(rng: &mut impl Rng, s: f64) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
        rng.gen_range(-s..s),
    )
}

/// Draws bodies, free motions and symbol values; binds the bodies'
/// symbols.
pub(crate) fn draw(
    d: &Derivation,
    rng: &mut ChaCha8Rng,
    given: Option<&[ParticleCloud]>,
    consistent: &Rc<Consistent>,
) -> Result<(Draw, Values), VerifyError> {
    let ph = &d.physics;
    let mut values = Values::default();
    let mut eqs = Vec::new();
    let mut bases: Vec<ParticleCloud> = Vec::new();
    let mut folds = Vec::new();
    for (k, b) in ph.bodies.iter().enumerate() {
        let fold = rng.gen_range(3..=6);
        let cloud = match (given, twin(ph, k)) {
            // Given bodies have their symmetry already.
            (Some(g), _) => base_body(b, &g[k], Symmetry::None, fold, false)?,
            // Declared as an earlier body (two wheels sharing m_w, I_w,
            // J_w): the same particles, or the shared symbols could not
            // be bound from both.
            (None, Some(j)) => bases[j].clone(),
            (None, None) => {
                let cloud = base_body(b, &drawn_body(b, rng)?, b.symmetry, fold, true)?;
                declared_mass(b, &ph.bodies[..k], &bases, cloud)?
            }
        };
        eqs.extend(body_equations(b, &cloud));
        bases.push(cloud);
        folds.push(fold);
    }
    // Symbols the bodies and knowns bind are left unbound here.
    let declared: Vec<Atom> = ph
        .bodies
        .iter()
        .flat_map(|b| {
            let mut v = b.mass.as_ref().map(Poly::atoms).unwrap_or_default();
            v.extend(
                b.mass_centre
                    .iter()
                    .filter(|_| !b.inertia_about_centre)
                    .flat_map(|c| c.0.iter().flat_map(Poly::atoms)),
            );
            v.extend(b.inertia.0.iter().flatten().flat_map(Poly::atoms));
            v
        })
        .chain(
            ph.knowns
                .iter()
                .flat_map(|k| k.value.components().into_iter().flat_map(Poly::atoms)),
        )
        .collect();
    for name in d.symbols.names() {
        match d.symbols.get(name) {
            Some(Decl::Constant) => {
                let a = Atom::constant(name);
                if !declared.contains(&a) {
                    let v = rng.gen_range(0.5..2.0);
                    values.set(a, v, v);
                }
            }
            Some(Decl::Time) => {
                let a = Atom::time(name, 0);
                for n in 0..=MAX_ORDER {
                    let x = nth(a, n);
                    if !declared.contains(&x) {
                        let v = rng.gen_range(-2.0..2.0);
                        values.set(x, v, v);
                    }
                }
            }
            _ => {}
        }
    }
    // What the file declares positive (cos θ of an angle below a right
    // angle) is drawn so: the angle (or the constant) drawn again.
    for &p in &ph.positive {
        let q = match p.kind() {
            AtomKind::Sin(q) | AtomKind::Cos(q) => q,
            _ => p,
        };
        if declared.contains(&q) {
            continue;
        }
        let mut tries = 0;
        while values.get(p).is_some_and(|(v, _)| v <= 0.0) {
            tries += 1;
            if tries > 64 {
                return Err(declaration(
                    d,
                    format!("no drawn value of {q} makes {p} positive, as [symbols] positive says"),
                ));
            }
            let v = if q.is_time_dependent() {
                rng.gen_range(-2.0..2.0)
            } else {
                rng.gen_range(0.5..2.0)
            };
            values.set(q, v, v);
        }
    }
    consistent.away_from_singularities(&mut values, &declared);
    // The dependent coordinates from the configuration constraints.
    if let Some(s) = &consistent.speeds {
        super::configuration::meet(d, &s.configuration, &mut values, &declared, rng)?;
    }
    bind_all(d, &mut values, eqs)?;
    // The coordinates' rates from the speeds, the dependent speeds from
    // the constraints.
    consistent.fill(d, &mut values)?;
    let mut bodies = Vec::new();
    let mut moments = Vec::new();
    let mut centres = Vec::new();
    for (b, base) in ph.bodies.iter().zip(&bases) {
        let (cloud, c) = place(d, b, base, &values)?;
        moments.push(CloudMoments::of(&cloud));
        bodies.push(cloud);
        centres.push(c);
    }
    let mut attitudes = FxHashMap::default();
    for (i, m) in ph.frames.iter().enumerate() {
        if *m == FrameMotion::AngularVelocity {
            attitudes.insert(i, *random_rotation(rng).matrix());
        }
    }
    let mut points = FxHashMap::default();
    let free = ph
        .points
        .iter()
        .filter(|p| p.kind == PointKind::Free)
        .map(|p| p.name.clone())
        .chain(
            ph.bodies
                .iter()
                .filter(|b| b.about_centre())
                .filter_map(|b| b.centre.clone()),
        );
    for name in free {
        let r: [Vector3<f64>; ORDERS] = std::array::from_fn(|_| random_vector(rng, 3.0));
        points.insert(
            name,
            PointJet {
                r,
                mag: std::array::from_fn(|n| r[n].norm()),
            },
        );
    }
    Ok((
        Draw {
            bases,
            folds,
            bodies,
            moments,
            centres,
            attitudes,
            points,
            consistent: consistent.clone(),
            drawn: given.is_none(),
            kane: KaneCache::default(),
        },
        values,
    ))
}

/// Σ m (|q|² E − q qᵀ) about the origin.
fn inertia_about_origin(c: &ParticleCloud) -> Matrix3<f64> {
    (0..c.len())
        .map(|k| {
            let (q, m) = c.particle(k);
            m * (Matrix3::identity() * q.norm_squared() - q * q.transpose())
        })
        .sum()
}

/// The body axes along which every particle of `b` lies: a moment of
/// inertia declared zero on the diagonal (`principal(Ip, Ip, 0)`, a
/// slender rod along z) is `Σ m (x² + y²) = 0`, which only particles on
/// that axis (through the point the inertia is about) have. Two zero
/// moments put every particle at the point.
pub(crate) fn line_axes(b: &Body) -> [bool; 3] {
    std::array::from_fn(|k| b.inertia.0[k][k].is_zero())
}

/// `cloud` with the particles moved onto the axes `zero` flags (every
/// coordinate off them set to 0): a line body along the one flagged axis,
/// a point mass for two or three. Unchanged when none is flagged.
pub(crate) fn on_axes(
    cloud: &ParticleCloud,
    zero: [bool; 3],
) -> Result<ParticleCloud, VerifyError> {
    if !zero.iter().any(|z| *z) {
        return Ok(cloud.clone());
    }
    // Coordinate j survives when every flagged axis is j.
    let keep: [f64; 3] =
        std::array::from_fn(|j| f64::from(u8::from((0..3).all(|k| !zero[k] || k == j))));
    Ok(map_particles(cloud, |p, m| {
        [(p.component_mul(&Vector3::from(keep)), m)]
    })?)
}

/// The earlier body whose declared inertia (with a symbol in it), symmetry
/// and reference are those of body `k`, if any: it is drawn as that one.
fn twin(ph: &hdot_sym::derivation::physics::Physics, k: usize) -> Option<usize> {
    let b = &ph.bodies[k];
    if b.inertia.0.iter().flatten().all(|p| p.atoms().is_empty()) {
        return None;
    }
    ph.bodies[..k].iter().position(|e| {
        e.inertia == b.inertia
            && e.symmetry == b.symmetry
            && e.inertia_about_centre == b.inertia_about_centre
            && e.about_centre() == b.about_centre()
            && e.mass == b.mass
    })
}

/// `cloud` with the mass `b` declares when the declaration fixes it: a
/// number (`mass = "1"`), or the mass symbol of an earlier body (whose
/// drawn particles bound it), the particles' masses scaled to it (the
/// inertia scales with them, and its symbols are bound from the result).
fn declared_mass(
    b: &Body,
    earlier: &[Body],
    bases: &[ParticleCloud],
    cloud: ParticleCloud,
) -> Result<ParticleCloud, VerifyError> {
    let Some(mass) = &b.mass else {
        return Ok(cloud);
    };
    let target = match mass.as_constant() {
        Some(c) => c.to_f64(),
        None => match earlier.iter().position(|e| e.mass.as_ref() == Some(mass)) {
            Some(j) => bases[j].mass_properties().mass,
            None => return Ok(cloud),
        },
    };
    let have = cloud.mass_properties().mass;
    if !(target > 0.0 && target.is_finite()) {
        return Ok(cloud);
    }
    let f = target / have;
    Ok(map_particles(&cloud, |p, m| [(p, m * f)])?)
}

/// `cloud` (about the point its declared inertia is about) with the equal
/// moments of inertia the declaration states (`principal(I, I, I)`, or
/// `principal(A, A, C)` without an axisymmetry that makes them so): each
/// particle copied with the coordinates of the axes whose moments are
/// declared equal exchanged — for two, a reflection in the plane between
/// them; for three, the cyclic permutations —, each copy with its share
/// of the mass. A declared symmetry keeps: the exchange maps the axes of
/// equal moments onto each other. Bodies on a line (a zero moment) have
/// their two equal moments already.
pub(crate) fn equal_moments(b: &Body, cloud: &ParticleCloud) -> Result<ParticleCloud, VerifyError> {
    if line_axes(b).iter().any(|z| *z) {
        return Ok(cloud.clone());
    }
    let diag = |k: usize| &b.inertia.0[k][k];
    let equal = |i: usize, j: usize| diag(i) == diag(j);
    if equal(0, 1) && equal(1, 2) {
        return Ok(map_particles(cloud, |p, m| {
            [
                (p, m / 3.0),
                (Vector3::new(p.y, p.z, p.x), m / 3.0),
                (Vector3::new(p.z, p.x, p.y), m / 3.0),
            ]
        })?);
    }
    let transverse = match b.symmetry {
        Symmetry::Axisymmetric(k) => Some(((k + 1) % 3, (k + 2) % 3)),
        _ => None,
    };
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let already = transverse.is_some_and(|(a, c)| (a.min(c), a.max(c)) == (i, j));
        if equal(i, j) && !already {
            return Ok(map_particles(cloud, |p, m| {
                let mut q = p;
                q.swap_rows(i, j);
                [(p, m / 2.0), (q, m / 2.0)]
            })?);
        }
    }
    Ok(cloud.clone())
}

/// A random body for the declaration `b`, before its symmetry: on the
/// axis its zero moments of inertia require ([`line_axes`]).
fn drawn_body(b: &Body, rng: &mut ChaCha8Rng) -> Result<ParticleCloud, VerifyError> {
    on_axes(&random_body(rng)?, line_axes(b))
}

/// The body `b` drawn as `cloud`, given the symmetry `symmetry` (about
/// the origin) and moved so that the origin is the point its inertia is
/// about.
fn base_body(
    b: &Body,
    cloud: &ParticleCloud,
    symmetry: Symmetry,
    fold: usize,
    drawn: bool,
) -> Result<ParticleCloud, VerifyError> {
    let cloud = symmetric(cloud, symmetry, fold)?;
    let equal = |c: ParticleCloud| {
        if drawn { equal_moments(b, &c) } else { Ok(c) }
    };
    // About its centre, or G declared at the reference point: G moved to
    // the origin (along the symmetry axis or in the symmetry plane, where
    // the symmetry puts it, so the symmetry is kept).
    if b.about_centre()
        || b.inertia_about_centre
        || b.mass_centre.as_ref().is_some_and(|c| c.is_zero())
    {
        let g = cloud.mass_properties().center;
        return equal(map_particles(&cloud, |p, m| [(p - g, m)])?);
    }
    equal(cloud)
}

/// The body about its reference point and its centre from there: `base`
/// itself, or `base` moved by the declared `mass_centre` when its inertia
/// is about the centre.
fn place(
    d: &Derivation,
    b: &Body,
    base: &ParticleCloud,
    values: &Values,
) -> Result<(ParticleCloud, Vector3<f64>), VerifyError> {
    if !b.inertia_about_centre {
        return Ok((base.clone(), base.mass_properties().center));
    }
    let mc = b.mass_centre.as_ref().expect("validated by hdot-sym");
    let mut c = Vector3::zeros();
    for k in 0..3 {
        c[k] = values
            .eval(&mc.0[k])
            .map_err(|e| VerifyError::from(e).in_step(d, &format!("mass_centre of {}", b.name)))?
            .0;
    }
    Ok((map_particles(base, |p, m| [(p + c, m)])?, c))
}

/// The declarations of `b` as equations on the particles of `cloud`
/// (about the point its inertia is about).
fn body_equations(b: &Body, cloud: &ParticleCloud) -> Vec<(Poly, f64, f64, String)> {
    let mp = cloud.mass_properties();
    let measured = MeasuredBody {
        mass: mp.mass,
        centre: mp.center,
        inertia: inertia_about_origin(cloud),
    };
    declared_equations(b, &measured, !b.inertia_about_centre)
}

/// Applies conditions to the values (rules in order).
pub(crate) fn apply(
    d: &Derivation,
    values: &mut Values,
    rules: &[Rule],
) -> Result<(), VerifyError> {
    for r in rules {
        if !r.target.is_time_dependent() {
            // A constant's value (`s = 0`): a special case of the file.
            let (v, s) = match &r.value {
                RuleValue::QuarterTurns(t) => (*t as f64 * std::f64::consts::FRAC_PI_2, 1.0),
                RuleValue::Expr(p) => values
                    .eval(p)
                    .map_err(|e| VerifyError::from(e).in_step(d, &format!("given {}", r.text)))?,
            };
            values.set(r.target, v, s);
            continue;
        }
        let from = r.target.order();
        let base = Atom::time(r.target.name(), 0);
        match &r.value {
            RuleValue::QuarterTurns(t) => {
                values.set(base, *t as f64 * std::f64::consts::FRAC_PI_2, 1.0);
                for n in 1..=MAX_ORDER {
                    values.set(nth(base, n), 0.0, 0.0);
                }
            }
            RuleValue::Expr(p) => {
                // The rules are applied at every draw, step and state a
                // step measures (50,400 times for the disk rolling on a
                // plane): their rates are made once ([`rates`]).
                let rates = rates(p, (MAX_ORDER + 1).saturating_sub(from) as usize);
                for (n, q) in (from..=MAX_ORDER).zip(&rates.polys) {
                    let (v, s) = match values.eval(q) {
                        Ok(x) => x,
                        // Derivatives beyond those drawn (a rule in a rate).
                        Err(_) if n > from => break,
                        Err(e) => {
                            return Err(
                                VerifyError::from(e).in_step(d, &format!("given {}", r.text))
                            );
                        }
                    };
                    values.set(nth(base, n), v, s);
                }
            }
        }
    }
    Ok(())
}

/// Applies a step's `given`, then `[motion]`'s rules (whose derived
/// rates follow the step's conditions: rolling with θ̈ = 0 keeps the
/// rolling rates), then the step's `given` again (which wins).
pub(crate) fn constrain(
    d: &Derivation,
    values: &mut Values,
    given: &[Rule],
) -> Result<(), VerifyError> {
    apply(d, values, given)?;
    apply(d, values, &d.physics.motion)?;
    apply(d, values, given)
}

/// The draw and values of a step whose `symmetry` gives bodies more
/// symmetry, whose `given` sets free points at rest, or whose inequalities
/// (`given = ["A > B"]`) select a class of bodies: the bodies copied into
/// the symmetric form (about the point their inertia is about) and their
/// symbols bound again, the points' motion cut from the order given. For
/// inequalities every body is stretched along its own axes (by factors
/// from ¼ to 4, the two transverse axes of an axisymmetric body alike, so
/// that the symmetry is kept) until they hold with a margin of 10⁻³ of
/// their terms, every 25 tries drawn anew (given bodies too). `None` when
/// the step has no condition of these kinds.
pub(crate) fn for_step(
    d: &Derivation,
    m: &StepMeaning,
    draw: &Draw,
    values: &Values,
    rng: &mut ChaCha8Rng,
) -> Result<Option<(Draw, Values)>, VerifyError> {
    if m.symmetry.is_empty() && m.at_rest.is_empty() && m.bounds.is_empty() {
        return Ok(None);
    }
    let ph = &d.physics;
    let symmetry_of = |i: usize| m.symmetry.iter().find(|(k, _)| *k == i).map(|(_, s)| *s);
    let rebuilt: Vec<usize> = (0..ph.bodies.len())
        .filter(|i| !m.bounds.is_empty() || symmetry_of(*i).is_some())
        .collect();
    const TRIES: usize = 500;
    let mut draw = draw.clone();
    // Each rebuilt body in the step's symmetry, made once per body drawn
    // (not per try: only the stretch differs between tries).
    let mut symmetric: Vec<ParticleCloud> = Vec::new();
    for attempt in 0..TRIES {
        // A body no stretch can bring into the class (a lamina, for
        // A > B > C with its thin axis first) is drawn anew.
        if attempt % 25 == 24 {
            for &i in &rebuilt {
                let b = &ph.bodies[i];
                draw.bases[i] =
                    base_body(b, &drawn_body(b, rng)?, b.symmetry, draw.folds[i], true)?;
            }
            symmetric.clear();
        }
        if symmetric.is_empty() {
            symmetric = rebuilt
                .iter()
                .map(|&i| {
                    let sym = symmetry_of(i).unwrap_or(Symmetry::None);
                    base_body(
                        &ph.bodies[i],
                        &draw.bases[i],
                        sym,
                        draw.folds[i],
                        draw.drawn,
                    )
                })
                .collect::<Result<_, _>>()?;
        }
        let mut values = values.clone();
        let mut eqs = Vec::new();
        let mut bases = Vec::with_capacity(rebuilt.len());
        for (&i, sym_base) in rebuilt.iter().zip(&symmetric) {
            let b = &ph.bodies[i];
            let base = if !m.bounds.is_empty() && attempt > 0 {
                let mut f: [f64; 3] = std::array::from_fn(|_| 4f64.powf(rng.gen_range(-1.0..1.0)));
                if let Symmetry::Axisymmetric(k) = symmetry_of(i).unwrap_or(b.symmetry) {
                    f[(k + 2) % 3] = f[(k + 1) % 3];
                }
                map_particles(sym_base, |p, m| {
                    [(Vector3::new(f[0] * p.x, f[1] * p.y, f[2] * p.z), m)]
                })?
            } else {
                sym_base.clone()
            };
            let e = body_equations(b, &base);
            for (p, ..) in &e {
                for a in p.atoms() {
                    values.unset(a);
                }
            }
            eqs.extend(e);
            bases.push(base);
        }
        bind_all(d, &mut values, eqs)?;
        apply(d, &mut values, &ph.motion)?;
        let mut holds = true;
        for (p, _) in &m.bounds {
            let (v, s) = values.eval(p)?;
            holds &= v > 1e-3 * s;
        }
        if !holds {
            continue;
        }
        let mut draw = draw.clone();
        for (&i, base) in rebuilt.iter().zip(bases) {
            draw.bases[i] = base;
        }
        for &i in &rebuilt {
            let (cloud, c) = place(d, &ph.bodies[i], &draw.bases[i], &values)?;
            draw.moments[i] = CloudMoments::of(&cloud);
            draw.bodies[i] = cloud;
            draw.centres[i] = c;
        }
        for (name, order) in &m.at_rest {
            let p = draw.points.get_mut(name).expect("validated: a free point");
            for n in *order..ORDERS {
                p.r[n] = Vector3::zeros();
                p.mag[n] = 0.0;
            }
        }
        return Ok(Some((draw, values)));
    }
    let texts: Vec<&str> = m.bounds.iter().map(|(_, t)| t.as_str()).collect();
    Err(declaration(
        d,
        format!(
            "no body drawn in {TRIES} tries satisfies {} (stretched along its axes with the declared symmetry kept): can the declared bodies have it?",
            texts.join(", ")
        ),
    ))
}
