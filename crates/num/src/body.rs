//! Bodies: poses, primitives with analytic mass properties, composites,
//! and [`MassProperties`] (mass, centre, inertia about G in world axes).

use nalgebra::{Rotation3, UnitQuaternion, Vector3};

use crate::cloud::ParticleCloud;
use crate::error::BodyError;
use crate::inertia::Inertia;
pub use crate::mass::MassProperties;
use crate::mass::check_mass;

/// Position and attitude of a body's local frame in the world frame.
///
/// The local frame of every primitive has its origin at the primitive's
/// mass centre G and its axes along the axes of symmetry (see
/// [`Primitive`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position of the local origin (the primitive's G) in world axes.
    pub position: Vector3<f64>,
    /// Attitude: local → world rotation.
    pub rotation: UnitQuaternion<f64>,
}

impl Default for Pose {
    fn default() -> Self {
        Self::identity()
    }
}

impl Pose {
    /// The world frame itself.
    pub fn identity() -> Self {
        Self {
            position: Vector3::zeros(),
            rotation: UnitQuaternion::identity(),
        }
    }

    /// A pose from a position and a rotation matrix.
    pub fn new(position: Vector3<f64>, rotation: Rotation3<f64>) -> Self {
        Self {
            position,
            rotation: UnitQuaternion::from_rotation_matrix(&rotation),
        }
    }

    /// A translation only.
    pub fn translation(position: Vector3<f64>) -> Self {
        Self {
            position,
            rotation: UnitQuaternion::identity(),
        }
    }

    /// World coordinates of a point given in the local frame.
    pub fn transform_point(&self, local: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.rotation * local
    }

    /// The rotation as a matrix.
    pub fn rotation_matrix(&self) -> Rotation3<f64> {
        self.rotation.to_rotation_matrix()
    }
}

/// The rotation of the Eulerian angles (φ, θ, ψ) in radians, the one
/// convention of every scene (`docs/scenes.md`) and of the Eulerian-angle
/// models: precession φ about the fixed Z, nutation θ about the line of
/// nodes, spin ψ about the body z, `R = R_Z(φ) R_y(θ) R_z(ψ)` (z-y-z, as in
/// `docs/equations.md` §7).
///
/// # Example
/// ```
/// use hdot_num::body::eulerian_rotation;
/// use hdot_num::nalgebra::Vector3;
/// // θ tips the body z axis from Z towards X (φ = 0).
/// let z = eulerian_rotation(0.0, 0.5, 1.0) * Vector3::z();
/// assert!((z - Vector3::new(0.5f64.sin(), 0.0, 0.5f64.cos())).norm() < 1e-15);
/// ```
pub fn eulerian_rotation(phi: f64, theta: f64, psi: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), theta)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), psi)
}

/// A homogeneous primitive, in its local frame: origin at its mass centre,
/// axis of symmetry along local z unless said otherwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Primitive {
    /// Slender rod along local x, from −L/2 to L/2.
    Rod {
        /// Length L.
        length: f64,
    },
    /// Thin rectangular plate in the local xy plane, `a` along x, `b` along y.
    Plate {
        /// Side along x.
        a: f64,
        /// Side along y.
        b: f64,
    },
    /// Rectangular prism `a` (x) × `b` (y) × `c` (z).
    Prism {
        /// Side along x.
        a: f64,
        /// Side along y.
        b: f64,
        /// Side along z.
        c: f64,
    },
    /// Thin disk in the local xy plane, axis z.
    Disk {
        /// Radius.
        radius: f64,
    },
    /// Solid circular cylinder, axis z, from −L/2 to L/2.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Length L.
        length: f64,
    },
    /// Thick-walled tube, axis z (`inner = outer` is a thin tube,
    /// `inner = 0` a solid cylinder).
    HollowCylinder {
        /// Inner radius.
        inner: f64,
        /// Outer radius.
        outer: f64,
        /// Length.
        length: f64,
    },
    /// Thin ring in the local xy plane, axis z.
    Ring {
        /// Radius.
        radius: f64,
    },
    /// Solid sphere.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// Thin spherical shell.
    SphericalShell {
        /// Radius.
        radius: f64,
    },
    /// Solid right circular cone, axis z, apex up: base at z = −h/4,
    /// apex at z = 3h/4 (G at the origin).
    Cone {
        /// Base radius.
        radius: f64,
        /// Height h.
        height: f64,
    },
}

impl Primitive {
    /// The primitive's lower-case name (as in scene files).
    pub fn name(&self) -> &'static str {
        match self {
            Primitive::Rod { .. } => "rod",
            Primitive::Plate { .. } => "plate",
            Primitive::Prism { .. } => "prism",
            Primitive::Disk { .. } => "disk",
            Primitive::Cylinder { .. } => "cylinder",
            Primitive::HollowCylinder { .. } => "hollow_cylinder",
            Primitive::Ring { .. } => "ring",
            Primitive::Sphere { .. } => "sphere",
            Primitive::SphericalShell { .. } => "spherical_shell",
            Primitive::Cone { .. } => "cone",
        }
    }

    /// Named dimensions, for validation and printing.
    pub fn dimensions(&self) -> Vec<(&'static str, f64)> {
        match *self {
            Primitive::Rod { length } => vec![("length", length)],
            Primitive::Plate { a, b } => vec![("a", a), ("b", b)],
            Primitive::Prism { a, b, c } => vec![("a", a), ("b", b), ("c", c)],
            Primitive::Disk { radius }
            | Primitive::Ring { radius }
            | Primitive::Sphere { radius }
            | Primitive::SphericalShell { radius } => vec![("radius", radius)],
            Primitive::Cylinder { radius, length } => vec![("radius", radius), ("length", length)],
            Primitive::HollowCylinder {
                inner,
                outer,
                length,
            } => vec![("inner", inner), ("outer", outer), ("length", length)],
            Primitive::Cone { radius, height } => vec![("radius", radius), ("height", height)],
        }
    }

    /// Checks that every dimension is finite and positive (the inner
    /// radius of a tube may be zero and must not exceed the outer).
    pub fn validate(&self) -> Result<(), BodyError> {
        let what = self.name().to_string();
        for (field, value) in self.dimensions() {
            if !value.is_finite() {
                return Err(BodyError::NotFinite { what, field, value });
            }
            let may_be_zero = field == "inner";
            if value < 0.0 || (value == 0.0 && !may_be_zero) {
                return Err(BodyError::BadDimension {
                    what,
                    field,
                    value,
                    reason: "must be positive",
                });
            }
        }
        if let Primitive::HollowCylinder { inner, outer, .. } = *self
            && inner > outer
        {
            return Err(BodyError::BadDimension {
                what,
                field: "inner",
                value: inner,
                reason: "inner radius exceeds outer radius",
            });
        }
        Ok(())
    }

    /// Analytic principal moments `[I_x, I_y, I_z]` about G in the local
    /// axes, for mass `m` (the table of `docs/equations.md` §11).
    ///
    /// # Example
    /// ```
    /// use hdot_num::Primitive;
    /// let [ix, iy, iz] = Primitive::Disk { radius: 2.0 }.local_moments(3.0);
    /// assert_eq!((ix, iy, iz), (3.0, 3.0, 6.0));
    /// ```
    pub fn local_moments(&self, m: f64) -> [f64; 3] {
        match *self {
            Primitive::Rod { length: l } => [0.0, m * l * l / 12.0, m * l * l / 12.0],
            Primitive::Plate { a, b } => [
                m * b * b / 12.0,
                m * a * a / 12.0,
                m * (a * a + b * b) / 12.0,
            ],
            Primitive::Prism { a, b, c } => [
                m * (b * b + c * c) / 12.0,
                m * (c * c + a * a) / 12.0,
                m * (a * a + b * b) / 12.0,
            ],
            Primitive::Disk { radius: r } => [m * r * r / 4.0, m * r * r / 4.0, m * r * r / 2.0],
            Primitive::Cylinder {
                radius: r,
                length: l,
            } => {
                let t = m * (3.0 * r * r + l * l) / 12.0;
                [t, t, m * r * r / 2.0]
            }
            Primitive::HollowCylinder {
                inner,
                outer,
                length: l,
            } => {
                let s = inner * inner + outer * outer;
                let t = m * (3.0 * s + l * l) / 12.0;
                [t, t, m * s / 2.0]
            }
            Primitive::Ring { radius: r } => [m * r * r / 2.0, m * r * r / 2.0, m * r * r],
            Primitive::Sphere { radius: r } => [0.4 * m * r * r; 3],
            Primitive::SphericalShell { radius: r } => [2.0 * m * r * r / 3.0; 3],
            Primitive::Cone {
                radius: r,
                height: h,
            } => {
                let t = 3.0 * m * r * r / 20.0 + 3.0 * m * h * h / 80.0;
                [t, t, 3.0 * m * r * r / 10.0]
            }
        }
    }
}

/// A posed homogeneous primitive with its mass. Invariant: validated
/// dimensions, positive finite mass, finite pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    shape: Primitive,
    mass: f64,
    pose: Pose,
}

/// # Construction
impl Body {
    /// A body, checked (positive finite mass, valid dimensions, finite
    /// pose).
    pub fn try_new(shape: Primitive, mass: f64, pose: Pose) -> Result<Self, BodyError> {
        shape.validate()?;
        let what = shape.name().to_string();
        check_mass(&what, mass)?;
        let p = pose.position;
        for (field, value) in [("x", p.x), ("y", p.y), ("z", p.z)] {
            if !value.is_finite() {
                return Err(BodyError::NotFinite { what, field, value });
            }
        }
        let q = pose.rotation.coords;
        if q.iter().any(|v| !v.is_finite()) {
            return Err(BodyError::NotFinite {
                what,
                field: "rotation",
                value: f64::NAN,
            });
        }
        Ok(Self { shape, mass, pose })
    }
}

/// # Access and mass properties
impl Body {
    /// The primitive.
    pub fn shape(&self) -> &Primitive {
        &self.shape
    }
    /// The mass.
    pub fn mass(&self) -> f64 {
        self.mass
    }
    /// The pose.
    pub fn pose(&self) -> &Pose {
        &self.pose
    }

    /// Analytic mass properties in world axes.
    pub fn mass_properties(&self) -> MassProperties {
        let [ix, iy, iz] = self.shape.local_moments(self.mass);
        let local =
            Inertia::new_unchecked(nalgebra::Matrix3::from_diagonal(&Vector3::new(ix, iy, iz)));
        MassProperties {
            mass: self.mass,
            center: self.pose.position,
            inertia_g: local.rotated(&self.pose.rotation_matrix()),
        }
    }
}

/// One part of a composite.
#[derive(Debug, Clone, PartialEq)]
pub enum Part {
    /// A posed primitive.
    Solid(Body),
    /// A particle cloud in world coordinates.
    Cloud(ParticleCloud),
}

impl Part {
    /// Mass properties of the part (analytic for a primitive, exact sums
    /// for a cloud).
    pub fn mass_properties(&self) -> MassProperties {
        match self {
            Part::Solid(b) => b.mass_properties(),
            Part::Cloud(c) => c.mass_properties(),
        }
    }
}

/// A rigid assembly of parts. Invariant: at least one part.
#[derive(Debug, Clone, PartialEq)]
pub struct Composite {
    parts: Vec<Part>,
}

impl Composite {
    /// A composite, checked non-empty.
    pub fn try_new(parts: Vec<Part>) -> Result<Self, BodyError> {
        if parts.is_empty() {
            return Err(BodyError::Empty {
                what: "composite".into(),
            });
        }
        Ok(Self { parts })
    }
    /// The parts.
    pub fn parts(&self) -> &[Part] {
        &self.parts
    }
    /// Mass properties of the assembly (parallel-axis sum of the parts).
    pub fn mass_properties(&self) -> MassProperties {
        let props: Vec<MassProperties> = self.parts.iter().map(Part::mass_properties).collect();
        MassProperties::combine(&props).expect("composite is non-empty with positive masses")
    }
}
