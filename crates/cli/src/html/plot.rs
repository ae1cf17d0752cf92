//! SVG line plots of a page's series against time, drawn at the resolution
//! of a screen: each curve keeps, per pixel column, the first, smallest,
//! largest and last of its samples there (so a fast oscillation shows as
//! its band and a run of any length gives a plot of bounded size).

use std::fmt::Write;

use super::escape;
use super::motion::Plot;

/// Width and height of a plot's drawing (SVG user units, scaled to the page).
const WIDTH: f64 = 640.0;
const HEIGHT: f64 = 230.0;
/// Margins: left (tick labels), right, top (legend), bottom (time axis).
const LEFT: f64 = 64.0;
const RIGHT: f64 = 12.0;
const TOP: f64 = 26.0;
const BOTTOM: f64 = 30.0;
/// Colours of the curves, in order.
const COLOURS: [&str; 4] = ["#1f5fa8", "#c2410c", "#15803d", "#7e22ce"];

/// A tick label: plain decimals for ordinary sizes, otherwise `1.2e-13`.
pub fn tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&a) {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_owned()
    } else {
        format!("{v:.1e}")
    }
}

/// Up to about five round values covering `[lo, hi]`.
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    let raw = span / 4.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|k| k * mag)
        .find(|s| span / s <= 5.0)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// Per pixel column, the indices of the first, smallest, largest and last
/// samples of `v` there, in time order.
fn envelope(xs: &[f64], v: &[f64]) -> Vec<usize> {
    let mut out = vec![];
    let mut i = 0;
    while i < v.len() {
        let col = xs[i].floor();
        let start = i;
        let (mut lo, mut hi) = (i, i);
        while i < v.len() && xs[i].floor() == col {
            if v[i] < v[lo] {
                lo = i;
            }
            if v[i] > v[hi] {
                hi = i;
            }
            i += 1;
        }
        let mut keep = vec![start, lo, hi, i - 1];
        keep.sort_unstable();
        keep.dedup();
        out.extend(keep);
    }
    out
}

/// The plot as an `<svg>` element (or a note when it has no curve).
pub fn svg(plot: &Plot, t: &[f64]) -> String {
    let mut s = String::new();
    let title = if plot.unit.is_empty() {
        escape(&plot.title)
    } else {
        escape(&format!("{} ({})", plot.title, plot.unit))
    };
    if plot.series.is_empty() {
        let note = plot.note.as_deref().unwrap_or("nothing to plot");
        let _ = write!(
            s,
            "<figure><figcaption>{title}</figcaption><p class=\"note\">{}</p></figure>",
            escape(note)
        );
        return s;
    }
    let (t0, t1) = (t[0], t[t.len() - 1]);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in plot.series.iter().flat_map(|c| &c.values) {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    if hi - lo <= 1e-12 * hi.abs().max(lo.abs()) || hi - lo < f64::MIN_POSITIVE * 1e10 {
        let pad = if hi == 0.0 { 1.0 } else { 0.5 * hi.abs() };
        lo -= pad;
        hi += pad;
    }
    // A margin of 4 % so that no curve runs along the frame.
    let pad = 0.04 * (hi - lo);
    let (lo, hi) = (lo - pad, hi + pad);
    let (w, h) = (WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM);
    let x = |tt: f64| LEFT + w * (tt - t0) / (t1 - t0).max(f64::MIN_POSITIVE);
    let y = |v: f64| TOP + h * (hi - v) / (hi - lo);
    let _ = write!(
        s,
        "<figure><figcaption>{title}</figcaption><svg viewBox=\"0 0 {WIDTH} {HEIGHT}\" role=\"img\" \
         aria-label=\"{title}\"><rect x=\"{LEFT}\" y=\"{TOP}\" width=\"{w}\" height=\"{h}\" class=\"frame\"/>"
    );
    for v in ticks(lo, hi) {
        let yy = y(v);
        let _ = write!(
            s,
            "<line x1=\"{LEFT}\" x2=\"{:.1}\" y1=\"{yy:.1}\" y2=\"{yy:.1}\" class=\"grid\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" class=\"ty\">{}</text>",
            LEFT + w,
            LEFT - 4.0,
            yy + 4.0,
            tick(v)
        );
    }
    for v in ticks(t0, t1) {
        let xx = x(v);
        let _ = write!(
            s,
            "<line x1=\"{xx:.1}\" x2=\"{xx:.1}\" y1=\"{TOP}\" y2=\"{:.1}\" class=\"grid\"/>\
             <text x=\"{xx:.1}\" y=\"{:.1}\" class=\"tx\">{}</text>",
            TOP + h,
            TOP + h + 16.0,
            tick(v)
        );
    }
    let _ = write!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" class=\"tx\">t (s)</text>",
        LEFT + w - 12.0,
        HEIGHT - 2.0
    );
    let xs: Vec<f64> = t.iter().map(|tt| x(*tt)).collect();
    let mut lx = LEFT;
    for (k, c) in plot.series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let pts: Vec<String> = envelope(&xs, &c.values)
            .into_iter()
            .map(|i| format!("{:.1},{:.1}", xs[i], y(c.values[i])))
            .collect();
        let _ = write!(
            s,
            "<polyline points=\"{}\" stroke=\"{colour}\" class=\"curve\"/>\
             <rect x=\"{lx:.1}\" y=\"8\" width=\"14\" height=\"4\" fill=\"{colour}\"/>\
             <text x=\"{:.1}\" y=\"14\" class=\"legend\">{}</text>",
            pts.join(" "),
            lx + 18.0,
            escape(&c.name)
        );
        lx += 30.0 + 8.0 * c.name.chars().count() as f64;
    }
    s.push_str("</svg></figure>");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::html::motion::Series;

    /// A million samples of a fast oscillation give a plot of a few
    /// thousand points whose band still reaches the extremes.
    #[test]
    fn a_long_series_is_drawn_at_screen_resolution() {
        let n = 1_000_000;
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 1e-3).collect();
        let v: Vec<f64> = t.iter().map(|t| (50.0 * t).sin()).collect();
        let plot = Plot {
            title: "sin".into(),
            unit: String::new(),
            series: vec![Series {
                name: "x".into(),
                values: v,
            }],
            note: None,
        };
        let s = svg(&plot, &t);
        assert!(s.len() < 100_000, "{} bytes", s.len());
        let ys: Vec<f64> = s
            .split("points=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap()
            .split(' ')
            .map(|p| p.split(',').nth(1).unwrap().parse().unwrap())
            .collect();
        // The band's edges, 4 % inside the frame.
        let inner = 0.04 / 1.08 * (HEIGHT - TOP - BOTTOM);
        let (top, bottom) = (TOP + inner, HEIGHT - BOTTOM - inner);
        let min = ys.iter().cloned().fold(f64::INFINITY, f64::min);
        let max = ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (min - top).abs() < 0.2 && (max - bottom).abs() < 0.2,
            "{min} {max}"
        );
    }

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        for (lo, hi) in [
            (0.0, 1.0),
            (-3.2e-13, 7.9e-13),
            (0.5, 0.5000001),
            (-100.0, 2500.0),
        ] {
            let t = ticks(lo, hi);
            assert!((2..=6).contains(&t.len()), "{lo} {hi}: {t:?}");
            assert!(t.iter().all(|v| (lo..=hi).contains(v)), "{t:?}");
        }
    }
}
