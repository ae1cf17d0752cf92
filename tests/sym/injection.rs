//! TeX-hostile strings in every text field of a derivation file (issue
//! 21, item 3): control words (`\input`, `\end{document}`,
//! `\immediate\write18`, `\def`), unbalanced braces, `^^` character codes,
//! HTML and Markdown code fences, in the title, source, summary,
//! assumptions, docs, frame axes, labels and the notes' own title, author
//! and chapters. Every format is derived and the notes, slides and
//! fragment are written; no control word of the input survives as a
//! command, braces balance, and when pdflatex is installed the notes
//! compile. Names (of symbols, frames and steps) are what expressions
//! refer to: such a string there is refused at the name.

use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::document::Course;
use hdot_sym::notes;
use hdot_sym::render::{Format, render};
use hdot_tests::markup::{
    FORBIDDEN, PYTHON, TEX_HTML, assert_no_html, assert_safe, compile, control_words, have,
    toml_str, without_code,
};

/// `h` as a label of words: a label with `*`, `/` or `^`, or one that
/// starts with a number, is mathematics and must parse (a file whose
/// label does not is refused at the label, see `broken`).
fn text_label(h: &str) -> String {
    h.replace(['*', '/', '^'], "")
        .trim_start_matches(|c: char| c.is_ascii_digit())
        .to_owned()
}

/// A derivation with `h` in every text field.
fn file(h: &str) -> String {
    let t = toml_str(h);
    let label = toml_str(&text_label(h));
    format!(
        r#"
title = {t}
source = {t}
summary = {t}
assumptions = [{t}, {t}]
[symbols]
constants = ["m"]
time = ["w_x", "w_y", "w_z"]
[[abbreviation]]
name = "s"
value = "w_x + w_y"
doc = {t}
[[frame]]
name = "F"
doc = {t}
angular_velocity = "[w_x, w_y, w_z]"
[[frame]]
name = "B"
doc = {t}
axes = [{t}, "b", "c"]
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "H"
label = {label}
doc = {t}
value = "m*angvel(B)"
expect = ["m*w_x", "m*w_y", "m*w_z"]
[[step]]
name = "W"
doc = {t}
value = "m*w_x"
expect = "m*w_y"
"#
    )
}

fn derivation(h: &str) -> Derivation {
    load_str(h, &file(h)).unwrap_or_else(|e| panic!("{h}: {e}"))
}

#[test]
fn hostile_strings_in_every_field_reach_latex_and_markdown_escaped() {
    for h in TEX_HTML {
        let d = derivation(h);
        let fragment = render(&d, Format::Latex);
        assert_safe("derive --format latex", h, &fragment, 0);
        let markdown = render(&d, Format::Markdown);
        let (words, _) = control_words(&without_code(&markdown));
        for w in FORBIDDEN {
            assert!(
                !words.iter().any(|x| x == w),
                "markdown of {h:?}: \\{w} survives:\n{markdown}"
            );
        }
        assert_no_html("markdown", h, &markdown);
        // The other formats still run.
        for f in [Format::Unicode, Format::Sympy, Format::Json] {
            assert!(!render(&d, f).is_empty());
        }
        let mut course = Course::plain(std::slice::from_ref(&d));
        course.title = (*h).to_owned();
        course.author = (*h).to_owned();
        course.intro = (*h).to_owned();
        course.chapters[0].0 = (*h).to_owned();
        course.chapters[0].1 = (*h).to_owned();
        let doc = course.document(std::slice::from_ref(&d));
        assert_safe("notes", h, &notes::latex_document(&doc), 1);
        assert_safe("slides", h, &notes::slides_document(&doc), 1);
        let md = notes::markdown_document(&doc);
        assert_no_html("markdown notes", h, &md);
        compiles(h, &notes::latex_document(&doc));
    }
}

/// A symbol, frame or step named by a hostile string is refused with an
/// error at that name's line, saying what a name may be.
#[test]
fn hostile_names_are_refused_at_the_name() {
    for h in TEX_HTML.iter().chain(PYTHON) {
        let good = file("a doc");
        let t = toml_str(h);
        for (what, from, to) in [
            (
                "symbol",
                "constants = [\"m\"]",
                format!("constants = [\"m\", {t}]"),
            ),
            ("frame", "name = \"F\"", format!("name = {t}")),
            ("step", "name = \"W\"", format!("name = {t}")),
        ] {
            let line = good.lines().position(|l| l == from).expect("the field") + 1;
            let text = good.replacen(from, &to, 1);
            let e = load_str("n.toml", &text).expect_err(&format!("{what} named {h:?}"));
            assert_eq!(e.line, line, "{what} named {h:?}: {e}");
            assert!(
                e.message
                    .contains(&format!("is not a valid {what} name (a letter, then")),
                "{what} named {h:?}: {e}"
            );
        }
    }
}

/// The notes compile with pdflatex (shell escape off), when it is
/// installed; the test says so and goes on when it is not.
fn compiles(h: &str, tex: &str) {
    if have("pdflatex", &["--version"], "compiling the hostile notes") {
        let dir = tempfile::tempdir().unwrap();
        compile(&format!("the notes of {h:?}"), dir.path(), tex);
    }
}

// ------------------------------------------------------ SymPy export --

/// A derivation with `h` in every text field, symbols whose names are not
/// Python identifiers or are Python's own (`x²`, `é`, `ω`, `日本`,
/// `lambda`, `equations`, `Symbol`, `t_`), and solved steps kept as variables.
fn python_file(h: &str) -> String {
    let t = toml_str(h);
    let label = toml_str(&text_label(h));
    format!(
        r#"
title = {t}
source = {t}
summary = {t}
assumptions = [{t}]
[symbols]
constants = ["m", "é", "lambda", "t_", "Symbol", "日本"]
time = ["x²", "ω", "equations"]
[[abbreviation]]
name = "s"
value = "x² + ω"
doc = {t}
[[frame]]
name = "B"
doc = {t}
angular_velocity = "[ω, equations, x²]"
[[step]]
name = "H"
label = {label}
doc = {t}
value = "m*é*angvel(B)"
expect = ["m*é*ω", "m*é*equations", "m*é*x²"]
[[step]]
name = "solved"
doc = {t}
value = "solve(lambda*x²'' - Symbol*t_ + 日本*equations', x²'')"
[[step]]
name = "lambda_"
label = {label}
value = "mass_matrix(list(lambda*x²'' - Symbol*t_ + m*ω'', é*ω'' + x²), [x²'', ω''])"
"#
    )
}

#[test]
fn hostile_strings_and_names_reach_python_as_one_valid_program() {
    let python = have("python3", &["-c", "import ast"], "the SymPy export's parse");
    let sympy = python && have("python3", &["-c", "import sympy"], "the SymPy export's run");
    for h in PYTHON.iter().chain(TEX_HTML) {
        let d = load_str(h, &python_file(h)).unwrap_or_else(|e| panic!("{h:?}: {e}"));
        let py = render(&d, Format::Sympy);
        // Outside string literals no line of the input appears: every line
        // of the program is one hdot wrote.
        for line in py.lines() {
            assert!(
                !line.trim_start().starts_with("import os"),
                "{h:?}: the input wrote a line of Python:\n{py}"
            );
        }
        if !python {
            continue;
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("d.py");
        std::fs::write(&path, &py).unwrap();
        // Parsed as one program whose top level is the statements hdot
        // writes: the import, and assignments.
        let check = r#"
import ast, sys
tree = ast.parse(open(sys.argv[1], encoding='utf-8').read())
kinds = {type(s).__name__ for s in tree.body}
assert kinds <= {'ImportFrom', 'Assign'}, kinds
"#;
        let run = |code: &str| {
            std::process::Command::new("python3")
                .args(["-c", code])
                .arg(&path)
                .output()
                .unwrap()
        };
        let out = run(check);
        assert!(
            out.status.success(),
            "{h:?}: the SymPy export does not parse:\n{}\n{py}",
            String::from_utf8_lossy(&out.stderr)
        );
        if sympy {
            // Run, it builds one equation per component, every symbol by
            // its own name, and the labels name the steps as written.
            let exec = r#"
import sys
ns = {}
exec(open(sys.argv[1], encoding='utf-8').read(), ns)
print(len(ns['equations']), len(ns['labels']))
from sympy.core.function import AppliedUndef
eqs = ns['equations']
names = {s.name for e in eqs for s in e.free_symbols}
names |= {f.func.__name__ for e in eqs for f in e.atoms(AppliedUndef)}
names = sorted(names)
print('|'.join(names))
"#;
            let out = run(exec);
            assert!(
                out.status.success(),
                "{h:?}: the SymPy export does not run:\n{}\n{py}",
                String::from_utf8_lossy(&out.stderr)
            );
            let text = String::from_utf8_lossy(&out.stdout);
            let mut lines = text.lines();
            let counts = lines.next().unwrap();
            let shown: usize = d
                .steps
                .iter()
                .filter(|s| s.show)
                .map(|s| s.components().len())
                .sum();
            assert_eq!(counts, format!("{shown} {shown}"), "{h:?}:\n{py}");
            let names: Vec<&str> = lines.next().unwrap().split('|').collect();
            for n in ["m", "é", "lambda", "t_", "Symbol", "日本", "equations"] {
                assert!(
                    names.contains(&n),
                    "{h:?}: {n} missing from {names:?}\n{py}"
                );
            }
        }
    }
}

#[test]
fn symbol_names_outside_ascii_typeset_with_pdflatex() {
    let d = load_str("names", &python_file("names")).unwrap();
    let fragment = render(&d, Format::Latex);
    // Only ASCII and Latin-1 letters reach pdflatex (a comment aside).
    for l in fragment
        .lines()
        .filter(|l| !l.trim_start().starts_with('%'))
    {
        assert!(
            l.chars().all(|c| c.is_ascii() || matches!(c, 'À'..='ÿ')),
            "a character pdflatex cannot set, written raw:\n{l}"
        );
    }
    assert!(fragment.contains(r"\mathrm{\text{[U+65E5]}\text{[U+672C]}}"));
    let course = Course::plain(std::slice::from_ref(&d));
    let doc = course.document(std::slice::from_ref(&d));
    compiles("non-ASCII names", &notes::latex_document(&doc));
}
