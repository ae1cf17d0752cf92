//! Frames turned by Euler parameters (a unit quaternion): the rotation
//! `rotation = "quaternion(e_0, e_1, e_2, e_3)"` of a `[[frame]]`, its
//! direction cosine matrix (the textbook's, quadratic in the e's), the
//! frame's angular velocity derived from that matrix (the axial vector of
//! Cᵀ Ċ), and the reduction of any polynomial modulo the unit norm
//! e₀² + e₁² + e₂² + e₃² = 1.
//!
//! # The reduction modulo the norm
//!
//! Every value of a file with a quaternion frame is held with e₀ to at
//! most the first power: each e₀² is replaced by 1 − e₁² − e₂² − e₃². The
//! ideal (e·e − 1) is principal with leading monomial e₀², so the
//! remainder is the unique normal form of a polynomial in the ring
//! modulo the norm, and two values equal on the unit sphere are identical
//! after it (the canonical equality of `poly.rs`, extended). The rates of
//! the e's are not reduced (e·ė = 0 is not a rewriting rule): they are
//! replaced by the kinematic equations ė = ½ E(e)ᵀ ω (`attitude.rs`),
//! which keep e·ė = 0 identically.

use super::context::{Context, R};
use crate::atom::Atom;
use crate::parse::{Ast, AstKind, Span};
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

/// The name of the rotation: `quaternion(e_0, e_1, e_2, e_3)`.
pub(crate) const QUATERNION: &str = "quaternion";

/// The four Euler parameters of a `quaternion(…)` rotation, each a
/// declared function of time, none twice (`span` is the call's, at
/// `base` in the file).
pub(crate) fn parameters(cx: &Context<'_>, args: &[Ast], span: Span, base: usize) -> R<[Atom; 4]> {
    let usage = "Euler parameters are written quaternion(e_0, e_1, e_2, e_3): the scalar part first, \
                 four functions of time ([symbols] time)";
    let [a0, a1, a2, a3] = args else {
        return Err(cx.at(base, span, usage));
    };
    let mut e: Vec<Atom> = Vec::with_capacity(4);
    for a in [a0, a1, a2, a3] {
        let AstKind::Name { name, primes: 0 } = &a.kind else {
            return Err(cx.at(base, a.span, usage));
        };
        let atom = cx
            .symbols
            .atom(name, 0, a.span)
            .map_err(|err| cx.at(base, err.span, err.message))?;
        if !atom.is_time_dependent() {
            return Err(cx.at(base, a.span, format!("`{name}` is a constant: {usage}")));
        }
        if e.contains(&atom) {
            return Err(cx.at(
                base,
                a.span,
                format!("`{name}` is named twice: the four Euler parameters differ"),
            ));
        }
        e.push(atom);
    }
    Ok([e[0], e[1], e[2], e[3]])
}

/// The direction cosine matrix of the Euler parameters `e` (scalar part
/// first), taking the turned frame's components to its parent's
/// (`v_parent = C v_child`, as [`Mat3::rotation`]): for a turn by θ about
/// the unit axis λ, e₀ = cos(θ/2) and (e₁, e₂, e₃) = λ sin(θ/2),
/// C = (e₀² − ε·ε) 1 + 2 ε εᵀ + 2 e₀ [ε×] (Kane, Likins & Levinson,
/// *Spacecraft Dynamics*, §1.3), reduced modulo the norm.
pub(crate) fn direction_cosines(e: &[Atom; 4]) -> Mat3 {
    homogeneous(e).map(|x| reduce(x, e))
}

/// The direction cosine matrix as written, homogeneous of degree two in
/// the parameters: |e|² times a rotation for every e, so that Cᵀ Ċ is
/// |e|⁴ times the skew matrix of the angular velocity whatever the norm
/// (the reduced matrix's rate would differ from it by multiples of e·ė).
fn homogeneous(e: &[Atom; 4]) -> Mat3 {
    let p = |i: usize| Poly::atom(e[i]);
    let eps = Vec3::new([p(1), p(2), p(3)]);
    let diag = &(&p(0) * &p(0)) - &eps.dot(&eps);
    let two = Poly::int(2);
    let mut m = Mat3::identity().map(|x| x * &diag);
    for i in 0..3 {
        for j in 0..3 {
            let outer = &two * &(&eps.0[i] * &eps.0[j]);
            m.0[i][j] = &m.0[i][j] + &outer;
        }
    }
    // 2 e₀ [ε×]: (i, j) = −2 e₀ ε_k for (i, j, k) cyclic, +2 e₀ ε_k for (j, i).
    for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
        let t = &two * &(&p(0) * &eps.0[k]);
        m.0[i][j] = &m.0[i][j] - &t;
        m.0[j][i] = &m.0[j][i] + &t;
    }
    m
}

/// The angular velocity of the frame turned by the parameters `e`
/// relative to its parent, in its own components: the axial vector of the
/// skew-symmetric part of Cᵀ Ċ (C the homogeneous direction cosine
/// matrix), reduced modulo the norm (where it is 2 E(e) ė).
pub(crate) fn relative_angular_velocity(e: &[Atom; 4]) -> Vec3 {
    let c = homogeneous(e);
    let w = c.transpose().mul(&c.map(Poly::dt));
    let half = |a: &Poly, b: &Poly| {
        let d = a - b;
        reduce(
            &d.scale(&crate::rational::Rational::new(1, 2).expect("1/2")),
            e,
        )
    };
    Vec3::new([
        half(&w.0[2][1], &w.0[1][2]),
        half(&w.0[0][2], &w.0[2][0]),
        half(&w.0[1][0], &w.0[0][1]),
    ])
}

/// The rate of the norm's defining constraint ½ d/dt (e·e − 1) = e·ė, a
/// row of the kinematic equations beside the angular velocity's three.
pub(crate) fn norm_rate(e: &[Atom; 4]) -> Poly {
    let norm = e.iter().fold(Poly::zero(), |acc, &x| {
        &acc + &(&Poly::atom(x) * &Poly::atom(x))
    });
    (&norm - &Poly::one())
        .dt()
        .scale(&crate::rational::Rational::new(1, 2).expect("1/2"))
}

/// `p` modulo e₀² + e₁² + e₂² + e₃² = 1: each e₀^(2j+r) replaced by
/// (1 − e₁² − e₂² − e₃²)^j e₀^r (module doc).
pub fn reduce(p: &Poly, e: &[Atom; 4]) -> Poly {
    if !p.terms().iter().any(|(m, _)| m.exponent(e[0]) >= 2) {
        return p.clone();
    }
    let rest = e[1..].iter().fold(Poly::one(), |acc, &x| {
        &acc - &(&Poly::atom(x) * &Poly::atom(x))
    });
    let mut out = Poly::zero();
    for (m, c) in p.terms() {
        let k = m.exponent(e[0]);
        if k < 2 {
            out = &out + &Poly::term(m.clone(), c.clone());
            continue;
        }
        let kept = m.without(e[0], k - k % 2);
        let mut t = Poly::term(kept, c.clone());
        for _ in 0..k / 2 {
            t = &t * &rest;
        }
        out = &out + &t;
    }
    out
}

/// `p` reduced modulo the norm of every quaternion in `norms`.
pub fn reduce_all(p: &Poly, norms: &[[Atom; 4]]) -> Poly {
    norms.iter().fold(p.clone(), |acc, e| reduce(&acc, e))
}

/// A monomial's power of `e₀` is at most one after [`reduce`] (for tests).
#[cfg(test)]
fn reduced(p: &Poly, e0: Atom) -> bool {
    p.terms().iter().all(|(m, _)| m.exponent(e0) < 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Symbols;

    fn setup() -> (Symbols, [Atom; 4]) {
        let s = Symbols::parse_decl(&[], &["e_0", "e_1", "e_2", "e_3"]);
        let e = ["e_0", "e_1", "e_2", "e_3"].map(|n| Atom::time(n, 0));
        (s, e)
    }

    #[test]
    fn the_direction_cosines_are_orthogonal_on_the_unit_sphere() {
        let (_, e) = setup();
        let c = direction_cosines(&e);
        let ctc = c.transpose().mul(&c).map(|x| reduce(x, &e));
        for i in 0..3 {
            for j in 0..3 {
                let want = if i == j { Poly::one() } else { Poly::zero() };
                assert_eq!(ctc.0[i][j], want, "(CᵀC)[{i}][{j}]");
            }
        }
    }

    #[test]
    fn a_turn_about_z_is_the_elementary_rotation() {
        // e = (cos θ/2, 0, 0, sin θ/2): C(0,0) = 1 − 2 e₃² = cos θ, C(1,0) = 2 e₀ e₃ = sin θ.
        let (s, e) = setup();
        let c = direction_cosines(&e);
        assert_eq!(c.0[0][0], s.poly("1 - 2*e_2^2 - 2*e_3^2").unwrap());
        assert_eq!(c.0[1][0], s.poly("2*e_1*e_2 + 2*e_0*e_3").unwrap());
        assert_eq!(c.0[0][1], s.poly("2*e_1*e_2 - 2*e_0*e_3").unwrap());
    }

    #[test]
    fn the_reduction_leaves_e0_to_the_first_power_and_is_exact() {
        let (s, e) = setup();
        let p = s.poly("e_0^5*e_1 + e_0^2 + e_1^2 + e_2^2 + e_3^2").unwrap();
        let r = reduce(&p, &e);
        assert!(reduced(&r, e[0]));
        let want = s.poly("e_0*e_1*(1 - e_1^2 - e_2^2 - e_3^2)^2 + 1").unwrap();
        assert_eq!(r, want);
    }

    #[test]
    fn the_derived_angular_velocity_is_twice_e_times_the_rates() {
        let (s, e) = setup();
        let w = relative_angular_velocity(&e);
        // Kane, Likins & Levinson (1.3.21), written out.
        let want = [
            "2*(e_0*e_1' - e_1*e_0' + e_3*e_2' - e_2*e_3')",
            "2*(e_0*e_2' - e_2*e_0' + e_1*e_3' - e_3*e_1')",
            "2*(e_0*e_3' - e_3*e_0' + e_2*e_1' - e_1*e_2')",
        ];
        for (k, w_k) in want.iter().enumerate() {
            assert_eq!(w.0[k], s.poly(w_k).unwrap(), "ω component {k}");
        }
    }
}
