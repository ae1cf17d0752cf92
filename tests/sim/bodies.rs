//! Issue 10, item 8: one body schema for every scene. A simulation reads
//! its body from the `[[body]]` tables of `hdot dynamics` (primitives,
//! composites, clouds, poses); a composite from a worked problem runs; the
//! axes of the tables need not be principal; the former keys are refused
//! naming the new ones.

use std::path::Path;

use hdot_sim::run::{self, Output, Request};
use hdot_sim::scene::{Scene, SceneKind};
use hdot_sim::{Method, SimError, Step};
use nalgebra::{UnitQuaternion, Vector3};

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/examples")
}

fn final_state(scene: &Scene) -> Vec<f64> {
    let req = Request {
        method: Some(Method::Dop853),
        step: Some(Step::Tolerance(1e-12)),
        ..Request::default()
    };
    let plan = run::plan(scene, &req).unwrap();
    run::run(scene, &plan, &mut Output::default())
        .unwrap()
        .final_state
}

/// The bundled composite (a disk on a rod axle, pivoted at the axle's end)
/// moves as the heavy top of the mass properties worked out here by hand
/// from the reference table and the parallel-axis theorem.
#[test]
fn a_composite_top_moves_as_the_top_of_its_hand_computed_mass_properties() {
    let composite = Scene::from_file(&examples().join("sim-composite-top.toml")).unwrap();
    // Disk (0.3 kg, r = 0.05) at z = 0.1: I_axis = m r²/2, I_diam = m r²/4.
    // Rod (0.05 kg, L = 0.12) along z, centred at z = 0.06: m L²/12 across.
    let (md, r, zd): (f64, f64, f64) = (0.3, 0.05, 0.1);
    let (mr, l, zr): (f64, f64, f64) = (0.05, 0.12, 0.06);
    let m = md + mr;
    let zg = (md * zd + mr * zr) / m;
    let across =
        md * r * r / 4.0 + md * (zd - zg).powi(2) + mr * l * l / 12.0 + mr * (zr - zg).powi(2);
    let axial = md * r * r / 2.0;
    let text = format!(
        "name = \"by hand\"\nkind = \"heavy-top\"\nt_end = 3.0\ng = [0.0, 0.0, -9.81]\n\
         [[body]]\nprincipal_moments = [{across:e}, {across:e}, {axial:e}]\nmass = {m:e}\n\
         [top]\nfixed_point = [0.0, 0.0, {:e}]\n\
         [initial]\neuler_angles = [0.0, 0.4, 0.0]\nangular_velocity = [0.0, 0.0, 120.0]\n",
        -zg
    );
    let by_hand = Scene::parse(&text, Path::new("by-hand.toml")).unwrap();
    let (a, b) = (final_state(&composite), final_state(&by_hand));
    let d = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    // Two DOP853 runs at tol 1e-12 of the same equations, whose inputs
    // differ by round-off: far below the 1e-8 of a wrong moment or arm.
    assert!(d < 1e-7 * 120.0, "{a:?}\n{b:?}");
    // A wrong arm or moment is seen: move the pivot by 1 %.
    let off = Scene::parse(
        &text.replace(&format!("{:e}]", -zg), &format!("{:e}]", -1.01 * zg)),
        Path::new("off.toml"),
    )
    .unwrap();
    let e = final_state(&off);
    let d_off = a
        .iter()
        .zip(&e)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(d_off > 1e3 * d, "{d_off} vs {d}");
}

/// A prism posed at an angle in its `[[body]]` table: the body's principal
/// axes are found, and its motion in space is that of the same prism posed
/// along the axes and started with the same attitude and angular velocity
/// in space.
#[test]
fn tables_whose_axes_are_not_principal_give_the_same_motion() {
    let scene = |rotation: &str, attitude: &str, w: Vector3<f64>| {
        let text = format!(
            "name = \"prism\"\nkind = \"free\"\nt_end = 2.0\n[[body]]\nshape = \"prism\"\nmass = 1.5\n\
             a = 0.3\nb = 0.2\nc = 0.1\n{rotation}\n[initial]\n{attitude}\nangular_velocity = [{:e}, {:e}, {:e}]\n",
            w.x, w.y, w.z
        );
        Scene::parse(&text, Path::new("prism.toml")).unwrap()
    };
    let axis = Vector3::new(1.0, 2.0, -0.5).normalize();
    let angle = 0.7_f64;
    let r = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
    let w_local = Vector3::new(0.4, 3.0, -1.2);
    let posed = scene(
        &format!(
            "rotation = {{ axis = [{:e}, {:e}, {:e}], angle_deg = {:e} }}",
            axis.x,
            axis.y,
            axis.z,
            angle.to_degrees()
        ),
        "",
        r * w_local,
    );
    // The same prism posed along the axes, started with its axes where
    // the pose put them.
    let c = r.quaternion().coords;
    let plain = scene(
        "",
        &format!("attitude = [{:e}, {:e}, {:e}, {:e}]", c.w, c.x, c.y, c.z),
        w_local,
    );
    let q0 = |s: &Scene| match &s.kind {
        SceneKind::Free { q0, .. } => *q0,
        _ => unreachable!(),
    };
    // The posed scene's body axes, seen in its tables' axes, are not the
    // tables' own.
    assert!(q0(&posed).angle() > 0.1);
    for t in [0.0, 2.0] {
        let (yp, _) = run::reference_state(&posed, t).unwrap();
        let (yq, _) = run::reference_state(&plain, t).unwrap();
        let att = |y: &[f64; 7]| {
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(y[0], y[1], y[2], y[3]))
        };
        // Orientation in space of the prism's own axes: body attitude, back to
        // the tables' axes, then the pose.
        let local_posed = att(&yp) * q0(&posed).inverse() * r;
        let local_plain = att(&yq);
        assert!(
            local_posed.angle_to(&local_plain) < 1e-10,
            "t = {t}: {}",
            local_posed.angle_to(&local_plain)
        );
        // And the same angular velocity in space.
        let w_space = |y: &[f64; 7]| att(y) * Vector3::new(y[4], y[5], y[6]);
        assert!((w_space(&yp) - w_space(&yq)).norm() < 1e-10 * w_local.norm());
    }
}

/// The keys of the former simulation format are refused, naming the new ones.
#[test]
fn former_keys_are_refused_naming_the_new_ones() {
    let cases = [
        (
            "kind = \"free\"\n[body]\nprincipal_moments = [1.0, 2.0, 2.5]\n",
            "[[body]]",
        ),
        (
            "kind = \"heavy-top\"\n[[body]]\nshape = \"disk\"\nmass = 1.0\nradius = 0.1\n[top]\ndistance = 0.1\n",
            "top.fixed_point",
        ),
        (
            "kind = \"heavy-top\"\n[[body]]\nshape = \"disk\"\nmass = 1.0\nradius = 0.1\n[top]\nfixed_point = [0.0, 0.0, -0.1]\n",
            "g = [0.0, 0.0, -9.81]",
        ),
        (
            "kind = \"heavy-top\"\ng = [0.0, -9.81, 0.0]\n[[body]]\nshape = \"disk\"\nmass = 1.0\nradius = 0.1\n[top]\nfixed_point = [0.0, 0.0, -0.1]\n",
            "along −Z",
        ),
        (
            "kind = \"fixed-axis\"\n[shaft]\nrotor_moment = 0.01\nbearings = [-0.1, 0.1]\n[motor]\nstall_torque = 1.0\n",
            "shape = \"point\"",
        ),
        (
            "kind = \"free\"\n[[body]]\nshape = \"disk\"\nmass = 1.0\nradius = 0.1\nrotation = { euler_deg = [10.0, 0.0, 0.0] }\n",
            "euler_angles = [φ, θ, ψ]",
        ),
    ];
    for (body, says) in cases {
        let text = format!("name = \"old\"\nt_end = 1.0\n{body}");
        let err: SimError = Scene::parse(&text, Path::new("old.toml")).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("old.toml"), "{msg}");
        assert!(msg.contains(says), "`{msg}` lacks `{says}`");
    }
}
