//! Compiling the polynomials of derived equations to a [`Tape`]: where
//! each atom's value comes from (a coordinate, its rate or a generalized
//! speed, sin or cos of a coordinate, a constant folded in, or an applied
//! input), and how the tape's inputs are gathered from `(t, y)` once
//! planned. In a first-order model the coordinates' rates and the
//! dependent speeds are first replaced by what the kinematic equations
//! and the constraints give for them (the resolver's `replace`).

use hdot_num::eval::{Input, Tape};
use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::poly::Poly;

use super::{DerivedSpec, TimeFunction, at, err};
use crate::SimError;

/// Where the value of one atom of the compiled equations comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Source {
    /// `y[i]`: coordinate i.
    Coordinate(usize),
    /// `y[n + i]`: the rate of coordinate i (a second-order state).
    Rate(usize),
    /// `y[n + k]`: generalized speed k (a first-order state `(q, u)`).
    Speed(usize),
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
/// The tape gathers the state's components, and the sines and cosines of
/// the angles, itself ([`Tape::plan_inputs`]); `given` lists the other
/// inputs (applied inputs, unfolded values), written per evaluation.
#[derive(Debug, Clone)]
pub(super) struct Compiled {
    pub(super) tape: Tape,
    pub(super) sources: Vec<Source>,
    /// `slot ← source` for the inputs the state does not give.
    pub(super) given: Vec<(usize, Source)>,
}

/// Where the tape reads a source from in the state, if it does: `n`
/// coordinates, their rates or the speeds after them.
fn input(s: Source, n: usize) -> Input {
    match s {
        Source::Coordinate(i) => Input::Component(i),
        Source::Rate(i) | Source::Speed(i) => Input::Component(n + i),
        Source::SinOf(i) => Input::Sin(i),
        Source::CosOf(i) => Input::Cos(i),
        _ => Input::Given,
    }
}

pub(super) struct Resolver<'a> {
    pub(super) d: &'a Derivation,
    pub(super) spec: &'a DerivedSpec,
    pub(super) coordinates: &'a [Atom],
    /// The generalized speeds of a first-order state, in state order
    /// (empty for a second-order state `(q, q̇)`).
    pub(super) speeds: &'a [Atom],
    /// Atoms replaced before compiling (a first-order model's q̇ = f(q, u)
    /// and dependent speeds), each by a polynomial free of them.
    pub(super) replace: &'a [(Atom, Poly)],
    /// Angles carried in the state after the coordinates and their rates
    /// or speeds (see `carried.rs`), the first at `y[carried_base]`.
    pub(super) carried: &'a [Atom],
    pub(super) carried_base: usize,
    pub(super) inputs: &'a [(String, TimeFunction)],
}

impl Resolver<'_> {
    /// `p` with the atoms of `replace` replaced.
    pub(super) fn replaced(&self, p: &Poly) -> Poly {
        if self.replace.is_empty() {
            return p.clone();
        }
        p.subst(&mut |a| {
            self.replace
                .iter()
                .find(|(x, _)| *x == a)
                .map(|(_, v)| v.clone())
        })
    }

    pub(super) fn compile(&self, polys: &[Poly]) -> Result<Compiled, SimError> {
        let replaced: Vec<Poly>;
        let polys = if self.replace.is_empty() {
            polys
        } else {
            replaced = polys.iter().map(|p| self.replaced(p)).collect();
            &replaced
        };
        // Constants (and sin, cos of constant angles) are folded into the
        // coefficients: only the state and the inputs are read per
        // evaluation. A constant without a value stays an input, and its
        // source is the error below.
        let tape = Tape::compile_with(polys, &mut |a| match self.source(a) {
            Ok(Source::Value(v)) => Some(v),
            _ => None,
        });
        let mut tape = tape;
        let sources = tape
            .atoms()
            .iter()
            .map(|&a| self.source(a))
            .collect::<Result<Vec<_>, _>>()?;
        let n = self.coordinates.len();
        let mut planned = sources.iter();
        tape.plan_inputs(|_| input(*planned.next().expect("one source per atom"), n));
        // The plan orders the inputs as it gathers them: their sources in
        // that order.
        let sources = tape
            .atoms()
            .iter()
            .map(|&a| self.source(a))
            .collect::<Result<Vec<_>, _>>()?;
        let given = sources
            .iter()
            .enumerate()
            .filter(|(_, s)| input(**s, n) == Input::Given)
            .map(|(slot, s)| (slot, *s))
            .collect();
        Ok(Compiled {
            tape,
            sources,
            given,
        })
    }

    pub(super) fn source(&self, a: Atom) -> Result<Source, SimError> {
        let coord = |q: Atom| self.coordinates.iter().position(|&c| c == q);
        let speed = |u: Atom| self.speeds.iter().position(|&c| c == u);
        let first_order = !self.speeds.is_empty();
        let carried = |q: Atom| {
            self.carried
                .iter()
                .position(|&c| c == q)
                .map(|k| self.carried_base + k)
        };
        let input = |q: Atom| self.inputs.iter().position(|(n, _)| n == q.name());
        let constant = |q: Atom| -> Result<f64, SimError> {
            self.spec.constants.get(q.name()).copied().ok_or_else(|| {
                at("constants", err(format!(
                    "{}: the constant `{}` has no value: give it under the scene's `[constants]`, or bind it by a `[[body]]` table or the gravity vector `g`",
                    self.d.path,
                    q.name()
                )))
            })
        };
        Ok(match a.kind() {
            AtomKind::Var { time: false, .. } => Source::Value(constant(a)?),
            // A sum of constants (a denominator I′ + I L²/r²): its value.
            AtomKind::Sum { sum, .. } => {
                let mut missing = None;
                let v = sum.eval(&mut |b| {
                    constant(b).unwrap_or_else(|e| {
                        missing.get_or_insert(e);
                        f64::NAN
                    })
                });
                match missing {
                    Some(e) => return Err(e),
                    None => Source::Value(v),
                }
            }
            AtomKind::Var { order: 0, .. } if coord(a).is_some() => {
                Source::Coordinate(coord(a).expect("checked"))
            }
            AtomKind::Var { order: 0, .. } if carried(a).is_some() => {
                Source::Coordinate(carried(a).expect("checked"))
            }
            AtomKind::Var { order: 0, .. } if speed(a).is_some() => {
                Source::Speed(speed(a).expect("checked"))
            }
            AtomKind::Var { order: 1, .. } if !first_order && coord(a.base()).is_some() => {
                Source::Rate(coord(a.base()).expect("checked"))
            }
            AtomKind::Var { order: 0, .. } if input(a).is_some() => {
                Source::Input(input(a).expect("checked"))
            }
            AtomKind::Var { .. } => {
                let names = |v: &[Atom]| v.iter().map(|c| c.name()).collect::<Vec<_>>().join(", ");
                let why = if first_order {
                    format!(
                        "`{a}` is neither a coordinate, an independent speed, nor an input given as a function of t: \
                         the equations of a first-order model must be in q and u (coordinates: {}; speeds: {})",
                        names(self.coordinates),
                        names(self.speeds)
                    )
                } else {
                    format!(
                        "`{a}` is neither a coordinate, its rate, nor an input given as a function of t: \
                         the equations of motion must be in q and q̇ (coordinates: {})",
                        names(self.coordinates)
                    )
                };
                return Err(at("inputs", err(format!("{}: {why}", self.d.path))));
            }
            AtomKind::Sin(q) | AtomKind::Cos(q) => {
                let sin = matches!(a.kind(), AtomKind::Sin(_));
                if let Some(i) = coord(q).or_else(|| carried(q)) {
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
                    return Err(at(
                        "inputs",
                        err(format!(
                            "{}: `{a}` depends on `{}`, which is neither a coordinate nor an input",
                            self.d.path,
                            q.name()
                        )),
                    ));
                }
            }
        })
    }
}
