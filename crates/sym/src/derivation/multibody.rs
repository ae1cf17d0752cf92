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
        // The kinematic equation of a rate that has one.
        let equation = |a: Atom| match a.kind() {
            AtomKind::Var { order, .. } if order >= 1 => self.rate_of(a.base()),
            _ => None,
        };
        // Passes until no replacement brings in a rate to replace (q̈ → ḟ
        // holds q̇): a pass after that would change nothing, and it was a
        // walk over every atom and a copy of the whole result.
        let mut again = false;
        let pass = |p: &Poly, again: &mut bool| {
            p.subst(&mut |a| {
                let r = equation(a)?.dt_n(a.order() - 1);
                *again |= r.atoms().into_iter().any(|b| equation(b).is_some());
                Some(r)
            })
        };
        let mut p = pass(p, &mut again);
        while again {
            again = false;
            p = pass(&p, &mut again);
        }
        super::quaternion::reduce_all(&p, &self.unit_norms)
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
