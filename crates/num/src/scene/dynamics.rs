//! What a scene's problem yields: mass properties about G and the
//! reference, the resultants a motion requires and its unknown loads, the
//! velocities after an impact, and the particle-sum cross-check.

use std::collections::BTreeMap;

use nalgebra::Vector3;

use super::{Problem, Scene};
use crate::body::MassProperties;
use crate::discretize::{Discretization, DiscretizedComposite};
use crate::inertia::{Inertia, Principal};
use crate::solve::{LinearSystem, SolveError};
use crate::sums::{Kinetics, Motion, kinetics, mass_properties, rigid_kinetics};

/// What a problem solves to: the motion (after the impact, for impulse
/// problems) and the unknowns by name, or why they could not be solved.
struct Solved {
    motion: Motion,
    unknowns: Result<Vec<(String, f64)>, SolveError>,
}

/// Unknown names, their force and moment columns (about O), and the known
/// resultant force and moment about O.
type LoadSystem = (
    Vec<String>,
    Vec<Vector3<f64>>,
    Vec<Vector3<f64>>,
    Vector3<f64>,
    Vector3<f64>,
);

/// Mass properties of a scene's body, about G and about the reference.
#[derive(Debug, Clone, PartialEq)]
pub struct InertiaReport {
    /// Mass, centre, inertia about G (world axes).
    pub props: MassProperties,
    /// Inertia about the reference point O (world axes).
    pub inertia_o: Inertia,
    /// Principal moments and axes about G.
    pub principal: Principal,
}

/// Everything `hdot dynamics` reports.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsReport {
    /// Mass properties.
    pub inertia: InertiaReport,
    /// The motion used (after the impact, for impulse problems).
    pub motion: Motion,
    /// Kinetic quantities from the rigid-body formulas (analytic inertia).
    pub kinetics: Kinetics,
    /// The same quantities by particle sums over a discretised copy of the
    /// body, with the rigid formulas evaluated on the *discretised* mass
    /// properties: their largest relative difference (round-off level).
    pub particle_check: f64,
    /// Solved unknowns, by name (empty when there are none).
    pub unknowns: BTreeMap<String, f64>,
    /// Why the unknowns could not be solved, if so.
    pub unsolved: Option<SolveError>,
}

/// Discretisation used for the particle cross-check of scenes.
pub const CHECK_DISCRETIZATION: Discretization = Discretization {
    method: crate::discretize::Method::GaussLegendre(2),
    cells: 6,
};

impl Scene {
    /// Mass properties.
    pub fn inertia(&self) -> InertiaReport {
        let props = self.body.mass_properties();
        InertiaReport {
            inertia_o: props.inertia_about(&self.reference),
            principal: props.principal(),
            props,
        }
    }

    /// The known resultant (weight + known loads) and the equations
    /// `Σ F = rhs_f`, `Σ M_O = rhs_m` in the unknowns.
    fn load_system(&self, props: &MassProperties) -> LoadSystem {
        let o = self.reference;
        let mut names = Vec::new();
        let mut fcols = Vec::new();
        let mut mcols = Vec::new();
        let (mut f_known, mut m_known) = (Vector3::zeros(), Vector3::zeros());
        if let (Some(g), Problem::Motion(_)) = (self.g, &self.problem) {
            let w = g * props.mass;
            f_known += w;
            m_known += (props.center - o).cross(&w);
        }
        for l in &self.forces {
            f_known += l.known;
            m_known += (l.point - o).cross(&l.known);
            for (n, d) in &l.unknowns {
                names.push(n.clone());
                fcols.push(*d);
                mcols.push((l.point - o).cross(d));
            }
        }
        for c in &self.couples {
            m_known += c.known;
            for (n, d) in &c.unknowns {
                names.push(n.clone());
                fcols.push(Vector3::zeros());
                mcols.push(*d);
            }
        }
        (names, fcols, mcols, f_known, m_known)
    }

    /// Solves the scene: kinetic quantities, resultants, unknowns, and the
    /// particle-sum cross-check.
    pub fn dynamics(&self) -> DynamicsReport {
        let inertia = self.inertia();
        let props = inertia.props;
        let loads = self.load_system(&props);
        let mut unknowns = BTreeMap::new();
        let mut unsolved = None;
        let solved = match &self.problem {
            Problem::Statics => self.resultants(&props, Motion::default(), &loads),
            Problem::Motion(m) => self.resultants(&props, *m, &loads),
            Problem::Impulse {
                v_before,
                omega_before,
            } => self.impact(&props, (v_before, omega_before), &loads),
        };
        let motion = match solved {
            Solved {
                motion,
                unknowns: Ok(x),
            } => {
                unknowns.extend(x);
                motion
            }
            Solved {
                motion,
                unknowns: Err(e),
            } => {
                unsolved = Some(e);
                motion
            }
        };
        let kin = rigid_kinetics(&props, &motion, self.reference);
        DynamicsReport {
            particle_check: self.particle_check(&motion),
            inertia,
            motion,
            kinetics: kin,
            unknowns,
            unsolved,
        }
    }

    /// The unknown loads a given motion requires: `Σ F = m ā` and
    /// `Σ M_O = Ḣ_O` in the unknowns, each row scaled by the magnitudes of
    /// the terms that cancel in it.
    fn resultants(&self, props: &MassProperties, motion: Motion, loads: &LoadSystem) -> Solved {
        let (names, fcols, mcols, f_known, m_known) = loads;
        let o = self.reference;
        let k = rigid_kinetics(props, &motion, o);
        let rbar = props.center - o;
        let mut scale_f = k.force.norm() + f_known.norm();
        let mut scale_m = rbar.norm() * k.force.norm() + k.hdot_g.norm() + m_known.norm();
        if let Some(g) = self.g {
            scale_f += (g * props.mass).norm();
            scale_m += rbar.norm() * (g * props.mass).norm();
        }
        for l in self.forces.iter().chain(&self.couples) {
            scale_f += l.known.norm();
            scale_m += ((l.point - o).norm() + 1.0) * l.known.norm();
        }
        if names.is_empty() {
            return Solved {
                motion,
                unknowns: Ok(Vec::new()),
            };
        }
        let mut sys = LinearSystem {
            unknowns: names.clone(),
            ..Default::default()
        };
        for (axis, c) in ["x", "y", "z"].iter().enumerate() {
            sys.push_scaled(
                format!("ΣF_{c}"),
                fcols.iter().map(|v| v[axis]).collect(),
                k.force[axis] - f_known[axis],
                scale_f,
            );
        }
        for (axis, c) in ["x", "y", "z"].iter().enumerate() {
            sys.push_scaled(
                format!("ΣM_{c}"),
                mcols.iter().map(|v| v[axis]).collect(),
                k.moment_o[axis] - m_known[axis],
                scale_m,
            );
        }
        Solved {
            motion,
            unknowns: sys.solve().map(|x| names.iter().cloned().zip(x).collect()),
        }
    }

    /// An impact: v̄ and ω after it, and the unknown impulses, from linear
    /// and angular impulse–momentum and the constraints.
    fn impact(
        &self,
        props: &MassProperties,
        (v_before, omega_before): (&Vector3<f64>, &Vector3<f64>),
        loads: &LoadSystem,
    ) -> Solved {
        let (names, fcols, mcols, f_known, m_known) = loads;
        let o = self.reference;
        // unknowns: v̄ (3), ω (3), then the unknown impulses
        let mut all: Vec<String> = ["v_x", "v_y", "v_z", "omega_x", "omega_y", "omega_z"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        all.extend(names.iter().cloned());
        let n = all.len();
        let mut sys = LinearSystem {
            unknowns: all.clone(),
            ..Default::default()
        };
        let m = props.mass;
        let ig = props.inertia_g.matrix();
        let g = props.center;
        // m v̄₂ − Σ J = m v̄₁ + J_known
        for axis in 0..3 {
            let mut row = vec![0.0; n];
            row[axis] = m;
            for (k, c) in fcols.iter().enumerate() {
                row[6 + k] = -c[axis];
            }
            // The scale holds the terms that cancel in the sum.
            sys.push_scaled(
                format!("linear momentum {}", ["x", "y", "z"][axis]),
                row,
                m * v_before[axis] + f_known[axis],
                m * v_before.norm() + f_known.norm(),
            );
        }
        // I_G ω₂ − Σ (r − G) × J = I_G ω₁ + known angular impulse about G
        let m_known_g = m_known - (g - o).cross(f_known);
        let h1 = ig * omega_before;
        for axis in 0..3 {
            let mut row = vec![0.0; n];
            for j in 0..3 {
                row[3 + j] = ig[(axis, j)];
            }
            for (k, (fc, mc)) in fcols.iter().zip(mcols).enumerate() {
                // moment about G = moment about O − (G − O) × J
                row[6 + k] = -(mc - (g - o).cross(fc))[axis];
            }
            sys.push_scaled(
                format!("angular momentum {}", ["x", "y", "z"][axis]),
                row,
                h1[axis] + m_known_g[axis],
                props.inertia_g.trace().abs() * omega_before.norm()
                    + m_known.norm()
                    + (g - o).norm() * f_known.norm(),
            );
        }
        // constraints: d · (v̄ + ω × (P − G)) = value
        for c in &self.constraints {
            let mut row = vec![0.0; n];
            let r = c.point - g;
            // d · (ω × r) = ω · (r × d)
            let rd = r.cross(&c.direction);
            row[..3].copy_from_slice(c.direction.as_slice());
            row[3..6].copy_from_slice(rd.as_slice());
            sys.push(c.name.clone(), row, c.value);
        }
        match sys.solve() {
            Ok(x) => Solved {
                motion: Motion {
                    omega: Vector3::new(x[3], x[4], x[5]),
                    alpha: Vector3::zeros(),
                    v_g: Vector3::new(x[0], x[1], x[2]),
                    a_g: Vector3::zeros(),
                },
                unknowns: Ok(all.into_iter().zip(x.iter().copied()).collect()),
            },
            Err(e) => Solved {
                motion: Motion::default(),
                unknowns: Err(e),
            },
        }
    }

    /// Largest relative difference between particle sums over a
    /// discretised copy of the body and the rigid-body formulas applied to
    /// that copy's mass properties (a round-off-level check that the
    /// formulas and the sums agree on this scene).
    pub fn particle_check(&self, motion: &Motion) -> f64 {
        let src = DiscretizedComposite::new(&self.body, &CHECK_DISCRETIZATION);
        let Ok(p) = mass_properties(&src) else {
            return f64::NAN;
        };
        // the motion is given for the analytic centre; re-express it for
        // the discretised one (same rigid velocity field)
        let m = Motion {
            v_g: motion.velocity_at(&self.body.mass_properties().center, &p.center),
            a_g: motion.acceleration_at(&self.body.mass_properties().center, &p.center),
            ..*motion
        };
        let s = kinetics(&src, &m, p.center, self.reference);
        let r = rigid_kinetics(&p, &m, self.reference);
        let pairs = [
            (s.h_g, r.h_g),
            (s.h_o, r.h_o),
            (s.force, r.force),
            (s.hdot_g, r.hdot_g),
            (s.moment_o, r.moment_o),
        ];
        // Scales that include the magnitudes of the terms that cancel in
        // the sums (a prism spinning steadily about a principal axis has
        // zero resultants, made of particle terms of size m ω² r): a
        // relative difference is round-off against these, not against a
        // zero result.
        let rg = (p.inertia_g.trace() / p.mass).max(0.0).sqrt();
        let lever = 1.0 + (p.center - self.reference).norm() + rg;
        let (w, al) = (m.omega.norm(), m.alpha.norm());
        let speed = m.v_g.norm() + w * rg;
        let accel = m.a_g.norm() + (al + w * w) * rg;
        let i = p.inertia_g.trace().abs();
        let scale_h =
            s.h_g.norm() + s.h_o.norm() + s.momentum.norm() + i * w + p.mass * speed * lever;
        let scale_a = s.force.norm()
            + s.hdot_g.norm()
            + s.moment_o.norm()
            + i * (al + w * w)
            + p.mass * accel * lever;
        let mut worst: f64 = 0.0;
        for (k, (a, b)) in pairs.iter().enumerate() {
            let scale = if k < 2 { scale_h } else { scale_a };
            if scale > 0.0 {
                worst = worst.max((a - b).norm() / scale);
            }
        }
        if s.kinetic_energy > 0.0 {
            worst = worst.max((s.kinetic_energy - r.kinetic_energy).abs() / s.kinetic_energy);
        }
        worst
    }
}
