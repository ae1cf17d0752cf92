//! Equations of motion taken from a derivation file: the accelerations a
//! derivation solved for (`solve(eqs, [q1'', …])`), or its mass-matrix
//! form M(q) q̈ = f(q, q̇, t) (`mass_matrix`, `forcing`), compiled with
//! `hdot-num`'s [`Tape`] and integrated as `y = (q, q̇)`.
//!
//! What is integrated is exactly what was derived: the polynomials of the
//! steps, with abbreviations expanded, evaluated at the state. Each atom of
//! the compiled equations gets its value from one `Source`: a
//! coordinate or its rate (from the state), sin or cos of a coordinate,
//! a constant (from the scene), or an applied input given as a function of
//! time (from the scene, see [`TimeFunction`]).
//!
//! A coordinate singularity — a `sin q` or `cos q` that the equations
//! divide by coming near zero (Eulerian angles at θ = 0, π) — is reported
//! by [`System::check`] instead of being integrated through; so is a mass
//! matrix that cannot be factorised.
//!
//! The attitude of a frame of the derivation (its rotation from N through
//! the chain of `parent`/`rotation` frames) and its angular velocity are
//! evaluated from the derivation's own frames ([`DerivedModel::attitude`],
//! [`DerivedModel::angular_velocity`]), so a derived run can be compared
//! with a built-in model on the attitude matrix and ω.

use std::cell::RefCell;
use std::collections::BTreeMap;

use hdot_num::eval::Tape;
use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::{Derivation, Value};
use hdot_sym::poly::Poly;
use hdot_sym::vector::Mat3;
use nalgebra::{DMatrix, Matrix3, Vector3};

use crate::{SimError, System};

pub use super::time_function::TimeFunction;

/// Which steps of the derivation hold the equations of motion.
#[derive(Debug, Clone, PartialEq)]
pub enum EquationsSpec {
    /// A step whose value is a list of accelerations labelled by the
    /// unknowns (`solve(eqs, [q1'', q2'', …])`).
    Explicit {
        /// The step's name.
        step: String,
    },
    /// Two steps: M (an n × n array, `mass_matrix(…)`) and f (a list,
    /// `forcing(…)`), with the coordinates in the order of their columns.
    MassMatrix {
        /// The step holding M.
        mass_matrix: String,
        /// The step holding f.
        forcing: String,
        /// The coordinates q (not their accelerations), in column order.
        coordinates: Vec<String>,
    },
}

/// Everything a scene says about a derived model.
#[derive(Debug, Clone, PartialEq)]
pub struct DerivedSpec {
    /// Where the equations are.
    pub equations: EquationsSpec,
    /// Values of the derivation's constants.
    pub constants: BTreeMap<String, f64>,
    /// Time symbols that are applied inputs, as functions of t.
    pub inputs: BTreeMap<String, TimeFunction>,
    /// Steps whose values should stay constant along the motion (each is
    /// reported as a drift), in addition to those the derivation marks
    /// `conserved = true`.
    pub conserved: Vec<String>,
}

/// Where the value of one atom of the compiled equations comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    /// `y[i]`: coordinate i.
    Coordinate(usize),
    /// `y[n + i]`: the rate of coordinate i.
    Rate(usize),
    /// sin of coordinate i.
    SinOf(usize),
    /// cos of coordinate i.
    CosOf(usize),
    /// A constant (or sin/cos of a constant angle).
    Value(f64),
    /// Applied input k at time t.
    Input(usize),
    /// sin of applied input k.
    SinInput(usize),
    /// cos of applied input k.
    CosInput(usize),
}

/// A compiled set of polynomials and the source of each of its inputs.
#[derive(Debug, Clone)]
struct Compiled {
    tape: Tape,
    sources: Vec<Source>,
    gather: Gather,
}

/// How the inputs of a tape are filled from `(t, y)`, planned once from
/// the sources: slots copied from the state, one `sin_cos` per angle
/// whose sine and cosine are both read (one libm call instead of two),
/// and the rest (applied inputs, unfolded values) one by one: no match on
/// each atom's source per evaluation.
#[derive(Debug, Clone, Default)]
struct Gather {
    /// `slot ← y[index]`.
    copies: Vec<(usize, usize)>,
    /// `slot ← sin y[i]`, `slot ← cos y[i]`: `(i, sin slot, cos slot)`.
    trig: Vec<(usize, Option<usize>, Option<usize>)>,
    /// `slot ← source`, evaluated per source.
    other: Vec<(usize, Source)>,
}

impl Gather {
    fn plan(sources: &[Source], n: usize) -> Gather {
        let mut g = Gather::default();
        for (slot, &s) in sources.iter().enumerate() {
            match s {
                Source::Coordinate(i) => g.copies.push((slot, i)),
                Source::Rate(i) => g.copies.push((slot, n + i)),
                Source::SinOf(i) | Source::CosOf(i) => {
                    let k = match g.trig.iter().position(|t| t.0 == i) {
                        Some(k) => k,
                        None => {
                            g.trig.push((i, None, None));
                            g.trig.len() - 1
                        }
                    };
                    if matches!(s, Source::SinOf(_)) {
                        g.trig[k].1 = Some(slot);
                    } else {
                        g.trig[k].2 = Some(slot);
                    }
                }
                _ => g.other.push((slot, s)),
            }
        }
        g
    }
}

/// A quantity to report as a drift: a step's components.
#[derive(Debug, Clone)]
pub struct Conserved {
    /// The step's name.
    pub name: String,
    /// Why the step is an energy (its meaning is a sum of kinetic and
    /// potential energies, or its name, label or doc says `energy`);
    /// `None` for the other conserved steps (momenta).
    pub energy: Option<String>,
    compiled: Compiled,
}

/// Why a step is an energy, if it is: its `means` is a kinetic or
/// potential energy or a sum of them, or its name, label or doc has the
/// word `energy`.
pub fn energy_reason(s: &hdot_sym::derivation::Step) -> Option<String> {
    use hdot_sym::derivation::physics::{Meaning, Quantity};
    fn is_energy(m: &Meaning) -> bool {
        match m {
            Meaning::Quantity(Quantity::KineticEnergy | Quantity::PotentialEnergy, _) => true,
            Meaning::Sum(terms) => !terms.is_empty() && terms.iter().all(|(_, t)| is_energy(t)),
            Meaning::Scaled(_, t) => is_energy(t),
            _ => false,
        }
    }
    if let Some(m) = &s.meaning
        && is_energy(&m.meaning)
    {
        return Some(format!("means = \"{}\"", m.text));
    }
    [("name", &s.name), ("label", &s.label), ("doc", &s.doc)]
        .into_iter()
        .find(|(_, v)| v.to_lowercase().contains("energy"))
        .map(|(field, v)| format!("{field} = \"{v}\""))
}

#[derive(Debug, Clone)]
enum Form {
    Explicit(Compiled),
    /// M (row-major) and f, the outputs of one tape.
    MassMatrix(Compiled),
}

/// A trigonometric atom the equations divide by.
#[derive(Debug, Clone, PartialEq)]
struct Divisor {
    coordinate: usize,
    sin: bool,
}

/// The derived equations of motion, compiled.
#[derive(Debug)]
pub struct DerivedModel {
    coordinates: Vec<Atom>,
    form: Form,
    inputs: Vec<(String, TimeFunction)>,
    divisors: Vec<Divisor>,
    /// Constants that make the equations singular whatever the state
    /// (see [`DerivedModel::constant_singularity`]).
    singular: Vec<(String, String)>,
    conserved: Vec<Conserved>,
    /// The derivation's frames, in order: each frame's name and its
    /// motion, or why its attitude cannot be evaluated.
    frames: Vec<(String, Result<FrameChain, String>)>,
    /// The slots of the tapes' evaluation (see [`DerivedModel::eval`]).
    scratch: RefCell<Vec<f64>>,
}

#[derive(Debug, Clone)]
struct FrameChain {
    attitude: FrameAttitude,
    omega: Compiled,
}

/// How a frame's attitude relative to N is evaluated.
#[derive(Debug, Clone)]
enum FrameAttitude {
    /// A rotation (a function of the coordinates and inputs) from its
    /// parent, or from N when there is none.
    Rotation {
        parent: Option<usize>,
        rotation: Compiled,
    },
    /// A frame given by a constant angular velocity ω (its own components),
    /// coinciding with N at t = 0: `exp(t [ω]×)`.
    Spin(Vector3<f64>),
}

fn err(message: impl Into<String>) -> SimError {
    SimError::Derived {
        message: message.into(),
    }
}

/// # Construction
impl DerivedModel {
    /// Compiles the equations `spec` names in `d`.
    pub fn new(d: &Derivation, spec: &DerivedSpec) -> Result<DerivedModel, SimError> {
        let step = |name: &str| {
            d.steps.iter().find(|s| s.name == name).ok_or_else(|| {
                err(format!(
                    "{}: no step named `{name}` (steps: {})",
                    d.path,
                    d.steps
                        .iter()
                        .map(|s| s.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })
        };
        // The outputs of one tape: q̈, or M (row-major) then f (one tape, so
        // that the two share their inputs, sines and products).
        let (coordinates, outputs): (Vec<Atom>, Vec<Poly>) = match &spec.equations {
            EquationsSpec::Explicit { step: name } => {
                let s = step(name)?;
                let Value::List { items, labels } = &s.value else {
                    return Err(err(format!(
                        "{}: step `{name}` is {}, not accelerations solved for (write it as solve(eqs, [q1'', q2'', …]), \
                         or name a mass_matrix and forcing step)",
                        d.path,
                        s.value.describe()
                    )));
                };
                if labels.len() != items.len()
                    || labels
                        .iter()
                        .any(|a| a.order() != 2 || !a.is_time_dependent())
                {
                    return Err(err(format!(
                        "{}: step `{name}` must be solved for second derivatives of time symbols ([q1'', q2'', …])",
                        d.path
                    )));
                }
                (labels.iter().map(|a| a.base()).collect(), items.clone())
            }
            EquationsSpec::MassMatrix {
                mass_matrix,
                forcing,
                coordinates,
            } => {
                let (sm, sf) = (step(mass_matrix)?, step(forcing)?);
                let n = coordinates.len();
                let m = match &sm.value {
                    Value::Array(rows) if rows.len() == n && rows.iter().all(|r| r.len() == n) => {
                        rows.iter().flatten().cloned().collect::<Vec<_>>()
                    }
                    Value::Matrix(m) if n == 3 => m.0.iter().flatten().cloned().collect(),
                    v => {
                        return Err(err(format!(
                            "{}: step `{mass_matrix}` is {}, not an {n}×{n} mass matrix",
                            d.path,
                            v.describe()
                        )));
                    }
                };
                let f = match &sf.value {
                    Value::List { items, .. } if items.len() == n => items.clone(),
                    Value::Vector(v, _) if n == 3 => v.0.to_vec(),
                    v => {
                        return Err(err(format!(
                            "{}: step `{forcing}` is {}, not a forcing list of {n}",
                            d.path,
                            v.describe()
                        )));
                    }
                };
                let coords = coordinates
                    .iter()
                    .map(|c| match d.symbols.get(c) {
                        Some(hdot_sym::Decl::Time) => Ok(Atom::time(c, 0)),
                        _ => Err(err(format!(
                            "{}: `{c}` is not a time symbol of the derivation",
                            d.path
                        ))),
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                (coords, m.into_iter().chain(f).collect())
            }
        };
        let n = coordinates.len();
        if n == 0 || n > MAX_DOF {
            return Err(err(format!(
                "{}: {n} coordinates; a derived model has 1 to {MAX_DOF}",
                d.path
            )));
        }
        let inputs: Vec<(String, TimeFunction)> = spec
            .inputs
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        let cx = Resolver {
            d,
            spec,
            coordinates: &coordinates,
            inputs: &inputs,
        };
        let unfold = |v: &[Poly]| v.iter().map(|p| d.unfold(p)).collect::<Vec<_>>();
        let mut divisors = Vec::new();
        let mut singular = Vec::new();
        let polys = unfold(&outputs);
        for p in &polys {
            for (m, _) in p.terms() {
                for &(a, e) in m.factors() {
                    if e >= 0 {
                        continue;
                    }
                    // A constant the equations divide by: zero (or an
                    // angle whose sine or cosine is below the divisor
                    // bound) makes them singular whatever the state.
                    if let AtomKind::Var { time: false, .. } = a.kind()
                        && spec.constants.get(a.name()) == Some(&0.0)
                        && !singular.iter().any(|(n, _)| n == a.name())
                    {
                        singular.push((
                            a.name().to_string(),
                            format!("the equations divide by the constant `{a}`, and it is 0"),
                        ));
                    }
                    let (q, sin) = match a.kind() {
                        AtomKind::Sin(q) => (q, true),
                        AtomKind::Cos(q) => (q, false),
                        _ => continue,
                    };
                    if !q.is_time_dependent()
                        && let Some(&v) = spec.constants.get(q.name())
                        && !singular.iter().any(|(n, _)| n == q.name())
                    {
                        let (f, value) = if sin {
                            ("sin", v.sin())
                        } else {
                            ("cos", v.cos())
                        };
                        if value.abs() < DIVISOR_BOUND {
                            singular.push((
                                q.name().to_string(),
                                format!(
                                    "the equations divide by {f}({q}), and with the constant `{q}` = {v} it is {value:.3e}: \
                                     they are singular for every state (choose another value of `{q}`, or derive the \
                                     equations for this case)"
                                ),
                            ));
                        }
                    }
                    if let Some(i) = coordinates.iter().position(|&c| c == q) {
                        let dv = Divisor { coordinate: i, sin };
                        if !divisors.contains(&dv) {
                            divisors.push(dv);
                        }
                    }
                }
            }
        }
        let compiled = cx.compile(&polys)?;
        let form = match &spec.equations {
            EquationsSpec::Explicit { .. } => Form::Explicit(compiled),
            EquationsSpec::MassMatrix { .. } => Form::MassMatrix(compiled),
        };
        let mut conserved = Vec::new();
        let mut names: Vec<&String> = d
            .steps
            .iter()
            .filter(|s| s.conserved)
            .map(|s| &s.name)
            .collect();
        for name in &spec.conserved {
            if !names.contains(&name) {
                names.push(name);
            }
        }
        for name in names {
            let s = step(name)?;
            let polys = unfold(&s.values().into_iter().cloned().collect::<Vec<_>>());
            conserved.push(Conserved {
                name: name.clone(),
                energy: energy_reason(s),
                compiled: cx.compile(&polys)?,
            });
        }
        // A frame's attitude is evaluated when it is a function of the
        // coordinates and inputs (a chain of rotations), or when the frame
        // is given by a constant angular velocity (turned by exp(t [ω]×)
        // from N, with which it coincides at t = 0); otherwise the reason.
        let frames = d
            .frames
            .iter()
            .map(|f| {
                let omega: Vec<Poly> = f.omega.0.iter().map(|p| d.unfold(p)).collect();
                let chain = (|| {
                    let omega = cx.compile(&omega).map_err(|e| e.to_string())?;
                    let attitude = match &f.parent {
                        Some((p, r)) => FrameAttitude::Rotation {
                            parent: d.frames.iter().position(|g| &g.name == p),
                            rotation: cx
                                .compile(&r.0.iter().flatten().cloned().collect::<Vec<_>>())
                                .map_err(|e| e.to_string())?,
                        },
                        None if f.omega.0.iter().all(|p| p.is_zero()) => FrameAttitude::Rotation {
                            parent: None,
                            rotation: cx
                                .compile(&Mat3::identity().0.iter().flatten().cloned().collect::<Vec<_>>())
                                .map_err(|e| e.to_string())?,
                        },
                        None if omega.sources.iter().all(|s| matches!(s, Source::Value(_))) => {
                            let mut w = [0.0; 3];
                            let mut buf = vec![0.0; omega.tape.slots()];
                            omega.tape.eval_slots(&mut buf, &mut w, false);
                            FrameAttitude::Spin(Vector3::from(w))
                        }
                        None => {
                            return Err(format!(
                                "it is given by its angular velocity, which is not constant ({}), not by a rotation: \
                                 its attitude is not a function of the coordinates",
                                f.omega.0.iter().map(|p| p.to_string()).collect::<Vec<_>>().join(", ")
                            ));
                        }
                    };
                    Ok(FrameChain { attitude, omega })
                })();
                (f.name.clone(), chain)
            })
            .collect();
        Ok(DerivedModel {
            coordinates,
            form,
            inputs,
            divisors,
            singular,
            conserved,
            frames,
            scratch: RefCell::new(Vec::new()),
        })
    }
}

/// The coordinates a step `mass_matrix(eqs, [q1'', q2'', …])` (or
/// `forcing(…)`) was written for, in the order of its columns: `None`
/// when the step's formula is not such a call with its unknowns in
/// brackets.
pub fn step_coordinates(d: &Derivation, step: &str) -> Option<Vec<String>> {
    use hdot_sym::parse::{AstKind, parse};
    let s = d.steps.iter().find(|s| s.name == step)?;
    let ast = parse(&s.formula).ok()?;
    let AstKind::Call { func, args } = &ast.kind else {
        return None;
    };
    if !matches!(func.as_str(), "mass_matrix" | "forcing") || args.len() != 2 {
        return None;
    }
    let AstKind::Vector { items, frame: None } = &args[1].kind else {
        return None;
    };
    items
        .iter()
        .map(|a| match &a.kind {
            AstKind::Name { name, primes: 2 } => Some(name.clone()),
            _ => None,
        })
        .collect()
}

/// The size below which a sine or cosine the equations divide by is a
/// singularity.
const DIVISOR_BOUND: f64 = 1e-9;

/// The largest number of coordinates a derived model takes.
pub const MAX_DOF: usize = 6;

struct Resolver<'a> {
    d: &'a Derivation,
    spec: &'a DerivedSpec,
    coordinates: &'a [Atom],
    inputs: &'a [(String, TimeFunction)],
}

impl Resolver<'_> {
    fn compile(&self, polys: &[Poly]) -> Result<Compiled, SimError> {
        // Constants (and sin, cos of constant angles) are folded into the
        // coefficients: only the state and the inputs are read per
        // evaluation. A constant without a value stays an input, and its
        // source is the error below.
        let tape = Tape::compile_with(polys, &mut |a| match self.source(a) {
            Ok(Source::Value(v)) => Some(v),
            _ => None,
        });
        let sources = tape
            .atoms()
            .iter()
            .map(|&a| self.source(a))
            .collect::<Result<Vec<_>, _>>()?;
        let gather = Gather::plan(&sources, self.coordinates.len());
        Ok(Compiled {
            tape,
            sources,
            gather,
        })
    }

    fn source(&self, a: Atom) -> Result<Source, SimError> {
        let coord = |q: Atom| self.coordinates.iter().position(|&c| c == q);
        let input = |q: Atom| self.inputs.iter().position(|(n, _)| n == q.name());
        let constant = |q: Atom| -> Result<f64, SimError> {
            self.spec.constants.get(q.name()).copied().ok_or_else(|| {
                err(format!(
                    "{}: the constant `{}` has no value: give it under the scene's `[constants]`, or bind it by a `[[body]]` table or the gravity vector `g`",
                    self.d.path,
                    q.name()
                ))
            })
        };
        Ok(match a.kind() {
            AtomKind::Var { time: false, .. } => Source::Value(constant(a)?),
            AtomKind::Var { order: 0, .. } if coord(a).is_some() => {
                Source::Coordinate(coord(a).expect("checked"))
            }
            AtomKind::Var { order: 1, .. } if coord(a.base()).is_some() => {
                Source::Rate(coord(a.base()).expect("checked"))
            }
            AtomKind::Var { order: 0, .. } if input(a).is_some() => {
                Source::Input(input(a).expect("checked"))
            }
            AtomKind::Var { .. } => {
                return Err(err(format!(
                    "{}: `{a}` is neither a coordinate, its rate, nor an input given as a function of t: \
                     the equations of motion must be in q and q̇ (coordinates: {})",
                    self.d.path,
                    self.coordinates
                        .iter()
                        .map(|c| c.name())
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            }
            AtomKind::Sin(q) | AtomKind::Cos(q) => {
                let sin = matches!(a.kind(), AtomKind::Sin(_));
                if let Some(i) = coord(q) {
                    if sin {
                        Source::SinOf(i)
                    } else {
                        Source::CosOf(i)
                    }
                } else if let Some(k) = input(q) {
                    if sin {
                        Source::SinInput(k)
                    } else {
                        Source::CosInput(k)
                    }
                } else if !q.is_time_dependent() {
                    let v = constant(q)?;
                    Source::Value(if sin { v.sin() } else { v.cos() })
                } else {
                    return Err(err(format!(
                        "{}: `{a}` depends on `{}`, which is neither a coordinate nor an input",
                        self.d.path,
                        q.name()
                    )));
                }
            }
        })
    }
}

/// # Queries
impl DerivedModel {
    /// The coordinates q, in state order (`y = (q, q̇)`).
    pub fn coordinates(&self) -> &[Atom] {
        &self.coordinates
    }

    /// The number of coordinates.
    pub fn dof(&self) -> usize {
        self.coordinates.len()
    }

    /// The quantities reported as drifts.
    pub fn conserved(&self) -> &[Conserved] {
        &self.conserved
    }

    /// The initial state from values of q and q̇ by coordinate name
    /// (`theta`, `theta'`); every one must be given.
    pub fn initial_state(&self, values: &BTreeMap<String, f64>) -> Result<Vec<f64>, SimError> {
        let n = self.dof();
        let mut y = vec![0.0; 2 * n];
        // A misspelt name is reported as such, before the name it misses.
        for key in values.keys() {
            let base = key.trim_end_matches('\'');
            if !self.coordinates.iter().any(|c| c.name() == base) || key.len() - base.len() > 1 {
                return Err(err(format!(
                    "initial value for `{key}`, which is not a coordinate or its rate"
                )));
            }
        }
        for (i, q) in self.coordinates.iter().enumerate() {
            for (k, key) in [q.name().to_string(), format!("{}'", q.name())]
                .into_iter()
                .enumerate()
            {
                let v = values.get(&key).copied().ok_or_else(|| {
                    err(format!(
                        "the initial value of `{key}` is missing (give every coordinate and its rate: {})",
                        self.coordinates
                            .iter()
                            .map(|c| format!("{0}, {0}'", c.name()))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ))
                })?;
                if !v.is_finite() {
                    return Err(err(format!(
                        "the initial value of `{key}` is not finite ({v})"
                    )));
                }
                y[k * n + i] = v;
            }
        }
        Ok(y)
    }

    /// Writes the value of each input of `c` at `(t, y)` into `into`.
    fn inputs_into(&self, c: &Compiled, t: f64, y: &[f64], into: &mut [f64]) {
        let g = &c.gather;
        for &(slot, i) in &g.copies {
            into[slot] = y[i];
        }
        for &(i, sin, cos) in &g.trig {
            match (sin, cos) {
                (Some(s), Some(c)) => (into[s], into[c]) = y[i].sin_cos(),
                (Some(s), None) => into[s] = y[i].sin(),
                (None, Some(c)) => into[c] = y[i].cos(),
                (None, None) => {}
            }
        }
        let n = self.dof();
        for &(slot, s) in &g.other {
            into[slot] = match s {
                Source::Coordinate(i) => y[i],
                Source::Rate(i) => y[n + i],
                Source::SinOf(i) => y[i].sin(),
                Source::CosOf(i) => y[i].cos(),
                Source::Value(v) => v,
                Source::Input(k) => self.inputs[k].1.eval(t),
                Source::SinInput(k) => self.inputs[k].1.eval(t).sin(),
                Source::CosInput(k) => self.inputs[k].1.eval(t).cos(),
            };
        }
    }

    /// Evaluates `c` at `(t, y)` in the model's scratch buffer (sized once:
    /// an evaluation allocates nothing).
    fn eval(&self, c: &Compiled, t: f64, y: &[f64], out: &mut [f64]) {
        let mut buf = self.scratch.borrow_mut();
        let slots = c.tape.slots();
        if buf.len() < slots {
            buf.resize(slots, 0.0);
        }
        self.inputs_into(c, t, y, &mut buf[..c.sources.len()]);
        c.tape.eval_slots(&mut buf, out, false);
    }

    /// The accelerations q̈ at `(t, y)`; `None` when the mass matrix cannot
    /// be factorised there.
    pub fn accelerations(&self, t: f64, y: &[f64], qdd: &mut [f64]) -> Option<()> {
        let n = self.dof();
        match &self.form {
            Form::Explicit(c) => {
                self.eval(c, t, y, qdd);
                Some(())
            }
            Form::MassMatrix(mf) => {
                // M and f on the stack (n ≤ MAX_DOF): no allocation.
                let mut buf = [0.0; MAX_DOF * MAX_DOF + MAX_DOF];
                let out = &mut buf[..n * n + n];
                self.eval(mf, t, y, out);
                solve_small(n, out, qdd)
            }
        }
    }

    /// A constant whose value makes the equations singular for every
    /// state, and why: one they divide by that is 0, or an angle whose
    /// sine or cosine they divide by is below the divisor bound (`1e-9`,
    /// as for the coordinates in [`DerivedModel::singularity`]).
    pub fn constant_singularity(&self) -> Option<(&str, &str)> {
        self.singular
            .first()
            .map(|(name, why)| (name.as_str(), why.as_str()))
    }

    /// The values of a conserved quantity at `(t, y)`.
    pub fn conserved_value(&self, q: &Conserved, t: f64, y: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; q.compiled.tape.outputs()];
        self.eval(&q.compiled, t, y, &mut out);
        out
    }

    /// Why the equations break down at `(t, y)`, if they do: a divisor
    /// `sin q`/`cos q` below `1e-9` in size, or a mass matrix with a
    /// reciprocal condition number below `1e-13`.
    pub fn singularity(&self, t: f64, y: &[f64]) -> Option<String> {
        for dv in &self.divisors {
            let q = y[dv.coordinate];
            let v = if dv.sin { q.sin() } else { q.cos() };
            if v.abs() < DIVISOR_BOUND {
                let name = self.coordinates[dv.coordinate].name();
                return Some(format!(
                    "{}({name}) = {v:.3e}, and the equations divide by it (a coordinate singularity: at {name} = {q:.6}, \
                     the coordinates cannot describe the motion)",
                    if dv.sin { "sin" } else { "cos" }
                ));
            }
        }
        if let Form::MassMatrix(mf) = &self.form {
            let n = self.dof();
            let mut mm = vec![0.0; n * n + n];
            self.eval(mf, t, y, &mut mm);
            let sv = DMatrix::from_row_slice(n, n, &mm[..n * n]).singular_values();
            let (lo, hi) = (sv.min(), sv.max());
            if lo.is_nan() || lo <= 1e-13 * hi {
                return Some(format!(
                    "the mass matrix is singular (singular values from {lo:.3e} to {hi:.3e})"
                ));
            }
        }
        None
    }

    /// The rotation matrix of frame `name` relative to N (columns: its
    /// axes in N's), evaluated from the derivation's chain of rotations; a
    /// frame given by a constant angular velocity coincides with N at
    /// t = 0. An error saying why when the frame, or a frame it hangs
    /// from, has no attitude that is a function of the state and t.
    pub fn attitude(&self, name: &str, t: f64, y: &[f64]) -> Result<Matrix3<f64>, String> {
        let mut i = self.frame_index(name)?;
        let mut r = Matrix3::identity();
        loop {
            let (fname, chain) = &self.frames[i];
            let f = chain.as_ref().map_err(|why| {
                if fname == name {
                    format!("the attitude of frame `{name}` cannot be evaluated: {why}")
                } else {
                    format!(
                        "the attitude of frame `{name}` cannot be evaluated: it hangs from frame `{fname}`, and {why}"
                    )
                }
            })?;
            match &f.attitude {
                FrameAttitude::Rotation { parent, rotation } => {
                    let mut m = [0.0; 9];
                    self.eval(rotation, t, y, &mut m);
                    r = Matrix3::from_row_slice(&m) * r;
                    match parent {
                        Some(p) => i = *p,
                        None => return Ok(r),
                    }
                }
                FrameAttitude::Spin(w) => {
                    return Ok(nalgebra::Rotation3::new(w * t).into_inner() * r);
                }
            }
        }
    }

    fn frame_index(&self, name: &str) -> Result<usize, String> {
        self.frames
            .iter()
            .position(|(n, _)| n == name)
            .ok_or_else(|| {
                format!(
                    "no frame `{name}` (frames: {})",
                    self.frames
                        .iter()
                        .map(|(n, _)| n.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })
    }

    /// The angular velocity of frame `name` relative to N, in its own axes.
    pub fn angular_velocity(&self, name: &str, t: f64, y: &[f64]) -> Result<Vector3<f64>, String> {
        let (_, f) = &self.frames[self.frame_index(name)?];
        let f = f.as_ref().map_err(|why| {
            format!("the angular velocity of frame `{name}` cannot be evaluated: {why}")
        })?;
        let mut w = [0.0; 3];
        self.eval(&f.omega, t, y, &mut w);
        Ok(Vector3::from(w))
    }
}

/// Solves `M q̈ = f` with `mf` = M (row-major, `n × n`) followed by f,
/// leaving q̈ in `x`; `None` when a pivot is exactly zero (M singular).
/// Gaussian elimination with partial pivoting on fixed-size arrays on the
/// stack, one instance per n ≤ [`MAX_DOF`] (unrolled, no allocation: a
/// general LU allocates its matrix per evaluation).
fn solve_small(n: usize, mf: &[f64], x: &mut [f64]) -> Option<()> {
    match n {
        1 => solve_fixed::<1>(mf, x),
        2 => solve_fixed::<2>(mf, x),
        3 => solve_fixed::<3>(mf, x),
        4 => solve_fixed::<4>(mf, x),
        5 => solve_fixed::<5>(mf, x),
        6 => solve_fixed::<6>(mf, x),
        _ => None,
    }
}

// Index loops read as the elimination is written (rows i and k of one array).
#[allow(clippy::needless_range_loop)]
fn solve_fixed<const N: usize>(mf: &[f64], x: &mut [f64]) -> Option<()> {
    let mut a = [[0.0; N]; N];
    for (i, row) in a.iter_mut().enumerate() {
        row.copy_from_slice(&mf[i * N..(i + 1) * N]);
    }
    let mut b = [0.0; N];
    b.copy_from_slice(&mf[N * N..N * N + N]);
    let mut inv = [0.0; N];
    for k in 0..N {
        // Partial pivoting by compare-and-swap with each row below (row k
        // ends with the largest |a[·][k]|): fixed indices only, so the
        // unrolled matrix can stay in registers.
        for i in k + 1..N {
            if a[i][k].abs() > a[k][k].abs() {
                let (top, rest) = a.split_at_mut(i);
                std::mem::swap(&mut top[k], &mut rest[0]);
                b.swap(i, k);
            }
        }
        if a[k][k] == 0.0 {
            return None;
        }
        inv[k] = 1.0 / a[k][k];
        for i in k + 1..N {
            let l = a[i][k] * inv[k];
            for j in k + 1..N {
                a[i][j] -= l * a[k][j];
            }
            b[i] -= l * b[k];
        }
    }
    for k in (0..N).rev() {
        let mut s = b[k];
        for j in k + 1..N {
            s -= a[k][j] * b[j];
        }
        b[k] = s * inv[k];
    }
    x.copy_from_slice(&b);
    Some(())
}

/// The model as an ODE on `y = (q, q̇)` with `N = 2 × dof` components.
pub struct DerivedSystem<'a, const N: usize>(pub &'a DerivedModel);

impl<const N: usize> System<N> for DerivedSystem<'_, N> {
    fn name(&self) -> &str {
        "derived"
    }

    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N] {
        let n = N / 2;
        let mut dy = [0.0; N];
        dy[..n].copy_from_slice(&y[n..]);
        if self.0.accelerations(t, y, &mut dy[n..]).is_none() {
            dy[n..].fill(f64::NAN);
        }
        dy
    }

    fn check(&self, t: f64, y: &[f64; N]) -> Result<(), SimError> {
        match self.0.singularity(t, y) {
            Some(why) => Err(SimError::CoordinateSingularity { t, why }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stack solve against nalgebra's LU for every size it takes, on
    /// seeded random matrices (and M x = f checked by its residual).
    #[test]
    fn the_small_solve_agrees_with_a_general_lu() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for n in 1..=MAX_DOF {
            for _ in 0..200 {
                let mf: Vec<f64> = (0..n * n + n).map(|_| next()).collect();
                let mut x = vec![0.0; n];
                solve_small(n, &mf, &mut x).expect("a random matrix is regular");
                let m = DMatrix::from_row_slice(n, n, &mf[..n * n]);
                let f = nalgebra::DVector::from_column_slice(&mf[n * n..]);
                let want = m.clone().lu().solve(&f).unwrap();
                // Both errors are bounded by the condition number times
                // the round-off of the solution's size.
                let sv = m.singular_values();
                let cond = sv.max() / sv.min();
                let scale = cond * (1.0 + want.amax()) * f64::EPSILON * 64.0;
                for i in 0..n {
                    assert!(
                        (x[i] - want[i]).abs() <= scale,
                        "n = {n}, x[{i}]: {} vs {} (scale {scale:.3e})",
                        x[i],
                        want[i]
                    );
                }
            }
        }
        // A zero pivot, wherever it appears, is a singular matrix.
        assert!(solve_small(2, &[1.0, 2.0, 2.0, 4.0, 1.0, 1.0], &mut [0.0; 2]).is_none());
        assert!(solve_small(1, &[0.0, 1.0], &mut [0.0; 1]).is_none());
        // Pivoting: a zero in the leading position is no singularity.
        let mut x = [0.0; 2];
        solve_small(2, &[0.0, 1.0, 1.0, 0.0, 3.0, 5.0], &mut x).unwrap();
        assert_eq!(x, [5.0, 3.0]);
    }
}
