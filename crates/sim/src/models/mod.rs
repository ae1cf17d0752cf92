//! The models of the motion: one self-describing entry per file (a
//! [`ModelEntry`]), and the one registry [`MODELS`] the model choice, the
//! `--model` help, the docs table and the refusals are all made from.
//!
//! Adding a model is one new file here — a const [`Descriptor`] (name,
//! what it applies to and why, closed form or integrated) and an
//! implementation of [`ModelEntry`] for its behaviour — and one line in
//! [`MODELS`] (least exact first: the choice takes the first
//! closed form that covers a scene, else the first entry chosen to
//! integrate it).

mod body;
pub mod derived;
pub mod elliptic;
pub mod euler_angles;
pub mod fixed_axis;
pub mod precession_angle;
pub mod rigid_body;
pub mod steady_precession;

use std::str::FromStr;

pub use body::reference_state;

use crate::SimError;
pub use crate::model::{Descriptor, Model, ModelEntry};

/// Every model, least exact first: the one list of them.
pub static MODELS: &[&dyn ModelEntry] = &[
    &fixed_axis::FIXED_AXIS,
    &steady_precession::STEADY_PRECESSION,
    &elliptic::ELLIPTIC,
    &precession_angle::PRECESSION_ANGLE,
    &rigid_body::RIGID_BODY,
    &euler_angles::EULER_ANGLES,
    &derived::DERIVED,
];

impl Model {
    /// Every model of the registry, in its order.
    pub fn all() -> impl Iterator<Item = Model> {
        MODELS.iter().map(|e| Model(*e))
    }

    /// The model called `name`.
    pub fn named(name: &str) -> Option<Model> {
        Model::all().find(|m| m.name() == name)
    }
}

impl FromStr for Model {
    type Err = SimError;
    fn from_str(s: &str) -> Result<Self, SimError> {
        Model::named(s).ok_or_else(|| SimError::UnknownName {
            what: "model",
            name: s.to_string(),
            expected: names(),
        })
    }
}

/// Every model's name, comma-separated, in the registry's order.
pub fn names() -> String {
    Model::all().map(Model::name).collect::<Vec<_>>().join(", ")
}

/// The help of `hdot simulate --model`.
pub fn help() -> String {
    format!("Model: {}.", names())
}

/// The models table of `docs/simulation.md`, as Markdown rows (a test
/// keeps the document in step with the registry).
pub fn docs_table() -> String {
    let mut s = String::from(
        "| model | applies to | why it is chosen there | closed form | integrates |\n|---|---|---|---|---|\n",
    );
    for e in MODELS {
        let closed = if e.integrated() { "no" } else { "yes" };
        let integrates = if e.can_integrate() { "yes" } else { "no" };
        s.push_str(&format!(
            "| `{}` | {} | {} | {closed} | {integrates} |\n",
            e.name(),
            e.applies_to().replace('|', "\\|"),
            e.why().replace('|', "\\|"),
        ));
    }
    s
}
