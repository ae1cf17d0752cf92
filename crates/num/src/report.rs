//! What `hdot inertia` and `hdot dynamics` print: one serialisable report
//! (the JSON keys of `docs/cli-numeric.md`) and its text form.

use std::collections::BTreeMap;
use std::fmt::Write;

use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

use crate::scene::{Problem, Scene};

/// A 3-vector as JSON.
pub type Vec3 = [f64; 3];
/// A 3×3 matrix as JSON, row-major.
pub type Mat3 = [[f64; 3]; 3];

fn v(a: &Vector3<f64>) -> Vec3 {
    [a.x, a.y, a.z]
}

fn m(a: &Matrix3<f64>) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[(i, j)]))
}

/// The report of a scene. Field names are the JSON keys.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Scene title.
    pub name: String,
    /// `statics`, `motion` or `impulse`.
    pub problem: &'static str,
    /// Reference point O.
    pub reference: Vec3,
    /// Total mass.
    pub mass: f64,
    /// Mass centre G.
    pub center: Vec3,
    /// Inertia tensor about G, world axes (products with a minus sign).
    #[serde(rename = "inertia_G")]
    pub inertia_g: Mat3,
    /// Inertia tensor about O, world axes.
    #[serde(rename = "inertia_O")]
    pub inertia_o: Mat3,
    /// Principal moments about G, ascending.
    pub principal_moments: Vec3,
    /// Principal axes: `principal_axes[i]` is the unit axis of moment `i`.
    pub principal_axes: [Vec3; 3],
    /// Angular momentum about G (absent for `hdot inertia`).
    #[serde(rename = "H_G", skip_serializing_if = "Option::is_none")]
    pub h_g: Option<Vec3>,
    /// Angular momentum about O.
    #[serde(rename = "H_O", skip_serializing_if = "Option::is_none")]
    pub h_o: Option<Vec3>,
    /// Kinetic energy.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kinetic_energy: Option<f64>,
    /// Resultant of the external forces the motion requires, m ā.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resultant_force: Option<Vec3>,
    /// Resultant moment about O the motion requires (Σ M_O).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resultant_moment: Option<Vec3>,
    /// Resultant moment about G, Ḣ_G = I α + ω × (I ω).
    #[serde(rename = "resultant_moment_G", skip_serializing_if = "Option::is_none")]
    pub resultant_moment_g: Option<Vec3>,
    /// Solved unknowns by name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unknowns: Option<BTreeMap<String, f64>>,
    /// Why the unknowns were not solved (underdetermined, inconsistent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unsolved: Option<String>,
    /// Largest relative difference between particle sums and rigid-body
    /// formulas on a discretised copy of the body.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub particle_check: Option<f64>,
}

impl Report {
    /// Mass properties only (`hdot inertia`).
    pub fn inertia(scene: &Scene) -> Self {
        let r = scene.inertia();
        let axes = r.principal.axes.matrix();
        Report {
            name: scene.name.clone(),
            problem: "statics",
            reference: v(&scene.reference),
            mass: r.props.mass,
            center: v(&r.props.center),
            inertia_g: m(r.props.inertia_g.matrix()),
            inertia_o: m(r.inertia_o.matrix()),
            principal_moments: v(&r.principal.moments),
            principal_axes: std::array::from_fn(|i| v(&axes.column(i).into_owned())),
            h_g: None,
            h_o: None,
            kinetic_energy: None,
            resultant_force: None,
            resultant_moment: None,
            resultant_moment_g: None,
            unknowns: None,
            unsolved: None,
            particle_check: None,
        }
    }

    /// Everything (`hdot dynamics`).
    pub fn dynamics(scene: &Scene) -> Self {
        let d = scene.dynamics();
        let mut r = Self::inertia(scene);
        let k = d.kinetics;
        let impulse = matches!(scene.problem, Problem::Impulse { .. });
        r.problem = match scene.problem {
            Problem::Statics => "statics",
            Problem::Motion(_) => "motion",
            Problem::Impulse { .. } => "impulse",
        };
        r.h_g = Some(v(&k.h_g));
        r.h_o = Some(v(&k.h_o));
        r.kinetic_energy = Some(k.kinetic_energy);
        if !impulse {
            r.resultant_force = Some(v(&k.force));
            r.resultant_moment = Some(v(&k.moment_o));
            r.resultant_moment_g = Some(v(&k.hdot_g));
        }
        r.unknowns = Some(d.unknowns);
        r.unsolved = d.unsolved.map(|e| e.to_string());
        r.particle_check = Some(d.particle_check);
        r
    }

    /// The first reported quantity that is not finite, by its JSON key
    /// (`None` when every number is finite). A report holding one is not
    /// printed: the command fails naming the quantity instead.
    pub fn non_finite(&self) -> Option<String> {
        let bad = |xs: &[f64]| xs.iter().any(|x| !x.is_finite());
        let mut named: Vec<(String, Vec<f64>)> = vec![
            ("mass".into(), vec![self.mass]),
            ("center".into(), self.center.to_vec()),
            ("reference".into(), self.reference.to_vec()),
            ("inertia_G".into(), self.inertia_g.concat()),
            ("inertia_O".into(), self.inertia_o.concat()),
            ("principal_moments".into(), self.principal_moments.to_vec()),
            ("principal_axes".into(), self.principal_axes.concat()),
        ];
        for (k, x) in [
            ("H_G", &self.h_g),
            ("H_O", &self.h_o),
            ("resultant_force", &self.resultant_force),
            ("resultant_moment", &self.resultant_moment),
            ("resultant_moment_G", &self.resultant_moment_g),
        ] {
            if let Some(x) = x {
                named.push((k.into(), x.to_vec()));
            }
        }
        if let Some(t) = self.kinetic_energy {
            named.push(("kinetic_energy".into(), vec![t]));
        }
        for (k, x) in self.unknowns.iter().flatten() {
            named.push((format!("unknowns.{k}"), vec![*x]));
        }
        named.into_iter().find(|(_, xs)| bad(xs)).map(|(k, _)| k)
    }

    /// Human-readable form (`--format text`), with `digits` significant
    /// digits.
    pub fn text(&self, digits: usize) -> String {
        // Round-off of an exact zero prints as 0 relative to the size of
        // the numbers it stands among, never to an absolute threshold (a
        // body of 1 mg and 1 mm has moments of 1e-13 that must print):
        // each group's largest entry, and for the rates the body's own
        // units (mass m, length L, per second) when the group is all zero.
        let mag = |xs: &[f64]| xs.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let opt_mag = |xs: &[&Option<Vec3>]| {
            xs.iter()
                .copied()
                .flatten()
                .fold(0.0_f64, |a, v| a.max(mag(v)))
        };
        let moments = mag(&self.principal_moments)
            .max(mag(&self.inertia_g.concat()))
            .max(mag(&self.inertia_o.concat()));
        let length = mag(&self.center)
            .max(mag(&self.reference))
            .max((mag(&self.principal_moments) / self.mass).sqrt());
        let (m, l) = (self.mass, length);
        let momenta = opt_mag(&[&self.h_g, &self.h_o]).max(m * l * l);
        let force = opt_mag(&[&self.resultant_force]).max(m * l);
        let moment = opt_mag(&[&self.resultant_moment, &self.resultant_moment_g]).max(m * l * l);
        let f = |x: f64, scale: f64| fmt_num_at(x, scale, digits);
        let fv = |a: &Vec3, scale: f64| {
            format!(
                "({}, {}, {})",
                f(a[0], scale),
                f(a[1], scale),
                f(a[2], scale)
            )
        };
        let mut s = String::new();
        let _ = writeln!(s, "{}", self.name);
        let _ = writeln!(s, "  mass              {}", f(self.mass, self.mass));
        let _ = writeln!(s, "  centre G          {}", fv(&self.center, length));
        let _ = writeln!(s, "  reference O       {}", fv(&self.reference, length));
        for (label, mat) in [
            ("inertia about G", &self.inertia_g),
            ("inertia about O", &self.inertia_o),
        ] {
            let _ = writeln!(s, "  {label} (world axes):");
            for row in mat {
                let _ = writeln!(
                    s,
                    "    [{:>12} {:>12} {:>12}]",
                    f(row[0], moments),
                    f(row[1], moments),
                    f(row[2], moments)
                );
            }
        }
        let _ = writeln!(
            s,
            "  principal moments {}",
            fv(&self.principal_moments, moments)
        );
        for (i, a) in self.principal_axes.iter().enumerate() {
            let _ = writeln!(s, "  principal axis {}  {}", i + 1, fv(a, 1.0));
        }
        if self.h_g.is_some() {
            let _ = writeln!(s, "  problem           {}", self.problem);
        }
        let opt = |s: &mut String, label: &str, x: &Option<Vec3>, scale: f64| {
            if let Some(x) = x {
                let _ = writeln!(s, "  {label:<17} {}", fv(x, scale));
            }
        };
        opt(&mut s, "H_G", &self.h_g, momenta);
        opt(&mut s, "H_O", &self.h_o, momenta);
        if let Some(t) = self.kinetic_energy {
            let _ = writeln!(s, "  kinetic energy    {}", f(t, t.abs().max(m * l * l)));
        }
        opt(&mut s, "ΣF = m ā", &self.resultant_force, force);
        opt(&mut s, "ΣM_O", &self.resultant_moment, moment);
        opt(&mut s, "ΣM_G = Ḣ_G", &self.resultant_moment_g, moment);
        if let Some(u) = &self.unknowns
            && !u.is_empty()
        {
            let scale = u.iter().fold(force.min(moment), |a, (_, x)| a.max(x.abs()));
            let _ = writeln!(s, "  unknowns:");
            for (k, x) in u {
                let _ = writeln!(s, "    {k:<14} = {}", f(*x, scale));
            }
        }
        if let Some(e) = &self.unsolved {
            let _ = writeln!(s, "  unknowns not solved: {e}");
        }
        if let Some(c) = self.particle_check {
            if c <= 1e-9 {
                let _ = writeln!(
                    s,
                    "  particle-sum check: ok (relative difference below 1e-9)"
                );
            } else {
                let _ = writeln!(
                    s,
                    "  particle-sum check: MISMATCH (relative difference {c:.1e})"
                );
            }
        }
        s
    }
}

/// `x` with `digits` significant digits; values below 10⁻¹² of `scale`
/// (round-off of an exact zero among numbers of that size) print as 0.
pub fn fmt_num_at(x: f64, scale: f64, digits: usize) -> String {
    if x == 0.0 || x.abs() < 1e-12 * scale.abs() {
        return "0".into();
    }
    let e = x.abs().log10().floor() as i32;
    if (-4..=6).contains(&e) {
        let decimals = (digits as i32 - 1 - e).max(0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{x:.prec$e}", prec = digits.saturating_sub(1))
    }
}
