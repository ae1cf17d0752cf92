//! Scenes of `kind = "derived"`: the equations of motion a derivation file
//! derived, with values for its constants, the initial coordinates and
//! rates, and applied inputs as functions of t (format in
//! `docs/simulation.md`, "Derived scenes").
//!
//! ```toml
//! name = "heavy top, derived in Eulerian angles"
//! kind = "derived"
//! t_end = 5.0
//! [derivation]
//! file = "heavy-top"                 # a bundled derivation's name, or a path (with / or .toml) from this scene's folder
//! accelerations = "accelerations"    # a step solved for [q1'', q2'', …]; or:
//! # mass_matrix = "mass_matrix", forcing = "forcing", coordinates = ["phi", "theta", "psi"]
//! frame = "R"                        # the body frame whose attitude and ω are reported
//! [constants]
//! I = 0.02
//! Ip = 0.05
//! [initial]
//! coordinates = { phi = 0.0, theta = 0.5, psi = 0.0 }
//! rates = { phi = 0.0, theta = 0.0, psi = 60.0 }
//! [inputs]                           # time symbols given as functions of t
//! M_a = "0.1*sin(2*t)"
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use serde::Deserialize;

use crate::SimError;
use crate::models::derived::{DerivedModel, DerivedSpec, EquationsSpec, TimeFunction};

/// The `[derivation]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDerivation {
    file: String,
    accelerations: Option<String>,
    mass_matrix: Option<String>,
    forcing: Option<String>,
    coordinates: Option<Vec<String>>,
    #[serde(default)]
    conserved: Vec<String>,
    frame: Option<String>,
}

/// The `[initial]` values of a derived scene.
#[derive(Debug, Default, Clone)]
pub(super) struct RawStart {
    pub coordinates: BTreeMap<String, f64>,
    pub rates: BTreeMap<String, f64>,
}

/// Finds a derivation a scene names: `Ok((shown path, text))`.
pub type Resolve<'a> = &'a dyn Fn(&str) -> Result<(PathBuf, String), String>;

/// The default resolver: a `file` with a `/` or ending in `.toml` is a path
/// from the scene's folder; a bare name is `derivations/NAME.toml` in the
/// scene's folder or any folder above it.
pub fn resolve_near(scene: &Path, name: &str) -> Result<(PathBuf, String), String> {
    let dir = scene.parent().unwrap_or(Path::new("."));
    let candidates: Vec<PathBuf> = if name.contains('/') || name.ends_with(".toml") {
        vec![dir.join(name)]
    } else {
        dir.ancestors()
            .map(|a| a.join("derivations").join(format!("{name}.toml")))
            .collect()
    };
    for c in &candidates {
        if c.is_file() {
            let text = std::fs::read_to_string(c)
                .map_err(|e| format!("cannot read {}: {e}", c.display()))?;
            return Ok((c.clone(), text));
        }
    }
    Err(if name.contains('/') || name.ends_with(".toml") {
        format!("no derivation file {}", dir.join(name).display())
    } else {
        format!("no derivation `{name}` in a `derivations` folder at or above the scene's folder")
    })
}

/// A validated derived scene.
#[derive(Debug, Clone)]
pub struct DerivedScene {
    /// The derivation file the equations come from.
    pub derivation: PathBuf,
    /// The compiled equations.
    pub model: Rc<DerivedModel>,
    /// What the scene asked for (constants, inputs, steps).
    pub spec: DerivedSpec,
    /// The initial state `(q, q̇)`.
    pub y0: Vec<f64>,
    /// The frame whose attitude and angular velocity are reported.
    pub frame: Option<String>,
}

impl DerivedScene {
    /// The state's component names: each coordinate, then each rate (`theta'`).
    pub fn state_names(&self) -> Vec<String> {
        let q = self.model.coordinates();
        q.iter()
            .map(|c| c.name().to_string())
            .chain(q.iter().map(|c| format!("{}'", c.name())))
            .collect()
    }
}

pub(super) fn parse(
    raw: Option<RawDerivation>,
    constants: BTreeMap<String, f64>,
    inputs: BTreeMap<String, String>,
    start: RawStart,
    file: &Path,
    resolve: Resolve<'_>,
) -> Result<DerivedScene, SimError> {
    let bad = |field: &str, message: String| SimError::BadField {
        file: file.to_path_buf(),
        field: field.to_string(),
        message,
    };
    let raw = raw.ok_or_else(|| {
        bad(
            "derivation",
            "missing table [derivation] (file = \"…\", and accelerations = \"…\" or mass_matrix/forcing/coordinates)".into(),
        )
    })?;
    let equations = match (
        raw.accelerations,
        raw.mass_matrix,
        raw.forcing,
        raw.coordinates,
    ) {
        (Some(step), None, None, None) => EquationsSpec::Explicit { step },
        (None, Some(mass_matrix), Some(forcing), Some(coordinates)) => EquationsSpec::MassMatrix {
            mass_matrix,
            forcing,
            coordinates,
        },
        _ => {
            return Err(bad(
                "derivation",
                "give either `accelerations` (a step solved for the accelerations) or all of \
                 `mass_matrix`, `forcing` and `coordinates`"
                    .into(),
            ));
        }
    };
    for (k, v) in &constants {
        if !v.is_finite() {
            return Err(bad(
                &format!("constants.{k}"),
                format!("must be finite, got {v}"),
            ));
        }
    }
    let constants_for_inputs = constants.clone();
    let inputs = inputs
        .into_iter()
        .map(|(k, text)| {
            TimeFunction::parse(&text, &constants_for_inputs)
                .map(|f| (k.clone(), f))
                .map_err(|e| bad(&format!("inputs.{k}"), e))
        })
        .collect::<Result<BTreeMap<_, _>, _>>()?;
    let (path, text) = resolve(&raw.file).map_err(|e| bad("derivation.file", e))?;
    let d = hdot_sym::derivation::load_str(&path.display().to_string(), &text)
        .map_err(|e| bad("derivation.file", e.to_string()))?;
    let spec = DerivedSpec {
        equations,
        constants,
        inputs,
        conserved: raw.conserved,
    };
    let model = DerivedModel::new(&d, &spec)?;
    let mut values = BTreeMap::new();
    for (k, v) in start.coordinates {
        values.insert(k, v);
    }
    for (k, v) in start.rates {
        values.insert(format!("{k}'"), v);
    }
    let y0 = model.initial_state(&values)?;
    if let Some(f) = &raw.frame
        && model.attitude(f, 0.0, &y0).is_none()
    {
        return Err(bad(
            "derivation.frame",
            format!(
                "`{f}` is not a frame of {} whose attitude is a function of the coordinates",
                path.display()
            ),
        ));
    }
    if let Some(why) = model.singularity(0.0, &y0) {
        return Err(bad(
            "initial",
            format!("the equations break down at the initial state: {why}"),
        ));
    }
    Ok(DerivedScene {
        derivation: path,
        model: Rc::new(model),
        spec,
        y0,
        frame: raw.frame,
    })
}
