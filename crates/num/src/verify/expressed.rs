//! Steps that express a constant vector of one frame in another's axes —
//! `express([0, 1, 0] in H, N).z`, the bicycle's front axle's vertical
//! component — need no `means`: they are the frames' relative attitude,
//! measured from the drawn rotation matrices, `R_Gᵀ R_F v`, never from the
//! engine's rotations. Read from the step's formula; compared in every
//! draw.

use hdot_sym::derivation::{Derivation, Step};
use hdot_sym::parse::{Ast, AstKind, parse};
use hdot_sym::poly::Poly;
use nalgebra::Vector3;

use super::draw::Draw;
use super::means::frame_index;
use super::world::World;
use super::{Comparison, StepCheck, VerifyError};
use crate::bind::Values;

/// A step `express(v in F, G)` or one component of it, v constant.
pub(crate) struct Expressed<'d> {
    step: &'d Step,
    v: [Poly; 3],
    from: usize,
    to: usize,
    /// The component taken (`.z`), or all three.
    component: Option<usize>,
}

/// `express(v in F, G)`: (v, F, G).
fn express(d: &Derivation, a: &Ast) -> Option<([Poly; 3], usize, usize)> {
    let AstKind::Call { func, args } = &a.kind else {
        return None;
    };
    let [v, to] = args.as_slice() else {
        return None;
    };
    if func != "express" {
        return None;
    }
    let AstKind::Vector {
        items,
        frame: Some((from, _)),
    } = &v.kind
    else {
        return None;
    };
    let AstKind::Name {
        name: to,
        primes: 0,
    } = &to.kind
    else {
        return None;
    };
    let known = |f: &str| d.frames.iter().any(|x| x.name == f);
    if items.len() != 3 || !known(from) || !known(to) {
        return None;
    }
    let v: Vec<Poly> = items
        .iter()
        .map(|i| {
            let AstKind::Num(r) = &i.kind else {
                return None;
            };
            Some(Poly::constant(r.clone()))
        })
        .collect::<Option<_>>()?;
    Some((
        [v[0].clone(), v[1].clone(), v[2].clone()],
        frame_index(d, from),
        frame_index(d, to),
    ))
}

/// The steps of `d` without a meaning that express a constant vector.
pub(crate) fn read(d: &Derivation) -> Vec<Expressed<'_>> {
    d.steps
        .iter()
        .filter(|s| s.meaning.is_none())
        .filter_map(|s| {
            let ast = parse(&s.formula).ok()?;
            let (of, component) = match &ast.kind {
                AstKind::Member(of, field, _) => (
                    of.as_ref(),
                    Some(["x", "y", "z"].iter().position(|c| c == field)?),
                ),
                _ => (&ast, None),
            };
            let (v, from, to) = express(d, of)?;
            let n = s.values().len();
            (n == component.map_or(3, |_| 1)).then_some(Expressed {
                step: s,
                v,
                from,
                to,
                component,
            })
        })
        .collect()
}

impl Expressed<'_> {
    /// The step's name.
    pub(crate) fn name(&self) -> &str {
        &self.step.name
    }

    /// The report's entry, before any draw.
    pub(crate) fn entry(&self, d: &Derivation) -> StepCheck {
        StepCheck {
            step: self.step.name.clone(),
            means: format!(
                "a vector of {} in {}'s axes (from the operation)",
                d.frames[self.from].name, d.frames[self.to].name
            ),
            conditions: String::new(),
            against: "R_Gᵀ R_F v from the drawn rotation matrices".into(),
            max_error: 0.0,
            worst: None,
            passed: true,
        }
    }

    /// The comparisons in one draw.
    pub(crate) fn compare(
        &self,
        d: &Derivation,
        draw: &Draw,
        values: &Values,
    ) -> Result<Vec<Comparison>, VerifyError> {
        let w = World::build(d, draw, values, &[])?;
        let mut v = Vector3::zeros();
        for (k, p) in self.v.iter().enumerate() {
            v[k] = values.eval(p).map_err(VerifyError::from)?.0;
        }
        let measured = w.frames[self.to][0].transpose() * (w.frames[self.from][0] * v);
        let derived = self
            .step
            .values()
            .into_iter()
            .map(|p| values.eval(&d.unfold(p)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| VerifyError::from(e).in_step(d, &self.step.name))?;
        let picked: Vec<usize> = match self.component {
            Some(c) => vec![c],
            None => vec![0, 1, 2],
        };
        Ok(picked
            .iter()
            .zip(derived)
            .map(|(&k, (x, s))| Comparison {
                quantity: match self.component {
                    Some(_) => self.step.name.clone(),
                    None => format!("{}.{}", self.step.name, ["x", "y", "z"][k]),
                },
                derived: x,
                direct: measured[k],
                scale: s + v.norm() + f64::MIN_POSITIVE,
            })
            .collect())
    }
}
