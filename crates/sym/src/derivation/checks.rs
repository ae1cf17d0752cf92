//! A step's `expect`: the expected form read in the shape of the step's
//! value (a scalar, three components or one vector expression, a list,
//! rows of a matrix or array), each component checked by canonical
//! difference.

use super::context::{Context, R};
use super::raw::{RawStep, string_contents};
use super::value::Value;
use super::{Abbreviation, Check, unfold};
use crate::poly::Poly;
use crate::present::{Presentation, present};

impl Context<'_> {
    /// Checks a step's value against its `expect`.
    pub fn checks(
        &self,
        s: &RawStep,
        value: &Value,
        abbrevs: &[Abbreviation],
        pres: &Presentation,
        axes: &[String; 3],
    ) -> R<Vec<Check>> {
        let Some(exp) = &s.expect else {
            return Ok(vec![]);
        };
        let sp = exp.span();
        let spans = string_contents(self.text, sp.start, sp.end);
        let strings = |a: &[toml::Value]| -> Option<Vec<String>> {
            a.iter().map(|x| x.as_str().map(str::to_owned)).collect()
        };
        // Rows of strings (a matrix or array step) are read row by row.
        let nested = matches!(exp.get_ref(), toml::Value::Array(a) if !a.is_empty() && a.iter().all(|r| r.is_array()));
        let texts: Vec<String> = match exp.get_ref() {
            toml::Value::String(t) => vec![t.clone()],
            toml::Value::Array(a) if a.iter().all(|x| x.is_str()) => strings(a).expect("strings"),
            toml::Value::Array(rows) if nested => {
                let rows: Option<Vec<Vec<String>>> = rows
                    .iter()
                    .map(|r| r.as_array().and_then(|r| strings(r)))
                    .collect();
                match rows {
                    Some(rows) => rows.into_iter().flatten().collect(),
                    None => {
                        return Err(self.diag(
                            sp.start,
                            sp.end,
                            "`expect` for a matrix is an array of rows, each an array of strings",
                        ));
                    }
                }
            }
            _ => {
                return Err(self.diag(
                    sp.start,
                    sp.end,
                    "`expect` is a string (scalar), an array of strings (vector or list) or an array of rows of \
                     strings (matrix or array)",
                ));
            }
        };
        // A single string for a vector step is a vector expression.
        if let (Value::Vector(v, frame), [text]) = (value, texts.as_slice()) {
            let base = spans.first().map_or(sp.start, |s| s.0);
            let ast = self.parse_at(text, base)?;
            let (w, wf) = self.vector(&ast, base)?;
            self.same_frame(base, ast.span, frame, &wf)?;
            return Ok((0..3)
                .map(|k| Check {
                    component: axes[k].clone(),
                    expected_text: format!("({text}).{}", axes[k]),
                    expected: present(&w.0[k], pres),
                    difference: difference(abbrevs, &v.0[k], &w.0[k]),
                })
                .collect());
        }
        let derived: Vec<(String, Poly)> = match value {
            Value::Scalar(p)
                if texts.len() == 1 && matches!(exp.get_ref(), toml::Value::String(_)) =>
            {
                vec![(String::new(), p.clone())]
            }
            Value::Vector(v, _) if texts.len() == 3 => {
                (0..3).map(|k| (axes[k].clone(), v.0[k].clone())).collect()
            }
            Value::List { items, .. }
                if !nested
                    && texts.len() == items.len()
                    && matches!(exp.get_ref(), toml::Value::Array(_)) =>
            {
                super::component_labels(value, axes)
                    .into_iter()
                    .zip(items.iter().cloned())
                    .collect()
            }
            Value::Matrix(_) | Value::Array(_)
                if nested && texts.len() == value.components().len() =>
            {
                super::component_labels(value, axes)
                    .into_iter()
                    .zip(value.components().into_iter().cloned())
                    .collect()
            }
            v => {
                return Err(self.diag(
                    sp.start,
                    sp.end,
                    format!(
                        "the step is {}, so `expect` must be {}",
                        v.describe(),
                        match v {
                            Value::Scalar(_) => "one string",
                            Value::Vector(..) =>
                                "an array of three strings or one vector expression",
                            Value::List { .. } =>
                                "an array of as many strings as the list has items",
                            Value::Matrix(_) | Value::Array(_) =>
                                "an array of rows, each an array of strings, as many as the step has",
                        }
                    ),
                ));
            }
        };
        let mut out = Vec::new();
        for (k, ((comp, got), text)) in derived.into_iter().zip(&texts).enumerate() {
            let base = spans.get(k).map_or(sp.start, |s| s.0);
            let ast = self.parse_at(text, base)?;
            let want = self.scalar(&ast, base)?;
            let difference = difference(abbrevs, &got, &want);
            // Keep the expectation as written when it is a plain formula in
            // the declared symbols; otherwise present its canonical form.
            let mut written = crate::expr::Expr::new();
            let expected = match self.symbols.lower(&ast, &mut written) {
                Ok(_) => written,
                Err(_) => present(&want, pres),
            };
            out.push(Check {
                component: comp,
                expected_text: text.clone(),
                expected,
                difference,
            });
        }
        Ok(out)
    }
}

/// `got − want` with the abbreviations unfolded. Both are canonical, so
/// equal values (a check that holds, the common case) differ by zero
/// without unfolding or subtracting anything; exactness is kept.
fn difference(abbrevs: &[Abbreviation], got: &Poly, want: &Poly) -> Poly {
    if got == want {
        Poly::zero()
    } else {
        &unfold(abbrevs, got) - &unfold(abbrevs, want)
    }
}
