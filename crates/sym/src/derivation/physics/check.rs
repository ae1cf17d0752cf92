//! The small checks every reader of the physical model shares: a spanned
//! string parsed at its place in the file, the message for an unknown
//! name, an expression of constants, and arguments written in the file's
//! symbols rather than in its steps.

use toml::Spanned;

use crate::derivation::context::{Context, R};
use crate::parse::{Ast, AstKind};
use crate::vector::Vec3;

/// Parses a spanned string; the AST and the byte offset of its contents.
pub(super) fn parse_spanned(cx: &Context<'_>, s: &Spanned<String>) -> R<(Ast, usize)> {
    let base = cx.content_start(s);
    Ok((cx.parse_at(s.get_ref(), base)?, base))
}

/// The message for a name that is not declared, listing those that are.
pub(super) fn unknown(what: &str, name: &str, known: &[String]) -> String {
    if known.is_empty() {
        format!("unknown {what} `{name}`: none is declared")
    } else {
        format!("unknown {what} `{name}` (declared: {})", known.join(", "))
    }
}

/// Checks `v` uses constants only.
pub(super) fn constant(cx: &Context<'_>, v: &Vec3, at: &Spanned<String>, key: &str) -> R<()> {
    if v.0
        .iter()
        .any(|p| p.atoms().iter().any(|a| a.is_time_dependent()))
    {
        let n = at.get_ref().len();
        return Err(cx.diag_string(
            at,
            0,
            n,
            format!("`{key}` must be an expression of constants"),
        ));
    }
    Ok(())
}

/// Refuses a step's name inside a meaning's arguments or a condition:
/// they are written in the file's symbols (a step would bring its derived
/// value into what it is compared with).
pub(super) fn no_step_names(cx: &Context<'_>, ast: &Ast, base: usize) -> R<()> {
    let mut err = None;
    walk(ast, &mut |a| {
        if let AstKind::Name { name, .. } = &a.kind
            && err.is_none()
            && cx.is_step(name)
        {
            err = Some(cx.at(
                base,
                a.span,
                format!(
                    "`{name}` is a step: a meaning's arguments and a step's conditions are written in the file's symbols (write what the step stands for, e.g. the impulse's components), so that the derived result is not compared with itself"
                ),
            ));
        }
    });
    err.map_or(Ok(()), Err)
}

/// Calls `f` on `a` and every node below it.
fn walk(a: &Ast, f: &mut dyn FnMut(&Ast)) {
    f(a);
    match &a.kind {
        AstKind::Num(_) | AstKind::Name { .. } => {}
        AstKind::Call { args, .. } => args.iter().for_each(|x| walk(x, f)),
        AstKind::Assign { value, .. } => walk(value, f),
        AstKind::Vector { items, .. } | AstKind::Add(items) | AstKind::Mul(items) => {
            items.iter().for_each(|x| walk(x, f))
        }
        AstKind::Recip(x) | AstKind::Neg(x) | AstKind::Pow(x, _) | AstKind::Member(x, ..) => {
            walk(x, f)
        }
        AstKind::Cross(x, y) => {
            walk(x, f);
            walk(y, f)
        }
    }
}
