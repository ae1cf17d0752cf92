//! Generalized speeds drawn consistent with the derivation: the dependent
//! speeds solved numerically from a `kane` step's constraint rows at the
//! drawn state (Euler parameters first scaled to unit norm), and each
//! coordinate's rates from the kinematic equations
//! q̇ = f(q, u), order by order (the rows' rates bring in the speeds'
//! rates, the equations' rates the coordinates' higher rates).

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::Derivation;
use hdot_sym::parse::{AstKind, parse};
use hdot_sym::poly::Poly;
use nalgebra::{DMatrix, DVector};

use super::{VerifyError, declaration};
use crate::bind::{Values, nth};
use crate::verify::jet::ORDERS;

/// The kinematic equations and the constraints of a derivation in the
/// speeds: rows linear in the speeds that vanish along the motion.
#[derive(Clone, Debug)]
pub(crate) struct Speeds {
    kinematics: Vec<(Atom, Poly)>,
    /// The constraint rows, coordinates' rates replaced by the kinematic
    /// equations.
    rows: Vec<Poly>,
    pub(crate) dependent: Vec<Atom>,
}

/// The names of a bracketed list of symbols (`[u_1, u_2]`).
fn names(a: &hdot_sym::parse::Ast) -> Option<Vec<Atom>> {
    match &a.kind {
        AstKind::Vector { items, frame: None } => items
            .iter()
            .map(|i| match &i.kind {
                AstKind::Name { name, primes: 0 } => Some(Atom::time(name, 0)),
                _ => None,
            })
            .collect(),
        _ => None,
    }
}

/// The first step `kane([u…], constraints, [u_dep…])` whose constraints
/// are an earlier step: that step's rows and the dependent speeds.
fn kane_step(d: &Derivation) -> Option<(Vec<Poly>, Vec<Atom>)> {
    d.steps.iter().find_map(|s| {
        let ast = parse(&s.formula).ok()?;
        let AstKind::Call { func, args } = &ast.kind else {
            return None;
        };
        if func != "kane" || args.len() != 3 {
            return None;
        }
        let AstKind::Name { name, primes: 0 } = &args[1].kind else {
            return None;
        };
        let rows = d.steps.iter().find(|t| &t.name == name)?;
        let rows = rows.value.components().into_iter().cloned().collect();
        Some((rows, names(&args[2])?))
    })
}

impl Speeds {
    /// The derivation's speeds, or `None` without `[kinematics]`.
    pub(crate) fn of(d: &Derivation) -> Option<Speeds> {
        let kinematics = d.kinematic_equations().to_vec();
        if kinematics.is_empty() {
            return None;
        }
        let (rows, dependent) = kane_step(d).unwrap_or_default();
        let rows = rows
            .iter()
            .map(|r| {
                r.subst(&mut |a| {
                    (a.order() == 1)
                        .then(|| kinematics.iter().find(|(q, _)| nth(*q, 1) == a))
                        .flatten()
                        .map(|(_, f)| f.clone())
                })
            })
            .collect();
        Some(Speeds {
            kinematics,
            rows,
            dependent,
        })
    }

    /// Fills in `values`, for derivative orders below `orders`: the
    /// dependent speeds' rates solved from the rows' rates, then the
    /// coordinates' next rates from the kinematic equations' rates. The
    /// coordinates and the independent speeds (and their rates) keep
    /// their values. `None` when a symbol is not bound yet.
    pub(crate) fn fill(
        &self,
        d: &Derivation,
        values: &mut Values,
        orders: usize,
    ) -> Result<Option<()>, VerifyError> {
        let mut rows = self.rows.clone();
        let mut rates: Vec<Poly> = self.kinematics.iter().map(|(_, f)| f.clone()).collect();
        for n in 0..orders as u32 {
            if !self.dependent.is_empty() && self.solve(d, values, &rows, n)?.is_none() {
                return Ok(None);
            }
            for ((q, _), f) in self.kinematics.iter().zip(&rates) {
                let Ok((v, s)) = values.eval(f) else {
                    return Ok(None);
                };
                values.set(nth(*q, n + 1), v, s);
            }
            if n + 1 < orders as u32 {
                rows = rows.iter().map(Poly::dt).collect();
                rates = rates.iter().map(Poly::dt).collect();
            }
        }
        Ok(Some(()))
    }

    /// The dependent speeds' `n`th rates from `rows` (the rows' `n`th
    /// rates, linear in them): least squares, exact when the rows are
    /// consistent.
    fn solve(
        &self,
        d: &Derivation,
        values: &mut Values,
        rows: &[Poly],
        n: u32,
    ) -> Result<Option<()>, VerifyError> {
        let deps: Vec<Atom> = self.dependent.iter().map(|&u| nth(u, n)).collect();
        for &u in &deps {
            values.set(u, 0.0, 0.0);
        }
        let eval = |v: &Values| -> Option<Vec<(f64, f64)>> {
            rows.iter().map(|r| v.eval(r).ok()).collect()
        };
        let Some(r0) = eval(values) else {
            return Ok(None);
        };
        let mut a = DMatrix::zeros(rows.len(), deps.len());
        for (j, &u) in deps.iter().enumerate() {
            let Some(rj) = eval(&values.with(u, 1.0)) else {
                return Ok(None);
            };
            for (i, (x, _)) in rj.iter().enumerate() {
                a[(i, j)] = x - r0[i].0;
            }
        }
        let b = DVector::from_iterator(r0.len(), r0.iter().map(|(x, _)| -x));
        let scale: f64 = r0.iter().map(|(_, s)| s).sum::<f64>() + 1.0;
        let svd = a.clone().svd(true, true);
        let smax = svd.singular_values.max();
        let smin = svd.singular_values.min();
        if deps.len() > rows.len() || smin <= 1e-9 * smax.max(f64::MIN_POSITIVE) {
            return Err(declaration(
                d,
                format!(
                    "the dependent speeds {} cannot be solved from the constraints at a drawn state \
                     (their matrix is singular there)",
                    self.dependent
                        .iter()
                        .map(ToString::to_string)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
        let x = svd
            .solve(&b, 0.0)
            .map_err(|e| declaration(d, format!("the constraints' solve failed: {e}")))?;
        for (&u, v) in deps.iter().zip(x.iter()) {
            values.set(u, *v, v.abs().max(scale / smax));
        }
        Ok(Some(()))
    }
}

/// Moves each drawn angle that the kinematic equations divide the sine
/// or cosine of (the 1/sin θ of 3-1-3 Euler angles) to where that sine or
/// cosine is at least ½ in magnitude, keeping the signs of both. Near
/// the coordinate singularity the coordinates' rates and their own rates
/// grow like 1/sinⁿ θ, and the particle sums cancel terms that large to
/// the moment's size, so their round-off is amplified past any tolerance
/// scaled to the result; the equations hold at every other attitude, so
/// the draw loses nothing. The angles in `fixed` (values a declaration
/// gives) are left.
pub(crate) fn away_from_singularities(d: &Derivation, values: &mut Values, fixed: &[Atom]) {
    let (mut by_sin, mut by_cos): (Vec<Atom>, Vec<Atom>) = (Vec::new(), Vec::new());
    for (_, f) in d.kinematic_equations() {
        for (m, _) in d.unfold(f).terms() {
            for &(a, e) in m.factors() {
                match a.kind() {
                    AtomKind::Sin(q) if e < 0 && !by_sin.contains(&q) => by_sin.push(q),
                    AtomKind::Cos(q) if e < 0 && !by_cos.contains(&q) => by_cos.push(q),
                    _ => {}
                }
            }
        }
    }
    let angles = by_sin.iter().chain(&by_cos).copied().collect::<Vec<_>>();
    for (k, &q) in angles.iter().enumerate() {
        if angles[..k].contains(&q) || fixed.contains(&q) {
            continue;
        }
        let Some((v, _)) = values.get(q) else {
            continue;
        };
        let (s, c) = v.sin_cos();
        let (sin, cos) = (by_sin.contains(&q), by_cos.contains(&q));
        let sign = |x: f64| if x < 0.0 { -1.0 } else { 1.0 };
        let (s2, c2) = if sin && cos && (s.abs() < 0.5 || c.abs() < 0.5) {
            // Both divide: |sin| in [½, √3/2], so |cos| is too.
            let m = 0.5 + (0.75_f64.sqrt() - 0.5) * s.abs();
            (sign(s) * m, sign(c) * (1.0 - m * m).sqrt())
        } else if sin && !cos && s.abs() < 0.5 {
            let m = 0.5 + s.abs() / 2.0;
            (sign(s) * m, sign(c) * (1.0 - m * m).sqrt())
        } else if cos && !sin && c.abs() < 0.5 {
            let m = 0.5 + c.abs() / 2.0;
            (sign(s) * (1.0 - m * m).sqrt(), sign(c) * m)
        } else {
            continue;
        };
        let moved = s2.atan2(c2);
        values.set(q, moved, moved);
    }
}

/// Draws the coordinates' rates from the speeds, the dependent speeds
/// from the constraints (see the module comment); nothing without
/// `[kinematics]`.
pub(crate) fn draw_consistent(d: &Derivation, values: &mut Values) -> Result<(), VerifyError> {
    super::quaternion::on_unit_sphere(d, values);
    if let Some(s) = Speeds::of(d) {
        let mut v = values.clone();
        if s.fill(d, &mut v, ORDERS)?.is_some() {
            *values = v;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use hdot_sym::derivation::load_str;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The rolling disk's speeds drawn from its constraint rows roll it
    /// along its heading at r times the spin — the file's own `[motion]`
    /// rule, stated from the geometry rather than derived — to second
    /// order (the dependent speeds' rates solved from the rows' rates).
    #[test]
    fn disk_rolls_along_its_heading_at_the_drawn_speeds() {
        let text = include_str!("../../../../derivations/disk-rolling-on-plane.toml");
        let d = load_str("disk-rolling-on-plane.toml", text).expect("the disk derives");
        let s = Speeds::of(&d).expect("the disk has speeds");
        assert_eq!(s.dependent, [Atom::time("u_4", 0), Atom::time("u_5", 0)]);
        let mut rng = ChaCha8Rng::seed_from_u64(24);
        for _ in 0..20 {
            let mut v = Values::default();
            for c in ["m", "g", "r", "I", "J"] {
                let x = rng.gen_range(0.5..2.0);
                v.set(Atom::constant(c), x, x);
            }
            for t in [
                "x", "y", "psi", "theta", "phi", "u_1", "u_2", "u_3", "u_4", "u_5",
            ] {
                for n in 0..=6 {
                    let x = rng.gen_range(-1.0..1.0);
                    v.set(Atom::time(t, n), x, x);
                }
            }
            s.fill(&d, &mut v, ORDERS).expect("solves").expect("bound");
            let at = |t: &str, n: u32| v.time(Atom::time(t, 0), n).expect("drawn").0;
            let r = v.get(Atom::constant("r")).expect("drawn").0;
            let (psi, dpsi) = (at("psi", 0), at("psi", 1));
            let (dphi, ddphi) = (at("phi", 1), at("phi", 2));
            let scale = r * (dphi.abs() + ddphi.abs() + dphi.abs() * dpsi.abs()) + 1.0;
            let tol = 1e-10 * scale;
            assert!((at("x", 1) - r * dphi * psi.cos()).abs() < tol);
            assert!((at("y", 1) - r * dphi * psi.sin()).abs() < tol);
            let ddx = r * (ddphi * psi.cos() - dphi * dpsi * psi.sin());
            let ddy = r * (ddphi * psi.sin() + dphi * dpsi * psi.cos());
            assert!((at("x", 2) - ddx).abs() < tol, "{} vs {ddx}", at("x", 2));
            assert!((at("y", 2) - ddy).abs() < tol, "{} vs {ddy}", at("y", 2));
        }
    }
}
