//! A step's label checked against its value: a label that is mathematics
//! prints as the left side of the step's equations, so it must be what the
//! value is. A step `solve(eq, x)` (or a `subst` of one) is labelled by
//! its unknown x or by a name; an expression label (`phi''*sin(theta)`) or
//! a time symbol (`psi'`) on any other step must equal the value
//! identically; `partial(T, q)` must be ∂T/∂q of the earlier step `T`.
//! A label `0` states that the value vanishes: on a solve step that is
//! never so; elsewhere it is an identity or a law of motion, which
//! `hdot verify` checks through the step's meaning. A label that is a name
//! (`Sigma M`, `H_G`, a constant's name on a step that is not a solve)
//! stays a name.

use super::context::{Context, R};
use super::raw::RawStep;
use super::unfold;
use super::value::Value;
use crate::label::LabelMath;
use crate::parse::{Ast, AstKind, parse};
use crate::poly::Poly;
use crate::symbols::Decl;

/// What a step's formula solves for, read from its outermost call
/// through `subst(…, rules)`.
enum Solved {
    /// Not a solve.
    No,
    /// `solve(eq, x)`: one unknown (or `solve(eq, x^k)`: its power).
    One(Poly),
    /// `solve(eqs, [x, y, …])`: several, each labelling its own item.
    Several,
}

impl Context<'_> {
    /// Checks that the label of step `s` (already read as `math`) is what
    /// its value is; the error names the step and the label.
    pub(crate) fn check_label(
        &self,
        s: &RawStep,
        value: &Value,
        math: Option<&LabelMath>,
    ) -> R<()> {
        let Some(label) = &s.label else {
            return Ok(());
        };
        let text = label.get_ref().trim();
        let n = s.name.get_ref();
        let fail = |msg: String| -> R<()> {
            Err(self.diag_string(
                label,
                0,
                label.get_ref().len(),
                format!("step `{n}`, field `label`: {msg}"),
            ))
        };
        let solved = self.solved(s.value.get_ref());
        // A plain word that is a declared symbol prints as that symbol.
        let symbol = self.symbol_label(text);
        match (solved, math, symbol) {
            (Solved::One(_) | Solved::Several, Some(LabelMath::Zero), _) => fail(
                "a step solved for its unknowns is not zero: `0 = …` would be false; label it with the unknown or a name"
                    .to_owned(),
            ),
            (Solved::Several, Some(_), _) | (Solved::Several, None, Some(_)) => fail(format!(
                "`{text}` labels a step solved for several unknowns, whose items are labelled by the unknowns \
                 themselves; label the step with a name (`accelerations`)"
            )),
            (Solved::One(x), Some(LabelMath::Expr(e)), _) => {
                self.same_unknown(text, &e.to_poly(), &x, &fail)
            }
            (Solved::One(x), None, Some(p)) => self.same_unknown(text, &p, &x, &fail),
            (Solved::One(x), Some(LabelMath::Partial(..) | LabelMath::Formula(_)), _) => fail(format!(
                "`{text}` is not what the step solves for: it gives {x}; label it `{x}` or with a name"
            )),
            (_, Some(LabelMath::Zero), _) | (Solved::One(_) | Solved::Several, None, None) => {
                Ok(())
            }
            (Solved::No, Some(LabelMath::Expr(e)), _) => {
                self.identical(text, value, &e.to_poly(), &fail)
            }
            (Solved::No, Some(LabelMath::Partial(f, q)), _) => {
                let Some(Value::Scalar(of)) = self.values.get(f) else {
                    return fail(format!(
                        "`{text}`: `{f}` is not an earlier step with a scalar value, so ∂{f}/∂{q} is not defined here"
                    ));
                };
                let want = unfold(&self.abbrevs, of).partial(*q);
                self.identical(text, value, &want, &fail)
            }
            // A time symbol (ψ̇) on a step that is not a solve: the
            // printed `ψ̇ = …` must be an identity.
            (Solved::No, None, Some(p)) if p.atoms().iter().any(|a| a.is_time_dependent()) => {
                self.identical(text, value, &p, &fail)
            }
            // A formula of names (`|H_G|^2`) reads as the names it shows.
            (Solved::No, None | Some(LabelMath::Formula(_)), _) => Ok(()),
        }
    }

    /// Whether the label `text` is exactly a declared constant or time
    /// symbol (with its primes), as a polynomial; abbreviations and other
    /// words are names.
    fn symbol_label(&self, text: &str) -> Option<Poly> {
        let base = text.trim_end_matches('\'');
        match self.symbols.get(base) {
            Some(Decl::Constant | Decl::Time) => self.symbols.poly(text).ok(),
            _ => None,
        }
    }

    /// The label of a solve for `x` must be `x`.
    fn same_unknown(
        &self,
        text: &str,
        label: &Poly,
        x: &Poly,
        fail: &dyn Fn(String) -> R<()>,
    ) -> R<()> {
        if (label - x).is_zero() {
            return Ok(());
        }
        fail(format!(
            "`{text}` is not what the step solves for: it gives {x}, so `{text} = …` would print a false equation; \
             label it `{x}` or with a name"
        ))
    }

    /// An expression label must equal a scalar value identically.
    fn identical(
        &self,
        text: &str,
        value: &Value,
        label: &Poly,
        fail: &dyn Fn(String) -> R<()>,
    ) -> R<()> {
        let Value::Scalar(v) = value else {
            return fail(format!(
                "`{text}` is a scalar expression, and the step is {}: label it with a name",
                value.describe()
            ));
        };
        let diff = &unfold(&self.abbrevs, v) - &unfold(&self.abbrevs, label);
        if diff.is_zero() {
            return Ok(());
        }
        fail(format!(
            "`{text}` is not the step's value (their difference is {diff}), so `{text} = …` would print a false \
             equation; label it with a name, or solve for what the label names (`solve(eq, x)` labelled `x`)"
        ))
    }

    /// What the formula of a step solves for.
    fn solved(&self, formula: &str) -> Solved {
        let Ok(mut ast) = parse(formula) else {
            return Solved::No;
        };
        loop {
            let AstKind::Call { func, args } = &ast.kind else {
                return Solved::No;
            };
            match (func.as_str(), args.as_slice()) {
                ("subst", [inner, ..]) => ast = inner.clone(),
                ("solve", [_, unknown]) => return self.unknown(unknown),
                _ => return Solved::No,
            }
        }
    }

    fn unknown(&self, a: &Ast) -> Solved {
        match &a.kind {
            AstKind::Name { name, primes } => self
                .symbols
                .atom(name, *primes, a.span)
                .map_or(Solved::No, |x| Solved::One(Poly::atom(x))),
            AstKind::Pow(base, k) => match self.unknown(base) {
                Solved::One(x) => Solved::One(x.pow(*k)),
                _ => Solved::No,
            },
            AstKind::Vector { .. } => Solved::Several,
            _ => Solved::No,
        }
    }
}
