//! The evaluation context of one derivation file: what is declared so
//! far (symbols, frames, abbreviations, steps' values, small and positive
//! symbols) and the diagnostics located in the file's text. The other
//! jobs on it are in their own files: `frames.rs` (frames and their
//! chain), `eval.rs` (expressions to values), `presentation.rs` and
//! `checks.rs` (a step's presentation and expectation).

use std::collections::HashMap;

use toml::Spanned;

use super::raw::RawSymbols;
use super::value::Value;
use super::{Abbreviation, Diagnostic, unfold};
use crate::atom::Atom;
use crate::frame::Frame;
use crate::parse::{Ast, AstKind, Span, parse};
use crate::poly::Poly;
use crate::symbols::{Decl, Symbols};

/// What a file has declared so far, and where its text is.
pub(crate) struct Context<'a> {
    pub(super) path: &'a str,
    pub(super) text: &'a str,
    pub symbols: Symbols,
    pub frames: Vec<Frame>,
    /// The values of the steps evaluated so far, by name.
    pub(super) values: HashMap<String, Value>,
    /// Symbols declared small (first order), for `linearize`.
    pub small: Vec<Atom>,
    /// The file's order of constant factors (`[symbols] order`).
    pub constant_order: Vec<String>,
    /// Constants declared positive, for `sign`.
    pub positive: Vec<Atom>,
    /// Abbreviations declared so far, in order.
    pub abbrevs: Vec<Abbreviation>,
    /// Generalized speeds and kinematic equations (`speeds.rs`).
    pub speeds: super::multibody::Speeds,
    /// The declared bodies, points, gravity and loads, once read (for
    /// operations such as `kane`).
    pub physics: super::physics::Physics,
    /// Applied forces and torques (`[[load]]`, `loads.rs`).
    pub loads: Vec<super::multibody::Load>,
    /// Rolling contacts (`[[contact]]`, `contact.rs`).
    pub contacts: Vec<super::contact::Contact>,
    /// What the file's steps solve for (`presentation.rs`): their terms
    /// are printed first.
    pub unknowns: Vec<Atom>,
}

/// A result whose error is located in the file.
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
            speeds: Default::default(),
            physics: Default::default(),
            loads: Vec::new(),
            contacts: Vec::new(),
            unknowns: Vec::new(),
        }
    }
}

/// # Diagnostics and parsing at a place in the file
impl Context<'_> {
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
}

/// # Declarations
impl Context<'_> {
    /// Declares `[symbols]`: constants, functions of time, small symbols
    /// (functions of time, first order), positive ones and the order of
    /// constant factors.
    pub fn declare_symbols(&mut self, s: &RawSymbols) -> R<()> {
        for (list, decl) in [
            (&s.constants, Decl::Constant),
            (&s.time, Decl::Time),
            (&s.small, Decl::Time),
            (&s.speeds, Decl::Time),
        ] {
            for name in list {
                self.declare(name, decl.clone())?;
            }
        }
        for name in &s.small {
            self.small.push(Atom::time(name.get_ref(), 0));
        }
        for name in &s.positive {
            self.declare_positive(name)?;
        }
        for name in &s.order {
            self.declare_order(name)?;
        }
        Ok(())
    }

    /// `p` with every abbreviation (and its derivatives) replaced by its
    /// definition.
    pub fn unfold(&self, p: &Poly) -> Poly {
        unfold(&self.abbrevs, p)
    }

    /// Refuses, located, a name that expressions could not refer to: a
    /// name is a letter, then letters, digits and `_` (`what` says what it
    /// names: "symbol", "frame", "step").
    pub fn valid_name(&self, s: &Spanned<String>, what: &str) -> R<()> {
        let name = s.get_ref();
        let valid = name.chars().next().is_some_and(|c| c.is_alphabetic())
            && name.chars().all(|c| c.is_alphanumeric() || c == '_');
        if valid {
            return Ok(());
        }
        Err(self.diag_string(
            s,
            0,
            name.len(),
            format!("`{name}` is not a valid {what} name (a letter, then letters, digits, _)"),
        ))
    }

    pub fn declare(&mut self, s: &Spanned<String>, decl: Decl) -> R<()> {
        let name = s.get_ref();
        self.valid_name(s, "symbol")?;
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

    /// Records a constant symbol, or sin/cos of a constant angle, as positive.
    pub fn declare_positive(&mut self, s: &Spanned<String>) -> R<()> {
        let base = self.content_start(s);
        let (atom, span) = self.listed_atom(
            s.get_ref(),
            base,
            false,
            "list constant symbols or sin/cos of a constant angle",
        )?;
        if atom.is_time_dependent() {
            return Err(self.at(
                base,
                span,
                "only constants (or sin/cos of a constant angle) can be declared positive",
            ));
        }
        self.positive.push(atom);
        Ok(())
    }

    /// The atom an item of a list of symbols names (`positive`,
    /// `collect`): a declared symbol — with primes only when `rates` — or
    /// sin/cos of one, with the item's span; `refusal` at the item when it
    /// is neither. `base` is the item's offset in the file.
    pub(crate) fn listed_atom(
        &self,
        item: &str,
        base: usize,
        rates: bool,
        refusal: &str,
    ) -> R<(Atom, Span)> {
        let ast = self.parse_at(item, base)?;
        let atom = match &ast.kind {
            AstKind::Name { name, primes } if rates || *primes == 0 => {
                self.symbols.atom(name, *primes, ast.span)
            }
            AstKind::Call { func, args } if func == "sin" || func == "cos" => {
                self.symbols.trig(func, args, ast.span)
            }
            _ => return Err(self.at(base, ast.span, refusal)),
        }
        .map_err(|e| self.at(base, e.span, e.message))?;
        Ok((atom, ast.span))
    }

    /// Whether `name` is a step evaluated so far.
    pub(crate) fn is_step(&self, name: &str) -> bool {
        self.values.contains_key(name)
    }

    pub fn bind(&mut self, name: &str, v: Value) {
        self.values.insert(name.to_owned(), v);
    }
}
