//! The raw tables of a simulation scene as written, before they are
//! checked: what `toml` reads, each table's keys and nothing more.

use std::collections::BTreeMap;

use serde::Deserialize;
use serde::de::IgnoredAny;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) name: String,
    #[serde(default)]
    pub(super) description: String,
    pub(super) kind: String,
    pub(super) t_end: f64,
    // `g`, `[[body]]` and `[[cloud]]`: the schema every scene shares, read
    // by `hdot_num::scene::bodies`.
    #[allow(dead_code)]
    pub(super) g: Option<IgnoredAny>,
    #[allow(dead_code)]
    pub(super) body: Option<IgnoredAny>,
    #[allow(dead_code)]
    pub(super) cloud: Option<IgnoredAny>,
    pub(super) initial: Option<RawInitial>,
    pub(super) top: Option<RawTop>,
    pub(super) shaft: Option<RawShaft>,
    pub(super) motor: Option<RawMotor>,
    pub(super) derivation: Option<RawDerivation>,
    pub(super) constants: Option<BTreeMap<String, f64>>,
    pub(super) inputs: Option<BTreeMap<String, String>>,
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
