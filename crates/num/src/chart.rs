//! Log–log line charts written as SVG and PNG (shared by the numeric and
//! simulation crates).
//!
//! One entry point, [`loglog_chart`], draws one line with markers per
//! [`Series`], a legend and logarithmic axes, and writes `<stem>.svg` and
//! `<stem>.png`. Text in the PNG is drawn with DejaVu Sans, vendored in
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
    let (w, h) = CHART_SIZE;
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, CHART_SIZE).into_drawing_area();
        draw(&root, title, x_label, y_label, &clean, ranges).map_err(|message| {
            ChartError::Draw {
                path: png_path.clone(),
                message,
            }
        })?;
    }
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let png_err = |e: png::EncodingError| ChartError::Png {
            path: png_path.clone(),
            message: e.to_string(),
        };
        let mut writer = enc.write_header().map_err(png_err)?;
        writer.write_image_data(&rgb).map_err(png_err)?;
    }
    stage(batch, &png_path, &bytes)
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
