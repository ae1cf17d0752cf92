//! Renders an evaluated [`Derivation`] as Unicode text, LaTeX, Markdown,
//! SymPy source or JSON.
//!
//! Each format shows the same things: the title and source, what is
//! assumed, the symbols and frames, then every shown step with its
//! components in textbook form and whether its expectation holds.

use std::fmt::Write;

use crate::derivation::{Derivation, Step, Value};
use crate::expr::Expr;
use crate::print::{self, Latex, Sympy, Unicode, latex_symbol, unicode_symbol};
use crate::symbols::Decl;

/// The output formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Unicode text for a terminal.
    Unicode,
    /// LaTeX `align*` blocks for lecture notes.
    Latex,
    /// Markdown with `$$` math.
    Markdown,
    /// Python source that rebuilds every equation with sympy.
    Sympy,
    /// Machine-readable JSON.
    Json,
}

/// Renders `d` in `format`.
pub fn render(d: &Derivation, format: Format) -> String {
    match format {
        Format::Unicode => unicode(d),
        Format::Latex => latex(d),
        Format::Markdown => markdown(d),
        Format::Sympy => sympy(d),
        Format::Json => serde_json::to_string_pretty(&json(d)).expect("JSON of plain data") + "\n",
    }
}

/// A label word with trailing primes: `epsilon_2''` → (`epsilon_2`, 2).
fn label_word(w: &str) -> (&str, u32) {
    let base = w.trim_end_matches('\'');
    (base, (w.len() - base.len()) as u32)
}

/// The body of a label (its words written by `symbol`, joined by `sep`)
/// and whether it already carries a subscript, so that a component must be
/// attached around parentheses.
fn label_body(label: &str, symbol: fn(&str, u32) -> String, sep: &str) -> (String, bool) {
    let words: Vec<String> = label
        .split_whitespace()
        .map(|w| {
            let (b, k) = label_word(w);
            symbol(b, k)
        })
        .collect();
    let subscripted = label
        .split_whitespace()
        .last()
        .is_some_and(|w| w.contains('_'));
    (words.join(sep), subscripted)
}

/// A label such as `Sigma M` with component `x`, in LaTeX: `\Sigma M_{x}`.
pub fn latex_label(label: &str, component: &str) -> String {
    match (label_body(label, latex_symbol, " "), component.is_empty()) {
        ((body, _), true) => body,
        ((body, false), false) => format!("{body}_{{{component}}}"),
        ((body, true), false) => format!(r"\left({body}\right)_{{{component}}}"),
    }
}

/// The unknown a component of a solved list is the value of (θ̈ in
/// θ̈ = …), when the step is one.
fn unknown_of(s: &Step, component: &str) -> Option<Expr> {
    let Value::List { labels, .. } = &s.value else {
        return None;
    };
    let a = labels.iter().find(|a| a.to_string() == component)?;
    let mut e = Expr::new();
    e.push(crate::expr::Node::Atom(*a));
    Some(e)
}

/// The left side of component `component` of step `s` in LaTeX: the
/// unknown for a solved list (`\ddot{\theta}`), else the label with the
/// component.
pub fn step_lhs_latex(s: &Step, component: &str) -> String {
    match unknown_of(s, component) {
        Some(e) => print::latex(&e),
        None => latex_label(&s.label, component),
    }
}

/// [`step_lhs_latex`] in Unicode (`θ̈`, `ΣM_x`).
pub fn step_lhs_unicode(s: &Step, component: &str) -> String {
    match unknown_of(s, component) {
        Some(e) => print::unicode(&e),
        None => unicode_label(&s.label, component),
    }
}

/// A label with component in Unicode: `ΣM_x`.
pub fn unicode_label(label: &str, component: &str) -> String {
    match (label_body(label, unicode_symbol, ""), component.is_empty()) {
        ((body, _), true) => body,
        ((body, false), false) => format!("{body}_{component}"),
        ((body, true), false) => format!("({body})_{component}"),
    }
}

fn unicode_names(d: &Derivation, want: fn(&Decl) -> bool) -> String {
    let names: Vec<String> = d
        .symbols
        .names()
        .iter()
        .filter(|n| d.symbols.get(n).is_some_and(want))
        .map(|n| unicode_symbol(n, 0))
        .collect();
    names.join(", ")
}

fn frame_omega_unicode(d: &Derivation, k: usize) -> String {
    let f = &d.frames[k];
    let c: Vec<String> = f
        .omega
        .0
        .iter()
        .map(|p| print::unicode(&Expr::from_poly(p)))
        .collect();
    format!("({})", c.join(", "))
}

fn unicode(d: &Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "{}", d.title);
    let _ = writeln!(o, "{}", "=".repeat(d.title.chars().count()));
    let _ = writeln!(o, "Source: {}", d.source);
    if !d.summary.is_empty() {
        let _ = writeln!(o, "\n{}", d.summary.trim());
    }
    if !d.assumptions.is_empty() {
        let _ = writeln!(o, "\nAssumptions:");
        for a in &d.assumptions {
            let _ = writeln!(o, "  • {a}");
        }
    }
    let consts = unicode_names(d, |x| matches!(x, Decl::Constant));
    let time = unicode_names(d, |x| matches!(x, Decl::Time));
    let _ = writeln!(o, "\nSymbols:");
    if !consts.is_empty() {
        let _ = writeln!(o, "  constants: {consts}");
    }
    if !time.is_empty() {
        let _ = writeln!(o, "  functions of time: {time}");
    }
    for a in &d.abbreviations {
        let e = print::unicode(&Expr::from_poly(&a.definition));
        let _ = writeln!(
            o,
            "  abbreviation: {} = {e}{}",
            unicode_symbol(&a.name, 0),
            doc_suffix(&a.doc)
        );
    }
    if d.frames.len() > 1 {
        let _ = writeln!(o, "\nFrames (Ω relative to N, in the frame's own axes):");
        for (k, f) in d.frames.iter().enumerate().skip(1) {
            let _ = writeln!(
                o,
                "  {}: Ω = {}{}",
                f.name,
                frame_omega_unicode(d, k),
                doc_suffix(&f.doc)
            );
        }
    }
    let mut n = 0;
    for s in d.steps.iter().filter(|s| s.show) {
        n += 1;
        let _ = writeln!(
            o,
            "\n{n}. {} = {}{}",
            unicode_label(&s.label, ""),
            s.formula,
            doc_suffix(&s.doc)
        );
        if let Value::Vector(_, f) = &s.value {
            let _ = writeln!(o, "   (components in frame {f})");
        }
        for (c, e) in &s.components {
            let _ = writeln!(o, "   {} = {}", step_lhs_unicode(s, c), print::unicode(e));
        }
        write_checks_unicode(&mut o, s);
    }
    o
}

fn doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!("  — {doc}")
    }
}

fn write_checks_unicode(o: &mut String, s: &Step) {
    if s.checks.is_empty() {
        return;
    }
    if s.checks.iter().all(|c| c.holds()) {
        let _ = writeln!(o, "   ✓ equals the expected (textbook) form");
        return;
    }
    for c in s.checks.iter().filter(|c| !c.holds()) {
        let _ = writeln!(
            o,
            "   ✗ {}: expected {}; derived − expected = {}",
            step_lhs_unicode(s, &c.component),
            print::unicode(&c.expected),
            print::unicode(&Expr::from_poly(&c.difference))
        );
    }
}

/// LaTeX-escapes plain text (titles and prose) for pdflatex with the T1
/// font encoding and `inputenc` utf8.
///
/// ASCII specials are escaped; Unicode mathematics becomes inline math:
/// Greek letters, operators (×, ·, ≥, ∫, Σ, →, …), super- and subscript
/// digits (`r²` → `r$^{2}$`), a letter with a combining or precomposed dot
/// (`ω̇`, `Ḣ` → `$\dot{\omega}$`, `$\dot{H}$`); a single letter with a
/// short subscript (`I_xy`, `ω_z`) is set as math (`$I_{xy}$`). Typographic
/// punctuation becomes its LaTeX ligature (`—` → `---`). The accented letters
/// of Latin-1 are left as they are (inputenc knows them); any other
/// character is written as its code point (`[U+2603]`), so the output
/// never holds a character pdflatex cannot typeset.
///
/// # Example
/// ```
/// use hdot_sym::render::latex_text;
/// assert_eq!(latex_text("ΣM = Ḣ, 50% & ω̇_x"), r"$\Sigma$M = $\dot{H}$, 50\% \& $\dot{\omega}_{x}$");
/// assert_eq!(latex_text("I_xy = ∫xy dm ≥ 0"), r"$I_{xy}$ = $\int$xy dm $\geq$ 0");
/// ```
pub fn latex_text(s: &str) -> String {
    let chars: Vec<char> = s.chars().collect();
    let mut segs: Vec<Seg> = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        // A letter followed by a combining accent.
        if let Some(acc) = chars.get(i + 1).and_then(|&n| combining_accent(n)) {
            let base = unicode_math(c).unwrap_or_else(|| math_letter(c));
            push_math(&mut segs, &format!("{acc}{{{base}}}"));
            i += 2;
            continue;
        }
        if c == '_'
            && let Some(len) = subscript_run(&chars, i)
        {
            // A single-letter word before the underscore becomes math too.
            if let Some(Seg::Text(t)) = segs.last_mut() {
                let mut it = t.chars().rev();
                if let (Some(l), next) = (it.next(), it.next())
                    && l.is_ascii_alphabetic()
                    && next.is_none_or(|n| !n.is_ascii_alphanumeric() && n != '\\')
                {
                    t.pop();
                    if t.is_empty() {
                        segs.pop();
                    }
                    push_math(&mut segs, &l.to_string());
                }
            }
            let sub: String = chars[i + 1..i + 1 + len]
                .iter()
                .map(|&c| match unicode_math(c) {
                    Some(m) => format!("{{{m}}}"),
                    None => c.to_string(),
                })
                .collect();
            push_math(&mut segs, &format!("_{{{sub}}}"));
            i += 1 + len;
            continue;
        }
        match c {
            '\\' => push_text(&mut segs, r"\textbackslash{}"),
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => push_text(&mut segs, &format!("\\{c}")),
            '~' => push_text(&mut segs, r"\textasciitilde{}"),
            '^' => push_text(&mut segs, r"\textasciicircum{}"),
            '<' => push_text(&mut segs, r"\textless{}"),
            '>' => push_text(&mut segs, r"\textgreater{}"),
            '|' => push_text(&mut segs, r"\textbar{}"),
            c if c.is_ascii() => push_text(&mut segs, &c.to_string()),
            c => {
                if let Some(t) = text_symbol(c) {
                    push_text(&mut segs, t);
                } else if let Some(m) = unicode_math(c) {
                    push_math(&mut segs, &m);
                } else if let Some((acc, base)) = precomposed_accent(c) {
                    push_math(&mut segs, &format!("{acc}{{{base}}}"));
                } else if matches!(c, 'À'..='ÿ') && c.is_alphabetic() {
                    push_text(&mut segs, &c.to_string());
                } else {
                    push_text(&mut segs, &format!("[U+{:04X}]", c as u32));
                }
            }
        }
        i += 1;
    }
    let mut out = String::with_capacity(s.len() + 16);
    for seg in segs {
        match seg {
            Seg::Text(t) => out.push_str(&t),
            Seg::Math(m) => {
                let _ = write!(out, "${m}$");
            }
        }
    }
    out
}

/// A piece of escaped prose: text, or math to be set between `$`.
enum Seg {
    Text(String),
    Math(String),
}

fn push_text(segs: &mut Vec<Seg>, t: &str) {
    match segs.last_mut() {
        Some(Seg::Text(s)) => s.push_str(t),
        _ => segs.push(Seg::Text(t.to_owned())),
    }
}

/// Appends math, merging with math just before it (`ω` + `_z` → `\omega_{z}`).
fn push_math(segs: &mut Vec<Seg>, m: &str) {
    match segs.last_mut() {
        Some(Seg::Math(s)) => {
            // `\omega` followed by a letter needs a space to stay a command.
            let ends_in_command = s
                .rsplit('\\')
                .next()
                .is_some_and(|w| !w.is_empty() && w.chars().all(|c| c.is_ascii_alphabetic()))
                && s.contains('\\');
            if ends_in_command && m.starts_with(|c: char| c.is_ascii_alphabetic()) {
                s.push(' ');
            }
            s.push_str(m);
        }
        _ => segs.push(Seg::Math(m.to_owned())),
    }
}

/// The length of a subscript after the `_` at `i`: 1 to 4 letters or
/// digits (ASCII or Greek) after a letter, digit, `)` or math character,
/// and followed by neither a letter nor a digit nor another `_`.
fn subscript_run(chars: &[char], i: usize) -> Option<usize> {
    let prev = *chars.get(i.checked_sub(1)?)?;
    if !(prev.is_alphanumeric() || prev == ')' || combining_accent(prev).is_some()) {
        return None;
    }
    let ok = |c: char| c.is_ascii_alphanumeric() || greek_char(c).is_some();
    let len = chars[i + 1..].iter().take_while(|&&c| ok(c)).count();
    let next = chars.get(i + 1 + len).copied();
    // A word before the underscore (`dt_rel`) is code, not a subscript.
    let word_start = chars[..i]
        .iter()
        .rev()
        .take_while(|c| c.is_alphanumeric() || combining_accent(**c).is_some())
        .filter(|c| combining_accent(**c).is_none())
        .count();
    let single = prev == ')' || word_start <= 1;
    ((1..=4).contains(&len) && single && next.is_none_or(|n| !n.is_alphanumeric() && n != '_'))
        .then_some(len)
}

/// A letter as math: itself when ASCII, else its code point as text.
fn math_letter(c: char) -> String {
    if c.is_ascii_alphanumeric() {
        c.to_string()
    } else {
        format!(r"\text{{[U+{:04X}]}}", c as u32)
    }
}

/// Combining accents over the preceding letter: dots of time derivatives,
/// hat, bar, tilde, vector arrow.
fn combining_accent(c: char) -> Option<&'static str> {
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
fn precomposed_accent(c: char) -> Option<(&'static str, char)> {
    const DOT: &[(char, char)] = &[
        ('Ḃ', 'B'),
        ('ḃ', 'b'),
        ('Ċ', 'C'),
        ('ċ', 'c'),
        ('Ḋ', 'D'),
        ('ḋ', 'd'),
        ('Ė', 'E'),
        ('ė', 'e'),
        ('Ḟ', 'F'),
        ('ḟ', 'f'),
        ('Ġ', 'G'),
        ('ġ', 'g'),
        ('Ḣ', 'H'),
        ('ḣ', 'h'),
        ('İ', 'I'),
        ('Ṁ', 'M'),
        ('ṁ', 'm'),
        ('Ṅ', 'N'),
        ('ṅ', 'n'),
        ('Ȯ', 'O'),
        ('ȯ', 'o'),
        ('Ṗ', 'P'),
        ('ṗ', 'p'),
        ('Ṙ', 'R'),
        ('ṙ', 'r'),
        ('Ṡ', 'S'),
        ('ṡ', 's'),
        ('Ṫ', 'T'),
        ('ṫ', 't'),
        ('Ẇ', 'W'),
        ('ẇ', 'w'),
        ('Ẋ', 'X'),
        ('ẋ', 'x'),
        ('Ẏ', 'Y'),
        ('ẏ', 'y'),
        ('Ż', 'Z'),
        ('ż', 'z'),
    ];
    const DDOT: &[(char, char)] = &[
        ('Ḧ', 'H'),
        ('ḧ', 'h'),
        ('ẗ', 't'),
        ('Ẅ', 'W'),
        ('ẅ', 'w'),
        ('Ẍ', 'X'),
        ('ẍ', 'x'),
    ];
    const BAR: &[(char, char)] = &[
        ('Ā', 'A'),
        ('ā', 'a'),
        ('Ē', 'E'),
        ('ē', 'e'),
        ('Ī', 'I'),
        ('ī', 'i'),
        ('Ō', 'O'),
        ('ō', 'o'),
        ('Ū', 'U'),
        ('ū', 'u'),
        ('Ȳ', 'Y'),
        ('ȳ', 'y'),
    ];
    if let Some(&(_, b)) = DOT.iter().find(|t| t.0 == c) {
        return Some((r"\dot", b));
    }
    if let Some(&(_, b)) = BAR.iter().find(|t| t.0 == c) {
        return Some((r"\bar", b));
    }
    DDOT.iter().find(|t| t.0 == c).map(|&(_, b)| (r"\ddot", b))
}

/// Typographic punctuation and text symbols, as text.
fn text_symbol(c: char) -> Option<&'static str> {
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

fn greek_char(c: char) -> Option<&'static str> {
    const T: &[(char, &str)] = &[
        ('α', r"\alpha"),
        ('β', r"\beta"),
        ('γ', r"\gamma"),
        ('δ', r"\delta"),
        ('ε', r"\varepsilon"),
        ('ϵ', r"\epsilon"),
        ('ζ', r"\zeta"),
        ('η', r"\eta"),
        ('θ', r"\theta"),
        ('ϑ', r"\vartheta"),
        ('ι', r"\iota"),
        ('κ', r"\kappa"),
        ('ϰ', r"\varkappa"),
        ('λ', r"\lambda"),
        ('μ', r"\mu"),
        ('µ', r"\mu"),
        ('ν', r"\nu"),
        ('ξ', r"\xi"),
        ('ο', "o"),
        ('π', r"\pi"),
        ('ϖ', r"\varpi"),
        ('ρ', r"\rho"),
        ('ϱ', r"\varrho"),
        ('σ', r"\sigma"),
        ('ς', r"\varsigma"),
        ('τ', r"\tau"),
        ('υ', r"\upsilon"),
        ('φ', r"\phi"),
        ('ϕ', r"\phi"),
        ('χ', r"\chi"),
        ('ψ', r"\psi"),
        ('ω', r"\omega"),
        ('Α', "A"),
        ('Β', "B"),
        ('Γ', r"\Gamma"),
        ('Δ', r"\Delta"),
        ('Ε', "E"),
        ('Ζ', "Z"),
        ('Η', "H"),
        ('Θ', r"\Theta"),
        ('Ι', "I"),
        ('Κ', "K"),
        ('Λ', r"\Lambda"),
        ('Μ', "M"),
        ('Ν', "N"),
        ('Ξ', r"\Xi"),
        ('Ο', "O"),
        ('Π', r"\Pi"),
        ('Ρ', "P"),
        ('Σ', r"\Sigma"),
        ('Τ', "T"),
        ('Υ', r"\Upsilon"),
        ('Φ', r"\Phi"),
        ('Χ', "X"),
        ('Ψ', r"\Psi"),
        ('Ω', r"\Omega"),
    ];
    T.iter().find(|t| t.0 == c).map(|t| t.1)
}

/// The LaTeX math for a Unicode character that belongs in math: Greek
/// letters, operators and relations, arrows, primes, super- and subscripts.
/// `None` for characters that are text.
pub fn unicode_math(c: char) -> Option<String> {
    if let Some(g) = greek_char(c) {
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

/// The `align*` block of one step.
pub fn latex_step(s: &Step) -> String {
    let mut o = String::from("\\begin{align*}\n");
    let lines: Vec<String> = s
        .components
        .iter()
        .map(|(c, e)| format!("  {} &= {}", step_lhs_latex(s, c), print::latex(e)))
        .collect();
    o.push_str(&lines.join(" \\\\\n"));
    o.push_str("\n\\end{align*}\n");
    o
}

fn latex(d: &Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "% {} — generated by hdot from {}", d.title, d.path);
    for s in d.steps.iter().filter(|s| s.show) {
        if !s.doc.is_empty() {
            let _ = writeln!(o, "% {}", s.doc);
        }
        o.push_str(&latex_step(s));
    }
    o
}

fn markdown(d: &Derivation) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "## {}\n", d.title);
    let _ = writeln!(o, "*Source:* {}  ", d.source);
    let _ = writeln!(o, "*File:* `{}`\n", d.path);
    if !d.summary.is_empty() {
        let _ = writeln!(o, "{}\n", d.summary.trim());
    }
    if !d.assumptions.is_empty() {
        let _ = writeln!(o, "**Assumptions.**\n");
        for a in &d.assumptions {
            let _ = writeln!(o, "- {a}");
        }
        o.push('\n');
    }
    for s in d.steps.iter().filter(|s| s.show) {
        let _ = writeln!(
            o,
            "**{}** = `{}`{}\n",
            s.name,
            s.formula,
            if s.doc.is_empty() {
                String::new()
            } else {
                format!(" — {}", s.doc)
            }
        );
        let lines: Vec<String> = s
            .components
            .iter()
            .map(|(c, e)| format!("{} &= {}", step_lhs_latex(s, c), print::latex(e)))
            .collect();
        let _ = writeln!(
            o,
            "$$\n\\begin{{aligned}}\n{}\n\\end{{aligned}}\n$$\n",
            lines.join(" \\\\\n")
        );
        if !s.checks.is_empty() {
            if s.checks.iter().all(|c| c.holds()) {
                let _ = writeln!(o, "✓ equals the expected (textbook) form.\n");
            } else {
                let _ = writeln!(o, "✗ does **not** equal the expected form.\n");
            }
        }
    }
    o
}

/// A Python identifier for a symbol name that cannot clash with the
/// names the export itself uses.
fn py_var(name: &str) -> String {
    const RESERVED: &[&str] = &[
        "t",
        "sin",
        "cos",
        "Eq",
        "Symbol",
        "Function",
        "Rational",
        "Integer",
        "equations",
        "expected",
        "abbreviations",
        "False",
        "None",
        "True",
        "and",
        "as",
        "assert",
        "async",
        "await",
        "break",
        "class",
        "continue",
        "def",
        "del",
        "elif",
        "else",
        "except",
        "finally",
        "for",
        "from",
        "global",
        "if",
        "import",
        "in",
        "is",
        "lambda",
        "nonlocal",
        "not",
        "or",
        "pass",
        "raise",
        "return",
        "try",
        "while",
        "with",
        "yield",
        "sympy",
        "labels",
    ];
    if RESERVED.contains(&name) {
        format!("{name}_")
    } else {
        name.to_owned()
    }
}

fn sympy(d: &Derivation) -> String {
    let var = |n: &str| py_var(n);
    let style = Sympy { var: &var };
    let mut o = String::new();
    let _ = writeln!(o, "# {} — generated by hdot from {}", d.title, d.path);
    let _ = writeln!(o, "# Source: {}", d.source);
    let _ = writeln!(
        o,
        "# Symbols are built by name with Symbol(...); functions of time are Function(...)(t)."
    );
    let _ = writeln!(
        o,
        "from sympy import Eq, Function, Integer, Rational, Symbol, cos, sin\n"
    );
    let _ = writeln!(o, "t = Symbol('t')");
    for n in d.symbols.names() {
        match d.symbols.get(n) {
            Some(Decl::Constant) => {
                let _ = writeln!(o, "{} = Symbol('{n}')", var(n));
            }
            Some(Decl::Time | Decl::Abbrev(_)) => {
                let _ = writeln!(o, "{} = Function('{n}')(t)", var(n));
            }
            None => {}
        }
    }
    let _ = writeln!(o, "\n# Abbreviations: name -> what it stands for.");
    let _ = writeln!(o, "abbreviations = {{");
    for a in &d.abbreviations {
        let _ = writeln!(
            o,
            "    {}: {},",
            var(&a.name),
            print::print(&Expr::from_poly(&a.definition), &style)
        );
    }
    let _ = writeln!(o, "}}\n");
    let mut eqs = Vec::new();
    let mut exps = Vec::new();
    let mut labels = Vec::new();
    for s in d.steps.iter().filter(|s| s.show) {
        // A Python string: primes (time derivatives) become `dot`.
        let base: String = s
            .label
            .split_whitespace()
            .collect::<String>()
            .replace('\'', "dot");
        // Solved values are equations for their unknowns: θ̈ = … has the
        // left side theta.diff(t, 2).
        let unknowns = match &s.value {
            Value::List { labels, .. } if !labels.is_empty() => labels.clone(),
            _ => Vec::new(),
        };
        for (k, (c, e)) in s.components.iter().enumerate() {
            let lhs = match unknowns.get(k) {
                Some(&a) => {
                    let mut x = Expr::new();
                    x.push(crate::expr::Node::Atom(a));
                    print::print(&x, &style)
                }
                None if c.is_empty() => format!("Symbol('{base}')"),
                None => format!("Symbol('{base}_{}')", c.replace('\'', "dot")),
            };
            labels.push(format!("'{}.{}'", s.name, c.replace('\'', "\\'")));
            eqs.push(format!("    Eq({lhs}, {}),", print::print(e, &style)));
            match s.checks.get(k) {
                Some(ch) => exps.push(format!(
                    "    Eq({lhs}, {}),",
                    print::print(&ch.expected, &style)
                )),
                None => exps.push("    None,".into()),
            }
        }
    }
    let _ = writeln!(
        o,
        "# One equation per component of every shown step, in textbook form."
    );
    let _ = writeln!(o, "equations = [\n{}\n]\n", eqs.join("\n"));
    let _ = writeln!(
        o,
        "# The expected (textbook) form of each equation, or None."
    );
    let _ = writeln!(o, "expected = [\n{}\n]\n", exps.join("\n"));
    let _ = writeln!(o, "# step.component of each equation.");
    let _ = writeln!(o, "labels = [{}]", labels.join(", "));
    o
}

/// The JSON document of a derivation, serialised straight from borrowed
/// data (a chain-6 document is 5 MB: building a `serde_json::Value` first
/// would copy all of it). Fields are declared in alphabetical order, the
/// order the documented output has always had.
#[derive(serde::Serialize)]
struct JsonDerivation<'a> {
    all_hold: bool,
    assumptions: &'a [String],
    checks: usize,
    name: &'a str,
    path: &'a str,
    source: &'a str,
    steps: Vec<JsonStep<'a>>,
    summary: &'a str,
    title: &'a str,
}

#[derive(serde::Serialize)]
struct JsonStep<'a> {
    components: Vec<JsonComponent<'a>>,
    doc: &'a str,
    formula: &'a str,
    label: &'a str,
    name: &'a str,
    show: bool,
    value: JsonKind<'a>,
}

#[derive(serde::Serialize)]
struct JsonKind<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    frame: Option<&'a str>,
    kind: &'static str,
}

#[derive(serde::Serialize)]
struct JsonComponent<'a> {
    canonical: String,
    check: Option<JsonCheck<'a>>,
    component: String,
    latex: String,
    source: String,
    terms: usize,
    text: String,
}

#[derive(serde::Serialize)]
struct JsonCheck<'a> {
    difference: String,
    expected: &'a str,
    holds: bool,
}

fn json(d: &Derivation) -> JsonDerivation<'_> {
    let steps = d
        .steps
        .iter()
        .map(|s| {
            let value = match &s.value {
                Value::Scalar(_) => JsonKind {
                    frame: None,
                    kind: "scalar",
                },
                Value::Vector(_, f) => JsonKind {
                    frame: Some(f.as_str()),
                    kind: "vector",
                },
                Value::Matrix(_) => JsonKind {
                    frame: None,
                    kind: "matrix",
                },
                Value::List { .. } => JsonKind {
                    frame: None,
                    kind: "list",
                },
                Value::Array(_) => JsonKind {
                    frame: None,
                    kind: "array",
                },
            };
            let values = s.values();
            let components = s
                .presented()
                .into_iter()
                .enumerate()
                .map(|(k, (component, e))| {
                    let check = s.checks.get(k).map(|ch| JsonCheck {
                        difference: ch.difference.to_source(),
                        expected: &ch.expected_text,
                        holds: ch.holds(),
                    });
                    // The presented form expanded. Presentation is exact, so
                    // without folded abbreviations that is the value itself
                    // (tests/sym/presentation.rs checks it for every file).
                    let (canonical, terms) = if s.presentation.fold.is_empty() {
                        (values[k].to_source(), values[k].len())
                    } else {
                        let p = e.to_poly();
                        (p.to_source(), p.len())
                    };
                    JsonComponent {
                        canonical,
                        check,
                        component,
                        latex: print::print(&e, &Latex),
                        source: e.to_string(),
                        terms,
                        text: print::print(&e, &Unicode),
                    }
                })
                .collect();
            JsonStep {
                components,
                doc: &s.doc,
                formula: &s.formula,
                label: &s.label,
                name: &s.name,
                show: s.show,
                value,
            }
        })
        .collect();
    JsonDerivation {
        all_hold: d.all_hold(),
        assumptions: &d.assumptions,
        checks: d.check_count(),
        name: &d.name,
        path: &d.path,
        source: &d.source,
        steps,
        summary: &d.summary,
        title: &d.title,
    }
}
