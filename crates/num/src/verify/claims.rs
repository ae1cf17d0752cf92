//! Claims a file makes beyond a step's meaning, checked: a step declared
//! `conserved = true` has a time derivative that vanishes along the
//! file's own equations of motion (each step solved for accelerations,
//! `solve(eqs, [q1'', …])`, or for the rates of generalized speeds,
//! `solve(eqs, [u1', …])` with the kinematic equations giving q̇, and each
//! `mass_matrix`/`forcing` pair, solved numerically), at the drawn states; a step labelled `0` states that its
//! value vanishes, which its meaning proves only when it is a law of
//! motion — a force, moment or generalized force the motion requires less
//! the loads applied — or when the value is identically zero.

use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::physics::{Meaning, Quantity};
use hdot_sym::derivation::{Derivation, Step, Value};
use hdot_sym::label::LabelMath;
use hdot_sym::parse::{AstKind, parse};
use hdot_sym::poly::Poly;
use nalgebra::{DMatrix, DVector};

use super::draw::{Draw, constrain};
use super::knowns::bind_knowns;
use super::world::World;
use super::{Comparison, StepCheck, VerifyError};
use crate::bind::Values;

/// One set of equations of motion stated by the file.
pub(crate) enum Equations<'d> {
    /// A step whose value is the accelerations, labelled by them.
    Solved {
        step: &'d Step,
        unknowns: Vec<Atom>,
        items: Vec<Poly>,
        /// The constants given values on the way ([`substituted`]).
        special: Vec<Atom>,
    },
    /// `mass_matrix(eqs, [q1'', …])` and `forcing(eqs, [q1'', …])`.
    MassMatrix {
        names: (String, String),
        unknowns: Vec<Atom>,
        m: Vec<Poly>,
        f: Vec<Poly>,
        special: Vec<Atom>,
    },
}

/// The constants a step's formula, or that of a step it names (and so on),
/// gives a value with `subst(…, c = e)`: equations derived so are a special
/// case of the file's model.
fn substituted(d: &Derivation, s: &Step) -> Vec<Atom> {
    fn walk(d: &Derivation, a: &hdot_sym::parse::Ast, seen: &mut Vec<String>, out: &mut Vec<Atom>) {
        match &a.kind {
            AstKind::Name { name, primes: 0 } => {
                if let Some(t) = d.steps.iter().find(|t| t.name == *name)
                    && !seen.contains(name)
                {
                    seen.push(name.clone());
                    if let Ok(ast) = parse(&t.formula) {
                        walk(d, &ast, seen, out);
                    }
                }
            }
            AstKind::Call { func, args } => {
                for x in args {
                    if let AstKind::Assign {
                        name,
                        primes: 0,
                        value,
                        ..
                    } = &x.kind
                    {
                        if func == "subst"
                            && let Ok(c) = d.symbols.atom(name, 0, x.span)
                            && !c.is_time_dependent()
                            && !out.contains(&c)
                        {
                            out.push(c);
                        }
                        walk(d, value, seen, out);
                    } else {
                        walk(d, x, seen, out);
                    }
                }
            }
            AstKind::Assign { value, .. } => walk(d, value, seen, out),
            AstKind::Vector { items, .. } | AstKind::Add(items) | AstKind::Mul(items) => {
                for x in items {
                    walk(d, x, seen, out);
                }
            }
            AstKind::Recip(x) | AstKind::Neg(x) | AstKind::Pow(x, _) | AstKind::Member(x, ..) => {
                walk(d, x, seen, out);
            }
            AstKind::Cross(x, y) => {
                walk(d, x, seen, out);
                walk(d, y, seen, out);
            }
            AstKind::Num(_) | AstKind::Name { .. } => {}
        }
    }
    let mut out = Vec::new();
    if let Ok(ast) = parse(&s.formula) {
        walk(d, &ast, &mut vec![s.name.clone()], &mut out);
    }
    out
}

impl Equations<'_> {
    fn name(&self) -> String {
        match self {
            Equations::Solved { step, .. } => step.name.clone(),
            Equations::MassMatrix { names, .. } => format!("{}, {}", names.0, names.1),
        }
    }

    /// The accelerations at `values`, each with the size of its round-off
    /// scale; `None` for a singular mass matrix.
    fn accelerations(&self, values: &Values) -> Result<Option<Vec<(f64, f64)>>, VerifyError> {
        match self {
            Equations::Solved { items, .. } => Ok(Some(
                items
                    .iter()
                    .map(|p| values.eval(p))
                    .collect::<Result<Vec<_>, _>>()?,
            )),
            Equations::MassMatrix { unknowns, m, f, .. } => {
                let n = unknowns.len();
                let mv = m
                    .iter()
                    .map(|p| values.eval(p))
                    .collect::<Result<Vec<_>, _>>()?;
                let fv = f
                    .iter()
                    .map(|p| values.eval(p))
                    .collect::<Result<Vec<_>, _>>()?;
                let mm = DMatrix::from_fn(n, n, |i, j| mv[i * n + j].0);
                let Some(inv) = mm.clone().try_inverse() else {
                    return Ok(None);
                };
                let x = &inv * DVector::from_fn(n, |i, _| fv[i].0);
                // Round-off of x = M⁻¹ f: |M⁻¹| (|f| + |M| |x|) on the
                // magnitudes of their terms.
                let rhs = DVector::from_fn(n, |i, _| {
                    fv[i].1 + (0..n).map(|j| mv[i * n + j].1 * x[j].abs()).sum::<f64>()
                });
                let size = inv.abs() * rhs;
                Ok(Some((0..n).map(|i| (x[i], size[i])).collect()))
            }
        }
    }

    /// Whether these equations hold wherever `c` is defined: none of the
    /// conserved value's constants was given a value on the way to them
    /// (equations with constants substituted, `subst(K, I = m*r^2/2)`, are
    /// a special case along which the general claim is not stated). A
    /// constant the equations do not hold is no such sign: a body rolling
    /// freely has accelerations free of its mass.
    fn covers(&self, c: &Conserved<'_>) -> bool {
        let special = match self {
            Equations::Solved { special, .. } | Equations::MassMatrix { special, .. } => special,
        };
        c.rates
            .iter()
            .flat_map(constants)
            .all(|a| !special.contains(&a))
    }

    fn unknowns(&self) -> &[Atom] {
        match self {
            Equations::Solved { unknowns, .. } | Equations::MassMatrix { unknowns, .. } => unknowns,
        }
    }
}

/// The constants of `p`.
fn constants(p: &Poly) -> Vec<Atom> {
    p.atoms()
        .into_iter()
        .filter(|a| matches!(a.kind(), AtomKind::Var { time: false, .. }))
        .collect()
}

/// The unknowns `[q1'', …]` (or `[u1', …]`) of a step written
/// `func(eqs, [q1'', …])`.
fn call_unknowns(d: &Derivation, s: &Step, func: &str) -> Option<Vec<Atom>> {
    let ast = parse(&s.formula).ok()?;
    let AstKind::Call { func: f, args } = &ast.kind else {
        return None;
    };
    let AstKind::Vector { items, frame: None } = &args.get(1)?.kind else {
        return None;
    };
    if f != func {
        return None;
    }
    items
        .iter()
        .map(|a| match &a.kind {
            AstKind::Name {
                name,
                primes: p @ (1 | 2),
            } => d
                .symbols
                .atom(name, *p, a.span)
                .ok()
                .filter(|x| x.is_time_dependent()),
            _ => None,
        })
        .collect()
}

/// Every set of equations of motion the file states.
pub(crate) fn equations(d: &Derivation) -> Vec<Equations<'_>> {
    let mut out = Vec::new();
    for s in &d.steps {
        if let Value::List { items, labels } = &s.value
            && !labels.is_empty()
            && labels.len() == items.len()
            && labels.iter().all(|a| {
                a.is_time_dependent()
                    && (a.order() == 2 || (a.order() == 1 && d.speeds().contains(&a.base())))
            })
            && call_unknowns(d, s, "solve").is_some()
        {
            out.push(Equations::Solved {
                step: s,
                unknowns: labels.clone(),
                items: items.iter().map(|p| d.unfold(p)).collect(),
                special: substituted(d, s),
            });
        }
        let Some(unknowns) = call_unknowns(d, s, "mass_matrix") else {
            continue;
        };
        let n = unknowns.len();
        let Some(forcing) = d
            .steps
            .iter()
            .find(|g| call_unknowns(d, g, "forcing").as_ref() == Some(&unknowns))
        else {
            continue;
        };
        let m: Vec<Poly> = match &s.value {
            Value::Array(rows) if rows.len() == n && rows.iter().all(|r| r.len() == n) => {
                rows.iter().flatten().map(|p| d.unfold(p)).collect()
            }
            Value::Matrix(m) if n == 3 => m.0.iter().flatten().map(|p| d.unfold(p)).collect(),
            _ => continue,
        };
        let f: Vec<Poly> = forcing.values().iter().map(|p| d.unfold(p)).collect();
        if f.len() != n {
            continue;
        }
        let mut special = substituted(d, s);
        special.extend(substituted(d, forcing));
        out.push(Equations::MassMatrix {
            names: (s.name.clone(), forcing.name.clone()),
            unknowns,
            m,
            f,
            special,
        });
    }
    out
}

/// A conserved step with its time derivative, compiled once.
pub(crate) struct Conserved<'d> {
    step: &'d Step,
    rates: Vec<Poly>,
}

/// The steps declared conserved, with their time derivatives.
pub(crate) fn conserved(d: &Derivation) -> Vec<Conserved<'_>> {
    d.steps
        .iter()
        .filter(|s| s.conserved)
        .map(|s| Conserved {
            step: s,
            rates: s.values().into_iter().map(|p| d.unfold(p).dt()).collect(),
        })
        .collect()
}

/// The report's entry for a conserved step, before any draw.
pub(crate) fn conserved_entry(c: &Conserved<'_>, eqs: &[Equations<'_>]) -> StepCheck {
    let eqs: Vec<&Equations<'_>> = eqs.iter().filter(|e| e.covers(c)).collect();
    StepCheck {
        step: c.step.name.clone(),
        means: "conserved".into(),
        conditions: String::new(),
        against: if eqs.is_empty() {
            "its rate along the file's equations of motion: the file states none (a step \
             `solve(eqs, [q1'', …])` or `mass_matrix` and `forcing`) that keeps the value's constants \
             free (not given values by `subst`)"
                .into()
        } else {
            format!(
                "its rate along the equations of motion of {}",
                eqs.iter()
                    .map(|e| format!("`{}`", e.name()))
                    .collect::<Vec<_>>()
                    .join(" and ")
            )
        },
        max_error: if eqs.is_empty() { f64::INFINITY } else { 0.0 },
        worst: None,
        passed: !eqs.is_empty(),
    }
}

/// The rate of each conserved step along each set of equations, in one
/// draw: zero for a true claim. Only the equations some conserved step is
/// compared along are solved: a file that states equations of motion and
/// no conserved step (the bicycle's mass matrix and forcing, 72
/// polynomials) solves none of them.
pub(crate) fn compare_conserved(
    d: &Derivation,
    draw: &Draw,
    values: &Values,
    conserved: &[Conserved<'_>],
    eqs: &[Equations<'_>],
) -> Result<Vec<Vec<Comparison>>, VerifyError> {
    let eqs: Vec<&Equations<'_>> = eqs
        .iter()
        .filter(|e| conserved.iter().any(|c| e.covers(c)))
        .collect();
    if eqs.is_empty() {
        return Ok(vec![Vec::new(); conserved.len()]);
    }
    let mut values = values.clone();
    constrain(d, &mut values, &[])?;
    if !d.physics.knowns.is_empty() {
        let w = World::build(d, draw, &values, &[])?;
        bind_knowns(d, &w, &mut values)?;
    }
    // In generalized speeds the coordinates' rates are the kinematic
    // equations' q̇ = f(q, u).
    for (q, f) in d.kinematic_equations() {
        let (x, s) = values.eval(&d.unfold(f)).map_err(VerifyError::from)?;
        values.set(crate::bind::nth(q.base(), 1), x, s);
    }
    let mut along = Vec::new();
    for e in eqs {
        let Some(acc) = e.accelerations(&values)? else {
            continue;
        };
        let mut v = values.clone();
        for (a, (x, s)) in e.unknowns().iter().zip(acc) {
            v.set(*a, x, s);
        }
        // The accelerations the rules tie to the solved ones follow them,
        // and so do those of the other kind, through the kinematic
        // equations; the rates of the speeds a `kane` step's constraints
        // make dependent follow the solved rates of the independent ones
        // through the constraint rows' rates.
        constrain(d, &mut v, &[])?;
        dependent_rates(d, draw, e.unknowns(), &mut v)?;
        complete_rates(d, e.unknowns(), &mut v)?;
        along.push((e, v));
    }
    conserved
        .iter()
        .map(|c| {
            let mut out = Vec::new();
            for (e, v) in along.iter().filter(|(e, _)| e.covers(c)) {
                let name = e.name();
                for (k, p) in c.rates.iter().enumerate() {
                    let (r, scale) = v
                        .eval(p)
                        .map_err(|e| VerifyError::from(e).in_step(d, &c.step.name))?;
                    let component = if c.rates.len() == 1 {
                        String::new()
                    } else {
                        format!(".{}", k + 1)
                    };
                    out.push(Comparison {
                        quantity: format!("d({}{component})/dt along `{name}`", c.step.name),
                        derived: r,
                        direct: 0.0,
                        scale: scale + f64::MIN_POSITIVE,
                    });
                }
            }
            Ok(out)
        })
        .collect()
}

/// With the independent speeds' rates solved, the dependent speeds' rates
/// from the constraint rows' rates (and the coordinates' second rates from
/// the kinematic equations' rates): without this a dependent speed keeps
/// the rate drawn with the drawn independent rates, and a conserved energy
/// written in it (or in the coordinates' rates) fails along the true
/// motion.
fn dependent_rates(
    d: &Derivation,
    draw: &Draw,
    solved: &[Atom],
    v: &mut Values,
) -> Result<(), VerifyError> {
    let Some(speeds) = &draw.consistent().speeds else {
        return Ok(());
    };
    let rates: Vec<Atom> = d
        .speeds()
        .iter()
        .map(|u| crate::bind::nth(u.base(), 1))
        .collect();
    if speeds.dependent.is_empty() || !solved.iter().any(|a| rates.contains(a)) {
        return Ok(());
    }
    let mut w = v.clone();
    if speeds.fill(d, &mut w, 2)?.is_some() {
        *v = w;
    }
    Ok(())
}

/// After a law of motion's unknowns are set, the rates of the other kind
/// follow from the kinematic equations q̇ = f(q, u): with the speeds'
/// rates solved, each q̈ = ḟ; with the coordinates' second rates solved,
/// the speeds' rates from ḟ = q̈, which is linear in them (least squares
/// through the SVD when there are more equations than speeds). Without
/// this the other kind keeps its random draw, and a conserved quantity
/// written in it (the energy in q̇ along Kane's equations in u̇) fails.
fn complete_rates(d: &Derivation, solved: &[Atom], v: &mut Values) -> Result<(), VerifyError> {
    let kinematics = d.kinematic_equations();
    if kinematics.is_empty() {
        return Ok(());
    }
    let second: Vec<(Atom, Poly)> = kinematics
        .iter()
        .map(|(q, f)| (crate::bind::nth(q.base(), 2), d.unfold(f).dt()))
        .collect();
    let rates: Vec<Atom> = d
        .speeds()
        .iter()
        .map(|u| crate::bind::nth(u.base(), 1))
        .collect();
    let solved_rates = solved.iter().any(|a| rates.contains(a));
    let solved_second = solved.iter().any(|a| second.iter().any(|(q, _)| q == a));
    if solved_rates && !solved_second {
        for (q, fd) in &second {
            let (x, s) = v.eval(fd).map_err(VerifyError::from)?;
            v.set(*q, x, s);
        }
    } else if solved_second && !solved_rates {
        let (m, n) = (second.len(), rates.len());
        let at = |v: &mut Values, unit: Option<usize>| -> Result<Vec<(f64, f64)>, VerifyError> {
            for (k, u) in rates.iter().enumerate() {
                v.set(*u, if Some(k) == unit { 1.0 } else { 0.0 }, 1.0);
            }
            second
                .iter()
                .map(|(_, fd)| v.eval(fd).map_err(VerifyError::from))
                .collect()
        };
        let base = at(v, None)?;
        let mut a = DMatrix::zeros(m, n);
        for k in 0..n {
            for (i, (x, _)) in at(v, Some(k))?.into_iter().enumerate() {
                a[(i, k)] = x - base[i].0;
            }
        }
        let mut scale = 0.0_f64;
        let b = DVector::from_iterator(
            m,
            second.iter().zip(&base).map(|((q, _), (x0, s0))| {
                let (qdd, sq) = v.get(*q).unwrap_or((0.0, 0.0));
                scale = scale.max(sq).max(*s0);
                qdd - x0
            }),
        );
        let Ok(x) = a.svd(true, true).solve(&b, 1e-12) else {
            return Ok(());
        };
        for (u, x) in rates.iter().zip(x.iter()) {
            v.set(*u, *x, scale.max(x.abs()));
        }
    }
    Ok(())
}

/// Whether a meaning is a law of motion: every quantity in it is one the
/// motion requires (a force, moment, generalized force or Kane's
/// generalized inertia force) or a load (weight, its moment, generalized
/// weight or Kane's generalized active force, an applied value), and at
/// least one is required by the motion.
pub(crate) fn is_law(m: &Meaning) -> bool {
    fn walk(m: &Meaning, required: &mut bool) -> bool {
        match m {
            Meaning::Quantity(q, _) => match q {
                Quantity::Force
                | Quantity::Moment
                | Quantity::GeneralizedForce
                | Quantity::GeneralizedInertiaForce => {
                    *required = true;
                    true
                }
                Quantity::Weight
                | Quantity::WeightMoment
                | Quantity::GeneralizedWeight
                | Quantity::GeneralizedActiveForce => true,
                _ => false,
            },
            Meaning::Applied(_) | Meaning::AppliedVector(..) => true,
            Meaning::Sum(t) => t.iter().all(|(_, x)| walk(x, required)),
            Meaning::List(items) => items.iter().all(|x| {
                let mut r = false;
                let ok = walk(x, &mut r);
                *required |= r;
                ok && r
            }),
            Meaning::Along(x, ..) | Meaning::Scaled(_, x) | Meaning::Linear(x) => walk(x, required),
            _ => false,
        }
    }
    let mut required = false;
    walk(m, &mut required) && required
}

/// The failed check of a step labelled `0` whose value is not zero and
/// whose meaning is not a law of motion (`None` when the label holds or
/// the step has no meaning: then it is not compared at all).
pub(crate) fn zero_label(d: &Derivation, s: &Step) -> Option<StepCheck> {
    if !matches!(s.label_math, Some(LabelMath::Zero)) {
        return None;
    }
    if s.values().iter().all(|p| d.unfold(p).is_zero()) {
        return None;
    }
    let m = s.meaning.as_ref()?;
    if is_law(&m.meaning) {
        return None;
    }
    Some(StepCheck {
        step: s.name.clone(),
        means: m.text.clone(),
        conditions: m.conditions.clone(),
        against: "label `0`: the value is printed as vanishing, which its meaning proves only when it is a \
                  law of motion (a force, moment or generalized force the motion requires less the applied \
                  loads)"
            .into(),
        max_error: f64::INFINITY,
        worst: None,
        passed: false,
    })
}
