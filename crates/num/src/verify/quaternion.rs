//! Frames turned by Euler parameters in a verification: the attitude jet
//! of such a frame (its direction cosine matrix, a polynomial in the
//! parameters, and its rates evaluated at the draw), and the draw of the
//! parameters on the unit sphere, where the derivation's values hold.

use hdot_sym::atom::Atom;
use hdot_sym::derivation::Derivation;
use hdot_sym::vector::Mat3;
use nalgebra::Matrix3;

use super::VerifyError;
use super::jet::{MatJet, ORDERS, mat_mat_to};
use super::world::poly_jet_to;
use crate::bind::Values;

/// The attitude jet and `∂R/∂q` of a frame turned from its parent (jet
/// `parent`, partial `parent_partial`) by the direction cosine matrix `c`
/// in the parameters `e`; `coordinate` is the world's coordinate, when it
/// is one of them.
pub(crate) fn turned(
    parent: &MatJet,
    parent_partial: &Matrix3<f64>,
    c: &Mat3,
    e: &[Atom; 4],
    coordinate: Option<Atom>,
    values: &Values,
    orders: usize,
) -> Result<(MatJet, Matrix3<f64>), VerifyError> {
    let mut rot: MatJet = [Matrix3::zeros(); ORDERS];
    for i in 0..3 {
        for j in 0..3 {
            let jet = poly_jet_to(&c.0[i][j], values, orders)?;
            for (n, v) in jet.iter().enumerate() {
                rot[n][(i, j)] = *v;
            }
        }
    }
    let jet = mat_mat_to(parent, &rot, orders);
    let mut partial = parent_partial * rot[0];
    if let Some(q) = coordinate.filter(|q| e.contains(q)) {
        let mut dc = Matrix3::zeros();
        for i in 0..3 {
            for j in 0..3 {
                dc[(i, j)] = values.eval(&c.0[i][j].partial(q))?.0;
            }
        }
        partial += parent[0] * dc;
    }
    Ok((jet, partial))
}

/// Scales the drawn Euler parameters of every quaternion frame of `d` to
/// unit norm (their rates, drawn afterwards from the kinematic equations,
/// keep it: e·ė = 0).
pub(crate) fn on_unit_sphere(d: &Derivation, values: &mut Values) {
    for e in &d.speeds.unit_norms {
        let drawn: Vec<Option<(f64, f64)>> = e.iter().map(|&x| values.get(x)).collect();
        let Some(drawn) = drawn.into_iter().collect::<Option<Vec<_>>>() else {
            continue;
        };
        let norm = drawn.iter().map(|(v, _)| v * v).sum::<f64>().sqrt();
        if norm > 0.0 {
            for (&x, (v, _)) in e.iter().zip(drawn) {
                values.set(x, v / norm, 1.0);
            }
        }
    }
}
