//! Words the backends write around the mathematics: a step's title, the
//! sentence for a relation that holds identically, sentences with a
//! capital and a full stop, code and anchors.

use crate::document::StepBlock;
use crate::escape;
use crate::prose;

/// A step's title in LaTeX (also Markdown's math): `Step 3: $\\Sigma M$`,
/// the label as mathematics; only `Step 3` for a step labelled `0` (its
/// equations read `… = 0`). Number 0 gives the title of a slide without
/// a doc: the label alone.
pub(super) fn step_title(n: usize, st: &StepBlock) -> String {
    if st.heading.is_zero() {
        if n == 0 {
            "Equation".to_owned()
        } else {
            format!("Step {n}")
        }
    } else if n == 0 {
        format!("${}$", st.heading.latex())
    } else {
        format!("Step {n}: ${}$", st.heading.latex())
    }
}

/// The sentence that replaces `0 = 0` for a step whose result vanishes
/// identically, as prose of the backend.
pub(super) fn vanishes_text(markdown: bool) -> String {
    let text = capitalise(crate::document::VANISHES);
    if markdown {
        format!("*{}.*", prose::markdown(&text))
    } else {
        format!("\\emph{{{}.}}", prose::latex(&text))
    }
}

/// Code (a formula as written, a file name) for `\texttt`: every
/// character is kept as it is written, none becomes math.
pub(super) fn latex_code(s: &str) -> String {
    escape::latex(s, escape::Latex::Code)
}

pub(super) fn label_key(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}

/// The text with a capital first letter and a final full stop.
pub(super) fn sentence(s: &str) -> String {
    let s = capitalise(s.trim());
    if s.is_empty() || s.ends_with(['.', '!', '?', ':']) {
        s
    } else {
        format!("{s}.")
    }
}

/// The text with a capital first letter, unless it begins with notation
/// that a capital would change: a function name before its argument
/// (`tan γ = …` stays `tan γ`), or a symbol — a lone letter other than the
/// article `a` (`q stands for q − π`: Q would be another symbol), a Greek
/// letter's name (`theta`, not Θ) or a name with a subscript or digit
/// (`u_1`, `q2`).
pub(super) fn capitalise(s: &str) -> String {
    let first = s
        .split(|c: char| !c.is_ascii_alphabetic())
        .next()
        .unwrap_or("");
    if prose::FUNCTIONS.contains(&first) && s[first.len()..].starts_with(' ') {
        return s.to_owned();
    }
    let word = s.split([' ', ',', ';', ':', '.']).next().unwrap_or("");
    let symbol = (first.len() == 1 && first != "a" && word == first)
        || (first == word && crate::symbols::greek(first).is_some())
        || (word.len() == first.len() + 1 && word.ends_with(|c: char| c.is_ascii_digit()))
        || word[first.len()..].starts_with('_') && !first.is_empty();
    if symbol {
        return s.to_owned();
    }
    let mut cs = s.chars();
    match cs.next() {
        Some(c) if c.is_ascii_lowercase() => c.to_ascii_uppercase().to_string() + cs.as_str(),
        _ => s.to_owned(),
    }
}

/// The sentence after a step some of whose equations are printed by name
/// (`names` as LaTeX math, `terms` their terms in all): where they are
/// defined — under *Coefficients* at the end of the section, or, on a
/// slide, in the notes. As LaTeX prose, or Markdown when `markdown`.
pub(super) fn named_text(names: &str, terms: usize, markdown: bool, slides: bool) -> String {
    let place = if slides {
        "in the notes, as is every entry named here"
    } else if markdown {
        "under *Coefficients* at the end of this section"
    } else {
        "under \\emph{Coefficients} at the end of this section"
    };
    let names = if markdown {
        escape::markdown_math(names)
    } else {
        names.to_owned()
    };
    let verb = if names.contains("allowbreak") {
        "are"
    } else {
        "is"
    };
    format!(
        "Too long to print here ({terms} terms in all), ${names}$ {verb} written by name and defined {place}."
    )
}

/// The sentence that opens a section's *Coefficients*.
pub(super) const COEFFICIENTS_INTRO: &str = "The results written by name in the steps above, \
     each with more than {NAMED} terms (hdot prints a result of that size by name).";

/// [`COEFFICIENTS_INTRO`] with the size.
pub(super) fn coefficients_intro() -> String {
    COEFFICIENTS_INTRO.replace("{NAMED}", &crate::document::NAMED_ABOVE.to_string())
}

#[cfg(test)]
mod tests {
    use super::capitalise;

    #[test]
    fn a_sentence_opening_with_a_symbol_keeps_its_case() {
        for (text, want) in [
            ("q stands for q − π", "q stands for q − π"),
            ("theta is the lean", "theta is the lean"),
            ("u_1 is the spin", "u_1 is the spin"),
            ("q2 is the second angle", "q2 is the second angle"),
            ("tan γ = v/r", "tan γ = v/r"),
            ("a disk rolls", "A disk rolls"),
            ("the lean", "The lean"),
            ("thetas are angles", "Thetas are angles"),
            ("", ""),
        ] {
            assert_eq!(capitalise(text), want, "{text}");
        }
    }
}
