//! `hdot simulate --html`: the page of a run — the report, SVG plots of
//! the coordinates, ω and the conserved quantities' drift against time,
//! and a 3D view of the bodies moving on a `<canvas>`, drawn by the small
//! script `view.js` (embedded) from the scene's `[[body]]` tables, the
//! run's attitudes and, for a derived scene, where each body is
//! (`place.rs`: the view upright and framed).
//!
//! The page reads only what a run returns ([`hdot_sim::run::Report`], its
//! trajectory, the attitude of a derived scene's frames and the place of
//! its bodies) and the scene's bodies as the scene read them; its size is
//! bounded whatever the run's length (the plots are drawn at screen
//! resolution, the animation has [`super::motion::FRAMES`] frames).

use std::fmt::Write;

use hdot_num::nalgebra::Vector3;
use hdot_sim::run::Report;
use hdot_sim::scene::Scene;
use serde_json::{Value, json};

use super::motion::{Motion, Track};
use super::place::{self, Placed};
use super::shapes::{self, Shape, round};
use super::shell::{Shell, report_table};
use super::{PageError, plot};

/// The view's script, written in this project.
const VIEW_JS: &str = include_str!("view.js");

/// The page of `report`, a run of `scene` (whose `[[body]]` tables it
/// draws as the scene read them).
pub fn simulation_page(scene: &Scene, report: &Report) -> Result<String, PageError> {
    let motion = Motion::new(scene, report)?;
    let data = view_data(scene, &motion);
    // No `<` in a script element (`</script>` would end it, `<!--` would
    // change how it ends): JSON writes it `\u003c`, inside strings only.
    let data = data.to_string().replace('<', "\\u003c");
    let mut s = String::with_capacity(256 << 10);
    let _ = write!(
        s,
        "<section class=\"view\" aria-label=\"the motion in 3D\">\n<h2>The motion</h2>\n\
         <canvas id=\"view\" width=\"720\" height=\"480\"></canvas>\n\
         <div class=\"controls\"><button id=\"play\" type=\"button\">Pause</button>\
         <label>speed <select id=\"speed\"><option value=\"0.1\">×0.1</option>\
         <option value=\"0.25\">×0.25</option><option value=\"0.5\">×0.5</option>\
         <option value=\"1\" selected>×1</option><option value=\"2\">×2</option>\
         <option value=\"4\">×4</option></select></label>\
         <input id=\"scrub\" type=\"range\" min=\"0\" max=\"{}\" value=\"0\" aria-label=\"time\">\
         <output id=\"time\">t = 0 s</output></div>\n<p id=\"legend\" class=\"note\"></p>\n</section>\n",
        motion.frames.len() - 1
    );
    s.push_str("<section class=\"report\">\n<h2>Report</h2>\n");
    s.push_str(&report_table(&report.to_string()));
    s.push_str("</section>\n<section class=\"plots\">\n<h2>Against time</h2>\n");
    for p in &motion.plots {
        s.push_str(&plot::svg(p, &motion.t));
        s.push('\n');
    }
    s.push_str("</section>\n");
    let shell = Shell {
        title: &scene.name,
        command: "hdot simulate",
        description: &scene.description,
        detail: format!("{} · kind {}", scene.file.display(), scene.kind.name()),
    };
    let scripts = format!(
        "<script id=\"motion\" type=\"application/json\">{data}</script>\n<script>\n{VIEW_JS}</script>\n"
    );
    Ok(shell.page(&s, &scripts))
}

/// A rotation track as the page's data: 9 numbers (row-major) per frame.
fn rotations_json(track: &Track, frames: usize) -> (Value, Option<String>) {
    match &track.rotations {
        Ok(r) => (
            Value::from(
                r.iter()
                    .flat_map(|m| (0..3).flat_map(move |i| (0..3).map(move |j| round(m[(i, j)]))))
                    .collect::<Vec<_>>(),
            ),
            None,
        ),
        Err(why) => {
            let id = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
            (
                Value::from(id.repeat(frames)),
                Some(format!("drawn at rest: {why}")),
            )
        }
    }
}

/// One group of parts as drawn, before it becomes the page's data.
struct Drawn {
    frame: String,
    parts: Vec<Shape>,
    rot: Value,
    placed: Placed,
}

/// The groups a derived scene draws: each group of `[[body]]` tables
/// (`of`) turning with its derivation body's frame (or the nearest frame
/// above it whose attitude is known) and placed at the body's reference
/// point.
fn derived_groups(
    scene: &Scene,
    ds: &hdot_sim::scene::DerivedScene,
    motion: &Motion,
    notes: &mut Vec<String>,
) -> Vec<Drawn> {
    let frames = motion.frames.len();
    let mut out = vec![];
    for g in &scene.bodies.groups {
        let name =
            g.of.clone()
                .or_else(|| ds.model.bodies().next().map(str::to_owned));
        let chain = name
            .as_ref()
            .and_then(|n| ds.body_frames.iter().find(|(b, _)| b == n))
            .map(|(_, c)| c.clone())
            .or_else(|| ds.frame.clone().map(|f| vec![f]))
            .unwrap_or_default();
        let track = motion.frame_track(scene, &chain);
        if let (Some(first), Ok(_)) = (chain.first(), &track.rotations)
            && *first != track.frame
        {
            notes.push(format!(
                "{} turns with frame {} (the attitude of its own frame {first} is not a function \
                 of the coordinates).",
                g.of.as_deref().unwrap_or("The body"),
                track.frame
            ));
        }
        let positions = match &name {
            Some(n) => match motion.body_positions(scene, n) {
                Ok(p) => Some(p),
                Err(why) => {
                    notes.push(format!("{why}: {n} is drawn at the origin."));
                    None
                }
            },
            None => None,
        };
        let (rot, note) = rotations_json(&track, frames);
        notes.extend(note);
        let parts = shapes::shapes(&g.body, &Vector3::zeros());
        let reach = parts.iter().map(Shape::reach).fold(0.0, f64::max);
        out.push(Drawn {
            frame: track.frame,
            parts,
            rot,
            placed: Placed { positions, reach },
        });
    }
    if out.is_empty() {
        notes.push("the scene has no [[body]] table: nothing to draw".into());
    }
    out
}

/// What `view.js` draws: frame times, the groups of parts with their
/// rotations and places, the view's turn (up at the top), scale and
/// centre, gravity, and the top's axis or the free body's angular
/// momentum.
fn view_data(scene: &Scene, motion: &Motion) -> Value {
    let frames = motion.frames.len();
    let mut notes = vec![];
    let groups = match scene.derivation() {
        Some(ds) => derived_groups(scene, ds, motion, &mut notes),
        None => match (&scene.bodies.body, &motion.body) {
            (Some(body), Some(track)) => {
                let origin = scene.body_frame.map_or_else(Vector3::zeros, |f| f.origin);
                let parts = shapes::shapes(body, &origin);
                let reach = parts.iter().map(Shape::reach).fold(0.0, f64::max);
                let (rot, note) = rotations_json(track, frames);
                notes.extend(note);
                vec![Drawn {
                    frame: track.frame.clone(),
                    parts,
                    rot,
                    placed: Placed {
                        positions: None,
                        reach,
                    },
                }]
            }
            _ => vec![],
        },
    };
    let bearings = scene.shaft().map(|(shaft, _)| shaft.bearings);
    let extra = bearings.map_or(0.0, |b| b[0].abs().max(b[1].abs()));
    let placed: Vec<Placed> = groups.iter().map(|g| g.placed.clone()).collect();
    let (reach, centre) = place::framing(&placed, frames, extra);
    let reach = if reach.is_finite() && reach > 0.0 {
        reach
    } else {
        1.0
    };
    // A top's figure axis (body axis 3, through the pivot and G).
    let on_pivot = scene.rigid_body().is_some_and(|b| b.pivot.is_some());
    let axis = scene.body_frame.filter(|_| on_pivot).map(|f| {
        let a = f.axes * Vector3::z() * reach;
        [round(a.x), round(a.y), round(a.z)]
    });
    let g = place::gravity(scene);
    let momentum = motion.momentum.and_then(|h| {
        let n = h.norm();
        (n > 0.0 && n.is_finite()).then(|| [round(h.x / n), round(h.y / n), round(h.z / n)])
    });
    let groups: Vec<Value> = groups
        .into_iter()
        .map(|g| {
            json!({
                "frame": g.frame,
                "parts": g.parts.iter().map(Shape::to_json).collect::<Vec<_>>(),
                "rot": g.rot,
                "pos": g.placed.positions.as_deref().map(place::track_json),
            })
        })
        .collect();
    json!({
        "t": motion.frames.iter().map(|t| round(*t)).collect::<Vec<_>>(),
        "groups": groups,
        "scale": round(reach),
        "view": place::rotation_json(&place::upright(g.map(|g| -g))),
        "centre": centre.as_deref().map(place::track_json),
        "g": g.map(|g| [round(g.x), round(g.y), round(g.z)]),
        "axis": axis,
        "momentum": momentum,
        "bearings": bearings,
        "notes": notes,
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use hdot_sim::run::{self, Output, Request};

    use super::*;

    /// A run of the bundled heavy top (the scene and the report with the
    /// trajectory).
    fn heavy_top() -> (Scene, Report) {
        let path = Path::new("docs/examples/sim-heavy-top.toml");
        let scene = crate::catalog::scene(path).unwrap();
        let plan = run::plan(&scene, &Request::default()).unwrap();
        let mut out = Output {
            store: true,
            ..Output::default()
        };
        let report = run::run(&scene, &plan, &mut out).unwrap();
        (scene, report)
    }

    #[test]
    fn a_non_finite_sample_is_refused_and_located() {
        let (scene, mut report) = heavy_top();
        assert!(simulation_page(&scene, &report).is_ok());
        let rows = report.trajectory.as_mut().unwrap();
        let t = rows[7][0];
        rows[7][3] = f64::NAN;
        let e = simulation_page(&scene, &report).unwrap_err();
        assert!(
            matches!(&e, PageError::NonFinite { sample: 7, quantity, .. } if quantity == "q_y"),
            "{e}"
        );
        assert!(e.to_string().contains(&format!("at t = {t}")), "{e}");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(
            crate::html::escape("a<b & \"c\"</script>"),
            "a&lt;b &amp; &quot;c&quot;&lt;/script&gt;"
        );
    }
}
