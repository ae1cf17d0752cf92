//! The operations of the expression language: a registry of
//! self-describing entries (STYLE.md 14).
//!
//! Each operation lives in its own file and is declared once, as an
//! `Op`: its names, its signature, one line of documentation and its
//! evaluation. The evaluator looks functions up here, the error for an
//! unknown function lists `OPS`, and the function table of
//! `docs/derivation-format.md` is generated from it (a test keeps the
//! document in step with [`catalogue`]).

mod angvel;
mod coeff;
mod constraints;
mod contact;
mod dt;
mod express;
mod in_speeds;
mod kane;
mod lagrange;
mod linearize;
mod list;
mod mass_matrix;
mod matrix;
mod partial;
mod position;
mod sign;
mod solve;
mod state_space;
mod subst;
mod trig;
mod vector;
mod velocity;

pub(crate) use express::express_in;
pub(crate) use mass_matrix::linear_system;
pub(crate) use solve::{determinant, solve_system, sum_inverse};
pub(crate) use subst::quarter_turns;

use super::context::{Context, R};
use super::value::Value;
use crate::atom::Atom;
use crate::parse::{Ast, AstKind, Span};
use crate::poly::Poly;
use crate::vector::Vec3;

/// One operation of the expression language.
pub(crate) struct Op {
    /// The names it is called by (`principal` and `diag` are one operation).
    pub names: &'static [&'static str],
    /// How it is called, for the docs and messages: `solve(eqs, [x, y, …])`.
    pub signature: &'static str,
    /// What it does, one or two sentences (Markdown).
    pub doc: &'static str,
    /// The evaluation.
    pub eval: fn(&Call<'_, '_>) -> R<Value>,
}

/// The operations that take an operating point (`name = value`
/// arguments) at which an angle given a multiple of π/2 is shifted, so
/// that their result is in the angle's deviation from it
/// (`derivation::operating::shifted_angles`).
pub(crate) static AT_OPERATING_POINT: &[&Op] = &[&kane::KANE, &linearize::LINEARIZE];

/// Whether `func` names one of [`AT_OPERATING_POINT`].
pub(crate) fn takes_operating_point(func: &str) -> bool {
    AT_OPERATING_POINT.iter().any(|op| op.names.contains(&func))
}

/// Every operation, in the order of the docs table.
pub(crate) static OPS: &[&Op] = &[
    &trig::SIN_COS,
    &dt::DT,
    &dt::DT_REL,
    &vector::CROSS,
    &vector::DOT,
    &angvel::ANGVEL,
    &matrix::INERTIA,
    &matrix::PRINCIPAL,
    &matrix::TRANSPOSE,
    &express::EXPRESS,
    &subst::SUBST,
    &linearize::LINEARIZE,
    &state_space::STATE_MATRIX,
    &state_space::INPUT_MATRIX,
    &state_space::STATE_MASS,
    &coeff::COEFF,
    &coeff::JACOBIAN,
    &partial::PARTIAL,
    &lagrange::LAGRANGE,
    &in_speeds::IN_SPEEDS,
    &position::POSITION,
    &velocity::VELOCITY,
    &velocity::ROLLING,
    &contact::CONTACT_VELOCITY,
    &contact::ROLLING_CONSTRAINTS,
    &contact::CONTACT_HEIGHT,
    &contact::CONTACT_TANGENT,
    &contact::CONTACT_CONSTRAINTS,
    &kane::KANE,
    &list::LIST,
    &solve::SOLVE,
    &mass_matrix::MASS_MATRIX,
    &mass_matrix::FORCING,
    &sign::SIGN,
];

/// The operation called `name`.
pub(crate) fn find(name: &str) -> Option<&'static Op> {
    OPS.iter().copied().find(|op| op.names.contains(&name))
}

/// Every function name, for the "unknown function" message.
pub(crate) fn names() -> String {
    OPS.iter()
        .flat_map(|op| op.names.iter().copied())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `(signature, doc)` of every operation, in the order of the docs table.
pub fn catalogue() -> Vec<(&'static str, &'static str)> {
    OPS.iter().map(|op| (op.signature, op.doc)).collect()
}

/// The function table of `docs/derivation-format.md`, as Markdown rows.
pub fn docs_table() -> String {
    let mut s = String::from("| function | meaning |\n|---|---|\n");
    for (sig, doc) in catalogue() {
        s.push_str(&format!("| `{}` | {} |\n", sig.replace('|', "\\|"), doc));
    }
    s
}

/// A call being evaluated: the function name, its arguments and where
/// they are in the file.
pub(crate) struct Call<'c, 'a> {
    pub cx: &'c Context<'a>,
    pub func: &'c str,
    pub args: &'c [Ast],
    /// Byte offset of the expression string in the file.
    pub base: usize,
    /// The span of the whole call.
    pub span: Span,
}

impl Call<'_, '_> {
    /// An error at `span` (inside the expression string).
    pub fn err<T>(&self, span: Span, msg: impl Into<String>) -> R<T> {
        Err(self.cx.at(self.base, span, msg))
    }

    /// Checks the number of arguments.
    pub fn arity(&self, n: usize) -> R<()> {
        if self.args.len() == n {
            Ok(())
        } else {
            self.err(
                self.span,
                format!(
                    "`{}` takes {n} argument{}, found {}",
                    self.func,
                    if n == 1 { "" } else { "s" },
                    self.args.len()
                ),
            )
        }
    }

    /// Checks the number of arguments is in `lo..=hi`.
    pub fn arity_between(&self, lo: usize, hi: usize) -> R<()> {
        if (lo..=hi).contains(&self.args.len()) {
            Ok(())
        } else {
            self.err(
                self.span,
                format!(
                    "`{}` takes {lo} to {hi} arguments, found {}",
                    self.func,
                    self.args.len()
                ),
            )
        }
    }

    /// Argument `i`, evaluated.
    pub fn value(&self, i: usize) -> R<Value> {
        self.cx.eval(&self.args[i], self.base)
    }

    /// Argument `i`, which must be a scalar.
    pub fn scalar(&self, i: usize) -> R<Poly> {
        self.cx.scalar(&self.args[i], self.base)
    }

    /// Argument `i`, which must be a vector.
    pub fn vector(&self, i: usize) -> R<(Vec3, String)> {
        self.cx.vector(&self.args[i], self.base)
    }

    /// Argument `i`, which must be a frame name; its index.
    pub fn frame(&self, i: usize) -> R<usize> {
        self.cx.frame_arg(&self.args[i], self.base)
    }

    /// Argument `i`, which must be a symbol (with primes).
    pub fn symbol(&self, i: usize) -> R<Atom> {
        self.cx.symbol_arg(&self.args[i], self.base)
    }

    /// Argument `i`: one symbol, or symbols in brackets `[x, y, …]`;
    /// whether it was a bracket list.
    pub fn symbols(&self, i: usize) -> R<(Vec<Atom>, bool)> {
        let a = &self.args[i];
        match &a.kind {
            AstKind::Vector { items, frame: None } if !items.is_empty() => {
                let mut out = Vec::with_capacity(items.len());
                for it in items {
                    let s = self.cx.symbol_arg(it, self.base)?;
                    if out.contains(&s) {
                        return self.err(it.span, format!("`{s}` is listed twice"));
                    }
                    out.push(s);
                }
                Ok((out, true))
            }
            AstKind::Name { .. } => Ok((vec![self.symbol(i)?], false)),
            _ => self.err(
                a.span,
                "expected a symbol or symbols in brackets, such as theta'' or [phi'', theta'', psi'']",
            ),
        }
    }
}

/// The coefficient of `a` (to the first power) in `p`.
pub(crate) fn coefficient(p: &Poly, a: Atom) -> Poly {
    Poly::from_terms(
        p.terms()
            .iter()
            .filter(|(m, _)| m.exponent(a) == 1)
            .map(|(m, c)| (m.without(a, 1), c.clone())),
    )
}
