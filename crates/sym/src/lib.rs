//! # hdot-sym: the symbolic core of hdot
//!
//! This crate owns everything that is exact: rational numbers, atoms,
//! the canonical polynomial form, time derivatives, substitution, the
//! printers, vectors and tensors of expressions, reference frames, and the
//! derivation engine that runs a derivation file and checks its
//! expectations.
//!
//! It does **not** own numbers in floating point (the `hdot-num` crate
//! evaluates derived results on discretised bodies), motion in time
//! (`hdot-sim`), or the command line (`hdot`). The cut follows the
//! dependency graph: the symbolic core needs no linear algebra library
//! and no I/O beyond reading a derivation file, so it builds in seconds and
//! can be embedded anywhere; the numeric crates depend on it, never the
//! other way round.
//!
//! ## The path of data
//!
//! derivation file (TOML) → [`derivation::load`] (parses, resolves names,
//! reports errors at file:line:column, evaluates the steps on canonical
//! [`Poly`] values, checks expectations) →
//! [`present`] (textbook form as an [`Expr`] tree) → [`print`](mod@print) / [`render`]
//! (Unicode, LaTeX, Markdown, SymPy, JSON).
//!
//! ## Design
//!
//! * Atoms are interned `u32` handles ([`Atom`]); time derivatives are
//!   atoms of their own, so no unevaluated derivative node exists.
//! * Every value is kept in the canonical form [`Poly`]: sorted terms,
//!   exact rational coefficients, `sin²` rewritten as `1 − cos²`. Equality
//!   of expressions is `==` on this form.
//! * [`Expr`] is a flat, children-first node store used for the written
//!   shape of expressions (parser input, printer output).

pub mod atom;
pub mod chain;
pub mod course;
pub mod derivation;
pub mod diff;
pub mod document;
pub mod escape;
pub mod expr;
pub mod frame;
pub mod label;
pub mod limits;
pub mod notes;
pub mod parse;
pub mod partial;
pub mod poly;
pub mod present;
pub mod print;
pub mod prose;
pub mod rational;
pub mod render;
pub mod subst;
pub mod symbols;
pub mod textfile;
pub mod vector;
pub mod work;

pub use atom::{Atom, AtomKind};
pub use expr::{Expr, Node};
pub use poly::{Monomial, Poly};
pub use rational::Rational;
pub use symbols::{Decl, Symbols};
pub use vector::{Mat3, Vec3};
