//! # Derived equations against particle sums
//!
//! A system of particles at fixed relative positions is a rigid body, so a
//! derived result must agree with the direct particle sum to round-off.
//! For each supported derivation this module draws random bodies (clouds,
//! coarsely discretised posed primitives and composites, coaxial stacks),
//! gives them the symmetry the derivation assumes (see below), binds the
//! derivation's symbols from the particle sums of *the same particles*
//! (moments and products of inertia as integrals, `I_xy = ∫xy dm`: the
//! tensor holds them with a minus sign), evaluates the derived step with a
//! compiled [`Tape`] and compares it with a value computed independently of
//! the derivation: a direct particle sum (Σ m r × a, Σ m r × v, Σ ½ m v²,
//! the inertia about P), or — where the step is kinematics, not kinetics —
//! the exact time derivative of a known trajectory (rotation matrices
//! R(t) = R₁(q₁(t)) R₂(q₂(t)) … differentiated by the product rule, never
//! through ω or the transport theorem), or a numeric linear-algebra answer
//! computed from the particle inertia (a solve, a Jacobian's eigenvalues).
//!
//! | family (file) | derivations | bodies |
//! |---|---|---|
//! | [`free`] | `principal-axis-stability` | triaxial principal |
//!
//! (The rotation chains of [`motion`] are shared with the simulation's
//! tests.)
//!
//! Steps that only restate the symbols (`r = [x, y, z]`, `F̂ = [F_x, F_y,
//! F_z]`) are not compared: evaluating them returns the bound values
//! themselves. [`coverage`] lists, per derivation, what each step is
//! compared against and what is not compared; `hdot verify` prints it.
//!
//! The error of a comparison is `|derived − direct| / scale`, where the
//! scale is the sum of the magnitudes of the derived terms with every
//! symbol replaced by a bound on its size (inertia components by
//! `Σ m |r|²`, a moment that is divided by by its own value, vector
//! components by the vector's norm, sin and cos by 1) plus the magnitude
//! of the direct value (and, where the direct computation cancels large
//! terms, their magnitude); it passes below [`TOLERANCE_ULPS`] units of
//! round-off.

mod bodies;
mod declared;
pub mod free;
pub mod motion;
pub mod quantities;
pub mod rigid;
#[cfg(feature = "proptest")]
pub mod strategy;
pub mod world;

use std::collections::HashMap;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::poly::Poly;
use nalgebra::{Rotation3, Vector3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

pub use bodies::{random_body, random_cloud, random_state};
pub use declared::{
    Draw, MeasuredBody, Options, Report, StepCheck, Values, bind_bodies, check, check_bodies,
    check_with, symmetric,
};

use crate::cloud::ParticleCloud;
use crate::error::BodyError;
use crate::eval::Tape;

/// Pass threshold, in units of `f64::EPSILON` relative to the scale.
pub const TOLERANCE_ULPS: f64 = 256.0;

/// The derivations with a numeric check, by file stem.
pub const SUPPORTED: &[&str] = &["principal-axis-stability"];

/// What a derivation's check compares, step by step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coverage {
    /// The derivation (file stem).
    pub derivation: &'static str,
    /// `(steps, compared against)`: particle sums, or numerics on the
    /// particle inertia.
    pub compared: &'static [(&'static str, &'static str)],
    /// `(steps, compared against)`: kinematics, compared with the exact
    /// derivatives of a known motion (no particle sum is involved).
    pub kinematic: &'static [(&'static str, &'static str)],
    /// `(steps, why not compared)`.
    pub not_compared: &'static [(&'static str, &'static str)],
}

/// Per derivation: each step and what it is compared against.
pub const COVERAGE: &[Coverage] = &[Coverage {
    derivation: "principal-axis-stability",
    compared: &[
        ("M", "Σ m r × a, disturbed spin"),
        (
            "L",
            "central difference of Σ m r × a (exact for a quadratic)",
        ),
        (
            "eps3_rate, eps2_acc",
            "J ε, J² ε with J = −I⁻¹ ∂(ω × Iω)/∂ω from particle sums",
        ),
        ("k_1", "−λ²/Ω², λ the largest eigenvalue of J"),
        (
            "sign_*",
            "sign of −λ² for spin about the largest, middle, smallest moment",
        ),
    ],
    kinematic: &[],
    not_compared: &[],
}];

/// What the check of `name` compares, when it has one.
pub fn coverage(name: &str) -> Option<&'static Coverage> {
    COVERAGE.iter().find(|c| c.derivation == name)
}

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
    /// A numeric solve failed (singular particle inertia).
    #[error("{derivation}: {what} is singular")]
    Singular {
        /// Derivation name.
        derivation: String,
        /// What could not be solved.
        what: &'static str,
    },
    /// A random body was invalid (a bug in the sampler).
    #[error(transparent)]
    Body(#[from] BodyError),
    /// The declarations cannot be met by the drawn bodies and motions.
    #[error("{derivation}: {message}")]
    Declaration {
        /// Derivation name.
        derivation: String,
        /// What is wrong.
        message: String,
    },
}

impl VerifyError {
    pub(crate) fn unbound(d: &Derivation, step: &str, a: Atom) -> VerifyError {
        VerifyError::Unbound {
            derivation: d.name.clone(),
            step: step.into(),
            symbol: a.to_string(),
        }
    }

    /// The same error, attributed to `step` of `d`.
    pub(crate) fn in_step(self, d: &Derivation, step: &str) -> VerifyError {
        match self {
            VerifyError::Unbound { symbol, .. } => VerifyError::Unbound {
                derivation: d.name.clone(),
                step: step.into(),
                symbol,
            },
            e => e,
        }
    }
}

/// A random instantaneous state. Each check uses the fields it needs:
///
/// - `omega`, `alpha`: ω and α (body axes); for derivations in Eulerian
///   angles the rates (φ̇, θ̇, ψ̇) and accelerations of `angles`; for
///   `principal-axis-stability` the spin Ω (from `omega.x`) and ε̇.
/// - `v`: v̄ (body axes); the disturbance ε; the point's
///   velocity in the rotating frame; H_G = 1 + |v| for the torque-free body.
/// - `a`: ā; the point's acceleration in the rotating frame.
/// - `axes`, `offset`: the derivation's body axes and G − O (or G − P,
///   the point's position, the height of G above O on a rotor's axis).
/// - `angles`, `spin`: Eulerian angles; the body's spin angle, rate and
///   acceleration relative to a frame that does not spin with it.
/// - `fold`: copies (≥ 3) rotated about the axis of an axisymmetric body.
/// - `axis`: the principal axis that spins (`principal-axis-stability`).
/// - `stretch`: how elongated or flattened a torque-free body is made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// ω (body axes).
    pub omega: Vector3<f64>,
    /// α (body axes).
    pub alpha: Vector3<f64>,
    /// v̄ (body axes).
    pub v: Vector3<f64>,
    /// ā (body axes).
    pub a: Vector3<f64>,
    /// Body axes in world coordinates (columns), unless the derivation
    /// fixes them (principal axes).
    pub axes: Rotation3<f64>,
    /// G − O (or G − P), body axes.
    pub offset: Vector3<f64>,
    /// Eulerian angles (φ, θ, ψ), each in (−π, π).
    pub angles: Vector3<f64>,
    /// Spin of a body relative to a non-spinning frame: (β, β̇, β̈).
    pub spin: Vector3<f64>,
    /// Rotated copies that make a body axisymmetric (3–6).
    pub fold: usize,
    /// Principal axis index (0–2).
    pub axis: usize,
    /// In (0.1, 4): `1 + stretch` is the ratio Σ m z² / Σ m x² of an
    /// elongated body, its inverse that of a flattened one.
    pub stretch: f64,
}

/// One derived value against its direct value.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// `step[component]`.
    pub quantity: String,
    /// The derived result, evaluated.
    pub derived: f64,
    /// The direct value (particle sum or independent numerics).
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
            .and_then(|(cloud, state)| check_named(d, &cloud, &state).expect("supported"));
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

type CheckFn = fn(&Derivation, &ParticleCloud, &State) -> Result<Vec<Comparison>, VerifyError>;

/// Runs the check of `d` on one body (world coordinates) and state.
/// `None` when the derivation has no numeric check.
pub fn check_named(
    d: &Derivation,
    cloud: &ParticleCloud,
    state: &State,
) -> Option<Result<Vec<Comparison>, VerifyError>> {
    let f: CheckFn = match d.name.as_str() {
        "principal-axis-stability" => free::principal_axis_stability,
        _ => return None,
    };
    Some(f(d, cloud, state))
}

/// Values of the derivation's symbols by (name, derivative order), and
/// bounds on their magnitudes. `sin` and `cos` of a bound angle are
/// evaluated, with size 1.
#[derive(Default)]
pub(crate) struct Binding {
    value: HashMap<(&'static str, u32), f64>,
    size: HashMap<(&'static str, u32), f64>,
}

impl Binding {
    pub(crate) fn set(&mut self, name: &'static str, order: u32, value: f64, size: f64) {
        self.value.insert((name, order), value);
        self.size.insert((name, order), size);
    }

    /// A value that is its own size (a positive moment, a magnitude).
    pub(crate) fn scalar(&mut self, name: &'static str, order: u32, value: f64) {
        self.set(name, order, value, value.abs());
    }

    /// The components of `v`, each sized by the norm of `v`.
    pub(crate) fn vector(&mut self, names: [&'static str; 3], order: u32, v: &Vector3<f64>) {
        for (name, x) in names.into_iter().zip(v.iter()) {
            self.set(name, order, *x, v.norm());
        }
    }

    fn lookup(&self, a: Atom, size: bool) -> Option<f64> {
        let map = if size { &self.size } else { &self.value };
        let angle = |x: Atom| match x.kind() {
            AtomKind::Var { name, order, .. } => self.value.get(&(name, order)).copied(),
            _ => None,
        };
        match a.kind() {
            AtomKind::Var { name, order, .. } => map.get(&(name, order)).copied(),
            AtomKind::Sin(x) => angle(x).map(|t| if size { 1.0 } else { t.sin() }),
            AtomKind::Cos(x) => angle(x).map(|t| if size { 1.0 } else { t.cos() }),
        }
    }
}

/// The components of a step, flattened (vectors x, y, z; matrices by
/// rows), with abbreviations (and their derivatives) unfolded.
fn components(d: &Derivation, step: &str) -> Result<Vec<Poly>, VerifyError> {
    let s = d
        .steps
        .iter()
        .find(|s| s.name == step)
        .ok_or_else(|| VerifyError::MissingStep {
            derivation: d.name.clone(),
            step: step.into(),
        })?;
    Ok(s.values().into_iter().map(|p| d.unfold(p)).collect())
}

/// Evaluates `step` under `b` and compares component `k` with `direct[k]`.
pub(crate) fn compare(
    d: &Derivation,
    step: &str,
    b: &Binding,
    direct: &[f64],
) -> Result<Vec<Comparison>, VerifyError> {
    compare_scaled(d, step, b, direct, &[])
}

/// [`compare`], adding `extra[k]` (the magnitude of terms the direct
/// computation cancels) to the scale of component `k`.
pub(crate) fn compare_scaled(
    d: &Derivation,
    step: &str,
    b: &Binding,
    direct: &[f64],
    extra: &[f64],
) -> Result<Vec<Comparison>, VerifyError> {
    let polys = components(d, step)?;
    if polys.len() != direct.len() {
        return Err(VerifyError::WrongShape {
            derivation: d.name.clone(),
            step: step.into(),
            expected: match direct.len() {
                1 => "a scalar",
                3 => "a vector",
                _ => "a matrix",
            },
        });
    }
    let tape = Tape::compile(&polys);
    let mut values = Vec::with_capacity(tape.atoms().len());
    let mut sizes = Vec::with_capacity(tape.atoms().len());
    for &a in tape.atoms() {
        let unbound = || VerifyError::Unbound {
            derivation: d.name.clone(),
            step: step.into(),
            symbol: a.name().to_string(),
        };
        values.push(b.lookup(a, false).ok_or_else(unbound)?);
        sizes.push(b.lookup(a, true).ok_or_else(unbound)?.abs());
    }
    let mut derived = vec![0.0; polys.len()];
    let mut scale = vec![0.0; polys.len()];
    tape.eval(&values, &mut derived);
    tape.eval_abs(&sizes, &mut scale);
    let mut scale: Vec<f64> = (0..polys.len())
        .map(|k| scale[k] + direct[k].abs() + extra.get(k).copied().unwrap_or(0.0))
        .collect();
    // A vector's (or matrix's) components are computed to round-off of
    // its size (they mix under a rotation): each is compared on the
    // largest scale.
    let top = scale.iter().copied().fold(0.0, f64::max);
    scale.fill(top);
    let axes = ["x", "y", "z"];
    Ok((0..polys.len())
        .map(|k| Comparison {
            quantity: match polys.len() {
                1 => step.to_string(),
                3 => format!("{step}.{}", axes[k]),
                _ => format!("{step}.{}{}", axes[k / 3], axes[k % 3]),
            },
            derived: derived[k],
            direct: direct[k],
            scale: scale[k] + f64::MIN_POSITIVE,
        })
        .collect())
}
