//! Reading a stability scene (`kind = "stability"`, docs/stability.md):
//! the derivation and its M, C, K steps, the constants, the sweep; and
//! the matrices compiled once in the parameter ([`LinearMatrices`]).
//!
//! ```toml
//! name = "sleeping top"
//! kind = "stability"
//! [derivation]
//! file = "sleeping-top"      # a derivation's name, or a path from this scene's folder
//! mass = "M"                 # steps: n × n arrays, columns in the coordinates' order
//! damping = "C"              # optional (zero when left out)
//! stiffness = "K"
//! [constants]
//! I = 0.02
//! [sweep]
//! parameter = "omega"        # a declared constant, not given under [constants]
//! from = 0.0
//! to = 100.0
//! count = 1000
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use hdot_num::eval::Tape;
use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::{Derivation, Value};
use hdot_sym::poly::Poly;
use hdot_sym::symbols::Decl;
use nalgebra::DMatrix;
use serde::Deserialize;
use toml::Spanned;

use crate::SimError;
use crate::scene::{Resolve, resolve_near};

/// The most values one sweep takes (its eigenvalues are kept in memory).
pub const MAX_COUNT: usize = 1_000_000;

/// The most coordinates a stability scene takes (A is 2n × 2n).
pub const MAX_DOF: usize = 32;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: String,
    #[serde(default)]
    description: String,
    #[allow(dead_code)] // checked before the rest is read
    kind: String,
    derivation: RawDerivation,
    #[serde(default)]
    constants: BTreeMap<String, Spanned<f64>>,
    sweep: RawSweep,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDerivation {
    file: Spanned<String>,
    mass: Spanned<String>,
    damping: Option<Spanned<String>>,
    stiffness: Spanned<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    parameter: Spanned<String>,
    from: Spanned<f64>,
    to: Spanned<f64>,
    count: Spanned<i64>,
}

/// A validated stability scene.
#[derive(Debug, Clone)]
pub struct StabilityScene {
    /// The scene's name.
    pub name: String,
    /// Free text.
    pub description: String,
    /// The scene file (as named in messages).
    pub file: PathBuf,
    /// The derivation the matrices come from.
    pub derivation: PathBuf,
    /// The constant swept.
    pub parameter: String,
    /// The first value of the sweep.
    pub from: f64,
    /// The last value of the sweep.
    pub to: f64,
    /// The number of values (at least 2), evenly spaced from `from` to `to`.
    pub count: usize,
    /// The compiled matrices.
    pub matrices: LinearMatrices,
}

/// Where an input of the matrices' tape comes from: the parameter, or
/// its sine or cosine.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Input {
    Value,
    Sin,
    Cos,
}

/// M, C and K compiled once: one tape whose outputs are their entries
/// (row-major, M then C then K) and whose only inputs are the parameter
/// (and its sine and cosine); every other constant is folded in.
#[derive(Debug, Clone)]
pub struct LinearMatrices {
    n: usize,
    tape: Tape,
    inputs: Vec<Input>,
    /// The steps holding M, C (if any) and K.
    steps: [Option<String>; 3],
}

/// # Construction
impl StabilityScene {
    /// Reads a stability scene; its derivation is found by [`resolve_near`].
    pub fn from_file(path: &Path) -> Result<StabilityScene, SimError> {
        let text = hdot_sym::textfile::read(path).map_err(|e| match e.io {
            Some(kind) => SimError::Io {
                file: path.to_path_buf(),
                source: std::io::Error::new(kind, e.message),
            },
            None => SimError::Parse {
                file: path.to_path_buf(),
                message: e.to_string(),
            },
        })?;
        StabilityScene::parse_with(&text, path, &|name| resolve_near(path, name))
    }

    /// Parses and validates a stability scene's text; `file` names it in
    /// messages, `resolve` finds its derivation.
    pub fn parse_with(
        text: &str,
        file: &Path,
        resolve: Resolve<'_>,
    ) -> Result<StabilityScene, SimError> {
        let parse_error = |e: toml::de::Error| SimError::Parse {
            file: file.to_path_buf(),
            message: e.to_string(),
        };
        // The kind first: a simulation scene is told so, not that its
        // fields are unknown here.
        let table: toml::Table = toml::from_str(text).map_err(parse_error)?;
        let kind = table.get("kind").and_then(|v| v.as_str()).unwrap_or("");
        if kind != "stability" {
            let line = text
                .lines()
                .position(|l| l.trim_start().starts_with("kind"))
                .map_or(String::new(), |k| format!("line {}: ", k + 1));
            return Err(SimError::BadField {
                file: file.to_path_buf(),
                field: "kind".into(),
                message: format!(
                    "{line}a stability scene has kind = \"stability\", not {} (a simulation \
                     scene is run by `hdot simulate`)",
                    if kind.is_empty() {
                        "none".to_string()
                    } else {
                        format!("\"{kind}\"")
                    }
                ),
            });
        }
        let raw: RawScene = toml::from_str(text).map_err(parse_error)?;
        let bad = |field: &str, span: std::ops::Range<usize>, message: String| SimError::BadField {
            file: file.to_path_buf(),
            field: field.to_string(),
            message: format!("line {}: {message}", line_at(text, span.start)),
        };
        let sw = &raw.sweep;
        let (from, to) = (*sw.from.get_ref(), *sw.to.get_ref());
        for (field, v) in [("sweep.from", &sw.from), ("sweep.to", &sw.to)] {
            if !v.get_ref().is_finite() {
                return Err(bad(
                    field,
                    v.span(),
                    format!("must be finite, got {}", v.get_ref()),
                ));
            }
        }
        if from >= to {
            return Err(bad(
                "sweep.to",
                sw.to.span(),
                format!("must be greater than sweep.from ({from}), got {to}"),
            ));
        }
        if !(to - from).is_finite() {
            return Err(bad(
                "sweep.to",
                sw.to.span(),
                format!("the range from {from} to {to} overflows"),
            ));
        }
        let count = *sw.count.get_ref();
        if !(2..=MAX_COUNT as i64).contains(&count) {
            return Err(bad(
                "sweep.count",
                sw.count.span(),
                format!("must be from 2 to {MAX_COUNT}, got {count}"),
            ));
        }
        for (k, v) in &raw.constants {
            if !v.get_ref().is_finite() {
                return Err(bad(
                    &format!("constants.{k}"),
                    v.span(),
                    format!("must be finite, got {}", v.get_ref()),
                ));
            }
        }
        let rd = &raw.derivation;
        let (path, dtext) =
            resolve(rd.file.get_ref()).map_err(|e| bad("derivation.file", rd.file.span(), e))?;
        let d = hdot_sym::derivation::load_str(&path.display().to_string(), &dtext)
            .map_err(|e| bad("derivation.file", rd.file.span(), e.to_string()))?;
        let declared: Vec<&str> = d
            .symbols
            .names()
            .iter()
            .filter(|n| d.symbols.get(n) == Some(&Decl::Constant))
            .map(String::as_str)
            .collect();
        let parameter = sw.parameter.get_ref().clone();
        if !declared.contains(&parameter.as_str()) {
            return Err(bad(
                "sweep.parameter",
                sw.parameter.span(),
                format!(
                    "`{parameter}` is not a constant of {} (its constants: {})",
                    path.display(),
                    declared.join(", ")
                ),
            ));
        }
        let mut constants = BTreeMap::new();
        for (k, v) in &raw.constants {
            if !declared.contains(&k.as_str()) {
                return Err(bad(
                    &format!("constants.{k}"),
                    v.span(),
                    format!(
                        "`{k}` is not a constant of {} (its constants: {})",
                        path.display(),
                        declared.join(", ")
                    ),
                ));
            }
            if *k == parameter {
                return Err(bad(
                    &format!("constants.{k}"),
                    v.span(),
                    format!("`{k}` is the swept parameter: its values are the sweep's"),
                ));
            }
            constants.insert(k.clone(), *v.get_ref());
        }
        let steps = [
            ("derivation.mass", Some(&rd.mass)),
            ("derivation.damping", rd.damping.as_ref()),
            ("derivation.stiffness", Some(&rd.stiffness)),
        ];
        let matrices = LinearMatrices::new(&d, &steps, &constants, &parameter).map_err(
            |(field, message)| {
                let span = steps
                    .iter()
                    .find(|(f, _)| *f == field)
                    .and_then(|(_, s)| s.map(|s| s.span()))
                    .unwrap_or(0..0);
                bad(field, span, format!("{}: {message}", path.display()))
            },
        )?;
        Ok(StabilityScene {
            name: raw.name,
            description: raw.description,
            file: file.to_path_buf(),
            derivation: path,
            parameter,
            from,
            to,
            count: count as usize,
            matrices,
        })
    }

    /// The sweep's values: `count` evenly spaced from `from` to `to`
    /// (both included, the last exactly `to`), each the double nearest to
    /// the decimal it stands for (`grid.rs`: 0.9, not 0.8999999999999999).
    pub fn values(&self) -> Vec<f64> {
        super::grid::values(self.from, self.to, self.count)
    }
}

/// The 1-based line of byte `offset` in `text`.
fn line_at(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// # Construction
impl LinearMatrices {
    /// Compiles the steps `steps` names (M, C or none, K) of `d`, with
    /// `constants` folded in and `parameter` the tape's one input. An
    /// error names the scene's field and what is wrong.
    fn new(
        d: &Derivation,
        steps: &[(&'static str, Option<&Spanned<String>>); 3],
        constants: &BTreeMap<String, f64>,
        parameter: &str,
    ) -> Result<LinearMatrices, (&'static str, String)> {
        let mut n = None;
        let mut polys: [Option<Vec<Poly>>; 3] = [None, None, None];
        for (k, (field, step)) in steps.iter().enumerate() {
            let Some(step) = step else { continue };
            let name = step.get_ref();
            let s = d.steps.iter().find(|s| &s.name == name).ok_or_else(|| {
                (
                    *field,
                    format!(
                        "no step named `{name}` (steps: {})",
                        d.steps
                            .iter()
                            .map(|s| s.name.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })?;
            let rows: Vec<Vec<Poly>> = match &s.value {
                Value::Array(rows) => rows.clone(),
                Value::Matrix(m) => m.0.iter().map(|r| r.to_vec()).collect(),
                Value::Scalar(p) => vec![vec![p.clone()]],
                v => {
                    return Err((
                        *field,
                        format!(
                            "step `{name}` is {}, not a square matrix (write it as \
                             jacobian(eqs, [q1'', q2'', …]) or a matrix literal)",
                            v.describe()
                        ),
                    ));
                }
            };
            let size = rows.len();
            if size == 0 || rows.iter().any(|r| r.len() != size) {
                return Err((
                    *field,
                    format!("step `{name}` is {}, not square", s.value.describe()),
                ));
            }
            match n {
                None => n = Some(size),
                Some(m) if m != size => {
                    return Err((
                        *field,
                        format!(
                            "step `{name}` is {size}×{size}, but the matrices before it are \
                             {m}×{m}: M, C and K are of one size (one row per coordinate)"
                        ),
                    ));
                }
                _ => {}
            }
            polys[k] = Some(rows.iter().flatten().map(|p| d.unfold(p)).collect());
        }
        let n = n.unwrap_or(0);
        if n > MAX_DOF {
            return Err((
                "derivation.mass",
                format!("{n} coordinates; a stability scene takes 1 to {MAX_DOF}"),
            ));
        }
        // Every atom must be a constant with a value, the parameter, or
        // sin or cos of one: the linearised matrices do not depend on the
        // state.
        for (k, (field, step)) in steps.iter().enumerate() {
            let (Some(step), Some(ps)) = (step, &polys[k]) else {
                continue;
            };
            for (e, p) in ps.iter().enumerate() {
                for a in p.atoms() {
                    check_atom(a, constants, parameter).map_err(|why| {
                        (
                            *field,
                            format!(
                                "step `{}`, entry ({}, {}): {why}",
                                step.get_ref(),
                                e / n + 1,
                                e % n + 1
                            ),
                        )
                    })?;
                }
            }
        }
        let zero = vec![Poly::zero(); n * n];
        let all: Vec<Poly> = polys
            .iter()
            .flat_map(|p| p.as_ref().unwrap_or(&zero).iter().cloned())
            .collect();
        let tape = Tape::compile_with(&all, &mut |a| value_of(a, constants));
        let inputs = tape
            .atoms()
            .iter()
            .map(|&a| match a.kind() {
                AtomKind::Sin(_) => Input::Sin,
                AtomKind::Cos(_) => Input::Cos,
                AtomKind::Var { .. } | AtomKind::Sum { .. } => Input::Value,
            })
            .collect();
        Ok(LinearMatrices {
            n,
            tape,
            inputs,
            steps: [0, 1, 2].map(|k| steps[k].1.map(|s| s.get_ref().clone())),
        })
    }
}

/// Why atom `a` cannot appear in a linearised matrix, if it cannot.
fn check_atom(a: Atom, constants: &BTreeMap<String, f64>, parameter: &str) -> Result<(), String> {
    let q = match a.kind() {
        AtomKind::Sin(q) | AtomKind::Cos(q) => q,
        AtomKind::Var { .. } => a,
        AtomKind::Sum { sum, .. } => {
            if sum.atoms().iter().any(|b| b.name() == parameter) {
                return Err(format!(
                    "the parameter `{parameter}` occurs in the sum {a} that the matrices divide by: \
                     sweep a parameter that is not in a denominator"
                ));
            }
            return sum
                .atoms()
                .into_iter()
                .try_for_each(|b| check_atom(b, constants, parameter));
        }
    };
    if q.is_time_dependent() {
        return Err(format!(
            "`{a}` depends on `{}`, a function of time: the linearised matrices must be \
             constant (substitute the operating point, e.g. subst(K, theta = 0))",
            q.name()
        ));
    }
    if q.name() != parameter && !constants.contains_key(q.name()) {
        return Err(format!(
            "the constant `{}` has no value: give it under the scene's [constants]",
            q.name()
        ));
    }
    Ok(())
}

/// The value of a constant atom (or sin/cos of one) the tape folds in;
/// `None` for the parameter.
fn value_of(a: Atom, constants: &BTreeMap<String, f64>) -> Option<f64> {
    match a.kind() {
        AtomKind::Sin(q) => constants.get(q.name()).map(|v| v.sin()),
        AtomKind::Cos(q) => constants.get(q.name()).map(|v| v.cos()),
        AtomKind::Var { name, .. } => constants.get(name).copied(),
        // Folded by the tape from its atoms' values.
        AtomKind::Sum { .. } => None,
    }
}

/// # Evaluation
impl LinearMatrices {
    /// The number of coordinates n (A is 2n × 2n).
    pub fn dof(&self) -> usize {
        self.n
    }

    /// The steps holding M, C (`None` when the scene gives none) and K.
    pub fn steps(&self) -> &[Option<String>; 3] {
        &self.steps
    }

    /// M, C and K at parameter value `p`, row-major, one after the other
    /// (3 n² values), into `out`; `scratch` is the tape's work space.
    pub fn eval(&self, p: f64, scratch: &mut Vec<f64>, out: &mut [f64]) {
        let (s, c) = p.sin_cos();
        let inputs: Vec<f64> = self
            .inputs
            .iter()
            .map(|i| match i {
                Input::Value => p,
                Input::Sin => s,
                Input::Cos => c,
            })
            .collect();
        self.tape.eval_with(&inputs, scratch, out, false);
    }

    /// The state matrix A = [[0, I], [−M⁻¹K, −M⁻¹C]] at `p` (state
    /// (q, q̇)); an error when an entry is not finite or M is singular.
    pub fn state_matrix(&self, p: f64, scratch: &mut Vec<f64>) -> Result<DMatrix<f64>, String> {
        let n = self.n;
        let mut mck = vec![0.0; 3 * n * n];
        self.eval(p, scratch, &mut mck);
        let names = ["M", "C", "K"];
        if let Some(k) = mck.iter().position(|v| !v.is_finite()) {
            let which = k / (n * n);
            let e = k % (n * n);
            return Err(format!(
                "entry ({}, {}) of {} (step `{}`) is {}",
                e / n + 1,
                e % n + 1,
                names[which],
                self.steps[which].as_deref().unwrap_or("?"),
                mck[k]
            ));
        }
        let m = DMatrix::from_row_slice(n, n, &mck[..n * n]);
        let sv = m.singular_values();
        let (lo, hi) = (sv.min(), sv.max());
        if lo.is_nan() || lo <= 1e-13 * hi {
            return Err(format!(
                "the mass matrix M (step `{}`) is singular (singular values from {lo:.3e} to \
                 {hi:.3e})",
                self.steps[0].as_deref().unwrap_or("?")
            ));
        }
        let lu = m.lu();
        let c = DMatrix::from_row_slice(n, n, &mck[n * n..2 * n * n]);
        let k = DMatrix::from_row_slice(n, n, &mck[2 * n * n..]);
        let (Some(mk), Some(mc)) = (lu.solve(&k), lu.solve(&c)) else {
            return Err(format!(
                "the mass matrix M (step `{}`) cannot be factorised",
                self.steps[0].as_deref().unwrap_or("?")
            ));
        };
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
            for j in 0..n {
                a[(n + i, j)] = -mk[(i, j)];
                a[(n + i, n + j)] = -mc[(i, j)];
            }
        }
        Ok(a)
    }
}
