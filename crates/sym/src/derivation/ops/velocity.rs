//! `velocity(P)` and `rolling(B, P)`: velocities of declared points in N,
//! written in the generalized speeds — and the rewriting they share with
//! `kane`: coordinates' rates through `[kinematics]`, dependent speeds
//! through constraints solved for them, and the check that a velocity is
//! linear in the speeds.

use super::express::express_in;
use super::{Call, Op};
use crate::atom::{Atom, AtomKind};
use crate::derivation::context::R;
use crate::derivation::physics::PointKind;
use crate::derivation::value::Value;
use crate::poly::Poly;
use crate::vector::Vec3;

pub(crate) const VELOCITY: Op = Op {
    names: &["velocity"],
    signature: "velocity(P)",
    doc: "the velocity in N of the declared point `P` (fixed, or placed `from` another point with `at`, or a \
          body's centre placed by its `mass_centre`), in the components of the frame of its `at`; written in the \
          generalized speeds when `[kinematics]` gives them (so not for `lagrange`, which refuses speeds)",
    eval: velocity,
};

pub(crate) const ROLLING: Op = Op {
    names: &["rolling"],
    signature: "rolling(B, P)",
    doc: "the velocity in N of the material point of body `B` that is at the declared point `P` (a contact): \
          v_ref + ω_B × r, with `P` placed `from` the body's reference point or the reference point `from` `P`; \
          it vanishes when `B` rolls without slipping at `P` (the nonholonomic constraints of `kane`)",
    eval: rolling,
};

fn velocity(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    let name = point_name(c, 0)?;
    let sp = Speedmap::plain(c);
    let (v, f) = sp.point_velocity(&name, 0)?;
    Ok(Value::Vector(v, c.cx.frames[f].name.clone()))
}

fn rolling(c: &Call<'_, '_>) -> R<Value> {
    c.arity(2)?;
    let cx = c.cx;
    let body = match &c.args[0].kind {
        crate::parse::AstKind::Name { name, primes: 0 } => {
            cx.physics.bodies.iter().find(|b| &b.name == name)
        }
        _ => None,
    };
    let Some(body) = body else {
        let names: Vec<&str> = cx.physics.bodies.iter().map(|b| b.name.as_str()).collect();
        return c.err(
            c.args[0].span,
            format!("expected a declared body (one of {})", names.join(", ")),
        );
    };
    let p = point_name(c, 1)?;
    let sp = Speedmap::plain(c);
    let placed = |of: &str| cx.physics.point(of).map(|q| &q.kind);
    // r from the reference point to P, and its frame.
    let (r, rf) = match (placed(&p), placed(&body.point)) {
        (Some(PointKind::From { from, at, frame }), _) if *from == body.point => {
            (at.clone(), frame.clone())
        }
        (_, Some(PointKind::From { from, at, frame })) if *from == p => (at.neg(), frame.clone()),
        _ => {
            return c.err(
                c.args[1].span,
                format!(
                    "place `{p}` `from` body `{}`'s reference point `{}` (or that point `from` `{p}`)",
                    body.name, body.point
                ),
            );
        }
    };
    let fi = cx.frame_index(&rf).expect("the point's frame exists");
    let (v, vf) = sp.point_velocity(&body.point, 0)?;
    let v = sp.express(v, vf, fi)?;
    let w = sp.express(cx.frames[body.frame].omega.clone(), body.frame, fi)?;
    let w = sp.vec(&w, "")?;
    let r = r.map(|q| cx.unfold(q));
    Ok(Value::Vector(sp.vec(&v.add(&w.cross(&r)), "")?, rf))
}

/// Argument `i`, the name of a declared point.
fn point_name(c: &Call<'_, '_>, i: usize) -> R<String> {
    let ph = &c.cx.physics;
    if let crate::parse::AstKind::Name { name, primes: 0 } = &c.args[i].kind
        && ph.point(name).is_some()
    {
        return Ok(name.clone());
    }
    let names = ph.point_names();
    c.err(
        c.args[i].span,
        format!("expected a declared point (one of {})", names.join(", ")),
    )
}

/// Rewrites values in the speeds for one call: coordinates' rates by
/// `[kinematics]`, then dependent speeds by their values in the others.
pub(crate) struct Speedmap<'c, 'a, 'b> {
    pub c: &'c Call<'a, 'b>,
    /// Each dependent speed with its value in the independent ones.
    pub dependent: Vec<(Atom, Poly)>,
}

impl<'c, 'a, 'b> Speedmap<'c, 'a, 'b> {
    /// Without dependent speeds.
    pub fn plain(c: &'c Call<'a, 'b>) -> Self {
        Speedmap {
            c,
            dependent: Vec::new(),
        }
    }

    /// `p` in the (independent) speeds.
    pub fn poly(&self, p: &Poly) -> Poly {
        let cx = self.c.cx;
        let p = cx.speeds.in_speeds(&cx.unfold(p));
        if self.dependent.is_empty() {
            return p;
        }
        p.subst(&mut |a| match a.kind() {
            AtomKind::Var { order: 0, .. } => self
                .dependent
                .iter()
                .find(|(u, _)| *u == a)
                .map(|(_, v)| v.clone()),
            _ => None,
        })
    }

    /// `v` in the speeds; an error naming `what` when a rate of a
    /// coordinate without a kinematic equation is left.
    pub fn vec(&self, v: &Vec3, what: &str) -> R<Vec3> {
        let cx = self.c.cx;
        let v = v.map(|p| self.poly(p));
        let left =
            v.0.iter()
                .flat_map(Poly::atoms)
                .find(|a| a.order() > 0 && !cx.speeds.speeds.contains(&a.base()));
        match left {
            Some(a) => self.c.err(
                self.c.span,
                format!(
                    "`{a}` occurs in {}: give `{}` a kinematic equation in [kinematics]",
                    if what.is_empty() { "a velocity" } else { what },
                    a.base()
                ),
            ),
            None => Ok(v),
        }
    }

    /// `v` from frame `from`'s components to frame `to`'s.
    pub fn express(&self, v: Vec3, from: usize, to: usize) -> R<Vec3> {
        let cx = self.c.cx;
        express_in(cx, v, from, to).ok_or_else(|| {
            cx.at(
                self.c.base,
                self.c.span,
                format!(
                    "no chain of rotations relates frames {} and {}",
                    cx.frames[from].name, cx.frames[to].name
                ),
            )
        })
    }

    /// The velocity in N of the declared point `name` and the frame of its
    /// components: zero for a fixed point, the velocity of the point it is
    /// measured from plus the rate in N of the vector from it.
    pub fn point_velocity(&self, name: &str, depth: usize) -> R<(Vec3, usize)> {
        let (c, cx) = (self.c, self.c.cx);
        let Some(p) = cx.physics.point(name) else {
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
                    "point `{name}` moves freely: its velocity is not declared; place it with `from` and `at`"
                ),
            ),
            PointKind::From { from, at, frame } => {
                // Declarations forbid cycles; the depth is a guard only.
                if depth > cx.physics.point_names().len() {
                    return c.err(c.span, format!("point `{name}` leads back to itself"));
                }
                let (vf, ff) = self.point_velocity(from, depth + 1)?;
                let fi = cx.frame_index(frame).expect("the point's frame exists");
                let at = at.map(|p| cx.unfold(p));
                let w = self.vec(&cx.frames[fi].omega, "")?;
                let rel = at.dt().add(&w.cross(&at));
                let vf = self.express(vf, ff, fi)?;
                Ok((self.vec(&vf.add(&rel), "")?, fi))
            }
        }
    }
}

/// Checks that every component of `v` is linear in the declared speeds
/// (each term holds at most one speed, to the first power); the message
/// names `what`.
pub(crate) fn linear_in_speeds(c: &Call<'_, '_>, ps: &[Poly], what: &str) -> R<()> {
    let speeds = &c.cx.speeds.speeds;
    for p in ps {
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
                return c.err(c.span, format!("{what} is not linear in the speeds"));
            }
        }
    }
    Ok(())
}
