//! Scenes of a rigid body free or on a fixed point (`kind = "free"` and
//! `"heavy-top"`): the pivot and gravity of a heavy top, the body axes
//! (principal, axis 3 through G for a top), and the initial attitude and
//! angular velocity — given, or those of a steady precession.

use std::path::Path;

use hdot_num::scene::{Bodies, RawBodies, bodies_from};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use super::raw::{RawInitial, RawSteady, RawTop};
use super::text::at_line;
use super::{BodyFrame, NO_BODY, STEADY_TOL, SceneKind, bad_field, finite3, unit_attitude};
use crate::exact::SteadyTop;
use crate::{PrincipalMoments, SimError};

/// An initial attitude, body angular velocity and the steady precession
/// they start, if they do.
type Start = (UnitQuaternion<f64>, Vector3<f64>, Option<SteadyTop>);

/// A free body (`heavy` false) or a heavy top: what moves, its body
/// frame in the tables' axes, and its initial state; and the shared
/// tables as read (the scene keeps them).
pub(super) fn read(
    top: Option<RawTop>,
    shared: RawBodies,
    initial: &RawInitial,
    heavy: bool,
    file: &Path,
    text: &str,
) -> Result<(SceneKind, BodyFrame, Bodies), SimError> {
    let bad = |field: &str, message: String| bad_field(file, field, message);
    let all = bodies_from(file, text, shared)?;
    all.refuse_of(file)?;
    let (g, g_line) = (all.g, all.g_line);
    let body = all
        .body
        .as_ref()
        .ok_or_else(|| bad("body", NO_BODY.into()))?;
    let props = body.mass_properties();
    let (about, axis3, weight_arm) = if heavy {
        let (o, weight_arm) = pivot(top, g, g_line, props.center, props.mass, (file, text))?;
        (
            *props.inertia_about(&o).matrix(),
            Some(props.center - o),
            weight_arm,
        )
    } else {
        if top.is_some() {
            return Err(bad(
                "top",
                "only a scene of kind \"heavy-top\" has a pivot".into(),
            ));
        }
        (*props.inertia_g.matrix(), None, 0.0)
    };
    let (moments, axes) = body_axes(&about, axis3).map_err(|m| bad("body", m))?;
    let body_frame = BodyFrame {
        origin: props.center - axis3.unwrap_or_else(Vector3::zeros),
        axes,
    };
    let moments = PrincipalMoments::new(moments).map_err(|e| bad("body", e.to_string()))?;
    let (q0, w0, steady) = match initial.steady_precession {
        Some(s) => {
            if !heavy {
                return Err(bad(
                    "initial.steady_precession",
                    "only a heavy top has a forced steady precession; a free axisymmetric body precesses by itself".into(),
                ));
            }
            steady_start(s, moments.get(), weight_arm, file, text)?
        }
        None => {
            let (q0, w0) = given_start(initial, moments.get(), &axes, file, text)?;
            let steady = if heavy {
                detect_steady(moments.get(), weight_arm, &q0, &w0)
            } else {
                None
            };
            (q0, w0, steady)
        }
    };
    let kind = if heavy {
        SceneKind::HeavyTop {
            moments,
            weight_arm,
            q0,
            w0,
            steady,
        }
    } else {
        SceneKind::Free { moments, q0, w0 }
    };
    Ok((kind, body_frame, all))
}

/// A heavy top's pivot O (in the tables' axes) and its weight × the
/// distance from O to G, with gravity along −Z checked.
fn pivot(
    top: Option<RawTop>,
    g: Option<Vector3<f64>>,
    g_line: usize,
    centre: Vector3<f64>,
    mass: f64,
    (file, text): (&Path, &str),
) -> Result<(Vector3<f64>, f64), SimError> {
    let bad = |field: &str, message: String| bad_field(file, field, message);
    let top = top.ok_or_else(|| {
        bad(
            "top",
            "missing table [top] (fixed_point = [x, y, z])".into(),
        )
    })?;
    if let Some((key, _)) = [
        ("distance", top.distance.is_some()),
        ("mass", top.mass.is_some()),
        ("g", top.g.is_some()),
    ]
    .iter()
    .find(|(_, set)| *set)
    {
        return Err(bad(
            &format!("top.{key}"),
            "no longer read: the mass comes from the `[[body]]` tables, the pivot is \
             `top.fixed_point = [x, y, z]` in the body's axes (a distance l below G on \
             the axis: [0, 0, -l] for a body centred at the origin), and gravity is \
             `g = [0.0, 0.0, -9.81]` at the top of the file (docs/scenes.md)"
                .into(),
        ));
    }
    let o = top.fixed_point.ok_or_else(|| {
        bad(
            "top.fixed_point",
            "missing: the pivot O in the body's axes".into(),
        )
    })?;
    let o = finite3(o, "top.fixed_point", (file, text))?;
    // The moments about O add m |OG|²: finite with room to spare.
    if !(mass * (centre - o).norm_squared() * 1e6).is_finite() {
        return Err(bad(
            "top.fixed_point",
            format!(
                "{}the pivot {:?} is so far from the mass centre that m |OG|² (the moments \
                 about it) is beyond the range of f64: rescale the units",
                at_line(text, "fixed_point"),
                [o.x, o.y, o.z]
            ),
        ));
    }
    let g = g.ok_or_else(|| {
        bad(
            "g",
            "a heavy top needs gravity: `g = [0.0, 0.0, -9.81]` (space Z up)".into(),
        )
    })?;
    let gn = g.norm();
    if !gn.is_finite() {
        return Err(bad(
            "g",
            format!(
                "line {g_line}: |g| of {:?} is beyond the range of f64 once squared: \
                 rescale the units",
                [g.x, g.y, g.z]
            ),
        ));
    }
    if !(gn > 0.0 && g.x.hypot(g.y) <= 1e-12 * gn && g.z < 0.0) {
        return Err(bad(
            "g",
            format!(
                "line {g_line}: the heavy top's space Z is up, so gravity points along −Z: \
                 give g = [0.0, 0.0, -g] (got {:?})",
                [g.x, g.y, g.z]
            ),
        ));
    }
    let l = (centre - o).norm();
    if l.is_nan() || l <= 0.0 {
        return Err(bad(
            "top.fixed_point",
            "the pivot is at the mass centre: no gravity torque (give a free scene)".into(),
        ));
    }
    Ok((o, mass * gn * l))
}

/// The initial attitude and body angular velocity of a heavy top started
/// in the steady precession `s` (§7), and that precession.
fn steady_start(
    s: RawSteady,
    i: [f64; 3],
    weight_arm: f64,
    file: &Path,
    text: &str,
) -> Result<Start, SimError> {
    let bad = |field: &str, message: String| bad_field(file, field, message);
    if (i[0] - i[1]).abs() > 1e-12 * i[0] {
        return Err(bad(
            "body",
            "steady precession needs I_1 = I_2 (symmetric top)".into(),
        ));
    }
    if !(s.theta > 0.0 && s.theta < std::f64::consts::PI) {
        return Err(bad(
            "initial.steady_precession.theta",
            "must lie in (0, π)".into(),
        ));
    }
    if !s.spin.is_finite() {
        return Err(bad(
            "initial.steady_precession.spin",
            format!("{}must be finite, got {}", at_line(text, "spin"), s.spin),
        ));
    }
    let phi_dot = SteadyTop::slow_precession_rate(i[2], i[0], weight_arm, s.theta, s.spin)
        .ok_or_else(|| {
            bad(
                "initial.steady_precession.spin",
                "too slow for a steady precession at this θ".into(),
            )
        })?;
    let top = SteadyTop {
        phi0: 0.0,
        theta: s.theta,
        psi0: 0.0,
        phi_dot,
        psi_dot: s.spin - phi_dot * s.theta.cos(),
        omega_z: s.spin,
    };
    let y = top.state(0.0);
    Ok((
        crate::systems::free::attitude(&y),
        Vector3::new(y[4], y[5], y[6]),
        Some(top),
    ))
}

/// The initial attitude and body angular velocity as given (attitude or
/// Eulerian angles; angular momentum or velocity, in the tables' axes),
/// turned into the body axes `axes` and checked to stay in f64's range.
fn given_start(
    initial: &RawInitial,
    i: [f64; 3],
    axes: &Rotation3<f64>,
    file: &Path,
    text: &str,
) -> Result<(UnitQuaternion<f64>, Vector3<f64>), SimError> {
    let bad = |field: &str, message: String| bad_field(file, field, message);
    let q0 = match (initial.attitude, initial.euler_angles) {
        (Some(q), None) => unit_attitude(q, &format!("{}: initial.attitude", file.display()))?,
        (None, Some(e)) => {
            let e = finite3(e, "initial.euler_angles", (file, text))?;
            hdot_num::body::eulerian_rotation(e.x, e.y, e.z)
        }
        (None, None) => UnitQuaternion::identity(),
        _ => {
            return Err(bad(
                "initial",
                "give at most one of `attitude` and `euler_angles`".into(),
            ));
        }
    };
    // ω and H are given in the axes of the [[body]] tables; the models
    // take them in the body (principal) axes.
    let to_body = axes.transpose();
    let q0 = q0 * UnitQuaternion::from_rotation_matrix(axes);
    // |H|² and 2E·I must be finite with room to spare: the closed forms
    // and the invariants square them.
    let in_range = |w: &Vector3<f64>| {
        let h2: f64 = (0..3).map(|k| (i[k] * w[k]).powi(2)).sum();
        let e2: f64 = (0..3).map(|k| i[k] * w[k] * w[k]).sum();
        let imax = i[0].max(i[1]).max(i[2]);
        (h2 * 1e6).is_finite() && (e2 * imax * 1e6).is_finite()
    };
    // The field at fault: the rates, or the body when its moments alone
    // are out of range (a mass of 1e300 with ω = 60 rad/s).
    let moments_out = !in_range(&Vector3::new(1.0, 1.0, 1.0));
    let overflow = |field: &str, v: &Vector3<f64>| {
        let key = field.rsplit('.').next().unwrap_or(field);
        if moments_out {
            return bad(
                "body",
                format!(
                    "the principal moments {i:?} are beyond the range of f64 once squared \
                     (|H|² and the energy square them): rescale the units (mass, length)"
                ),
            );
        }
        bad(
            field,
            format!(
                "{}|H|² = Σ (I_i ω_i)² is beyond the range of f64 (components {:?}): \
                 rescale the units",
                at_line(text, key),
                [v.x, v.y, v.z]
            ),
        )
    };
    let w0 = match (initial.angular_momentum, initial.angular_velocity) {
        (Some(h), None) => {
            let h = to_body * finite3(h, "initial.angular_momentum", (file, text))?;
            let w = Vector3::new(h.x / i[0], h.y / i[1], h.z / i[2]);
            if !in_range(&w) {
                return Err(overflow("initial.angular_momentum", &h));
            }
            w
        }
        (None, Some(w)) => {
            let w = to_body * finite3(w, "initial.angular_velocity", (file, text))?;
            if !in_range(&w) {
                return Err(overflow("initial.angular_velocity", &w));
            }
            w
        }
        _ => {
            return Err(bad(
                "initial",
                "give exactly one of `angular_momentum` and `angular_velocity`".into(),
            ));
        }
    };
    // ω² must not underflow: the invariants and the closed forms square it.
    let w2 = w0.norm_squared();
    if w0.amax() != 0.0 && w2 < 1e-290 {
        let (field, key) = if initial.angular_momentum.is_some() {
            ("initial.angular_momentum", "angular_momentum")
        } else {
            ("initial.angular_velocity", "angular_velocity")
        };
        return Err(bad(
            field,
            format!(
                "{}the angular velocity |ω| = {:e} (in body axes) is so small that \
                 ω² underflows f64: rescale the units (moments, time)",
                at_line(text, key),
                w0.amax()
            ),
        ));
    }
    Ok((q0, w0))
}
/// Relative size of the products of inertia (to the trace) under which
/// the axes of the `[[body]]` tables are taken as the body's principal axes.
const DIAGONAL_TOL: f64 = 1e-12;

/// The body axes of a simulation: principal axes of `inertia` (about G, or
/// about the pivot O; in the axes of the `[[body]]` tables), with axis 3
/// along `axis3` (from O to G) when given. The tables' own axes are kept
/// when they are principal already (so that ω is given in them as
/// written); otherwise the principal axes are found. Returns the moments
/// and the rotation whose columns are the body axes in the tables' axes.
fn body_axes(
    inertia: &Matrix3<f64>,
    axis3: Option<Vector3<f64>>,
) -> Result<([f64; 3], Rotation3<f64>), String> {
    let trace = inertia.trace();
    let off = inertia[(0, 1)]
        .abs()
        .max(inertia[(0, 2)].abs())
        .max(inertia[(1, 2)].abs());
    let along_z = axis3.is_none_or(|a| a.x.hypot(a.y) <= DIAGONAL_TOL * a.norm() && a.z > 0.0);
    if off <= DIAGONAL_TOL * trace && along_z {
        return Ok((
            [inertia[(0, 0)], inertia[(1, 1)], inertia[(2, 2)]],
            Rotation3::identity(),
        ));
    }
    let Some(a) = axis3 else {
        let p = hdot_num::Inertia::new_unchecked(*inertia).principal();
        return Ok((p.moments.into(), p.axes));
    };
    let e3 = a.normalize();
    let ie3 = inertia * e3;
    let i3 = e3.dot(&ie3);
    if (ie3 - e3 * i3).norm() > 1e-9 * trace {
        return Err(
            "the mass centre G is not on a principal axis of inertia through the pivot O: the built-in \
             heavy top needs G on such an axis (the axis of a symmetric top); a derived scene \
             integrates other bodies"
                .into(),
        );
    }
    // Principal axes in the plane normal to e3.
    let u = if e3.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = (u - e3 * e3.dot(&u)).normalize();
    let v = e3.cross(&u);
    let (uu, vv, uv) = (
        u.dot(&(inertia * u)),
        v.dot(&(inertia * v)),
        u.dot(&(inertia * v)),
    );
    let alpha = 0.5 * (2.0 * uv).atan2(uu - vv);
    let e1 = u * alpha.cos() + v * alpha.sin();
    let e2 = e3.cross(&e1);
    let axes = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[e1, e2, e3]));
    Ok(([e1.dot(&(inertia * e1)), e2.dot(&(inertia * e2)), i3], axes))
}

/// A heavy top given by attitude and ω is in steady precession when θ̇ = 0,
/// it is symmetric and §7's relation holds to [`STEADY_TOL`].
fn detect_steady(
    i: [f64; 3],
    weight_arm: f64,
    q0: &UnitQuaternion<f64>,
    w0: &Vector3<f64>,
) -> Option<SteadyTop> {
    if (i[0] - i[1]).abs() > 1e-12 * i[0] {
        return None;
    }
    let (phi, theta, psi) = crate::systems::euler_angles::angles_from_quaternion(q0);
    if theta.sin() < 1e-8 {
        return None;
    }
    let (s, c) = psi.sin_cos();
    // §7 frame components: ω' = R_z(ψ) ω.
    let wx = c * w0.x - s * w0.y;
    let wy = s * w0.x + c * w0.y;
    let scale = w0.norm().max(f64::MIN_POSITIVE);
    if wy.abs() > 1e-12 * scale {
        return None;
    }
    let phi_dot = -wx / theta.sin();
    let top = SteadyTop {
        phi0: phi,
        theta,
        psi0: psi,
        phi_dot,
        psi_dot: w0.z - phi_dot * theta.cos(),
        omega_z: w0.z,
    };
    (top.residual(i[2], i[0], weight_arm) <= STEADY_TOL).then_some(top)
}
