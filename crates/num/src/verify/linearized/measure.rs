//! The measurement half of [`super::Plan`]: per draw, the Jacobian of
//! −(F_r + F_r*) on the particles at the operating point by central
//! differences (Richardson-extrapolated in a coordinate, exact but for
//! round-off in a speed or a rate; the module doc of [`super`] gives the
//! steps and the error estimates), and each inferred step compared with
//! its entries. The plan itself — which steps are measured, and why the
//! others are not — is read from the file in [`super`].

use hdot_sym::atom::Atom;
use hdot_sym::derivation::Derivation;
use hdot_sym::derivation::physics::{Arg, Bodies, Quantity};
use hdot_sym::poly::Poly;

use super::super::configuration;
use super::super::draw::{Draw, MAX_ORDER};
use super::super::knowns::world_with_knowns;
use super::super::quantities::{Measured, measure};
use super::super::{Comparison, TOLERANCE_ULPS, VerifyError, declaration};
use super::{Inferred, Kind, Plan};
use crate::bind::{Values, nth};

impl Plan<'_> {
    /// Every measured step's comparisons in one draw, in the order of
    /// [`Plan::entries`].
    pub(crate) fn compare(
        &self,
        d: &Derivation,
        draw: &Draw,
        values: &Values,
    ) -> Result<Vec<Vec<Comparison>>, VerifyError> {
        let mut cache: Vec<(Vec<(Atom, Poly)>, Jacobian)> = Vec::new();
        let mut out = Vec::new();
        for i in &self.inferred {
            let mut at = values.clone();
            for (a, p) in &i.subst {
                let (x, s) = values
                    .eval(p)
                    .map_err(|e| VerifyError::from(e).in_step(d, &i.step.name))?;
                at.set(*a, x, s);
            }
            let j = match cache.iter().position(|(s, _)| *s == i.subst) {
                Some(k) => &cache[k].1,
                None => {
                    // The columns the steps at these values need.
                    let mut needed: Vec<Atom> = Vec::new();
                    for o in self.inferred.iter().filter(|o| o.subst == i.subst) {
                        let vars = match &o.kind {
                            Kind::Kane => &self.vars,
                            Kind::Jacobian { vars, .. } => vars,
                        };
                        for z in vars {
                            if !needed.contains(z) {
                                needed.push(*z);
                            }
                        }
                    }
                    let j = self.jacobian(d, draw, &at, needed)?;
                    cache.push((i.subst.clone(), j));
                    &cache.last().expect("pushed").1
                }
            };
            out.push(self.compare_one(d, i, j, values, &at)?);
        }
        Ok(out)
    }

    fn compare_one(
        &self,
        d: &Derivation,
        i: &Inferred<'_>,
        j: &Jacobian,
        values: &Values,
        at: &Values,
    ) -> Result<Vec<Comparison>, VerifyError> {
        let in_step = |e: crate::bind::BindError| VerifyError::from(e).in_step(d, &i.step.name);
        let cmp = |quantity: String, derived: (f64, f64), m: Entry| {
            let tolerance = TOLERANCE_ULPS * f64::EPSILON;
            Comparison {
                quantity,
                derived: derived.0,
                direct: m.value,
                scale: derived.1
                    + m.value.abs()
                    + m.roundoff
                    + m.truncation / tolerance
                    + f64::MIN_POSITIVE,
            }
        };
        let mut out = Vec::new();
        match &i.kind {
            Kind::Kane => {
                // The operating point's values of the deviations.
                let mut x0 = at.clone();
                for &z in &self.vars {
                    x0.set(z, self.op_value(at, z)?, 0.0);
                }
                for (r, e) in self.equations.iter().enumerate() {
                    let label = format!("{}.{}", i.step.name, r + 1);
                    out.push(cmp(
                        format!("{label} at the operating point"),
                        x0.eval(e).map_err(in_step)?,
                        j.value[r],
                    ));
                    for &z in &self.vars {
                        out.push(cmp(
                            format!("∂{label}/∂{z}"),
                            values.eval(&e.partial(z)).map_err(in_step)?,
                            j.column(z)[r],
                        ));
                    }
                }
            }
            Kind::Jacobian { rows, vars } => {
                let entries = i.step.values();
                for (a, &r) in rows.iter().enumerate() {
                    for (b, z) in vars.iter().enumerate() {
                        let Some(p) = entries.get(a * vars.len() + b) else {
                            continue;
                        };
                        let m = j.column(*z)[r];
                        out.push(cmp(
                            format!("{}.{}{}", i.step.name, a + 1, b + 1),
                            values.eval(&d.unfold(p)).map_err(in_step)?,
                            m,
                        ));
                    }
                }
            }
        }
        Ok(out)
    }

    /// The operating value of deviation `z` at `values`: its listed value,
    /// zero for a rate of a listed symbol, and otherwise its drawn value.
    fn op_value(&self, values: &Values, z: Atom) -> Result<f64, VerifyError> {
        if let Some((_, p)) = self.op.iter().find(|(a, _)| *a == z) {
            return Ok(values.eval(p).map_err(VerifyError::from)?.0);
        }
        let base = Atom::time(z.name(), 0);
        if self
            .op
            .iter()
            .any(|(a, _)| Atom::time(a.name(), 0) == base && a.order() < z.order())
        {
            return Ok(0.0);
        }
        Ok(values.get(z).map_or(0.0, |v| v.0))
    }

    /// The state at the operating point (at `values`' constants), with
    /// deviation `z` moved by `h`: the dependent coordinates, the dependent
    /// speeds and the coordinates' rates solved again.
    fn state(
        &self,
        d: &Derivation,
        draw: &Draw,
        values: &Values,
        moved: Option<(Atom, f64)>,
    ) -> Result<Values, VerifyError> {
        let mut v = values.clone();
        for (a, p) in &self.op {
            let (x, _) = values
                .eval(p)
                .map_err(|e| VerifyError::from(e).in_step(d, &self.kane_name()))?;
            v.set(*a, x, x.abs().max(1.0));
            for n in 1..=MAX_ORDER.saturating_sub(a.order()) {
                v.set(nth(*a, n), 0.0, 0.0);
            }
        }
        if let Some((z, h)) = moved {
            let x = v.get(z).map_or(0.0, |x| x.0) + h;
            v.set(z, x, x.abs().max(h.abs()));
        }
        let Some(speeds) = &draw.consistent().speeds else {
            return Err(declaration(
                d,
                format!(
                    "step `{}`: Kane's equations need [kinematics]",
                    self.kane_name()
                ),
            ));
        };
        if !configuration::newton(&speeds.configuration, &mut v)
            .map_err(|e| e.in_step(d, &self.kane_name()))?
        {
            return Err(declaration(
                d,
                format!(
                    "step `{}`: the configuration constraints have no solution near the operating point moved by {}",
                    self.kane_name(),
                    moved.map_or_else(|| "nothing".to_string(), |(z, h)| format!("{h:e} in {z}"))
                ),
            ));
        }
        // The forces read the models' accelerations: the rates to the
        // second (the jerk the models also carry is not read).
        if speeds.fill(d, &mut v, 2)?.is_none() {
            return Err(declaration(
                d,
                format!(
                    "step `{}`: a symbol of the constraints or the kinematic equations has no value",
                    self.kane_name()
                ),
            ));
        }
        Ok(v)
    }

    fn kane_name(&self) -> String {
        self.kane.map_or_else(String::new, |k| k.name.clone())
    }

    /// −(F_r + F_r*) for each independent speed on the particles at
    /// `values`, and the magnitudes of the terms summed.
    fn forces(
        &self,
        d: &Derivation,
        draw: &Draw,
        values: &Values,
    ) -> Result<(Vec<f64>, f64), VerifyError> {
        let mut values = values.clone();
        let w = world_with_knowns(d, draw, &mut values, &[])?;
        let mut out = Vec::with_capacity(self.speeds.len());
        let mut scale = 0.0;
        for &u in &self.speeds {
            let args = [Arg::Body(Bodies::System), Arg::Speed(u)];
            let mut f = 0.0;
            for q in [
                Quantity::GeneralizedActiveForce,
                Quantity::GeneralizedInertiaForce,
            ] {
                let (m, s) = (measure(q).compute)(&w, &args)?;
                let Measured::Scalar(x) = m else {
                    unreachable!("a generalized force is a scalar")
                };
                f -= x;
                scale += s;
            }
            out.push(f);
        }
        Ok((out, scale))
    }

    /// The forces at the operating point and their derivative in each
    /// deviation of `vars`.
    fn jacobian(
        &self,
        d: &Derivation,
        draw: &Draw,
        values: &Values,
        vars: Vec<Atom>,
    ) -> Result<Jacobian, VerifyError> {
        let base = self.state(d, draw, values, None)?;
        let (f0, s0) = self.forces(d, draw, &base)?;
        let value = f0
            .iter()
            .map(|&x| Entry {
                value: x,
                roundoff: s0,
                truncation: 0.0,
            })
            .collect();
        let mut columns = Vec::new();
        for &z in &vars {
            columns.push(self.derivative(d, draw, values, &base, z)?);
        }
        Ok(Jacobian {
            value,
            vars,
            columns,
        })
    }

    /// ∂F/∂z at the operating point ([module docs](self)).
    fn derivative(
        &self,
        d: &Derivation,
        draw: &Draw,
        values: &Values,
        base: &Values,
        z: Atom,
    ) -> Result<Vec<Entry>, VerifyError> {
        let z0 = base.get(z).map_or(0.0, |v| v.0);
        let coordinate = z.order() == 0 && !d.speeds().contains(&z);
        let h = if coordinate {
            (1.0 + z0.abs()) / 256.0
        } else {
            (1.0 + z0.abs()) / 2.0
        };
        let n = self.speeds.len();
        let mut scale: f64 = 0.0;
        let mut quotient = |step: f64| -> Result<Vec<f64>, VerifyError> {
            let (p, sp) = self.forces(d, draw, &self.state(d, draw, values, Some((z, step)))?)?;
            let (m, sm) = self.forces(d, draw, &self.state(d, draw, values, Some((z, -step)))?)?;
            scale = scale.max(sp).max(sm);
            Ok((0..n).map(|r| (p[r] - m[r]) / (2.0 * step)).collect())
        };
        let d1 = quotient(h)?;
        let d2 = quotient(h / 2.0)?;
        if !coordinate {
            // Quadratic in a speed, affine in a rate: D(h) is exact, and
            // D(h/2) differs from it by round-off only.
            return Ok((0..n)
                .map(|r| Entry {
                    value: d1[r],
                    roundoff: 4.0 * scale / h,
                    truncation: (d1[r] - d2[r]).abs(),
                })
                .collect());
        }
        let d4 = quotient(h / 4.0)?;
        Ok((0..n)
            .map(|r| {
                let coarse = (4.0 * d2[r] - d1[r]) / 3.0;
                let fine = (4.0 * d4[r] - d2[r]) / 3.0;
                Entry {
                    value: fine,
                    roundoff: 12.0 * scale / h,
                    truncation: (coarse - fine).abs(),
                }
            })
            .collect())
    }
}

/// One measured entry: its value, the magnitudes its round-off is
/// relative to, and the estimated error of the difference quotient.
#[derive(Clone, Copy, Debug)]
struct Entry {
    value: f64,
    roundoff: f64,
    truncation: f64,
}

/// The forces at the operating point and their derivatives, one column
/// per deviation.
struct Jacobian {
    value: Vec<Entry>,
    vars: Vec<Atom>,
    columns: Vec<Vec<Entry>>,
}

impl Jacobian {
    /// The column of deviation `z` (measured: [`Plan::compare`] asks for
    /// every deviation its steps name).
    fn column(&self, z: Atom) -> &[Entry] {
        let c = self
            .vars
            .iter()
            .position(|v| *v == z)
            .expect("every deviation a step names is measured");
        &self.columns[c]
    }
}
