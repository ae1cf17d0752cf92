//! Stored particle clouds in structure-of-arrays layout, from code or CSV.
//!
//! CSV format: one particle per line, `x,y,z,m`; an optional header line
//! whose first field is not a number (e.g. `x,y,z,m`); blank lines and
//! lines starting with `#` are skipped. Every error names the file, the
//! line and the field.

use std::path::{Path, PathBuf};

use nalgebra::Vector3;

use crate::error::{BodyError, CsvError, CsvErrorKind};
use crate::mass::MassProperties;
use crate::sums::{Block, LEAF, ParticleSource};

/// Point masses in world coordinates, stored as four arrays.
/// Invariant: non-empty, positions finite, masses finite and positive,
/// and the mass properties (total mass, centre, inertia) finite.
#[derive(Debug, Clone, PartialEq)]
pub struct ParticleCloud {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    m: Vec<f64>,
}

/// # Construction
impl ParticleCloud {
    /// A cloud from `(position, mass)` pairs, checked.
    ///
    /// # Example
    /// ```
    /// use hdot_num::ParticleCloud;
    /// use nalgebra::Vector3;
    /// let c = ParticleCloud::try_from_particles([(Vector3::x(), 1.0), (-Vector3::x(), 1.0)]).unwrap();
    /// let p = c.mass_properties();
    /// assert_eq!(p.mass, 2.0);
    /// assert_eq!(p.inertia_g.moments(), [0.0, 2.0, 2.0]);
    /// assert!(ParticleCloud::try_from_particles([(Vector3::x(), 0.0)]).is_err());
    /// ```
    pub fn try_from_particles(
        particles: impl IntoIterator<Item = (Vector3<f64>, f64)>,
    ) -> Result<Self, BodyError> {
        let particles = particles.into_iter();
        let n = particles.size_hint().0;
        let mut c = Self {
            x: Vec::with_capacity(n),
            y: Vec::with_capacity(n),
            z: Vec::with_capacity(n),
            m: Vec::with_capacity(n),
        };
        for (i, (p, m)) in particles.enumerate() {
            // The particle's name is formatted only for an error: clouds
            // are built per draw in `verify`, and the name cost more than
            // the checks.
            let what = || format!("particle {i}");
            for (field, value) in [("x", p.x), ("y", p.y), ("z", p.z)] {
                if !value.is_finite() {
                    return Err(BodyError::NotFinite {
                        what: what(),
                        field,
                        value,
                    });
                }
            }
            crate::mass::check_mass("", m).or_else(|_| crate::mass::check_mass(&what(), m))?;
            c.x.push(p.x);
            c.y.push(p.y);
            c.z.push(p.z);
            c.m.push(m);
        }
        if c.m.is_empty() {
            return Err(BodyError::Empty {
                what: "particle cloud".into(),
            });
        }
        if let Some((field, value)) = c.overflow() {
            return Err(BodyError::NotFinite {
                what: "particle cloud".into(),
                field,
                value,
            });
        }
        Ok(c)
    }

    /// The first of the cloud's mass properties that is not finite (the
    /// sums of finite particles can overflow), with its value: the
    /// invariant that [`ParticleCloud::mass_properties`] relies on.
    fn overflow(&self) -> Option<(&'static str, f64)> {
        let mass: f64 = self.m.iter().sum();
        if !mass.is_finite() {
            return Some(("mass", mass));
        }
        let p = crate::sums::mass_properties(self).ok()?;
        if let Some(x) = p.center.iter().find(|x| !x.is_finite()) {
            return Some(("mass centre", *x));
        }
        p.inertia_g
            .matrix()
            .iter()
            .find(|x| !x.is_finite())
            .map(|x| ("inertia", *x))
    }

    /// A cloud from four arrays, checked.
    pub fn try_from_arrays(
        x: Vec<f64>,
        y: Vec<f64>,
        z: Vec<f64>,
        m: Vec<f64>,
    ) -> Result<Self, BodyError> {
        if x.len() != m.len() || y.len() != m.len() || z.len() != m.len() {
            return Err(BodyError::BadDimension {
                what: "particle cloud".into(),
                field: "length",
                value: m.len() as f64,
                reason: "x, y, z and m must have the same length",
            });
        }
        Self::try_from_particles((0..m.len()).map(|i| (Vector3::new(x[i], y[i], z[i]), m[i])))
    }

    /// Reads a CSV file (see the module docs).
    pub fn from_csv_path(path: &Path) -> Result<Self, CsvError> {
        let text = hdot_sym::textfile::read(path).map_err(|e| CsvError {
            file: path.to_path_buf(),
            line: e.line_column().map_or(0, |(l, _)| l),
            field: "-".into(),
            kind: CsvErrorKind::Io(match e.line_column() {
                Some((_, c)) => format!("column {c}: {}", e.message),
                None => e.message,
            }),
        })?;
        Self::from_csv_str(path, &text)
    }

    /// Parses CSV text; `file` is the name used in errors.
    ///
    /// # Example
    /// ```
    /// use hdot_num::ParticleCloud;
    /// let e = ParticleCloud::from_csv_str("c.csv".as_ref(), "x,y,z,m\n0,0,0,1\n1,2,x3,1\n").unwrap_err();
    /// assert_eq!(e.to_string(), "c.csv:3: field `z`: not a number: \"x3\"");
    /// ```
    pub fn from_csv_str(file: &Path, text: &str) -> Result<Self, CsvError> {
        const FIELDS: [&str; 4] = ["x", "y", "z", "m"];
        let err = |line: usize, field: &str, kind| CsvError {
            file: PathBuf::from(file),
            line,
            field: field.to_string(),
            kind,
        };
        let mut cols: [Vec<f64>; 4] = Default::default();
        // The line of each particle, for an error found in the sums.
        let mut lines: Vec<usize> = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let t = raw.trim();
            if t.is_empty() || t.starts_with('#') {
                continue;
            }
            let parts: Vec<&str> = t.split(',').map(str::trim).collect();
            let is_header = cols[0].is_empty()
                && parts.first().is_some_and(|f| f.parse::<f64>().is_err())
                && parts.iter().all(|f| FIELDS.contains(f));
            if is_header {
                continue;
            }
            if parts.len() > 4 {
                return Err(err(line, "-", CsvErrorKind::TooMany(parts.len())));
            }
            for (k, name) in FIELDS.iter().enumerate() {
                let Some(s) = parts.get(k).filter(|s| !s.is_empty()) else {
                    return Err(err(line, name, CsvErrorKind::Missing));
                };
                let v: f64 = s
                    .parse()
                    .map_err(|_| err(line, name, CsvErrorKind::NotANumber(s.to_string())))?;
                if !v.is_finite() {
                    return Err(err(line, name, CsvErrorKind::NotFinite(v)));
                }
                if k == 3 && v <= 0.0 {
                    return Err(err(line, name, CsvErrorKind::NonPositiveMass(v)));
                }
                if k == 3 && v < f64::MIN_POSITIVE {
                    return Err(err(line, name, CsvErrorKind::TinyMass(v)));
                }
                cols[k].push(v);
            }
            lines.push(line);
        }
        if cols[3].is_empty() {
            return Err(err(0, "-", CsvErrorKind::Empty));
        }
        let [x, y, z, m] = cols;
        let c = Self { x, y, z, m };
        if let Some((what, _)) = c.overflow() {
            let (row, column) = c.overflow_at();
            return Err(err(lines[row], column, CsvErrorKind::Overflow(what)));
        }
        Ok(c)
    }

    /// Where the sums of an overflowing cloud overflow: the first particle
    /// whose mass, first or second moment takes a running sum past the
    /// largest number, and its column (`m`, or the coordinate `x`, `y`,
    /// `z` whose moment it is); when every running sum stays finite (the
    /// inertia about G overflows as a difference), the particle and
    /// coordinate with the largest second moment `m q²`.
    fn overflow_at(&self) -> (usize, &'static str) {
        const COORDS: [&str; 3] = ["x", "y", "z"];
        let mut mass = 0.0_f64;
        let mut first = [0.0_f64; 3];
        let mut second = [0.0_f64; 3];
        let mut largest = (0, "m", 0.0_f64);
        for i in 0..self.len() {
            let (p, m) = self.particle(i);
            mass += m;
            if !mass.is_finite() {
                return (i, "m");
            }
            for k in 0..3 {
                first[k] += m * p[k];
                second[k] += m * p[k] * p[k];
                if !(first[k].is_finite() && second[k].is_finite()) {
                    return (i, COORDS[k]);
                }
                if m * p[k] * p[k] > largest.2 {
                    largest = (i, COORDS[k], m * p[k] * p[k]);
                }
            }
        }
        (largest.0, largest.1)
    }
}

/// # Access
impl ParticleCloud {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.m.len()
    }
    /// Always false (a cloud is never empty).
    pub fn is_empty(&self) -> bool {
        self.m.is_empty()
    }
    /// The four arrays `(x, y, z, m)`.
    pub fn arrays(&self) -> (&[f64], &[f64], &[f64], &[f64]) {
        (&self.x, &self.y, &self.z, &self.m)
    }
    /// Particle `i` as `(position, mass)`.
    #[inline]
    pub fn particle(&self, i: usize) -> (Vector3<f64>, f64) {
        (Vector3::new(self.x[i], self.y[i], self.z[i]), self.m[i])
    }
    /// Mass properties by particle sums (exact for a cloud up to round-off).
    pub fn mass_properties(&self) -> MassProperties {
        crate::sums::mass_properties(self).expect("a cloud is non-empty with positive masses")
    }
    /// Stores all particles of any source (e.g. a discretised primitive).
    pub fn collect_from<S: ParticleSource + ?Sized>(src: &S) -> Result<Self, BodyError> {
        let n = src.len();
        let mut c = Self {
            x: Vec::with_capacity(n),
            y: Vec::with_capacity(n),
            z: Vec::with_capacity(n),
            m: Vec::with_capacity(n),
        };
        let mut lo = 0;
        while lo < n {
            let hi = (lo + LEAF).min(n);
            src.visit(lo, hi, &mut |b| {
                c.x.extend_from_slice(b.x);
                c.y.extend_from_slice(b.y);
                c.z.extend_from_slice(b.z);
                c.m.extend_from_slice(b.m);
            });
            lo = hi;
        }
        if c.m.is_empty() {
            return Err(BodyError::Empty {
                what: "particle cloud".into(),
            });
        }
        if let Some((field, value)) = c.overflow() {
            return Err(BodyError::NotFinite {
                what: "particle cloud".into(),
                field,
                value,
            });
        }
        Ok(c)
    }
}

impl ParticleSource for ParticleCloud {
    fn len(&self) -> usize {
        self.m.len()
    }
    fn visit(&self, lo: usize, hi: usize, f: &mut dyn FnMut(Block<'_>)) {
        f(Block {
            x: &self.x[lo..hi],
            y: &self.y[lo..hi],
            z: &self.z[lo..hi],
            m: &self.m[lo..hi],
        });
    }
}
