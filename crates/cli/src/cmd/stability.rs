//! `hdot stability SCENE`: sweep a parameter of linearised equations
//! M q̈ + C q̇ + K q = 0, write the eigenvalues (CSV and chart, and with
//! `--html` a page) and report where the motion is stable.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use hdot_num::chart::{Panel, Series, panels_chart_into};
use hdot_sim::stability::{self, Edge, Interval, MARGIN, STRICT_MARGIN, StabilityScene, Sweep};

use crate::output::{self, OutputError};

// Arguments of `hdot stability`.
#[derive(Debug, Args)]
pub struct StabilityArgs {
    /// Stability scene (TOML, `kind = "stability"`), or a bundled example's name.
    pub scene: PathBuf,
    /// Directory for `eigenvalues.csv`, `eigenvalues.svg` and `eigenvalues.png`.
    #[arg(long, default_value = ".")]
    pub out: PathBuf,
    /// Also write the report and the chart as one self-contained web page.
    #[arg(long)]
    pub html: Option<PathBuf>,
}

/// Sweeps at least this long get a progress bar (on a terminal).
const PROGRESS_FROM: usize = 20_000;

/// Runs `hdot stability`.
pub fn run(args: StabilityArgs) -> anyhow::Result<ExitCode> {
    let scene = crate::catalog::stability_scene(&args.scene)?;
    let stem = args.out.join("eigenvalues");
    let csv = stem.with_extension("csv");
    if let Some(page) = &args.html {
        let (svg, png) = (stem.with_extension("svg"), stem.with_extension("png"));
        crate::html::refuse_page_path(
            page,
            &[args.scene.as_path(), scene.derivation.as_path()],
            &[("the CSV", &csv), ("the chart", &svg), ("the chart", &png)],
        )?;
    }
    let bar = (scene.count >= PROGRESS_FROM && std::io::stderr().is_terminal()).then(|| {
        let bar = indicatif::ProgressBar::new(scene.count as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} values, eta {eta}")
                .expect("valid template"),
        );
        bar
    });
    let mut progress = |done: usize, _total: usize| {
        if let Some(b) = &bar {
            b.set_position(done as u64);
        }
    };
    let sweep = stability::sweep(&scene, &mut progress);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let sweep = sweep?;
    let report = report(&scene, &sweep);

    std::fs::create_dir_all(&args.out)
        .map_err(|e| OutputError::new(format!("cannot create {}", args.out.display()), e))?;
    let mut batch = output::Batch::new();
    batch
        .write(&csv, stability::csv(&sweep).as_bytes())
        .map_err(|e| OutputError::new(format!("cannot write {}", csv.display()), e))?;
    let title = format!("{}: eigenvalues against {}", scene.name, scene.parameter);
    panels_chart_into(&mut batch, &stem, &title, &scene.parameter, &panels(&sweep)).map_err(
        |e| {
            OutputError::new(
                "cannot write the chart",
                std::io::Error::other(e.to_string()),
            )
        },
    )?;
    batch
        .commit()
        .map_err(|e| OutputError::new(format!("cannot write {}", stem.display()), e))?;
    if let Some(page) = &args.html {
        let svg = std::fs::read_to_string(stem.with_extension("svg"))
            .map_err(|e| OutputError::new("cannot read the chart back", e))?;
        output::write_atomic(
            page,
            crate::html::stability_page(&scene, &report, &svg).as_bytes(),
        )?;
    }
    crate::out!("{report}");
    crate::outln!(
        "wrote {}, {}.svg, {}.png{}",
        csv.display(),
        stem.display(),
        stem.display(),
        args.html
            .as_ref()
            .map(|p| format!(", {}", p.display()))
            .unwrap_or_default()
    );
    Ok(ExitCode::SUCCESS)
}

/// The panels of the chart: real parts, then imaginary parts, one line
/// per eigenvalue column.
fn panels(s: &Sweep) -> Vec<Panel> {
    let n = s.eigenvalues.first().map_or(0, Vec::len);
    let part = |im: bool| {
        (0..n)
            .map(|k| {
                Series::new(
                    format!("λ{}", k + 1),
                    s.values
                        .iter()
                        .zip(&s.eigenvalues)
                        .map(|(&p, ev)| (p, if im { ev[k].im } else { ev[k].re }))
                        .collect(),
                )
            })
            .collect()
    };
    vec![
        Panel {
            y_label: "Re λ".into(),
            series: part(false),
        },
        Panel {
            y_label: "Im λ".into(),
            series: part(true),
        },
    ]
}

/// The text report: what was swept, and the intervals.
fn report(scene: &StabilityScene, s: &Sweep) -> String {
    let m = &scene.matrices;
    let steps = m.steps();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "scene:      {} ({})",
        hdot_sym::escape::terminal(&scene.name),
        hdot_sym::escape::terminal(&scene.file.display().to_string())
    );
    let _ = writeln!(
        out,
        "equations:  M q'' + C q' + K q = 0 from {} (M = `{}`, C = {}, K = `{}`), {} coordinates",
        scene.derivation.display(),
        steps[0].as_deref().unwrap_or("?"),
        steps[1]
            .as_deref()
            .map_or("0".to_string(), |c| format!("`{c}`")),
        steps[2].as_deref().unwrap_or("?"),
        m.dof()
    );
    let _ = writeln!(
        out,
        "sweep:      {} from {} to {}, {} values; eigenvalues of A = [[0, I], [-M^-1 K, -M^-1 C]]",
        scene.parameter, scene.from, scene.to, scene.count
    );
    let _ = writeln!(
        out,
        "stable (every real part below -{STRICT_MARGIN:e} |A|): {}",
        intervals(&s.parameter, &s.stable)
    );
    let _ = writeln!(
        out,
        "not unstable (no real part above {MARGIN:e} |A|): {}",
        intervals(&s.parameter, &s.not_unstable)
    );
    out
}

/// `p in [a, b]` for each interval, each refined end with as many
/// decimals as its precision gives; or `nowhere in the sweep`.
fn intervals(p: &str, list: &[Interval]) -> String {
    if list.is_empty() {
        return "nowhere in the sweep".into();
    }
    let end = |v: f64, e: Edge| match e {
        Edge::SweepEnd => format!("{v} (sweep end)"),
        Edge::Boundary { half_width } => {
            let decimals = if half_width > 0.0 {
                (-(2.0 * half_width).log10()).ceil().clamp(0.0, 16.0) as usize
            } else {
                16
            };
            format!("{v:.decimals$}")
        }
    };
    list.iter()
        .map(|i| {
            format!(
                "{p} in [{}, {}]",
                end(i.lo, i.lo_edge),
                end(i.hi, i.hi_edge)
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}
