//! The linearized Kane equations measured on the particles: a step
//! `kane(…, q = q₀, u = u₀, …)` (Kane's equations to first order about an
//! operating point) and the steps the algebra takes from it —
//! `jacobian(list(K.1, K.3), [z…])` (a mass, damping or stiffness matrix)
//! and `subst(C, v = 1)` of such a step (constants given values) — have no
//! `means` of their own: what they are follows from the operation, and is
//! measured here.
//!
//! The step K = −(F_r + F_r*) to first order is `K(x₀) + Σ_z J_z (z − z₀)`,
//! J the Jacobian of the nonlinear generalized forces at the operating
//! point x₀. Those forces are measured on the drawn particles as for a
//! `means` of `generalized_active_force` and `generalized_inertia_force`
//! (constrained partial velocities from the particles, [`super::partials`])
//! at the operating point and at it with one deviation z (a coordinate, a
//! speed or a speed's rate in K) moved — the dependent coordinates solved
//! again from the configuration constraints, the dependent speeds and the
//! coordinates' rates again from the constraint rows and the kinematic
//! equations. With central differences
//! `D(h) = [F(z₀ + h) − F(z₀ − h)] / 2h`:
//!
//! - for a coordinate (F is trigonometric in it), `h = 2⁻⁸ (1 + |z₀|)` and
//!   the column is the Richardson extrapolation
//!   `R(h/2) = [4 D(h/4) − D(h/2)] / 3`, of error O(h⁴), estimated by
//!   `|R(h) − R(h/2)|` (about 15 times the error of `R(h/2)`), its
//!   round-off by `12 S/h`;
//! - for a speed or a speed's rate (F is quadratic in the speeds, affine in
//!   their rates), `h = (1 + |z₀|)/2` and the column is `D(h)`, exact but
//!   for round-off (`4 S/h`); `|D(h) − D(h/2)|` is the estimate.
//!
//! S is the magnitudes of the terms the forces are summed from. A
//! comparison passes when `|derived − measured|` is within the estimate
//! plus [`super::TOLERANCE_ULPS`] of round-off of the magnitudes (the
//! quotient's round-off bound and both values). Each draw measures some
//! sixty forces, four models of the bodies each, so the steps are compared
//! in the first [`DRAWS`] draws only.
//!
//! A linearized `kane` step is measured only when it is the one whose
//! constraints the draw reads ([`super::speeds`]: rows that are earlier
//! steps or their components); otherwise, and for an operating angle of a
//! multiple of π/2, the step stays among those not compared, with the
//! reason.

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::{Derivation, Step};
use hdot_sym::parse::{Ast, AstKind, parse};
use hdot_sym::poly::Poly;

use super::{StepCheck, TOLERANCE_ULPS};

mod measure;

/// The draws the linearized steps are measured in (the first ones): each
/// is a Jacobian of some sixty force measurements on the particles, each
/// four models of the bodies (the state and each speed raised by one).
pub(crate) const DRAWS: usize = 2;

/// What a step without `means` is measured as.
#[derive(Clone, Debug)]
enum Kind {
    /// The linearized `kane` step: its value at the operating point and
    /// its coefficient of each deviation.
    Kane,
    /// `jacobian(rows of K, [z…])`: the entries ∂K_row/∂z.
    Jacobian { rows: Vec<usize>, vars: Vec<Atom> },
}

/// A step measured through the linearized Kane equations.
struct Inferred<'d> {
    step: &'d Step,
    kind: Kind,
    /// Constants given values (`subst(C, v = 1)`), as written.
    subst: Vec<(Atom, Poly)>,
}

/// The linearized `kane` step of a file and the steps taken from it, read
/// once per check.
pub(crate) struct Plan<'d> {
    /// The `kane` step.
    kane: Option<&'d Step>,
    /// Its independent speeds, one equation each.
    speeds: Vec<Atom>,
    /// The operating point.
    op: Vec<(Atom, Poly)>,
    /// The deviations K is linear in.
    vars: Vec<Atom>,
    /// K's equations, abbreviations unfolded.
    equations: Vec<Poly>,
    inferred: Vec<Inferred<'d>>,
    /// Steps that look linearized but are not measured, with the reason.
    refused: Vec<(String, String)>,
}

/// The names of a bracketed list of symbols with their primes.
fn symbols(d: &Derivation, a: &Ast) -> Option<Vec<Atom>> {
    let AstKind::Vector { items, frame: None } = &a.kind else {
        return None;
    };
    items
        .iter()
        .map(|i| match &i.kind {
            AstKind::Name { name, primes } => d.symbols.atom(name, *primes, i.span).ok(),
            _ => None,
        })
        .collect()
}

/// `name = value` arguments as (atom, value); `Err` with the reason when
/// one is not a value this module reads.
fn assignments(d: &Derivation, formula: &str, args: &[Ast]) -> Result<Vec<(Atom, Poly)>, String> {
    args.iter()
        .map(|a| {
            let AstKind::Assign {
                name,
                primes,
                name_span,
                value,
            } = &a.kind
            else {
                return Err("an argument after `name = value` ones".into());
            };
            let atom = d
                .symbols
                .atom(name, *primes, *name_span)
                .map_err(|e| e.message)?;
            let text = &formula[value.span.start..value.span.end];
            let p = d.symbols.poly(text).map_err(|_| {
                format!("the operating value `{name} = {text}` (a multiple of π is not read here)")
            })?;
            Ok((atom, d.unfold(&p)))
        })
        .collect()
}

impl<'d> Plan<'d> {
    /// Reads the linearized `kane` step of `d` (the first with an operating
    /// point) and the steps taken from it.
    pub(crate) fn of(d: &'d Derivation, constrained_step: Option<&str>) -> Plan<'d> {
        let mut plan = Plan {
            kane: None,
            speeds: Vec::new(),
            op: Vec::new(),
            vars: Vec::new(),
            equations: Vec::new(),
            inferred: Vec::new(),
            refused: Vec::new(),
        };
        for s in d.steps.iter().filter(|s| s.meaning.is_none()) {
            let Ok(ast) = parse(&s.formula) else {
                continue;
            };
            let AstKind::Call { func, args } = &ast.kind else {
                continue;
            };
            match func.as_str() {
                "kane" if plan.kane.is_none() => plan.read_kane(d, s, args, constrained_step),
                "jacobian" => plan.read_jacobian(d, s, args),
                "subst" => plan.read_subst(d, s, &s.formula, args),
                "state_matrix" | "state_mass" if plan.kane.is_some() => {
                    let k = plan.kane.map_or("", |k| k.name.as_str());
                    plan.refused.push((
                        s.name.clone(),
                        format!(
                            "the state-space form of `{k}`'s matrices, which are compared: E = diag(I, M) \
                             (or I), A from −[K C] and the kinematic rows"
                        ),
                    ));
                }
                _ => {}
            }
        }
        plan
    }

    fn read_kane(
        &mut self,
        d: &'d Derivation,
        s: &'d Step,
        args: &[Ast],
        constrained_step: Option<&str>,
    ) {
        let positional = args
            .iter()
            .take_while(|a| !matches!(a.kind, AstKind::Assign { .. }))
            .count();
        if positional == args.len() {
            return;
        }
        let refuse = |plan: &mut Self, why: String| plan.refused.push((s.name.clone(), why));
        if positional >= 3 && constrained_step != Some(s.name.as_str()) {
            return refuse(
                self,
                "its constraints are not rows of earlier steps, which verification reads to draw the \
                 motion"
                    .into(),
            );
        }
        let op = match assignments(d, &s.formula, &args[positional..]) {
            Ok(op) => op,
            Err(why) => return refuse(self, why),
        };
        let Some(speeds) = symbols(d, &args[0]) else {
            return;
        };
        let equations: Vec<Poly> = s.values().into_iter().map(|p| d.unfold(p)).collect();
        if equations.len() != speeds.len() {
            return;
        }
        let mut vars: Vec<Atom> = equations
            .iter()
            .flat_map(Poly::atoms)
            .filter(|a| a.is_time_dependent())
            .collect();
        vars.sort_by_key(|a| a.sort_key());
        vars.dedup();
        if let Some(a) = vars
            .iter()
            .find(|a| !matches!(a.kind(), AtomKind::Var { .. }))
        {
            return refuse(self, format!("it holds {a}, not a deviation"));
        }
        let linear = equations.iter().all(|e| {
            vars.iter()
                .all(|&z| e.partial(z).atoms().iter().all(|a| !vars.contains(a)))
        });
        if !linear {
            return refuse(self, "it is not linear in its deviations".into());
        }
        // The configuration constraints it names (`ground`): the draw
        // solves the dependent coordinates from them.
        if let Some(AstKind::Call { func, args: rows }) = args.get(1).map(|a| &a.kind)
            && func == "list"
        {
            for r in rows {
                let AstKind::Name { name, primes: 0 } = &r.kind else {
                    continue;
                };
                let Some(t) = d
                    .steps
                    .iter()
                    .find(|t| t.name == *name && t.meaning.is_none())
                else {
                    continue;
                };
                let moves = t.values().iter().any(|p| {
                    d.unfold(p)
                        .atoms()
                        .iter()
                        .any(|a| a.order() > 0 || d.speeds().contains(a))
                });
                if !moves {
                    self.refused.push((
                        name.clone(),
                        format!(
                            "a configuration constraint of `{}`: the draw solves the dependent coordinates \
                             from it, so it vanishes at every drawn state by construction",
                            s.name
                        ),
                    ));
                }
            }
        }
        self.kane = Some(s);
        self.speeds = speeds;
        self.op = op;
        self.vars = vars;
        self.equations = equations;
        self.inferred.push(Inferred {
            step: s,
            kind: Kind::Kane,
            subst: Vec::new(),
        });
    }

    /// Refuses `s` when the step it is taken from (the first argument:
    /// `K`, `list(K.1, K.3)`) was refused; true then.
    fn taken_from_refused(&mut self, s: &Step, of: &Ast) -> bool {
        let name = match &of.kind {
            AstKind::Name { name, primes: 0 } => Some(name),
            AstKind::Call { func, args } if func == "list" => {
                args.iter().find_map(|a| match &a.kind {
                    AstKind::Member(of, ..) => match &of.kind {
                        AstKind::Name { name, primes: 0 } => Some(name),
                        _ => None,
                    },
                    _ => None,
                })
            }
            _ => None,
        };
        let Some(name) = name.filter(|n| self.refused.iter().any(|(r, _)| r == *n)) else {
            return false;
        };
        self.refused
            .push((s.name.clone(), format!("taken from `{name}`, not compared")));
        true
    }

    /// `jacobian(K, [z…])` or `jacobian(list(K.a, K.b, …), [z…])`.
    fn read_jacobian(&mut self, d: &'d Derivation, s: &'d Step, args: &[Ast]) {
        let [of, vars] = args else {
            return;
        };
        if self.taken_from_refused(s, of) {
            return;
        }
        let Some(k) = self.kane else {
            return;
        };
        let rows: Option<Vec<usize>> = match &of.kind {
            AstKind::Name { name, primes: 0 } if *name == k.name => {
                Some((0..self.speeds.len()).collect())
            }
            AstKind::Call { func, args } if func == "list" => args
                .iter()
                .map(|a| match &a.kind {
                    AstKind::Member(of, field, _) => match &of.kind {
                        AstKind::Name { name, primes: 0 } if *name == k.name => field
                            .parse::<usize>()
                            .ok()
                            .and_then(|i| i.checked_sub(1))
                            .filter(|i| *i < self.speeds.len()),
                        _ => None,
                    },
                    _ => None,
                })
                .collect(),
            _ => None,
        };
        let (Some(rows), Some(vars)) = (rows, symbols(d, vars)) else {
            return;
        };
        if let Some(z) = vars.iter().find(|z| !self.movable(d, **z)) {
            self.refused.push((
                s.name.clone(),
                format!("{z} is not a coordinate, speed or speed's rate the draw can move"),
            ));
            return;
        }
        self.inferred.push(Inferred {
            step: s,
            kind: Kind::Jacobian { rows, vars },
            subst: Vec::new(),
        });
    }

    /// `subst(C, c = e, …)` of a measured step, constants given values.
    fn read_subst(&mut self, d: &'d Derivation, s: &'d Step, formula: &str, args: &[Ast]) {
        let Some((of, rest)) = args.split_first() else {
            return;
        };
        if self.taken_from_refused(s, of) {
            return;
        }
        let AstKind::Name { name, primes: 0 } = &of.kind else {
            return;
        };
        let Some(base) = self.inferred.iter().find(|i| i.step.name == *name) else {
            return;
        };
        let (kind, mut subst) = (base.kind.clone(), base.subst.clone());
        match assignments(d, formula, rest) {
            Ok(more) if more.iter().all(|(a, _)| !a.is_time_dependent()) => subst.extend(more),
            Ok(_) => {
                self.refused.push((
                    s.name.clone(),
                    "it gives a time symbol a value, not a constant".into(),
                ));
                return;
            }
            Err(why) => {
                self.refused.push((s.name.clone(), why));
                return;
            }
        }
        self.inferred.push(Inferred {
            step: s,
            kind,
            subst,
        });
    }

    /// Whether `z` is an independent coordinate, speed or speed's rate.
    fn movable(&self, d: &Derivation, z: Atom) -> bool {
        let AtomKind::Var { time: true, .. } = z.kind() else {
            return false;
        };
        let base = Atom::time(z.name(), 0);
        let coordinate = d.kinematic_equations().iter().any(|(q, _)| *q == base);
        let speed = d.speeds().contains(&base);
        (coordinate && z.order() == 0) || (speed && z.order() <= 1)
    }

    /// The names of the steps measured here.
    pub(crate) fn measured(&self) -> impl Iterator<Item = &str> {
        self.inferred.iter().map(|i| i.step.name.as_str())
    }

    /// The steps that look linearized but are not measured, with why.
    pub(crate) fn refused(&self) -> &[(String, String)] {
        &self.refused
    }

    /// The report's entries, before any draw.
    pub(crate) fn entries(&self) -> Vec<StepCheck> {
        let k = self.kane.map_or("K", |k| k.name.as_str());
        self.inferred
            .iter()
            .map(|i| {
                let what = match &i.kind {
                    Kind::Kane => {
                        "−(F_r + F_r*) to first order about the operating point".to_string()
                    }
                    Kind::Jacobian { vars, .. } => format!(
                        "∂({k})/∂({}) at the operating point",
                        vars.iter()
                            .map(ToString::to_string)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                };
                let at = if i.subst.is_empty() {
                    String::new()
                } else {
                    format!(
                        ", at {}",
                        i.subst
                            .iter()
                            .map(|(a, p)| format!("{a} = {}", p.to_source()))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                };
                StepCheck {
                    step: i.step.name.clone(),
                    means: format!("{what}{at} (from the operation)"),
                    conditions: String::new(),
                    against:
                        "generalized active and inertia forces on the particles at the operating \
                              point, differentiated by Richardson-extrapolated central differences"
                            .into(),
                    max_error: 0.0,
                    worst: None,
                    passed: true,
                }
            })
            .collect()
    }

    /// States in each measured step's `against` (its [`Plan::entries`]
    /// entry, after the draws) the bound its worst comparison was held
    /// to: the estimate plus [`TOLERANCE_ULPS`] of round-off. The scale
    /// folds the estimate in, so the relative error alone reads ~1e-17.
    pub(crate) fn state_bounds<'a>(entries: impl Iterator<Item = &'a mut StepCheck>) {
        for s in entries {
            if let Some(c) = &s.worst {
                let bound = TOLERANCE_ULPS * f64::EPSILON * c.scale;
                s.against.push_str(&format!(
                    "; tolerance used at {}: |derived − measured| ≤ {bound:.3e} (|measured| {:.3e})",
                    c.quantity,
                    c.direct.abs()
                ));
            }
        }
    }
}
