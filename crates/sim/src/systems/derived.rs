//! Equations of motion taken from a derivation file: the accelerations a
//! derivation solved for (`solve(eqs, [q1'', …])`), or its mass-matrix
//! form M(q) q̈ = f(q, q̇, t) (`mass_matrix`, `forcing`), compiled with
//! `hdot-num`'s [`Tape`] and integrated as `y = (q, q̇)`; or a first-order
//! form in generalized speeds, the kinematic equations q̇ = f(q, u) with
//! the speeds' rates solved for or in mass-matrix form, integrated as
//! `y = (q, u)` (`derived/first_order.rs`).
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
//! with a built-in model on the attitude matrix and ω; so is where each
//! declared body is ([`DerivedModel::position`], `derived/positions.rs`).

use std::collections::BTreeMap;

use hdot_sym::atom::Atom;
use nalgebra::{DMatrix, Matrix3, Vector3};

use crate::{SimError, System};

pub use super::time_function::TimeFunction;

mod build;
mod carried;
mod compile;
mod first_order;
mod holonomic;
mod multiplier;
mod positions;
mod small_solve;
mod symmetric_solve;
mod unit_norm;

pub use build::{in_speed_rates, step_coordinates};
use compile::{Compiled, Source};
pub use holonomic::{ConstraintMonitor, NewtonFailure};
pub use multiplier::{MultiplierSpec, VelocityMonitor};
use symmetric_solve::MassSolve;

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
    /// A first-order form in generalized speeds: the derivation's
    /// kinematic equations q̇ = f(q, u) and the speeds' rates; the state
    /// is `(q, u)`, q in the order of `[kinematics]`, u the independent
    /// speeds in the order the rates' step solves for them.
    FirstOrder {
        /// Where the speeds' rates are.
        rates: SpeedRates,
        /// A step solved for the dependent speeds in the others
        /// (`solve(constraints, [u4, u5])`), replaced by their values.
        dependent: Option<String>,
        /// Configuration constraints f(q) = 0 and their dependent
        /// coordinates (`derived/holonomic.rs`).
        holonomic: Option<HolonomicSpec>,
    },
}

/// Configuration constraints f(q) = 0 of a first-order model: solved for
/// the dependent coordinates at the start, monitored along the run and
/// (by default) kept by projection after each step.
#[derive(Debug, Clone, PartialEq)]
pub struct HolonomicSpec {
    /// The steps whose components are f (each a scalar or a list).
    pub steps: Vec<String>,
    /// The dependent coordinates q_d, one per constraint.
    pub dependent: Vec<String>,
    /// Whether q_d is projected back onto f = 0 after every step.
    pub project: bool,
}

/// Where a first-order model's speed rates are.
#[derive(Debug, Clone, PartialEq)]
pub enum SpeedRates {
    /// A step `solve(eqs, [u1', u2', …])`.
    Explicit {
        /// The step's name.
        step: String,
    },
    /// Steps `mass_matrix(eqs, [u1', …])` and `forcing(eqs, [u1', …])`:
    /// M(q) u̇ = f(q, u).
    MassMatrix {
        /// The step holding M.
        mass_matrix: String,
        /// The step holding f.
        forcing: String,
    },
    /// The multiplier form M u̇ − f = A_cᵀ λ, A_c u̇ + b = 0, solved for
    /// u̇ and λ at each evaluation (`derived/multiplier.rs`).
    Multiplier(MultiplierSpec),
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

// A tag byte (`repr(u8)`): `DerivedSystem::rhs` matches on the form at
// every evaluation, and the niche in the tapes' vectors that Rust uses
// otherwise took ~8 instructions to decode.
#[derive(Debug, Clone)]
#[repr(u8)]
enum Form {
    /// q̈ (second order), or q̇ then u̇ (first order).
    Explicit(Compiled),
    /// M (row-major) and f, the outputs of one tape; then q̇ in a first-order
    /// model; and how M q̈ = f is solved.
    MassMatrix(Compiled, MassSolve),
    /// M, f, A_c and b of a multiplier form, then q̇.
    Multiplier(Compiled, multiplier::Layout),
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
    /// The independent generalized speeds of a first-order state
    /// `(q, u)`, in state order; empty for a second-order state `(q, q̇)`.
    speeds: Vec<Atom>,
    /// Angles a `[motion]` rule's rate ties to the state (a frame turns by
    /// them), carried at the end of the state, and their rates.
    carried: Vec<Atom>,
    carried_rates: Option<Compiled>,
    /// The length of the state `(q, q̇)` when it is that and nothing
    /// else (second order, no carried angles), 0 otherwise: the one test
    /// `DerivedSystem::rhs` makes for its direct path (a comparison with
    /// its `N`).
    plain_state: usize,
    form: Form,
    inputs: Vec<(String, TimeFunction)>,
    divisors: Vec<Divisor>,
    /// Constants that make the equations singular whatever the state
    /// (see [`DerivedModel::constant_singularity`]).
    singular: Vec<(String, String)>,
    conserved: Vec<Conserved>,
    /// Configuration constraints and their dependent coordinates.
    holonomic: Option<holonomic::Holonomic>,
    /// The quaternions of the state, normalized after every step.
    unit_norms: unit_norm::UnitNorms,
    /// The derivation's frames, in order: each frame's name and its
    /// motion, or why its attitude cannot be evaluated.
    frames: Vec<(String, Result<FrameChain, String>)>,
    /// Where each declared body's reference point is (`derived/positions.rs`).
    placements: Vec<(String, positions::Placement)>,
    /// The derivation's gravity, compiled.
    gravity: Option<positions::Piece>,
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
        rotation: Box<Compiled>,
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

/// An error traced to the scene's `field`, unless it is traced already.
fn at(field: &str, e: SimError) -> SimError {
    match e {
        SimError::Derived { message } => SimError::DerivedField {
            field: field.to_string(),
            message,
        },
        e => e,
    }
}

/// An error met while compiling the steps `steps`, said to be there.
fn in_steps(steps: &[&str], e: SimError) -> SimError {
    let names = steps
        .iter()
        .map(|s| format!("`{s}`"))
        .collect::<Vec<_>>()
        .join(" and ");
    let which = if steps.len() == 1 { "step" } else { "steps" };
    match e {
        SimError::Derived { message } => SimError::Derived {
            message: format!("{message} (in {which} {names})"),
        },
        SimError::DerivedField { field, message } => SimError::DerivedField {
            field,
            message: format!("{message} (in {which} {names})"),
        },
        e => e,
    }
}

/// The size below which a sine or cosine the equations divide by is a
/// singularity.
const DIVISOR_BOUND: f64 = 1e-9;

/// The largest number of coordinates a derived model takes (of speeds in
/// a first-order model with the speeds' rates solved for or in
/// mass-matrix form).
pub const MAX_DOF: usize = 6;

/// The largest number of components of a derived model's state (a
/// multiplier form's coordinates and speeds, the carried angles).
pub const MAX_STATE: usize = 18;

/// # Queries
impl DerivedModel {
    /// The coordinates q, in state order (`y = (q, q̇)` or `(q, u)`).
    pub fn coordinates(&self) -> &[Atom] {
        &self.coordinates
    }

    /// The independent generalized speeds of a first-order model, in
    /// state order (`y = (q, u)`); empty for a second-order model.
    pub fn speeds(&self) -> &[Atom] {
        &self.speeds
    }

    /// Whether the state is `(q, u)` (first order) rather than `(q, q̇)`.
    pub fn is_first_order(&self) -> bool {
        !self.speeds.is_empty()
    }

    /// The number of coordinates.
    pub fn dof(&self) -> usize {
        self.coordinates.len()
    }

    /// The angles carried at the end of the state: a frame turns by them
    /// and a `[motion]` rule gives their rate (`psi' = -(L/r)*phi'`).
    pub fn carried(&self) -> &[Atom] {
        &self.carried
    }

    /// Where the carried angles start in the state: after `(q, q̇)` or
    /// `(q, u)`.
    pub fn carried_base(&self) -> usize {
        if self.is_first_order() {
            self.coordinates.len() + self.speeds.len()
        } else {
            2 * self.coordinates.len()
        }
    }

    /// The number of the state's components: `2 × dof`, or the
    /// coordinates and speeds of a first-order model, and the carried
    /// angles.
    pub fn state_len(&self) -> usize {
        self.carried_base() + self.carried.len()
    }

    /// The state's component names: each coordinate, then each rate
    /// (`theta'`) or each speed (`u_1`), then each carried angle.
    pub fn state_names(&self) -> Vec<String> {
        let q = self.coordinates.iter().map(|c| c.name().to_string());
        let names: Vec<String> = if self.is_first_order() {
            q.chain(self.speeds.iter().map(|u| u.name().to_string()))
                .collect()
        } else {
            q.chain(self.coordinates.iter().map(|c| format!("{}'", c.name())))
                .collect()
        };
        names
            .into_iter()
            .chain(self.carried.iter().map(|a| a.name().to_string()))
            .collect()
    }

    /// The quantities reported as drifts.
    pub fn conserved(&self) -> &[Conserved] {
        &self.conserved
    }

    /// The initial state from values of q and q̇ (or u) by name (`theta`,
    /// `theta'`, `u_1`); every one must be given, except the carried
    /// angles (0 unless given).
    pub fn initial_state(&self, values: &BTreeMap<String, f64>) -> Result<Vec<f64>, SimError> {
        let names = self.state_names();
        let mut y = vec![0.0; names.len()];
        // A misspelt name is reported as such, before the name it misses.
        for key in values.keys() {
            if !names.contains(key) {
                let what = if self.is_first_order() {
                    "a coordinate or an independent speed"
                } else {
                    "a coordinate or its rate"
                };
                return Err(err(format!(
                    "initial value for `{key}`, which is not {what} (the state: {})",
                    names.join(", ")
                )));
            }
        }
        let base = self.carried_base();
        for (k, (slot, key)) in y.iter_mut().zip(&names).enumerate() {
            // A carried angle starts at 0 unless given.
            // So does a dependent speed, solved from the constraints.
            let dependent = self.dependent_speeds().contains(key);
            if dependent && values.contains_key(key) {
                return Err(err(format!(
                    "`{key}` is a dependent speed, solved from the velocity constraints A_c u = 0: \
                     give the independent speeds only"
                )));
            }
            let v = values
                .get(key)
                .copied()
                .or((k >= base || dependent).then_some(0.0));
            let v = v.ok_or_else(|| {
                err(format!(
                    "the initial value of `{key}` is missing (give every component of the state: {})",
                    names.join(", ")
                ))
            })?;
            if !v.is_finite() {
                return Err(err(format!(
                    "the initial value of `{key}` is not finite ({v})"
                )));
            }
            *slot = v;
        }
        Ok(y)
    }

    /// Writes the value of each input of `c` the state does not give
    /// (applied inputs at t, unfolded values) into `into`.
    fn given_into(&self, c: &Compiled, t: f64, y: &[f64], into: &mut [f64]) {
        let n = self.dof();
        for &(slot, s) in &c.given {
            into[slot] = match s {
                Source::Coordinate(i) => y[i],
                Source::Rate(i) | Source::Speed(i) => y[n + i],
                Source::SinOf(i) => y[i].sin(),
                Source::CosOf(i) => y[i].cos(),
                Source::Value(v) => v,
                Source::Input(k) => self.inputs[k].1.eval(t),
                Source::SinInput(k) => self.inputs[k].1.eval(t).sin(),
                Source::CosInput(k) => self.inputs[k].1.eval(t).cos(),
            };
        }
    }

    /// Evaluates `c` at `(t, y)`: the tape gathers its inputs from the
    /// state itself, in one call, in a buffer on its stack (an evaluation
    /// allocates nothing).
    #[inline(always)]
    fn eval(&self, c: &Compiled, t: f64, y: &[f64], out: &mut [f64]) {
        if c.given.is_empty() {
            c.tape.eval_at(y, |_| {}, out);
        } else {
            c.tape
                .eval_at(y, |slots| self.given_into(c, t, y, slots), out);
        }
    }

    /// The rate of the state, `ẏ` at `(t, y)`: `(q̇, q̈)` or `(q̇, u̇)`;
    /// `None` when the mass matrix cannot be factorised there.
    pub fn rates(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Option<()> {
        if let Some(c) = &self.carried_rates {
            let base = self.carried_base();
            self.eval(c, t, y, &mut dy[base..base + self.carried.len()]);
        }
        if self.is_first_order() {
            return self.first_order_rates(t, y, dy);
        }
        let n = self.dof();
        dy[..n].copy_from_slice(&y[n..2 * n]);
        self.second_order_accelerations(t, y, &mut dy[n..2 * n])
    }

    /// The accelerations q̈ at `(t, y)` of a second-order model; `None`
    /// when the mass matrix cannot be factorised there, or the model is of
    /// first order (see [`DerivedModel::rates`]).
    pub fn accelerations(&self, t: f64, y: &[f64], qdd: &mut [f64]) -> Option<()> {
        if self.is_first_order() {
            return None;
        }
        self.second_order_accelerations(t, y, qdd)
    }

    /// Whether the state is `(q, q̇)` and nothing else: second order, no
    /// carried angles.
    fn is_plain_second_order(&self) -> bool {
        !self.is_first_order() && self.carried_rates.is_none()
    }

    /// [`DerivedModel::plain_state`]'s value, set when the model is built.
    fn plain_state_of(&self) -> usize {
        if self.is_plain_second_order() {
            2 * self.dof()
        } else {
            0
        }
    }

    /// [`DerivedModel::accelerations`] of a model known to be of second
    /// order.
    #[inline(always)]
    fn second_order_accelerations(&self, t: f64, y: &[f64], qdd: &mut [f64]) -> Option<()> {
        let n = self.dof();
        match &self.form {
            Form::Explicit(c) => {
                self.eval(c, t, y, qdd);
                Some(())
            }
            // M and f on the stack, in a buffer sized for n ≤ 3 when it
            // fits: clearing the one sized for MAX_DOF (42 slots) was a
            // `memset` call of ~35 instructions per evaluation.
            Form::MassMatrix(mf, solve) if n <= 3 => {
                self.mass_matrix_accelerations::<{ 3 * 3 + 3 }>(mf, solve, t, y, qdd)
            }
            Form::MassMatrix(mf, solve) => self
                .mass_matrix_accelerations::<{ MAX_DOF * MAX_DOF + MAX_DOF }>(mf, solve, t, y, qdd),
            Form::Multiplier(..) => None,
        }
    }

    /// q̈ from `M q̈ = f`, M and f evaluated into a buffer of `L ≥ n² + n`
    /// slots on the stack (no allocation).
    #[inline(always)]
    fn mass_matrix_accelerations<const L: usize>(
        &self,
        mf: &Compiled,
        solve: &MassSolve,
        t: f64,
        y: &[f64],
        qdd: &mut [f64],
    ) -> Option<()> {
        let n = self.dof();
        let mut buf = [0.0; L];
        let out = &mut buf[..n * n + n];
        // M's structural zeros are left as the cleared buffer has them.
        if mf.given.is_empty() {
            mf.tape.eval_at_cleared(y, |_| {}, out);
        } else {
            mf.tape
                .eval_at_cleared(y, |slots| self.given_into(mf, t, y, slots), out);
        }
        solve.solve(out, qdd)
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

    /// The size of a conserved quantity's components at `(t, y)`: per
    /// component the sum of its terms' magnitudes, `Σ |c · monomial|` —
    /// for an energy T + V, the kinetic and potential energies it is made
    /// of, which stay apart from zero when their sum is zero.
    pub fn conserved_size(&self, q: &Conserved, t: f64, y: &[f64]) -> Vec<f64> {
        let c = &q.compiled;
        let mut inputs = vec![0.0; c.tape.atoms().len()];
        let mut out = vec![0.0; c.tape.outputs()];
        // The inputs as the tape gathers them at `(t, y)`, then the terms'
        // magnitudes at them.
        c.tape.eval_at(
            y,
            |slots| {
                self.given_into(c, t, y, slots);
                inputs.copy_from_slice(slots);
            },
            &mut out,
        );
        c.tape.eval_abs(&inputs, &mut out);
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
        if let Some(why) = self.multiplier_singularity(t, y) {
            return Some(why);
        }
        if let Form::MassMatrix(mf, _) = &self.form {
            // M is over the speeds' rates in a first-order model.
            let n = if self.is_first_order() {
                self.speeds.len()
            } else {
                self.dof()
            };
            let mut mm = vec![0.0; mf.tape.outputs()];
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

/// The model as an ODE on `y = (q, q̇)` with `N = 2 × dof` components, or
/// on `y = (q, u)` (first order) with the coordinates and speeds.
pub struct DerivedSystem<'a, const N: usize>(pub &'a DerivedModel);

impl<const N: usize> System<N> for DerivedSystem<'_, N> {
    fn name(&self) -> &str {
        "derived"
    }

    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N] {
        let mut dy = [0.0; N];
        let m = self.0;
        // A state (q, q̇) with nothing after it: q̇ copied at a length known
        // when compiled, and q̈ from the equations with no call to `rates`
        // (its frame and a `memcpy` call were ~70 of the heavy top's ~560
        // instructions per evaluation).
        let done = if N > 0 && m.plain_state == N {
            let (q, v) = dy.split_at_mut(N / 2);
            q.copy_from_slice(&y[N / 2..]);
            m.second_order_accelerations(t, y, v)
        } else {
            m.rates(t, y, &mut dy)
        };
        if done.is_none() {
            let n = m.dof();
            dy[n..].fill(f64::NAN);
        }
        dy
    }

    /// The configuration constraints' residual recorded and, when the
    /// scene asks for it (the default), q_d projected back onto f = 0; a
    /// multiplier form's dependent speeds solved from A_c u = 0 and the
    /// velocity constraints' residual recorded.
    fn project(&self, y: &mut [f64; N]) -> bool {
        // f(q) has no applied input (refused when compiled): t is not read;
        // nor has A_c (a multiplier form with inputs is refused).
        let e = self.0.keep_unit_norms(y);
        let q = self.0.keep_constraints(0.0, y);
        let u = self.0.keep_velocity_constraints(0.0, y);
        e || q || u
    }

    fn check(&self, t: f64, y: &[f64; N]) -> Result<(), SimError> {
        match self.0.singularity(t, y) {
            Some(why) => Err(SimError::CoordinateSingularity { t, why }),
            None => Ok(()),
        }
    }
}
