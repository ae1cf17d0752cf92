//! Verification from what a derivation file declares (its `[[body]]`,
//! `[[point]]`, `gravity`, `[[known]]`, `[motion]` and each step's
//! `means`), independent of the file's name.
//!
//! For each draw: random bodies with the declared symmetry (particles
//! copied so the symmetry is exact), random constant values, random values
//! and derivatives of every time symbol (then the `[motion]` conditions and
//! a step's `given` applied), random attitudes of frames given by their
//! angular velocity and random motions of free points. The file's symbols
//! are bound from particle sums of the same particles (mass, G, inertia
//! about the reference point in the body axes) and from the quantities
//! `[[known]]` declares. Every step with a meaning is evaluated with a
//! compiled [`Tape`] and compared with the measured quantity
//! ([`super::quantities`]), computed from the motion of the particles
//! ([`super::world`]), never from the engine's ω or transport theorem.

use std::collections::{BTreeMap, HashMap};

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::physics::{
    Body, FrameMotion, Meaning, PointKind, Rule, RuleValue, StepMeaning, Symmetry,
};
use hdot_sym::derivation::{Derivation, Step, Value};
use hdot_sym::poly::Poly;
use hdot_sym::symbols::Decl;
use nalgebra::{Matrix3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::bodies::{axisymmetric, map_particles, mirrored, random_body, random_rotation};
use super::means::{against_of, frame_index, meaning_value};
use super::world::{ORDERS, PointJet, World, mat_t_vec, vee};
use super::{Comparison, VerifyError};
use crate::bind::{MeasuredBody, Values, bind_all, declared_equations, nth};
use crate::cloud::ParticleCloud;
use crate::eval::Tape;

/// Highest derivative order drawn for a time symbol.
const MAX_ORDER: u32 = 6;

/// How many draws and from which seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Random bodies and motions (at least 1).
    pub draws: usize,
    /// Seed of the ChaCha generator.
    pub seed: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options { draws: 50, seed: 0 }
    }
}

/// One compared step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepCheck {
    /// The step's name.
    pub step: String,
    /// Its meaning as written.
    pub means: String,
    /// Its conditions as written (`given = [...]`, `symmetry = {...}`),
    /// empty without.
    pub conditions: String,
    /// What the meaning was measured as.
    pub against: String,
    /// The largest relative error over the draws.
    pub max_error: f64,
    /// The comparison with the largest error.
    pub worst: Option<Comparison>,
    /// Whether every comparison passed.
    pub passed: bool,
}

/// The result of [`check`].
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The derivation's name.
    pub derivation: String,
    /// Draws made.
    pub draws: usize,
    /// The steps with a meaning, compared.
    pub steps: Vec<StepCheck>,
    /// The steps without a meaning (not compared).
    pub not_compared: Vec<String>,
}

impl Report {
    /// Whether every compared step passed (true when none was compared).
    pub fn passed(&self) -> bool {
        self.steps.iter().all(|s| s.passed)
    }

    /// The largest relative error.
    pub fn max_error(&self) -> f64 {
        self.steps.iter().map(|s| s.max_error).fold(0.0, f64::max)
    }

    /// The worst comparison over all steps.
    pub fn worst(&self) -> Option<&Comparison> {
        self.steps
            .iter()
            .filter(|s| s.worst.is_some())
            .max_by(|a, b| a.max_error.total_cmp(&b.max_error))
            .and_then(|s| s.worst.as_ref())
    }

    /// What the file would need for a step to be compared, when none is.
    pub fn hint(&self, d: &Derivation) -> Option<String> {
        if !self.steps.is_empty() {
            return None;
        }
        Some(if d.physics.bodies.is_empty() {
            "no step has a meaning: declare the bodies ([[body]], [[point]]) and say what steps mean (`means = \"moment(body, O)\"`); see docs/derivation-format.md".into()
        } else {
            "no step has a meaning: add `means = \"…\"` to the steps (see docs/derivation-format.md, *Meanings*)".into()
        })
    }
}

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
    centres: Vec<Vector3<f64>>,
    attitudes: HashMap<usize, Matrix3<f64>>,
    points: HashMap<String, PointJet>,
}

impl Draw {
    /// The particles of body `i` (body axes, about its reference point).
    pub fn body(&self, i: usize) -> &ParticleCloud {
        &self.bodies[i]
    }

    /// G of body `i` from its reference point, body axes.
    pub fn centre(&self, i: usize) -> Vector3<f64> {
        self.centres[i]
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
            let c = axisymmetric(cloud, fold)?;
            // z to axis k by a cyclic permutation (a proper rotation).
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

fn declaration(d: &Derivation, message: String) -> VerifyError {
    VerifyError::Declaration {
        derivation: d.name.clone(),
        message,
    }
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
fn draw(
    d: &Derivation,
    rng: &mut ChaCha8Rng,
    given: Option<&[ParticleCloud]>,
) -> Result<(Draw, Values), VerifyError> {
    let ph = &d.physics;
    let mut values = Values::default();
    let mut eqs = Vec::new();
    let mut bases = Vec::new();
    let mut folds = Vec::new();
    for (k, b) in ph.bodies.iter().enumerate() {
        let fold = rng.gen_range(3..=6);
        let cloud = match given {
            // Given bodies have their symmetry already.
            Some(g) => base_body(b, &g[k], Symmetry::None, fold)?,
            None => base_body(b, &drawn_body(b, rng)?, b.symmetry, fold)?,
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
    bind_all(d, &mut values, eqs)?;
    let mut bodies = Vec::new();
    let mut centres = Vec::new();
    for (b, base) in ph.bodies.iter().zip(&bases) {
        let (cloud, c) = place(d, b, base, &values)?;
        bodies.push(cloud);
        centres.push(c);
    }
    let mut attitudes = HashMap::new();
    for (i, m) in ph.frames.iter().enumerate() {
        if *m == FrameMotion::AngularVelocity {
            attitudes.insert(i, *random_rotation(rng).matrix());
        }
    }
    let mut points = HashMap::new();
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
            centres,
            attitudes,
            points,
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
) -> Result<ParticleCloud, VerifyError> {
    let cloud = symmetric(cloud, symmetry, fold)?;
    // About its centre, or G declared at the reference point: G moved to
    // the origin (along the symmetry axis or in the symmetry plane, where
    // the symmetry puts it, so the symmetry is kept).
    if b.about_centre()
        || b.inertia_about_centre
        || b.mass_centre.as_ref().is_some_and(|c| c.is_zero())
    {
        let g = cloud.mass_properties().center;
        return Ok(map_particles(&cloud, |p, m| [(p - g, m)])?);
    }
    Ok(cloud)
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
fn apply(d: &Derivation, values: &mut Values, rules: &[Rule]) -> Result<(), VerifyError> {
    for r in rules {
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
                let mut q = p.clone();
                for n in from..=MAX_ORDER {
                    let (v, s) = match values.eval(&q) {
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
                    q = q.dt();
                }
            }
        }
    }
    Ok(())
}

/// Applies a step's `given`, then `[motion]`'s rules (whose derived
/// rates follow the step's conditions: rolling with θ̈ = 0 keeps the
/// rolling rates), then the step's `given` again (which wins).
fn constrain(d: &Derivation, values: &mut Values, given: &[Rule]) -> Result<(), VerifyError> {
    apply(d, values, given)?;
    apply(d, values, &d.physics.motion)?;
    apply(d, values, given)
}

/// Measures each of `[motion] vanishes` in one draw: zero along every
/// motion the rules allow.
fn compare_vanishing(
    d: &Derivation,
    draw: &Draw,
    values: &Values,
) -> Result<Vec<Vec<Comparison>>, VerifyError> {
    let mut values = values.clone();
    constrain(d, &mut values, &[])?;
    let w = World::build(d, draw, &values, &[])?;
    bind_knowns(d, &w, &mut values)?;
    let w = World::build(d, draw, &values, &[])?;
    d.physics
        .vanishes
        .iter()
        .map(|(m, text)| {
            let (v, scale) = meaning_value(&w, m)?;
            let direct = v.components(&w, None);
            let labels: Vec<String> = match direct.len() {
                1 => vec![text.clone()],
                _ => ["X", "Y", "Z"]
                    .iter()
                    .map(|a| format!("{text}.{a}"))
                    .collect(),
            };
            Ok(direct
                .iter()
                .zip(labels)
                .map(|(x, quantity)| Comparison {
                    quantity,
                    derived: 0.0,
                    direct: *x,
                    scale: scale + f64::MIN_POSITIVE,
                })
                .collect())
        })
        .collect()
}

/// Binds the symbols of `[[known]]` from the measured quantities (and
/// their time derivatives, for point and frame kinematics).
fn bind_knowns(d: &Derivation, w: &World<'_>, values: &mut Values) -> Result<(), VerifyError> {
    for k in &d.physics.knowns {
        let jets: Vec<[f64; 3]> = match (&k.value, &k.meaning) {
            (Value::Vector(_, f), m) => {
                let fi = frame_index(d, f);
                let x = kinematic_jet(w, m);
                match x {
                    Some(x) => {
                        let rf = &w.frames[fi];
                        let c = mat_t_vec(rf, &x);
                        (0..3).map(|i| [c[0][i], c[1][i], c[2][i]]).collect()
                    }
                    None => {
                        let (v, _) = meaning_value(w, m)?;
                        let v = w.frames[fi][0].transpose() * v.vector();
                        (0..3).map(|i| [v[i], f64::NAN, f64::NAN]).collect()
                    }
                }
            }
            // A scalar, or a matrix entry by entry (row by row).
            (_, m) => meaning_value(w, m)?
                .0
                .components(w, None)
                .into_iter()
                .map(|x| [x, f64::NAN, f64::NAN])
                .collect(),
        };
        let (_, size) = meaning_value(w, &k.meaning)?;
        for (p, jet) in k.value.components().into_iter().zip(jets) {
            let atoms: Vec<Atom> = p
                .atoms()
                .into_iter()
                .filter(|a| !values.bound(*a))
                .collect();
            bind_all(
                d,
                values,
                vec![(p.clone(), jet[0], size, format!("the known {}", k.text))],
            )?;
            // Derivatives: p = c s + r with c and r constant.
            if let [s] = atoms.as_slice()
                && p.atoms().iter().all(|a| *a == *s || !a.is_time_dependent())
                && s.is_time_dependent()
            {
                let (c, _) = values.eval(&p.partial(*s))?;
                for (n, x) in jet.iter().enumerate().skip(1) {
                    if x.is_finite() {
                        values.set(nth(*s, n as u32), x / c, size / c.abs());
                    }
                }
            }
        }
    }
    Ok(())
}

/// The jet (N's axes, orders 0..2) of a point-kinematics or angular-velocity
/// meaning.
fn kinematic_jet(w: &World<'_>, m: &Meaning) -> Option<[Vector3<f64>; ORDERS]> {
    use hdot_sym::derivation::physics::{Arg, Quantity};
    let Meaning::Quantity(q, args) = m else {
        return None;
    };
    let pt = |a: &Arg| match a {
        Arg::Point(p) => w.points[p].r,
        _ => unreachable!("validated"),
    };
    let z = Vector3::zeros();
    Some(match q {
        Quantity::Position => {
            let (p, o) = (pt(&args[0]), pt(&args[1]));
            std::array::from_fn(|n| p[n] - o[n])
        }
        Quantity::Velocity => {
            let p = pt(&args[0]);
            [p[1], p[2], p[3], z]
        }
        Quantity::AngularVelocity => {
            let Arg::Frame(f) = args[0] else {
                unreachable!("validated")
            };
            let r = &w.frames[f];
            [
                vee(&(r[1] * r[0].transpose())),
                vee(&(r[2] * r[0].transpose() + r[1] * r[1].transpose())),
                vee(&(r[3] * r[0].transpose()
                    + 2.0 * r[2] * r[1].transpose()
                    + r[1] * r[2].transpose())),
                z,
            ]
        }
        _ => return None,
    })
}

/// A step compiled once.
struct Compiled<'d> {
    step: &'d Step,
    meaning: &'d StepMeaning,
    tape: Tape,
    labels: Vec<String>,
    frame: Option<usize>,
}

fn compile<'d>(d: &'d Derivation, step: &'d Step, meaning: &'d StepMeaning) -> Compiled<'d> {
    let polys: Vec<Poly> = step.values().into_iter().map(|p| d.unfold(p)).collect();
    let tape = Tape::compile(&polys);
    let labels = match &step.value {
        Value::Scalar(_) => vec![step.name.clone()],
        Value::Vector(..) => step
            .axes
            .iter()
            .map(|a| format!("{}.{a}", step.name))
            .collect(),
        Value::Matrix(_) => (0..9)
            .map(|k| {
                format!(
                    "{}.{}{}",
                    step.name,
                    ["x", "y", "z"][k / 3],
                    ["x", "y", "z"][k % 3]
                )
            })
            .collect(),
        Value::List { items, labels } => (0..items.len())
            .map(|k| match labels.get(k) {
                Some(a) => format!("{}[{a}]", step.name),
                None => format!("{}.{}", step.name, k + 1),
            })
            .collect(),
        Value::Array(rows) => rows
            .iter()
            .enumerate()
            .flat_map(|(i, r)| {
                (0..r.len()).map(move |j| format!("{}.{}{}", step.name, i + 1, j + 1))
            })
            .collect(),
    };
    let frame = match &step.value {
        Value::Vector(_, f) => Some(frame_index(d, f)),
        _ => None,
    };
    Compiled {
        step,
        meaning,
        tape,
        labels,
        frame,
    }
}

impl Compiled<'_> {
    fn eval(&self, d: &Derivation, values: &Values) -> Result<(Vec<f64>, Vec<f64>), VerifyError> {
        let mut inputs = Vec::with_capacity(self.tape.atoms().len());
        let mut sizes = Vec::with_capacity(self.tape.atoms().len());
        for &a in self.tape.atoms() {
            let (v, s) = values.get(a).ok_or_else(|| VerifyError::Unbound {
                derivation: d.name.clone(),
                step: self.step.name.clone(),
                symbol: a.to_string(),
            })?;
            inputs.push(v);
            sizes.push(s);
        }
        let n = self.tape.outputs();
        let (mut out, mut scale) = (vec![0.0; n], vec![0.0; n]);
        self.tape.eval(&inputs, &mut out);
        self.tape.eval_abs(&sizes, &mut scale);
        Ok((out, scale))
    }
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
fn for_step(
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
    for attempt in 0..TRIES {
        // A body no stretch can bring into the class (a lamina, for
        // A > B > C with its thin axis first) is drawn anew.
        if attempt % 25 == 24 {
            for &i in &rebuilt {
                let b = &ph.bodies[i];
                draw.bases[i] = base_body(b, &drawn_body(b, rng)?, b.symmetry, draw.folds[i])?;
            }
        }
        let (mut draw, mut values) = (draw.clone(), values.clone());
        let mut eqs = Vec::new();
        for &i in &rebuilt {
            let b = &ph.bodies[i];
            let sym = symmetry_of(i).unwrap_or(Symmetry::None);
            let mut base = base_body(b, &draw.bases[i], sym, draw.folds[i])?;
            if !m.bounds.is_empty() && attempt > 0 {
                let mut f: [f64; 3] = std::array::from_fn(|_| 4f64.powf(rng.gen_range(-1.0..1.0)));
                if let Symmetry::Axisymmetric(k) = symmetry_of(i).unwrap_or(b.symmetry) {
                    f[(k + 2) % 3] = f[(k + 1) % 3];
                }
                base = map_particles(&base, |p, m| {
                    [(Vector3::new(f[0] * p.x, f[1] * p.y, f[2] * p.z), m)]
                })?;
            }
            let e = body_equations(b, &base);
            for (p, ..) in &e {
                for a in p.atoms() {
                    values.unset(a);
                }
            }
            eqs.extend(e);
            draw.bases[i] = base;
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
        for &i in &rebuilt {
            let (cloud, c) = place(d, &ph.bodies[i], &draw.bases[i], &values)?;
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

/// Compares one step in one draw.
fn compare_step(
    d: &Derivation,
    c: &Compiled<'_>,
    draw: &Draw,
    values: &Values,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<Comparison>, VerifyError> {
    let stepped = for_step(d, c.meaning, draw, values, rng)?;
    let (draw, values) = match &stepped {
        Some((dr, v)) => (dr, v),
        None => (draw, values),
    };
    let mut values = values.clone();
    constrain(d, &mut values, &c.meaning.given)?;
    let w = World::build(d, draw, &values, &coordinate(&c.meaning.meaning))?;
    bind_knowns(d, &w, &mut values)?;
    let w = World::build(d, draw, &values, &coordinate(&c.meaning.meaning))?;
    let (derived, dscale) = c.eval(d, &values)?;
    if let Meaning::MassMatrix(x, unknowns) | Meaning::Forcing(x, unknowns) = &c.meaning.meaning {
        let at = |vals: &Values| -> Result<(Vec<f64>, f64), VerifyError> {
            let w = World::build(d, draw, vals, &coordinate(x))?;
            let (v, s) = meaning_value(&w, x)?;
            Ok((v.components(&w, None), s))
        };
        let mut zero = values.clone();
        for a in unknowns {
            zero.set(*a, 0.0, 0.0);
        }
        constrain(d, &mut zero, &c.meaning.given)?;
        let (x0, mut scale) = at(&zero)?;
        let direct: Vec<f64> = if matches!(c.meaning.meaning, Meaning::Forcing(..)) {
            x0.iter().map(|v| -v).collect()
        } else {
            let mut cols = Vec::new();
            for a in unknowns {
                let mut unit = zero.clone();
                unit.set(*a, 1.0, 1.0);
                constrain(d, &mut unit, &c.meaning.given)?;
                let (xj, sj) = at(&unit)?;
                scale = scale.max(sj);
                cols.push(xj.iter().zip(&x0).map(|(p, q)| p - q).collect::<Vec<f64>>());
            }
            (0..x0.len())
                .flat_map(|i| cols.iter().map(move |col| col[i]))
                .collect()
        };
        let top = dscale.iter().copied().fold(0.0, f64::max)
            + scale
            + direct.iter().map(|x| x.abs()).fold(0.0, f64::max);
        return Ok(derived
            .iter()
            .zip(&direct)
            .zip(&c.labels)
            .map(|((x, y), l)| Comparison {
                quantity: l.clone(),
                derived: *x,
                direct: *y,
                scale: top + f64::MIN_POSITIVE,
            })
            .collect());
    }
    if let (Meaning::Solves(x), Value::List { labels, .. }) = (&c.meaning.meaning, &c.step.value) {
        // X at the solved accelerations must vanish; X is linear in them.
        let at = |vals: &Values| -> Result<(Vec<f64>, f64), VerifyError> {
            let w = World::build(d, draw, vals, &coordinate(x))?;
            let (v, s) = meaning_value(&w, x)?;
            Ok((v.components(&w, None), s))
        };
        let mut solved = values.clone();
        for (a, (v, s)) in labels.iter().zip(derived.iter().zip(&dscale)) {
            solved.set(*a, *v, *s);
        }
        constrain(d, &mut solved, &c.meaning.given)?;
        let (residual, rscale) = at(&solved)?;
        let mut zero = solved.clone();
        for a in labels {
            zero.set(*a, 0.0, 0.0);
        }
        constrain(d, &mut zero, &c.meaning.given)?;
        let (x0, _) = at(&zero)?;
        let mut scale = rscale;
        for (j, a) in labels.iter().enumerate() {
            let mut unit = zero.clone();
            unit.set(*a, 1.0, 1.0);
            constrain(d, &mut unit, &c.meaning.given)?;
            let (xj, _) = at(&unit)?;
            let col: f64 = xj
                .iter()
                .zip(&x0)
                .map(|(p, q)| (p - q).powi(2))
                .sum::<f64>()
                .sqrt();
            scale += col * dscale[j];
        }
        return Ok(residual
            .iter()
            .enumerate()
            .map(|(k, r)| Comparison {
                quantity: format!("{}: ({}).{}", c.step.name, c.meaning.text, k + 1),
                derived: *r,
                direct: 0.0,
                scale: scale + f64::MIN_POSITIVE,
            })
            .collect());
    }
    let (m, mscale) = meaning_value(&w, &c.meaning.meaning)?;
    let direct = m.components(&w, c.frame);
    let top = dscale.iter().copied().fold(0.0, f64::max)
        + mscale
        + direct.iter().map(|x| x.abs()).fold(0.0, f64::max);
    Ok(derived
        .iter()
        .zip(&direct)
        .zip(&c.labels)
        .map(|((x, y), l)| Comparison {
            quantity: l.clone(),
            derived: *x,
            direct: *y,
            scale: top + f64::MIN_POSITIVE,
        })
        .collect())
}

/// The coordinates the generalized quantities of `m` are taken for.
fn coordinate(m: &Meaning) -> Vec<Atom> {
    use hdot_sym::derivation::physics::Arg;
    let mut out = Vec::new();
    for (_, args) in m.quantities() {
        for a in args {
            if let Arg::Coordinate(q) = a
                && !out.contains(q)
            {
                out.push(*q);
            }
        }
    }
    out
}

/// Verifies every step of `d` that has a meaning, on `options.draws`
/// random bodies and motions.
///
/// # Errors
/// A declaration the drawn bodies cannot satisfy (an inertia entry
/// declared zero without the symmetry that makes it so), a step using a
/// symbol nothing binds, or an invalid random body.
///
/// # Example
/// ```
/// let text = r#"
/// title = "A spinning body"
/// source = "example"
/// [symbols]
/// constants = ["m", "A", "Bm", "C"]
/// time = ["w_x", "w_y", "w_z"]
/// [[frame]]
/// name = "B"
/// angular_velocity = "[w_x, w_y, w_z]"
/// [[body]]
/// name = "body"
/// frame = "B"
/// mass = "m"
/// inertia = "principal(A, Bm, C)"
/// symmetry = "principal"
/// [[step]]
/// name = "H"
/// value = "principal(A, Bm, C) * angvel(B)"
/// means = "angular_momentum(body, G)"
/// "#;
/// let d = hdot_sym::derivation::load_str("spin.toml", text).unwrap();
/// let r = hdot_num::verify::check(&d, &hdot_num::verify::Options { draws: 5, seed: 1 }).unwrap();
/// assert!(r.passed() && r.steps.len() == 1);
/// ```
pub fn check(d: &Derivation, options: &Options) -> Result<Report, VerifyError> {
    check_with(d, options, &mut || {})
}

/// [`check`], calling `tick` after each draw.
pub fn check_with(
    d: &Derivation,
    options: &Options,
    tick: &mut dyn FnMut(),
) -> Result<Report, VerifyError> {
    run(d, options, None, tick)
}

/// [`check`] on the given bodies instead of drawn ones: one particle cloud
/// per `[[body]]`, in the body's own axes about its reference point (G is
/// moved to the point when the body is declared about its centre or with
/// `mass_centre` zero). Only the motions and the other symbols are drawn,
/// `options.draws` times — except for a step whose `given` selects a
/// class of bodies (`A > B`): for it the bodies are stretched along their
/// axes, and drawn anew if that does not reach the class. The bodies must have the declared symmetry: a
/// declared form they do not have is reported as an error naming the
/// entry, as for drawn bodies. With the `proptest` feature,
/// [`super::strategy::declared_bodies`] generates them.
///
/// # Errors
/// As [`check`]; also when `bodies` does not have one cloud per declared
/// body.
pub fn check_bodies(
    d: &Derivation,
    bodies: &[ParticleCloud],
    options: &Options,
) -> Result<Report, VerifyError> {
    if bodies.len() != d.physics.bodies.len() {
        return Err(declaration(
            d,
            format!(
                "{} bodies given for {} declared",
                bodies.len(),
                d.physics.bodies.len()
            ),
        ));
    }
    run(d, options, Some(bodies), &mut || {})
}

fn run(
    d: &Derivation,
    options: &Options,
    given: Option<&[ParticleCloud]>,
    tick: &mut dyn FnMut(),
) -> Result<Report, VerifyError> {
    let compiled: Vec<Compiled<'_>> = d
        .steps
        .iter()
        .filter_map(|s| s.meaning.as_ref().map(|m| compile(d, s, m)))
        .collect();
    let mut per_step: BTreeMap<usize, StepCheck> = BTreeMap::new();
    for (k, c) in compiled.iter().enumerate() {
        let against = against_of(&c.meaning.meaning);
        per_step.insert(
            k,
            StepCheck {
                step: c.step.name.clone(),
                means: c.meaning.text.clone(),
                conditions: c.meaning.conditions.clone(),
                against,
                max_error: 0.0,
                worst: None,
                passed: true,
            },
        );
    }
    let vanishing = d.physics.vanishes.len();
    for (j, (m, text)) in d.physics.vanishes.iter().enumerate() {
        per_step.insert(
            compiled.len() + j,
            StepCheck {
                step: "[motion] vanishes".into(),
                means: text.clone(),
                conditions: String::new(),
                against: against_of(m),
                max_error: 0.0,
                worst: None,
                passed: true,
            },
        );
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let mut draws = 0;
    if !compiled.is_empty() || vanishing > 0 {
        for _ in 0..options.draws.max(1) {
            let (dr, mut values) = draw(d, &mut rng, given)?;
            apply(d, &mut values, &d.physics.motion)?;
            let steps = compiled
                .iter()
                .map(|c| compare_step(d, c, &dr, &values, &mut rng))
                .collect::<Result<Vec<_>, _>>()?;
            let vanish = compare_vanishing(d, &dr, &values)?;
            for (k, cs) in steps.into_iter().chain(vanish).enumerate() {
                let s = per_step.get_mut(&k).expect("inserted");
                for cmp in cs {
                    let e = cmp.relative_error();
                    s.passed &= cmp.passes();
                    if s.worst.is_none() || e > s.max_error {
                        s.max_error = e;
                        s.worst = Some(cmp);
                    }
                }
            }
            draws += 1;
            tick();
        }
    }
    Ok(Report {
        derivation: d.name.clone(),
        draws,
        steps: per_step.into_values().collect(),
        not_compared: d
            .steps
            .iter()
            .filter(|s| s.meaning.is_none())
            .map(|s| s.name.clone())
            .collect(),
    })
}
