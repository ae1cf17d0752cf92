//! The constraints of a `[[contact]]` (declared in `contact.rs`):
//! `contact_velocity(C)`, the velocity of the wheel's material point at
//! the contact, v_centre + ω × r g; `rolling_constraints(C)`, its two
//! components along the ground (nonholonomic, linear in the speeds);
//! `contact_height(C)`, the contact point's height above the ground, and
//! `contact_tangent(C)`, (axle × g)·ẑ (configuration constraints f(q) = 0);
//! `contact_constraints(C, …)`, all of them that are not identically zero,
//! as `kane` takes them.

use super::express_in;
use super::position::chain;
use super::velocity::Speedmap;
use super::{Call, Op};
use crate::derivation::contact::Contact;
use crate::derivation::context::R;
use crate::derivation::physics::PointKind;
use crate::derivation::value::Value;
use crate::parse::AstKind;
use crate::poly::Poly;
use crate::vector::Vec3;

pub(crate) const CONTACT_VELOCITY: Op = Op {
    names: &["contact_velocity"],
    signature: "contact_velocity(C)",
    doc: "the velocity in N of the wheel's material point at the `[[contact]]` `C`, v_centre + ω × r g (no rate of \
          the auxiliary angle), in the components of the contact's `plane` frame; it vanishes when the wheel rolls \
          without slipping, its z component along the motion that keeps the height constraint",
    eval: velocity,
};

pub(crate) const ROLLING_CONSTRAINTS: Op = Op {
    names: &["rolling_constraints"],
    signature: "rolling_constraints(C)",
    doc: "the two nonholonomic constraints of the `[[contact]]` `C`: the x and y components of `contact_velocity(C)` \
          (along the ground), a list, linear in the speeds",
    eval: rolling,
};

pub(crate) const CONTACT_HEIGHT: Op = Op {
    names: &["contact_height"],
    signature: "contact_height(C)",
    doc: "the height above the ground (N's z, the plane z = 0) of the `[[contact]]` `C`'s point: a configuration \
          constraint f(q) = 0 (identically zero when the contact point is where the coordinates place the wheel)",
    eval: height,
};

pub(crate) const CONTACT_TANGENT: Op = Op {
    names: &["contact_tangent"],
    signature: "contact_tangent(C)",
    doc: "(a × g)·ẑ for the axle a and the direction g from the centre to the `[[contact]]` `C`: the rim's tangent \
          at the contact is horizontal, so the contact is the rim's lowest point — the configuration constraint of the \
          auxiliary angle (identically zero without one)",
    eval: tangent,
};

pub(crate) const CONTACT_CONSTRAINTS: Op = Op {
    names: &["contact_constraints"],
    signature: "contact_constraints(C1, C2, …)",
    doc: "every constraint of the listed `[[contact]]`s for `kane`: for each, its two rolling constraints, then its \
          height and tangent configuration constraints that are not identically zero (a list)",
    eval: all,
};

/// Argument `i`, the name of a declared contact.
fn contact<'c>(c: &'c Call<'_, '_>, i: usize) -> R<&'c Contact> {
    let contacts = &c.cx.contacts;
    if let AstKind::Name { name, primes: 0 } = &c.args[i].kind
        && let Some(k) = contacts.iter().find(|k| &k.name == name)
    {
        return Ok(k);
    }
    let names: Vec<&str> = contacts.iter().map(|k| k.name.as_str()).collect();
    c.err(
        c.args[i].span,
        if names.is_empty() {
            "expected a contact: declare one with [[contact]]".to_string()
        } else {
            format!("expected a declared contact (one of {})", names.join(", "))
        },
    )
}

/// v_centre + ω × r g in the plane frame's components.
fn material_velocity(c: &Call<'_, '_>, k: &Contact) -> R<Vec3> {
    let cx = c.cx;
    let sp = Speedmap::plain(c);
    let (v, vf) = sp.point_velocity(&k.centre, 0)?;
    let v = sp.express(v, vf, k.frame)?;
    let wheel = &cx.physics.bodies[k.wheel];
    let w = sp.express(cx.frames[wheel.frame].omega.clone(), wheel.frame, k.frame)?;
    let r = k.down.scale(&k.radius);
    let v = sp.vec(&v.add(&w.cross(&r)), "the contact's velocity")?;
    sp.express(v, k.frame, k.plane)
}

fn velocity(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    let k = contact(c, 0)?;
    let v = material_velocity(c, k)?;
    Ok(Value::Vector(v, c.cx.frames[k.plane].name.clone()))
}

fn rolling(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    let [x, y, _] = material_velocity(c, contact(c, 0)?)?.0;
    Ok(Value::list(vec![x, y]))
}

/// N's z in frame `f`'s components.
fn up_in(c: &Call<'_, '_>, f: usize) -> R<Vec3> {
    express_in(c.cx, Vec3::unit(2), 0, f).ok_or_else(|| {
        c.cx.at(
            c.base,
            c.span,
            format!(
                "no chain of rotations relates frames N and {}",
                c.cx.frames[f].name
            ),
        )
    })
}

/// The contact point's height: the `at` vectors from it back to a fixed
/// point (the chain `position` walks) and that point's place, along N's z.
fn height_of(c: &Call<'_, '_>, k: &Contact) -> R<Poly> {
    let cx = c.cx;
    let (pieces, fixed) = chain(c, &k.name)?;
    let mut h = Poly::zero();
    for (v, f) in &pieces {
        h = &h + &cx.unfold(&v.dot(&up_in(c, *f)?));
    }
    let place = cx.physics.point(&fixed);
    if let Some(PointKind::Fixed(v, frame)) = place.map(|p| &p.kind) {
        let f = cx.frame_index(frame).expect("the point's frame exists");
        h = &h + &cx.unfold(&v.dot(&up_in(c, f)?));
    }
    Ok(h)
}

fn tangent_of(c: &Call<'_, '_>, k: &Contact) -> R<Poly> {
    Ok(k.axle.cross(&k.down).dot(&up_in(c, k.frame)?))
}

fn height(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    Ok(Value::Scalar(height_of(c, contact(c, 0)?)?))
}

fn tangent(c: &Call<'_, '_>) -> R<Value> {
    c.arity(1)?;
    Ok(Value::Scalar(tangent_of(c, contact(c, 0)?)?))
}

fn all(c: &Call<'_, '_>) -> R<Value> {
    if c.args.is_empty() {
        return c.err(c.span, "contact_constraints(…) needs at least one contact");
    }
    let mut rolling = Vec::new();
    let mut configuration = Vec::new();
    for i in 0..c.args.len() {
        let k = contact(c, i)?;
        let [x, y, _] = material_velocity(c, k)?.0;
        rolling.extend([x, y]);
        for f in [height_of(c, k)?, tangent_of(c, k)?] {
            if !f.is_zero() {
                configuration.push(f);
            }
        }
    }
    rolling.extend(configuration);
    Ok(Value::list(rolling))
}
