//! The shapes a simulation page draws, from a scene's `[[body]]` and
//! `[[cloud]]` tables: each primitive with its dimensions and pose, and a
//! body known only by its moments (or a cloud of points) as the box of the
//! same moments — or, when two of them are equal (a wheel given by its
//! moments), the cylinder of the same moments.

use hdot_num::nalgebra::{Matrix3, Vector3};
use hdot_num::{Composite, MassProperties, Part, Primitive};
use serde_json::{Value, json};

/// One drawn part, in the drawing frame's axes (the tables' axes, moved
/// by `-origin`).
#[derive(Debug, Clone)]
pub struct Shape {
    /// `rod`, `box`, `disk`, `ring`, `cylinder`, `sphere`, `cone`, `point`.
    pub kind: &'static str,
    /// Dimensions: rod `[L]`; box `[a, b, c]`; disk, ring, sphere `[r]`;
    /// cylinder `[r, L]`; cone `[r, h]` (base at −h/4); point `[]`.
    pub dims: Vec<f64>,
    /// Position of the part's centre.
    pub position: Vector3<f64>,
    /// The part's local axes (columns) in the drawing frame's axes.
    pub axes: Matrix3<f64>,
}

impl Shape {
    /// The radius of a sphere about the drawing frame's origin that holds it.
    pub fn reach(&self) -> f64 {
        let own = match self.kind {
            "box" => 0.5 * self.dims.iter().map(|d| d * d).sum::<f64>().sqrt(),
            "cylinder" => self.dims[0].hypot(0.5 * self.dims[1]),
            "cone" => self.dims[0].hypot(0.75 * self.dims[1]),
            "rod" => 0.5 * self.dims[0],
            "point" => 0.0,
            _ => self.dims[0],
        };
        self.position.norm() + own
    }

    /// The part as the page's data.
    pub fn to_json(&self) -> Value {
        let a = &self.axes;
        json!({
            "k": self.kind,
            "d": self.dims.iter().map(|v| round(*v)).collect::<Vec<_>>(),
            "p": [round(self.position.x), round(self.position.y), round(self.position.z)],
            "r": (0..3).flat_map(|i| (0..3).map(move |j| round(a[(i, j)]))).collect::<Vec<_>>(),
        })
    }
}

/// A number with 6 significant digits (the page's data need no more).
pub fn round(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return 0.0;
    }
    let e = 5 - v.abs().log10().floor() as i32;
    let p = 10f64.powi(e.clamp(-300, 300));
    (v * p).round() / p
}

/// The shapes of `body`, moved by `-origin`.
pub fn shapes(body: &Composite, origin: &Vector3<f64>) -> Vec<Shape> {
    body.parts()
        .iter()
        .flat_map(|part| match part {
            Part::Solid(b) => {
                let pose = b.pose();
                let axes = *pose.rotation_matrix().matrix();
                let position = pose.position - origin;
                let (kind, dims) = primitive(b.shape());
                vec![Shape {
                    kind,
                    dims,
                    position,
                    axes,
                }]
            }
            Part::Cloud(c) if c.len() == 1 => {
                let (p, _) = c.particle(0);
                vec![Shape {
                    kind: "point",
                    dims: vec![],
                    position: p - origin,
                    axes: Matrix3::identity(),
                }]
            }
            Part::Cloud(c) => vec![moments_box(&c.mass_properties(), origin)],
        })
        .collect()
}

fn primitive(p: &Primitive) -> (&'static str, Vec<f64>) {
    match *p {
        Primitive::Rod { length } => ("rod", vec![length]),
        Primitive::Plate { a, b } => ("box", vec![a, b, 0.0]),
        Primitive::Prism { a, b, c } => ("box", vec![a, b, c]),
        Primitive::Disk { radius } => ("disk", vec![radius]),
        Primitive::Ring { radius } => ("ring", vec![radius]),
        Primitive::Cylinder { radius, length } => ("cylinder", vec![radius, length]),
        Primitive::HollowCylinder { outer, length, .. } => ("cylinder", vec![outer, length]),
        Primitive::Sphere { radius } | Primitive::SphericalShell { radius } => {
            ("sphere", vec![radius])
        }
        Primitive::Cone { radius, height } => ("cone", vec![radius, height]),
    }
}

/// The homogeneous box with the mass and principal moments of `props`,
/// along its principal axes: `a² = 6 (I₂ + I₃ − I₁) / m`, and so on; when
/// exactly two moments are equal, the homogeneous cylinder with them,
/// along the third axis: `r² = 2 I_a / m`, `L² = (12 I_d − 6 I_a) / m`
/// (I_a about the axis, I_d across it; `I_a ≤ 2 I_d` for a real body).
fn moments_box(props: &MassProperties, origin: &Vector3<f64>) -> Shape {
    let p = props.principal();
    let i = p.moments;
    let m = props.mass;
    // The distinct moment's index, when the other two are a repeated pair.
    let axial = match p.multiplicity {
        [1, 2, 2] => Some(0),
        [2, 2, 1] => Some(2),
        _ => None,
    };
    if let Some(k) = axial {
        let (a, d) = (i[k], i[(k + 1) % 3]);
        let c = p.axes.matrix();
        // Columns turned cyclically (a proper rotation) so the axis is z.
        let axes = Matrix3::from_columns(&[
            c.column((k + 1) % 3).into_owned(),
            c.column((k + 2) % 3).into_owned(),
            c.column(k).into_owned(),
        ]);
        return Shape {
            kind: "cylinder",
            dims: vec![
                (2.0 * a / m).max(0.0).sqrt(),
                ((12.0 * d - 6.0 * a) / m).max(0.0).sqrt(),
            ],
            position: props.center - origin,
            axes,
        };
    }
    let side = |a: f64, b: f64, c: f64| (6.0 * (b + c - a) / m).max(0.0).sqrt();
    Shape {
        kind: "box",
        dims: vec![
            side(i[0], i[1], i[2]),
            side(i[1], i[2], i[0]),
            side(i[2], i[0], i[1]),
        ],
        position: props.center - origin,
        axes: *p.axes.matrix(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hdot_num::ParticleCloud;

    /// The box of a cloud's moments has the cloud's moments (the box's
    /// `I₁ = m (b² + c²) / 12`), to round-off of the eigen-solver.
    #[test]
    fn the_box_of_the_moments_has_the_moments() {
        let pts = [
            (Vector3::new(0.3, 0.0, 0.0), 1.0),
            (Vector3::new(-0.3, 0.0, 0.0), 1.0),
            (Vector3::new(0.0, 0.1, 0.05), 2.0),
            (Vector3::new(0.0, -0.1, -0.05), 2.0),
        ];
        let cloud = ParticleCloud::try_from_particles(pts).unwrap();
        let props = cloud.mass_properties();
        let b = moments_box(&props, &Vector3::zeros());
        let p = props.principal();
        let [a, bb, c] = [b.dims[0], b.dims[1], b.dims[2]];
        let m = props.mass;
        let got = [
            m * (bb * bb + c * c) / 12.0,
            m * (a * a + c * c) / 12.0,
            m * (a * a + bb * bb) / 12.0,
        ];
        let scale = p.moments.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for k in 0..3 {
            assert!(
                (got[k] - p.moments[k]).abs() <= 1e-12 * scale,
                "{got:?} vs {:?}",
                p.moments
            );
        }
    }

    /// A cloud with two equal moments (a wheel's six equivalent points)
    /// is drawn as the cylinder of its moments, along its distinct axis.
    #[test]
    fn the_cylinder_of_axisymmetric_moments_has_the_moments() {
        let (m, r, h) = (2.0, 0.3, 0.05);
        let pts = [
            (Vector3::new(r, 0.0, 0.0), m / 6.0),
            (Vector3::new(-r, 0.0, 0.0), m / 6.0),
            (Vector3::new(0.0, h, 0.0), m / 6.0),
            (Vector3::new(0.0, -h, 0.0), m / 6.0),
            (Vector3::new(0.0, 0.0, r), m / 6.0),
            (Vector3::new(0.0, 0.0, -r), m / 6.0),
        ];
        let props = ParticleCloud::try_from_particles(pts)
            .unwrap()
            .mass_properties();
        let s = moments_box(&props, &Vector3::zeros());
        assert_eq!(s.kind, "cylinder");
        let [rad, len] = [s.dims[0], s.dims[1]];
        let axial = m * rad * rad / 2.0;
        let across = m * (3.0 * rad * rad + len * len) / 12.0;
        let i = props.inertia_g.matrix();
        let scale = i.trace();
        assert!((axial - i[(1, 1)]).abs() <= 1e-12 * scale, "{axial} vs {i}");
        assert!(
            (across - i[(0, 0)]).abs() <= 1e-12 * scale,
            "{across} vs {i}"
        );
        // Along the distinct axis, y, and a proper rotation.
        assert!((s.axes.column(2).dot(&Vector3::y()).abs() - 1.0).abs() < 1e-12);
        assert!((s.axes.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rounding_keeps_six_significant_digits() {
        for (v, r) in [
            (1.23456789, 1.23457),
            (-0.000123456789, -0.000123457),
            (98765432.1, 98765400.0),
        ] {
            assert!(
                (round(v) - r).abs() <= 1e-12 * r.abs(),
                "{v} → {}",
                round(v)
            );
        }
    }
}
