//! The evaluator: derivation-file expressions to canonical values.
//!
//! Arithmetic, vectors, components and names are evaluated here; every
//! named function is an operation of the registry in [`super::ops`], one
//! file each.

use toml::Spanned;

use super::context::{Context, R};
use super::ops::{self, Call};
use super::raw::RawStep;
use super::value::Value;
use crate::atom::Atom;
use crate::parse::{Ast, AstKind, Span};
use crate::poly::Poly;
use crate::vector::Vec3;

impl Context<'_> {
    /// Parses and evaluates a spanned string that must be a scalar.
    pub fn scalar_in(&self, s: &Spanned<String>) -> R<Poly> {
        let base = self.content_start(s);
        let ast = self.parse_at(s.get_ref(), base)?;
        self.scalar(&ast, base)
    }

    pub(crate) fn scalar(&self, ast: &Ast, base: usize) -> R<Poly> {
        match self.eval(ast, base)? {
            Value::Scalar(p) => Ok(p),
            v => Err(self.at(
                base,
                ast.span,
                format!("expected a scalar, found {}", v.describe()),
            )),
        }
    }

    pub(crate) fn vector(&self, ast: &Ast, base: usize) -> R<(Vec3, String)> {
        match self.eval(ast, base)? {
            Value::Vector(v, f) => Ok((v, f)),
            v => Err(self.at(
                base,
                ast.span,
                format!("expected a vector, found {}", v.describe()),
            )),
        }
    }

    pub(crate) fn three_scalars(&self, items: &[Ast], span: Span, base: usize) -> R<Vec3> {
        if items.len() != 3 {
            return Err(self.at(
                base,
                span,
                format!("a vector has three components, found {}", items.len()),
            ));
        }
        Ok(Vec3([
            self.scalar(&items[0], base)?,
            self.scalar(&items[1], base)?,
            self.scalar(&items[2], base)?,
        ]))
    }

    pub fn eval_step(&self, s: &RawStep) -> R<Value> {
        let base = self.content_start(&s.value);
        let ast = self.parse_at(s.value.get_ref(), base)?;
        self.eval(&ast, base)
    }

    pub(crate) fn eval(&self, ast: &Ast, base: usize) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        match &ast.kind {
            AstKind::Num(r) => Ok(Value::Scalar(Poly::constant(r.clone()))),
            AstKind::Name { name, primes } => self.name(name, *primes, ast.span, base),
            AstKind::Vector { items, frame } => self.vector_literal(items, frame, ast.span, base),
            AstKind::Add(items) => self.sum(items, base),
            AstKind::Neg(x) => Ok(self.eval(x, base)?.map(&mut |p| -p)),
            AstKind::Mul(items) => self.product(items, base),
            AstKind::Recip(_) => unreachable!("divisors occur only inside products"),
            AstKind::Pow(b, n) => {
                let p = self.scalar(b, base)?;
                Ok(Value::Scalar(p.pow(*n)))
            }
            AstKind::Cross(a, b) => self.cross(a, b, base, ast.span),
            AstKind::Member(v, comp, sp) => self.member(v, comp, *sp, base),
            AstKind::Assign { name_span, .. } => err(
                *name_span,
                "`name = value` is only allowed inside subst(…)".into(),
            ),
            AstKind::Call { func, args } => self.call(func, args, base, ast.span),
        }
    }
    /// A name: an earlier step, a symbol (with primes); anything else is
    /// an error that says what the name is.
    fn name(&self, name: &str, primes: u32, span: Span, base: usize) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        if primes == 0
            && let Some(v) = self.values.get(name)
        {
            return Ok(v.clone());
        }
        if self.symbols.get(name).is_some() {
            let a = self
                .symbols
                .atom(name, primes, span)
                .map_err(|e| self.at(base, e.span, e.message))?;
            return Ok(Value::Scalar(Poly::atom(a)));
        }
        if self.frame_index(name).is_some() {
            return err(
                span,
                format!("`{name}` is a frame; write angvel({name}) for its angular velocity"),
            );
        }
        if self.values.contains_key(name) {
            return err(
                span,
                format!("`{name}` is a step, not a time-dependent symbol: write dt({name})"),
            );
        }
        if name == "pi" {
            return err(
                span,
                "`pi` is not a number in an expression: it is exact only as an angle \
                 substituted into sin and cos, `subst(x, theta = pi/2)` with a multiple \
                 of pi/2; for another angle declare a constant (e.g. `beta`) and \
                 substitute `theta = beta`"
                    .to_owned(),
            );
        }
        err(
            span,
            format!("unknown name `{name}`: not a declared symbol, an earlier step or a frame"),
        )
    }

    /// A vector literal `[a, b, c]` or `[a, b, c] in F`.
    fn vector_literal(
        &self,
        items: &[Ast],
        frame: &Option<(String, Span)>,
        span: Span,
        base: usize,
    ) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        let f = match frame {
            Some((f, sp)) => match self.frame_index(f) {
                Some(_) => f.clone(),
                None => return err(*sp, format!("unknown frame `{f}`")),
            },
            None => match self.default_frame() {
                Some(f) => f.to_owned(),
                None => {
                    return err(
                        span,
                        "several frames are declared: say which with `[…] in F`".into(),
                    );
                }
            },
        };
        Ok(Value::Vector(self.three_scalars(items, span, base)?, f))
    }

    /// A sum: scalars, vectors in one frame, matrices, lists and arrays
    /// of one length.
    fn sum(&self, items: &[Ast], base: usize) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        let mut acc = self.eval(&items[0], base)?;
        // Scalar terms are gathered and summed in one pass when the run of
        // them ends: adding them one by one would merge the growing sum
        // into a new one at every term, quadratic in a sum of many
        // distinct terms (50,000 constants).
        let mut scalars: Vec<Poly> = Vec::new();
        let flush = |acc: Value, scalars: &mut Vec<Poly>| match acc {
            Value::Scalar(a) if !scalars.is_empty() => {
                Value::Scalar(std::iter::once(a).chain(scalars.drain(..)).sum())
            }
            acc => acc,
        };
        for it in &items[1..] {
            let v = match (&acc, self.eval(it, base)?) {
                (Value::Scalar(_), Value::Scalar(b)) => {
                    scalars.push(b);
                    continue;
                }
                (_, v) => v,
            };
            acc = match (flush(acc, &mut scalars), v) {
                (Value::Scalar(a), Value::Scalar(b)) => Value::Scalar(&a + &b),
                (Value::Vector(a, fa), Value::Vector(b, fb)) => {
                    self.same_frame(base, it.span, &fa, &fb)?;
                    Value::Vector(a.add(&b), fa)
                }
                (Value::Matrix(a), Value::Matrix(b)) => Value::Matrix(a.add(&b)),
                (
                    Value::List {
                        items: a,
                        labels: la,
                    },
                    Value::List {
                        items: b,
                        labels: lb,
                    },
                ) if a.len() == b.len() => Value::List {
                    items: a.iter().zip(&b).map(|(x, y)| x + y).collect(),
                    labels: if la == lb { la } else { Vec::new() },
                },
                (Value::Array(a), Value::Array(b))
                    if a.len() == b.len() && a.iter().zip(&b).all(|(x, y)| x.len() == y.len()) =>
                {
                    Value::Array(
                        a.iter()
                            .zip(&b)
                            .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p + q).collect())
                            .collect(),
                    )
                }
                (a, b) => {
                    return err(
                        it.span,
                        format!("cannot add {} to {}", b.describe(), a.describe()),
                    );
                }
            };
        }
        Ok(flush(acc, &mut scalars))
    }

    /// A product (a divisor is a factor `Recip`).
    fn product(&self, items: &[Ast], base: usize) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        // Every factor first (a divisor as its inverse), so that the
        // term budget of the whole product is checked before any of
        // it is expanded.
        let mut factors = Vec::with_capacity(items.len());
        for it in items {
            if let AstKind::Recip(d) = &it.kind {
                let p = self.scalar(d, base)?;
                // A sum of constants known not to be zero divides too.
                let inv = match p.inverse_divisor() {
                    Some(inv) => Some(inv),
                    None => match super::ops::sum_inverse(&p, &self.positive) {
                        Some(Ok(inv)) => Some(inv),
                        Some(Err(why)) => {
                            return err(
                                d.span,
                                format!(
                                    "cannot divide by {}: {why}",
                                    crate::expr::Expr::from_poly(&p)
                                ),
                            );
                        }
                        None => None,
                    },
                };
                let Some(inv) = inv else {
                    let what = if p.is_zero() {
                        "division by zero".to_owned()
                    } else {
                        format!("cannot divide by {}", crate::expr::Expr::from_poly(&p))
                    };
                    return err(d.span, format!("{what}: {}", crate::poly::DIVISOR_RULE));
                };
                factors.push((it, Value::Scalar(inv), true));
            } else {
                factors.push((it, self.eval(it, base)?, false));
            }
        }
        let scalars: Vec<&Poly> = factors
            .iter()
            .filter_map(|(_, v, _)| match v {
                Value::Scalar(p) => Some(p),
                _ => None,
            })
            .collect();
        if scalars.len() > 1 {
            let n = Poly::product_terms_at_least(&scalars);
            crate::limits::allow_terms(usize::try_from(n).unwrap_or(usize::MAX));
        }
        let mut factors = factors.into_iter();
        let (_, mut acc, _) = factors.next().expect("a product has factors");
        for (it, v, divisor) in factors {
            if divisor {
                let Value::Scalar(inv) = v else {
                    unreachable!("a divisor is a scalar")
                };
                acc = acc.map(&mut |x| x * &inv);
                continue;
            }
            acc = match (acc, v) {
                (Value::Scalar(a), Value::Scalar(b)) => Value::Scalar(&a * &b),
                (Value::Scalar(s), v) | (v, Value::Scalar(s)) => v.map(&mut |x| &s * x),
                (Value::Matrix(m), Value::Vector(v, f)) => Value::Vector(m.mul_vec(&v), f),
                (Value::Matrix(a), Value::Matrix(b)) => Value::Matrix(a.mul(&b)),
                (Value::Array(a), Value::List { items, .. })
                    if a.iter().all(|r| r.len() == items.len()) =>
                {
                    Value::list(
                        a.iter()
                            .map(|r| r.iter().zip(&items).map(|(p, q)| p * q).sum())
                            .collect(),
                    )
                }
                (Value::Vector(..), Value::Vector(..)) => {
                    return err(
                        it.span,
                        "the product of two vectors is ambiguous: use dot(a, b) or cross(a, b)"
                            .into(),
                    );
                }
                (a, b) => {
                    return err(
                        it.span,
                        format!("cannot multiply {} by {}", a.describe(), b.describe()),
                    );
                }
            };
        }
        Ok(acc)
    }

    /// A component: `v.x` of a vector (by its frame's axes), `m.xy` of a
    /// matrix, `l.1` of a list.
    fn member(&self, v: &Ast, comp: &str, sp: Span, base: usize) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        match self.eval(v, base)? {
            Value::Vector(v, f) => {
                let fr = &self.frames[self.frame_index(&f).expect("frame")];
                match fr.axes.iter().position(|a| a == comp) {
                    Some(k) => Ok(Value::Scalar(v.0[k].clone())),
                    None => err(
                        sp,
                        format!("frame {f} has axes {}, not `{comp}`", fr.axes.join(", ")),
                    ),
                }
            }
            Value::Matrix(m) => {
                let rows: Vec<Vec<Poly>> = m.0.iter().map(|r| r.to_vec()).collect();
                match entry(&rows, comp) {
                    Some(p) => Ok(Value::Scalar(p)),
                    None => err(
                        sp,
                        format!(
                            "a matrix element is named by two axes such as `xy`, or by its row and column from 1 \
                             such as `12`, not `{comp}`"
                        ),
                    ),
                }
            }
            Value::Array(rows) => match entry(&rows, comp) {
                Some(p) => Ok(Value::Scalar(p)),
                None => {
                    let (n, m) = (rows.len(), rows.first().map_or(0, Vec::len));
                    let axes = if (n, m) == (3, 3) {
                        ", or by two axes such as `xy`"
                    } else {
                        ""
                    };
                    err(
                        sp,
                        format!(
                            "an element of a {n}×{m} array is named by its row (1 to {n}) and column (1 to {m}), \
                             such as `12`{axes}, not `{comp}`"
                        ),
                    )
                }
            },
            Value::List { items, labels } => {
                let k = comp
                    .parse::<usize>()
                    .ok()
                    .filter(|k| (1..=items.len()).contains(k));
                match k {
                    Some(k) => Ok(Value::Scalar(items[k - 1].clone())),
                    None => {
                        let named = if labels.is_empty() {
                            String::new()
                        } else {
                            format!(
                                " (the values of {})",
                                labels
                                    .iter()
                                    .map(|a| a.to_string())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            )
                        };
                        err(
                            sp,
                            format!(
                                "a list's items are numbered 1 to {}{named}, not `{comp}`",
                                items.len()
                            ),
                        )
                    }
                }
            }
            s => err(sp, format!("{} has no components", s.describe())),
        }
    }

    pub(crate) fn cross(&self, a: &Ast, b: &Ast, base: usize, span: Span) -> R<Value> {
        let (x, fx) = self.vector(a, base)?;
        let (y, fy) = self.vector(b, base)?;
        self.same_frame(base, span, &fx, &fy)?;
        Ok(Value::Vector(x.cross(&y), fx))
    }

    fn call(&self, func: &str, args: &[Ast], base: usize, span: Span) -> R<Value> {
        let Some(op) = ops::find(func) else {
            return Err(self.at(
                base,
                span,
                format!(
                    "unknown function `{func}`; known functions: {}",
                    ops::names()
                ),
            ));
        };
        (op.eval)(&Call {
            cx: self,
            func,
            args,
            base,
            span,
        })
    }

    /// A symbol (with primes) as an argument.
    pub(crate) fn symbol_arg(&self, a: &Ast, base: usize) -> R<Atom> {
        match &a.kind {
            AstKind::Name { name, primes } => self
                .symbols
                .atom(name, *primes, a.span)
                .map_err(|e| self.at(base, e.span, e.message)),
            _ => Err(self.at(base, a.span, "expected a symbol such as omega_x or theta''")),
        }
    }
}

/// The element `comp` of a matrix or an array by rows: `ij`, its row and
/// column counted from 1 (`12`), or two axes of a 3×3 one (`xy`).
fn entry(rows: &[Vec<Poly>], comp: &str) -> Option<Poly> {
    let (n, m) = (rows.len(), rows.first().map_or(0, Vec::len));
    let [a, b]: [char; 2] = comp.chars().collect::<Vec<_>>().try_into().ok()?;
    let (i, j) = match (a.to_digit(10), b.to_digit(10)) {
        (Some(i), Some(j)) if i >= 1 && j >= 1 => (i as usize - 1, j as usize - 1),
        (None, None) if (n, m) == (3, 3) => {
            let axis = |c: char| "xyz".find(c);
            (axis(a)?, axis(b)?)
        }
        _ => return None,
    };
    rows.get(i)?.get(j).cloned()
}
