//! `kane([u1, …])` and `kane([u1, …], constraints, [u4, …])`: Kane's
//! equations of the declared bodies in the generalized speeds — partial
//! velocities of the mass centres and partial angular velocities of the
//! body frames (with dependent speeds eliminated through constraints
//! linear in the speeds), the generalized active forces of gravity and the
//! generalized inertia forces, written as −(F_r + F_r*) = 0 for each
//! independent speed.

use super::mass_matrix::linear_system;
use super::solve::solve_system;
use super::velocity::{Speedmap, linear_in_speeds};
use super::{Call, Op, coefficient};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::multibody::Load;
use crate::derivation::physics::Body;
use crate::derivation::value::Value;
use crate::parse::AstKind;
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

pub(crate) const KANE: Op = Op {
    names: &["kane"],
    signature: "kane([u1, u2, …]), kane([u1, …], constraints, [u4, …])",
    doc: "Kane's equations of the declared bodies for the listed (independent) generalized speeds: for each u_r, \
          Σ (v_G,r · (m a_G − m g) + ω_r · (I_G α + ω × I_G ω)), where v_G,r and ω_r are the partial velocities \
          of each mass centre and body frame and g is `gravity`, less v_P,r · F and ω_r · T of each `[[load]]` \
          (= −(F_r + F_r*), zero along the motion); \
          velocities are written in the speeds through `[kinematics]`. With constraints (a vector or `list` \
          that vanishes, linear in the speeds, such as `rolling(B, P)`) the dependent speeds listed last are \
          solved for and eliminated. A list, one equation per independent speed, linear in their rates",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    if c.args.len() != 1 {
        c.arity(3)?;
    }
    let cx = c.cx;
    if cx.speeds.is_empty() {
        return c.err(
            c.span,
            "Kane's method needs generalized speeds: declare [symbols] speeds and a [kinematics] table",
        );
    }
    let us = speeds_arg(c, 0, &[])?;
    let sp = match c.args.len() {
        3 => {
            let deps = speeds_arg(c, 2, &us)?;
            Speedmap {
                c,
                dependent: dependent_speeds(c, &deps)?,
            }
        }
        _ => Speedmap::plain(c),
    };
    if cx.physics.bodies.is_empty() {
        return c.err(
            c.span,
            "Kane's method sums over the declared bodies: declare them with [[body]]",
        );
    }
    let mut eqs = vec![Poly::zero(); us.len()];
    for b in &cx.physics.bodies {
        let terms = body_terms(&sp, b, &us)?;
        for (e, t) in eqs.iter_mut().zip(terms) {
            *e = &*e + &t;
        }
    }
    for l in &cx.loads {
        let terms = load_terms(&sp, l, &us)?;
        for (e, t) in eqs.iter_mut().zip(terms) {
            *e = &*e - &t;
        }
    }
    Ok(Value::list(eqs))
}

/// A `[[load]]`'s generalized active force for each speed: v_P,r · F for a
/// force at P, ω_r · T for a torque on a frame.
fn load_terms(sp: &Speedmap<'_, '_, '_>, l: &Load, us: &[Atom]) -> R<Vec<Poly>> {
    let cx = sp.c.cx;
    let (v, f) = match l {
        Load::Force {
            point,
            force,
            frame,
        } => {
            let (v, fv) = sp.point_velocity(point, 0)?;
            let what = format!("the velocity of point {point}");
            (sp.vec(&v, &what)?, sp.express(force.clone(), *frame, fv)?)
        }
        Load::Torque {
            on,
            torque,
            in_frame,
        } => {
            let what = format!("the angular velocity of {}", cx.frames[*on].name);
            (
                sp.vec(&cx.frames[*on].omega, &what)?,
                sp.express(torque.clone(), *in_frame, *on)?,
            )
        }
    };
    linear_in_speeds(sp.c, &v.0, "a loaded point's or frame's velocity")?;
    unlisted(sp, &v, us, "a load")?;
    let f = f.map(|p| sp.poly(p));
    Ok(us
        .iter()
        .map(|&u| v.map(|p| coefficient(p, u)).dot(&f))
        .collect())
}

/// An error when a declared speed that is neither listed nor dependent
/// occurs in `v` (its partial velocity would be lost).
fn unlisted(sp: &Speedmap<'_, '_, '_>, v: &Vec3, us: &[Atom], of: &str) -> R<()> {
    let c = sp.c;
    let left =
        v.0.iter()
            .flat_map(Poly::atoms)
            .find(|a| c.cx.speeds.speeds.contains(a) && !us.contains(a));
    match left {
        Some(u) => c.err(
            c.span,
            format!(
                "`{u}` occurs in the velocities of {of} but is not listed: list it with the speeds, or as a \
                 dependent speed with the constraints that determine it"
            ),
        ),
        None => Ok(()),
    }
}

/// Argument `i`: declared speeds in brackets, none of them in `taken`.
fn speeds_arg(c: &Call<'_, '_>, i: usize, taken: &[Atom]) -> R<Vec<Atom>> {
    let (us, _) = c.symbols(i)?;
    for (k, &u) in us.iter().enumerate() {
        let span = match &c.args[i].kind {
            AstKind::Vector { items, .. } => items[k].span,
            _ => c.args[i].span,
        };
        if !c.cx.speeds.speeds.contains(&u) {
            return c.err(
                span,
                format!("`{u}` is not a declared speed ([symbols] speeds)"),
            );
        }
        if taken.contains(&u) {
            return c.err(
                span,
                format!("`{u}` is listed as independent and as dependent"),
            );
        }
    }
    Ok(us)
}

/// The constraints (argument 1) solved for the dependent speeds `deps`.
fn dependent_speeds(c: &Call<'_, '_>, deps: &[Atom]) -> R<Vec<(Atom, Poly)>> {
    let span = c.args[1].span;
    let v = c.value(1)?;
    let Some(eqs) = v.equations() else {
        return c.err(
            span,
            format!(
                "the constraints are a vector or a list that vanishes, found {}",
                v.describe()
            ),
        );
    };
    let plain = Speedmap::plain(c);
    let eqs: Vec<Poly> = eqs
        .iter()
        .map(|p| plain.poly(p))
        .filter(|p| !p.is_zero())
        .collect();
    if let Some(a) = eqs.iter().flat_map(Poly::atoms).find(|a| a.order() > 0) {
        return c.err(
            span,
            format!(
                "`{a}` occurs in the constraints: they are written in the coordinates and the speeds (give `{}` a kinematic equation)",
                a.base()
            ),
        );
    }
    let at = |msg: String| c.cx.at(c.base, span, msg);
    linear_in_speeds(c, &eqs, "a constraint").map_err(|e| at(e.message))?;
    if eqs.len() != deps.len() {
        return Err(at(format!(
            "{} independent constraint equation{} for {} dependent speed{}: give one dependent speed per constraint",
            eqs.len(),
            if eqs.len() == 1 { "" } else { "s" },
            deps.len(),
            if deps.len() == 1 { "" } else { "s" },
        )));
    }
    let (m, f) = linear_system(&eqs, deps).map_err(at)?;
    let x = solve_system(&m, &f)
        .map_err(|e| at(format!("the dependent speeds cannot be eliminated: {e}")))?;
    Ok(deps.iter().copied().zip(x).collect())
}

/// Body `b`'s share of each speed's equation: v_G,r · (m a_G − m g) +
/// ω_r · (I_G α + ω × I_G ω).
fn body_terms(sp: &Speedmap<'_, '_, '_>, b: &Body, us: &[Atom]) -> R<Vec<Poly>> {
    let c = sp.c;
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
    let w = sp.vec(
        &cx.frames[bi].omega,
        &format!("the angular velocity of {name}"),
    )?;
    let (vp, fp) = sp.point_velocity(&b.point, 0)?;
    let vp = sp.express(vp, fp, bi)?;
    let what = format!("the velocity of {name}'s mass centre");
    let vg = sp.vec(&vp.add(&w.cross(&r)), &what)?;
    linear_in_speeds(c, &vg.0, &what)?;
    linear_in_speeds(c, &w.0, &format!("the angular velocity of {name}"))?;
    let left =
        vg.0.iter()
            .chain(&w.0)
            .flat_map(Poly::atoms)
            .find(|a| cx.speeds.speeds.contains(a) && !us.contains(a));
    if let Some(u) = left {
        return c.err(
            c.span,
            format!(
                "`{u}` occurs in the velocities of {name} but is not listed: list it with the speeds, or as a \
                 dependent speed with the constraints that determine it"
            ),
        );
    }
    let ag = sp.vec(&vg.dt().add(&w.cross(&vg)), "")?;
    let alpha = sp.vec(&w.dt(), "")?;
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
        force = force.sub(&sp.express(g.clone(), gi, bi)?.scale(&m));
    }
    Ok(us
        .iter()
        .map(|&u| {
            let vr: Vec3 = vg.map(|p| coefficient(p, u));
            let wr: Vec3 = w.map(|p| coefficient(p, u));
            &vr.dot(&force) + &wr.dot(&hdot)
        })
        .collect())
}
