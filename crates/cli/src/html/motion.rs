//! The motion a simulation page shows, from what a run returned: the
//! samples (a closed-form run, which records only its end, is sampled at
//! screen resolution from its closed form), the series each plot draws,
//! and the attitude of every drawn frame and the place of every derived
//! body at every sample.

use hdot_sim::nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use hdot_sim::run::{self, Report};
use hdot_sim::scene::Scene;
use hdot_sim::systems::free::{FreeBody, Gravity};

use super::PageError;

/// The model whose rows hold Eulerian angles instead of a quaternion.
const EULER_ANGLES: &str = "euler-angles";

/// Samples of a closed-form run (it records only its end state).
const CLOSED_FORM_SAMPLES: usize = 2000;

/// Frames of the animation: the run resampled at this many equal steps
/// (the page's size does not grow with the run's length).
pub const FRAMES: usize = 1200;

/// One curve of a plot: a name and a value at each sample.
#[derive(Debug, Clone)]
pub struct Series {
    /// What it is (`θ`, `ω_1`, `energy`).
    pub name: String,
    /// One value per sample time.
    pub values: Vec<f64>,
}

/// One plot: a title, the unit of its vertical axis, its curves.
#[derive(Debug, Clone)]
pub struct Plot {
    /// Title above the plot.
    pub title: String,
    /// Unit of the values (`rad`, `rad/s`, `N`; empty when mixed or none).
    pub unit: String,
    /// Curves, all over [`Motion::t`].
    pub series: Vec<Series>,
    /// Why the plot is empty, when it is (no conserved quantity).
    pub note: Option<String>,
}

/// The attitude of one drawn frame: drawing axes → space axes at each sample.
#[derive(Debug, Clone)]
pub struct Track {
    /// The frame's name (`body`, `shaft`, or a derivation's frame).
    pub frame: String,
    /// One rotation per animation frame; `Err` says why the frame's
    /// attitude is not a function of the state (drawn at rest).
    pub rotations: Result<Vec<Matrix3<f64>>, String>,
}

/// What a page shows of a run.
#[derive(Debug, Clone)]
pub struct Motion {
    /// Sample times of the plots.
    pub t: Vec<f64>,
    /// Times of the animation frames (equal steps over the run).
    pub frames: Vec<f64>,
    /// Coordinates, angular velocity, drifts.
    pub plots: Vec<Plot>,
    /// The attitude of the built-in body or shaft (`None` for a derived
    /// scene, whose frames are looked up with [`Motion::frame_track`]).
    pub body: Option<Track>,
    /// The state at each animation frame (time first), for a derived
    /// scene's frames.
    anim: Vec<Vec<f64>>,
    /// The angular momentum of a free body, fixed in space.
    pub momentum: Option<Vector3<f64>>,
}

/// The rows the page samples: the stored trajectory, or the closed form
/// sampled at [`CLOSED_FORM_SAMPLES`] times when the run recorded only its
/// end. Every value must be finite.
fn rows(scene: &Scene, report: &Report) -> Result<Vec<Vec<f64>>, PageError> {
    let stored = report.trajectory.clone().unwrap_or_default();
    let t_end = report.plan.t_end;
    let rows = if stored.len() >= 2 {
        stored
    } else {
        let times =
            (0..=CLOSED_FORM_SAMPLES).map(|i| t_end * i as f64 / CLOSED_FORM_SAMPLES as f64);
        if scene.rigid_body().is_some() {
            times
                .map(|t| {
                    let (y, _) = run::reference_state(scene, t)
                        .map_err(|e| PageError::Run(e.to_string()))?;
                    Ok(std::iter::once(t).chain(y).collect())
                })
                .collect::<Result<_, PageError>>()?
        } else if let Some((shaft, y0)) = scene.shaft() {
            times
                .map(|t| {
                    let y = shaft.exact(y0, t);
                    let r = shaft.reactions(y[1]);
                    vec![
                        t,
                        y[0],
                        y[1],
                        r.bearing_a[0],
                        r.bearing_a[1],
                        r.bearing_b[0],
                        r.bearing_b[1],
                    ]
                })
                .collect()
        } else {
            stored
        }
    };
    if rows.len() < 2 {
        return Err(PageError::Run(
            "the run returned fewer than two samples".into(),
        ));
    }
    let names = column_names(scene, report);
    for (i, row) in rows.iter().enumerate() {
        if let Some(k) = row.iter().position(|v| !v.is_finite()) {
            return Err(PageError::NonFinite {
                sample: i,
                t: row[0],
                quantity: names
                    .get(k)
                    .cloned()
                    .unwrap_or_else(|| format!("column {k}")),
                value: row[k],
            });
        }
    }
    Ok(rows)
}

/// The names of a row's columns, time first.
fn column_names(scene: &Scene, report: &Report) -> Vec<String> {
    run::stream_header(scene, report.plan.model)
        .split(',')
        .map(str::to_owned)
        .collect()
}

/// Refuses a non-finite value of a derived series: `sample` is its index.
fn finite(what: &str, t: &[f64], values: &[f64]) -> Result<(), PageError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(PageError::NonFinite {
            sample: i,
            t: t[i],
            quantity: what.to_owned(),
            value: values[i],
        }),
        None => Ok(()),
    }
}

/// Continuous angles: each sample moved by whole turns to the previous one.
fn unwrap(values: &mut [f64]) {
    let tau = std::f64::consts::TAU;
    for i in 1..values.len() {
        let d = values[i] - values[i - 1];
        values[i] -= tau * (d / tau).round();
    }
}

fn series(name: &str, values: Vec<f64>) -> Series {
    Series {
        name: name.to_owned(),
        values,
    }
}

/// A plot whose curves differ in range by more than a factor of
/// [`RANGE_RATIO`] split into plots of curves of like range (a spin angle
/// of hundreds of radians would flatten a nutation of a tenth).
fn split_by_range(plot: Plot) -> Vec<Plot> {
    let range = |s: &Series| {
        let (lo, hi) = s
            .values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(*v), h.max(*v))
            });
        hi - lo
    };
    // Each curve with its place in the plot, so the parts keep the order.
    if plot.series.is_empty() {
        return vec![plot];
    }
    let mut rest: Vec<(usize, Series)> = plot.series.into_iter().enumerate().collect();
    let mut out: Vec<Vec<(usize, Series)>> = vec![];
    while !rest.is_empty() {
        let top = rest.iter().map(|(_, s)| range(s)).fold(0.0f64, f64::max);
        let (big, small) = rest
            .into_iter()
            .partition(|(_, s)| range(s) * RANGE_RATIO >= top);
        out.push(big);
        rest = small;
        if out.len() == 3 && !rest.is_empty() {
            out.push(std::mem::take(&mut rest));
        }
    }
    out.sort_by_key(|part| part.first().map_or(0, |(i, _)| *i));
    let split = out.len() > 1;
    out.into_iter()
        .map(|part| {
            let series: Vec<Series> = part.into_iter().map(|(_, s)| s).collect();
            let title = if split {
                let names: Vec<&str> = series.iter().map(|s| s.name.as_str()).collect();
                format!("{}: {}", plot.title, names.join(", "))
            } else {
                plot.title.clone()
            };
            Plot {
                title,
                unit: plot.unit.clone(),
                series,
                note: plot.note.clone(),
            }
        })
        .collect()
}

/// See [`split_by_range`].
const RANGE_RATIO: f64 = 5.0;

/// `rows` linearly interpolated at `n + 1` equal steps of time; with
/// `quaternion`, columns 1–4 are a unit quaternion (kept on one sign and
/// renormalised).
fn resample(rows: &[Vec<f64>], n: usize, quaternion: bool) -> Vec<Vec<f64>> {
    let (t0, t1) = (rows[0][0], rows[rows.len() - 1][0]);
    let mut j = 0;
    (0..=n)
        .map(|i| {
            let t = t0 + (t1 - t0) * i as f64 / n as f64;
            while j + 2 < rows.len() && rows[j + 1][0] <= t {
                j += 1;
            }
            let (a, b) = (&rows[j], &rows[j + 1]);
            let span = b[0] - a[0];
            let s = if span > 0.0 {
                ((t - a[0]) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let flip = if quaternion && (1..5).map(|k| a[k] * b[k]).sum::<f64>() < 0.0 {
                -1.0
            } else {
                1.0
            };
            let mut row: Vec<f64> = a
                .iter()
                .zip(b)
                .enumerate()
                .map(|(k, (x, y))| {
                    let y = if (1..5).contains(&k) { flip * y } else { *y };
                    x + s * (y - x)
                })
                .collect();
            row[0] = t;
            if quaternion {
                let norm = row[1..5].iter().map(|v| v * v).sum::<f64>().sqrt();
                row[1..5].iter_mut().for_each(|v| *v /= norm);
            }
            row
        })
        .collect()
}

fn relative_drift(values: &[f64]) -> Vec<f64> {
    let v0 = values[0];
    let scale = values
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    values.iter().map(|v| (v - v0) / scale).collect()
}

/// # Construction
impl Motion {
    /// The motion of `report`'s run of `scene`.
    pub fn new(scene: &Scene, report: &Report) -> Result<Motion, PageError> {
        let rows = rows(scene, report)?;
        let t: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        let rigid = scene.rigid_body();
        let quaternion = rigid.is_some() && report.plan.model.name() != EULER_ANGLES;
        let anim = resample(&rows, FRAMES, quaternion);
        let mut m = if let Some(b) = rigid {
            let body = FreeBody {
                moments: b.moments.get(),
                gravity: b.pivot.map(|p| Gravity {
                    weight_arm: p.weight_arm,
                }),
            };
            body_motion(scene, report, &body, &rows, &anim)
        } else if scene.shaft().is_some() {
            shaft_motion(&rows, &anim)
        } else if let Some(ds) = scene.derivation() {
            derived_motion(ds, &rows, &column_names(scene, report))
        } else {
            return Err(PageError::Run(
                "the page draws a rigid body, a shaft or a derivation's coordinates, and this scene \
                 holds none of them"
                    .into(),
            ));
        };
        m.t = t;
        for p in &m.plots {
            for s in &p.series {
                finite(
                    &format!("{} of the plot {}", s.name, p.title),
                    &m.t,
                    &s.values,
                )?;
            }
        }
        m.plots = m.plots.into_iter().flat_map(split_by_range).collect();
        m.frames = anim.iter().map(|r| r[0]).collect();
        m.anim = anim;
        Ok(m)
    }

    /// The place of a derivation's body `name` (its reference point, in
    /// space) at each animation frame; `Err` says why it is not known (it
    /// is drawn at the origin).
    pub fn body_positions(&self, scene: &Scene, name: &str) -> Result<Vec<Vector3<f64>>, String> {
        let ds = scene.derivation().ok_or("not a derived scene")?;
        let p: Vec<Vector3<f64>> = self
            .anim
            .iter()
            .map(|row| ds.model.position(name, row[0], &row[1..]))
            .collect::<Result<_, _>>()?;
        match p.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
            Some(i) => Err(format!(
                "the place of body `{name}` is not finite at t = {}",
                self.frames[i]
            )),
            None => Ok(p),
        }
    }

    /// The attitude of a derivation's frame: the first of `chain` (a frame
    /// and its ancestors) whose attitude is a function of the state.
    pub fn frame_track(&self, scene: &Scene, chain: &[String]) -> Track {
        let Some(ds) = scene.derivation() else {
            return Track {
                frame: String::new(),
                rotations: Err("not a derived scene".into()),
            };
        };
        let mut why = String::from("no frame");
        for f in chain {
            let r: Result<Vec<Matrix3<f64>>, String> = self
                .anim
                .iter()
                .map(|row| ds.model.attitude(f, row[0], &row[1..]))
                .collect();
            match r {
                Ok(r) if r.iter().all(|m| m.iter().all(|v| v.is_finite())) => {
                    return Track {
                        frame: f.clone(),
                        rotations: Ok(r),
                    };
                }
                Ok(_) => why = format!("the attitude of frame `{f}` is not finite"),
                Err(e) if why == "no frame" => why = e,
                Err(_) => {}
            }
        }
        Track {
            frame: chain.first().cloned().unwrap_or_default(),
            rotations: Err(why),
        }
    }
}

/// A free body or heavy top: Eulerian angles, ω, energy and momentum drifts.
fn body_motion(
    scene: &Scene,
    report: &Report,
    body: &FreeBody,
    rows: &[Vec<f64>],
    anim: &[Vec<f64>],
) -> Motion {
    let state = |r: &Vec<f64>| -> [f64; 7] {
        if report.plan.model.name() == EULER_ANGLES {
            let q = hdot_num::body::eulerian_rotation(r[1], r[2], r[3]).into_inner();
            [q.w, q.i, q.j, q.k, r[4], r[5], r[6]]
        } else {
            std::array::from_fn(|k| r[k + 1])
        }
    };
    let states: Vec<[f64; 7]> = rows.iter().map(state).collect();
    let attitudes: Vec<UnitQuaternion<f64>> = states
        .iter()
        .map(hdot_sim::systems::free::attitude)
        .collect();
    let mut angles = [vec![], vec![], vec![]];
    for q in &attitudes {
        let (phi, theta, psi) = hdot_sim::systems::euler_angles::angles_from_quaternion(q);
        angles[0].push(phi);
        angles[1].push(theta);
        angles[2].push(psi);
    }
    unwrap(&mut angles[0]);
    unwrap(&mut angles[2]);
    let [phi, theta, psi] = angles;
    let omega = |k: usize| states.iter().map(|y| y[k + 4]).collect::<Vec<_>>();
    let energy: Vec<f64> = states.iter().map(|y| body.energy(y)).collect();
    let h: Vec<f64> = states.iter().map(|y| body.momentum_invariant(y)).collect();
    let h_name = if body.gravity.is_some() { "H_Z" } else { "|H|" };
    // Drawing axes (the tables', from the body frame's origin) → space.
    let axes_t = scene
        .body_frame
        .map(|f| f.axes.inverse())
        .unwrap_or_else(Rotation3::identity);
    let rotations = anim
        .iter()
        .map(|r| {
            hdot_sim::systems::free::attitude(&state(r))
                .to_rotation_matrix()
                .matrix()
                * axes_t.matrix()
        })
        .collect();
    let momentum = body.gravity.is_none().then(|| {
        let y = &states[0];
        let i = body.moments;
        attitudes[0] * Vector3::new(i[0] * y[4], i[1] * y[5], i[2] * y[6])
    });
    Motion {
        t: vec![],
        plots: vec![
            Plot {
                title: "Eulerian angles".into(),
                unit: "rad".into(),
                series: vec![series("φ", phi), series("θ", theta), series("ψ", psi)],
                note: None,
            },
            Plot {
                title: "ω in the body's principal axes".into(),
                unit: "rad/s".into(),
                series: vec![
                    series("ω_1", omega(0)),
                    series("ω_2", omega(1)),
                    series("ω_3", omega(2)),
                ],
                note: None,
            },
            Plot {
                title: "conserved quantities: (I(t) − I(0)) / max |I|".into(),
                unit: String::new(),
                series: vec![
                    series("energy", relative_drift(&energy)),
                    series(h_name, relative_drift(&h)),
                ],
                note: None,
            },
        ],
        body: Some(Track {
            frame: "body".into(),
            rotations: Ok(rotations),
        }),
        frames: vec![],
        anim: vec![],
        momentum,
    }
}

/// A shaft: angle, ω and the bearing reactions; nothing is conserved.
fn shaft_motion(rows: &[Vec<f64>], anim: &[Vec<f64>]) -> Motion {
    let col = |k: usize| rows.iter().map(|r| r[k]).collect::<Vec<_>>();
    let rotations = anim
        .iter()
        .map(|r| *Rotation3::from_axis_angle(&Vector3::z_axis(), r[1]).matrix())
        .collect();
    Motion {
        t: vec![],
        plots: vec![
            Plot {
                title: "angle of the shaft".into(),
                unit: "rad".into(),
                series: vec![series("angle", col(1))],
                note: None,
            },
            Plot {
                title: "ω about the shaft's axis".into(),
                unit: "rad/s".into(),
                series: vec![series("ω", col(2))],
                note: None,
            },
            Plot {
                title: "bearing reactions".into(),
                unit: "N".into(),
                series: vec![
                    series("A_x", col(3)),
                    series("A_y", col(4)),
                    series("B_x", col(5)),
                    series("B_y", col(6)),
                ],
                note: None,
            },
        ],
        body: Some(Track {
            frame: "shaft".into(),
            rotations: Ok(rotations),
        }),
        frames: vec![],
        anim: vec![],
        momentum: None,
    }
}

/// A derived scene: its coordinates, rates (or the reported frame's ω)
/// and the drift of each conserved step.
fn derived_motion(
    ds: &hdot_sim::scene::DerivedScene,
    rows: &[Vec<f64>],
    names: &[String],
) -> Motion {
    let n = ds.model.dof();
    let col = |k: usize| rows.iter().map(|r| r[k]).collect::<Vec<_>>();
    // The carried angles (after the rates) are coordinates too.
    let base = ds.model.carried_base();
    let coordinates = (1..=n)
        .chain(base + 1..names.len())
        .map(|k| series(&names[k], col(k)))
        .collect();
    let rates = match &ds.frame {
        Some(f) => {
            let w: Vec<Vector3<f64>> = rows
                .iter()
                .map(|r| {
                    ds.model
                        .angular_velocity(f, r[0], &r[1..])
                        .unwrap_or_else(|_| Vector3::repeat(f64::NAN))
                })
                .collect();
            Plot {
                title: format!("ω of frame {f} in its own axes"),
                unit: "rad/s".into(),
                series: (0..3)
                    .map(|k| series(&format!("ω_{}", k + 1), w.iter().map(|v| v[k]).collect()))
                    .collect(),
                note: None,
            }
        }
        None => Plot {
            title: "rates of the coordinates".into(),
            unit: String::new(),
            series: (n + 1..=base).map(|k| series(&names[k], col(k))).collect(),
            note: None,
        },
    };
    let drifts: Vec<Series> = ds
        .model
        .conserved()
        .iter()
        .map(|q| {
            let v: Vec<Vec<f64>> = rows
                .iter()
                .map(|r| ds.model.conserved_value(q, r[0], &r[1..]))
                .collect();
            let norm = |x: &[f64]| x.iter().map(|c| c * c).sum::<f64>().sqrt();
            let scale = v
                .iter()
                .fold(0.0f64, |m, x| m.max(norm(x)))
                .max(f64::MIN_POSITIVE);
            let d = v
                .iter()
                .map(|x| norm(&x.iter().zip(&v[0]).map(|(a, b)| a - b).collect::<Vec<_>>()) / scale)
                .collect();
            series(&q.name, d)
        })
        .collect();
    let note = drifts
        .is_empty()
        .then(|| "the derivation marks no step `conserved = true`".to_owned());
    Motion {
        t: vec![],
        plots: vec![
            Plot {
                title: "coordinates".into(),
                unit: String::new(),
                series: coordinates,
                note: None,
            },
            rates,
            Plot {
                title: "conserved steps: |I(t) − I(0)| / max |I|".into(),
                unit: String::new(),
                series: drifts,
                note,
            },
        ],
        body: None,
        frames: vec![],
        anim: vec![],
        momentum: None,
    }
}
