//! Tests of hdot-sym, one module per concern:
//!
//! - `strategies`: the named proptest strategies (random expression trees);
//! - `algebra`: laws of the algebra that hold for every input (proptest);
//! - `identities`: one-line `input => expected` identities;
//! - `presentation`: presented forms expand back to the derived values;
//! - `snapshots`: every derivation file in every output format (insta);
//! - `textbook`: printed forms a textbook would use, on files written for
//!   them (`textbook/*.toml`, insta);
//! - `broken`: broken derivation files, each asserting its error's location;
//! - `newcomer`: a new user's multibody findings, on files written for them;
//! - `subst`: substitution in a derivation, angles set to 0 among them;
//! - `work_budget`: deterministic work of reference workloads against the
//!   committed budget (`work_budget.toml`).

mod algebra;
mod attitude;
mod broken;
mod chain;
mod contact;
mod equations_of_motion;
mod identities;
mod injection;
mod joints;
mod kane;
mod labels;
mod laurent;
mod lecturer;
mod linearize;
mod newcomer;
mod notes;
mod presentation;
mod snapshots;
mod speeds;
mod strategies;
mod subst;
mod textbook;
mod work_budget;
