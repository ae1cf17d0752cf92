//! The infix syntax of derivation files: tokenizer and Pratt-style parser.
//!
//! ```text
//! expr    := term (('+' | '-') term)*
//! term    := '-' term | factor (('*' | '/') factor)*
//! factor  := postfix ('^' INT)?
//! postfix := primary ('.' IDENT)*            component: H.x
//! primary := INT ('/' INT)?                  exact rational literal
//!          | IDENT "'"*                      symbol (primes: time derivatives)
//!          | IDENT '(' args ')'              function call
//!          | '[' expr (',' expr)* ']' ('in' IDENT)?   vector in a frame
//!          | '(' expr ')'
//! args    := (IDENT '=' expr | expr) (',' ...)*
//! ```
//!
//! Written by hand rather than with a parser generator because the grammar
//! is a dozen lines and the errors must point at a byte span inside a TOML
//! string, which the derivation loader maps to file:line:column.

use crate::rational::Rational;

/// How deeply an expression may nest: parentheses, brackets, function
/// calls, unary minus signs and `.component` selections each open a level.
/// Parsing and evaluation recurse once per level, so the bound keeps both
/// far from the stack's end; a human-written expression rarely needs ten.
/// Deeper expressions are an error that says to split them into steps.
pub const MAX_DEPTH: usize = 100;

/// The most digits of one integer literal (numerator or denominator). A
/// coefficient is also bounded in bits by
/// [`Limits::max_bits`](crate::limits::Limits), which arithmetic can reach;
/// this bounds what the parser is handed (a million-digit literal is
/// refused before it is converted).
pub const MAX_DIGITS: usize = 1000;

/// A byte range inside the parsed text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Span {
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    fn to(self, other: Span) -> Span {
        Span {
            start: self.start,
            end: other.end,
        }
    }
}

/// A parse error with the span it concerns.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct ParseError {
    /// Where in the text.
    pub span: Span,
    /// What went wrong.
    pub message: String,
}

fn err<T>(span: Span, message: impl Into<String>) -> Result<T, ParseError> {
    Err(ParseError {
        span,
        message: message.into(),
    })
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Int(String),
    Ident(String),
    Prime,
    Sym(char),
    End,
}

fn tokenize(text: &str) -> Result<Vec<(Tok, Span)>, ParseError> {
    let mut out = Vec::new();
    let mut it = text.char_indices().peekable();
    while let Some(&(i, c)) = it.peek() {
        if c.is_whitespace() {
            it.next();
        } else if c.is_ascii_digit() {
            let mut end = i;
            while let Some(&(j, d)) = it.peek() {
                if d.is_ascii_digit() {
                    end = j + 1;
                    it.next();
                } else {
                    break;
                }
            }
            let s = text[i..end].to_owned();
            if s.len() > MAX_DIGITS {
                return err(
                    Span { start: i, end },
                    format!(
                        "a number literal of {} digits: at most {MAX_DIGITS} are allowed",
                        s.len()
                    ),
                );
            }
            if let Some(&(j, '.')) = it.peek() {
                return err(
                    Span {
                        start: i,
                        end: j + 1,
                    },
                    "decimal numbers are not allowed in symbolic expressions; write an exact fraction such as 3/2",
                );
            }
            out.push((Tok::Int(s), Span { start: i, end }));
        } else if c.is_alphabetic() || c == '_' {
            let mut end = i;
            while let Some(&(j, d)) = it.peek() {
                if d.is_alphanumeric() || d == '_' {
                    end = j + d.len_utf8();
                    it.next();
                } else {
                    break;
                }
            }
            out.push((Tok::Ident(text[i..end].to_owned()), Span { start: i, end }));
        } else if c == '\'' {
            it.next();
            out.push((
                Tok::Prime,
                Span {
                    start: i,
                    end: i + 1,
                },
            ));
        } else if "+-*/^()[],.=×·".contains(c) {
            it.next();
            let len = c.len_utf8();
            let c = match c {
                '×' => 'x',
                '·' => '*',
                c => c,
            };
            out.push((
                Tok::Sym(c),
                Span {
                    start: i,
                    end: i + len,
                },
            ));
        } else {
            return err(
                Span {
                    start: i,
                    end: i + c.len_utf8(),
                },
                format!("unexpected character `{c}`"),
            );
        }
    }
    out.push((
        Tok::End,
        Span {
            start: text.len(),
            end: text.len(),
        },
    ));
    Ok(out)
}

/// A node of the syntax tree, with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Ast {
    /// What it is.
    pub kind: AstKind,
    /// Where it is.
    pub span: Span,
}

/// The kinds of syntax-tree nodes.
#[derive(Clone, Debug, PartialEq)]
pub enum AstKind {
    /// A non-negative rational literal.
    Num(Rational),
    /// A name with `primes` time derivatives.
    Name {
        /// The name.
        name: String,
        /// Number of `'` marks.
        primes: u32,
    },
    /// `f(args…)`.
    Call {
        /// Function name.
        func: String,
        /// Arguments.
        args: Vec<Ast>,
    },
    /// `name = value` inside a call's argument list (`name'` for a rate).
    Assign {
        /// The name on the left.
        name: String,
        /// Number of `'` marks after the name.
        primes: u32,
        /// Span of the name.
        name_span: Span,
        /// The value.
        value: Box<Ast>,
    },
    /// `[a, b, c] in F`.
    Vector {
        /// Components.
        items: Vec<Ast>,
        /// The frame named after `in`, with its span.
        frame: Option<(String, Span)>,
    },
    /// `a + b - c` (a subtracted term is a `Neg`).
    Add(Vec<Ast>),
    /// `a * b / c` (a divisor is a `Recip`).
    Mul(Vec<Ast>),
    /// A divisor in a product.
    Recip(Box<Ast>),
    /// Unary minus.
    Neg(Box<Ast>),
    /// `a ^ n`.
    Pow(Box<Ast>, u32),
    /// `a × b`.
    Cross(Box<Ast>, Box<Ast>),
    /// `v.x`: a component.
    Member(Box<Ast>, String, Span),
}

struct Parser {
    toks: Vec<(Tok, Span)>,
    pos: usize,
    /// Levels of nesting open at the current token (see [`MAX_DEPTH`]).
    depth: usize,
}

/// Parses one expression; the whole text must be consumed.
pub fn parse(text: &str) -> Result<Ast, ParseError> {
    let mut p = Parser {
        toks: tokenize(text)?,
        pos: 0,
        depth: 0,
    };
    let e = p.expr()?;
    match p.peek() {
        Tok::End => Ok(e),
        t => err(
            p.span(),
            format!("unexpected {} after the end of the expression", describe(t)),
        ),
    }
}

fn describe(t: &Tok) -> String {
    match t {
        Tok::Int(s) => format!("number `{s}`"),
        Tok::Ident(s) => format!("name `{s}`"),
        Tok::Prime => "`'`".into(),
        Tok::Sym(c) => format!("`{c}`"),
        Tok::End => "end of expression".into(),
    }
}

impl Parser {
    fn peek(&self) -> &Tok {
        &self.toks[self.pos].0
    }
    fn peek_at(&self, k: usize) -> &Tok {
        &self.toks[(self.pos + k).min(self.toks.len() - 1)].0
    }
    fn span(&self) -> Span {
        self.toks[self.pos].1
    }
    fn prev_span(&self) -> Span {
        self.toks[self.pos.saturating_sub(1)].1
    }
    /// The current token, and a step past it unless it is the end. A
    /// token passed is never read again (only its span), so it is moved
    /// out, not cloned.
    fn bump(&mut self) -> (Tok, Span) {
        if self.pos < self.toks.len() - 1 {
            self.pos += 1;
            let (t, span) = &mut self.toks[self.pos - 1];
            (std::mem::replace(t, Tok::Prime), *span)
        } else {
            self.toks[self.pos].clone()
        }
    }
    fn eat(&mut self, c: char) -> bool {
        if *self.peek() == Tok::Sym(c) {
            self.bump();
            true
        } else {
            false
        }
    }
    fn expect(&mut self, c: char, what: &str) -> Result<Span, ParseError> {
        if self.eat(c) {
            Ok(self.prev_span())
        } else {
            err(
                self.span(),
                format!("expected `{c}` {what}, found {}", describe(self.peek())),
            )
        }
    }

    /// Opens one level of nesting, refusing to go deeper than [`MAX_DEPTH`].
    fn enter(&mut self) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return err(
                self.span(),
                format!(
                    "the expression nests deeper than {MAX_DEPTH} levels (parentheses, calls, signs, components); split it into steps"
                ),
            );
        }
        Ok(())
    }

    fn expr(&mut self) -> Result<Ast, ParseError> {
        self.enter()?;
        let e = self.expr_inner();
        self.depth -= 1;
        e
    }

    fn expr_inner(&mut self) -> Result<Ast, ParseError> {
        let first = self.term()?;
        let start = first.span;
        let mut items = vec![first];
        loop {
            if self.eat('+') {
                items.push(self.term_no_unary()?);
            } else if self.eat('-') {
                let s = self.prev_span();
                let t = self.term_no_unary()?;
                let span = s.to(t.span);
                items.push(Ast {
                    kind: AstKind::Neg(Box::new(t)),
                    span,
                });
            } else {
                break;
            }
        }
        Ok(if items.len() == 1 {
            items.pop().expect("one item")
        } else {
            let span = start.to(items.last().expect("items").span);
            Ast {
                kind: AstKind::Add(items),
                span,
            }
        })
    }

    fn term(&mut self) -> Result<Ast, ParseError> {
        if self.eat('-') {
            let s = self.prev_span();
            self.enter()?;
            let t = self.term()?;
            self.depth -= 1;
            let span = s.to(t.span);
            return Ok(Ast {
                kind: AstKind::Neg(Box::new(t)),
                span,
            });
        }
        self.term_no_unary()
    }

    fn term_no_unary(&mut self) -> Result<Ast, ParseError> {
        if *self.peek() == Tok::Sym('-') || *self.peek() == Tok::Sym('+') {
            return err(
                self.span(),
                "two signs in a row; put the second term in parentheses",
            );
        }
        let first = self.cross()?;
        let start = first.span;
        let mut items = vec![first];
        loop {
            if self.eat('*') {
                items.push(self.cross()?);
            } else if self.eat('/') {
                let s = self.prev_span();
                let f = self.factor(false)?;
                let span = s.to(f.span);
                items.push(Ast {
                    kind: AstKind::Recip(Box::new(f)),
                    span,
                });
            } else {
                break;
            }
        }
        Ok(if items.len() == 1 {
            items.pop().expect("one item")
        } else {
            let span = start.to(items.last().expect("items").span);
            Ast {
                kind: AstKind::Mul(items),
                span,
            }
        })
    }

    /// `a × b` (written `×` or ` x ` is not accepted: `x` is a name).
    fn cross(&mut self) -> Result<Ast, ParseError> {
        let a = self.factor(true)?;
        if *self.peek() == Tok::Sym('x') {
            self.bump();
            let b = self.factor(true)?;
            let span = a.span.to(b.span);
            return Ok(Ast {
                kind: AstKind::Cross(Box::new(a), Box::new(b)),
                span,
            });
        }
        Ok(a)
    }

    fn factor(&mut self, allow_rational: bool) -> Result<Ast, ParseError> {
        let base = self.postfix(allow_rational)?;
        if self.eat('^') {
            let (t, s) = self.bump();
            let Tok::Int(n) = t else {
                return err(s, "the exponent must be a non-negative integer literal");
            };
            let Ok(n) = n.parse::<u32>() else {
                return err(s, "exponent too large");
            };
            let span = base.span.to(s);
            return Ok(Ast {
                kind: AstKind::Pow(Box::new(base), n),
                span,
            });
        }
        Ok(base)
    }

    fn postfix(&mut self, allow_rational: bool) -> Result<Ast, ParseError> {
        let mut e = self.primary(allow_rational)?;
        let depth = self.depth;
        while self.eat('.') {
            // Each selection nests the tree one level deeper.
            self.enter()?;
            let (t, s) = self.bump();
            let name = match t {
                Tok::Ident(name) | Tok::Int(name) => name,
                _ => {
                    return err(
                        s,
                        "expected a component name after `.` (such as x, y, z or 1, 2, 3)",
                    );
                }
            };
            let span = e.span.to(s);
            e = Ast {
                kind: AstKind::Member(Box::new(e), name, s),
                span,
            };
        }
        self.depth = depth;
        Ok(e)
    }

    fn primary(&mut self, allow_rational: bool) -> Result<Ast, ParseError> {
        let (t, s) = self.bump();
        match t {
            Tok::Int(n) => {
                let mut text = n;
                let mut span = s;
                if allow_rational
                    && *self.peek() == Tok::Sym('/')
                    && matches!(self.peek_at(1), Tok::Int(_))
                {
                    self.bump();
                    let (Tok::Int(d), ds) = self.bump() else {
                        unreachable!()
                    };
                    if d.chars().all(|c| c == '0') {
                        return err(ds, "division by zero");
                    }
                    text = format!("{text}/{d}");
                    span = s.to(ds);
                }
                let r = Rational::parse(&text).expect("digits parse");
                Ok(Ast {
                    kind: AstKind::Num(r),
                    span,
                })
            }
            Tok::Ident(name) => {
                if self.eat('(') {
                    let args = self.args()?;
                    let close = self.expect(')', "to close the argument list")?;
                    return Ok(Ast {
                        kind: AstKind::Call { func: name, args },
                        span: s.to(close),
                    });
                }
                let mut primes = 0;
                let mut span = s;
                while *self.peek() == Tok::Prime {
                    primes += 1;
                    span = s.to(self.bump().1);
                }
                Ok(Ast {
                    kind: AstKind::Name { name, primes },
                    span,
                })
            }
            Tok::Sym('(') => {
                let e = self.expr()?;
                self.expect(')', "to close the parenthesis")?;
                Ok(e)
            }
            Tok::Sym('[') => {
                let mut items = vec![self.expr()?];
                while self.eat(',') {
                    items.push(self.expr()?);
                }
                let close = self.expect(']', "to close the vector")?;
                let mut span = s.to(close);
                let mut frame = None;
                if *self.peek() == Tok::Ident("in".into()) {
                    self.bump();
                    let (t, fs) = self.bump();
                    let Tok::Ident(f) = t else {
                        return err(fs, "expected a frame name after `in`");
                    };
                    span = span.to(fs);
                    frame = Some((f, fs));
                }
                Ok(Ast {
                    kind: AstKind::Vector { items, frame },
                    span,
                })
            }
            Tok::End => err(s, "expected an expression, found the end of the text"),
            t => err(s, format!("expected an expression, found {}", describe(&t))),
        }
    }

    fn args(&mut self) -> Result<Vec<Ast>, ParseError> {
        let mut args = Vec::new();
        if *self.peek() == Tok::Sym(')') {
            return Ok(args);
        }
        loop {
            let mut k = 1;
            while *self.peek_at(k) == Tok::Prime {
                k += 1;
            }
            if let (Tok::Ident(name), Tok::Sym('=')) =
                (self.peek().clone(), self.peek_at(k).clone())
            {
                let (_, ns) = self.bump();
                let mut name_span = ns;
                for _ in 1..k {
                    name_span = ns.to(self.bump().1);
                }
                self.bump();
                let v = self.expr()?;
                let span = ns.to(v.span);
                let primes = (k - 1) as u32;
                args.push(Ast {
                    kind: AstKind::Assign {
                        name,
                        primes,
                        name_span,
                        value: Box::new(v),
                    },
                    span,
                });
            } else {
                args.push(self.expr()?);
            }
            if !self.eat(',') {
                break;
            }
        }
        Ok(args)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_point_at_the_offending_token() {
        let e = parse("a + * b").unwrap_err();
        assert_eq!(e.span, Span { start: 4, end: 5 });
        let e = parse("a + 1.5").unwrap_err();
        assert!(e.message.contains("decimal"));
        let e = parse("f(a, b").unwrap_err();
        assert_eq!(e.span.start, 6);
    }

    #[test]
    fn nesting_and_literals_are_bounded() {
        let ok = format!(
            "{}a{}",
            "(".repeat(MAX_DEPTH - 1),
            ")".repeat(MAX_DEPTH - 1)
        );
        assert!(parse(&ok).is_ok());
        for deep in [
            format!("{}a{}", "(".repeat(10_000), ")".repeat(10_000)),
            format!("{}a", "-".repeat(10_000)),
            format!("{}a{}", "dt(".repeat(10_000), ")".repeat(10_000)),
            format!("a{}", ".x".repeat(10_000)),
            format!("{}a", "[".repeat(10_000)),
        ] {
            let e = parse(&deep).unwrap_err();
            assert!(e.message.contains("nests deeper"), "{}", e.message);
        }
        let e = parse(&"7".repeat(MAX_DIGITS + 1)).unwrap_err();
        assert!(e.message.contains("digits"), "{}", e.message);
        assert!(parse(&"7".repeat(MAX_DIGITS)).is_ok());
    }

    #[test]
    fn rational_literals_and_division() {
        let a = parse("1/2*m").unwrap();
        let AstKind::Mul(items) = a.kind else {
            panic!()
        };
        assert_eq!(items[0].kind, AstKind::Num(Rational::new(1, 2).unwrap()));
    }
}
