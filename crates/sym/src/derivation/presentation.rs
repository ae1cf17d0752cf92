//! A step's presentation as the file asks for it: the atoms to collect
//! by (`collect`), the factors to pull out (`factor`, kept as written) and
//! the abbreviations to fold back in (`fold`); and the file's unknowns,
//! whose terms every step prints first.

use super::Abbreviation;
use super::context::{Context, R};
use super::raw::{RawStep, string_contents};
use crate::atom::Atom;
use crate::parse::{Ast, AstKind, parse};
use crate::present::Presentation;

impl Context<'_> {
    /// The presentation of a step: atoms to collect by, abbreviations to fold.
    pub fn presentation(&self, s: &RawStep, abbrevs: &[Abbreviation]) -> R<Presentation> {
        let mut pres = Presentation {
            constant_order: self.constant_order.clone(),
            unknowns: self.unknowns.clone(),
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

/// # Unknowns
impl Context<'_> {
    /// What the steps `solve` for — `solve(eq, x)`, `solve(eqs, [x, y])`,
    /// `solve(eq, x^k)` — read from the steps as written, before any is
    /// evaluated, so that an equation written before its solve prints
    /// the unknowns' terms first: a (A_x − B_x) + … = 0 solved later for
    /// A_x and B_x. A value that does not parse, or a target that is not
    /// a declared symbol, adds nothing (its step reports the error).
    pub fn solve_targets(&self, steps: &[RawStep]) -> Vec<Atom> {
        let mut out = Vec::new();
        for s in steps {
            if let Ok(ast) = parse(s.value.get_ref()) {
                self.targets_in(&ast, &mut out);
            }
        }
        out
    }

    fn targets_in(&self, ast: &Ast, out: &mut Vec<Atom>) {
        let push = |target: &Ast, out: &mut Vec<Atom>| {
            let target = match &target.kind {
                AstKind::Pow(base, _) => base,
                _ => target,
            };
            if let AstKind::Name { name, primes } = &target.kind
                && let Ok(a) = self.symbols.atom(name, *primes, target.span)
                && !out.contains(&a)
            {
                out.push(a);
            }
        };
        match &ast.kind {
            AstKind::Call { func, args } => {
                if func == "solve"
                    && let Some(t) = args.get(1)
                {
                    match &t.kind {
                        AstKind::Vector { items, .. } => {
                            for i in items {
                                push(i, out);
                            }
                        }
                        _ => push(t, out),
                    }
                }
                for a in args {
                    self.targets_in(a, out);
                }
            }
            AstKind::Assign { value, .. } => self.targets_in(value, out),
            AstKind::Vector { items, .. } | AstKind::Add(items) | AstKind::Mul(items) => {
                for i in items {
                    self.targets_in(i, out);
                }
            }
            AstKind::Recip(a) | AstKind::Neg(a) | AstKind::Pow(a, _) | AstKind::Member(a, ..) => {
                self.targets_in(a, out)
            }
            AstKind::Cross(a, b) => {
                self.targets_in(a, out);
                self.targets_in(b, out);
            }
            AstKind::Num(_) | AstKind::Name { .. } => {}
        }
    }
}
