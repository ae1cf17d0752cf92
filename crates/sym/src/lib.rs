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
//!
//! ## Public surface
//!
//! What a user crate needs, and nothing it could come to depend on by
//! accident (`examples/course-tests`, `hdot-num`, `hdot-sim` and the CLI
//! use no more):
//!
//! * running a derivation: [`derivation`] (load, steps, values,
//!   expectations, declared physics), [`course`] (a lecturer's
//!   expectations), [`chain`] (the chained derivations);
//! * the values: [`Poly`], [`Monomial`], [`Atom`], [`AtomKind`],
//!   [`Rational`], [`Symbols`], [`Decl`], [`Vec3`], [`Mat3`], [`Frame`],
//!   [`Expr`] and [`Node`], and [`parse`] for formulas as written;
//! * showing them: [`present`], [`print`](mod@print), [`render`],
//!   [`document`], [`notes`], [`label`], [`prose`], [`escape`] (one
//!   escaping function per output language), [`limits`] and [`work`]
//!   (the bounds and counters of presentation), [`textfile`] (reading a
//!   file with located encoding errors).
//!
//! The algebra behind the values — differentiation in time (`diff`),
//! partial derivatives (`partial`), substitution (`subst`), the rational
//! numbers' arithmetic (`rational`) and frames' kinematics (`frame`) — is
//! internal: it is reached through the methods of [`Poly`], [`Vec3`] and
//! [`Frame`] and through the derivation language, so it can change without
//! breaking a user crate.

pub mod angle_sum;
pub mod atom;
pub mod chain;
pub mod course;
pub mod derivation;
pub(crate) mod diff;
pub mod document;
pub mod escape;
pub mod expr;
pub(crate) mod frame;
pub mod label;
pub mod limits;
pub mod notes;
pub mod parse;
pub(crate) mod partial;
pub mod poly;
pub mod present;
pub mod print;
pub mod prose;
pub(crate) mod rational;
pub mod render;
pub(crate) mod subst;
pub mod symbols;
pub mod textfile;
pub mod vector;
pub mod work;

pub use atom::{Atom, AtomKind};
pub use expr::{Expr, Node};
pub use frame::Frame;
pub use poly::{Monomial, Poly};
pub use rational::Rational;
pub use symbols::{Decl, Symbols};
pub use vector::{Mat3, Vec3};
