//! Scenes of a shaft in two bearings driven by a motor (`kind =
//! "fixed-axis"`): the `[shaft]` and `[motor]` tables, the inertia of the
//! `[[body]]` tables about the shaft's axis, and the initial angle and rate.

use std::path::Path;

use hdot_num::scene::{Bodies, RawBodies, bodies_from};
use nalgebra::Vector3;

use super::raw::{RawInitial, RawMotor, RawShaft};
use super::text::at_line;
use super::{NO_BODY, SceneKind, bad_field};
use crate::SimError;
use crate::systems::Shaft;

/// A fixed-axis scene: the shaft (from its tables and bodies) and its
/// initial angle and rate; and the shared tables as read (the scene keeps
/// them).
pub(super) fn read(
    shaft: Option<RawShaft>,
    motor: Option<RawMotor>,
    shared: RawBodies,
    initial: &RawInitial,
    file: &Path,
    text: &str,
) -> Result<(SceneKind, Bodies), SimError> {
    let bad = |field: &str, message: String| bad_field(file, field, message);
    let s = shaft.ok_or_else(|| bad("shaft", "missing table [shaft]".into()))?;
    let motor = motor.ok_or_else(|| bad("motor", "missing table [motor]".into()))?;
    if s.rotor_moment.is_some() || s.masses.is_some() {
        return Err(bad(
            if s.masses.is_some() {
                "shaft.masses"
            } else {
                "shaft.rotor_moment"
            },
            "no longer read: what turns is given by `[[body]]` tables in the shaft's axes \
             (z along the shaft through the origin), e.g. a point mass \
             `[[body]] shape = \"point\", mass = 0.05, position = [0.04, 0.0, 0.06]`, and a \
             balanced rotor `[[body]] shape = \"disk\"` or `principal_moments = […]` with \
             its mass (docs/scenes.md)"
                .into(),
        ));
    }
    if !(s.bearings[0].is_finite() && s.bearings[1].is_finite() && s.bearings[0] != s.bearings[1]) {
        return Err(bad(
            "shaft.bearings",
            "two distinct finite positions needed".into(),
        ));
    }
    let all = bodies_from(file, text, shared)?;
    all.refuse_of(file)?;
    let body = all
        .body
        .as_ref()
        .ok_or_else(|| bad("body", NO_BODY.into()))?;
    let props = body.mass_properties();
    // Inertia about the origin O on the axis, in the shaft's axes: I_z on
    // the diagonal, products ∫xz dm = −I[0][2].
    let about_o = props.inertia_about(&Vector3::zeros());
    let io = about_o.matrix();
    let (iz, ixz, iyz) = (io[(2, 2)], -io[(0, 2)], -io[(1, 2)]);
    if !(iz > 0.0 && iz.is_finite()) {
        return Err(bad(
            "body",
            "the moment about the shaft's axis (z through the origin) must be positive".into(),
        ));
    }
    let no_load = motor.no_load_speed.unwrap_or(f64::INFINITY);
    // Each value at its own field and line (NaN fails every comparison).
    for (ok, field, key, want, got) in [
        (
            motor.stall_torque.is_finite(),
            "motor.stall_torque",
            "stall_torque",
            "a finite torque",
            motor.stall_torque,
        ),
        (
            no_load > 0.0,
            "motor.no_load_speed",
            "no_load_speed",
            "a positive speed",
            no_load,
        ),
        (
            s.friction >= 0.0 && s.friction.is_finite(),
            "shaft.friction",
            "friction",
            "a finite coefficient ≥ 0",
            s.friction,
        ),
    ] {
        if !ok {
            return Err(bad(
                field,
                format!("{}{want} is needed, got {got}", at_line(text, key)),
            ));
        }
    }
    let shaft = Shaft {
        i_z: iz,
        i_xz: ixz,
        i_yz: iyz,
        mass: props.mass,
        xbar: props.center.x,
        ybar: props.center.y,
        stall_torque: motor.stall_torque,
        no_load_speed: no_load,
        friction: s.friction,
        bearings: s.bearings,
    };
    let y0 = [initial.angle.unwrap_or(0.0), initial.rate.unwrap_or(0.0)];
    for (k, key) in ["angle", "rate"].iter().enumerate() {
        if !y0[k].is_finite() {
            let field = format!("initial.{key}");
            return Err(bad(
                &field,
                format!(
                    "{}must be finite, got {}",
                    super::text::at_field_line(text, &field),
                    y0[k]
                ),
            ));
        }
    }
    Ok((SceneKind::FixedAxis { shaft, y0 }, all))
}
