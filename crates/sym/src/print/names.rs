//! Symbol names as the printers write them: a name split into base and
//! subscript, Greek bases, primes, derivative dots and superscripts, in
//! LaTeX and Unicode (the one table of Greek letters is `symbols::GREEK`).

/// The Greek names the printers know (`omega` → ω / `\omega`), in the
/// order of their table.
pub fn greek_names() -> impl Iterator<Item = &'static str> {
    crate::symbols::GREEK.iter().map(|g| g.0)
}

/// Splits a symbol name into its base and subscript: `omega_x` → (`omega`, `x`).
///
/// The first `_` starts the subscript; each further `_` separates one
/// index of it from the next, and the indices print separated by commas
/// (a textbook's A_{c,rate}, I_{B,xx}): `A_c_rate` is `A_{c,rate}` in LaTeX
/// and `A_{c,rate}` in Unicode, braced there because it holds a comma.
pub(crate) fn split_name(name: &str) -> (&str, Option<&str>) {
    match name.split_once('_') {
        Some((b, s)) if !b.is_empty() && !s.is_empty() => (b, Some(s)),
        _ => (name, None),
    }
}

/// A base name written as a single capital followed by `p` means a prime:
/// `Ip` is I′ (the transverse moment of an axisymmetric body).
pub(crate) fn primed_base(base: &str) -> Option<char> {
    let mut cs = base.chars();
    match (cs.next(), cs.next(), cs.next()) {
        (Some(c), Some('p'), None) if c.is_ascii_uppercase() => Some(c),
        _ => None,
    }
}

/// The LaTeX of a base name (no derivative marks); `xbar` is x̄.
fn latex_base(base: &str) -> String {
    if let Some(inner) = base.strip_suffix("bar").filter(|b| !b.is_empty()) {
        return format!(r"\bar{{{}}}", latex_base(inner));
    }
    if let Some((latex, _)) = crate::symbols::greek(base) {
        return latex.to_owned();
    }
    if let Some(c) = primed_base(base) {
        return format!("{c}'");
    }
    // A name is letters and digits; one outside ASCII is written by the
    // table of Unicode in LaTeX (a Greek letter, an accented Latin letter),
    // never raw, so that pdflatex can typeset it.
    let mut cs = base.chars();
    match (cs.next(), cs.next()) {
        (Some(c), None) => crate::escape::latex_math_char(c),
        _ => format!(r"\mathrm{{{}}}", crate::escape::latex_math(base)),
    }
}

fn unicode_base(base: &str) -> String {
    if let Some(inner) = base.strip_suffix("bar").filter(|b| !b.is_empty()) {
        return format!("{}\u{304}", unicode_base(inner));
    }
    if let Some((_, c)) = crate::symbols::greek(base) {
        return c.to_string();
    }
    if let Some(c) = primed_base(base) {
        return format!("{c}′");
    }
    base.to_owned()
}

fn latex_sub(sub: &str) -> String {
    let parts: Vec<String> = sub
        .split('_')
        .map(|p| {
            crate::symbols::greek(p)
                .map_or_else(|| crate::escape::latex_math(p), |g| g.0.to_owned())
        })
        .collect();
    let s = parts.join(",");
    if s.chars().count() == 1 {
        format!("_{s}")
    } else {
        format!("_{{{s}}}")
    }
}

/// LaTeX for a symbol name with `order` time derivatives: `\dot{\omega}_x`.
pub fn latex_symbol(name: &str, order: u32) -> String {
    let (base, sub) = split_name(name);
    let b = latex_base(base);
    let b = match order {
        0 => b,
        1 => format!(r"\dot{{{b}}}"),
        2 => format!(r"\ddot{{{b}}}"),
        3 => format!(r"\dddot{{{b}}}"),
        4 => format!(r"\ddddot{{{b}}}"),
        n => format!("{{{b}}}^{{({n})}}"),
    };
    match sub {
        Some(s) => format!("{b}{}", latex_sub(s)),
        None => b,
    }
}

/// Unicode for a symbol name with `order` time derivatives: `ω̇_x`.
pub fn unicode_symbol(name: &str, order: u32) -> String {
    let (base, sub) = split_name(name);
    let mut b = unicode_base(base);
    match order {
        0 => {}
        1 => b.push('\u{307}'),
        2 => b.push('\u{308}'),
        3 => b.push('\u{20DB}'),
        4 => b.push('\u{20DC}'),
        n => b.push_str(&format!("⁽{}⁾", superscript(n))),
    }
    match sub {
        // One index as it is (ω_x, I_xy); several, separated by commas,
        // in braces: `A_c_rate` is A_{c,rate}, never `A_c,rate`.
        Some(s) if s.contains('_') => {
            let s: Vec<String> = s.split('_').map(unicode_base).collect();
            format!("{b}_{{{}}}", s.join(","))
        }
        Some(s) => format!("{b}_{}", unicode_base(s)),
        None => b,
    }
}

pub(crate) fn superscript(n: u32) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}
