//! sin and cos of a sum of angles — `cos(q1 + q2)`, `sin(2*theta)`,
//! `cos(q - pi/2)` — written out by the addition formulas in sines and
//! cosines of the single angles, the only trigonometric atoms of the
//! algebra: cos(a + b) = cos a cos b − sin a sin b and
//! sin(a + b) = sin a cos b + cos a sin b; a multiple k q is q added k
//! times, a multiple of π/2 enters by its exact sine and cosine. The
//! result is canonical, so an expectation written with `cos(q1 + q2)`
//! equals a derived result in cos q1, sin q2.
use crate::atom::Atom;
use crate::parse::{Ast, AstKind, ParseError, Span};
use crate::poly::Poly;
use crate::rational::Rational;

/// The largest multiple of one angle (`sin(64*q)`): a multiple expands to
/// a polynomial of that degree.
pub const MAX_MULTIPLE: i64 = 64;

/// One angle of a sum: its symbol's name, where it is written, and its
/// integer multiple.
type Multiple = (String, Span, i64);

/// An angle argument read as Σ kᵢ qᵢ + k₀ π/2: each symbol's name, span
/// and integer multiple, and the quarter turns k₀. `None` when `ast` is
/// not of that form.
fn read(ast: &Ast) -> Option<(Vec<Multiple>, i64)> {
    fn walk(a: &Ast, sign: i64, out: &mut Vec<Multiple>, turns: &mut i64) -> bool {
        if let Some(k) = crate::derivation::ops::quarter_turns(a) {
            // Only turns modulo 4 count, which wrapping keeps.
            *turns = turns.wrapping_add(sign.wrapping_mul(k));
            return true;
        }
        match &a.kind {
            AstKind::Name { name, primes: 0 } => {
                out.push((name.clone(), a.span, sign));
                true
            }
            AstKind::Neg(x) => walk(x, -sign, out, turns),
            AstKind::Add(items) => items.iter().all(|x| walk(x, sign, out, turns)),
            AstKind::Mul(items) => {
                let mut k = sign;
                let mut name = None;
                for it in items {
                    match &it.kind {
                        // Saturating: a product past i64 is refused as a
                        // multiple past MAX_MULTIPLE, never an overflow.
                        AstKind::Num(r) if r.is_integer() && r.to_f64().abs() <= 1e6 => {
                            k = k.saturating_mul(r.to_f64() as i64);
                        }
                        AstKind::Name { name: n, primes: 0 } if name.is_none() => {
                            name = Some((n.clone(), it.span));
                        }
                        _ => return false,
                    }
                }
                match name {
                    // An unknown name is blamed on itself, a multiple on
                    // the whole product.
                    Some((n, span)) => {
                        let at = if k.abs() > MAX_MULTIPLE { a.span } else { span };
                        out.push((n, at, k));
                        true
                    }
                    None => false,
                }
            }
            _ => false,
        }
    }
    let (mut out, mut turns) = (Vec::new(), 0);
    walk(ast, 1, &mut out, &mut turns).then_some((out, turns))
}

/// `(cos x, sin x)` of the sum `x = a + b` from both parts'.
fn add(a: &(Poly, Poly), b: &(Poly, Poly)) -> (Poly, Poly) {
    (
        &(&a.0 * &b.0) - &(&a.1 * &b.1),
        &(&a.1 * &b.0) + &(&a.0 * &b.1),
    )
}

/// sin or cos (`func`) of the angle written `arg`, as a polynomial in the
/// sines and cosines of its symbols; `atom` resolves a symbol's name (an
/// error at its span for an unknown one or a rate). `Ok(None)` when `arg`
/// is not a sum of integer multiples of angles and of π/2.
pub fn expand(
    func: &str,
    arg: &Ast,
    atom: &dyn Fn(&str, Span) -> Result<Atom, ParseError>,
) -> Result<Option<Poly>, ParseError> {
    let Some((terms, turns)) = read(arg) else {
        return Ok(None);
    };
    let one = || Poly::constant(Rational::int(1));
    let mut acc = match turns.rem_euclid(4) {
        0 => (one(), Poly::zero()),
        1 => (Poly::zero(), one()),
        2 => (-&one(), Poly::zero()),
        _ => (Poly::zero(), -&one()),
    };
    for (name, span, k) in terms {
        if k.abs() > MAX_MULTIPLE {
            return Err(ParseError {
                span,
                message: format!(
                    "`{func}` of {k} times `{name}`: a multiple of an angle is at most {MAX_MULTIPLE} (it is written out as a polynomial of that degree)"
                ),
            });
        }
        let q = atom(&name, span)?;
        let (Some(c), Some(s)) = (Atom::cos(q), Atom::sin(q)) else {
            return Err(ParseError {
                span,
                message: format!("`{name}` is not an angle: sin and cos take angle symbols"),
            });
        };
        let unit = (Poly::atom(c), Poly::atom(s));
        let step = if k < 0 {
            (unit.0.clone(), -&unit.1)
        } else {
            unit
        };
        for _ in 0..k.abs() {
            acc = add(&acc, &step);
        }
    }
    Ok(Some(if func == "sin" { acc.1 } else { acc.0 }))
}
