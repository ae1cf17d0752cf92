//! A step's presentation as the file asks for it: the atoms to collect
//! by (`collect`), the factors to pull out (`factor`, kept as written) and
//! the abbreviations to fold back in (`fold`).

use super::Abbreviation;
use super::context::{Context, R};
use super::raw::{RawStep, string_contents};
use crate::present::Presentation;

impl Context<'_> {
    /// The presentation of a step: atoms to collect by, abbreviations to fold.
    pub fn presentation(&self, s: &RawStep, abbrevs: &[Abbreviation]) -> R<Presentation> {
        let mut pres = Presentation {
            constant_order: self.constant_order.clone(),
            ..Presentation::default()
        };
        if let Some(list) = &s.collect {
            let spans = string_contents(self.text, list.span().start, list.span().end);
            for (k, item) in list.get_ref().iter().enumerate() {
                let base = spans.get(k).map_or(list.span().start, |s| s.0);
                let (atom, _) = self.listed_atom(
                    item,
                    base,
                    true,
                    "collect by symbols such as omega_x, omega_x' or sin(theta)",
                )?;
                pres.collect.push(atom);
            }
        }
        if let Some(list) = &s.factor {
            let spans = string_contents(self.text, list.span().start, list.span().end);
            for (k, item) in list.get_ref().iter().enumerate() {
                let base = spans.get(k).map_or(list.span().start, |s| s.0);
                let ast = self.parse_at(item, base)?;
                pres.factors.push(self.scalar(&ast, base)?);
                // Printed as written when it is a plain formula.
                let mut written = crate::expr::Expr::new();
                if self.symbols.lower(&ast, &mut written).is_err() {
                    written = crate::expr::Expr::new();
                }
                pres.factor_forms.push(written);
            }
        }
        if let Some(list) = &s.fold {
            let spans = string_contents(self.text, list.span().start, list.span().end);
            for (k, item) in list.get_ref().iter().enumerate() {
                match abbrevs.iter().find(|a| &a.name == item) {
                    Some(a) => pres.fold.push((a.atom, a.definition.clone())),
                    None => {
                        let (s0, s1) = spans
                            .get(k)
                            .copied()
                            .unwrap_or((list.span().start, list.span().end));
                        return Err(self.diag(
                            s0,
                            s1,
                            format!("`{item}` is not a declared [[abbreviation]]"),
                        ));
                    }
                }
            }
        }
        Ok(pres)
    }
}
