//! Reading a scene's text: the place of a value (line of a byte offset),
//! errors that name the file, line and field, and the checks every value
//! passes (finite numbers, three-component vectors, non-zero directions).

use std::path::Path;

use nalgebra::Vector3;
use toml::Spanned;

use super::SceneError;
use crate::body::MassProperties;

pub(super) type V3 = [f64; 3];
/// A vector as written: checked for three finite components when read,
/// so that a fourth component or a NaN is an error at the key's line.
pub(super) type RV = Spanned<Vec<f64>>;
/// A number as written, with its place.
pub(super) type RF = Spanned<f64>;

/// The byte offsets of a text's line breaks, found once, so that the line
/// of an offset is a binary search: a scene of N bodies asks N times, and
/// counting from the start each time made loading quadratic in N.
pub(super) struct Lines(Vec<usize>);

impl Lines {
    pub(super) fn new(text: &str) -> Lines {
        Lines(text.match_indices('\n').map(|(i, _)| i).collect())
    }

    /// Line (1-based) of a byte offset.
    pub(super) fn of(&self, offset: usize) -> usize {
        self.0.partition_point(|&nl| nl < offset) + 1
    }
}

pub(super) fn v3(a: V3) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// The file being read, for errors that name a line and a field.
pub(super) struct Cx<'a> {
    pub(super) file: &'a Path,
    pub(super) text: &'a str,
    pub(super) lines: Lines,
}

impl<'a> Cx<'a> {
    pub(super) fn new(file: &'a Path, text: &'a str) -> Cx<'a> {
        Cx {
            file,
            text,
            lines: Lines::new(text),
        }
    }

    pub(super) fn err(&self, line: usize, field: &str, message: String) -> SceneError {
        SceneError {
            file: self.file.to_path_buf(),
            line,
            field: field.to_string(),
            message,
        }
    }

    /// The line a value is written on (that of its key, unless the value
    /// itself spans lines).
    pub(super) fn line<T>(&self, v: &Spanned<T>) -> usize {
        self.lines.of(v.span().start)
    }

    /// A number, checked finite.
    pub(super) fn scalar(&self, field: &str, v: &RF) -> Result<f64, SceneError> {
        let x = *v.get_ref();
        if !x.is_finite() {
            return Err(self.err(self.line(v), field, format!("not finite: {x}")));
        }
        Ok(x)
    }

    /// A vector, checked to have three finite components.
    pub(super) fn vec3(&self, field: &str, v: &RV) -> Result<V3, SceneError> {
        let c = v.get_ref();
        let line = self.line(v);
        let Ok(a) = <V3>::try_from(c.as_slice()) else {
            return Err(self.err(
                line,
                field,
                format!("a vector has 3 components, not {}", c.len()),
            ));
        };
        if let Some(x) = a.iter().find(|x| !x.is_finite()) {
            return Err(self.err(line, field, format!("not finite: {x}")));
        }
        Ok(a)
    }

    /// A direction: a non-zero vector, normalised without overflow.
    pub(super) fn unit(&self, field: &str, v: &RV) -> Result<Vector3<f64>, SceneError> {
        let a = self.vec3(field, v)?;
        unit_of(&v3(a)).ok_or_else(|| self.err(self.line(v), field, "zero vector".into()))
    }
}

/// `|v|` without overflow or underflow of the squares (components of 1e200
/// or 1e-200 are fine).
pub(super) fn safe_norm(v: &Vector3<f64>) -> f64 {
    let m = v.amax();
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * (v / m).norm()
}

/// `v / |v|` without overflow or underflow; `None` for the zero vector.
pub fn unit_of(v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let m = v.amax();
    if m == 0.0 || !m.is_finite() {
        return None;
    }
    let w = v / m;
    Some(w / w.norm())
}

pub(super) fn props_finite(p: &MassProperties) -> bool {
    p.mass.is_finite()
        && p.center.iter().all(|x| x.is_finite())
        && p.inertia_g.matrix().iter().all(|x| x.is_finite())
}
