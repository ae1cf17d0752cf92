//! `[[contact]]`: a wheel's rim rolling on the ground (N's x-y plane),
//! read and checked. It declares the contact point — the wheel's centre
//! plus r g, g the unit vector in the wheel's plane from the centre to
//! the rim's lowest point — which is a `[[point]]` like any other. g is an
//! axis of a frame that carries the axle and does not spin with the wheel
//! (a lean frame), or, when no such axis stays in the wheel's plane and
//! vertical, g = cos χ d + sin χ (a × d) with an auxiliary angle χ kept by
//! the configuration constraint (a × g)·ẑ = 0 (the rim's tangent at the
//! contact is horizontal). This keeps every expression polynomial in sin
//! and cos: the normalised g of the general case needs a square root. The
//! constraints themselves are `ops/contact.rs`.

use super::context::{Context, R};
use super::ops::express_in;
use super::physics::{Point, PointKind};
use super::raw::RawContact;
use crate::atom::{Atom, AtomKind};
use crate::poly::Poly;
use crate::rational::Rational;
use crate::symbols::Decl;
use crate::vector::Vec3;
use toml::Spanned;

/// A declared rolling contact.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact {
    /// The contact point it declares.
    pub name: String,
    /// Index of the rolling body.
    pub wheel: usize,
    /// The wheel's centre, a declared point on its axle.
    pub centre: String,
    /// Index of the frame that carries the axle (`frame`).
    pub frame: usize,
    /// The axle, a unit axis of `frame`.
    pub axle: Vec3,
    /// g: from the centre to the contact, a unit vector in `frame`'s
    /// components (in the auxiliary angle when there is one).
    pub down: Vec3,
    /// The wheel's radius, an expression in constants.
    pub radius: Poly,
    /// The auxiliary angle χ, when the contact has one.
    pub angle: Option<Atom>,
    /// Index of the frame whose x and y the rolling constraints are
    /// written in (its z is N's z).
    pub plane: usize,
}

/// Reads every `[[contact]]`: the contacts and the points they declare
/// (which join the file's points).
pub(crate) fn declare(cx: &Context<'_>, raw: &[RawContact]) -> R<(Vec<Contact>, Vec<Point>)> {
    let mut contacts = Vec::with_capacity(raw.len());
    let mut points: Vec<Point> = Vec::with_capacity(raw.len());
    for c in raw {
        let (contact, point) = one(cx, c, &points)?;
        contacts.push(contact);
        points.push(point);
    }
    Ok((contacts, points))
}

fn whole(cx: &Context<'_>, s: &Spanned<String>, msg: impl Into<String>) -> super::Diagnostic {
    cx.diag_string(s, 0, s.get_ref().len(), msg)
}

/// An axis of frame `f` named `text` (`y`, or `-z` for the opposite
/// direction) as a unit vector in its components.
fn axis(cx: &Context<'_>, f: usize, s: &Spanned<String>, key: &str) -> R<Vec3> {
    let text = s.get_ref().trim();
    let (sign, name) = match text.strip_prefix('-') {
        Some(rest) => (-1, rest.trim()),
        None => (1, text.strip_prefix('+').unwrap_or(text).trim()),
    };
    let frame = &cx.frames[f];
    match frame.axes.iter().position(|a| a == name) {
        Some(k) => Ok(Vec3::unit(k).scale(&Poly::constant(Rational::int(sign)))),
        None => Err(whole(
            cx,
            s,
            format!(
                "`{key}` is an axis of frame {} ({}, or one of them with a minus sign), found `{text}`",
                frame.name,
                frame.axes.join(", ")
            ),
        )),
    }
}

/// With `gravity` declared: at every coordinate 0 the contact direction
/// must point down (along the weight), not to the rim's highest point.
fn lowest(cx: &Context<'_>, c: &RawContact, frame: usize, down: &Vec3) -> R<()> {
    let Some((g, gf)) = &cx.physics.gravity else {
        return Ok(());
    };
    let gi = cx.frame_index(gf).expect("gravity's frame exists");
    let Some(g) = express_in(cx, g.clone(), gi, frame) else {
        return Ok(());
    };
    let zero = g.dot(down).subst(&mut |a| {
        if !a.is_time_dependent() {
            return None;
        }
        Some(match a.kind() {
            AtomKind::Cos(_) => Poly::one(),
            _ => Poly::zero(),
        })
    });
    if !zero.is_zero() && zero.terms().iter().all(|(_, k)| k.is_negative()) {
        return Err(whole(
            cx,
            &c.down,
            format!(
                "at zero angles `down` points up, against the weight (gravity · g = {zero}): the contact would be \
                 the rim's highest point; give the opposite axis"
            ),
        ));
    }
    Ok(())
}

/// The contact point's name (not taken), the wheel's index and its centre.
fn wheel_and_centre(cx: &Context<'_>, c: &RawContact, earlier: &[Point]) -> R<(usize, String)> {
    let name = c.name.get_ref();
    let taken = cx
        .physics
        .points
        .iter()
        .chain(earlier)
        .any(|p| &p.name == name)
        || cx
            .physics
            .bodies
            .iter()
            .any(|b| b.centre.as_deref() == Some(name))
        || cx.symbols.get(name).is_some()
        || cx.frame_index(name).is_some();
    if taken {
        return Err(whole(
            cx,
            &c.name,
            format!(
                "`{name}` is already a point, a symbol or a frame: the contact declares its own point"
            ),
        ));
    }
    let Some(wheel) = cx
        .physics
        .bodies
        .iter()
        .position(|b| &b.name == c.wheel.get_ref())
    else {
        let known: Vec<&str> = cx.physics.bodies.iter().map(|b| b.name.as_str()).collect();
        return Err(whole(
            cx,
            &c.wheel,
            format!(
                "`{}` is not a declared body (one of {})",
                c.wheel.get_ref(),
                known.join(", ")
            ),
        ));
    };
    let body = &cx.physics.bodies[wheel];
    let centre = match &c.centre {
        Some(s) => {
            if cx.physics.point(s.get_ref()).is_none() {
                let known = cx.physics.point_names();
                return Err(whole(
                    cx,
                    s,
                    format!(
                        "`{}` is not a declared point (one of {})",
                        s.get_ref(),
                        known.join(", ")
                    ),
                ));
            }
            s.get_ref().clone()
        }
        None => body.point.clone(),
    };
    if cx.physics.point(&centre).is_none() {
        return Err(whole(
            cx,
            &c.wheel,
            format!(
                "body `{}`'s reference point `{centre}` is not a declared point: give the contact its `centre`",
                body.name
            ),
        ));
    }
    Ok((wheel, centre))
}

/// `p` at every coordinate 0: sin → 0, cos → 1, a time symbol → 0.
fn at_zero(p: &Poly) -> Poly {
    p.subst(&mut |a| {
        if !a.is_time_dependent() {
            return None;
        }
        Some(match a.kind() {
            AtomKind::Cos(_) => Poly::one(),
            _ => Poly::zero(),
        })
    })
}

/// At every coordinate 0 the contact point (the centre plus `rim`, in
/// `frame`'s components) must be on the ground, N's z = 0, when the
/// centre's place is known (through the `at` vectors back to a fixed
/// point): a radius that does not match where the centre is placed
/// (the centre r above the ground, `radius = "2*r"`) would otherwise
/// become a configuration constraint nobody wrote, found only when the
/// constraints are solved.
fn on_the_ground(
    cx: &Context<'_>,
    c: &RawContact,
    centre: &str,
    frame: usize,
    rim: &Vec3,
) -> R<()> {
    let mut pieces: Vec<(Vec3, usize)> = Vec::new();
    let mut at = centre.to_owned();
    loop {
        let index = |f: &str| cx.frame_index(f).expect("the point's frame exists");
        match cx.physics.point(&at).map(|p| &p.kind) {
            Some(PointKind::From { from, at: v, frame }) => {
                if pieces.len() > cx.physics.point_names().len() {
                    return Ok(());
                }
                pieces.push((v.clone(), index(frame)));
                at = from.clone();
            }
            Some(PointKind::Fixed(v, f)) => {
                pieces.push((v.clone(), index(f)));
                break;
            }
            // A free centre: its height is not declared.
            _ => return Ok(()),
        }
    }
    let mut centre_height = Poly::zero();
    for (v, f) in pieces {
        let Some(v) = express_in(cx, v.map(|p| cx.unfold(p)), f, 0) else {
            return Ok(());
        };
        centre_height = &centre_height + &v.0[2];
    }
    let Some(rim) = express_in(cx, rim.map(|p| cx.unfold(p)), frame, 0) else {
        return Ok(());
    };
    let (centre0, rim0) = (at_zero(&centre_height), at_zero(&rim.0[2]));
    let height = &centre0 + &rim0;
    if height.is_zero() {
        return Ok(());
    }
    Err(whole(
        cx,
        &c.radius,
        format!(
            "at every coordinate 0 the contact point is {height} above the ground (N's z = 0), not on it: the \
             centre `{centre}` is {centre0} above the ground there and the rim reaches {} below it; make \
             `radius` the distance from the centre to the rim (or place `{centre}` that high)",
            -&rim0
        ),
    ))
}

/// The radius: a positive constant expression.
fn radius(cx: &Context<'_>, c: &RawContact) -> R<Poly> {
    let radius = cx.unfold(&cx.scalar_in(&c.radius)?);
    if radius.is_zero() {
        return Err(whole(cx, &c.radius, "the wheel's radius is zero"));
    }
    if let Some(a) = radius.atoms().into_iter().find(|a| a.is_time_dependent()) {
        return Err(whole(
            cx,
            &c.radius,
            format!("the wheel's radius is a constant expression: `{a}` varies in time"),
        ));
    }
    if radius
        .as_constant()
        .is_some_and(|r| r.is_negative() || r.is_zero())
    {
        return Err(whole(cx, &c.radius, "the wheel's radius must be positive"));
    }
    Ok(radius)
}

/// The frame of the rolling constraints' components: its z is N's.
fn plane(cx: &Context<'_>, c: &RawContact) -> R<usize> {
    let plane = match &c.plane {
        Some(s) => cx
            .frame_index(s.get_ref())
            .ok_or_else(|| whole(cx, s, format!("`{}` is not a declared frame", s.get_ref())))?,
        None => 0,
    };
    let up = Vec3::unit(2);
    let plane_z = express_in(cx, up.clone(), plane, 0);
    if plane_z.as_ref() != Some(&up) {
        let s = c.plane.as_ref().expect("N's z is its own");
        return Err(whole(
            cx,
            s,
            format!(
                "the constraints are written in the x and y of a frame whose z is N's (the ground's normal): \
                 {}'s z is not",
                s.get_ref()
            ),
        ));
    }
    Ok(plane)
}

/// g, from the centre to the contact, in `frame`'s components, and the
/// auxiliary angle it is written in (if any).
fn direction(
    cx: &Context<'_>,
    c: &RawContact,
    frame: usize,
    axle: &Vec3,
    d: Vec3,
) -> R<(Vec3, Option<Atom>)> {
    let up = Vec3::unit(2);
    let Some(n) = express_in(cx, up, 0, frame) else {
        return Err(whole(
            cx,
            c.frame.as_ref().unwrap_or(&c.wheel),
            format!(
                "no chain of rotations relates frame {} to N",
                cx.frames[frame].name
            ),
        ));
    };
    let side = axle.cross(&d);
    Ok(match &c.angle {
        None => {
            let tilt = side.dot(&n);
            if !tilt.is_zero() {
                return Err(whole(
                    cx,
                    &c.down,
                    format!(
                        "`down` leaves the rim's lowest point as frame {} turns ((axle × down)·ẑ = {tilt}): give the \
                         contact an auxiliary angle, `angle = \"chi\"`",
                        cx.frames[frame].name
                    ),
                ));
            }
            (d, None)
        }
        Some(s) => {
            let chi = s.get_ref();
            let ok = matches!(cx.symbols.get(chi), Some(Decl::Time))
                && !cx.speeds.speeds.contains(&Atom::time(chi, 0));
            if !ok {
                return Err(whole(
                    cx,
                    s,
                    format!(
                        "the auxiliary angle `{chi}` is a coordinate: declare it under [symbols] time (and its rate \
                         in [kinematics])"
                    ),
                ));
            }
            let chi = Atom::time(chi, 0);
            let cos = Poly::atom(Atom::cos(chi).expect("an angle"));
            let sin = Poly::atom(Atom::sin(chi).expect("an angle"));
            (d.scale(&cos).add(&side.scale(&sin)), Some(chi))
        }
    })
}

fn one(cx: &Context<'_>, c: &RawContact, earlier: &[Point]) -> R<(Contact, Point)> {
    let name = c.name.get_ref();
    let (wheel, centre) = wheel_and_centre(cx, c, earlier)?;
    let body = &cx.physics.bodies[wheel];
    let frame = match &c.frame {
        Some(s) => cx
            .frame_index(s.get_ref())
            .ok_or_else(|| whole(cx, s, format!("`{}` is not a declared frame", s.get_ref())))?,
        None => match &cx.frames[body.frame].parent {
            Some((p, _)) => cx.frame_index(p).expect("the parent exists"),
            None => body.frame,
        },
    };
    let axle = axis(cx, frame, &c.axle, "axle")?;
    let d = axis(cx, frame, &c.down, "down")?;
    if !axle.dot(&d).is_zero() {
        return Err(whole(
            cx,
            &c.down,
            "`down` must be square to the axle: the direction from the centre to the rim in the wheel's plane",
        ));
    }
    let radius = radius(cx, c)?;
    let plane = plane(cx, c)?;
    let (down, angle) = direction(cx, c, frame, &axle, d)?;
    lowest(cx, c, frame, &down)?;
    on_the_ground(cx, c, &centre, frame, &down.scale(&radius))?;
    let point = Point {
        name: name.clone(),
        doc: format!("the contact point of {} on the ground", body.name),
        kind: PointKind::From {
            from: centre.clone(),
            at: down.scale(&radius),
            frame: cx.frames[frame].name.clone(),
        },
    };
    let contact = Contact {
        name: name.clone(),
        wheel,
        centre,
        frame,
        axle,
        down,
        radius,
        angle,
        plane,
    };
    Ok((contact, point))
}
