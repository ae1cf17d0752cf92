//! Line charts written as SVG and PNG (shared by the numeric and
//! simulation crates and the command line).
//!
//! [`loglog_chart`] draws one line with markers per [`Series`], a legend
//! and logarithmic axes (convergence, work–precision);
//! [`panels_chart_into`] draws lines on linear axes in panels stacked
//! over one x axis (eigenvalues against a parameter). Both write
//! `<stem>.svg` and `<stem>.png`. Text in the PNG is drawn with DejaVu Sans, vendored in
//! `crates/num/assets/fonts/` (licence next to it), through plotters'
//! `ab_glyph` feature, so the build needs no system font library.
//!
//! Both files are written to a temporary file in the target directory and
//! renamed into place: a failed or interrupted run never leaves a
//! half-written chart.
//!
//! # Example
//!
//! ```
//! use hdot_num::chart::{Series, loglog_chart};
//! let dir = tempfile::tempdir().unwrap();
//! let s = Series::new("midpoint", vec![(8.0, 1e-2), (64.0, 2.5e-3), (512.0, 6.2e-4)]);
//! loglog_chart(&dir.path().join("err"), "Error", "particles", "relative error", &[s]).unwrap();
//! assert!(dir.path().join("err.svg").exists());
//! assert!(dir.path().join("err.png").exists());
//! ```

use crate::fsio::Batch;
use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;

/// The font every chart uses (DejaVu Sans, see `assets/fonts/`).
static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");
/// Family name under which the vendored font is registered with plotters.
const FAMILY: &str = "sans-serif";

/// Size of the PNG in pixels (the SVG uses the same user units).
pub const CHART_SIZE: (u32, u32) = (900, 600);

/// One line of a chart: a legend label and its `(x, y)` points.
///
/// Points with a non-finite or non-positive coordinate cannot be shown on
/// log axes; [`loglog_chart`] skips them (and fails if nothing is left).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points in drawing order.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A series from a label and its points.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
        }
    }
}

/// Why a chart could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    /// No series has a point that can be drawn on log axes.
    #[error("chart {path}: no finite positive point to draw")]
    NoData {
        /// The chart's path stem.
        path: PathBuf,
    },
    /// Creating, writing or renaming a file failed.
    #[error("chart {path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// Plotters failed while drawing.
    #[error("chart {path}: drawing failed: {message}")]
    Draw {
        /// The file concerned.
        path: PathBuf,
        /// Plotters' message.
        message: String,
    },
    /// PNG encoding failed.
    #[error("chart {path}: PNG encoding failed: {message}")]
    Png {
        /// The file concerned.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is compiled in and known to parse; a failure here would
        // show as missing text, not as a panic.
        let _ = plotters::style::register_font(FAMILY, FontStyle::Normal, FONT);
    });
}

/// Colours of the series, in order (colour-blind friendly, Okabe–Ito).
const COLOURS: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
];

/// Writes a log–log chart of `series` to `<path_stem>.svg` and
/// `<path_stem>.png`: one line with markers per series, a legend, log axes
/// spanning the data (rounded out to whole decades).
///
/// The parent directory must exist. Both files appear complete or neither
/// does (temporary files, then renames: [`crate::fsio`]).
pub fn loglog_chart(
    path_stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), ChartError> {
    let mut batch = Batch::new();
    loglog_chart_into(&mut batch, path_stem, title, x_label, y_label, series)?;
    batch.commit().map_err(|source| ChartError::Io {
        path: path_stem.to_path_buf(),
        source,
    })
}

/// As [`loglog_chart`], but stages the two files in `batch`, to appear
/// together with the other files of the command when it is committed.
pub fn loglog_chart_into(
    batch: &mut Batch,
    path_stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), ChartError> {
    register_font();
    let clean: Vec<Series> = series
        .iter()
        .map(|s| Series {
            label: s.label.clone(),
            points: s
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0)
                .collect(),
        })
        .collect();
    let all = clean.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let mut any = false;
    for &(x, y) in all {
        any = true;
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !any {
        return Err(ChartError::NoData {
            path: path_stem.to_path_buf(),
        });
    }
    let decade = |v: f64, up: bool| {
        let e = v.log10();
        10f64.powf(if up { e.ceil() } else { e.floor() })
    };
    let (mut x0, mut x1) = (decade(x0, false), decade(x1, true));
    let (mut y0, mut y1) = (decade(y0, false), decade(y1, true));
    if x1 <= x0 {
        x0 /= 10.0;
        x1 *= 10.0;
    }
    if y1 <= y0 {
        y0 /= 10.0;
        y1 *= 10.0;
    }
    let ranges = (x0..x1, y0..y1);

    // SVG
    let svg_path = path_stem.with_extension("svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CHART_SIZE).into_drawing_area();
        draw(&root, title, x_label, y_label, &clean, ranges.clone()).map_err(|message| {
            ChartError::Draw {
                path: svg_path.clone(),
                message,
            }
        })?;
    }
    stage(batch, &svg_path, svg.as_bytes())?;

    // PNG
    let png_path = path_stem.with_extension("png");
    let rgb = render_rgb(|root| draw(root, title, x_label, y_label, &clean, ranges.clone()))
        .map_err(|message| ChartError::Draw {
            path: png_path.clone(),
            message,
        })?;
    stage_png(batch, &png_path, &rgb)
}

/// Draws a chart of [`CHART_SIZE`] into an RGB buffer with `draw`.
fn render_rgb(
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<Vec<u8>, String> {
    let (w, h) = CHART_SIZE;
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, CHART_SIZE).into_drawing_area();
        draw(&root)?;
    }
    Ok(rgb)
}

/// Encodes an RGB buffer of [`CHART_SIZE`] as PNG and stages it in `batch`.
fn stage_png(batch: &mut Batch, png_path: &Path, rgb: &[u8]) -> Result<(), ChartError> {
    let (w, h) = CHART_SIZE;
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let png_err = |e: png::EncodingError| ChartError::Png {
            path: png_path.to_path_buf(),
            message: e.to_string(),
        };
        let mut writer = enc.write_header().map_err(png_err)?;
        writer.write_image_data(rgb).map_err(png_err)?;
    }
    stage(batch, png_path, &bytes)
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    (xr, yr): (std::ops::Range<f64>, std::ops::Range<f64>),
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FAMILY, 26))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(xr.log_scale(), yr.log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style((FAMILY, 16))
        .axis_desc_style((FAMILY, 18))
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
        .draw()
        .map_err(e)?;
    for (i, s) in series.iter().enumerate() {
        if s.points.is_empty() {
            continue;
        }
        let colour = COLOURS[i % COLOURS.len()];
        let style = ShapeStyle::from(&colour).stroke_width(2);
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), style))
            .map_err(e)?
            .label(s.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(2))
            });
        let marker = i % 3;
        chart
            .draw_series(
                s.points
                    .iter()
                    .map(move |&p| -> DynElement<DB, (f64, f64)> {
                        match marker {
                            0 => Circle::new(p, 4, colour.filled()).into_dyn(),
                            1 => TriangleMarker::new(p, 5, colour.filled()).into_dyn(),
                            _ => Cross::new(p, 4, colour.stroke_width(2)).into_dyn(),
                        }
                    }),
            )
            .map_err(e)?;
    }
    chart
        .configure_series_labels()
        .label_font((FAMILY, 16))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

fn stage(batch: &mut Batch, path: &Path, bytes: &[u8]) -> Result<(), ChartError> {
    batch.write(path, bytes).map_err(|source| ChartError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// One panel of a [`panels_chart_into`] chart: its y-axis label and lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// The y axis's label.
    pub y_label: String,
    /// The lines (drawn without markers; non-finite points are skipped).
    pub series: Vec<Series>,
}

/// Writes a chart of panels stacked one above the other, sharing the
/// linear x axis, to `<path_stem>.svg` and `<path_stem>.png` staged in
/// `batch`: each panel's lines on linear axes spanning its data (a zero
/// line drawn when the range crosses zero), a legend in the first panel
/// when there are at most [`LEGEND_MAX`] lines.
pub fn panels_chart_into(
    batch: &mut Batch,
    path_stem: &Path,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<(), ChartError> {
    register_font();
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let span = |it: &mut dyn Iterator<Item = f64>| {
        it.fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)))
    };
    let points = || {
        panels.iter().flat_map(|p| {
            p.series
                .iter()
                .flat_map(|s| s.points.iter().filter(|q| finite(q)))
        })
    };
    if points().next().is_none() {
        return Err(ChartError::NoData {
            path: path_stem.to_path_buf(),
        });
    }
    let x = padded(span(&mut points().map(|p| p.0)), 0.0);
    let ys: Vec<std::ops::Range<f64>> = panels
        .iter()
        .map(|p| {
            let mut it = p
                .series
                .iter()
                .flat_map(|s| s.points.iter().filter(|q| finite(q)).map(|q| q.1));
            padded(span(&mut it), 0.05)
        })
        .collect();
    let svg_path = path_stem.with_extension("svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CHART_SIZE).into_drawing_area();
        draw_panels(&root, title, x_label, panels, &x, &ys).map_err(|message| {
            ChartError::Draw {
                path: svg_path.clone(),
                message,
            }
        })?;
    }
    stage(batch, &svg_path, svg.as_bytes())?;
    let png_path = path_stem.with_extension("png");
    let rgb = render_rgb(|root| draw_panels(root, title, x_label, panels, &x, &ys)).map_err(
        |message| ChartError::Draw {
            path: png_path.clone(),
            message,
        },
    )?;
    stage_png(batch, &png_path, &rgb)
}

/// The most lines a panel chart labels in a legend.
pub const LEGEND_MAX: usize = 12;

/// A data range widened by `pad` of its width on each side; a range of
/// zero width (or none) is widened to one around its value.
fn padded((lo, hi): (f64, f64), pad: f64) -> std::ops::Range<f64> {
    if lo > hi {
        return -1.0..1.0;
    }
    let w = hi - lo;
    if w <= f64::EPSILON * lo.abs().max(hi.abs()) {
        let d = lo.abs().max(1.0) * 0.5;
        return (lo - d)..(hi + d);
    }
    (lo - pad * w)..(hi + pad * w)
}

fn draw_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    panels: &[Panel],
    xr: &std::ops::Range<f64>,
    yrs: &[std::ops::Range<f64>],
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, (FAMILY, 24)).map_err(e)?;
    let areas = root.split_evenly((panels.len().max(1), 1));
    for (k, (panel, area)) in panels.iter().zip(&areas).enumerate() {
        let yr = yrs[k].clone();
        let last = k + 1 == panels.len();
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(if last { 45 } else { 20 })
            .y_label_area_size(80)
            .build_cartesian_2d(xr.clone(), yr.clone())
            .map_err(e)?;
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(panel.y_label.as_str())
            .label_style((FAMILY, 15))
            .axis_desc_style((FAMILY, 17))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(200, 200, 200));
        if last {
            mesh.x_desc(x_label);
        }
        mesh.draw().map_err(e)?;
        if yr.start < 0.0 && yr.end > 0.0 {
            chart
                .draw_series(LineSeries::new(
                    [(xr.start, 0.0), (xr.end, 0.0)],
                    BLACK.stroke_width(1),
                ))
                .map_err(e)?;
        }
        let legend = k == 0 && panel.series.len() <= LEGEND_MAX;
        for (i, s) in panel.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            // Runs of finite points, so that a gap is not drawn across.
            let mut drawn = false;
            for run in s.points.split(|p| !(p.0.is_finite() && p.1.is_finite())) {
                if run.is_empty() {
                    continue;
                }
                let a = chart
                    .draw_series(LineSeries::new(run.iter().copied(), colour.stroke_width(2)))
                    .map_err(e)?;
                if legend && !drawn {
                    a.label(s.label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(2))
                    });
                }
                drawn = true;
            }
        }
        if legend && !panel.series.is_empty() {
            chart
                .configure_series_labels()
                .label_font((FAMILY, 14))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(e)?;
        }
    }
    root.present().map_err(e)?;
    Ok(())
}
