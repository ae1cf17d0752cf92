//! What a file declares for a system of bodies, as data: its generalized
//! speeds with their kinematic equations (`Speeds`) and its applied loads
//! (`Load`). Reading and checking them is `speeds.rs` and `loads.rs`; the
//! context holds them; `ops/kane.rs` uses them.

use crate::atom::{Atom, AtomKind};
use crate::poly::Poly;
use crate::vector::Vec3;

/// The speeds a file declares and its kinematic equations.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Speeds {
    /// The generalized speeds u, in declaration order.
    pub speeds: Vec<Atom>,
    /// q̇ = f(q, u) for each coordinate q (undifferentiated), in the
    /// file's order, abbreviations unfolded.
    pub kinematics: Vec<(Atom, Poly)>,
    /// The Euler parameters of every quaternion frame (scalar part first):
    /// values are reduced modulo their unit norm (`quaternion.rs`).
    pub unit_norms: Vec<[Atom; 4]>,
}

impl Speeds {
    /// Whether the file declares no speeds.
    pub fn is_empty(&self) -> bool {
        self.speeds.is_empty()
    }

    /// The kinematic equation of coordinate `q`.
    pub fn rate_of(&self, q: Atom) -> Option<&Poly> {
        self.kinematics
            .iter()
            .find(|(c, _)| *c == q)
            .map(|(_, f)| f)
    }

    /// `p` with every rate of a coordinate that has a kinematic equation
    /// replaced: q̇ by f(q, u), q̈ by ḟ (whose q̇ are replaced in turn), …
    /// The result holds no rate of those coordinates, and is reduced
    /// modulo the unit norm of the Euler parameters.
    pub fn in_speeds(&self, p: &Poly) -> Poly {
        let mut p = p.clone();
        loop {
            let mut changed = false;
            p = p.subst(&mut |a| match a.kind() {
                AtomKind::Var { order, .. } if order >= 1 => {
                    let f = self.rate_of(a.base())?;
                    changed = true;
                    Some(f.dt_n(order - 1))
                }
                _ => None,
            });
            if !changed {
                return super::quaternion::reduce_all(&p, &self.unit_norms);
            }
        }
    }
}

/// One applied load.
#[derive(Clone, Debug, PartialEq)]
pub enum Load {
    /// A force (components in the frame of that index) at a declared point.
    Force {
        /// The point it acts at.
        point: String,
        /// The force.
        force: Vec3,
        /// The frame of its components.
        frame: usize,
    },
    /// A torque (a couple) on the frame of that index, components in `in_frame`.
    Torque {
        /// The frame (a body's) it turns.
        on: usize,
        /// The torque.
        torque: Vec3,
        /// The frame of its components.
        in_frame: usize,
    },
}
