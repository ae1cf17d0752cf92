//! Binding a derivation's declared symbols to numbers: the values (and
//! size bounds) of its symbols, and the symbols of its `[[body]]` and
//! `gravity` declarations solved from the mass properties of given bodies.
//!
//! Both floors above the bodies use it: `hdot verify` binds the symbols of
//! the random bodies it draws ([`crate::verify`]), and a simulation binds
//! those of the bodies a derived scene gives (`hdot-sim`'s derived
//! scenes), so neither reaches into the other.

use std::collections::BTreeMap;

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::Body;
use hdot_sym::poly::Poly;
use nalgebra::{Matrix3, Vector3};
use rustc_hash::FxHashMap;

/// Why symbols could not be bound.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BindError {
    /// An expression uses a symbol that has no value (the symbol as
    /// printed).
    #[error("{0} has no value")]
    Unbound(String),
    /// The declarations cannot be met by the given bodies (or solved for
    /// their symbols).
    #[error("{derivation}: {message}")]
    Declaration {
        /// Derivation name.
        derivation: String,
        /// What is wrong.
        message: String,
    },
}

fn declaration(d: &Derivation, message: String) -> BindError {
    BindError::Declaration {
        derivation: d.name.clone(),
        message,
    }
}

/// Values of symbols (constants, and time symbols with their derivative
/// order) and bounds on their sizes.
///
/// Looked up for every factor of every term a verification evaluates, so
/// keyed by Fx (an atom is a small integer; the std's SipHash was a
/// quarter of the nonlinear bicycle's instructions); the map's order is
/// never what a result depends on (every iteration below is per entry,
/// sorted or collected into an ordered map).
#[derive(Clone, Debug, Default)]
pub struct Values {
    map: FxHashMap<Atom, (f64, f64)>,
}

/// The `n`th derivative of a time atom.
pub(crate) fn nth(a: Atom, n: u32) -> Atom {
    Atom::time(a.name(), a.order() + n)
}

impl Values {
    /// Value and size of an atom (sin and cos of a bound angle included).
    pub fn get(&self, a: Atom) -> Option<(f64, f64)> {
        match a.kind() {
            AtomKind::Var { .. } => self.map.get(&a).copied(),
            AtomKind::Sin(q) => self.map.get(&q).map(|v| (v.0.sin(), 1.0)),
            AtomKind::Cos(q) => self.map.get(&q).map(|v| (v.0.cos(), 1.0)),
            // A sum of constants: its value, and the sum of its terms'
            // magnitudes as its size.
            AtomKind::Sum { sum, .. } => {
                let mut known = true;
                let (mut v, mut size) = (0.0, 0.0);
                for (m, c) in sum.terms() {
                    let (mut t, mut s) = (c.to_f64(), c.to_f64().abs());
                    for &(b, e) in m.factors() {
                        let (bv, bs) = self.get(b).unwrap_or_else(|| {
                            known = false;
                            (f64::NAN, f64::NAN)
                        });
                        t *= bv.powi(e);
                        s *= bs.powi(e);
                    }
                    v += t;
                    size += s.abs();
                }
                known.then_some((v, size))
            }
        }
    }

    /// The `n`th derivative of time atom `a`.
    pub fn time(&self, a: Atom, n: u32) -> Option<(f64, f64)> {
        self.get(nth(a, n))
    }

    pub(crate) fn set(&mut self, a: Atom, v: f64, size: f64) {
        self.map.insert(a, (v, size.abs()));
    }

    /// These values with every small symbol (and each derivative of one)
    /// times `h`: the disturbance scaled.
    pub(crate) fn scale_small(&self, small: &[Atom], h: f64) -> Values {
        let mut out = self.clone();
        for (a, v) in out.map.iter_mut() {
            if a.is_time_dependent() && small.contains(&a.base()) {
                v.0 *= h;
                v.1 *= h.abs();
            }
        }
        out
    }

    /// These values with `a` set to `v` (of size |v|).
    pub(crate) fn with(&self, a: Atom, v: f64) -> Values {
        let mut out = self.clone();
        out.set(a, v, v);
        out
    }

    /// A fingerprint of every value's and size's bits that does not
    /// depend on the map's order (a sum of one hash per entry, no sort):
    /// values with the same bits have the same fingerprint; whether they
    /// are the same is [`Values::same_bits`].
    pub(crate) fn fingerprint(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        self.map.iter().fold(0u64, |h, (a, (v, s))| {
            let mut f = rustc_hash::FxHasher::default();
            (a, v.to_bits(), s.to_bits()).hash(&mut f);
            h.wrapping_add(f.finish())
        })
    }

    /// Whether `other` binds the same atoms to values and sizes of the
    /// same bits (`0.0` and `-0.0` differ here): every computation from
    /// them gives the same bits.
    pub(crate) fn same_bits(&self, other: &Values) -> bool {
        self.map.len() == other.map.len()
            && self.map.iter().all(|(a, (v, s))| {
                other
                    .map
                    .get(a)
                    .is_some_and(|(w, t)| w.to_bits() == v.to_bits() && t.to_bits() == s.to_bits())
            })
    }

    /// A fingerprint of these values as a state of the atoms `reads`
    /// (sorted): the bits of each read atom's value and size, every other
    /// atom by its presence only; a sum of one hash per entry (no sort).
    /// Values that are the same state have the same fingerprint; whether
    /// they are is [`Values::same_state`].
    pub(crate) fn state_fingerprint(&self, reads: &[Atom]) -> u64 {
        use std::hash::{Hash, Hasher};
        self.map.iter().fold(0u64, |h, (a, (v, s))| {
            let mut f = rustc_hash::FxHasher::default();
            if reads.binary_search(a).is_ok() {
                (a, v.to_bits(), s.to_bits()).hash(&mut f);
            } else {
                a.hash(&mut f);
            }
            h.wrapping_add(f.finish())
        })
    }

    /// Whether `other` binds the same atoms, those of `reads` (sorted) to
    /// values and sizes of the same bits: the same state of `reads`.
    pub(crate) fn same_state(&self, other: &Values, reads: &[Atom]) -> bool {
        self.map.len() == other.map.len()
            && self.map.iter().all(|(a, (v, s))| {
                other.map.get(a).is_some_and(|(w, t)| {
                    reads.binary_search(a).is_err()
                        || (w.to_bits() == v.to_bits() && t.to_bits() == s.to_bits())
                })
            })
    }

    pub(crate) fn unset(&mut self, a: Atom) {
        self.map.remove(&a);
    }

    pub(crate) fn bound(&self, a: Atom) -> bool {
        self.get(a).is_some()
    }

    /// Value and size (Σ |terms| with each atom at its size) of `p`.
    ///
    /// # Errors
    /// [`BindError::Unbound`] naming the first atom without a value.
    pub fn eval(&self, p: &Poly) -> Result<(f64, f64), BindError> {
        let (mut v, mut s) = (0.0, 0.0);
        for (m, c) in p.terms() {
            let (mut tv, mut ts) = (c.to_f64(), c.to_f64().abs());
            for &(a, e) in m.factors() {
                let (x, sx) = self
                    .get(a)
                    .ok_or_else(|| BindError::Unbound(a.to_string()))?;
                tv *= x.powi(e);
                ts *= if e < 0 { x.abs() } else { sx }.powi(e);
            }
            v += tv;
            s += ts;
        }
        Ok((v, s))
    }
}

/// Binds the one unbound symbol of each `(poly, target)` (linear in it),
/// as long as progress is made; checks those without one.
pub(crate) fn bind_all(
    d: &Derivation,
    values: &mut Values,
    mut eqs: Vec<(Poly, f64, f64, String)>,
) -> Result<(), BindError> {
    loop {
        let before = eqs.len();
        let mut rest = Vec::new();
        for (p, target, size, what) in eqs {
            let unbound: Vec<Atom> = {
                let mut u: Vec<Atom> = p
                    .atoms()
                    .into_iter()
                    .map(|a| match a.kind() {
                        AtomKind::Sin(q) | AtomKind::Cos(q) => q,
                        _ => a,
                    })
                    .filter(|a| !values.bound(*a))
                    .collect();
                u.sort_by_key(|a| a.sort_key());
                u.dedup();
                u
            };
            match unbound.as_slice() {
                [] => {
                    let (v, s) = values.eval(&p)?;
                    if (v - target).abs() > 1e-9 * (s + size.abs() + target.abs()) {
                        return Err(declaration(
                            d,
                            format!(
                                "{what} is declared {} = {v:e} but the body has {target:e}: the declared symmetry does not make it so",
                                p.to_source()
                            ),
                        ));
                    }
                }
                [s] if p.terms().iter().all(|(m, _)| m.exponent(*s) <= 1)
                    && Atom::sin(*s).is_none_or(|x| !p.contains(x))
                    && Atom::cos(*s).is_none_or(|x| !p.contains(x)) =>
                {
                    let coef = p.partial(*s);
                    let rest = p.subst(&mut |a| (a == *s).then(Poly::zero));
                    let (c, _) = values.eval(&coef)?;
                    let (r, _) = values.eval(&rest)?;
                    if c == 0.0 {
                        return Err(declaration(
                            d,
                            format!("{what}: cannot solve {} for {s}", p.to_source()),
                        ));
                    }
                    values.set(*s, (target - r) / c, size / c.abs());
                }
                _ => rest.push((p, target, size, what)),
            }
        }
        if rest.is_empty() {
            return Ok(());
        }
        if rest.len() == before {
            let (p, _, _, what) = &rest[0];
            return Err(declaration(
                d,
                format!(
                    "{what}: {} has more than one symbol not bound yet (bind all but one elsewhere)",
                    p.to_source()
                ),
            ));
        }
        eqs = rest;
    }
}

/// What a given body has for a derivation's `[[body]]`, in the body
/// frame's axes: its mass, G from the reference point, and the inertia
/// tensor about the point the declared inertia is about.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasuredBody {
    /// Σ m.
    pub mass: f64,
    /// G from the reference point.
    pub centre: Vector3<f64>,
    /// Σ m (|ρ|² E − ρ ρᵀ) about the reference point, or about G when the
    /// declaration's inertia is about the centre.
    pub inertia: Matrix3<f64>,
}

/// Binds the symbols of a derivation's body declarations (mass,
/// `mass_centre`, inertia) from given bodies, one per declared body
/// (`None`: not given), with the symbols `given` already known; a
/// declared entry the bodies do not meet is an error naming it; the
/// file's `gravity` (declared in N) binds its symbols from `gravity`, a
/// vector in N's axes, when given. Returns every constant bound this way,
/// by name. A simulation binds its bodies' symbols so (`hdot_sim::scene`,
/// derived scenes), and verification those of the bodies it draws.
pub fn bind_bodies(
    d: &Derivation,
    measured: &[Option<MeasuredBody>],
    gravity: Option<Vector3<f64>>,
    given: &BTreeMap<String, f64>,
) -> Result<BTreeMap<String, f64>, BindError> {
    let mut values = Values::default();
    for (name, v) in given {
        values.set(Atom::constant(name), *v, *v);
    }
    let mut eqs = Vec::new();
    if let Some(g) = gravity {
        let declared = d.physics.gravity.as_ref().filter(|(_, f)| f == "N");
        let Some((v, _)) = declared else {
            return Err(declaration(
                d,
                "a gravity vector is given but the file declares no gravity in N".into(),
            ));
        };
        for k in 0..3 {
            eqs.push((
                v.0[k].clone(),
                g[k],
                g.norm(),
                format!("component {} of gravity", k + 1),
            ));
        }
    }
    for (b, m) in d.physics.bodies.iter().zip(measured) {
        if let Some(m) = m {
            eqs.extend(declared_equations(b, m, true));
        }
    }
    bind_all(d, &mut values, eqs)?;
    Ok(values
        .map
        .iter()
        .filter(|(a, _)| !given.contains_key(a.name()))
        .map(|(a, (v, _))| (a.name().to_string(), *v))
        .collect())
}

/// The declarations of `b` as equations on a body's measured properties
/// (those of `mass_centre` when `with_centre`).
pub(crate) fn declared_equations(
    b: &Body,
    m: &MeasuredBody,
    with_centre: bool,
) -> Vec<(Poly, f64, f64, String)> {
    let (mass, c, i) = (m.mass, m.centre, m.inertia);
    // The body's extent: the size positions are computed to.
    let extent = (i.trace() / mass).sqrt() + c.norm();
    let mut eqs: Vec<_> = b
        .mass
        .iter()
        .map(|p| (p.clone(), mass, mass, format!("the mass of {}", b.name)))
        .collect();
    for k in (0..3).filter(|_| b.mass_centre.is_some() && with_centre) {
        eqs.push((
            b.mass_centre.as_ref().expect("declared").0[k].clone(),
            c[k],
            extent,
            format!("component {} of the mass centre of {}", k + 1, b.name),
        ));
    }
    let size = 0.5 * i.trace();
    for r in 0..3 {
        for s in r..3 {
            eqs.push((
                b.inertia.0[r][s].clone(),
                i[(r, s)],
                size,
                format!("inertia entry ({}, {}) of {}", r + 1, s + 1, b.name),
            ));
        }
    }
    eqs
}
