//! Where each declared body is along the run, and which way is down: the
//! position in N of a body's reference point (its `point`), summed along
//! the chain of `at` vectors back to a fixed point — each vector compiled
//! on the tape in the state and turned into N by its frame's attitude —
//! and the derivation's gravity in N. A drawing of the run puts each
//! body's shapes where the body is, and up (against gravity) at the top.

use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::PointKind;
use hdot_sym::poly::Poly;
use hdot_sym::vector::Vec3;
use nalgebra::Vector3;

use super::DerivedModel;
use super::compile::{Compiled, Resolver};

/// A vector of a chain: its components, compiled, in the frame named.
#[derive(Debug, Clone)]
pub(super) struct Piece {
    frame: String,
    components: Compiled,
}

/// Where a body's reference point is: the pieces from the fixed point at
/// the root of its chain (that point's own place from N's origin the
/// first), or why it is not a function of the state.
pub(super) type Placement = Result<Vec<Piece>, String>;

/// The placement of every declared body, in the order of the
/// declarations, and the derivation's gravity, compiled.
pub(super) fn compile(
    d: &Derivation,
    cx: &Resolver<'_>,
) -> (Vec<(String, Placement)>, Option<Piece>) {
    (placements(d, cx), gravity(d, cx))
}

fn placements(d: &Derivation, cx: &Resolver<'_>) -> Vec<(String, Placement)> {
    d.physics
        .bodies
        .iter()
        .map(|b| {
            let placement = chain(d, &b.point).and_then(|vectors| {
                vectors
                    .into_iter()
                    .map(|(v, frame)| piece(d, cx, v, frame))
                    .collect()
            });
            (b.name.clone(), placement)
        })
        .collect()
}

/// The derivation's gravity (weight per unit mass), compiled; `None`
/// when it declares none or a symbol of it has no value.
fn gravity(d: &Derivation, cx: &Resolver<'_>) -> Option<Piece> {
    let (g, frame) = d.physics.gravity.as_ref()?;
    piece(d, cx, g, frame).ok()
}

fn piece(d: &Derivation, cx: &Resolver<'_>, v: &Vec3, frame: &str) -> Result<Piece, String> {
    let polys: Vec<Poly> = v.0.iter().map(|p| d.unfold(p)).collect();
    Ok(Piece {
        frame: frame.to_owned(),
        components: cx.compile(&polys).map_err(|e| e.to_string())?,
    })
}

/// The vectors (with their frames) from N's origin to the point `name`:
/// a declared point's `at` vectors back to the fixed point it hangs from,
/// or a body's mass centre placed from that body's reference point.
fn chain<'d>(d: &'d Derivation, name: &str) -> Result<Vec<(&'d Vec3, &'d str)>, String> {
    let ph = &d.physics;
    let mut out = Vec::new();
    let mut at = name;
    // Each step moves to another point: more steps than points and bodies
    // is a loop.
    for _ in 0..=ph.points.len() + ph.bodies.len() {
        if let Some(p) = ph.points.iter().find(|p| p.name == at) {
            match &p.kind {
                PointKind::Fixed(v, frame) => {
                    out.push((v, frame.as_str()));
                    out.reverse();
                    return Ok(out);
                }
                PointKind::From { from, at: v, frame } => {
                    out.push((v, frame.as_str()));
                    at = from;
                }
                PointKind::Free => {
                    return Err(format!(
                        "point `{at}` moves freely (the file declares no place for it)"
                    ));
                }
            }
        } else if let Some(b) = ph
            .bodies
            .iter()
            .find(|b| b.centre.as_deref() == Some(at) && b.point != at)
            && let Some(v) = &b.mass_centre
        {
            out.push((v, d.frames[b.frame].name.as_str()));
            at = &b.point;
        } else {
            return Err(format!(
                "`{at}` is placed by no `[[point]]` from a fixed point (a body free to move about \
                 its own centre)"
            ));
        }
    }
    Err(format!("point `{name}` is placed relative to itself"))
}

/// # Queries
impl DerivedModel {
    /// The bodies the derivation declares, in order.
    pub fn bodies(&self) -> impl Iterator<Item = &str> {
        self.placements.iter().map(|(b, _)| b.as_str())
    }

    /// The position in N of body `name`'s reference point (from N's
    /// origin) at `(t, y)`; an error saying why when it is not a function
    /// of the state (a point that moves freely, a body about its own
    /// centre placed by no point, a frame whose attitude is not known).
    pub fn position(&self, name: &str, t: f64, y: &[f64]) -> Result<Vector3<f64>, String> {
        let (_, placement) = self
            .placements
            .iter()
            .find(|(b, _)| b == name)
            .ok_or_else(|| format!("no body `{name}`"))?;
        let pieces = placement
            .as_ref()
            .map_err(|why| format!("the place of body `{name}` is not known: {why}"))?;
        let mut r = Vector3::zeros();
        for p in pieces {
            r += self.in_n(p, t, y)?;
        }
        Ok(r)
    }

    /// The derivation's gravity in N at `(t, y)` (its frame is inertial,
    /// so the state only places that frame); `None` when it declares none.
    pub fn gravity(&self, t: f64, y: &[f64]) -> Option<Vector3<f64>> {
        self.gravity.as_ref().and_then(|g| self.in_n(g, t, y).ok())
    }

    /// A piece's vector in N's components at `(t, y)`.
    fn in_n(&self, p: &Piece, t: f64, y: &[f64]) -> Result<Vector3<f64>, String> {
        let mut v = [0.0; 3];
        self.eval(&p.components, t, y, &mut v);
        Ok(self.attitude(&p.frame, t, y)? * Vector3::from(v))
    }
}
