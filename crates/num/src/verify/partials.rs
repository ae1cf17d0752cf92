//! Kane's partial velocities measured at a drawn state, never taken from
//! the engine: the model is built at the drawn speeds and again with one
//! independent speed raised by one — the dependent speeds solved again
//! from the constraint rows and the coordinates' rates again from the
//! kinematic equations ([`super::speeds`]) — and, the velocities being
//! linear in the speeds, each particle's, point's and frame's partial
//! velocity for that speed is the difference of the two (exact up to
//! rounding). These are the constrained partial velocities: the dependent
//! speeds move with the independent one as the constraints require.
//! Their sums over a body's particles (`Σ m δv`, `Σ m a · δv`) are formed
//! from the body's particle sums (the particles are `r = r_P + R q`).
//! The models are made once per state and speed ([`KaneWorlds`]).

use std::rc::Rc;

use hdot_sym::atom::Atom;
use hdot_sym::derivation::physics::Bodies;
use nalgebra::Vector3;

use super::world::{Placed, World, vee};
use super::{VerifyError, declaration};
use crate::bind::Values;

/// The model at the drawn speeds (`base`) and with one speed raised by
/// one (`raised`), velocities consistent with the constraints in both.
pub(crate) struct Partials<'d> {
    base: Rc<World<'d>>,
    raised: Rc<World<'d>>,
}

/// The models [`Partials`] are read from at one state, made once: every
/// generalized active and inertia force of a step (two per speed, and a
/// mass matrix measures them again at each unit rate) shares the model at
/// the drawn speeds and each speed's raised model.
#[derive(Default)]
pub(crate) struct KaneWorlds<'d> {
    /// The values with the dependent speeds and the coordinates' rates
    /// filled in, and the model at them.
    base: Option<(Values, Rc<World<'d>>)>,
    /// Each speed's raised model, by speed.
    raised: Vec<(Atom, Rc<World<'d>>)>,
}

/// The two models of [`Partials`] for speed `u` at the state of `w`, made
/// once per state ([`KaneWorlds`]).
///
/// # Errors
/// A file without kinematic equations, a dependent speed named (its
/// partial velocities are not those of Kane's equations), or constraints
/// whose dependent speeds cannot be solved at the state.
pub(crate) fn partials<'d>(w: &World<'d>, u: Atom) -> Result<Partials<'d>, VerifyError> {
    if let Some(p) = cached(w, u) {
        return Ok(p);
    }
    let d = w.d;
    let Some(speeds) = &w.draw.consistent().speeds else {
        return Err(declaration(
            d,
            "a generalized active or inertia force needs the kinematic equations ([kinematics])"
                .into(),
        ));
    };
    if speeds.dependent.contains(&u) {
        return Err(declaration(
            d,
            format!(
                "`{u}` is a dependent speed of the `kane` step: Kane's generalized forces are taken for the \
                 independent speeds"
            ),
        ));
    }
    let unbound = || {
        declaration(
            d,
            "a symbol of the kinematic equations or of the constraints has no value".into(),
        )
    };
    let known = w.kane.borrow().base.clone();
    let (base, base_world) = match known {
        Some(b) => b,
        None => {
            let mut base = w.values.clone();
            speeds.fill(d, &mut base, 1)?.ok_or_else(unbound)?;
            let world = Rc::new(World::build(d, w.draw, &base, &[])?);
            w.kane.borrow_mut().base = Some((base.clone(), world.clone()));
            (base, world)
        }
    };
    let (x, _) = base.get(u).ok_or_else(unbound)?;
    let mut raised = base.with(u, x + 1.0);
    speeds.fill(d, &mut raised, 1)?.ok_or_else(unbound)?;
    let raised = Rc::new(World::build(d, w.draw, &raised, &[])?);
    w.kane.borrow_mut().raised.push((u, raised.clone()));
    Ok(Partials {
        base: base_world,
        raised,
    })
}

/// The models for `u` made before at the state of `w`.
fn cached<'d>(w: &World<'d>, u: Atom) -> Option<Partials<'d>> {
    let k = w.kane.borrow();
    let base = k.base.as_ref()?.1.clone();
    let raised = k.raised.iter().find(|(v, _)| *v == u)?.1.clone();
    Some(Partials { base, raised })
}

impl Partials<'_> {
    /// `Σ m δv` over the particles of `b` (δv each particle's partial
    /// velocity) and the sum of their magnitudes, from each body's
    /// particle sums ([`super::placed::Placed::partial_momentum`]).
    pub(crate) fn momentum(&self, b: Bodies) -> (Vector3<f64>, f64) {
        self.raised.placed(b).iter().zip(self.base.placed(b)).fold(
            (Vector3::zeros(), 0.0),
            |(v, m), (r, q)| {
                let (bv, bm) = Placed::partial_momentum(r, q);
                (v + bv, m + bm)
            },
        )
    }

    /// `Σ m a · δv` over the particles of `b`, a their accelerations in
    /// `w` (the model at the same instant), and the sum of the magnitudes
    /// of its terms ([`super::placed::Placed::partial_power`]).
    pub(crate) fn inertia(&self, w: &World<'_>, b: Bodies) -> (f64, f64) {
        w.placed(b)
            .iter()
            .zip(self.raised.placed(b).iter().zip(self.base.placed(b)))
            .fold((0.0, 0.0), |(v, m), (p, (r, q))| {
                let (bv, bm) = p.partial_power::<2>(r, q);
                (v + bv, m + bm)
            })
    }

    /// The partial velocity of point `name` and its magnitude.
    pub(crate) fn point(&self, name: &str) -> (Vector3<f64>, f64) {
        let (p, q) = (&self.raised.points[name], &self.base.points[name]);
        (p.r[1] - q.r[1], p.mag[1] + q.mag[1])
    }

    /// The partial angular velocity of frame `f` (N's axes) and its
    /// magnitude.
    pub(crate) fn frame(&self, f: usize) -> (Vector3<f64>, f64) {
        let omega = |w: &World<'_>| {
            let r = &w.frames[f];
            (vee(&(r[1] * r[0].transpose())), r[1].norm())
        };
        let ((p, ps), (q, qs)) = (omega(&self.raised), omega(&self.base));
        (p - q, ps + qs)
    }
}
