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
//! # or, first order in generalized speeds (state (q, u), [initial] speeds):
//! # rates = "rates" (a step solved for [u1', …]), or mass_matrix/forcing in [u1', …],
//! # and dependent = "dependent" (a step solved for the dependent speeds)
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
//!
//! Instead of numbers for a body's mass, mass centre and moments, a
//! derived scene may give the body itself as `[[body]]` tables (the schema
//! of every scene, `docs/scenes.md`), written in the axes of the
//! derivation body's frame with the origin at its reference point; `of =
//! "top"` names the derivation body a table makes up (not needed when the
//! derivation declares one). The symbols of the derivation's declarations
//! (`mass = "m"`, `mass_centre = "[0, 0, l] in R"`, `inertia =
//! "principal(Ip, Ip, I)"`) are bound from the tables' mass properties
//! ([`hdot_num::bind::bind_bodies`]), after checking that the body has
//! the declared symmetry. The scene's gravity vector `g` binds the symbols
//! of the derivation's `gravity` the same way.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use hdot_num::scene::{Bodies, RawBodies, bodies_from};
use hdot_sym::derivation::Derivation;
use hdot_sym::symbols::Decl;

use super::bind::{bind_scene_bodies, check_gravity};
use super::raw::{RawDerivation, RawInitial};
use super::resolve::Resolve;
use super::text::{line_of_after, line_of_field};
use crate::SimError;
use crate::systems::derived::{
    DerivedModel, DerivedSpec, EquationsSpec, HolonomicSpec, MultiplierSpec, NewtonFailure,
    SpeedRates, TimeFunction,
};

/// The `[initial]` values of a derived scene.
#[derive(Debug, Default, Clone)]
struct RawStart {
    coordinates: BTreeMap<String, f64>,
    rates: BTreeMap<String, f64>,
    speeds: BTreeMap<String, f64>,
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
    /// The initial state `(q, q̇)`, or `(q, u)` for a first-order model.
    pub y0: Vec<f64>,
    /// The frame whose attitude and angular velocity are reported.
    pub frame: Option<String>,
    /// The derivation's declared bodies, each with the frame fixed in it
    /// followed by that frame's ancestors (what a drawing of the scene's
    /// `[[body]]` groups turns with: the first whose attitude is a
    /// function of the state).
    pub body_frames: Vec<(String, Vec<String>)>,
}

impl DerivedScene {
    /// The state's component names: each coordinate, then each rate
    /// (`theta'`) or, in a first-order model, each speed (`u_1`).
    pub fn state_names(&self) -> Vec<String> {
        self.model.state_names()
    }
}

/// The tables of a derived scene, and whether each table of the built-in
/// kinds (`[top]`, `[shaft]`, `[motor]`) is given (refused here).
pub(super) struct Tables {
    /// `[derivation]`.
    pub derivation: Option<RawDerivation>,
    /// `[constants]`.
    pub constants: BTreeMap<String, f64>,
    /// `[inputs]`.
    pub inputs: BTreeMap<String, String>,
    /// The built-in kinds' tables, and whether each is given.
    pub builtin: [(&'static str, bool); 3],
    /// `g`, `[[body]]` and `[[cloud]]`, as parsed with the rest.
    pub shared: RawBodies,
}

/// A derived scene from its tables, its `[initial]` table, and the shared
/// `[[body]]` tables (parsed with the rest of `text`); and those tables as
/// read (the scene keeps them).
pub(super) fn read(
    tables: Tables,
    initial: RawInitial,
    file: &Path,
    text: &str,
    resolve: Resolve<'_>,
) -> Result<(DerivedScene, Bodies), SimError> {
    let builtin = [
        ("initial.attitude", initial.attitude.is_some()),
        ("initial.euler_angles", initial.euler_angles.is_some()),
        (
            "initial.angular_momentum",
            initial.angular_momentum.is_some(),
        ),
        (
            "initial.angular_velocity",
            initial.angular_velocity.is_some(),
        ),
        (
            "initial.steady_precession",
            initial.steady_precession.is_some(),
        ),
        ("initial.angle", initial.angle.is_some()),
        ("initial.rate", initial.rate.is_some()),
    ];
    if let Some((field, _)) = tables.builtin.iter().chain(&builtin).find(|(_, set)| *set) {
        return Err(SimError::BadField {
            file: file.to_path_buf(),
            field: field.to_string(),
            message:
                "a derived scene gives its state as `initial.coordinates` and `initial.rates`, \
                      its bodies as `[[body]]` tables (or their masses and moments under \
                      `[constants]`) and g under `[constants]`"
                    .into(),
        });
    }
    let start = RawStart {
        coordinates: initial.coordinates.unwrap_or_default(),
        rates: initial.rates.unwrap_or_default(),
        speeds: initial.speeds.unwrap_or_default(),
    };
    let bodies = bodies_from(file, text, tables.shared)?;
    let scene = parse(
        tables.derivation,
        tables.constants,
        &bodies,
        tables.inputs,
        start,
        (file, text),
        resolve,
    )?;
    Ok((scene, bodies))
}

/// A derived model's error traced to a field of the scene, as that
/// field's error at its line (the derivation and its step follow in the
/// message): the scene is what the user edits.
fn located(file: &Path, text: &str, e: SimError) -> SimError {
    match e {
        SimError::DerivedField { field, message } => {
            // A constant with no value has no line of its own: the
            // `[constants]` table, else the line naming the derivation.
            let line = line_of_field(text, &field).or_else(|| {
                (field == "constants")
                    .then(|| line_of_field(text, "derivation.file"))
                    .flatten()
            });
            SimError::BadField {
                file: file.to_path_buf(),
                field,
                message: match line {
                    Some(n) => format!("line {n}: {message}"),
                    None => message,
                },
            }
        }
        e => e,
    }
}

fn parse(
    raw: Option<RawDerivation>,
    mut constants: BTreeMap<String, f64>,
    bodies: &Bodies,
    inputs: BTreeMap<String, String>,
    start: RawStart,
    (file, scene_text): (&Path, &str),
    resolve: Resolve<'_>,
) -> Result<DerivedScene, SimError> {
    // (Scene::parse_with adds the line of the field.)
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
    let holonomic_raw = (
        raw.holonomic.clone(),
        raw.dependent_coordinates.clone(),
        raw.project,
    );
    let mut equations = match (
        raw.accelerations,
        raw.rates,
        raw.mass_matrix,
        raw.forcing,
        raw.coordinates,
    ) {
        (Some(step), None, None, None, None) => EquationsSpec::Explicit { step },
        (None, Some(step), None, None, None) => EquationsSpec::FirstOrder {
            rates: SpeedRates::Explicit { step },
            dependent: raw.dependent.clone(),
            holonomic: None,
        },
        (None, None, Some(mass_matrix), Some(forcing), coordinates) => EquationsSpec::MassMatrix {
            mass_matrix,
            forcing,
            coordinates: coordinates.unwrap_or_default(),
        },
        _ => {
            return Err(bad(
                "derivation",
                "give either `accelerations` (a step solved for the accelerations), `rates` (a step \
                 solved for the generalized speeds' rates) or `mass_matrix` and `forcing` (and, if \
                 the mass-matrix step does not list its unknowns, `coordinates`)"
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
    let (path, text) = resolve(&raw.file).map_err(|e| bad("derivation.file", e))?;
    let d = hdot_sym::derivation::load_str(&path.display().to_string(), &text)
        .map_err(|e| bad("derivation.file", e.to_string()))?;
    // A mass-matrix form in the speeds' rates ([u1', …]) is of first order.
    if let EquationsSpec::MassMatrix {
        mass_matrix,
        forcing,
        coordinates,
    } = &equations
        && coordinates.is_empty()
        && crate::systems::derived::in_speed_rates(&d, mass_matrix)
    {
        equations = EquationsSpec::FirstOrder {
            rates: SpeedRates::MassMatrix {
                mass_matrix: mass_matrix.clone(),
                forcing: forcing.clone(),
            },
            dependent: raw.dependent.clone(),
            holonomic: None,
        };
    }
    multiplier_form(
        (
            &raw.constraint_matrix,
            &raw.constraint_bias,
            &raw.dependent_speeds,
        ),
        &mut equations,
    )
    .map_err(|(f, m)| bad(f, m))?;
    if let EquationsSpec::MassMatrix {
        mass_matrix,
        coordinates,
        ..
    } = &mut equations
    {
        coordinates_of_step(&d, mass_matrix, coordinates)
            .map_err(|e| bad("derivation.coordinates", e))?;
    }
    let first_order = matches!(equations, EquationsSpec::FirstOrder { .. });
    if raw.dependent.is_some() && !first_order {
        return Err(bad(
            "derivation.dependent",
            "dependent speeds belong to a first-order model: name the speeds' rates with `rates` \
             (or a mass_matrix and forcing in [u1', …])"
                .into(),
        ));
    }
    let holonomic = holonomic_spec(&holonomic_raw, first_order).map_err(|(f, m)| bad(f, m))?;
    if let EquationsSpec::FirstOrder { holonomic: h, .. } = &mut equations {
        *h = holonomic;
    }
    let (given, wanted) = if first_order {
        (
            "initial.rates",
            "`initial.speeds` (the independent generalized speeds)",
        )
    } else {
        ("initial.speeds", "`initial.rates` (the coordinates' rates)")
    };
    if (first_order && !start.rates.is_empty()) || (!first_order && !start.speeds.is_empty()) {
        return Err(bad(
            given,
            format!("the state of these equations is given by `initial.coordinates` and {wanted}"),
        ));
    }
    let declared: Vec<&str> = d
        .symbols
        .names()
        .iter()
        .filter(|n| d.symbols.get(n) == Some(&Decl::Constant))
        .map(String::as_str)
        .collect();
    if let Some(k) = constants.keys().find(|k| !declared.contains(&k.as_str())) {
        return Err(bad(
            &format!("constants.{k}"),
            format!(
                "`{k}` is not a constant of {} (its constants: {})",
                path.display(),
                declared.join(", ")
            ),
        ));
    }
    let from_g = check_gravity(&d, &path, bodies, &constants, file)?;
    let bound = bind_scene_bodies(&d, &path, bodies, &constants, from_g.as_ref(), file)?;
    let from_bodies: Vec<String> = bound.keys().cloned().collect();
    constants.extend(bound);
    let constants_for_inputs = constants.clone();
    let inputs = inputs
        .into_iter()
        .map(|(k, text)| {
            let field = format!("inputs.{k}");
            let f =
                TimeFunction::parse(&text, &constants_for_inputs).map_err(|e| bad(&field, e))?;
            // An input the run would start from as NaN or infinity fails
            // the integration with no name: refused here, at its field.
            let start = f.eval(0.0);
            if !start.is_finite() {
                return Err(bad(
                    &field,
                    format!("`{text}` is {start} at t = 0: an input must be finite"),
                ));
            }
            Ok((k.clone(), f))
        })
        .collect::<Result<BTreeMap<_, _>, _>>()?;
    let spec = DerivedSpec {
        equations,
        constants,
        inputs,
        conserved: raw.conserved,
    };
    let model = DerivedModel::new(&d, &spec).map_err(|e| located(file, scene_text, e))?;
    check_inputs(&d, &path, &model, &spec, file, scene_text)?;
    if let Some((name, why)) = model.constant_singularity() {
        // The field that gave the constant its value: `[constants]`, or
        // the `[[body]]` tables or gravity vector that bound it.
        let field = if from_bodies.iter().any(|k| k == name) {
            "body".to_string()
        } else {
            format!("constants.{name}")
        };
        return Err(bad(&field, format!("{}: {why}", path.display())));
    }
    // A value that is not finite, at its own field and line (the model
    // would only say which component).
    for (table, given) in [
        ("coordinates", &start.coordinates),
        ("rates", &start.rates),
        ("speeds", &start.speeds),
    ] {
        if let Some((k, v)) = given.iter().find(|(_, v)| !v.is_finite()) {
            let line = line_of_after(scene_text, k, table)
                .or_else(|| line_of_field(scene_text, &format!("initial.{table}")));
            return Err(bad(
                &format!("initial.{table}.{k}"),
                format!(
                    "{}the initial value of `{k}` must be finite, got {v}",
                    line.map_or(String::new(), |n| format!("line {n}: "))
                ),
            ));
        }
    }
    let mut values = BTreeMap::new();
    for (k, v) in start.coordinates {
        values.insert(k, v);
    }
    for (k, v) in start.rates {
        values.insert(format!("{k}'"), v);
    }
    values.extend(start.speeds);
    let y0 = model.initial_state(&values).map_err(|e| match e {
        SimError::Derived { message } => bad("initial", message),
        e => e,
    })?;
    let y0 = solve_holonomic(&model, y0, (file, scene_text))?;
    let y0 = solve_dependent_speeds(&model, y0, (file, scene_text))?;
    if let Some(f) = &raw.frame
        && let Err(why) = model
            .attitude(f, 0.0, &y0)
            .and(model.angular_velocity(f, 0.0, &y0))
    {
        return Err(bad(
            "derivation.frame",
            format!("{} (frames of {})", why, path.display()),
        ));
    }
    if let Some(why) = model.singularity(0.0, &y0) {
        return Err(bad(
            "initial",
            format!("the equations break down at the initial state: {why}"),
        ));
    }
    if let Some(why) = model.unit_norm_refusal(&y0) {
        return Err(bad("initial.coordinates", why));
    }
    let body_frames = body_frames(&d);
    Ok(DerivedScene {
        derivation: path,
        model: Rc::new(model),
        spec,
        y0,
        frame: raw.frame,
        body_frames,
    })
}

/// A first-order mass-matrix form turned into a multiplier form when the
/// `[derivation]` table names a `constraint_matrix` (with its
/// `constraint_bias` and `dependent_speeds`), or the field and why not.
fn multiplier_form(
    (a, b, u): (&Option<String>, &Option<String>, &Option<Vec<String>>),
    equations: &mut EquationsSpec,
) -> Result<(), (&'static str, String)> {
    let (Some(a), Some(b), Some(u)) = (a, b, u) else {
        return match (a, b, u) {
            (None, None, None) => Ok(()),
            _ => Err((
                if a.is_none() {
                    "derivation.constraint_matrix"
                } else if b.is_none() {
                    "derivation.constraint_bias"
                } else {
                    "derivation.dependent_speeds"
                },
                "a multiplier form names all three of `constraint_matrix` (A_c), \
                 `constraint_bias` (b) and `dependent_speeds`"
                    .into(),
            )),
        };
    };
    let EquationsSpec::FirstOrder {
        rates: SpeedRates::MassMatrix {
            mass_matrix,
            forcing,
        },
        dependent: None,
        ..
    } = equations
    else {
        return Err((
            "derivation.constraint_matrix",
            "a multiplier form needs `mass_matrix` and `forcing` in the speeds' rates \
             (mass_matrix(eqs, [u1', …])) and no `dependent` step"
                .into(),
        ));
    };
    *equations = EquationsSpec::FirstOrder {
        rates: SpeedRates::Multiplier(MultiplierSpec {
            mass_matrix: mass_matrix.clone(),
            forcing: forcing.clone(),
            constraint_matrix: a.clone(),
            constraint_bias: b.clone(),
            dependent_speeds: u.clone(),
        }),
        dependent: None,
        holonomic: None,
    };
    Ok(())
}

/// The initial state with a multiplier form's dependent speeds solved
/// from its velocity constraints A_c u = 0 (unchanged without).
fn solve_dependent_speeds(
    model: &DerivedModel,
    mut y0: Vec<f64>,
    (file, text): (&Path, &str),
) -> Result<Vec<f64>, SimError> {
    if model.solve_dependent_speeds(0.0, &mut y0).is_some() {
        return Ok(y0);
    }
    let line = line_of_field(text, "derivation.dependent_speeds")
        .map_or(String::new(), |n| format!("line {n}: "));
    Err(SimError::BadField {
        file: file.to_path_buf(),
        field: "derivation.dependent_speeds".into(),
        message: format!(
            "{line}the velocity constraints cannot be solved for the dependent speeds {} at the \
             initial configuration: the constraint matrix's columns of these speeds are singular \
             there (choose other dependent speeds)",
            model.dependent_speeds().join(", ")
        ),
    })
}

/// The configuration constraints the `[derivation]` table names
/// (`holonomic`, `dependent_coordinates`, `project`), or the field and
/// why they are refused.
fn holonomic_spec(
    (holonomic, dependent, project): &(Option<Vec<String>>, Option<Vec<String>>, Option<bool>),
    first_order: bool,
) -> Result<Option<HolonomicSpec>, (&'static str, String)> {
    match (holonomic, dependent) {
        (None, None) if project.is_some() => Err((
            "derivation.project",
            "projects onto configuration constraints: name them with `holonomic` (their steps) \
             and `dependent_coordinates`"
                .into(),
        )),
        (None, None) => Ok(None),
        (Some(_), None) => Err((
            "derivation.holonomic",
            "configuration constraints need their dependent coordinates: \
             `dependent_coordinates = [\"q\", …]`, one per constraint"
                .into(),
        )),
        (None, Some(_)) => Err((
            "derivation.dependent_coordinates",
            "dependent coordinates belong to configuration constraints: name their steps with \
             `holonomic = [\"f\", …]`"
                .into(),
        )),
        (Some(_), Some(_)) if !first_order => Err((
            "derivation.holonomic",
            "configuration constraints are kept in a first-order model (state (q, u), its \
             dependent coordinates' rates from the constraints' rates): name the speeds' rates with \
             `rates` (or a mass_matrix and forcing in [u1', …])"
                .into(),
        )),
        (Some(steps), Some(dependent)) => Ok(Some(HolonomicSpec {
            steps: steps.clone(),
            dependent: dependent.clone(),
            project: project.unwrap_or(true),
        })),
    }
}

/// The initial state with its dependent coordinates solved from the
/// configuration constraints by Newton's method, from the scene's guess
/// (unchanged without constraints).
fn solve_holonomic(
    model: &DerivedModel,
    mut y0: Vec<f64>,
    (file, text): (&Path, &str),
) -> Result<Vec<f64>, SimError> {
    let Some((steps, dependent)) = model.holonomic() else {
        return Ok(y0);
    };
    let names = model.state_names();
    let guess = dependent
        .iter()
        .map(|q| {
            let v = names
                .iter()
                .position(|n| n == q)
                .map_or(f64::NAN, |i| y0[i]);
            format!("{q} = {v}")
        })
        .collect::<Vec<_>>()
        .join(", ");
    let field = format!("initial.coordinates.{}", dependent[0]);
    let line =
        line_of_field(text, "initial.coordinates").map_or(String::new(), |n| format!("line {n}: "));
    let steps = steps
        .iter()
        .map(|s| format!("`{s}`"))
        .collect::<Vec<_>>()
        .join(", ");
    let why = match model.solve_constraints(0.0, &mut y0, true) {
        Ok(_) => return rate_vanishes(model, y0, (file, text), &steps),
        Err(NewtonFailure::NoConvergence { residual }) => format!(
            "no solution near the initial guess ({guess}): Newton's method on the configuration \
             constraint(s) {steps} in {} did not converge (|f| = {residual:.3e} at its last \
             iterate); give a guess nearer a configuration that satisfies them",
            dependent.join(", ")
        ),
        Err(NewtonFailure::Singular { at }) => format!(
            "the configuration constraint(s) {steps} cannot be solved for {} from the initial guess \
             ({guess}): their Jacobian with respect to {} is singular at {} (choose other dependent \
             coordinates, or another guess)",
            dependent.join(", "),
            dependent.join(", "),
            dependent
                .iter()
                .zip(&at)
                .map(|(q, v)| format!("{q} = {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    Err(SimError::BadField {
        file: file.to_path_buf(),
        field,
        message: format!("{line}{why}"),
    })
}

/// The constraints' rate must vanish along the motion the equations
/// integrate: the dependent speeds (the step `dependent`) must come from
/// the constraints' rates ḟ = 0, or the dependent coordinates would be
/// integrated by a rate of their own and projection would fight the
/// motion. Checked at the initial configuration with the independent
/// speeds set to 1, 1.1, 1.2, … (any speeds must do).
fn rate_vanishes(
    model: &DerivedModel,
    y0: Vec<f64>,
    (file, text): (&Path, &str),
    steps: &str,
) -> Result<Vec<f64>, SimError> {
    let speeds: Vec<f64> = (0..model.speeds().len())
        .map(|k| 1.0 + 0.1 * k as f64)
        .collect();
    match model.constraint_rate(0.0, &y0, &speeds) {
        Some((rate, scale)) if rate > 1e-9 * scale => {
            let line = line_of_field(text, "derivation.dependent")
                .or_else(|| line_of_field(text, "derivation.holonomic"))
                .map_or(String::new(), |n| format!("line {n}: "));
            Err(SimError::BadField {
                file: file.to_path_buf(),
                field: "derivation.dependent".into(),
                message: format!(
                    "{line}the rate of the configuration constraint(s) {steps} does not vanish with \
                     the dependent speeds of these equations (|df/dt| = {rate:.3e} against terms of \
                     {scale:.3e} at the initial configuration, with the speeds {}): name as \
                     `dependent` a step that solves the constraints' rates for the dependent speeds, \
                     e.g. solve(list(in_speeds(dt(f)), …), [u…])",
                    model
                        .speeds()
                        .iter()
                        .zip(&speeds)
                        .map(|(u, v)| format!("{u} = {v}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            })
        }
        _ => Ok(y0),
    }
}

/// The derivation's declared bodies, each with the frame fixed in it
/// followed by that frame's ancestors.
fn body_frames(d: &Derivation) -> Vec<(String, Vec<String>)> {
    d.physics
        .bodies
        .iter()
        .map(|b| {
            let mut chain = vec![d.frames[b.frame].name.clone()];
            while let Some((parent, _)) = d
                .frames
                .iter()
                .find(|f| Some(&f.name) == chain.last())
                .and_then(|f| f.parent.as_ref())
                && chain.len() <= d.frames.len()
            {
                chain.push(parent.clone());
            }
            (b.name.clone(), chain)
        })
        .collect()
}

/// Each `[inputs]` name must be a time symbol of the derivation that is
/// not a coordinate of the equations (a coordinate's value comes from the
/// state; a name that is no time symbol would be ignored).
fn check_inputs(
    d: &Derivation,
    path: &Path,
    model: &DerivedModel,
    spec: &DerivedSpec,
    file: &Path,
    text: &str,
) -> Result<(), SimError> {
    let coordinates: Vec<&str> = model.coordinates().iter().map(|c| c.name()).collect();
    let applied: Vec<&str> = d
        .symbols
        .names()
        .iter()
        .filter(|n| d.symbols.get(n) == Some(&Decl::Time) && !coordinates.contains(&n.as_str()))
        .map(String::as_str)
        .collect();
    let time_symbols = if applied.is_empty() {
        "none".to_string()
    } else {
        applied.join(", ")
    };
    for k in spec.inputs.keys() {
        let why = if coordinates.contains(&k.as_str()) {
            format!(
                "`{k}` is a coordinate of the equations of {} (its value comes from the state, \
                 `[initial]` starts it); an input gives a time symbol that is not a coordinate \
                 as a function of t (those of this derivation: {time_symbols})",
                path.display()
            )
        } else if d.symbols.get(k) != Some(&Decl::Time) {
            format!(
                "`{k}` is not a time symbol of {} (its time symbols that are not \
                 coordinates: {time_symbols})",
                path.display()
            )
        } else {
            continue;
        };
        let field = format!("inputs.{k}");
        let message = match line_of_field(text, &field) {
            Some(n) => format!("line {n}: {why}"),
            None => why,
        };
        return Err(SimError::BadField {
            file: file.to_path_buf(),
            field,
            message,
        });
    }
    Ok(())
}

/// The mass-matrix form's coordinates: those the step lists
/// (`mass_matrix(eqs, [q1'', …])`) when the scene gives none; those given,
/// which must then be the step's in its order (M's columns are in that
/// order: another order would integrate other equations).
fn coordinates_of_step(d: &Derivation, step: &str, given: &mut Vec<String>) -> Result<(), String> {
    let listed = crate::systems::derived::step_coordinates(d, step);
    match (given.is_empty(), listed) {
        (true, Some(q)) => *given = q,
        (true, None) => {
            return Err(format!(
                "missing: step `{step}` of {} is not written mass_matrix(eqs, [q1'', …]), so give the \
                 coordinates in the order of its columns",
                d.path
            ));
        }
        (false, Some(q)) if q != *given => {
            return Err(format!(
                "[{}] is not the order of step `{step}`'s unknowns ({}): M's columns are in that \
                 order, so write coordinates = [{}] (or leave `coordinates` out)",
                given.join(", "),
                q.iter()
                    .map(|c| format!("{c}''"))
                    .collect::<Vec<_>>()
                    .join(", "),
                q.iter()
                    .map(|c| format!("\"{c}\""))
                    .collect::<Vec<_>>()
                    .join(", "),
            ));
        }
        _ => {}
    }
    Ok(())
}
