//! The HTML backend: the lecture notes as a static site ([`html_site`]) —
//! an index with the contents in the course's order and one page per
//! derivation, with a stylesheet for screen and print — every equation
//! as MathML from the expression tree (`mathml.rs`), carrying its LaTeX
//! as `alttext`; no script, nothing fetched from the network. Every
//! string of a file goes through [`escape::html`].
//!
//! Each page states how many `<math>` elements it holds, computed from
//! the document model ([`section_math_count`]), as `data-equations` on
//! its `<main>`, so a browser test can check that every equation is
//! rendered.

use std::fmt::Write;

use super::layout::{
    failure_lines, omega_inline, step_lines, symbol_list, write_coefficient_lines,
};
use super::mathml::{self, Row};
use super::words::{capitalise, coefficients_intro, label_key, sentence};
use super::{LINE_BUDGET, has_chapters};
use crate::document::{Backend, Document, Lhs, Section, StepBlock, Verdict};
use crate::escape;
use crate::label::latex_name;
use crate::print;
use crate::prose;

/// Estimated width (characters of math, [`mathml::width`]) of a frame's
/// angular velocity written as a row `(ω_x, ω_y, ω_z)` beyond which it is
/// written as a column: what fits a phone's line (400 px) in the list of
/// frames beside the frame's name.
const FRAME_ROW_BUDGET: f32 = 30.0;

/// The HTML backend.
pub struct Html;

impl Backend for Html {
    fn name(&self) -> &'static str {
        "html"
    }

    fn section(&self, s: &Section) -> String {
        let mut o = String::new();
        html_section(&mut o, "", s, &StepIds::new(s));
        o
    }

    fn document(&self, _: &Document) -> Option<String> {
        // The notes are a site of several pages: see `html_site`.
        None
    }
}

/// The stylesheet of the site (screen and print).
pub const HTML_CSS: &str = include_str!("html.css");

/// File name of the stylesheet.
pub const HTML_CSS_FILE: &str = "hdot-notes.css";

/// File name of the index page.
pub const HTML_INDEX: &str = "index.html";

/// The `generator` of every page: a folder whose `index.html` names it
/// is hdot's output (and may be written over).
pub const HTML_GENERATOR: &str = "hdot notes --html";

/// One file of the site: its name and content.
pub struct SitePage {
    /// File name (no folder).
    pub file: String,
    /// The text.
    pub text: String,
    /// How many `<math>` elements the page holds, from the document model.
    pub equations: usize,
}

/// The file name of each section's page, in document order: its name as
/// an anchor key, made unique.
fn page_files(doc: &Document) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for s in doc.chapters.iter().flat_map(|c| &c.sections) {
        let key = label_key(&s.name).to_ascii_lowercase();
        let key = if key.is_empty() || key == "index" {
            format!("d-{key}")
        } else {
            key
        };
        let mut file = format!("{key}.html");
        let mut n = 2;
        while out.contains(&file) {
            file = format!("{key}-{n}.html");
            n += 1;
        }
        out.push(file);
    }
    out
}

/// The notes as a static site: `index.html`, one page per derivation and
/// the stylesheet.
pub fn html_site(doc: &Document) -> Vec<SitePage> {
    let files = page_files(doc);
    let chapters = has_chapters(doc);
    let mut pages = vec![SitePage {
        file: HTML_INDEX.to_owned(),
        text: index_page(doc, &files),
        equations: 0,
    }];
    let sections: Vec<(usize, usize, &Section)> = doc
        .chapters
        .iter()
        .enumerate()
        .flat_map(|(i, c)| c.sections.iter().enumerate().map(move |(k, s)| (i, k, s)))
        .collect();
    for (n, &(i, k, s)) in sections.iter().enumerate() {
        let number = if chapters {
            format!("{}.{}", i + 1, k + 1)
        } else {
            format!("{}.", k + 1)
        };
        let mut body = String::new();
        let link = |m: Option<usize>, rel: &str, what: &str| match m {
            Some(m) => format!(
                "<a rel=\"{rel}\" href=\"{}\">{what}: {}</a>",
                escape::html(&files[m]),
                plain(&sections[m].2.title)
            ),
            None => String::new(),
        };
        let nav = format!(
            "<nav class=\"pages\"><span class=\"prev\">{}</span><a href=\"{HTML_INDEX}\">Contents</a>\
             <span class=\"next\">{}</span></nav>\n",
            link(n.checked_sub(1), "prev", "Previous"),
            link(Some(n + 1).filter(|&m| m < sections.len()), "next", "Next")
        );
        body.push_str(&nav);
        let equations = section_math_count(s);
        let _ = writeln!(body, "<main data-equations=\"{equations}\">");
        if chapters {
            let _ = writeln!(
                body,
                "<p class=\"chapter\">Chapter {}: {}</p>",
                i + 1,
                prose_html(&doc.chapters[i].title)
            );
        }
        html_section(&mut body, &number, s, &StepIds::new(s));
        body.push_str("</main>\n");
        body.push_str(&nav);
        pages.push(SitePage {
            file: files[n].clone(),
            text: page(
                &format!("{} — {}", plain(&s.title), plain(&doc.title)),
                &body,
            ),
            equations,
        });
    }
    pages.push(SitePage {
        file: HTML_CSS_FILE.to_owned(),
        text: HTML_CSS.to_owned(),
        equations: 0,
    });
    pages
}

/// A whole page around `body`.
fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <meta name=\"generator\" content=\"{HTML_GENERATOR}\">\n<title>{title}</title>\n\
         <link rel=\"stylesheet\" href=\"{HTML_CSS_FILE}\">\n</head>\n<body>\n{body}\
         <footer>Generated by <code>hdot notes --html</code> from the derivation files; \
         do not edit.</footer>\n</body>\n</html>\n"
    )
}

/// The index: title, author, introduction and the contents.
fn index_page(doc: &Document, files: &[String]) -> String {
    let mut o = String::from("<main data-equations=\"0\">\n");
    let _ = writeln!(o, "<h1>{}</h1>", prose_html(&doc.title));
    if !doc.author.is_empty() {
        let _ = writeln!(o, "<p class=\"author\">{}</p>", prose_html(&doc.author));
    }
    if !doc.intro.trim().is_empty() {
        let _ = writeln!(o, "<p>{}</p>", prose_html(doc.intro.trim()));
    }
    let chapters = has_chapters(doc);
    o.push_str("<nav class=\"contents\" aria-label=\"contents\">\n<h2>Contents</h2>\n<ol>\n");
    let mut n = 0;
    for c in &doc.chapters {
        if chapters {
            let _ = write!(
                o,
                "<li><span class=\"chapter\">{}</span>",
                prose_html(&c.title)
            );
            if !c.intro.trim().is_empty() {
                let _ = write!(o, "<p>{}</p>", prose_html(c.intro.trim()));
            }
            o.push_str("\n<ol>\n");
        }
        for s in &c.sections {
            let _ = writeln!(
                o,
                "<li><a href=\"{}\">{}</a></li>",
                escape::html(&files[n]),
                prose_html(&s.title)
            );
            n += 1;
        }
        if chapters {
            o.push_str("</ol></li>\n");
        }
    }
    o.push_str("</ol>\n</nav>\n</main>\n");
    page(&plain(&doc.title), &o)
}

/// Prose as HTML: its text escaped, and each formula [`prose::pieces`]
/// finds in it (the notation as written between the text pieces, without
/// `$`) set in italics with its `_` subscripts and `^` superscripts as
/// such, escaped too.
fn prose_html(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 16);
    let mut rest = s;
    for p in prose::pieces(s) {
        let prose::Piece::Text(t) = p else { continue };
        let Some(at) = rest.find(t.as_str()) else {
            // Not found as written: the rest as plain text.
            o.push_str(&escape::html(&prose::unicode(rest)));
            return o;
        };
        formula_html(&mut o, &rest[..at]);
        o.push_str(&escape::html(&t));
        rest = &rest[at + t.len()..];
    }
    formula_html(&mut o, rest);
    o
}

/// Notation of prose (`r_G × m g`, `$T = ½ m v^2$`) as italic HTML.
fn formula_html(o: &mut String, notation: &str) {
    let f = notation.replace('$', "");
    let f = f.trim();
    if f.is_empty() {
        o.push_str(&escape::html(notation));
        return;
    }
    let lead = &notation[..notation.len() - notation.trim_start().len()];
    let trail = &notation[notation.trim_end().len()..];
    o.push_str(&escape::html(&lead.replace('$', "")));
    o.push_str("<span class=\"formula\">");
    let mut chars = f.chars().peekable();
    while let Some(c) = chars.next() {
        let script = match c {
            '_' => "sub",
            '^' => "sup",
            _ => "",
        };
        let run: String = if script.is_empty() {
            String::new()
        } else {
            let mut r = String::new();
            while let Some(&n) = chars.peek().filter(|n| n.is_alphanumeric()) {
                r.push(n);
                chars.next();
            }
            r
        };
        if run.is_empty() {
            o.push_str(&escape::html(&c.to_string()));
        } else {
            let _ = write!(o, "<{script}>{}</{script}>", escape::html(&run));
        }
    }
    o.push_str("</span>");
    o.push_str(&escape::html(&trail.replace('$', "")));
}

/// Prose as plain text for a `<title>` or a link.
fn plain(s: &str) -> String {
    escape::html(&prose::unicode(s))
}

/// Code (a formula as written, a file name).
fn code(s: &str) -> String {
    format!("<code>{}</code>", escape::html(s))
}

/// The anchor of each step of a section, unique within it.
struct StepIds(Vec<String>);

impl StepIds {
    fn new(s: &Section) -> StepIds {
        let mut out: Vec<String> = Vec::new();
        for st in &s.steps {
            let base = format!("step-{}", label_key(&st.name));
            let mut id = base.clone();
            let mut n = 2;
            while out.contains(&id) {
                id = format!("{base}-{n}");
                n += 1;
            }
            out.push(id);
        }
        StepIds(out)
    }
}

/// How many `<math>` elements [`html_section`] writes for `s`, counted
/// from the document model: one for each list of symbols, abbreviation
/// and frame, one for each step's heading that is a label, one for each
/// step's result that does not vanish, one for each failed expectation.
pub fn section_math_count(s: &Section) -> usize {
    let lists = usize::from(!s.constants.is_empty()) + usize::from(!s.time.is_empty());
    let steps: usize = s
        .steps
        .iter()
        .map(|st| {
            usize::from(!st.heading.is_zero())
                + usize::from(!st.vanishes() && has_block(st))
                + usize::from(matches!(st.verdict, Verdict::Fails(_)))
        })
        .sum();
    let coefficients = usize::from(defined_on_page(s));
    lists + s.abbreviations.len() + s.frames.len() + steps + coefficients
}

/// The shape of a step's result set as a matrix: rows and columns.
fn matrix_shape(st: &StepBlock) -> Option<(usize, usize)> {
    st.shape.filter(|(n, m)| {
        n * m == st.equations.len() && n * m > 1 && matches!(st.heading, Lhs::Label(..))
    })
}

/// Whether a step that does not vanish shows its result: not when every
/// equation is written by name and the result is not a matrix (whose
/// names are shown).
fn has_block(st: &StepBlock) -> bool {
    !st.has_named() || matrix_shape(st).is_some() || (0..st.equations.len()).any(|k| !st.named(k))
}

/// A list of symbol names as inline math.
fn symbols_math(names: &[String]) -> String {
    let body: Vec<String> = names.iter().map(|n| mathml::name(n, 0)).collect();
    mathml::math(&body.join("<mo>,</mo>"), &symbol_list(names), false)
}

fn doc_suffix(doc: &str) -> String {
    if doc.is_empty() {
        String::new()
    } else {
        format!(" — {}", prose_html(doc))
    }
}

/// One derivation: its heading, what is assumed, then every step.
fn html_section(o: &mut String, number: &str, s: &Section, ids: &StepIds) {
    let id = escape::html(&label_key(&s.name).to_ascii_lowercase());
    let number = if number.is_empty() {
        String::new()
    } else {
        format!("<span class=\"number\">{number}</span> ")
    };
    let _ = writeln!(
        o,
        "<article class=\"derivation\" id=\"{id}\">\n<h1>{number}{}</h1>",
        prose_html(&s.title)
    );
    let _ = writeln!(
        o,
        "<p class=\"source\"><b>Source:</b> {}<br><b>File:</b> {}</p>",
        prose_html(&s.source),
        code(&s.path)
    );
    if !s.summary.is_empty() {
        let _ = writeln!(o, "<p class=\"summary\">{}</p>", prose_html(&s.summary));
    }
    let _ = writeln!(
        o,
        "<h2 id=\"{id}-assumed\">What is assumed</h2>\n<ul class=\"assumed\">"
    );
    for a in &s.assumptions {
        let _ = writeln!(o, "<li>{}</li>", prose_html(a));
    }
    if !s.constants.is_empty() {
        let _ = writeln!(o, "<li>Constants: {}.</li>", symbols_math(&s.constants));
    }
    if !s.time.is_empty() {
        let _ = writeln!(o, "<li>Functions of time: {}.</li>", symbols_math(&s.time));
    }
    for (name, def, doc) in &s.abbreviations {
        let body = format!("{}<mo>=</mo>{}", mathml::name(name, 0), mathml::expr(def));
        let latex = format!("{} = {}", latex_name(name, 0), print::latex(def));
        let _ = writeln!(
            o,
            "<li>Abbreviation: {}{}</li>",
            mathml::math(&body, &latex, false),
            doc_suffix(doc)
        );
    }
    if !s.frames.is_empty() {
        let _ = writeln!(
            o,
            "<li>Frames, each with its angular velocity Ω relative to the inertial frame \
             <i>N</i>, in the frame's own axes:<ul>"
        );
        for f in &s.frames {
            let parent = match &f.parent {
                Some(p) => format!(" (turned from <i>{}</i>)", escape::html(p)),
                None => String::new(),
            };
            let comps: Vec<String> = f.omega.iter().map(|e| mathml::expr(&e.rhs)).collect();
            // Components that fit a phone's line as a row, or else a column
            // (an inline equation cannot break: it would scroll).
            let row = format!(
                "<mrow><mo>(</mo>{}<mo>)</mo></mrow>",
                comps.join("<mo>,</mo>")
            );
            let value = if mathml::width(&row) <= FRAME_ROW_BUDGET {
                row
            } else {
                mathml::matrix(&comps, 1)
            };
            let body = format!(
                "<msub><mi mathvariant=\"normal\">Ω</mi>{}</msub><mo>=</mo>{value}",
                mathml::name(&f.name, 0),
            );
            let latex = format!(
                r"\Omega_{{{}}} = {}",
                latex_name(&f.name, 0),
                omega_inline(f)
            );
            let _ = writeln!(
                o,
                "<li><i>{}</i>, axes <i>{}</i>{parent}: {}{}</li>",
                escape::html(&f.name),
                escape::html(&f.axes.join(", ")),
                mathml::math(&body, &latex, false),
                doc_suffix(&f.doc)
            );
        }
        o.push_str("</ul></li>\n");
    }
    o.push_str("</ul>\n");
    let _ = writeln!(o, "<h2 id=\"{id}-steps\">Steps</h2>");
    for (k, st) in s.steps.iter().enumerate() {
        step_html(o, k + 1, st, &ids.0[k]);
    }
    coefficients_html(o, s, &id);
    o.push_str("</article>\n");
}

/// One step: its heading (an anchor), what it does, the formula as
/// written, the result and the verdict.
fn step_html(o: &mut String, n: usize, st: &StepBlock, id: &str) {
    let heading = if st.heading.is_zero() {
        String::new()
    } else {
        format!(
            ": {}",
            mathml::math(&mathml::lhs(&st.heading), &st.heading.latex(), false)
        )
    };
    let _ = writeln!(
        o,
        "<section class=\"step\" id=\"{id}\">\n<h3><a href=\"#{id}\">Step {n}</a>{heading}</h3>"
    );
    if !st.doc.trim().is_empty() {
        let _ = writeln!(o, "<p>{}</p>", prose_html(&sentence(&st.doc)));
    }
    let frame = st
        .frame
        .as_ref()
        .map(|f| format!(", components in frame <i>{}</i>", escape::html(f)))
        .unwrap_or_default();
    let _ = writeln!(
        o,
        "<p class=\"written\">Written in the file as {}{frame}.</p>",
        code(&st.formula)
    );
    if st.vanishes() {
        let _ = writeln!(
            o,
            "<p><em>{}</em></p>",
            escape::html(&sentence(crate::document::VANISHES))
        );
    } else if has_block(st) {
        let latex = format!(
            "\\begin{{aligned}}\n{}\n\\end{{aligned}}",
            step_lines(st, LINE_BUDGET)
        );
        let _ = writeln!(
            o,
            "<div class=\"equation\">{}</div>",
            mathml::math(&step_body(st), &latex, true)
        );
    }
    if let Some(text) = named_prose(st) {
        let _ = writeln!(o, "<p class=\"named\">{}</p>", prose_html(&text));
    }
    if !st.condition.is_empty() {
        let _ = writeln!(
            o,
            "<p class=\"condition\">(for {})</p>",
            prose_html(&st.condition)
        );
    }
    match &st.verdict {
        Verdict::NoExpectation => {
            let _ = writeln!(
                o,
                "<p class=\"verdict\"><em>{}</em></p>",
                sentence(Verdict::NONE)
            );
        }
        Verdict::Holds => {
            let _ = writeln!(
                o,
                "<p class=\"verdict holds\">✓ {}</p>",
                sentence(Verdict::HOLDS)
            );
        }
        Verdict::Fails(f) => {
            let _ = writeln!(
                o,
                "<p class=\"verdict fails\">✗ <strong>{}</strong> ({}):</p>",
                capitalise(Verdict::FAILS),
                Verdict::fails_shown("−")
            );
            let mut rows: Vec<Row> = Vec::new();
            for (exp, diff) in f {
                let lhs = format!(
                    "<msup>{}<mtext>expected</mtext></msup>",
                    mathml::lhs(&exp.lhs)
                );
                rows.extend(mathml::equation_rows(&lhs, &exp.rhs, LINE_BUDGET));
                rows.extend(mathml::equation_rows(
                    "<mtext>difference</mtext>",
                    &diff.rhs,
                    LINE_BUDGET,
                ));
            }
            let latex = format!(
                "\\begin{{aligned}}\n{}\n\\end{{aligned}}",
                failure_lines(f, LINE_BUDGET)
            );
            let _ = writeln!(
                o,
                "<div class=\"equation\">{}</div>",
                mathml::math(&mathml::table(&rows), &latex, true)
            );
        }
    }
    o.push_str("</section>\n");
}

/// The MathML of a step's result: a matrix as a matrix when its columns
/// fit the line, else one equation per component, aligned at `=`.
fn step_body(st: &StepBlock) -> String {
    if let Some((n, m)) = matrix_shape(st) {
        // An entry written by name shows its name; below the diagonal of a
        // symmetric matrix, the name of the entry above it.
        let owner = |k: usize| {
            let (i, j) = (k / m, k % m);
            if st.symmetric && i > j { j * m + i } else { k }
        };
        let entries: Vec<String> = (0..n * m)
            .map(|k| {
                let o = owner(k);
                if st.named(o) {
                    mathml::lhs(&st.equations[o].lhs)
                } else {
                    mathml::expr(&st.equations[k].rhs)
                }
            })
            .collect();
        let lhs = mathml::lhs(&st.heading);
        let columns: f32 = (0..m)
            .map(|j| {
                (0..n)
                    .map(|i| mathml::width(&entries[i * m + j]))
                    .fold(0.0, f32::max)
            })
            .sum::<f32>()
            + 2.0 * m as f32;
        // A matrix with entries written by name is set as a matrix (its
        // box scrolls when it is wider than the line).
        if st.has_named() || columns + mathml::width(&lhs) + 3.0 <= LINE_BUDGET {
            return mathml::table(&[(lhs, format!("<mo>=</mo>{}", mathml::matrix(&entries, m)))]);
        }
    }
    let rows: Vec<Row> = st
        .equations
        .iter()
        .enumerate()
        .filter(|(k, _)| !st.named(*k))
        .flat_map(|(_, e)| mathml::rows(e, LINE_BUDGET))
        .collect();
    mathml::table(&rows)
}

/// The sentence after a step some of whose equations are written by name
/// (their names in Unicode, between `$` signs for [`prose_html`]); `None`
/// when it names none.
fn named_prose(st: &StepBlock) -> Option<String> {
    let ks: Vec<usize> = (0..st.equations.len()).filter(|&k| st.named(k)).collect();
    if ks.is_empty() {
        return None;
    }
    let names: Vec<String> = ks
        .iter()
        .map(|&k| format!("${}$", st.equations[k].lhs.unicode()))
        .collect();
    let terms: usize = ks.iter().map(|&k| st.terms[k]).sum();
    Some(format!(
        "Too long to print here ({terms} terms in all), {} are written by name; see \
         Coefficients at the end of this page.",
        names.join(", ")
    ))
}

/// The terms of the definitions of named coefficients a page holds at
/// most: a term of MathML takes about 250 bytes, and a page of the notes
/// must stay under 2 MB (`scripts/check_pages.py`). Beyond it, the page
/// names each coefficient with its size and refers to the PDF notes and
/// the exports, which define them.
const PAGE_TERMS: usize = 2000;

/// Whether the page of `s` defines its named coefficients: it has some,
/// and they are within [`PAGE_TERMS`].
fn defined_on_page(s: &Section) -> bool {
    let coefficients = s.coefficients();
    !coefficients.is_empty() && coefficients.iter().map(|(_, t)| t).sum::<usize>() <= PAGE_TERMS
}

/// A section's *Coefficients*: the definitions of the results its steps
/// write by name, as one aligned block; or, above [`PAGE_TERMS`], their
/// names and sizes and where they are defined.
fn coefficients_html(o: &mut String, s: &Section, id: &str) {
    let coefficients = s.coefficients();
    if coefficients.is_empty() {
        return;
    }
    let _ = writeln!(o, "<h2 id=\"{id}-coefficients\">Coefficients</h2>");
    let _ = writeln!(o, "<p>{}</p>", escape::html(&coefficients_intro()));
    if !defined_on_page(s) {
        let total: usize = coefficients.iter().map(|(_, t)| t).sum();
        let _ = writeln!(
            o,
            "<p>Their definitions, {total} terms in all, are more than a web page holds: \
             they are in the notes as PDF and Markdown (<code>hdot notes</code>) and in the \
             SymPy and JSON exports (<code>hdot derive {} --format sympy</code>).</p>\n<ul class=\"coefficients\">",
            escape::html(&s.name)
        );
        for (e, terms) in &coefficients {
            let _ = writeln!(
                o,
                "<li>{}: {terms} terms</li>",
                prose_html(&format!("${}$", e.lhs.unicode()))
            );
        }
        o.push_str("</ul>\n");
        return;
    }
    let rows: Vec<Row> = coefficients
        .iter()
        .flat_map(|(e, _)| mathml::rows(e, LINE_BUDGET))
        .collect();
    let mut latex = String::from("\\begin{aligned}\n");
    write_coefficient_lines(&mut latex, s, LINE_BUDGET);
    latex.push_str("\n\\end{aligned}");
    let _ = writeln!(
        o,
        "<div class=\"equation\">{}</div>",
        mathml::math(&mathml::table(&rows), &latex, true)
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    const HOSTILE: &str = "<script>alert(1)</script> & \"q\" 'a'";

    fn hostile_derivation() -> crate::derivation::Derivation {
        let text = format!(
            r#"
title = "{h}"
source = "{h}"
summary = "{h}"
assumptions = ["{h}"]
[symbols]
constants = ["I"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "B"
doc = "{h}"
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "H"
doc = "{h}"
value = "principal(I, I, I) * angvel(B)"
expect = ["I*w_x", "I*w_y", "I*w_x"]
"#,
            h = HOSTILE.replace('"', "\\\"")
        );
        crate::derivation::load_str("<x>.toml", &text).unwrap()
    }

    #[test]
    fn prose_formulas_are_set_with_scripts() {
        assert_eq!(
            prose_html("the moment r_G × m g on the right"),
            "the moment <span class=\"formula\">r<sub>G</sub> × m g</span> on the right"
        );
        assert_eq!(
            prose_html("$T = ½ m v^2$ holds, <b>"),
            "<span class=\"formula\">T = ½ m v<sup>2</sup></span> holds, &lt;b&gt;"
        );
        assert_eq!(prose_html("plain words."), "plain words.");
        assert_eq!(
            prose_html("$x_<b>$"),
            "<span class=\"formula\">x_&lt;b&gt;</span>"
        );
    }

    #[test]
    fn hostile_strings_never_reach_the_page_raw() {
        let d = hostile_derivation();
        let doc = crate::document::Course::plain(std::slice::from_ref(&d))
            .document(std::slice::from_ref(&d));
        let site = html_site(&doc);
        assert_eq!(site.len(), 3);
        for p in &site {
            assert!(!p.text.contains("<script"), "{}", p.text);
            assert!(!p.text.contains("\"q\""), "{}", p.text);
        }
        let page = &site[1];
        assert!(page.text.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
        // The count written into the page is the number of <math> elements.
        assert_eq!(page.text.matches("<math").count(), page.equations);
        assert!(
            page.text
                .contains(&format!("data-equations=\"{}\"", page.equations))
        );
        // The failed expectation is shown.
        assert!(page.text.contains("Does not equal the expected form"));
    }
}
