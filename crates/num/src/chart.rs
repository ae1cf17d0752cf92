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

use plotters::chart::MeshStyle;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The font every chart uses (DejaVu Sans, see `assets/fonts/`).
static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");
/// Family name under which the vendored font is registered with plotters.
const FAMILY: &str = "sans-serif";

/// Size of the PNG in pixels (the SVG uses the same user units). A page
/// shows the SVG at most this wide (1:1 on a desktop) and scales it down
/// to a phone's column, so the text sizes below are chosen for a 400 px
/// screen: a tick label there is still 10 px high.
pub const CHART_SIZE: (u32, u32) = (640, 440);

/// Text sizes as plotters takes them (its SVG writes a size s as s/1.24
/// px): tick labels, axis descriptions, legend entries, the title.
const TICK: u32 = 21;
const DESC: u32 = 22;
const LEGEND: u32 = 21;
const TITLE: u32 = 21;

/// Room right of the plot for half of the last x tick label, which is
/// centred on its tick and would otherwise be cut at the chart's edge.
const RIGHT: u32 = 36;

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
    let chart = LogLog {
        title,
        x_label,
        y_label,
        series: &clean,
        ranges,
    };
    stage_both(batch, path_stem, &chart)
}

/// A chart that can draw itself on any plotters backend (the SVG and the
/// PNG are drawn by the same code).
trait Drawing {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Draws `chart` as `<stem>.svg` and `<stem>.png`, staged in `batch`.
fn stage_both(batch: &mut Batch, path_stem: &Path, chart: &impl Drawing) -> Result<(), ChartError> {
    let svg_path = path_stem.with_extension("svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CHART_SIZE).into_drawing_area();
        chart.draw(&root).map_err(|message| ChartError::Draw {
            path: svg_path.clone(),
            message,
        })?;
    }
    stage(batch, &svg_path, svg.as_bytes())?;
    let png_path = path_stem.with_extension("png");
    let rgb = render_rgb(|root| chart.draw(root)).map_err(|message| ChartError::Draw {
        path: png_path.clone(),
        message,
    })?;
    stage_png(batch, &png_path, &rgb)
}

/// The plot area of a chart on `area`: its margins (room on the right for
/// the last x tick label) and the label areas left and below.
fn plot_area<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    margin: u32,
    x_area: u32,
) -> ChartBuilder<'a, 'b, DB> {
    let mut b = ChartBuilder::on(area);
    b.margin(margin)
        .margin_right(RIGHT.max(margin))
        .x_label_area_size(x_area)
        .y_label_area_size(90);
    b
}

/// The axes' one style: text sizes, the font, grid lines.
fn styled<'m, 'a, 'b, X: Ranged, Y: Ranged, DB: DrawingBackend>(
    mesh: &'m mut MeshStyle<'a, 'b, X, Y, DB>,
) -> &'m mut MeshStyle<'a, 'b, X, Y, DB> {
    // At most six labels on an axis: at this size more would run into
    // each other (100.0120.0140.0 on a 640-unit axis).
    mesh.x_labels(6)
        .y_labels(6)
        .label_style((FAMILY, TICK))
        .axis_desc_style((FAMILY, DESC))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
}

/// The legend's one style, in the upper right corner.
fn legend<'a, 'b, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &'b mut ChartContext<'a, DB, CT>,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .label_font((FAMILY, LEGEND))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| e.to_string())
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

/// A log–log chart of series (see [`loglog_chart`]).
struct LogLog<'s> {
    title: &'s str,
    x_label: &'s str,
    y_label: &'s str,
    series: &'s [Series],
    ranges: (std::ops::Range<f64>, std::ops::Range<f64>),
}

impl Drawing for LogLog<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
        let (xr, yr) = self.ranges.clone();
        root.fill(&WHITE).map_err(e)?;
        let mut chart = plot_area(root, 16, 55)
            .caption(self.title, (FAMILY, TITLE))
            .build_cartesian_2d(xr.log_scale(), yr.log_scale())
            .map_err(e)?;
        styled(&mut chart.configure_mesh())
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(e)?;
        for (i, s) in self.series.iter().enumerate() {
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
        legend(&mut chart)?;
        root.present().map_err(e)?;
        Ok(())
    }
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
    let chart = Panels {
        title,
        x_label,
        panels,
        xr: x,
        yrs: ys,
    };
    stage_both(batch, path_stem, &chart)
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

/// Panels over one x axis (see [`panels_chart_into`]).
struct Panels<'s> {
    title: &'s str,
    x_label: &'s str,
    panels: &'s [Panel],
    xr: std::ops::Range<f64>,
    yrs: Vec<std::ops::Range<f64>>,
}

impl Drawing for Panels<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
        let xr = &self.xr;
        root.fill(&WHITE).map_err(e)?;
        let root = root.titled(self.title, (FAMILY, TITLE)).map_err(e)?;
        let areas = root.split_evenly((self.panels.len().max(1), 1));
        for (k, (panel, area)) in self.panels.iter().zip(&areas).enumerate() {
            let yr = self.yrs[k].clone();
            let last = k + 1 == self.panels.len();
            let mut chart = plot_area(area, 10, if last { 50 } else { 24 })
                .build_cartesian_2d(xr.clone(), yr.clone())
                .map_err(e)?;
            let mut mesh = chart.configure_mesh();
            styled(&mut mesh).y_desc(panel.y_label.as_str());
            if last {
                mesh.x_desc(self.x_label);
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
            let labelled = k == 0 && panel.series.len() <= LEGEND_MAX;
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
                    if labelled && !drawn {
                        a.label(s.label.clone()).legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(2))
                        });
                    }
                    drawn = true;
                }
            }
            if labelled && !panel.series.is_empty() {
                legend(&mut chart)?;
            }
        }
        root.present().map_err(e)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `<text>` elements of an SVG: x, anchor, font size, whether it is
    /// turned, and the text.
    fn texts(svg: &str) -> Vec<(f64, String, f64, bool, String)> {
        let attr = |tag: &str, name: &str| {
            tag.split_once(&format!(" {name}=\""))
                .and_then(|(_, r)| r.split_once('"'))
                .map(|(v, _)| v.to_owned())
        };
        svg.split("<text")
            .skip(1)
            .map(|t| {
                let (tag, rest) = t.split_once('>').expect("a tag");
                let text = rest.split_once("</text>").expect("closed").0.to_owned();
                let x = attr(tag, "x").and_then(|v| v.parse().ok()).unwrap_or(0.0);
                let size = attr(tag, "font-size")
                    .and_then(|v| v.trim_end_matches("px").parse().ok())
                    .unwrap_or(0.0);
                let anchor = attr(tag, "text-anchor").unwrap_or_else(|| "start".into());
                (x, anchor, size, tag.contains("transform"), text)
            })
            .collect()
    }

    /// Every label lies inside the chart — the last x tick label of a
    /// linear axis, centred on the plot's right edge, was cut in half —
    /// and reads at 10 px or more on a 400 px phone, where a page scales
    /// the chart to a 384 px column.
    #[test]
    fn every_label_fits_inside_the_chart_and_reads_on_a_phone() {
        let dir = tempfile::tempdir().unwrap();
        let mut batch = Batch::new();
        let line = |k: f64| {
            Series::new(
                format!("λ{k}"),
                (0..=50)
                    .map(|i| {
                        let x = 1.25 * f64::from(i);
                        (x, (x * k).sin())
                    })
                    .collect(),
            )
        };
        let panels = [
            Panel {
                y_label: "Re λ".into(),
                series: vec![line(0.1), line(0.2)],
            },
            Panel {
                y_label: "Im λ".into(),
                series: vec![line(0.3)],
            },
        ];
        let stem = dir.path().join("panels");
        panels_chart_into(&mut batch, &stem, "Eigenvalues", "speed v (m/s)", &panels).unwrap();
        let log = dir.path().join("log");
        let s = Series::new("rk4", vec![(10.0, 1e-3), (1000.0, 1e-9)]);
        loglog_chart_into(&mut batch, &log, "Work", "evaluations", "error", &[s]).unwrap();
        batch.commit().unwrap();
        let width = f64::from(CHART_SIZE.0);
        for stem in [stem, log] {
            let svg = std::fs::read_to_string(stem.with_extension("svg")).unwrap();
            let texts = texts(&svg);
            assert!(texts.len() > 10, "{svg}");
            let right = texts
                .iter()
                .filter(|t| !t.3)
                .map(|t| t.0)
                .fold(0.0, f64::max);
            for (x, anchor, size, turned, text) in &texts {
                assert!(size * 384.0 / width >= 10.0, "{text:?} at {size} px");
                if *turned {
                    continue;
                }
                // DejaVu Sans averages under 0.62 em per character.
                let w = 0.62 * size * text.chars().count() as f64;
                let (l, r) = match anchor.as_str() {
                    "middle" => (x - w / 2.0, x + w / 2.0),
                    "end" => (x - w, *x),
                    _ => (*x, x + w),
                };
                assert!(
                    l >= 0.0 && r <= width,
                    "{text:?} from {l} to {r} in {width}"
                );
            }
            assert!(right > 0.8 * width, "no label near the right edge");
        }
    }
}
