//! Generalized speeds drawn consistent with the derivation: the dependent
//! speeds solved numerically from a `kane` step's constraint rows at the
//! drawn state (Euler parameters first scaled to unit norm; a
//! configuration constraint f(q) = 0 enters as its rate, and is met by
//! the drawn coordinates, [`super::configuration`]), and each
//! coordinate's rates from the kinematic equations
//! q̇ = f(q, u), order by order (the rows' rates bring in the speeds'
//! rates, the equations' rates the coordinates' higher rates). What
//! these are read from is read once per check ([`Consistent`]).

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::physics::Rule;
use hdot_sym::derivation::{Derivation, Load};
use hdot_sym::parse::{AstKind, parse};
use hdot_sym::poly::Poly;
use nalgebra::{DMatrix, DVector};

use super::prepared::Prepared;
use super::{VerifyError, declaration};
use crate::bind::{Values, nth};
use crate::verify::jet::ORDERS;

/// The kinematic equations and the constraints of a derivation in the
/// speeds, read once per check: rows linear in the speeds that vanish
/// along the motion, and the configuration constraints with the
/// coordinates they are solved for.
#[derive(Clone, Debug)]
pub(crate) struct Speeds {
    /// The coordinates the kinematic equations give the rates of.
    coordinates: Vec<Atom>,
    /// `rates[n]`, polynomial k: the `n`th rate of coordinate k's
    /// kinematic equation.
    rates: Vec<Prepared>,
    /// `rows[n]`: the `n`th rates of the constraint rows, coordinates'
    /// rates replaced by the kinematic equations (a configuration
    /// constraint's row is its rate). Both prepared once: they are
    /// evaluated at every draw and at every state a linearisation
    /// measures ([`Prepared`]).
    rows: Vec<Prepared>,
    /// `coefficients[n]`, polynomial `i · dependent.len() + j`: row i's
    /// coefficient of dependent speed j's `n`th rate in `rows[n]`.
    coefficients: Vec<Prepared>,
    pub(crate) dependent: Vec<Atom>,
    /// The configuration constraints f(q) = 0, solved for the dependent
    /// coordinates at a draw ([`super::configuration`]).
    pub(crate) configuration: Configuration,
}

/// The configuration constraints of a `kane` step and the dependent
/// coordinates listed for them.
#[derive(Clone, Debug, Default)]
pub(crate) struct Configuration {
    /// The `kane` step's name.
    pub(crate) step: String,
    /// The constraints, abbreviations unfolded.
    pub(crate) rows: Vec<Poly>,
    /// The coordinates solved for.
    pub(crate) dependent: Vec<Atom>,
    /// `∂f_i/∂q_k` for the dependent coordinates q_k.
    pub(crate) jacobian: Vec<Vec<Poly>>,
    /// The rows, then the Jacobian's entries row by row, prepared once:
    /// Newton's method evaluates them at every draw and at every state a
    /// linearisation measures ([`Prepared`]).
    pub(crate) prepared: Prepared,
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

/// The constraint rows a `kane` step names: an earlier step (`edge`), or
/// a `list(…)` of earlier steps and their components (`rear.x`,
/// `front.2`, `ground`).
fn constraint_rows(d: &Derivation, a: &hdot_sym::parse::Ast) -> Option<Vec<Poly>> {
    let step = |name: &str| d.steps.iter().find(|t| t.name == name);
    let whole = |name: &str| -> Option<Vec<Poly>> {
        Some(
            step(name)?
                .value
                .components()
                .into_iter()
                .cloned()
                .collect(),
        )
    };
    match &a.kind {
        AstKind::Name { name, primes: 0 } => whole(name),
        AstKind::Call { func, args } if func == "list" => {
            let mut rows = Vec::new();
            for item in args {
                match &item.kind {
                    AstKind::Name { name, primes: 0 } => rows.extend(whole(name)?),
                    AstKind::Member(of, field, _) => {
                        let AstKind::Name { name, primes: 0 } = &of.kind else {
                            return None;
                        };
                        let all = whole(name)?;
                        let k = match field.as_str() {
                            "x" => 0,
                            "y" => 1,
                            "z" => 2,
                            n => n.parse::<usize>().ok()?.checked_sub(1)?,
                        };
                        rows.push(all.get(k)?.clone());
                    }
                    _ => return None,
                }
            }
            Some(rows)
        }
        _ => None,
    }
}

/// A `kane` step's name, its constraint rows, the dependent speeds and
/// the dependent coordinates.
type KaneStep = (String, Vec<Poly>, Vec<Atom>, Vec<Atom>);

/// The first step `kane([u…], constraints, [u_dep…] (, [q_dep…]) …)`
/// whose constraints are earlier steps ([`KaneStep`]).
fn kane_step(d: &Derivation) -> Option<KaneStep> {
    d.steps.iter().find_map(|s| {
        let ast = parse(&s.formula).ok()?;
        let AstKind::Call { func, args } = &ast.kind else {
            return None;
        };
        if func != "kane" || args.len() < 3 {
            return None;
        }
        let rows = constraint_rows(d, &args[1])?;
        let coordinates = match args.get(3).map(|a| &a.kind) {
            Some(AstKind::Vector { .. }) => names(&args[3])?,
            _ => Vec::new(),
        };
        Some((s.name.clone(), rows, names(&args[2])?, coordinates))
    })
}

impl Speeds {
    /// The derivation's speeds, or `None` without `[kinematics]`; ready to
    /// [`Speeds::fill`] `orders` orders (at most [`ORDERS`]). The rows'
    /// rates above are neither differentiated nor their coefficients taken
    /// (the linearised bicycle's fourth-order coefficients were a fifth of
    /// its verification, filled to two orders).
    pub(crate) fn of(d: &Derivation, orders: usize) -> Option<Speeds> {
        let orders = orders.clamp(1, ORDERS);
        let kinematics = d.kinematic_equations().to_vec();
        if kinematics.is_empty() {
            return None;
        }
        let (step, rows, dependent, coordinates) = kane_step(d).unwrap_or_default();
        let in_speeds = |r: &Poly| {
            r.subst(&mut |a| {
                (a.order() == 1)
                    .then(|| kinematics.iter().find(|(q, _)| nth(*q, 1) == a))
                    .flatten()
                    .map(|(_, f)| f.clone())
            })
        };
        let speeds = d.speeds();
        let mut configuration = Configuration {
            step,
            rows: Vec::new(),
            dependent: coordinates,
            jacobian: Vec::new(),
            prepared: Prepared::default(),
        };
        let rows: Vec<Poly> = rows
            .iter()
            .map(|r| {
                let unfolded = d.unfold(r);
                let moves = unfolded
                    .atoms()
                    .iter()
                    .any(|a| a.order() > 0 || speeds.contains(a));
                if moves {
                    in_speeds(r)
                } else {
                    let r = unfolded;
                    // f(q) = 0: its rate is the row, linear in the speeds.
                    let rate = in_speeds(&r.dt());
                    configuration.rows.push(r);
                    rate
                }
            })
            .collect();
        configuration.jacobian = configuration
            .rows
            .iter()
            .map(|r| {
                configuration
                    .dependent
                    .iter()
                    .map(|&q| r.partial(q))
                    .collect()
            })
            .collect();
        configuration.prepared = Prepared::new(
            &configuration
                .rows
                .iter()
                .chain(configuration.jacobian.iter().flatten())
                .cloned()
                .collect::<Vec<_>>(),
        );
        let mut all_rows = vec![rows];
        let mut rates = vec![
            kinematics
                .iter()
                .map(|(_, f)| f.clone())
                .collect::<Vec<_>>(),
        ];
        for n in 1..orders {
            all_rows.push(all_rows[n - 1].iter().map(Poly::dt).collect());
            rates.push(rates[n - 1].iter().map(Poly::dt).collect());
        }
        Some(Speeds {
            coordinates: kinematics.iter().map(|(q, _)| *q).collect(),
            rates: rates.iter().map(|r| Prepared::new(r)).collect(),
            rows: all_rows.iter().map(|r| Prepared::new(r)).collect(),
            coefficients: all_rows
                .iter()
                .enumerate()
                .map(|(n, rows)| {
                    let of: Vec<Poly> = rows
                        .iter()
                        .flat_map(|r| dependent.iter().map(move |&u| r.partial(nth(u, n as u32))))
                        .collect();
                    Prepared::new(&of)
                })
                .collect(),
            dependent,
            configuration,
        })
    }

    /// The atoms [`Speeds::fill`] reads for the speeds and the
    /// coordinates' first rates (order 0): the constraint rows, their
    /// coefficients in the dependent speeds and the kinematic equations,
    /// as held (a sine or cosine as itself).
    pub(crate) fn reads(&self) -> Vec<Atom> {
        [&self.rows[0], &self.coefficients[0], &self.rates[0]]
            .iter()
            .flat_map(|p| p.atoms().iter().copied())
            .chain(self.dependent.iter().copied())
            .collect()
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
        debug_assert!(orders <= self.rows.len(), "speeds made for fewer orders");
        for n in 0..orders.min(self.rows.len()) {
            if !self.dependent.is_empty() && self.solve(d, values, n as u32)?.is_none() {
                return Ok(None);
            }
            let rates = &self.rates[n];
            let mut at = rates.resolve(values);
            for (k, q) in self.coordinates.iter().enumerate() {
                let Ok((v, s)) = rates.eval(k, &at) else {
                    return Ok(None);
                };
                let rate = nth(*q, n as u32 + 1);
                values.set(rate, v, s);
                // A later equation that reads this rate reads it set.
                if let Some(slot) = rates.slot(rate) {
                    at[slot] = values.get(rate);
                }
            }
        }
        Ok(Some(()))
    }

    /// The dependent speeds' `n`th rates from the rows' `n`th rates
    /// (linear in them): least squares, exact when the rows are
    /// consistent.
    fn solve(
        &self,
        d: &Derivation,
        values: &mut Values,
        n: u32,
    ) -> Result<Option<()>, VerifyError> {
        let rows = &self.rows[n as usize];
        let deps: Vec<Atom> = self.dependent.iter().map(|&u| nth(u, n)).collect();
        for &u in &deps {
            values.set(u, 0.0, 0.0);
        }
        let at = rows.resolve(values);
        let Some(r0) = (0..rows.len())
            .map(|i| rows.eval(i, &at).ok())
            .collect::<Option<Vec<(f64, f64)>>>()
        else {
            return Ok(None);
        };
        // The rows are linear in the rates solved for: their matrix is
        // the coefficients, evaluated (not the rows evaluated again with
        // each rate at one).
        let coefficients = &self.coefficients[n as usize];
        let at = coefficients.resolve(values);
        let mut a = DMatrix::zeros(rows.len(), deps.len());
        for i in 0..rows.len() {
            for j in 0..deps.len() {
                let Ok((x, _)) = coefficients.eval(i * deps.len() + j, &at) else {
                    return Ok(None);
                };
                a[(i, j)] = x;
            }
        }
        let b = DVector::from_iterator(r0.len(), r0.iter().map(|(x, _)| -x));
        let scale: f64 = r0.iter().map(|(_, s)| s).sum::<f64>() + 1.0;
        let svd = a.svd(true, true);
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

/// What a check draws consistent motions with, read from the
/// derivation once per check (never per draw or per state): the speeds
/// and constraints ([`Speeds`]) and the angles whose sine or cosine the
/// kinematic equations divide by.
#[derive(Debug, Default)]
pub(crate) struct Consistent {
    /// The speeds, `None` without `[kinematics]`.
    pub(crate) speeds: Option<Speeds>,
    /// The atoms partial velocities are a function of
    /// ([`super::partials::velocity_reads`]); empty without speeds.
    velocity_reads: Vec<Atom>,
    /// The orders of rates a draw is filled to ([`fill_orders`]).
    orders: usize,
    /// Angles whose sine a kinematic equation divides by.
    by_sin: Vec<Atom>,
    /// … and whose cosine.
    by_cos: Vec<Atom>,
}

impl Consistent {
    /// Reads `d`'s kinematic equations and constraints.
    pub(crate) fn of(d: &Derivation) -> Consistent {
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
        // At least two (`fill_orders`): a linearisation's states and a
        // conserved step's solved rates are filled to two.
        let orders = fill_orders(d);
        let speeds = Speeds::of(d, orders);
        Consistent {
            velocity_reads: speeds
                .as_ref()
                .map(|s| super::partials::velocity_reads(d, s))
                .unwrap_or_default(),
            speeds,
            orders,
            by_sin,
            by_cos,
        }
    }

    /// The atoms partial velocities are a function of, sorted.
    pub(crate) fn velocity_reads(&self) -> &[Atom] {
        &self.velocity_reads
    }

    /// Moves each drawn angle that the kinematic equations divide the
    /// sine or cosine of (the 1/sin θ of 3-1-3 Euler angles) to where
    /// that sine or cosine is at least ½ in magnitude, keeping the signs
    /// of both. Near the coordinate singularity the coordinates' rates
    /// and their own rates grow like 1/sinⁿ θ, and the particle sums
    /// cancel terms that large to the moment's size, so their round-off
    /// is amplified past any tolerance scaled to the result; the
    /// equations hold at every other attitude, so the draw loses nothing.
    /// The angles in `fixed` (values a declaration gives) are left.
    pub(crate) fn away_from_singularities(&self, values: &mut Values, fixed: &[Atom]) {
        let (by_sin, by_cos) = (&self.by_sin, &self.by_cos);
        let angles = by_sin.iter().chain(by_cos).copied().collect::<Vec<_>>();
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
    pub(crate) fn fill(&self, d: &Derivation, values: &mut Values) -> Result<(), VerifyError> {
        super::quaternion::on_unit_sphere(d, values);
        if let Some(s) = &self.speeds {
            let mut v = values.clone();
            if s.fill(d, &mut v, self.orders)?.is_some() {
                *values = v;
            }
        }
        Ok(())
    }
}

/// How many orders of rates [`Consistent::fill`] makes consistent
/// ([`Speeds::fill`]: order n solves the dependent speeds' nth rates and
/// gives the coordinates' (n+1)th). The models' quantities read the
/// motion to the accelerations — the coordinates' second rates and the
/// speeds' first, orders 0 and 1 — and the rates above them only as the
/// jerk, which only a `[[known]]`'s kinematic jet reads; a derived value,
/// a step's value (compared, or checked to vanish), a meaning's or a
/// load's expression reads the rates it holds. Every
/// order is filled for a file with `[[known]]` or with rules that set a
/// time symbol (`[motion]`, a step's `given`: their rates are applied to
/// the sixth). The rates above are left as drawn, read by nothing; the
/// rows' third rates were a third of the linearised bicycle's
/// verification.
fn fill_orders(d: &Derivation) -> usize {
    let sets_time = |r: &Rule| r.target.is_time_dependent();
    let meanings = d.steps.iter().filter_map(|s| s.meaning.as_ref());
    if !d.physics.knowns.is_empty()
        || d.physics.motion.iter().any(sets_time)
        || meanings.clone().any(|m| m.given.iter().any(sets_time))
    {
        return ORDERS;
    }
    let mut polys: Vec<&Poly> = Vec::new();
    for s in &d.steps {
        polys.extend(s.values());
    }
    for m in meanings {
        m.meaning.expressions(&mut polys);
        polys.extend(m.bounds.iter().map(|(p, _)| p));
    }
    for l in &d.loads {
        match l {
            Load::Force { force: v, .. } | Load::Torque { torque: v, .. } => polys.extend(&v.0),
        }
    }
    let mut atoms: Vec<Atom> = polys.iter().flat_map(|p| p.atoms()).collect();
    atoms.sort_unstable();
    atoms.dedup();
    // An abbreviation reads what its definition reads.
    let read = atoms
        .iter()
        .flat_map(|&a| d.unfold(&Poly::atom(a)).atoms())
        .filter(|a| a.is_time_dependent())
        .map(|a| a.order() as usize + 1)
        .max()
        .unwrap_or(0);
    read.clamp(2, ORDERS)
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
        let s = Speeds::of(&d, ORDERS).expect("the disk has speeds");
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
