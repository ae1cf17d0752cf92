//! `kane([u1, …])` and `kane([u1, …], constraints, [u4, …])`: Kane's
//! equations of the declared bodies in the generalized speeds — partial
//! velocities of the mass centres and partial angular velocities of the
//! body frames (with dependent speeds eliminated through constraints
//! linear in the speeds), the generalized active forces of gravity and the
//! generalized inertia forces, written as −(F_r + F_r*) = 0 for each
//! independent speed; exactly, or to first order about an operating point
//! (the constraints and that expansion are `constraints.rs`).

use super::constraints::{Linear, coordinates_arg, eliminate};
use super::velocity::{Speedmap, linear_in_speeds};
use super::{Call, Op, coefficient};
use crate::atom::Atom;
use crate::derivation::context::R;
use crate::derivation::multibody::Load;
use crate::derivation::operating::OperatingPoint;
use crate::derivation::physics::Body;
use crate::derivation::value::Value;
use crate::parse::AstKind;
use crate::poly::Poly;
use crate::vector::{Mat3, Vec3};

pub(crate) const KANE: Op = Op {
    names: &["kane"],
    signature: "kane([u1, u2, …]), kane([u1, …], constraints, [u4, …]), kane([u1, …], constraints, [u4, …], [q4, …]), kane(…, q = q0, u = u0, …)",
    doc: "Kane's equations of the declared bodies for the listed (independent) generalized speeds: for each u_r, \
          Σ (v_G,r · (m a_G − m g) + ω_r · (I_G α + ω × I_G ω)), where v_G,r and ω_r are the partial velocities \
          of each mass centre and body frame and g is `gravity`, less v_P,r · F and ω_r · T of each `[[load]]` \
          (= −(F_r + F_r*), zero along the motion); \
          velocities are written in the speeds through `[kinematics]`. With constraints (a vector or `list` \
          that vanishes, linear in the speeds, such as `rolling(B, P)`) the dependent speeds listed last are \
          solved for and eliminated; a constraint free of the speeds is a configuration constraint f(q) = 0, whose \
          rate joins the velocity constraints, with its dependent coordinate listed after the dependent speeds. \
          With an operating point `q = value, …` (as `linearize`), the equations to first order about it: \
          velocities to first order in the coordinates, the dependent speeds solved at the operating point and \
          corrected to first order, the dependent coordinates by implicit differentiation of the configuration \
          constraints. A list, one equation per independent speed, linear in their rates",
    eval,
};

fn eval(c: &Call<'_, '_>) -> R<Value> {
    let cx = c.cx;
    let positional = c
        .args
        .iter()
        .take_while(|a| !matches!(a.kind, AstKind::Assign { .. }))
        .count();
    if !matches!(positional, 1 | 3 | 4) {
        return c.err(
            c.span,
            format!(
                "`kane` takes the speeds, then optionally the constraints, the dependent speeds and the dependent \
                 coordinates, then optionally an operating point `q = value, …`; found {positional} argument{} \
                 before the operating point",
                if positional == 1 { "" } else { "s" }
            ),
        );
    }
    if cx.speeds.is_empty() {
        return c.err(
            c.span,
            "Kane's method needs generalized speeds: declare [symbols] speeds and a [kinematics] table",
        );
    }
    let op = OperatingPoint::read(c, &c.args[positional..])?;
    // What the file wrote: the points' places and the loads.
    let written = cx
        .physics
        .points
        .iter()
        .chain(&cx.physics.centres)
        .filter_map(|p| match &p.kind {
            crate::derivation::physics::PointKind::From { at, .. } => Some(at.clone()),
            _ => None,
        })
        .chain(cx.loads.iter().map(|l| match l {
            crate::derivation::multibody::Load::Force { force, .. } => force.clone(),
            crate::derivation::multibody::Load::Torque { torque, .. } => torque.clone(),
        }));
    for v in written {
        if let Some(a) = v.0.iter().find_map(|p| op.outside_trig(&cx.unfold(p))) {
            return c.err(c.span, super::linearize::outside_trig_message(a));
        }
    }
    let lin = (!op.is_empty()).then(|| Linear { c, op });
    let us = speeds_arg(c, 0, &[])?;
    let (sp, coordinates) = if positional >= 3 {
        let deps = speeds_arg(c, 2, &us)?;
        let qdeps = if positional == 4 {
            coordinates_arg(c, 3)?
        } else {
            Vec::new()
        };
        let e = eliminate(c, &deps, &qdeps, lin.as_ref())?;
        (
            Speedmap {
                c,
                dependent: e.speeds,
            },
            e.coordinates,
        )
    } else {
        (Speedmap::plain(c), Vec::new())
    };
    if cx.physics.bodies.is_empty() {
        return c.err(
            c.span,
            "Kane's method sums over the declared bodies: declare them with [[body]]",
        );
    }
    let mut eqs = vec![Poly::zero(); us.len()];
    for b in &cx.physics.bodies {
        let terms = body_terms(&sp, b, &us, lin.as_ref())?;
        for (e, t) in eqs.iter_mut().zip(terms) {
            *e = &*e + &t;
        }
    }
    for l in &cx.loads {
        let terms = load_terms(&sp, l, &us, lin.as_ref())?;
        for (e, t) in eqs.iter_mut().zip(terms) {
            *e = &*e - &t;
        }
    }
    if let Some(lin) = &lin {
        // The dependent coordinates' deviations, by implicit
        // differentiation of the configuration constraints.
        eqs = eqs
            .iter()
            .map(|e| {
                lin.full(e).map(|e| {
                    e.subst(&mut |a| {
                        coordinates
                            .iter()
                            .find(|(q, _)| *q == a)
                            .map(|(_, v)| v.clone())
                    })
                })
            })
            .collect::<R<Vec<_>>>()?;
    }
    Ok(Value::list(eqs))
}

/// A `[[load]]`'s generalized active force for each speed: v_P,r · F for a
/// force at P, ω_r · T for a torque on a frame.
fn load_terms(
    sp: &Speedmap<'_, '_, '_>,
    l: &Load,
    us: &[Atom],
    lin: Option<&Linear<'_, '_, '_>>,
) -> R<Vec<Poly>> {
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
    let Some(lin) = lin else {
        return Ok(us
            .iter()
            .map(|&u| dot(&v.map(|p| coefficient(p, u)), &f))
            .collect());
    };
    let v = lin.vec(&v, Linear::positional)?;
    let f = lin.vec(&f, Linear::full)?;
    us.iter()
        .map(|&u| lin.full(&dot(&v.map(|p| coefficient(p, u)), &f)))
        .collect()
}

/// `a · b` accumulated in one sum ([`Poly::sum_of_products`]).
fn dot(a: &Vec3, b: &Vec3) -> Poly {
    Poly::sum_of_products(a.0.iter().zip(&b.0))
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

/// Body `b`'s share of each speed's equation: v_G,r · (m a_G − m g) +
/// ω_r · (I_G α + ω × I_G ω).
fn body_terms(
    sp: &Speedmap<'_, '_, '_>,
    b: &Body,
    us: &[Atom],
    lin: Option<&Linear<'_, '_, '_>>,
) -> R<Vec<Poly>> {
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
    // About an operating point: velocities to first order in the
    // coordinates (exact in the speeds, so that the partial velocities are
    // first order too), accelerations and the rest to first order in all.
    let (w, vg) = match lin {
        Some(lin) => (
            lin.vec(&w, Linear::positional)?,
            lin.vec(&vg, Linear::positional)?,
        ),
        None => (w, vg),
    };
    let mut ag = sp.vec(&vg.dt().add(&w.cross(&vg)), "")?;
    let mut alpha = sp.vec(&w.dt(), "")?;
    if let Some(lin) = lin {
        ag = lin.vec(&ag, Linear::full)?;
        alpha = lin.vec(&alpha, Linear::full)?;
    }
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
    let mut hdot = ig.mul_vec(&alpha).add(&w.cross(&iw));
    let mut force = ag.scale(&m);
    if let Some((g, gf)) = &cx.physics.gravity {
        let gi = cx.frame_index(gf).expect("gravity's frame exists");
        force = force.sub(&sp.express(g.clone(), gi, bi)?.scale(&m));
    }
    if let Some(lin) = lin {
        hdot = lin.vec(&hdot, Linear::full)?;
        force = lin.vec(&force.map(|p| cx.unfold(p)), Linear::full)?;
    }
    us.iter()
        .map(|&u| {
            let vr: Vec3 = vg.map(|p| coefficient(p, u));
            let wr: Vec3 = w.map(|p| coefficient(p, u));
            let e =
                Poly::sum_of_products(vr.0.iter().zip(&force.0).chain(wr.0.iter().zip(&hdot.0)));
            match lin {
                Some(lin) => lin.full(&e),
                None => Ok(e),
            }
        })
        .collect()
}
