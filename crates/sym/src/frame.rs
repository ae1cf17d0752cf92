//! Reference frames that carry their angular velocity.
//!
//! A frame's angular velocity Ω (relative to the inertial frame N) is held
//! by its components *in the frame itself*. The time derivative of a vector
//! expressed in a rotating frame is the transport theorem:
//! `(dQ/dt)_N = (dQ/dt)_rel + Ω × Q`.
//!
//! # Example
//! ```
//! use hdot_sym::{Frame, Symbols, Vec3};
//! let s = Symbols::parse_decl(&["I"], &["w_x", "w_y", "w_z"]);
//! let p = |t: &str| s.poly(t).unwrap();
//! let b = Frame::rotating("B", Vec3::new([p("w_x"), p("w_y"), p("w_z")]));
//! let h = Vec3::new([p("I*w_x"), p("I*w_y"), p("I*w_z")]);
//! let hdot = b.dt(&h);
//! assert_eq!(hdot.0[0], p("I*w_x'")); // ω × Iω = 0 for a sphere
//! ```

use crate::vector::{Mat3, Vec3};

/// A reference frame.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The frame's name as written in the derivation file.
    pub name: String,
    /// Names of its three axes (`x, y, z` or `1, 2, 3`).
    pub axes: [String; 3],
    /// Angular velocity relative to the inertial frame, in this frame's components.
    pub omega: Vec3,
    /// The parent frame and the matrix taking this frame's components to the
    /// parent's (`v_parent = R v_self`), when the frame is defined by a rotation.
    pub parent: Option<(String, Mat3)>,
    /// The Euler parameters (scalar part first) when the rotation from the
    /// parent is `quaternion(e_0, e_1, e_2, e_3)`: the matrix is quadratic
    /// in them and they keep a unit norm.
    pub quaternion: Option<[crate::atom::Atom; 4]>,
    /// One-line description.
    pub doc: String,
}

impl Frame {
    /// The inertial frame `N` (Ω = 0).
    pub fn inertial(name: &str) -> Frame {
        Frame {
            name: name.to_owned(),
            axes: ["x".into(), "y".into(), "z".into()],
            omega: Vec3::zero(),
            parent: None,
            quaternion: None,
            doc: String::new(),
        }
    }

    /// A frame rotating with angular velocity `omega` (its own components).
    pub fn rotating(name: &str, omega: Vec3) -> Frame {
        Frame {
            omega,
            ..Frame::inertial(name)
        }
    }

    /// The inertial-frame time derivative of a vector expressed in this frame:
    /// component derivatives plus Ω × v.
    pub fn dt(&self, v: &Vec3) -> Vec3 {
        v.dt().add(&self.omega.cross(v))
    }
}
