//! The evaluator: derivation-file expressions to canonical values.
//!
//! Arithmetic, vectors, frames and names are evaluated here; every named
//! function is an operation of the registry in [`super::ops`], one file
//! each.

use std::collections::HashMap;

use toml::Spanned;

use super::ops::{self, Call};
use super::raw::{RawFrame, RawStep, string_contents};
pub use super::value::Value;
use super::{Abbreviation, Check, Diagnostic, unfold};
use crate::atom::Atom;
use crate::frame::Frame;
use crate::parse::{Ast, AstKind, Span, parse};
use crate::poly::Poly;
use crate::present::{Presentation, present};
use crate::symbols::{Decl, Symbols};
use crate::vector::{Mat3, Vec3};

pub(crate) struct Context<'a> {
    path: &'a str,
    text: &'a str,
    pub symbols: Symbols,
    pub frames: Vec<Frame>,
    values: HashMap<String, Value>,
    /// Symbols declared small (first order), for `linearize`.
    pub small: Vec<Atom>,
    /// The file's order of constant factors (`[symbols] order`).
    pub constant_order: Vec<String>,
    /// Constants declared positive, for `sign`.
    pub positive: Vec<Atom>,
    /// Abbreviations declared so far, in order.
    pub abbrevs: Vec<Abbreviation>,
}

pub(crate) type R<T> = Result<T, Diagnostic>;

impl<'a> Context<'a> {
    pub fn new(path: &'a str, text: &'a str) -> Context<'a> {
        let mut n = Frame::inertial("N");
        n.doc = "inertial (Newtonian) frame".into();
        Context {
            path,
            text,
            symbols: Symbols::new(),
            frames: vec![n],
            values: HashMap::new(),
            small: Vec::new(),
            constant_order: Vec::new(),
            positive: Vec::new(),
            abbrevs: Vec::new(),
        }
    }

    /// `p` with every abbreviation (and its derivatives) replaced by its
    /// definition.
    pub fn unfold(&self, p: &Poly) -> Poly {
        unfold(&self.abbrevs, p)
    }

    /// The frame called `name` (it exists: values only name known frames).
    pub fn frame(&self, name: &str) -> &Frame {
        &self.frames[self.frame_index(name).expect("frame exists")]
    }

    /// A diagnostic at bytes `start..end`: offsets into the file, or into
    /// a string's value counted from its content start (mapped past the
    /// string's escapes, [`super::raw::file_offset`]).
    pub(crate) fn diag(&self, start: usize, end: usize, msg: impl Into<String>) -> Diagnostic {
        let at = |i| super::raw::file_offset(self.text, i);
        Diagnostic::at(self.path, self.text, at(start), at(end), msg)
    }

    /// The byte offset where the contents of a spanned TOML string begin.
    pub(crate) fn content_start(&self, s: &Spanned<String>) -> usize {
        let start = s.span().start;
        let rest = &self.text[start.min(self.text.len())..];
        if rest.starts_with("\"\"\"") || rest.starts_with("'''") {
            start + 3 + usize::from(rest[3..].starts_with('\n'))
        } else if rest.starts_with('"') || rest.starts_with('\'') {
            start + 1
        } else {
            start
        }
    }

    /// A diagnostic at bytes `from..to` of the contents of a spanned string.
    pub fn diag_string(
        &self,
        s: &Spanned<String>,
        from: usize,
        to: usize,
        msg: impl Into<String>,
    ) -> Diagnostic {
        let base = self.content_start(s);
        self.diag(base + from, base + to, msg)
    }

    pub(crate) fn at(&self, base: usize, span: Span, msg: impl Into<String>) -> Diagnostic {
        self.diag(base + span.start, base + span.end, msg)
    }

    pub(crate) fn parse_at(&self, text: &str, base: usize) -> R<Ast> {
        parse(text).map_err(|e| self.at(base, e.span, e.message))
    }

    pub fn declare(&mut self, s: &Spanned<String>, decl: Decl) -> R<()> {
        let name = s.get_ref();
        let valid = name.chars().next().is_some_and(|c| c.is_alphabetic())
            && name.chars().all(|c| c.is_alphanumeric() || c == '_');
        if !valid {
            return Err(self.diag_string(
                s,
                0,
                name.len(),
                format!("`{name}` is not a valid symbol name (letters, digits, _)"),
            ));
        }
        if matches!(name.as_str(), "sin" | "cos" | "in" | "pi" | "t") {
            return Err(self.diag_string(
                s,
                0,
                name.len(),
                format!("`{name}` is reserved and cannot be a symbol"),
            ));
        }
        if !self.symbols.declare(name, decl) {
            return Err(self.diag_string(s, 0, name.len(), format!("`{name}` is declared twice")));
        }
        Ok(())
    }

    /// Records a constant symbol, or sin/cos of a constant angle, as positive.
    /// A name of `[symbols] order`: a declared constant, listed once.
    pub fn declare_order(&mut self, s: &Spanned<String>) -> R<()> {
        let name = s.get_ref();
        let (from, to) = (0, name.len());
        if !matches!(self.symbols.get(name), Some(Decl::Constant)) {
            return Err(self.diag_string(
                s,
                from,
                to,
                format!("`{name}` in [symbols] order is not a declared constant"),
            ));
        }
        if self.constant_order.contains(name) {
            return Err(self.diag_string(
                s,
                from,
                to,
                format!("`{name}` is listed twice in order"),
            ));
        }
        self.constant_order.push(name.clone());
        Ok(())
    }

    pub fn declare_positive(&mut self, s: &Spanned<String>) -> R<()> {
        let base = self.content_start(s);
        let ast = self.parse_at(s.get_ref(), base)?;
        let atom = match &ast.kind {
            AstKind::Name { name, primes: 0 } => self.symbols.atom(name, 0, ast.span),
            AstKind::Call { func, args } if func == "sin" || func == "cos" => {
                self.symbols.trig(func, args, ast.span)
            }
            _ => {
                return Err(self.at(
                    base,
                    ast.span,
                    "list constant symbols or sin/cos of a constant angle",
                ));
            }
        }
        .map_err(|e| self.at(base, e.span, e.message))?;
        if atom.is_time_dependent() {
            return Err(self.at(
                base,
                ast.span,
                "only constants (or sin/cos of a constant angle) can be declared positive",
            ));
        }
        self.positive.push(atom);
        Ok(())
    }

    /// Whether `name` is a step evaluated so far.
    pub(crate) fn is_step(&self, name: &str) -> bool {
        self.values.contains_key(name)
    }

    pub fn bind(&mut self, name: &str, v: Value) {
        self.values.insert(name.to_owned(), v);
    }

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

    pub(crate) fn frame_index(&self, name: &str) -> Option<usize> {
        self.frames.iter().position(|f| f.name == name)
    }

    pub(crate) fn frame_arg(&self, ast: &Ast, base: usize) -> R<usize> {
        if let AstKind::Name { name, primes: 0 } = &ast.kind
            && let Some(i) = self.frame_index(name)
        {
            return Ok(i);
        }
        let known: Vec<&str> = self.frames.iter().map(|f| f.name.as_str()).collect();
        Err(self.at(
            base,
            ast.span,
            format!("expected a frame name (one of {})", known.join(", ")),
        ))
    }

    /// Adds a frame built by [`Context::frame_of`].
    pub fn push_frame(&mut self, frame: Frame) {
        self.frames.push(frame);
    }

    /// Builds the frame a `[[frame]]` table declares (not yet added).
    pub fn frame_of(&self, f: &RawFrame) -> R<Frame> {
        let name = f.name.get_ref();
        if self.frame_index(name).is_some() || self.symbols.get(name).is_some() {
            return Err(self.diag_string(
                &f.name,
                0,
                name.len(),
                format!("`{name}` is already a frame or a symbol"),
            ));
        }
        let mut frame = Frame::inertial(name);
        frame.doc = f.doc.clone();
        if let Some(axes) = &f.axes {
            let a = axes.get_ref();
            if a.len() != 3 || a.iter().any(|s| s.is_empty()) {
                let sp = axes.span();
                return Err(self.diag(
                    sp.start,
                    sp.end,
                    "`axes` must name three axes, such as [\"1\", \"2\", \"3\"]",
                ));
            }
            if let Some(k) = (1..3).find(|&k| a[..k].contains(&a[k])) {
                let sp = axes.span();
                return Err(self.diag(
                    sp.start,
                    sp.end,
                    format!(
                        "`axes` names the axis `{}` twice: the three axes of a frame must differ",
                        a[k]
                    ),
                ));
            }
            frame.axes = [a[0].clone(), a[1].clone(), a[2].clone()];
        }
        match (&f.angular_velocity, &f.parent, &f.rotation) {
            (Some(w), None, None) => {
                let base = self.content_start(w);
                let ast = self.parse_at(w.get_ref(), base)?;
                let AstKind::Vector { items, frame: fr } = &ast.kind else {
                    return Err(self.at(
                        base,
                        ast.span,
                        "the angular velocity must be a vector literal such as [omega_x, omega_y, omega_z]",
                    ));
                };
                if let Some((other, sp)) = fr
                    && other != name
                {
                    return Err(self.at(
                        base,
                        *sp,
                        format!("a frame's angular velocity is given in its own components (`in {name}`)"),
                    ));
                }
                frame.omega = self.three_scalars(items, ast.span, base)?;
            }
            (None, Some(parent), Some(rot)) => {
                let Some(pi) = self.frame_index(parent.get_ref()) else {
                    let p = parent.get_ref();
                    return Err(self.diag_string(
                        parent,
                        0,
                        p.len(),
                        format!("unknown parent frame `{p}` (declare it first)"),
                    ));
                };
                let base = self.content_start(rot);
                let parent_frame = &self.frames[pi];
                let bad = || {
                    format!(
                        "a rotation is written axis(angle), such as {}(phi)",
                        parent_frame.axes[2]
                    )
                };
                // Axes named by numbers (`3(beta)`) are not names the
                // expression parser reads as a function: split them off.
                let text = rot.get_ref();
                let lead = text.len() - text.trim_start().len();
                let numbered = parent_frame.axes.iter().position(|a| {
                    a.starts_with(|c: char| c.is_ascii_digit())
                        && text[lead..].starts_with(&format!("{a}("))
                });
                let (k, arg, base) = if let Some(k) = numbered {
                    let off = lead + parent_frame.axes[k].len();
                    let arg = self.parse_at(&text[off..], base + off)?;
                    (k, arg, base + off)
                } else {
                    let ast = self.parse_at(text, base)?;
                    let AstKind::Call { func, args } = &ast.kind else {
                        return Err(self.at(base, ast.span, bad()));
                    };
                    let Some(k) = parent_frame.axes.iter().position(|a| a == func) else {
                        return Err(self.at(
                            base,
                            ast.span,
                            format!(
                                "`{func}` is not an axis of frame {}; {}",
                                parent_frame.name,
                                bad()
                            ),
                        ));
                    };
                    let [arg] = args.as_slice() else {
                        return Err(self.at(base, ast.span, bad()));
                    };
                    (k, arg.clone(), base)
                };
                let AstKind::Name { name: q, primes: 0 } = &arg.kind else {
                    return Err(self.at(
                        base,
                        arg.span,
                        "the rotation angle must be a declared symbol",
                    ));
                };
                let q = self
                    .symbols
                    .atom(q, 0, arg.span)
                    .map_err(|e| self.at(base, e.span, e.message))?;
                let r = Mat3::rotation(k, q);
                // Ω_child = Rᵀ Ω_parent + q̇ e_k (e_k is shared by parent and child).
                let mut omega = r.transpose().mul_vec(&parent_frame.omega);
                if let Some(qd) = q.derivative() {
                    omega.0[k] = &omega.0[k] + &Poly::atom(qd);
                }
                frame.omega = omega;
                frame.parent = Some((parent_frame.name.clone(), r));
            }
            _ => {
                let n = f.name.get_ref().len();
                return Err(self.diag_string(
                    &f.name,
                    0,
                    n,
                    "a frame needs either `angular_velocity` or both `parent` and `rotation`",
                ));
            }
        }
        Ok(frame)
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

    /// The matrix taking components in frame `i` to its root frame, and the root.
    pub(crate) fn to_root(&self, mut i: usize) -> (usize, Mat3) {
        let mut r = Mat3::identity();
        while let Some((p, m)) = &self.frames[i].parent {
            r = m.mul(&r);
            i = self.frame_index(p).expect("parent exists");
        }
        (i, r)
    }

    /// When one frame is an ancestor of the other, turns `v` one rotation
    /// at a time (vector products only, no matrix products).
    pub(crate) fn along_chain(&self, mut v: Vec3, from: usize, to: usize) -> Option<Vec3> {
        let rot = |i: usize| &self.frames[i].parent.as_ref().expect("not a root").1;
        let ancestors = |mut i: usize| {
            let mut v = vec![i];
            while let Some((p, _)) = &self.frames[i].parent {
                i = self.frame_index(p).expect("parent exists");
                v.push(i);
            }
            v
        };
        let up = ancestors(from);
        if let Some(pos) = up.iter().position(|&i| i == to) {
            for &i in &up[..pos] {
                v = rot(i).mul_vec(&v);
            }
            return Some(v);
        }
        let down = ancestors(to);
        let pos = down.iter().position(|&i| i == from)?;
        for &i in down[..pos].iter().rev() {
            v = rot(i).transpose().mul_vec(&v);
        }
        Some(v)
    }

    pub fn eval_step(&self, s: &RawStep) -> R<Value> {
        let base = self.content_start(&s.value);
        let ast = self.parse_at(s.value.get_ref(), base)?;
        self.eval(&ast, base)
    }

    pub fn axes_of(&self, v: &Value) -> [String; 3] {
        match v {
            Value::Vector(_, f) => self.frames[self.frame_index(f).expect("frame exists")]
                .axes
                .clone(),
            _ => ["x".into(), "y".into(), "z".into()],
        }
    }

    fn default_frame(&self) -> Option<&str> {
        match self.frames.len() {
            1 => Some("N"),
            2 => Some(&self.frames[1].name),
            _ => None,
        }
    }

    pub(crate) fn same_frame(&self, base: usize, span: Span, a: &str, b: &str) -> R<()> {
        if a == b {
            Ok(())
        } else {
            Err(self.at(
                base,
                span,
                format!(
                    "vectors in different frames ({a} and {b}); convert one with express(v, {a})"
                ),
            ))
        }
    }

    pub(crate) fn eval(&self, ast: &Ast, base: usize) -> R<Value> {
        let err = |span: Span, m: String| -> R<Value> { Err(self.at(base, span, m)) };
        match &ast.kind {
            AstKind::Num(r) => Ok(Value::Scalar(Poly::constant(r.clone()))),
            AstKind::Name { name, primes } => {
                if *primes == 0
                    && let Some(v) = self.values.get(name)
                {
                    return Ok(v.clone());
                }
                if self.symbols.get(name).is_some() {
                    let a = self
                        .symbols
                        .atom(name, *primes, ast.span)
                        .map_err(|e| self.at(base, e.span, e.message))?;
                    return Ok(Value::Scalar(Poly::atom(a)));
                }
                if self.frame_index(name).is_some() {
                    return err(
                        ast.span,
                        format!(
                            "`{name}` is a frame; write angvel({name}) for its angular velocity"
                        ),
                    );
                }
                if self.values.contains_key(name) {
                    return err(
                        ast.span,
                        format!(
                            "`{name}` is a step, not a time-dependent symbol: write dt({name})"
                        ),
                    );
                }
                if name == "pi" {
                    return err(
                        ast.span,
                        "`pi` is not a number in an expression: it is exact only as an angle \
                         substituted into sin and cos, `subst(x, theta = pi/2)` with a multiple \
                         of pi/2; for another angle declare a constant (e.g. `beta`) and \
                         substitute `theta = beta`"
                            .to_owned(),
                    );
                }
                err(
                    ast.span,
                    format!(
                        "unknown name `{name}`: not a declared symbol, an earlier step or a frame"
                    ),
                )
            }
            AstKind::Vector { items, frame } => {
                let f = match frame {
                    Some((f, sp)) => match self.frame_index(f) {
                        Some(_) => f.clone(),
                        None => return err(*sp, format!("unknown frame `{f}`")),
                    },
                    None => match self.default_frame() {
                        Some(f) => f.to_owned(),
                        None => {
                            return err(
                                ast.span,
                                "several frames are declared: say which with `[…] in F`".into(),
                            );
                        }
                    },
                };
                Ok(Value::Vector(self.three_scalars(items, ast.span, base)?, f))
            }
            AstKind::Add(items) => {
                let mut acc = self.eval(&items[0], base)?;
                for it in &items[1..] {
                    let v = self.eval(it, base)?;
                    acc = match (acc, v) {
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
                            if a.len() == b.len()
                                && a.iter().zip(&b).all(|(x, y)| x.len() == y.len()) =>
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
                Ok(acc)
            }
            AstKind::Neg(x) => Ok(self.eval(x, base)?.map(&mut |p| -p)),
            AstKind::Mul(items) => {
                // Every factor first (a divisor as its inverse), so that the
                // term budget of the whole product is checked before any of
                // it is expanded.
                let mut factors = Vec::with_capacity(items.len());
                for it in items {
                    if let AstKind::Recip(d) = &it.kind {
                        let p = self.scalar(d, base)?;
                        let Some(inv) = p.inverse_divisor() else {
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
                                "the product of two vectors is ambiguous: use dot(a, b) or cross(a, b)".into(),
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
            AstKind::Recip(_) => unreachable!("divisors occur only inside products"),
            AstKind::Pow(b, n) => {
                let p = self.scalar(b, base)?;
                Ok(Value::Scalar(p.pow(*n)))
            }
            AstKind::Cross(a, b) => self.cross(a, b, base, ast.span),
            AstKind::Member(v, comp, sp) => match self.eval(v, base)? {
                Value::Vector(v, f) => {
                    let fr = &self.frames[self.frame_index(&f).expect("frame")];
                    match fr.axes.iter().position(|a| a == comp) {
                        Some(k) => Ok(Value::Scalar(v.0[k].clone())),
                        None => err(
                            *sp,
                            format!("frame {f} has axes {}, not `{comp}`", fr.axes.join(", ")),
                        ),
                    }
                }
                Value::Matrix(m) => {
                    let ax = ["x", "y", "z"];
                    let pos = |c: &str| ax.iter().position(|a| *a == c);
                    let (i, j) = (comp.get(0..1).and_then(pos), comp.get(1..2).and_then(pos));
                    match (i, j, comp.len()) {
                        (Some(i), Some(j), 2) => Ok(Value::Scalar(m.0[i][j].clone())),
                        _ => err(
                            *sp,
                            format!(
                                "a matrix element is named by two axes such as `xy`, not `{comp}`"
                            ),
                        ),
                    }
                }
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
                                *sp,
                                format!(
                                    "a list's items are numbered 1 to {}{named}, not `{comp}`",
                                    items.len()
                                ),
                            )
                        }
                    }
                }
                s => err(*sp, format!("{} has no components", s.describe())),
            },
            AstKind::Assign { name_span, .. } => err(
                *name_span,
                "`name = value` is only allowed inside subst(…)".into(),
            ),
            AstKind::Call { func, args } => self.call(func, args, base, ast.span),
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
                let ast = self.parse_at(item, base)?;
                let atom = match &ast.kind {
                    AstKind::Name { name, primes } => self.symbols.atom(name, *primes, ast.span),
                    AstKind::Call { func, args } if func == "sin" || func == "cos" => {
                        self.symbols.trig(func, args, ast.span)
                    }
                    _ => {
                        return Err(self.at(
                            base,
                            ast.span,
                            "collect by symbols such as omega_x, omega_x' or sin(theta)",
                        ));
                    }
                }
                .map_err(|e| self.at(base, e.span, e.message))?;
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
                    difference: &unfold(abbrevs, &v.0[k]) - &unfold(abbrevs, &w.0[k]),
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
            let difference = &unfold(abbrevs, &got) - &unfold(abbrevs, &want);
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
