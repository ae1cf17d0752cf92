//! The revolute-joint shorthand of a frame's `rotation`: `about([k_x, k_y,
//! k_z], q)` turns the parent by the angle q about the hinge axis k, a unit
//! vector of constants in the parent's components — the rotation matrix
//! R = cos q E + sin q [k]× + (1 − cos q) k kᵀ (Rodrigues), which for a
//! coordinate axis is the `x(q)`, `y(q)`, `z(q)` of any other frame.

use super::context::{Context, R};
use crate::atom::Atom;
use crate::parse::{Ast, AstKind, Span};
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

/// The name of the shorthand in a `rotation` string.
pub(crate) const ABOUT: &str = "about";

/// The hinge axis `axis` (the first argument of `about`, a vector literal
/// in the parent's components) and the matrix taking the child's
/// components to the parent's for the angle `q`. Errors name the axis:
/// a component that varies in time, a zero vector, a vector not of unit
/// length.
pub(crate) fn hinge(cx: &Context<'_>, axis: &Ast, q: Atom, base: usize) -> R<(Mat3, Vec3)> {
    let at = |span: Span, msg: String| cx.at(base, span, msg);
    let AstKind::Vector { items, frame: None } = &axis.kind else {
        return Err(at(
            axis.span,
            "the hinge axis is a vector literal in the parent frame's components, such as \
             [sin(lambda), 0, cos(lambda)]"
                .into(),
        ));
    };
    let k = cx.three_scalars(items, axis.span, base)?;
    let k = k.map(|p| cx.unfold(p));
    if let Some(a) =
        k.0.iter()
            .flat_map(Poly::atoms)
            .find(|a| a.is_time_dependent())
    {
        return Err(at(
            axis.span,
            format!("the hinge axis is fixed in the parent frame: `{a}` varies in time"),
        ));
    }
    let norm2 = k.dot(&k);
    if norm2.is_zero() {
        return Err(at(axis.span, "the hinge axis has zero length".into()));
    }
    if norm2 != Poly::one() {
        return Err(at(
            axis.span,
            format!(
                "the hinge axis must be a unit vector, but its squared length is {norm2}: divide it by its length"
            ),
        ));
    }
    let (c, s) = (
        Poly::atom(Atom::cos(q).expect("an angle symbol")),
        Poly::atom(Atom::sin(q).expect("an angle symbol")),
    );
    let one_c = &Poly::one() - &c;
    let [kx, ky, kz] = &k.0;
    let skew = Mat3([
        [Poly::zero(), -kz, ky.clone()],
        [kz.clone(), Poly::zero(), -kx],
        [-ky, kx.clone(), Poly::zero()],
    ]);
    let r = Mat3(std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let d = if i == j { c.clone() } else { Poly::zero() };
            &(&d + &(&s * &skew.0[i][j])) + &(&one_c * &(&k.0[i] * &k.0[j]))
        })
    }));
    Ok((r, k))
}
