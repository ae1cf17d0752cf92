//! Prose with mathematics in it: summaries, step docs, assumptions,
//! sources and titles of derivation files.
//!
//! Prose is written in the notation hdot prints (ΣM_x, ω̇_z, (Ḣ_O)_Oxyz,
//! I′ sin θ). [`pieces`] splits it into text and math: whatever stands
//! between `$` signs is math, and outside them a run of words that is
//! clearly notation (it holds a Greek letter, a dot or bar accent, a
//! subscript such as `M_x`, a prime, a superscript, or an operator between
//! such words) becomes one piece of math, so `ΣM_O = r̄ × m ā + Ḣ_G` is
//! typeset as one formula, not as letters with literal underscores; a
//! comma between the arguments of a bracket the formula opened does not
//! end it (`M(q) q̈ = f(q, q̇, t)` is one formula). Each
//! output format renders the pieces: [`latex`] (and the PDF), [`markdown`]
//! (`$…$` math) and [`unicode`] (the text as written, without `$`).
//!
//! A derivation's prose may also name its declared symbols as they are
//! written in its formulas (`theta'`, `omega_z`, `beta`, `I'` for the
//! constant `Ip`): [`in_notation`] rewrites each such word into the
//! notation the printers give the symbol (θ̇, ω_z, β, I′), before any
//! format sees it, so every format typesets it as that symbol.
//!
//! Inside `$…$` the same notation is used: `$ΣM_O = (Ḣ_O)_Oxyz$`;
//! multi-letter subscripts and `^` exponents are allowed there. A `$`
//! without a closing `$` is a dollar sign.
//!
//! # Example
//! ```
//! use hdot_sym::prose;
//! assert_eq!(
//!     prose::latex("Transport theorem: ΣM_O = (Ḣ_O)_Oxyz + Ω × H_O."),
//!     r"Transport theorem: $\Sigma M_{O} = (\dot{H}_{O})_{Oxyz} + \Omega \times H_{O}$."
//! );
//! assert_eq!(prose::latex("$T = ½ m v^2$ holds"), r"$T = \tfrac{1}{2} m v^{2}$ holds");
//! assert_eq!(prose::markdown("the rate ω_z, 50%"), r"the rate $\omega_{z}$, 50%");
//! assert_eq!(prose::unicode("$ω_z$ is constant"), "ω_z is constant");
//! // Brackets inside a formula keep it whole; a lone symbol letter is math.
//! assert_eq!(
//!     prose::latex("steady when cos θ = m g L/(2 (I′ − J) Ω²)."),
//!     r"steady when $\cos \theta = m g L/(2 (I' - J) \Omega^{2})$."
//! );
//! assert_eq!(prose::latex("A disk of mass m about O"), r"A disk of mass $m$ about $O$");
//! ```

use crate::escape::{self, Latex, precomposed_accent};
use crate::symbols::{self, Decl, Symbols};

pub use crate::escape::{combining_accent, unicode_math};

/// A piece of prose: text as written, or math as LaTeX.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Piece {
    /// Plain text, unescaped.
    Text(String),
    /// Math, as LaTeX (without the `$`).
    Math(String),
}

/// Splits prose into text and math (see the module documentation).
pub fn pieces(s: &str) -> Vec<Piece> {
    let mut out: Vec<Piece> = Vec::new();
    let mut rest = s;
    while !rest.is_empty() {
        match explicit_math(rest) {
            Some((before, math, after)) => {
                words(before, &mut out);
                push(&mut out, Piece::Math(math_latex(math.trim())));
                rest = after;
            }
            None => {
                words(rest, &mut out);
                break;
            }
        }
    }
    out
}

/// The text before the first `$…$`, its content and the text after.
fn explicit_math(s: &str) -> Option<(&str, &str, &str)> {
    let open = s.find('$')?;
    let close = s[open + 1..].find('$')? + open + 1;
    if close == open + 1 {
        return None;
    }
    Some((&s[..open], &s[open + 1..close], &s[close + 1..]))
}

/// Appends text made of `parts` as [`push`] would a `Piece::Text` of
/// their concatenation, but into the last text piece in place: one
/// string for a run of words, not one per word.
fn push_text(out: &mut Vec<Piece>, parts: &[&str]) {
    match out.last_mut() {
        Some(Piece::Text(a)) => parts.iter().for_each(|p| a.push_str(p)),
        _ => out.push(Piece::Text(parts.concat())),
    }
}

fn push(out: &mut Vec<Piece>, p: Piece) {
    match (out.last_mut(), p) {
        (Some(Piece::Text(a)), Piece::Text(b)) => a.push_str(&b),
        (_, Piece::Math(m)) if m.is_empty() => {}
        (_, p) => out.push(p),
    }
}

/// `s` with each declared symbol written as in a formula — `theta'`,
/// `omega_z`, `beta`, a constant `I'` whose name is `Ip` — in the notation
/// the printers give it (θ̇, ω_z, β, I′). A word is such a name when it
/// is a whole word (not part of `top's` or `dt_rel`) and declared in
/// `symbols`; a constant with primes is primed (I′), a function of time
/// differentiated (θ̇). Other words are left as written.
///
/// # Example
/// ```
/// use hdot_sym::{Symbols, prose};
/// let s = Symbols::parse_decl(&["Ip", "beta", "Omega"], &["theta", "omega_z"]);
/// assert_eq!(
///     prose::in_notation("theta' and omega_z at beta; I' Omega^2, the top's", &s),
///     "θ̇ and ω_z at β; I′ Ω^2, the top's"
/// );
/// ```
pub fn in_notation(s: &str, symbols: &Symbols) -> String {
    let mut o = String::with_capacity(s.len() + 8);
    let mut rest = s;
    let mut prev: Option<char> = None;
    while let Some(c) = rest.chars().next() {
        let boundary = prev.is_none_or(|p| !(p.is_alphanumeric() || p == '_' || p == '\\'));
        if c.is_ascii_alphabetic() && boundary {
            let len = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            let primes = rest[len..].chars().take_while(|&c| c == '\'').count();
            let end = len + primes;
            let after = rest[end..].chars().next();
            let whole = after.is_none_or(|a| !(a.is_alphanumeric() || a == '_'));
            let word = &rest[..len];
            if let Some(t) = whole
                .then(|| symbol_notation(word, primes, symbols))
                .flatten()
            {
                o.push_str(&t);
                prev = t.chars().last();
                rest = &rest[end..];
                continue;
            }
            o.push_str(word);
            prev = word.chars().last();
            rest = &rest[len..];
            continue;
        }
        o.push(c);
        prev = Some(c);
        rest = &rest[c.len_utf8()..];
    }
    o
}

/// The notation of the declared symbol `name` written with `primes`, or
/// `None` when it is not one (see [`in_notation`]).
fn symbol_notation(name: &str, primes: usize, symbols: &Symbols) -> Option<String> {
    let order = u32::try_from(primes).ok()?;
    match symbols.get(name) {
        Some(Decl::Time | Decl::Abbrev(_)) => Some(crate::print::unicode_symbol(name, order)),
        Some(Decl::Constant) => Some(crate::print::unicode_symbol(name, 0) + &"′".repeat(primes)),
        // `I'` for the constant `Ip`, which prints as I′.
        None if primes == 1 && matches!(symbols.get(&format!("{name}p")), Some(Decl::Constant)) => {
            Some(crate::print::unicode_symbol(&format!("{name}p"), 0))
        }
        None => None,
    }
}

/// What a word of prose is, for the purpose of finding formulas in it.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    /// Clearly notation: a Greek letter, an accent, a subscript, a prime…
    Math,
    /// An operator or relation between formulas (`=`, `+`, `×`).
    Op,
    /// A single letter, a number or a function name: math next to math.
    Atom,
    /// A word.
    Word,
}

const OPS: &[&str] = &[
    "=", "+", "−", "-", "×", "·", "≠", "≥", "≤", "≈", "→", "⇒", "/", "<", ">", "≡", "∝",
];
/// Names of functions written before their argument in notation (tan γ).
pub(crate) const FUNCTIONS: &[&str] = &["sin", "cos", "tan", "cot", "exp", "ln", "log"];

fn kind(core: &str) -> Kind {
    if core.is_empty() {
        return Kind::Word;
    }
    if OPS.contains(&core) {
        return Kind::Op;
    }
    // A word of ASCII letters (most of prose) has no accent, subscript or
    // operator in it: a symbol letter, a function name or a word, as below.
    if core.bytes().all(|b| b.is_ascii_alphabetic()) {
        return if (core.len() == 1 && core != "a") || FUNCTIONS.contains(&core) {
            Kind::Atom
        } else {
            Kind::Word
        };
    }
    let chars: Vec<char> = core.chars().collect();
    let mathy = chars.iter().enumerate().any(|(i, &c)| {
        symbols::greek_latex(c).is_some()
            || combining_accent(c).is_some()
            || precomposed_accent(c).is_some()
            || (c != '−' && c != '…' && unicode_math(c).is_some())
            || (c == '−' && chars.len() > 1)
            || (c == '_' && subscript_len(&chars, i).is_some())
            || (c == '^' && i > 0 && i + 1 < chars.len())
            || (c == '=' && chars.len() > 1)
    });
    if mathy {
        return Kind::Math;
    }
    // `d(m`, `(x)/dt`: letters in brackets or over a slash, as in a
    // derivative written in prose.
    let bracketed = chars.iter().any(|c| "()/".contains(*c))
        && chars
            .iter()
            .all(|c| c.is_ascii_alphanumeric() || "()/".contains(*c))
        && core
            .split(|c: char| !c.is_ascii_alphabetic())
            .all(|w| w.len() <= 2);
    if bracketed {
        return Kind::Atom;
    }
    let ascii_letters = chars.iter().all(|c| c.is_ascii_alphabetic());
    if (ascii_letters && chars.len() == 1 && core != "a")
        || FUNCTIONS.contains(&core)
        || core.chars().all(|c| c.is_ascii_digit() || c == '.')
            && core.starts_with(|c: char| c.is_ascii_digit())
    {
        return Kind::Atom;
    }
    Kind::Word
}

/// The length of a subscript after the `_` at `i` in a word: letters and
/// digits (ASCII or Greek) after a letter, digit, accent, prime or `)`,
/// up to the end of the word or a closing bracket.
fn subscript_len(chars: &[char], i: usize) -> Option<usize> {
    let prev = *chars.get(i.checked_sub(1)?)?;
    if !(prev.is_alphanumeric()
        || prev == ')'
        || prev == '′'
        || combining_accent(prev).is_some()
        || symbols::greek_latex(prev).is_some())
    {
        return None;
    }
    // A word of several ASCII letters before the underscore (`dt_rel`) is
    // code, not a symbol with a subscript.
    let word: usize = chars[..i]
        .iter()
        .rev()
        .take_while(|c| c.is_ascii_alphanumeric())
        .count();
    let at_start = i == word || !chars[i - word - 1].is_ascii_alphanumeric();
    let two = word == 2 && at_start && {
        let (a, b) = (chars[i - 2], chars[i - 1]);
        a.is_ascii_uppercase() || (a == 'd' && b.is_ascii_uppercase())
    };
    if word > 1 && !two {
        // Two letters are allowed when the first is a capital or a `d`
        // before a capital (`dH_O/dt`); longer words (`dt_rel`) are code.
        return None;
    }
    let ok = |c: char| c.is_ascii_alphanumeric() || symbols::greek_latex(c).is_some();
    let len = chars[i + 1..].iter().take_while(|&&c| ok(c)).count();
    let next = chars.get(i + 1 + len).copied();
    (len >= 1 && next.is_none_or(|n| !n.is_alphanumeric() && n != '_')).then_some(len)
}

/// Splits `s` into words and turns each run of notation into math.
fn words(s: &str, out: &mut Vec<Piece>) {
    let mut toks: Vec<Tok> = Vec::new();
    let mut rest = s;
    // Leading whitespace.
    let ws = rest.len() - rest.trim_start().len();
    if ws > 0 {
        push_text(out, &[&rest[..ws]]);
        rest = &rest[ws..];
    }
    while !rest.is_empty() {
        let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let word = &rest[..end];
        let after = &rest[end..];
        let ws = after.len() - after.trim_start().len();
        let (lead, core, trail) = split_punct(word);
        toks.push(Tok {
            lead,
            core,
            trail,
            space: &after[..ws],
            kind: kind(core),
        });
        rest = &after[ws..];
    }
    // Runs: maximal sequences of Math/Op/Atom tokens, holding at least one
    // Math token (or an Op between Atoms, or a lone symbol letter), trimmed
    // of operators at either end. Brackets may open and close inside a run,
    // `m g L/(2 (I′ − J) Ω²)`; a run whose brackets do not balance is cut
    // at the first punctuation instead, as plain words would be.
    let mut k = 0;
    while k < toks.len() {
        // A word is text (no run of notation starts at it).
        let made = if toks[k].kind == Kind::Word {
            None
        } else {
            [true, false]
                .into_iter()
                .find_map(|brackets| formula(&toks, k, run_end(&toks, k, brackets), out))
        };
        match made {
            Some(end) => k = end,
            None => {
                // Not a formula: the first token as text.
                let t = &toks[k];
                push_text(out, &[t.lead, t.core, t.trail, t.space]);
                k += 1;
            }
        }
    }
}

/// A token of prose: leading punctuation, core, trailing punctuation and
/// the whitespace after it.
struct Tok<'a> {
    lead: &'a str,
    core: &'a str,
    trail: &'a str,
    space: &'a str,
    kind: Kind,
}

/// Opening minus closing brackets in `s`.
fn depth(s: &str) -> i32 {
    s.matches(['(', '[']).count() as i32 - s.matches([')', ']']).count() as i32
}

/// Whether `s` is made of brackets from `set` only (and is not empty).
fn only(s: &str, set: &str) -> bool {
    !s.is_empty() && s.chars().all(|c| set.contains(c))
}

/// The end (exclusive) of the run of notation starting at `k`. With
/// `brackets`, a bracket before a word or after it does not end the run
/// when the run itself opened or opens it; without, only a comma between
/// the arguments of a bracket does not.
fn run_end(toks: &[Tok], k: usize, brackets: bool) -> usize {
    if toks[k].kind == Kind::Word {
        return k;
    }
    let mut open = depth(toks[k].core) + if brackets { depth(toks[k].lead) } else { 0 };
    let mut end = k + 1;
    while end < toks.len() && toks[end].kind != Kind::Word {
        let (prev, t) = (&toks[end - 1], &toks[end]);
        let lead_ok = t.lead.is_empty() || (brackets && only(t.lead, "(["));
        let closes = -depth(prev.trail);
        let trail_ok = prev.trail.is_empty()
            || (prev.trail == "," && open > 0)
            || (brackets && only(prev.trail, ")]") && open - closes >= 0);
        if !(lead_ok && trail_ok) {
            break;
        }
        if brackets {
            open += depth(prev.trail) + depth(t.lead);
        }
        open += depth(t.core);
        end += 1;
    }
    end
}

/// Pushes the tokens `k..end` as a formula (with the text around it) and
/// returns `end`, or pushes nothing and returns `None` when they hold no
/// notation or their brackets do not balance.
fn formula(toks: &[Tok], k: usize, end: usize, out: &mut Vec<Piece>) -> Option<usize> {
    // Trim operators from both ends.
    let (mut a, mut b) = (k, end);
    while a < b && toks[a].kind == Kind::Op {
        a += 1;
    }
    while b > a && toks[b - 1].kind == Kind::Op {
        b -= 1;
    }
    let run = &toks[a..b];
    // A lone letter is a symbol (the mass m, the point O, L/2), except the
    // article: `a`, and `A` opening a sentence before a word (`A disk`).
    let lone = |i: usize| {
        let t = &toks[i];
        if t.kind != Kind::Atom {
            return false;
        }
        let mut chars = t.core.chars();
        let first = chars.next();
        let rest = chars.as_str();
        let article = t.core == "A"
            && (i == 0 || toks[i - 1].trail.ends_with(['.', ':', ';', '!', '?']))
            && toks
                .get(i + 1)
                .is_some_and(|n| n.kind == Kind::Word && n.core.starts_with(char::is_lowercase));
        // An initial of a name (`A. Lecturer`, `J. R. Smith`).
        let initial_like =
            |t: &Tok| t.trail == "." && t.core.len() == 1 && t.core.starts_with(char::is_uppercase);
        let initial = initial_like(t)
            && (i == 0 || initial_like(&toks[i - 1]))
            && toks.get(i + 1).is_some_and(|n| {
                initial_like(n) || n.kind == Kind::Word && n.core.starts_with(char::is_uppercase)
            });
        t.kind == Kind::Atom
            && !article
            && !initial
            && first.is_some_and(|c| c.is_ascii_alphabetic())
            && (rest.is_empty()
                || rest
                    .strip_prefix('/')
                    .is_some_and(|d| !d.is_empty() && d.chars().all(|c| c.is_ascii_digit())))
    };
    let has_math = (a..b).any(|i| toks[i].kind == Kind::Math || lone(i))
        || (run.len() >= 3 && run.iter().any(|t| t.kind == Kind::Op));
    if end == k || run.is_empty() || !has_math {
        return None;
    }
    // The first token's bracket belongs to the formula when the formula
    // closes it; any other leading punctuation is text.
    let first = &toks[a];
    let lead_in = if only(first.lead, "([") {
        first.lead
    } else {
        ""
    };
    let mut m = String::from(lead_in);
    for (j, t) in run.iter().enumerate() {
        if j > 0 {
            m.push_str(t.lead);
        }
        m.push_str(&math_latex(t.core));
        if j + 1 < run.len() {
            m.push_str(t.trail); // a comma between arguments, a closing bracket
            m.push(' ');
        }
    }
    // The brackets the run left open close inside the formula.
    let last = &toks[b - 1];
    let mut trail = last.trail;
    let mut open = depth(&m);
    while open > 0 && trail.starts_with([')', ']']) {
        m.push_str(&trail[..1]);
        trail = &trail[1..];
        open -= 1;
    }
    let (lead_text, m) = if open > 0 && m.starts_with(lead_in) && open as usize <= lead_in.len() {
        // A bracket before the formula that it does not close is text.
        let n = open as usize;
        (&first.lead[..n], m[n..].to_owned())
    } else {
        (&first.lead[..first.lead.len() - lead_in.len()], m)
    };
    let balanced = m.chars().try_fold(0i32, |d, c| {
        let d = d + depth(c.encode_utf8(&mut [0; 4]));
        (d >= 0).then_some(d)
    }) == Some(0);
    if !balanced
        && (a..b)
            .any(|i| i > a && !toks[i].lead.is_empty() || i + 1 < b && only(toks[i].trail, ")]"))
    {
        // Brackets across words that do not balance: let the caller cut
        // the run at the first punctuation instead.
        return None;
    }
    for t in &toks[k..a] {
        push_text(out, &[t.lead, t.core, t.trail, t.space]);
    }
    push_text(out, &[lead_text]);
    push(out, Piece::Math(m));
    push_text(out, &[trail, last.space]);
    for t in &toks[b..end] {
        push_text(out, &[t.lead, t.core, t.trail, t.space]);
    }
    Some(end)
}

/// Splits a word into leading punctuation, core and trailing punctuation;
/// a bracket stays in the core when it is matched inside it.
fn split_punct(word: &str) -> (&str, &str, &str) {
    let mut core = word;
    let mut lead_len = 0;
    let mut trail_len = 0;
    loop {
        let opens = core.matches(['(', '[']).count();
        let closes = core.matches([')', ']']).count();
        if let Some(c) = core.chars().last()
            && (".,;:!?\"'’”".contains(c) && !(c == '\'' && core.len() > 1)
                || (")]".contains(c) && closes > opens))
        {
            core = &core[..core.len() - c.len_utf8()];
            trail_len += c.len_utf8();
            continue;
        }
        if let Some(c) = core.chars().next()
            && ("\"‘“".contains(c) || ("([".contains(c) && opens > closes))
        {
            core = &core[c.len_utf8()..];
            lead_len += c.len_utf8();
            continue;
        }
        break;
    }
    (&word[..lead_len], core, &word[word.len() - trail_len..])
}

/// LaTeX math for notation as hdot prints it: `ΣM_x` → `\Sigma M_{x}`,
/// `(Ḣ_O)_Oxyz` → `(\dot{H}_{O})_{Oxyz}`, `sin²θ` → `\sin^{2}\theta`.
pub fn math_latex(s: &str) -> String {
    let chars: Vec<char> = s.chars().collect();
    let mut o = String::new();
    let mut i = 0;
    // Whether `o` ends with a control word (a backslash and letters), so
    // that a letter must be spaced: read back over the letters at its end
    // only, not the whole formula at every atom.
    let push_atom = |o: &mut String, t: &str| {
        let letters = o.bytes().rev().take_while(u8::is_ascii_alphabetic).count();
        let ends_cmd =
            letters > 0 && o.len() > letters && { o.as_bytes()[o.len() - letters - 1] == b'\\' };
        if ends_cmd && t.starts_with(|c: char| c.is_ascii_alphabetic()) {
            o.push(' ');
        }
        o.push_str(t);
    };
    while i < chars.len() {
        let c = chars[i];
        if let Some(acc) = chars.get(i + 1).and_then(|&n| combining_accent(n)) {
            let base = symbols::greek_latex(c).map_or_else(|| escape::letter(c), str::to_owned);
            push_atom(&mut o, &format!("{acc}{{{base}}}"));
            i += 2;
            continue;
        }
        if (c == '_' || c == '^') && i + 1 < chars.len() {
            let ok = |c: char| c.is_ascii_alphanumeric() || symbols::greek_latex(c).is_some();
            let len = chars[i + 1..].iter().take_while(|&&c| ok(c)).count();
            if len > 0 {
                let run = &chars[i + 1..i + 1 + len];
                let sub: String = if len >= 3 && run.iter().all(|c| c.is_ascii_lowercase()) {
                    // A word as a subscript (`r_rel`) is upright.
                    format!(r"\mathrm{{{}}}", run.iter().collect::<String>())
                } else {
                    run.iter()
                        .map(|&c| {
                            symbols::greek_latex(c)
                                .map_or_else(|| c.to_string(), |g| format!("{{{g}}}"))
                        })
                        .collect()
                };
                o.push_str(&format!("{c}{{{sub}}}"));
                i += 1 + len;
                continue;
            }
        }
        if c.is_ascii_alphabetic() {
            let len = chars[i..]
                .iter()
                .take_while(|c| c.is_ascii_alphabetic())
                .count();
            let w: String = chars[i..i + len].iter().collect();
            if FUNCTIONS.contains(&w.as_str()) {
                push_atom(&mut o, &format!("\\{w}"));
                // A thin space between the function and its argument is
                // LaTeX's own; a space in the source is dropped.
            } else {
                push_atom(&mut o, &w);
            }
            i += len;
            continue;
        }
        // A run of super- or subscripts (`E⁻¹`) is one script, `^{-1}`.
        if let Some((script, n)) = escape::script_run(&chars[i..]) {
            push_atom(&mut o, &script);
            i += n;
            continue;
        }
        let t: String = match c {
            ' ' => " ".into(),
            // A script mark with nothing to attach to (at the end, before
            // a space or another mark) is the character itself.
            '_' | '^'
                if chars
                    .get(i + 1)
                    .is_none_or(|n| n.is_whitespace() || "_^".contains(*n)) =>
            {
                escape::latex_math_char(c)
            }
            '_' | '^' => c.to_string(),
            c if c.is_ascii_alphanumeric() => c.to_string(),
            c => escape::latex_math_char(c),
        };
        push_atom(&mut o, &t);
        i += 1;
    }
    o
}

/// Text for LaTeX: special characters escaped, a permitted line break
/// after a slash, typographic punctuation as LaTeX ligatures; any notation that is not in a math piece is kept
/// visible as its code point.
fn latex_plain(s: &str) -> String {
    escape::latex(s, Latex::Text)
}

/// [`latex`] of a line: an argument of a LaTeX command (`\title`,
/// `\author`, `\section`, a frame's title) cannot hold a paragraph
/// break, so line breaks and runs of white space are single spaces.
pub fn latex_line(s: &str) -> String {
    latex(&one_line(s))
}

/// `s` on one line: line breaks and runs of white space as single spaces.
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Prose as LaTeX text with `$…$` math; it holds only characters pdflatex
/// can typeset (ASCII and the accented letters of Latin-1).
pub fn latex(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 16);
    for p in pieces(s) {
        match p {
            Piece::Text(t) => o.push_str(&latex_plain(&t)),
            Piece::Math(m) => {
                o.push('$');
                o.push_str(&m);
                o.push('$');
            }
        }
    }
    o
}

/// Prose as Markdown with `$…$` math; `*`, `_`, `` ` ``, `[`, `<` and `\`
/// in text show as themselves.
pub fn markdown(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 16);
    for p in pieces(s) {
        match p {
            Piece::Text(t) => o.push_str(&escape::markdown(&t)),
            Piece::Math(m) => {
                o.push('$');
                o.push_str(&escape::markdown_math(&m));
                o.push('$');
            }
        }
    }
    o
}

/// Prose for a terminal: as written, without the `$` around math.
pub fn unicode(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    let mut rest = s;
    while let Some((before, math, after)) = explicit_math(rest) {
        o.push_str(before);
        o.push_str(math.trim());
        rest = after;
    }
    o.push_str(rest);
    o
}

/// Plain ASCII (PDF bookmarks): Greek letters by name, other symbols dropped.
pub fn ascii(s: &str) -> String {
    let mut o = String::new();
    for c in unicode(s).chars() {
        match c {
            c if c.is_ascii_alphanumeric() || " .,:;()'-/+=".contains(c) => o.push(c),
            '−' => o.push('-'),
            c => {
                if let Some(name) = symbols::greek_name(c) {
                    o.push_str(name);
                } else if let Some((_, b)) = precomposed_accent(c) {
                    o.push(b);
                }
            }
        }
    }
    o
}
