//! The lecture notes (`hdot notes`): the committed copies in `docs/notes/`
//! are regenerated from `derivations/` and must match byte for byte; the
//! LaTeX holds only characters pdflatex can typeset; the printer-coverage
//! appendix covers every Greek name of the printer.

use std::path::{Path, PathBuf};

use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::notes;
use hdot_sym::render::latex_text;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every derivation file, sorted by name, named as `hdot notes` names it
/// when run from the repository root.
fn derivations() -> Vec<Derivation> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("derivations"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            let shown = format!("derivations/{name}");
            load_str(&shown, &std::fs::read_to_string(p).unwrap()).unwrap_or_else(|e| panic!("{e}"))
        })
        .collect()
}

fn assert_up_to_date(file: &str, fresh: &str) {
    let path = root().join("docs/notes").join(file);
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != fresh {
        let line = committed
            .lines()
            .zip(fresh.lines())
            .position(|(a, b)| a != b)
            .map_or_else(
                || committed.lines().count().min(fresh.lines().count()) + 1,
                |k| k + 1,
            );
        panic!(
            "docs/notes/{file} is out of date with derivations/ (first difference at line {line}); \
             refresh it with `{}` and commit it",
            notes::REFRESH_COMMAND
        );
    }
}

#[test]
fn committed_markdown_notes_are_up_to_date() {
    assert_up_to_date(
        notes::MARKDOWN_FILE,
        &notes::markdown_document(&derivations()),
    );
}

#[test]
fn committed_latex_notes_are_up_to_date() {
    assert_up_to_date(notes::LATEX_FILE, &notes::latex_document(&derivations()));
}

#[test]
fn every_derivation_has_a_section_in_both_documents() {
    let ds = derivations();
    let tex = notes::latex_document(&ds);
    let md = notes::markdown_document(&ds);
    for d in &ds {
        assert!(
            tex.contains(&latex_text(&d.title)),
            "{} not in the LaTeX",
            d.title
        );
        assert!(
            tex.contains(&format!("\\label{{sec:{}}}", d.name)),
            "{}",
            d.name
        );
        assert!(
            md.contains(&format!("<a id=\"{}\"></a>", d.name)),
            "{}",
            d.name
        );
    }
    assert!(tex.contains(r"\section{Printer coverage}"));
}

#[test]
fn latex_holds_only_characters_pdflatex_can_typeset() {
    let tex = notes::latex_document(&derivations());
    for (k, line) in tex.lines().enumerate() {
        for c in line.chars() {
            assert!(
                c.is_ascii() || (('À'..='ÿ').contains(&c) && c.is_alphabetic()),
                "line {}: character {c:?} (U+{:04X}) in {line}",
                k + 1,
                c as u32
            );
        }
        assert!(
            !line.contains("[U+"),
            "line {}: unmapped character in {line}",
            k + 1
        );
    }
}

/// Every Greek name the printer knows is printed by the coverage appendix
/// (and so goes through the LaTeX compile).
#[test]
fn coverage_includes_every_greek_name_of_the_printer() {
    let names: Vec<&str> = hdot_sym::print::greek_names().collect();
    assert!(names.len() >= 20, "{names:?}");
    let printed: String = notes::coverage()
        .iter()
        .map(|c| hdot_sym::print::latex(&c.expr))
        .collect();
    for n in names {
        let tex = hdot_sym::print::latex_symbol(n, 0);
        assert!(printed.contains(&tex), "coverage does not print {tex}");
    }
}

macro_rules! latex_text_cases {
    ($($name:ident: $input:expr => $expected:expr;)*) => {
        $(#[test] fn $name() { assert_eq!(latex_text($input), $expected); })*
    };
}

latex_text_cases! {
    prose_specials: "50% & $5 #1 {a} ~ ^ \\" => r"50\% \& \$5 \#1 \{a\} \textasciitilde{} \textasciicircum{} \textbackslash{}";
    prose_combining_dots: "ω̇ and θ̈" => r"$\dot{\omega}$ and $\ddot{\theta}$";
    prose_dotted_subscript: "ω̇_z = ψ̈" => r"$\dot{\omega}_{z}$ = $\ddot{\psi}$";
    prose_precomposed_dots: "Ḣ_G and ṙ" => r"$\dot{H}_{G}$ and $\dot{r}$";
    prose_bars: "m ā at G, ȳ" => r"m $\bar{a}$ at G, $\bar{y}$";
    prose_operators: "ΣM = r × F · n ≥ 0 ≠ 1" => r"$\Sigma$M = r $\times$ F $\cdot$ n $\geq$ 0 $\neq$ 1";
    prose_integral_and_subscript: "I_xy = ∫xy dm" => r"$I_{xy}$ = $\int$xy dm";
    prose_code_word_keeps_underscore: "dt_rel(H)" => r"dt\_rel(H)";
    prose_superscripts: "sin²θ, Rᵀ, 90°" => r"sin$^{2}\theta$, R$^{T}$, 90$^{\circ}$";
    prose_primes_and_half: "I′ and ½ m v²" => r"I$'$ and $\tfrac{1}{2}$ m v$^{2}$";
    prose_punctuation: "a — b – c … “q” §3" => r"a --- b -- c \ldots{} ``q'' \S{}3";
    prose_latin1_kept: "Poincaré" => "Poincaré";
    prose_unknown_character: "snow ☃" => "snow [U+2603]";
}
