//! `kane([u1, u2, …])`: Kane's equations of the declared bodies in the
//! generalized speeds — partial velocities of the mass centres and partial
//! angular velocities of the body frames, the generalized active forces
//! of gravity and the generalized inertia forces, written as
//! −(F_r + F_r*) = 0 for each speed.

use super::express::express_in;
use super::{Call, Op, coefficient};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::physics::{Body, PointKind};
use crate::derivation::value::Value;
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

pub(crate) const KANE: Op = Op {
    names: &["kane"],
    signature: "kane([u1, u2, …])",
    doc: "Kane's equations of the declared bodies for the listed generalized speeds: for each u_r, \
          Σ (v_G,r · m a_G + ω_r · (I_G α + ω × I_G ω)) − F_r, where v_G,r and ω_r are the partial velocities \
          of each mass centre and body frame and F_r the generalized active force of gravity (= −(F_r + F_r*), \
          zero along the motion); velocities are written in the speeds through `[kinematics]`. A list, one \
          equation per speed, linear in the speeds' rates",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    let cx = c.cx;
    let (us, _) = c.symbols(0)?;
    if cx.speeds.is_empty() {
        return c.err(
            c.span,
            "Kane's method needs generalized speeds: declare [symbols] speeds and a [kinematics] table",
        );
    }
    for (k, &u) in us.iter().enumerate() {
        if !cx.speeds.speeds.contains(&u) {
            let span = match &c.args[0].kind {
                crate::parse::AstKind::Vector { items, .. } => items[k].span,
                _ => c.args[0].span,
            };
            return c.err(
                span,
                format!("`{u}` is not a declared speed ([symbols] speeds)"),
            );
        }
    }
    if cx.physics.bodies.is_empty() {
        return c.err(
            c.span,
            "Kane's method sums over the declared bodies: declare them with [[body]]",
        );
    }
    let mut eqs = vec![Poly::zero(); us.len()];
    for b in &cx.physics.bodies {
        let terms = body_terms(c, b, &us)?;
        for (e, t) in eqs.iter_mut().zip(terms) {
            *e = &*e + &t;
        }
    }
    Ok(Value::list(eqs))
}

/// Body `b`'s share of each speed's equation: v_G,r · (m a_G − m g) +
/// ω_r · (I_G α + ω × I_G ω).
fn body_terms(c: &Call<'_, '_>, b: &Body, us: &[Atom]) -> R<Vec<Poly>> {
    let cx = c.cx;
    let name = &b.name;
    let Some(m) = b.mass.clone() else {
        return c.err(
            c.span,
            format!("body `{name}` has no `mass`: Kane's method needs it"),
        );
    };
    let Some(r) = b.mass_centre.clone() else {
        return c.err(
            c.span,
            format!("body `{name}` does not say where its mass centre is (`mass_centre`)"),
        );
    };
    let bi = b.frame;
    let speeds = |v: &Vec3, what: &str| in_speeds(c, v, what);
    let w = speeds(
        &cx.frames[bi].omega,
        &format!("the angular velocity of {name}"),
    )?;
    let (vp, fp) = point_velocity(c, &b.point, 0)?;
    let vp = express_in(cx, vp, fp, bi).ok_or_else(|| {
        cx.at(
            c.base,
            c.span,
            format!(
                "no chain of rotations relates the frame of point `{}` to body `{name}`'s",
                b.point
            ),
        )
    })?;
    let vg = speeds(
        &vp.add(&w.cross(&r)),
        &format!("the velocity of {name}'s mass centre"),
    )?;
    linear(c, &vg, &format!("the velocity of {name}'s mass centre"))?;
    linear(c, &w, &format!("the angular velocity of {name}"))?;
    let ag = speeds(&vg.dt().add(&w.cross(&vg)), "")?;
    let alpha = speeds(&w.dt(), "")?;
    let ig = if b.inertia_about_centre || r.is_zero() {
        b.inertia.clone()
    } else {
        // Parallel axes: I_G = I_P − m (|r|² E − r rᵀ).
        let rr = r.dot(&r);
        let shift = Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let d = if i == j { rr.clone() } else { Poly::zero() };
                &m * &(&d - &(&r.0[i] * &r.0[j]))
            })
        }));
        b.inertia.add(&shift.map(|p| -p))
    };
    let iw = ig.mul_vec(&w);
    let hdot = ig.mul_vec(&alpha).add(&w.cross(&iw));
    let mut force = ag.scale(&m);
    if let Some((g, gf)) = &cx.physics.gravity {
        let gi = cx.frame_index(gf).expect("gravity's frame exists");
        let g = express_in(cx, g.clone(), gi, bi).ok_or_else(|| {
            cx.at(
                c.base,
                c.span,
                format!("no chain of rotations relates gravity's frame {gf} to body `{name}`'s"),
            )
        })?;
        force = force.sub(&g.scale(&m));
    }
    Ok(us
        .iter()
        .map(|&u| {
            let vr = vg.map(|p| coefficient(p, u));
            let wr = w.map(|p| coefficient(p, u));
            &vr.dot(&force) + &wr.dot(&hdot)
        })
        .collect())
}

/// The velocity in N of the declared point `name` and the frame of its
/// components: zero for a fixed point, the velocity of the point it is
/// measured from plus the rate in N of the vector from it.
fn point_velocity(c: &Call<'_, '_>, name: &str, depth: usize) -> R<(Vec3, usize)> {
    let cx = c.cx;
    let Some(p) = cx.physics.points.iter().find(|p| p.name == name) else {
        return c.err(
            c.span,
            format!(
                "point `{name}` is a body's centre whose motion is not declared: place the body at a declared \
                 [[point]] (`point = …` with `from` and `at`) and give `mass_centre`"
            ),
        );
    };
    match &p.kind {
        PointKind::Fixed(..) => Ok((Vec3::zero(), 0)),
        PointKind::Free => c.err(
            c.span,
            format!(
                "point `{name}` moves freely: Kane's method needs its velocity; place it with `from` and `at`"
            ),
        ),
        PointKind::From { from, at, frame } => {
            // Declarations forbid cycles; the depth is a guard only.
            if depth > cx.physics.points.len() {
                return c.err(c.span, format!("point `{name}` leads back to itself"));
            }
            let (vf, ff) = point_velocity(c, from, depth + 1)?;
            let fi = cx.frame_index(frame).expect("the point's frame exists");
            let at = at.map(|p| cx.unfold(p));
            let w = in_speeds(c, &cx.frames[fi].omega, "")?;
            let rel = at.dt().add(&w.cross(&at));
            let vf = express_in(cx, vf, ff, fi).ok_or_else(|| {
                cx.at(
                    c.base,
                    c.span,
                    format!("no chain of rotations relates the frames of points `{from}` and `{name}`"),
                )
            })?;
            Ok((in_speeds(c, &vf.add(&rel), "")?, fi))
        }
    }
}

/// `v` in the speeds (`[kinematics]`); an error naming `what` when a rate
/// of a coordinate without a kinematic equation is left.
fn in_speeds(c: &Call<'_, '_>, v: &Vec3, what: &str) -> R<Vec3> {
    let cx = c.cx;
    let v = v.map(|p| cx.speeds.in_speeds(&cx.unfold(p)));
    let left =
        v.0.iter()
            .flat_map(Poly::atoms)
            .find(|a| a.order() > 0 && !cx.speeds.speeds.contains(&a.base()));
    match left {
        Some(a) => c.err(
            c.span,
            format!(
                "`{a}` occurs in {}: give `{}` a kinematic equation in [kinematics]",
                if what.is_empty() { "a velocity" } else { what },
                a.base()
            ),
        ),
        None => Ok(v),
    }
}

/// Checks that `v` is linear in the declared speeds (each term holds at
/// most one speed, to the first power).
fn linear(c: &Call<'_, '_>, v: &Vec3, what: &str) -> R<()> {
    let speeds = &c.cx.speeds.speeds;
    for p in &v.0 {
        for (m, _) in p.terms() {
            let degree: i32 = m
                .factors()
                .iter()
                .filter(|(a, _)| speeds.contains(a))
                .map(|f| f.1)
                .sum();
            if degree > 1
                || m.factors()
                    .iter()
                    .any(|(a, e)| speeds.contains(a) && *e < 0)
            {
                return c.err(
                    c.span,
                    format!("{what} is not linear in the speeds: the kinematic equations must be linear in them"),
                );
            }
        }
    }
    Ok(())
}
