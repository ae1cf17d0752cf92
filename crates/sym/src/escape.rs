//! Escaping: how any string of a file is written in each output language,
//! in one place. [`latex`] for LaTeX (text, typewriter code, math, a
//! comment line), [`markdown`] and [`markdown_code`] for Markdown,
//! [`python_str`], [`python_comment`] and [`python_name`] for the SymPy
//! export, [`html`] for the web pages, [`terminal`] for error messages; every field of every backend that
//! is not built from expression trees goes through one of them, so no
//! string a user wrote reaches an output as commands (`\input`,
//! `\write18`, `\def`, unbalanced braces, HTML, a line of Python).
//!
//! The tables of how a Unicode character is written in LaTeX (Greek
//! letters are in [`crate::symbols`]) live here too: operators and arrows
//! ([`unicode_math`]), accents ([`combining_accent`]), typographic
//! punctuation. The output holds only characters pdflatex can typeset:
//! ASCII and the accented letters of Latin-1; anything else is kept
//! visible as its code point.
//!
//! # Example
//! ```
//! use hdot_sym::escape::{Latex, latex, markdown_code};
//! assert_eq!(latex(r"50% \input{x}", Latex::Text), r"50\% \textbackslash{}input\{x\}");
//! assert_eq!(latex(r"\def\x{\x}", Latex::Math), r"\backslash def\backslash x\{\backslash x\}");
//! assert_eq!(latex("a'b, c", Latex::Code), r"a\textquotesingle{}b,\allowbreak{} c");
//! assert_eq!(latex("E⁻¹ A", Latex::Math), "E^{-1} A");
//! assert_eq!(markdown_code("a `b`"), "`` a `b` ``");
//! use hdot_sym::escape::{python_comment, python_name, python_str};
//! assert_eq!(python_str("it's\n"), r"'it\'s\n'");
//! assert_eq!(python_comment("a\nimport os"), "a import os");
//! assert_eq!(python_name("ωx"), "_u3c9_x");
//! ```

use std::fmt::Write as _;

use crate::symbols;

/// Where in a LaTeX document a string is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Latex {
    /// Running text (prose that is not math): a permitted line break after
    /// a slash, typographic punctuation as LaTeX ligatures.
    Text,
    /// Typewriter text (`\texttt`: a formula as written, a file name):
    /// straight quotes, a permitted line break after a comma.
    Code,
    /// Inside math (`\mathrm{…}`, a subscript): every character that means
    /// something to TeX escaped.
    Math,
    /// A comment line: only line breaks (which would end the comment) and
    /// control characters are replaced, by spaces.
    Comment,
}

/// `s` escaped for LaTeX at `to` (see [`Latex`]).
pub fn latex(s: &str, to: Latex) -> String {
    let mut o = String::with_capacity(s.len() + 8);
    let chars: Vec<char> = s.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        i += 1;
        if c.is_control() && !(to == Latex::Text && matches!(c, '\n' | '\t')) {
            o.push(' ');
            continue;
        }
        // A run of super- or subscripts (`E⁻¹`) is one script, `^{-1}`
        // (none of them is ASCII, as most of prose is).
        if to != Latex::Comment
            && !c.is_ascii()
            && let Some((script, n)) = script_run(&chars[i - 1..])
        {
            if to == Latex::Math {
                o.push_str(&script);
            } else {
                o.push('$');
                o.push_str(&script);
                o.push('$');
            }
            i += n - 1;
            continue;
        }
        match (to, c) {
            (Latex::Comment, c) => o.push(c),
            (Latex::Math, c) => o.push_str(&latex_math_char(c)),
            (_, '\\') => o.push_str(r"\textbackslash{}"),
            (_, '&' | '%' | '$' | '#' | '_' | '{' | '}') => {
                o.push('\\');
                o.push(c);
            }
            (_, '~') => o.push_str(r"\textasciitilde{}"),
            (_, '^') => o.push_str(r"\textasciicircum{}"),
            (_, '<') => o.push_str(r"\textless{}"),
            (_, '>') => o.push_str(r"\textgreater{}"),
            (Latex::Text, '|') => o.push_str(r"\textbar{}"),
            // A path such as docs/equations.md may break after a slash.
            (Latex::Text, '/') => o.push_str(r"/\allowbreak{}"),
            // Straight quotes in typewriter type, and a break point after
            // commas so long formulas can wrap.
            (Latex::Code, '\'') => o.push_str(r"\textquotesingle{}"),
            (Latex::Code, '"') => o.push_str(r"\textquotedbl{}"),
            (Latex::Code, ',') => o.push_str(r",\allowbreak{}"),
            (_, c) if c.is_ascii() => o.push(c),
            (_, c) => o.push_str(&latex_text_char(c)),
        }
    }
    o
}

/// `s` escaped inside LaTeX math: [`latex`] at [`Latex::Math`].
pub fn latex_math(s: &str) -> String {
    latex(s, Latex::Math)
}

/// One character inside LaTeX math: letters and digits as themselves,
/// TeX's special characters escaped, non-ASCII notation by its table.
pub fn latex_math_char(c: char) -> String {
    match c {
        '{' => r"\{".into(),
        '}' => r"\}".into(),
        '%' | '&' | '#' | '$' | '_' => format!("\\{c}"),
        '\\' => r"\backslash ".into(),
        '~' => r"\sim ".into(),
        '^' => r"\hat{}".into(),
        // A backtick means nothing in math, and in a Markdown page it
        // would open a code span across the `$`: the grave accent it is.
        '`' => r"\grave{}".into(),
        c if c.is_control() => " ".into(),
        c if c.is_ascii() => c.to_string(),
        c => {
            if let Some(g) = symbols::greek_latex(c) {
                g.to_owned()
            } else if let Some(m) = unicode_math(c) {
                m
            } else if let Some((acc, b)) = precomposed_accent(c) {
                format!("{acc}{{{b}}}")
            } else if let Some(t) = text_symbol(c) {
                format!(r"\text{{{t}}}")
            } else {
                letter(c)
            }
        }
    }
}

/// A non-ASCII character in LaTeX text: typographic punctuation as
/// ligatures, a Latin-1 letter as itself, notation as math, anything else
/// as its code point.
fn latex_text_char(c: char) -> String {
    if let Some(t) = text_symbol(c) {
        t.to_owned()
    } else if matches!(c, 'À'..='ÿ') && c.is_alphabetic() {
        c.to_string()
    } else if let Some(m) = unicode_math(c) {
        format!("${m}$")
    } else if let Some((acc, b)) = precomposed_accent(c) {
        format!("${acc}{{{b}}}$")
    } else {
        format!("[U+{:04X}]", c as u32)
    }
}

/// A letter as math: itself when ASCII, a Latin-1 letter as text, else its
/// code point (visible in the output, never a pdflatex error).
pub fn letter(c: char) -> String {
    if c.is_ascii_alphanumeric() {
        c.to_string()
    } else if matches!(c, 'À'..='ÿ') && c.is_alphabetic() {
        format!(r"\text{{{c}}}")
    } else {
        format!(r"\text{{[U+{:04X}]}}", c as u32)
    }
}

/// Markdown text: `\`, `*`, `_`, `` ` ``, `$`, `[`, `]` and `<` show as
/// themselves (no emphasis, code, math, link or HTML); control characters
/// other than line breaks and tabs as spaces.
pub fn markdown(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if c.is_control() && !matches!(c, '\n' | '\t') {
            o.push(' ');
            continue;
        }
        if "\\*_`$[]<".contains(c) {
            o.push('\\');
        }
        o.push(c);
    }
    o
}

/// LaTeX math for a Markdown page (`$…$`, `$$…$$`): a `<` that a
/// Markdown reader would take for the start of an HTML tag (before a
/// letter, `/`, `!` or `?`) is followed by a space, which math ignores.
pub fn markdown_math(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    let mut cs = s.chars().peekable();
    while let Some(c) = cs.next() {
        o.push(c);
        if c == '<'
            && cs
                .peek()
                .is_some_and(|n| n.is_alphabetic() || "/!?".contains(*n))
        {
            o.push(' ');
        }
    }
    o
}

/// Markdown inline code holding `s` as written: fenced by one backtick
/// more than its longest run of backticks, line breaks as spaces.
pub fn markdown_code(s: &str) -> String {
    let s: String = s
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let longest = s.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    if longest == 0 {
        format!("`{s}`")
    } else {
        let fence = "`".repeat(longest + 1);
        format!("{fence} {s} {fence}")
    }
}

/// A Python string literal holding `s`: single-quoted, with `\\`, `'`
/// and every control or line-separator character as an escape, so that
/// the literal ends where it should whatever `s` holds.
pub fn python_str(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 2);
    o.push('\'');
    for c in s.chars() {
        match c {
            '\\' => o.push_str(r"\\"),
            '\'' => o.push_str(r"\'"),
            '\n' => o.push_str(r"\n"),
            '\r' => o.push_str(r"\r"),
            '\t' => o.push_str(r"\t"),
            c if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('\'');
    o
}

/// The text of a Python comment line: control and line-separator
/// characters (which could end the comment) as spaces.
pub fn python_comment(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') {
                ' '
            } else {
                c
            }
        })
        .collect()
}

/// An ASCII Python identifier spelling `s`: ASCII letters, digits and `_`
/// as themselves, any other character as `_u<hex>_`, and a leading digit
/// (or an empty name) after a `_`. Distinct names without `_u` give
/// distinct identifiers; callers that must avoid every clash (keywords,
/// their own names) still check what they give out.
pub fn python_name(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    if s.chars().next().is_none_or(|c| c.is_ascii_digit()) {
        o.push('_');
    }
    for c in s.chars() {
        if c.is_ascii_alphanumeric() || c == '_' {
            o.push(c);
        } else {
            let _ = write!(o, "_u{:x}_", c as u32);
        }
    }
    o
}

/// HTML text and attribute values (a page of the notes, a simulation or a
/// chart page): `&`, `<`, `>`, `"` and `'` as character references, so a
/// string shows as written and never opens a tag, a script or an
/// attribute; control characters other than line breaks and tabs (which
/// HTML does not allow) as spaces.
///
/// # Example
/// ```
/// use hdot_sym::escape::html;
/// assert_eq!(html("a<b & \"c\"</script>"), "a&lt;b &amp; &quot;c&quot;&lt;/script&gt;");
/// assert_eq!(html("it's\u{7}"), "it&#39;s ");
/// ```
pub fn html(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            '\n' | '\t' => out.push(c),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Text for a terminal (an error message quoting a file): control
/// characters other than line breaks and tabs, which could move the cursor
/// or recolour the screen, written visibly as `\u{1b}`.
///
/// # Example
/// ```
/// use hdot_sym::escape::terminal;
/// assert_eq!(terminal("a\u{1b}[31m b\n"), "a\\u{1b}[31m b\n");
/// ```
pub fn terminal(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        if c.is_control() && !matches!(c, '\n' | '\t') {
            let _ = write!(o, "\\u{{{:x}}}", c as u32);
        } else {
            o.push(c);
        }
    }
    o
}

// ------------------------------------------------------------- tables --

/// Combining accents over the preceding letter: dots of time derivatives,
/// hat, bar, tilde, vector arrow.
/// Combining accents over the preceding letter: dots of time derivatives,
/// hat, bar, tilde, vector arrow.
pub fn combining_accent(c: char) -> Option<&'static str> {
    Some(match c {
        '\u{307}' => r"\dot",
        '\u{308}' => r"\ddot",
        '\u{20DB}' => r"\dddot",
        '\u{20DC}' => r"\ddddot",
        '\u{302}' => r"\hat",
        '\u{303}' => r"\tilde",
        '\u{304}' | '\u{305}' => r"\bar",
        '\u{20D7}' => r"\vec",
        _ => return None,
    })
}

/// Precomposed Latin letters with a dot, diaeresis or bar above (`Ḣ`,
/// `ẋ`, `ẍ`, `ā`): time derivatives and mean values in prose. Latin-1
/// letters with a diaeresis (`ö`) are left to the text font.
pub(crate) fn precomposed_accent(c: char) -> Option<(&'static str, char)> {
    const DOT: &str = "ḂBḃbĊCċcḊDḋdĖEėeḞFḟfĠGġgḢHḣhİIṀMṁmṄNṅnȮOȯoṖPṗpṘRṙrṠSṡsṪTṫtẆWẇwẊXẋxẎYẏyŻZżz";
    const DDOT: &str = "ḦHḧhẗtẄWẅwẌXẍx";
    const BAR: &str = "ĀAāaĒEēeĪIīiŌOōoŪUūuȲYȳy";
    // Asked of every character of prose: ASCII is never in the tables, and
    // the tables are read in pairs where they are (no copy).
    if c.is_ascii() {
        return None;
    }
    for (table, acc) in [(DOT, r"\dot"), (DDOT, r"\ddot"), (BAR, r"\bar")] {
        let mut cs = table.chars();
        while let (Some(accented), Some(base)) = (cs.next(), cs.next()) {
            if accented == c {
                return Some((acc, base));
            }
        }
    }
    None
}

/// Typographic punctuation and text symbols, as LaTeX text.
pub(crate) fn text_symbol(c: char) -> Option<&'static str> {
    Some(match c {
        '§' => r"\S{}",
        '¶' => r"\P{}",
        '—' => "---",
        '–' | '‒' => "--",
        '‐' | '‑' => "-",
        '‘' => "`",
        '’' => "'",
        '“' => "``",
        '”' => "''",
        '„' => ",,",
        '«' => r"\guillemotleft{}",
        '»' => r"\guillemotright{}",
        '…' => r"\ldots{}",
        '\u{a0}' => "~",
        '\u{2009}' | '\u{202F}' | '\u{2002}' | '\u{2003}' => r"\,",
        '\u{200B}' | '\u{FEFF}' | '\u{AD}' => "",
        '†' => r"\dag{}",
        '‡' => r"\ddag{}",
        '©' => r"\textcopyright{}",
        '®' => r"\textregistered{}",
        '•' => r"\textbullet{}",
        '✓' | '✔' => r"$\checkmark$",
        '✗' | '✘' => r"$\times$",
        _ => return None,
    })
}

/// A run of Unicode superscript (or subscript) characters at the start of
/// `chars` (`⁻¹`, `₁₂`, `ᵀ`) as one LaTeX script, `^{-1}`: written
/// character by character it would be `^{-}^{1}`, a double superscript
/// and a LaTeX error. The script and how many characters it took; `None`
/// when `chars` does not start with a super- or subscript.
pub fn script_run(chars: &[char]) -> Option<(String, usize)> {
    let mut mark = None;
    let mut body = String::new();
    let mut n = 0;
    for &c in chars {
        let Some(m) = unicode_math(c) else { break };
        let (Some(inner), Some(here)) = (
            m.get(1..)
                .and_then(|r| r.strip_prefix('{')?.strip_suffix('}')),
            m.chars().next().filter(|k| matches!(k, '^' | '_')),
        ) else {
            break;
        };
        if mark.is_some_and(|k| k != here) {
            break;
        }
        mark = Some(here);
        body.push_str(inner);
        n += 1;
    }
    let mark = mark?;
    Some((format!("{mark}{{{body}}}"), n))
}

/// The LaTeX math for a Unicode character that belongs in math (Greek
/// letters are in [`symbols::greek_latex`]): operators and relations,
/// arrows, primes, super- and subscripts. `None` for characters that are
/// text.
pub fn unicode_math(c: char) -> Option<String> {
    // Every character of the tables below is beyond ASCII: prose is
    // mostly ASCII, asked of character by character.
    if c.is_ascii() {
        return None;
    }
    if let Some(g) = symbols::greek_latex(c) {
        return Some(g.to_owned());
    }
    const SUP: &str = "⁰¹²³⁴⁵⁶⁷⁸⁹";
    const SUB: &str = "₀₁₂₃₄₅₆₇₈₉";
    if let Some(k) = SUP.chars().position(|d| d == c) {
        return Some(format!("^{{{k}}}"));
    }
    if let Some(k) = SUB.chars().position(|d| d == c) {
        return Some(format!("_{{{k}}}"));
    }
    let s = match c {
        '⁺' => "^{+}",
        '⁻' => "^{-}",
        'ⁿ' => "^{n}",
        'ⁱ' => "^{i}",
        'ᵀ' => "^{T}",
        'ᵗ' => "^{t}",
        '₊' => "_{+}",
        '₋' => "_{-}",
        'ₓ' => "_{x}",
        'ᵧ' => "_{y}",
        'ₐ' => "_{a}",
        'ₑ' => "_{e}",
        'ₒ' => "_{o}",
        'ᵢ' => "_{i}",
        'ⱼ' => "_{j}",
        'ₖ' => "_{k}",
        'ₙ' => "_{n}",
        '×' => r"\times",
        '·' | '⋅' => r"\cdot",
        '÷' => r"\div",
        '∗' => r"\ast",
        '∘' => r"\circ",
        '−' => "-",
        '±' => r"\pm",
        '∓' => r"\mp",
        '≥' | '⩾' => r"\geq",
        '≤' | '⩽' => r"\leq",
        '≠' => r"\neq",
        '≈' => r"\approx",
        '≡' => r"\equiv",
        '≔' => r"\mathrel{:=}",
        '∼' => r"\sim",
        '≪' => r"\ll",
        '≫' => r"\gg",
        '∝' => r"\propto",
        '∫' => r"\int",
        '∮' => r"\oint",
        '∑' => r"\sum",
        '∏' => r"\prod",
        '∂' => r"\partial",
        '∇' => r"\nabla",
        '∞' => r"\infty",
        '√' => r"\surd",
        '∈' => r"\in",
        '∉' => r"\notin",
        '⊂' => r"\subset",
        '⊆' => r"\subseteq",
        '∪' => r"\cup",
        '∩' => r"\cap",
        '∀' => r"\forall",
        '∃' => r"\exists",
        '∅' => r"\emptyset",
        '⊥' => r"\perp",
        '∥' => r"\parallel",
        '‖' => r"\|",
        '∠' => r"\angle",
        '→' => r"\to",
        '←' => r"\leftarrow",
        '↔' => r"\leftrightarrow",
        '⇒' => r"\Rightarrow",
        '⇐' => r"\Leftarrow",
        '⇔' => r"\Leftrightarrow",
        '↦' => r"\mapsto",
        '⟨' => r"\langle",
        '⟩' => r"\rangle",
        '′' => "'",
        '″' => "''",
        '‴' => "'''",
        '°' => r"^{\circ}",
        '½' => r"\tfrac{1}{2}",
        '¼' => r"\tfrac{1}{4}",
        '¾' => r"\tfrac{3}{4}",
        'ℏ' => r"\hbar",
        'ℓ' => r"\ell",
        '¬' => r"\neg",
        '∧' => r"\wedge",
        '∨' => r"\vee",
        '⊗' => r"\otimes",
        '⊕' => r"\oplus",
        '⋯' => r"\cdots",
        '⋮' => r"\vdots",
        _ => return None,
    };
    Some(s.to_owned())
}
