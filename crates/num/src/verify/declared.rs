//! Verification from what a derivation file declares (its `[[body]]`,
//! `[[point]]`, `gravity`, `[[known]]`, `[motion]` and each step's
//! `means`), independent of the file's name.
//!
//! This file runs the check and compares: for each draw ([`super::draw`]:
//! random bodies with the declared symmetry, random values of the
//! symbols, the `[motion]` conditions and a step's `given` applied,
//! random attitudes and free points) the file's symbols are bound from
//! particle sums of the same particles ([`crate::bind`]) and from the
//! quantities `[[known]]` declares. Every step with a meaning is evaluated with a
//! compiled [`Tape`] and compared with the measured quantity
//! ([`super::quantities`]), computed from the motion of the particles
//! ([`super::world`]), never from the engine's ω or transport theorem.

use std::collections::BTreeMap;
use std::rc::Rc;

use hdot_sym::atom::Atom;
use hdot_sym::derivation::physics::{Meaning, StepMeaning};
use hdot_sym::derivation::{Derivation, Step, Value};
use hdot_sym::poly::Poly;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::draw::{Draw, apply, constrain, draw, for_step};
use super::knowns::world_with_knowns;
use super::means::{against_of, frame_index, meaning_value};
use super::speeds::Consistent;
use super::world::World;
use super::{Comparison, StepCheck, VerifyError, claims, declaration, expressed, linearized};
use crate::bind::Values;
use crate::cloud::ParticleCloud;
use crate::eval::Tape;

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

    /// The names of the compared steps that failed, in the file's order.
    pub fn failed(&self) -> Vec<&str> {
        self.steps
            .iter()
            .filter(|s| !s.passed)
            .map(|s| s.step.as_str())
            .collect()
    }

    /// The largest relative error.
    pub fn max_error(&self) -> f64 {
        self.steps.iter().map(|s| s.max_error).fold(0.0, f64::max)
    }

    /// The worst comparison of the steps that failed, or of every step
    /// when none did: a failed check is never reported by a comparison of
    /// a step that passed (a step can fail with a larger tolerance's error
    /// below another's, or without any comparison — a conserved claim with
    /// no equations of motion to take its rate along —, then `None`).
    pub fn worst(&self) -> Option<&Comparison> {
        let failed = !self.passed();
        self.steps
            .iter()
            .filter(|s| s.worst.is_some() && (!failed || !s.passed))
            .max_by(|a, b| a.max_error.total_cmp(&b.max_error))
            .and_then(|s| s.worst.as_ref())
    }

    /// The first step that failed, when one did.
    pub fn first_failure(&self) -> Option<&StepCheck> {
        self.steps.iter().find(|s| !s.passed)
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

/// Measures each of `[motion] vanishes` in one draw: zero along every
/// motion the rules allow.
fn compare_vanishing<'a>(
    d: &'a Derivation,
    draw: &'a Draw,
    values: &Values,
    shared: &Shared<'a>,
) -> Result<Vec<Vec<Comparison>>, VerifyError> {
    let (_, w) = shared.world(d, draw, values, &[])?;
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

/// A step (or an abbreviation) compiled once.
struct Compiled<'d> {
    /// Its name.
    name: String,
    /// Its value (an abbreviation's definition, a scalar).
    value: Value,
    meaning: &'d StepMeaning,
    tape: Tape,
    labels: Vec<String>,
    frame: Option<usize>,
}

fn compile<'d>(d: &'d Derivation, step: &'d Step, meaning: &'d StepMeaning) -> Compiled<'d> {
    compile_value(d, &step.name, step.value.clone(), &step.axes, meaning)
}

fn compile_value<'d>(
    d: &'d Derivation,
    name: &str,
    value: Value,
    axes: &[String; 3],
    meaning: &'d StepMeaning,
) -> Compiled<'d> {
    let polys: Vec<Poly> = value
        .components()
        .into_iter()
        .map(|p| d.unfold(p))
        .collect();
    let tape = Tape::compile(&polys);
    let labels = match &value {
        Value::Scalar(_) => vec![name.to_owned()],
        Value::Vector(..) => axes.iter().map(|a| format!("{}.{a}", name)).collect(),
        Value::Matrix(_) => (0..9)
            .map(|k| {
                format!(
                    "{}.{}{}",
                    name,
                    ["x", "y", "z"][k / 3],
                    ["x", "y", "z"][k % 3]
                )
            })
            .collect(),
        Value::List { items, labels } => (0..items.len())
            .map(|k| match labels.get(k) {
                Some(a) => format!("{}[{a}]", name),
                None => format!("{}.{}", name, k + 1),
            })
            .collect(),
        Value::Array(rows) => rows
            .iter()
            .enumerate()
            .flat_map(|(i, r)| (0..r.len()).map(move |j| format!("{}.{}{}", name, i + 1, j + 1)))
            .collect(),
    };
    let frame = match &value {
        Value::Vector(_, f) => Some(frame_index(d, f)),
        _ => None,
    };
    Compiled {
        name: name.to_owned(),
        value,
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
                step: self.name.clone(),
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

/// The models of one draw at its drawn values, shared by every step
/// measured there (no `given`, no conditions of [`for_step`]) with the
/// same coordinates, and by `[motion] vanishes`: the values with `[motion]` applied and the symbols
/// of `[[known]]` bound, and the world at them. A world is a function of
/// the draw, the values and the coordinates, so a shared one has the bits
/// a world per step would have; sharing it also shares its measurements
/// at other values ([`World::measured_at`]: `mass_matrix` and `forcing`
/// of the same equations both measure them at zero accelerations) and the
/// partial velocities it has read. The nonlinear bicycle built ten
/// worlds at the same values per draw.
#[derive(Default)]
struct Shared<'a>(std::cell::RefCell<Vec<SharedWorld<'a>>>);

/// The coordinates, the values and the world at them.
type SharedWorld<'a> = (Vec<Atom>, Rc<Values>, Rc<World<'a>>);

impl<'a> Shared<'a> {
    /// The world at the drawn `values` for `coordinates`, built once.
    fn world(
        &self,
        d: &'a Derivation,
        draw: &'a Draw,
        values: &Values,
        coordinates: &[Atom],
    ) -> Result<(Rc<Values>, Rc<World<'a>>), VerifyError> {
        if let Some((_, v, w)) = self.0.borrow().iter().find(|(c, ..)| c == coordinates) {
            return Ok((v.clone(), w.clone()));
        }
        let mut values = values.clone();
        constrain(d, &mut values, &[])?;
        let w = Rc::new(world_with_knowns(d, draw, &mut values, coordinates)?);
        let values = Rc::new(values);
        self.0
            .borrow_mut()
            .push((coordinates.to_vec(), values.clone(), w.clone()));
        Ok((values, w))
    }
}

/// Compares one step in one draw.
fn compare_step<'a>(
    d: &'a Derivation,
    c: &Compiled<'_>,
    draw: &'a Draw,
    values: &Values,
    rng: &mut ChaCha8Rng,
    shared: &Shared<'a>,
) -> Result<Vec<Comparison>, VerifyError> {
    let stepped = for_step(d, c.meaning, draw, values, rng)?;
    let coordinates = coordinate(&c.meaning.meaning);
    match &stepped {
        None if c.meaning.given.is_empty() => {
            let (values, w) = shared.world(d, draw, values, &coordinates)?;
            measure_step(d, c, draw, &values, &w)
        }
        _ => {
            let (draw, values) = match &stepped {
                Some((dr, v)) => (dr, v),
                None => (draw, values),
            };
            let mut values = values.clone();
            constrain(d, &mut values, &c.meaning.given)?;
            let w = world_with_knowns(d, draw, &mut values, &coordinates)?;
            measure_step(d, c, draw, &values, &w)
        }
    }
}

/// [`compare_step`] once the step's values (conditions applied, knowns
/// bound) and its world `w` at them are made.
fn measure_step<'w>(
    d: &Derivation,
    c: &Compiled<'_>,
    draw: &Draw,
    values: &Values,
    w: &World<'w>,
) -> Result<Vec<Comparison>, VerifyError> {
    let (derived, dscale) = c.eval(d, values)?;
    if let Meaning::MassMatrix(x, unknowns) | Meaning::Forcing(x, unknowns) = &c.meaning.meaning {
        // `w` has the coordinates of `x` (those of the step's meaning).
        let at = |vals: &Values| -> Result<(Vec<f64>, f64), VerifyError> {
            w.measured_at(vals, x, |w| {
                let (v, s) = meaning_value(w, x)?;
                Ok((v.components(w, None), s))
            })
        };
        let mut zero = values.clone();
        for a in unknowns {
            zero.set(*a, 0.0, 0.0);
        }
        draw.consistent().fill(d, &mut zero)?;
        constrain(d, &mut zero, &c.meaning.given)?;
        let (x0, mut scale) = at(&zero)?;
        let direct: Vec<f64> = if matches!(c.meaning.meaning, Meaning::Forcing(..)) {
            x0.iter().map(|v| -v).collect()
        } else {
            let mut cols = Vec::new();
            for a in unknowns {
                let mut unit = zero.clone();
                unit.set(*a, 1.0, 1.0);
                draw.consistent().fill(d, &mut unit)?;
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
    if let (Meaning::Solves(x), Value::List { labels, .. }) = (&c.meaning.meaning, &c.value) {
        // X at the solved accelerations must vanish; X is linear in them.
        let at = |vals: &Values| -> Result<(Vec<f64>, f64), VerifyError> {
            w.measured_at(vals, x, |w| {
                let (v, s) = meaning_value(w, x)?;
                Ok((v.components(w, None), s))
            })
        };
        // Solved for the speeds' rates (u̇): the dependent speeds' rates and
        // the coordinates' accelerations follow them, as for `mass_matrix`.
        let speeds = labels.iter().all(|a| d.speeds().contains(&a.base()));
        let follow = |vals: &mut Values| -> Result<(), VerifyError> {
            if speeds {
                draw.consistent().fill(d, vals)?;
            }
            constrain(d, vals, &c.meaning.given)
        };
        let mut solved = values.clone();
        for (a, (v, s)) in labels.iter().zip(derived.iter().zip(&dscale)) {
            solved.set(*a, *v, *s);
        }
        follow(&mut solved)?;
        let (residual, rscale) = at(&solved)?;
        let mut zero = solved.clone();
        for a in labels {
            zero.set(*a, 0.0, 0.0);
        }
        follow(&mut zero)?;
        let (x0, _) = at(&zero)?;
        let mut scale = rscale;
        for (j, a) in labels.iter().enumerate() {
            let mut unit = zero.clone();
            unit.set(*a, 1.0, 1.0);
            follow(&mut unit)?;
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
                quantity: format!("{}: ({}).{}", c.name, c.meaning.text, k + 1),
                derived: *r,
                direct: 0.0,
                scale: scale + f64::MIN_POSITIVE,
            })
            .collect());
    }
    let (m, mscale) = meaning_value(w, &c.meaning.meaning)?;
    let direct = m.components(w, c.frame);
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
    let axes = ["x", "y", "z"].map(String::from);
    let compiled: Vec<Compiled<'_>> = d
        .abbreviations
        .iter()
        .filter_map(|a| {
            a.meaning
                .as_ref()
                .map(|m| compile_value(d, &a.name, Value::Scalar(a.definition.clone()), &axes, m))
        })
        .chain(
            d.steps
                .iter()
                .filter_map(|s| s.meaning.as_ref().map(|m| compile(d, s, m))),
        )
        .collect();
    let mut per_step: BTreeMap<usize, StepCheck> = BTreeMap::new();
    for (k, c) in compiled.iter().enumerate() {
        let against = against_of(&c.meaning.meaning);
        per_step.insert(
            k,
            StepCheck {
                step: c.name.clone(),
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
    let eqs = claims::equations(d);
    let conserved = claims::conserved(d);
    for (j, c) in conserved.iter().enumerate() {
        per_step.insert(
            compiled.len() + vanishing + j,
            claims::conserved_entry(c, &eqs),
        );
    }
    let consistent = Rc::new(Consistent::of(d));
    let constrained = consistent
        .speeds
        .as_ref()
        .map(|s| s.configuration.step.as_str())
        .filter(|s| !s.is_empty());
    let plan = linearized::Plan::of(d, constrained);
    let before = per_step.len();
    for (j, e) in plan.entries().into_iter().enumerate() {
        per_step.insert(before + j, e);
    }
    let expressed = expressed::read(d);
    let at = per_step.len();
    for (j, e) in expressed.iter().enumerate() {
        per_step.insert(at + j, e.entry(d));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let mut draws = 0;
    // Per step, the draws at which its meaning is not defined (a direct
    // value not finite: a direction `[0, -1/L, 0]` drawn at L = 0).
    let mut undefined: BTreeMap<usize, usize> = BTreeMap::new();
    if !compiled.is_empty() || vanishing > 0 || !conserved.is_empty() || before < per_step.len() {
        for _ in 0..options.draws.max(1) {
            let (dr, mut values) = draw(d, &mut rng, given, &consistent)?;
            apply(d, &mut values, &d.physics.motion)?;
            let shared = Shared::default();
            let steps = compiled
                .iter()
                .map(|c| compare_step(d, c, &dr, &values, &mut rng, &shared))
                .collect::<Result<Vec<_>, _>>()?;
            let vanish = compare_vanishing(d, &dr, &values, &shared)?;
            let rates = if eqs.is_empty() {
                vec![Vec::new(); conserved.len()]
            } else {
                claims::compare_conserved(d, &dr, &values, &conserved, &eqs)?
            };
            let linear = if draws < linearized::DRAWS {
                plan.compare(d, &dr, &values)?
            } else {
                vec![Vec::new(); plan.measured().count()]
            };
            let attitudes = expressed
                .iter()
                .map(|e| e.compare(d, &dr, &values))
                .collect::<Result<Vec<_>, _>>()?;
            for (k, cs) in steps
                .into_iter()
                .chain(vanish)
                .chain(rates)
                .chain(linear)
                .chain(attitudes)
                .enumerate()
            {
                let s = per_step.get_mut(&k).expect("inserted");
                let mut skipped = false;
                for cmp in cs {
                    if !cmp.direct.is_finite() {
                        skipped = true;
                        continue;
                    }
                    let e = cmp.relative_error();
                    s.passed &= cmp.passes();
                    if s.worst.is_none() || e > s.max_error {
                        s.max_error = e;
                        s.worst = Some(cmp);
                    }
                }
                if skipped {
                    *undefined.entry(k).or_default() += 1;
                }
            }
            draws += 1;
            tick();
        }
    }
    for (k, n) in undefined {
        let s = per_step.get_mut(&k).expect("inserted");
        s.against.push_str(&format!(
            "; not compared at {n} of {draws} draws, where the meaning is not defined (its measured value is not finite)"
        ));
        // A step measured at no draw has not been checked.
        s.passed &= s.worst.is_some();
    }
    linearized::Plan::state_bounds(
        per_step
            .range_mut(before..before + plan.measured().count())
            .map(|(_, s)| s),
    );
    let mut steps: Vec<StepCheck> = per_step.into_values().collect();
    steps.extend(d.steps.iter().filter_map(|s| claims::zero_label(d, s)));
    Ok(Report {
        derivation: d.name.clone(),
        draws,
        steps,
        not_compared: d
            .steps
            .iter()
            .filter(|s| {
                s.meaning.is_none()
                    && !plan.measured().any(|m| m == s.name)
                    && !expressed.iter().any(|e| e.name() == s.name)
            })
            .map(
                |s| match plan.refused().iter().find(|(n, _)| *n == s.name) {
                    Some((_, why)) => format!("{} ({why})", s.name),
                    None => s.name.clone(),
                },
            )
            .collect(),
    })
}
