//! The raw tables of a simulation scene as written, before they are
//! checked: what `toml` reads, each table's keys and nothing more.

use std::collections::BTreeMap;

use hdot_num::scene::{RawBodies, RawBody, RawCloud};
use serde::Deserialize;
use serde::de::IgnoredAny;
use toml::Spanned;

/// A scene's tables. `g`, `[[body]]` and `[[cloud]]` are the schema
/// every scene shares (`hdot_num::scene::RawBodies`, read by
/// `hdot_num::scene::bodies_from`): parsed here with the rest, so that the
/// text is parsed once; [`OwnTables`] skips them.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene<
    G = Spanned<Vec<f64>>,
    B = Vec<Spanned<RawBody>>,
    C = Vec<Spanned<RawCloud>>,
> {
    pub(super) name: String,
    #[serde(default)]
    pub(super) description: String,
    pub(super) kind: String,
    pub(super) t_end: f64,
    pub(super) g: Option<G>,
    pub(super) body: Option<B>,
    pub(super) cloud: Option<C>,
    pub(super) initial: Option<RawInitial>,
    pub(super) top: Option<RawTop>,
    pub(super) shaft: Option<RawShaft>,
    pub(super) motor: Option<RawMotor>,
    pub(super) derivation: Option<RawDerivation>,
    pub(super) constants: Option<BTreeMap<String, f64>>,
    pub(super) inputs: Option<BTreeMap<String, String>>,
}

/// The scene's own tables, the shared ones skipped: what is read when
/// the whole scene does not parse, so that an error of the scene's own
/// tables is reported as the scene's parse error and one of the shared
/// tables by the bodies reader (`hdot_num::scene::bodies`).
pub(super) type OwnTables = RawScene<IgnoredAny, IgnoredAny, IgnoredAny>;

impl RawScene {
    /// Takes the shared tables out, for `hdot_num::scene::bodies_from`.
    pub(super) fn shared(&mut self) -> RawBodies {
        RawBodies {
            g: self.g.take(),
            body: self.body.take().unwrap_or_default(),
            cloud: self.cloud.take().unwrap_or_default(),
        }
    }
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawInitial {
    pub(super) attitude: Option<[f64; 4]>,
    pub(super) euler_angles: Option<[f64; 3]>,
    pub(super) angular_momentum: Option<[f64; 3]>,
    pub(super) angular_velocity: Option<[f64; 3]>,
    pub(super) steady_precession: Option<RawSteady>,
    pub(super) angle: Option<f64>,
    pub(super) rate: Option<f64>,
    pub(super) coordinates: Option<BTreeMap<String, f64>>,
    pub(super) rates: Option<BTreeMap<String, f64>>,
    pub(super) speeds: Option<BTreeMap<String, f64>>,
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSteady {
    pub(super) theta: f64,
    pub(super) spin: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTop {
    pub(super) fixed_point: Option<[f64; 3]>,
    // Former keys, refused with the new ones named.
    pub(super) distance: Option<IgnoredAny>,
    pub(super) g: Option<IgnoredAny>,
    pub(super) mass: Option<IgnoredAny>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShaft {
    pub(super) bearings: [f64; 2],
    #[serde(default)]
    pub(super) friction: f64,
    // Former keys, refused with the new ones named.
    pub(super) rotor_moment: Option<IgnoredAny>,
    pub(super) masses: Option<IgnoredAny>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMotor {
    pub(super) stall_torque: f64,
    pub(super) no_load_speed: Option<f64>,
}

/// The `[derivation]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDerivation {
    pub(super) file: String,
    pub(super) accelerations: Option<String>,
    pub(super) rates: Option<String>,
    pub(super) dependent: Option<String>,
    pub(super) mass_matrix: Option<String>,
    pub(super) forcing: Option<String>,
    pub(super) coordinates: Option<Vec<String>>,
    #[serde(default)]
    pub(super) conserved: Vec<String>,
    pub(super) frame: Option<String>,
    /// Steps f(q) = 0 (configuration constraints) of a first-order model.
    pub(super) holonomic: Option<Vec<String>>,
    /// Their dependent coordinates, one per constraint.
    pub(super) dependent_coordinates: Option<Vec<String>>,
    /// Whether to project onto f = 0 after each step (default true).
    pub(super) project: Option<bool>,
    /// A multiplier form's constraint matrix A_c (A_c u = 0).
    pub(super) constraint_matrix: Option<String>,
    /// Its bias b (A_c u̇ + b = 0).
    pub(super) constraint_bias: Option<String>,
    /// The speeds solved from A_c u = 0, one per constraint.
    pub(super) dependent_speeds: Option<Vec<String>>,
}
