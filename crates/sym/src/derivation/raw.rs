//! The TOML layer of derivation files: plain data with source spans.

use serde::Deserialize;
use toml::Spanned;

use super::Diagnostic;

/// A whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawFile {
    pub title: String,
    pub source: String,
    #[serde(default)]
    pub summary: String,
    #[serde(default)]
    pub assumptions: Vec<String>,
    #[serde(default)]
    pub symbols: RawSymbols,
    #[serde(default, rename = "abbreviation")]
    pub abbreviations: Vec<RawAbbrev>,
    #[serde(default, rename = "frame")]
    pub frames: Vec<RawFrame>,
    #[serde(default, rename = "step")]
    pub steps: Vec<RawStep>,
    /// Resource limits for this file (crate::limits).
    pub limits: Option<RawLimits>,
    /// The weight per unit mass, a vector expression (`physics/declare.rs`).
    pub gravity: Option<Spanned<String>>,
    #[serde(default, rename = "point")]
    pub points: Vec<RawPoint>,
    #[serde(default, rename = "body")]
    pub bodies: Vec<RawBody>,
    #[serde(default, rename = "known")]
    pub knowns: Vec<RawKnown>,
    #[serde(default, rename = "support")]
    pub supports: Vec<RawSupport>,
    pub motion: Option<RawMotion>,
    /// `[kinematics]`: each coordinate's rate in the coordinates and the
    /// speeds (`speeds.rs`), or a table from which a frame's angles' rates
    /// are derived (`attitude.rs`).
    pub kinematics: Option<std::collections::BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    /// `[[load]]`: forces at points and torques on frames (`loads.rs`).
    #[serde(default, rename = "load")]
    pub loads: Vec<RawLoad>,
    /// `[[contact]]`: wheels rolling on the ground (`contact.rs`).
    #[serde(default, rename = "contact")]
    pub contacts: Vec<RawContact>,
}

/// `[[contact]]` (`contact.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawContact {
    pub name: Spanned<String>,
    pub wheel: Spanned<String>,
    pub centre: Option<Spanned<String>>,
    pub frame: Option<Spanned<String>>,
    pub axle: Spanned<String>,
    pub down: Spanned<String>,
    pub radius: Spanned<String>,
    pub angle: Option<Spanned<String>>,
    pub plane: Option<Spanned<String>>,
}

/// `[[load]]` (`loads.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLoad {
    pub point: Option<Spanned<String>>,
    pub force: Option<Spanned<String>>,
    pub frame: Option<Spanned<String>>,
    pub torque: Option<Spanned<String>>,
}

/// `[[support]]` (`physics/supports.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSupport {
    pub name: Spanned<String>,
    #[serde(default)]
    pub doc: String,
    pub kind: Spanned<String>,
    pub body: Option<Spanned<String>>,
    pub point: Option<Spanned<String>>,
    pub axis: Option<Spanned<String>>,
    pub carries: Option<Spanned<String>>,
    pub friction: Option<Spanned<bool>>,
}

/// `[[point]]` (`physics/bodies.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPoint {
    pub name: Spanned<String>,
    #[serde(default)]
    pub doc: String,
    pub fixed: Option<Spanned<bool>>,
    pub from: Option<Spanned<String>>,
    pub at: Option<Spanned<String>>,
}

/// `[[body]]` (`physics/bodies.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBody {
    pub name: Spanned<String>,
    #[serde(default)]
    pub doc: String,
    pub frame: Spanned<String>,
    pub point: Option<Spanned<String>>,
    pub centre: Option<Spanned<String>>,
    pub mass: Option<Spanned<String>>,
    pub mass_centre: Option<Spanned<String>>,
    pub inertia: Spanned<String>,
    /// The point `inertia` is about: the reference point (default) or the
    /// body's centre.
    pub inertia_about: Option<Spanned<String>>,
    pub symmetry: Option<Spanned<String>>,
}

/// `[[known]]` (`physics/declare.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawKnown {
    pub value: Spanned<String>,
    pub means: Spanned<String>,
}

/// `[motion]` (`physics/declare.rs`).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMotion {
    #[serde(default)]
    pub given: Vec<Spanned<String>>,
    #[serde(default)]
    pub vanishes: Vec<Spanned<String>>,
}

/// `[limits]`: overrides of [`crate::limits::Limits`].
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLimits {
    pub max_terms: Option<usize>,
    pub max_work: Option<u64>,
    pub max_exponent: Option<u32>,
    pub max_bits: Option<u64>,
}

impl RawLimits {
    /// `base` with the settings this table gives.
    pub fn over(&self, base: crate::limits::Limits) -> crate::limits::Limits {
        crate::limits::Limits {
            max_terms: self.max_terms.unwrap_or(base.max_terms),
            max_work: self.max_work.unwrap_or(base.max_work),
            max_exponent: self.max_exponent.unwrap_or(base.max_exponent),
            max_bits: self.max_bits.unwrap_or(base.max_bits),
        }
    }
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSymbols {
    #[serde(default)]
    pub constants: Vec<Spanned<String>>,
    #[serde(default)]
    pub time: Vec<Spanned<String>>,
    /// Functions of time that are small (first order) for `linearize`.
    #[serde(default)]
    pub small: Vec<Spanned<String>>,
    /// Declared constants known to be positive, for `sign`.
    #[serde(default)]
    pub positive: Vec<Spanned<String>>,
    /// The order constant factors are written in a product (present.rs).
    #[serde(default)]
    pub order: Vec<Spanned<String>>,
    /// Generalized speeds, functions of time, in order (`speeds.rs`).
    #[serde(default)]
    pub speeds: Vec<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawAbbrev {
    pub name: Spanned<String>,
    pub value: Spanned<String>,
    #[serde(default)]
    pub doc: String,
    /// What it means, verified like a step's (`physics/conditions.rs`).
    pub means: Option<Spanned<String>>,
    #[serde(default)]
    pub given: Vec<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawFrame {
    pub name: Spanned<String>,
    #[serde(default)]
    pub doc: String,
    /// Ω relative to N, in this frame's components.
    pub angular_velocity: Option<Spanned<String>>,
    /// The frame this one is turned from.
    pub parent: Option<Spanned<String>>,
    /// `z(phi)`: turned by `phi` about the parent's z axis.
    pub rotation: Option<Spanned<String>>,
    /// Axis names (default x, y, z).
    pub axes: Option<Spanned<Vec<String>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStep {
    pub name: Spanned<String>,
    pub value: Spanned<String>,
    pub label: Option<Spanned<String>>,
    #[serde(default)]
    pub doc: String,
    #[serde(default = "yes")]
    pub show: bool,
    pub expect: Option<Spanned<toml::Value>>,
    pub collect: Option<Spanned<Vec<String>>>,
    pub fold: Option<Spanned<Vec<String>>>,
    /// Known factors to print brackets as products of: `["A - B", "A - C"]`.
    pub factor: Option<Spanned<Vec<String>>>,
    /// What the step means physically (`physics/means.rs`).
    pub means: Option<Spanned<String>>,
    /// Conditions on the motion under which `means` holds.
    #[serde(default)]
    pub given: Vec<Spanned<String>>,
    /// Symmetries the bodies have for this step's `means` (besides their
    /// own): `{ body = "principal" }`.
    pub symmetry: Option<Spanned<std::collections::BTreeMap<String, Spanned<String>>>>,
    /// The step's value stays constant along every motion the equations
    /// of the file describe (a simulation reports its drift).
    #[serde(default)]
    pub conserved: bool,
}

fn yes() -> bool {
    true
}

/// What to write for a required field a table left out, by field name:
/// appended to the reader's "missing field" error.
const MISSING_FIELD_HINTS: &[(&str, &str)] = &[(
    "inertia",
    "every [[body]] states its inertia tensor about its point in its frame's axes: \
     `principal(A, B, C)`, `inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx)` with products of inertia, \
     or `principal(0, 0, 0)` for a point mass (docs/derivation-format.md, `[[body]]`)",
)];

pub(crate) fn parse(path: &str, text: &str) -> Result<RawFile, Diagnostic> {
    toml::from_str::<RawFile>(text).map_err(|e| {
        let span = e.span().unwrap_or(0..0);
        let message = e.message().trim();
        let hint = MISSING_FIELD_HINTS
            .iter()
            .find(|(f, _)| message == format!("missing field `{f}`"))
            .map(|(_, h)| format!(": {h}"))
            .unwrap_or_default();
        Diagnostic::at(
            path,
            text,
            span.start,
            span.end,
            format!("invalid derivation file: {message}{hint}"),
        )
    })
}

/// The byte ranges of the contents of the string literals inside
/// `text[start..end]` (basic `"…"`, literal `'…'`, and their triple-quoted
/// forms), in order.
pub(crate) fn string_contents(text: &str, start: usize, end: usize) -> Vec<(usize, usize)> {
    literals(text, start, end)
        .into_iter()
        .map(|(s, e, _)| (s, e))
        .collect()
}

/// Maps an offset into a string's value, written as the string's content
/// start in the file plus an offset into its unescaped value (as the spans
/// of parsed expressions are), to the offset in the file: an escape such
/// as `\t`, `\"` or `\u00e9` takes more bytes in the file than in the
/// value, and a caret after it would otherwise fall short. Offsets outside
/// a basic string are returned unchanged.
pub(crate) fn file_offset(text: &str, pos: usize) -> usize {
    let bytes = text.as_bytes();
    let Some((start, end, _)) = literals(text, 0, text.len())
        .into_iter()
        .find(|&(s, e, q)| q == b'"' && s <= pos && pos <= e)
    else {
        return pos;
    };
    let (mut i, mut v) = (start, start);
    while v < pos && i < end {
        if bytes[i] != b'\\' {
            i += 1;
            v += 1;
            continue;
        }
        let hex = |n: usize| {
            text.get(i + 2..i + 2 + n)
                .and_then(|h| u32::from_str_radix(h, 16).ok())
                .and_then(char::from_u32)
                .map_or(1, char::len_utf8)
        };
        match bytes.get(i + 1) {
            Some(b'u') => (i, v) = (i + 6, v + hex(4)),
            Some(b'U') => (i, v) = (i + 10, v + hex(8)),
            // A line-ending backslash drops the whitespace that follows.
            Some(b' ' | b'\t' | b'\r' | b'\n') => {
                i += 1;
                while i < end && bytes[i].is_ascii_whitespace() {
                    i += 1;
                }
            }
            _ => (i, v) = (i + 2, v + 1),
        }
    }
    i.min(end)
}

/// [`string_contents`] with the opening quote of each literal.
fn literals(text: &str, start: usize, end: usize) -> Vec<(usize, usize, u8)> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = start;
    while i < end.min(bytes.len()) {
        let q = bytes[i];
        if q == b'"' || q == b'\'' {
            let triple = bytes.get(i..i + 3) == Some(&[q, q, q][..]);
            let open = if triple { 3 } else { 1 };
            let mut j = i + open;
            if triple && bytes.get(j) == Some(&b'\n') {
                j += 1;
            }
            let cstart = j;
            while j < bytes.len() {
                if q == b'"' && bytes[j] == b'\\' {
                    j += 2;
                    continue;
                }
                if bytes[j] == q && (!triple || bytes.get(j..j + 3) == Some(&[q, q, q][..])) {
                    break;
                }
                j += 1;
            }
            out.push((cstart, j.min(bytes.len()), q));
            i = j + open;
        } else if q == b'#' {
            while i < end && bytes[i] != b'\n' {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    out
}
