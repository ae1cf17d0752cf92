//! Where a simulation page's view puts things: each drawn group's place in
//! space at every frame (a derived scene's body at its reference point,
//! evaluated by the derivation's model), the view's turn that puts up —
//! against gravity — at the top of the canvas, and the view's scale and
//! centre: fixed on the origin when everything stays near it, following
//! the bodies when they travel far compared with their size (a disk
//! rolling along its path, a bicycle riding away).

use hdot_num::nalgebra::{Rotation3, Vector3};
use hdot_sim::scene::Scene;
use serde_json::{Value, json};

use super::shapes::round;

/// How much farther than their own size the bodies must travel before
/// the view follows them instead of holding the origin.
pub const FOLLOW_RATIO: f64 = 3.0;

/// The radius a following view shows, in units of the bodies' own reach
/// about their centre: room for the paths behind them.
pub const FOLLOW_ROOM: f64 = 1.2;

/// The turn from space axes to the view's axes that takes `up` to +Z (the
/// canvas' up): the shortest one, or half a turn about X when `up` is −Z
/// (a scene whose Z points down: X stays, Y and Z change sign). The
/// identity without an up.
pub fn upright(up: Option<Vector3<f64>>) -> Rotation3<f64> {
    let Some(up) = up.filter(|u| u.norm() > 0.0 && u.iter().all(|c| c.is_finite())) else {
        return Rotation3::identity();
    };
    Rotation3::rotation_between(&up, &Vector3::z())
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI))
}

/// The unit vector of gravity in space axes, for the page: the scene's
/// `g` when it gives one, else a derived scene's gravity (its
/// derivation's, with the scene's constants); `None` without gravity.
pub fn gravity(scene: &Scene) -> Option<Vector3<f64>> {
    let g = scene.bodies.g.or_else(|| {
        scene
            .derivation()
            .and_then(|ds| ds.model.gravity(0.0, &ds.y0))
    })?;
    let n = g.norm();
    (n > 0.0 && n.is_finite()).then(|| g / n)
}

/// One drawn group as the view places it.
#[derive(Debug, Clone)]
pub struct Placed {
    /// Its reference point in space at each frame; `None`: at the origin.
    pub positions: Option<Vec<Vector3<f64>>>,
    /// The radius about that point that holds its shapes.
    pub reach: f64,
}

/// The view's scale (the radius it shows about its centre) and, when it
/// follows the bodies, its centre at each frame: the mean of the groups'
/// places. `extra` is a radius about the origin the view must hold too
/// (a shaft's bearings).
pub fn framing(groups: &[Placed], frames: usize, extra: f64) -> (f64, Option<Vec<Vector3<f64>>>) {
    let at = |g: &Placed, i: usize| g.positions.as_ref().map_or_else(Vector3::zeros, |p| p[i]);
    let fixed = groups
        .iter()
        .flat_map(|g| (0..frames).map(move |i| at(g, i).norm() + g.reach))
        .fold(extra, f64::max);
    let moves = groups.iter().any(|g| g.positions.is_some());
    if !moves || groups.is_empty() {
        return (fixed, None);
    }
    let centres: Vec<Vector3<f64>> = (0..frames)
        .map(|i| groups.iter().map(|g| at(g, i)).sum::<Vector3<f64>>() / groups.len() as f64)
        .collect();
    let follow = groups
        .iter()
        .flat_map(|g| {
            let c = &centres;
            (0..frames).map(move |i| (at(g, i) - c[i]).norm() + g.reach)
        })
        .fold(0.0f64, f64::max);
    if fixed > FOLLOW_RATIO * follow && follow > 0.0 {
        (FOLLOW_ROOM * follow, Some(centres))
    } else {
        (fixed, None)
    }
}

/// Points at each frame as the page's data: 3 numbers per frame.
pub fn track_json(points: &[Vector3<f64>]) -> Value {
    Value::from(
        points
            .iter()
            .flat_map(|p| [round(p.x), round(p.y), round(p.z)])
            .collect::<Vec<_>>(),
    )
}

/// A rotation as the page's data: 9 numbers, row-major (round-off of a
/// quarter or half turn's zeros written 0).
pub fn rotation_json(r: &Rotation3<f64>) -> Value {
    let m = r.matrix();
    let entry = |v: f64| if v.abs() < 1e-12 { 0.0 } else { round(v) };
    json!(
        (0..3)
            .flat_map(|i| (0..3).map(move |j| entry(m[(i, j)])))
            .collect::<Vec<_>>()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Up goes to the canvas' up, and the turn is proper; a Z-down scene
    /// keeps its X.
    #[test]
    fn upright_takes_up_to_z() {
        for up in [
            Vector3::z(),
            -Vector3::z(),
            Vector3::y(),
            Vector3::new(0.3, -0.4, 0.5).normalize(),
        ] {
            let r = upright(Some(up));
            assert!((r * up - Vector3::z()).norm() < 1e-12, "{up}");
            assert!((r.matrix().determinant() - 1.0).abs() < 1e-12);
        }
        assert!((upright(Some(-Vector3::z())) * Vector3::x() - Vector3::x()).norm() < 1e-12);
        assert_eq!(upright(None), Rotation3::identity());
    }

    /// Bodies that stay near the origin are framed about it; a body that
    /// travels twenty times its size is followed.
    #[test]
    fn the_view_follows_only_a_body_that_travels() {
        let near = Placed {
            positions: Some(vec![
                Vector3::new(1.0, 0.0, 0.0),
                Vector3::new(0.0, 1.0, 0.0),
            ]),
            reach: 0.8,
        };
        let pivot = Placed {
            positions: None,
            reach: 1.0,
        };
        let (scale, centre) = framing(&[pivot, near], 2, 0.0);
        assert!(centre.is_none());
        assert!((scale - 1.8).abs() < 1e-12, "{scale}");
        let far = Placed {
            positions: Some(vec![Vector3::zeros(), Vector3::new(6.0, 0.0, 0.0)]),
            reach: 0.3,
        };
        let (scale, centre) = framing(&[far], 2, 0.0);
        assert!((scale - FOLLOW_ROOM * 0.3).abs() < 1e-12, "{scale}");
        assert_eq!(centre.unwrap()[1], Vector3::new(6.0, 0.0, 0.0));
    }
}
