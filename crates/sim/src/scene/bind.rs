//! Binding the symbols a derivation declares for its bodies and its
//! gravity from a derived scene's `[[body]]` / `[[cloud]]` tables and its
//! `g` vector, after checking that each body has the declared symmetry.

use std::collections::BTreeMap;
use std::path::Path;

use hdot_num::bind::{MeasuredBody, bind_bodies};
use hdot_num::scene::{Bodies, Group};
use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::{Body, Symmetry};
use hdot_sym::poly::Poly;
use nalgebra::{Matrix3, Vector3};

use crate::SimError;

/// Relative tolerance of the symmetry a derivation body declares, checked
/// on the scene's body (that of the verifier's declared entries).
const SYMMETRY_TOL: f64 = 1e-9;

/// Binds the symbols of the derivation's `[[body]]` declarations from the
/// scene's `[[body]]` / `[[cloud]]` tables: each group of tables (`of`)
/// is one derivation body, written in its frame's axes with the origin at
/// its reference point; `gravity` is the symbol the scene's g bound
/// ([`check_gravity`]). Returns the constants bound, that symbol too.
pub(super) fn bind_scene_bodies(
    d: &Derivation,
    path: &Path,
    bodies: &Bodies,
    constants: &BTreeMap<String, f64>,
    gravity: Option<&(String, f64)>,
    file: &Path,
) -> Result<BTreeMap<String, f64>, SimError> {
    let groups = &bodies.groups;
    let declared = &d.physics.bodies;
    let bad = |g: &Group, message: String| SimError::BadField {
        file: file.to_path_buf(),
        field: g.field.clone(),
        message: format!("line {}: {message}", g.line),
    };
    let names = || {
        declared
            .iter()
            .map(|b| format!("`{}`", b.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut measured: Vec<Option<MeasuredBody>> = vec![None; declared.len()];
    let mut given_by: Vec<Option<&Group>> = vec![None; declared.len()];
    for g in groups {
        let k = match &g.of {
            Some(name) => declared
                .iter()
                .position(|b| &b.name == name)
                .ok_or_else(|| {
                    bad(
                        g,
                        format!(
                            "{} declares no body `{name}` (its bodies: {})",
                            path.display(),
                            if declared.is_empty() {
                                "none".into()
                            } else {
                                names()
                            }
                        ),
                    )
                })?,
            None if declared.len() == 1 => 0,
            None if declared.is_empty() => {
                return Err(bad(
                    g,
                    format!(
                        "{} declares no `[[body]]` whose symbols the tables could bind: give \
                         its parameters under `[constants]`",
                        path.display()
                    ),
                ));
            }
            None => {
                return Err(bad(
                    g,
                    format!(
                        "{} declares several bodies ({}): name the one these tables make up \
                         with `of = \"…\"`",
                        path.display(),
                        names()
                    ),
                ));
            }
        };
        let b = &declared[k];
        let props = g.body.mass_properties();
        // About the reference point (the tables' origin), or about G.
        let about_g = b.about_centre() || b.inertia_about_centre;
        let (centre, inertia) = if b.about_centre() {
            (Vector3::zeros(), *props.inertia_g.matrix())
        } else if about_g {
            (props.center, *props.inertia_g.matrix())
        } else {
            (
                props.center,
                *props.inertia_about(&Vector3::zeros()).matrix(),
            )
        };
        let m = MeasuredBody {
            mass: props.mass,
            centre,
            inertia,
        };
        check_symmetry(d, b, &m, about_g).map_err(|e| {
            bad(
                g,
                format!(
                    "the tables make up `{}` of {}, declared {e}",
                    b.name,
                    path.display()
                ),
            )
        })?;
        measured[k] = Some(m);
        given_by[k] = Some(g);
    }
    check_unbound(declared, &given_by, constants).map_err(|(b, missing)| {
        let first = given_by.iter().flatten().next().expect("a table was given");
        bad(
            first,
            format!(
                "the body `{b}` of {} has no `[[body]]` table (`of = \"{b}\"`) and its symbols \
                 {missing} are not under `[constants]`: give its tables, or its parameters as \
                 constants",
                path.display()
            ),
        )
    })?;
    // A symbol given under [constants] that a body's entry binds alone
    // (`mass = "m"`): given twice. A constant beside a bound symbol in one
    // entry (`z_B + r_R`) is what the entry binds the other from.
    for (k, b) in declared.iter().enumerate() {
        let Some(g) = given_by[k] else { continue };
        let alone = body_entries(b)
            .into_iter()
            .filter_map(|p| match p.atoms()[..] {
                [a] => Some(a),
                _ => None,
            });
        if let Some(a) = alone.into_iter().find(|a| constants.contains_key(a.name())) {
            return Err(SimError::BadField {
                file: file.to_path_buf(),
                field: format!("constants.{}", a.name()),
                message: format!(
                    "`{}` is also bound by the body `{}` ({} at line {}): give it once, under \
                     `[constants]` or by the body",
                    a.name(),
                    b.name,
                    g.field,
                    g.line
                ),
            });
        }
    }
    let mut given = constants.clone();
    given.extend(gravity.cloned());
    let mut bound = bind_bodies(d, &measured, bodies.g, &given).map_err(|e| {
        let message = format!("{}: {e}", path.display());
        match given_by.iter().flatten().next() {
            Some(g) => bad(g, message),
            None => SimError::BadField {
                file: file.to_path_buf(),
                field: "g".into(),
                message: format!("line {}: {message}", bodies.g_line),
            },
        }
    })?;
    bound.extend(gravity.cloned());
    Ok(bound)
}

/// The entries of a body's declaration: its mass, the components of its
/// mass centre, its inertia's entries.
fn body_entries(b: &Body) -> Vec<&Poly> {
    b.mass
        .iter()
        .chain(b.mass_centre.iter().flat_map(|c| c.0.iter()))
        .chain(b.inertia.0.iter().flatten())
        .collect()
}

/// The symbols of a body's declaration.
fn body_symbols(b: &Body) -> Vec<hdot_sym::atom::Atom> {
    body_entries(b).iter().flat_map(|p| p.atoms()).collect()
}

/// When the scene's tables bind some bodies (`given_by`), a body they do
/// not bind must have its symbols under `[constants]` (or bound by another
/// body's tables): `Err` names the first body left unbound and its missing
/// symbols.
fn check_unbound(
    declared: &[Body],
    given_by: &[Option<&Group>],
    constants: &BTreeMap<String, f64>,
) -> Result<(), (String, String)> {
    if given_by.iter().all(Option::is_none) {
        return Ok(());
    }
    let bound: Vec<String> = declared
        .iter()
        .zip(given_by)
        .filter(|(_, g)| g.is_some())
        .flat_map(|(b, _)| body_symbols(b))
        .map(|a| a.name().to_string())
        .collect();
    for (b, _) in declared.iter().zip(given_by).filter(|(_, g)| g.is_none()) {
        let mut missing: Vec<String> = body_symbols(b)
            .iter()
            .map(|a| a.name().to_string())
            .filter(|n| !constants.contains_key(n) && !bound.contains(n))
            .collect();
        missing.sort();
        missing.dedup();
        if !missing.is_empty() {
            return Err((b.name.clone(), missing.join(", ")));
        }
    }
    Ok(())
}

/// The scene's gravity vector `g` against the derivation's declaration
/// (`gravity = "[0, 0, -g] in N"`, or tilted,
/// `"[g*sin(beta), 0, -g*cos(beta)] in N"`): declared in N, the
/// components the file fixes (the zeros) met, a component that is one
/// symbol alone not given under `[constants]` too, and at most one of its
/// symbols left to bind — the others (the tilt) under `[constants]`. That
/// symbol is bound here from the component that fixes it best (the
/// largest coefficient at the constants' values: a tilt of 0 leaves
/// `g*sin(beta)` nothing to say), and every component is checked against
/// the scene's g. Returns the symbol and its value; every error is
/// located at the field `g` or the constant.
pub(super) fn check_gravity(
    d: &Derivation,
    path: &Path,
    bodies: &Bodies,
    constants: &BTreeMap<String, f64>,
    file: &Path,
) -> Result<Option<(String, f64)>, SimError> {
    let Some(g) = bodies.g else { return Ok(None) };
    let bad = |field: &str, message: String| SimError::BadField {
        file: file.to_path_buf(),
        field: field.to_string(),
        message,
    };
    let line = bodies.g_line;
    let Some((v, frame)) = &d.physics.gravity else {
        return Err(bad(
            "g",
            format!(
                "line {line}: {} declares no gravity (`gravity = \"[0, 0, -g] in N\"`), so no \
                 symbol of it stands for g",
                path.display()
            ),
        ));
    };
    let declared = format!(
        "[{}] in {frame}",
        v.0.iter()
            .map(|p| p.to_source())
            .collect::<Vec<_>>()
            .join(", ")
    );
    if frame != "N" {
        return Err(bad(
            "g",
            format!(
                "line {line}: {} declares gravity {declared}; a scene's g is in N's axes",
                path.display()
            ),
        ));
    }
    let scene_g = format!("[{}, {}, {}]", g.x, g.y, g.z);
    let mut unknown: Vec<&'static str> = Vec::new();
    for p in &v.0 {
        let atoms = p.atoms();
        if let [a] = atoms[..]
            && constants.contains_key(a.name())
        {
            return Err(bad(
                &format!("constants.{}", a.name()),
                format!(
                    "`{}` is also bound by the scene's g (line {line}, gravity {declared}): give it \
                     once, under `[constants]` or by g",
                    a.name()
                ),
            ));
        }
        for a in atoms {
            if !constants.contains_key(a.name()) && !unknown.contains(&a.name()) {
                unknown.push(a.name());
            }
        }
    }
    let symbols = v.0.iter().any(|p| !p.atoms().is_empty());
    if unknown.is_empty() && symbols {
        return Err(bad(
            "g",
            format!(
                "line {line}: {} declares gravity {declared}, whose symbols are all under \
                 `[constants]`, and the scene's g = {scene_g} would bind one of them again: give \
                 each once — leave g out, or leave the symbol for g's size out of `[constants]`",
                path.display()
            ),
        ));
    }
    if unknown.len() > 1 {
        let names = unknown.join(", ");
        return Err(bad(
            "g",
            format!(
                "line {line}: {} declares gravity {declared}, whose symbols {names} the scene's g = \
                 {scene_g} cannot all fix: give all of them but one under `[constants]` (a tilt, \
                 say `{} = 0.3`) and g along the direction they give, or leave g out and give them \
                 all under `[constants]`",
                path.display(),
                unknown[1]
            ),
        ));
    }
    let value = |name: &str| constants.get(name).copied().unwrap_or(f64::NAN);
    let eval = |p: &Poly, bound: Option<(&str, f64)>| {
        p.eval(&mut |a: Atom| {
            let x = |q: Atom| match bound {
                Some((n, v)) if n == q.name() => v,
                _ => value(q.name()),
            };
            match a.kind() {
                AtomKind::Sin(q) => x(q).sin(),
                AtomKind::Cos(q) => x(q).cos(),
                _ => x(a),
            }
        })
    };
    // The unknown from the component whose coefficient in it is largest.
    let bound = match unknown.first() {
        None => None,
        Some(&name) => {
            let u =
                v.0.iter()
                    .flat_map(|p| p.atoms())
                    .find(|a| a.name() == name);
            let u = u.expect("an atom of gravity");
            let linear = |p: &Poly| {
                !p.atoms().iter().any(|a| a.name() == name && *a != u)
                    && p.terms().iter().all(|(m, _)| m.exponent(u) <= 1)
            };
            let best = (0..3)
                .filter(|&k| linear(&v.0[k]))
                .map(|k| (k, eval(&v.0[k].partial(u), None)))
                .filter(|(_, c)| c.is_finite() && *c != 0.0)
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
            let Some((k, c)) = best else {
                return Err(bad(
                    "g",
                    format!(
                        "line {line}: {} declares gravity {declared}: no component is linear in \
                         `{name}` with a coefficient other than 0 at the constants' values, so the \
                         scene's g cannot fix it: give `{name}` under `[constants]` and leave g out",
                        path.display()
                    ),
                ));
            };
            let rest = eval(&v.0[k], Some((name, 0.0)));
            Some((name.to_string(), (g[k] - rest) / c))
        }
    };
    let at = bound.as_ref().map(|(n, x)| (n.as_str(), *x));
    let along: Vec<f64> = v.0.iter().map(|p| eval(p, at)).collect();
    let miss = (0..3).any(|k| {
        let d = (along[k] - g[k]).abs();
        d.is_nan() || d > 1e-9 * g.norm()
    });
    if miss {
        let fixed = bound
            .as_ref()
            .map(|(n, x)| format!(" (with {n} = {x} from it)"))
            .unwrap_or_default();
        return Err(bad(
            "g",
            format!(
                "line {line}: {} declares gravity {declared}: the scene's g = {scene_g}{fixed} must \
                 point along it, [{}, {}, {}] at the constants' values (space Z up: g = [0.0, 0.0, -9.81])",
                path.display(),
                along[0],
                along[1],
                along[2]
            ),
        ));
    }
    Ok(bound)
}

/// Whether the measured body has the symmetry `b` declares (about its
/// reference point, in its frame's axes): `Err` says what is declared and
/// what the body has.
fn check_symmetry(d: &Derivation, b: &Body, m: &MeasuredBody, about_g: bool) -> Result<(), String> {
    let frame = &d.frames[b.frame];
    let axes = &frame.axes;
    let i: &Matrix3<f64> = &m.inertia;
    let scale = i.trace();
    let extent = (scale / m.mass).sqrt() + m.centre.norm();
    let small = |x: f64, s: f64| x.abs() <= SYMMETRY_TOL * s;
    let product_zero = |r: usize, s: usize| small(i[(r, s)], scale);
    let (what, ok) = match b.symmetry {
        Symmetry::None => return Ok(()),
        Symmetry::Principal => (
            format!("with principal axes along {}'s axes", frame.name),
            product_zero(0, 1) && product_zero(0, 2) && product_zero(1, 2),
        ),
        Symmetry::Axisymmetric(k) => {
            let (p, q) = ((k + 1) % 3, (k + 2) % 3);
            (
                format!("axisymmetric about its {} axis", axes[k]),
                product_zero(0, 1)
                    && product_zero(0, 2)
                    && product_zero(1, 2)
                    && small(i[(p, p)] - i[(q, q)], scale)
                    && small(m.centre[p], extent)
                    && small(m.centre[q], extent),
            )
        }
        Symmetry::Plane(k) => {
            let (p, q) = ((k + 1) % 3, (k + 2) % 3);
            (
                format!(
                    "symmetric about its plane {}{}",
                    axes[p.min(q)],
                    axes[p.max(q)]
                ),
                product_zero(k, p) && product_zero(k, q) && small(m.centre[k], extent),
            )
        }
    };
    if ok {
        return Ok(());
    }
    let about = if about_g {
        "G".to_string()
    } else {
        format!("the reference point {}", b.point)
    };
    let declared = (0..3)
        .map(|r| {
            (0..3)
                .map(|s| b.inertia.0[r][s].to_source())
                .collect::<Vec<_>>()
                .join(", ")
        })
        .collect::<Vec<_>>()
        .join("; ");
    Err(format!(
        "{what} (inertia [{declared}]), but the body is not: about {about}, in {}'s axes, \
         inertia [{:.6e}, {:.6e}, {:.6e}; {:.6e}, {:.6e}, {:.6e}; {:.6e}, {:.6e}, {:.6e}], G at \
         [{:.6e}, {:.6e}, {:.6e}]",
        frame.name,
        i[(0, 0)],
        i[(0, 1)],
        i[(0, 2)],
        i[(1, 0)],
        i[(1, 1)],
        i[(1, 2)],
        i[(2, 0)],
        i[(2, 1)],
        i[(2, 2)],
        m.centre.x,
        m.centre.y,
        m.centre.z
    ))
}
