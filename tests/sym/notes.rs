//! The lecture notes and slides (`hdot notes`): the committed copies in
//! `docs/notes/` are regenerated from `derivations/` (arranged by
//! `derivations/notes.toml`) and must match byte for byte; chapters follow
//! the course; the LaTeX holds only characters pdflatex can typeset and no
//! raw notation in prose; sources are self-contained; a lecturer's own
//! files make notes with or without a manifest; the printer-coverage test
//! document covers every Greek name of the printer.

use std::path::{Path, PathBuf};

use hdot_sym::course::{self, MANIFEST_FILE};
use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::document::{Course, Document};
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
        .filter(|p| p.file_name().unwrap() != MANIFEST_FILE)
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

/// The bundled notes: the derivations arranged by the bundled manifest.
fn bundled() -> Document {
    let ds = derivations();
    let text = std::fs::read_to_string(root().join("derivations").join(MANIFEST_FILE)).unwrap();
    let c = course::parse("derivations/notes.toml", &text, &ds).unwrap_or_else(|e| panic!("{e}"));
    c.document(&ds)
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
    assert_up_to_date(notes::MARKDOWN_FILE, &notes::markdown_document(&bundled()));
}

#[test]
fn committed_latex_notes_are_up_to_date() {
    assert_up_to_date(notes::LATEX_FILE, &notes::latex_document(&bundled()));
}

#[test]
fn committed_slides_are_up_to_date() {
    assert_up_to_date(notes::SLIDES_FILE, &notes::slides_document(&bundled()));
}

#[test]
fn every_derivation_has_a_section_in_both_documents() {
    let ds = derivations();
    let doc = bundled();
    let tex = notes::latex_document(&doc);
    let md = notes::markdown_document(&doc);
    let slides = notes::slides_document(&doc);
    for d in &ds {
        assert!(
            tex.contains(&latex_text(&d.title)),
            "{} not in the LaTeX",
            d.title
        );
        assert!(
            slides.contains(&latex_text(&d.title)),
            "{} not in the slides",
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
    // The printer-coverage appendix is a test document, not in the notes.
    assert!(!tex.contains("Printer coverage") && !md.contains("Printer coverage"));
}

/// The chapters come in the order of the course, each derivation once.
#[test]
fn chapters_follow_the_course() {
    let doc = bundled();
    let titles: Vec<String> = doc
        .chapters
        .iter()
        .map(|c| c.title.to_lowercase())
        .collect();
    let order = [
        "angular momentum",
        "kinetic energy",
        "transport theorem",
        "euler's equations",
        "fixed axis",
        "gyroscope",
        "torque-free",
        "stability",
        "impulse",
    ];
    let mut at = 0;
    for want in order {
        let k = titles[at..]
            .iter()
            .position(|t| t.contains(want))
            .unwrap_or_else(|| panic!("no chapter `{want}` after chapter {at} in {titles:?}"));
        at += k + 1;
    }
    let mut names: Vec<&str> = doc
        .chapters
        .iter()
        .flat_map(|c| c.sections.iter().map(|s| s.name.as_str()))
        .collect();
    let n = names.len();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), n, "a derivation appears twice");
    assert_eq!(n, derivations().len(), "a derivation is missing");
    assert!(
        !doc.chapters
            .iter()
            .any(|c| c.title == "Further derivations"),
        "the manifest leaves a bundled derivation out"
    );
}

/// Every generated LaTeX (notes, slides, fragments, the coverage test
/// document) holds only characters pdflatex can typeset.
#[test]
fn latex_holds_only_characters_pdflatex_can_typeset() {
    let doc = bundled();
    let mut texts = vec![
        ("notes", notes::latex_document(&doc)),
        ("slides", notes::slides_document(&doc)),
        ("coverage", notes::coverage_document()),
    ];
    for d in derivations() {
        texts.push(("fragment", notes::latex_fragment(&d)));
    }
    for (what, tex) in texts {
        for (k, line) in tex.lines().enumerate() {
            for c in line.chars() {
                assert!(
                    c.is_ascii() || (('À'..='ÿ').contains(&c) && c.is_alphabetic()),
                    "{what} line {}: character {c:?} (U+{:04X}) in {line}",
                    k + 1,
                    c as u32
                );
            }
            assert!(
                !line.contains("[U+"),
                "{what} line {}: unmapped character in {line}",
                k + 1
            );
        }
    }
}

/// Prose in the notes has no raw notation: no literal underscore outside
/// code and file names, no Σ set apart from the letter it sums.
#[test]
fn prose_is_typeset() {
    let tex = notes::latex_document(&bundled());
    for (k, line) in tex.lines().enumerate() {
        let prose: String = strip_code(line);
        assert!(
            !prose.contains(r"\_"),
            "line {}: literal underscore in prose: {line}",
            k + 1
        );
        assert!(
            !prose.contains(r"$\Sigma$M") && !prose.contains(r"$\Sigma$F"),
            "line {}: Σ apart from its letter: {line}",
            k + 1
        );
    }
}

/// The line without its `\texttt{…}` groups.
fn strip_code(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(i) = rest.find(r"\texttt{") {
        out.push_str(&rest[..i]);
        let mut depth = 0;
        let mut end = rest.len();
        for (j, c) in rest[i + 7..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = i + 7 + j + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// Sources cite what a reader has: textbook sections and the project's
/// own equation reference, whose cited sections exist.
#[test]
fn sources_are_self_contained() {
    let reference = std::fs::read_to_string(root().join("docs/equations.md")).unwrap();
    for d in derivations() {
        let lower = d.source.to_lowercase();
        assert!(
            !lower.contains("reference sheet") && !lower.contains("shared/"),
            "{}: source cites a file outside the project: {}",
            d.path,
            d.source
        );
        let Some((_, cited)) = d.source.split_once("(docs/equations.md)") else {
            panic!(
                "{}: source does not cite docs/equations.md: {}",
                d.path, d.source
            );
        };
        let numbers: Vec<&str> = cited
            .split('§')
            .skip(1)
            .map(|s| {
                s.trim_start()
                    .split(|c: char| !c.is_ascii_digit())
                    .next()
                    .unwrap()
            })
            .collect();
        assert!(!numbers.is_empty(), "{}: no section cited", d.path);
        for n in numbers {
            assert!(
                reference.contains(&format!("\n## {n}. ")),
                "{}: docs/equations.md has no §{n}",
                d.path
            );
        }
    }
}

/// The printer-coverage test document prints every Greek name the printer
/// knows (and so goes through the LaTeX compile of scripts/build_notes).
#[test]
fn coverage_includes_every_greek_name_of_the_printer() {
    let names: Vec<&str> = hdot_sym::print::greek_names().collect();
    assert!(names.len() >= 20, "{names:?}");
    let doc = notes::coverage_document();
    for n in names {
        let tex = hdot_sym::print::latex_symbol(n, 0);
        assert!(doc.contains(&tex), "coverage does not print {tex}");
    }
}

// ------------------------------------------- a lecturer's own derivations --

/// Two small problems written for this test (not bundled).
fn own_files() -> Vec<Derivation> {
    let disk = r#"
title = "A spinning disk on a massless shaft"
source = "Written for the notes test"
summary = "The disk turns with ω_z about its axis; ΣM_G = (Ḣ_G)_Gxyz + ω × H_G."
[symbols]
constants = ["I", "Ip"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "B"
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "H"
value = "principal(Ip, Ip, I) * angvel(B)"
expect = ["Ip*w_x", "Ip*w_y", "I*w_z"]
[[step]]
name = "M"
label = "Sigma M"
doc = "transport theorem: $ΣM = Ḣ + ω × H$"
value = "dt_rel(H) + cross(angvel(B), H)"
"#;
    let rod = r#"
title = "Kinetic energy of a rod turning about its end"
source = "Written for the notes test"
[symbols]
constants = ["m", "L"]
time = ["theta"]
[[step]]
name = "T"
value = "m*L^2*theta'^2/6"
"#;
    vec![
        load_str("own/disk.toml", disk).unwrap_or_else(|e| panic!("{e}")),
        load_str("own/rod.toml", rod).unwrap_or_else(|e| panic!("{e}")),
    ]
}

#[test]
fn own_files_without_a_manifest_follow_in_the_order_given() {
    let ds = own_files();
    let doc = Course::plain(&ds).document(&ds);
    let tex = notes::latex_document(&doc);
    let a = tex.find(r"\section{A spinning disk").unwrap();
    let b = tex.find(r"\section{Kinetic energy of a rod").unwrap();
    assert!(a < b);
    assert!(tex.contains(r"$\Sigma M_{G} = (\dot{H}_{G})_{Gxyz} + \omega \times H_{G}$"));
    assert!(tex.contains(r"$\Sigma M = \dot{H} + \omega \times H$"));
}

#[test]
fn own_files_with_a_manifest_make_chapters_and_show_the_steps_chosen() {
    let ds = own_files();
    let manifest = r#"
title = "Dynamics II"
author = "A. Lecturer"
[[chapter]]
title = "Energy"
derivations = ["rod"]
[[chapter]]
title = "Moments"
derivations = ["disk"]
[steps]
disk = ["M"]
"#;
    let c = course::parse("own/notes.toml", manifest, &ds).unwrap_or_else(|e| panic!("{e}"));
    let doc = c.document(&ds);
    let tex = notes::latex_document(&doc);
    assert!(tex.contains(r"\title{Dynamics II}") && tex.contains(r"\author{A. Lecturer}"));
    let energy = tex.find(r"\section{Energy}").unwrap();
    let moments = tex.find(r"\section{Moments}").unwrap();
    let rod = tex.find(r"\subsection{Kinetic energy of a rod").unwrap();
    let disk = tex.find(r"\subsection{A spinning disk").unwrap();
    assert!(energy < rod && rod < moments && moments < disk);
    // Only step M of the disk is shown.
    let disk_part = &tex[disk..];
    assert!(disk_part.contains(r"\Sigma M_{x} &="));
    assert!(!disk_part.contains(r"H_{x} &="));
    let slides = notes::slides_document(&doc);
    assert!(slides.contains(r"\section{Energy}") && slides.contains(r"\begin{frame}"));
}

#[test]
fn manifest_errors_name_the_line_and_column() {
    let ds = own_files();
    let cases = [
        (
            "title = \"T\"\n[[chapter]]\ntitle = \"C\"\nderivations = [\"rod\", \"wheel\"]\n",
            (4, 24),
            "no derivation `wheel`",
        ),
        (
            "title = \"T\"\n[[chapter]]\ntitle = \"C\"\nderivations = [\"rod\", \"rod\"]\n",
            (4, 24),
            "listed twice",
        ),
        (
            "title = \"T\"\n[steps]\ndisk = [\"H\", \"Q\"]\n",
            (3, 15),
            "has no step `Q`",
        ),
        ("title = \"T\"\nchapters = []\n", (2, 1), "unknown field"),
    ];
    for (text, (line, column), message) in cases {
        let e = course::parse("own/notes.toml", text, &ds).unwrap_err();
        assert_eq!((e.line, e.column), (line, column), "{text}: {e}");
        assert!(e.message.contains(message), "{text}: {e}");
        assert_eq!(e.path, "own/notes.toml");
    }
}

/// A fragment is the notes' section of one derivation, ready to `\input`:
/// no preamble, no hdot macros, no hyperref commands.
#[test]
fn fragments_stand_alone() {
    for d in own_files().iter().chain(derivations().iter()) {
        let f = notes::latex_fragment(d);
        for forbidden in [
            r"\documentclass",
            r"\begin{document}",
            r"\texorpdfstring",
            r"\hdot",
        ] {
            assert!(!f.contains(forbidden), "{}: {forbidden}", d.path);
        }
        assert!(f.contains(r"\section{"), "{}", d.path);
        assert_eq!(
            f.matches(r"\begin{align*}").count(),
            f.matches(r"\end{align*}").count()
        );
    }
}

macro_rules! latex_text_cases {
    ($($name:ident: $input:expr => $expected:expr;)*) => {
        $(#[test] fn $name() { assert_eq!(latex_text($input), $expected); })*
    };
}

latex_text_cases! {
    prose_specials: "50% & $5 #1 {a} ~ ^ \\" => r"50\% \& \$5 \#1 \{a\} \textasciitilde{} \textasciicircum{} \textbackslash{}";
    prose_explicit_math: "so $ΣM_O = (Ḣ_O)_Oxyz$, then" => r"so $\Sigma M_{O} = (\dot{H}_{O})_{Oxyz}$, then";
    prose_formula_run: "Transport theorem: ΣM_O = (Ḣ_O)_Oxyz + Ω × H_O." => r"Transport theorem: $\Sigma M_{O} = (\dot{H}_{O})_{Oxyz} + \Omega \times H_{O}$.";
    prose_derivative_words: "ΣF = d(m v̄)/dt here" => r"$\Sigma F = d(m \bar{v})/dt$ here";
    prose_word_subscript: "ṙ_rel is taken in F" => r"$\dot{r}_{\mathrm{rel}}$ is taken in $F$";
    prose_article_stays_text: "a body with I′ sin θ ≠ 0" => r"a body with $I' \sin \theta \neq 0$";
    prose_combining_dots: "ω̇ and θ̈" => r"$\dot{\omega}$ and $\ddot{\theta}$";
    prose_dotted_subscript: "ω̇_z = ψ̈" => r"$\dot{\omega}_{z} = \ddot{\psi}$";
    prose_precomposed_dots: "Ḣ_G and ṙ" => r"$\dot{H}_{G}$ and $\dot{r}$";
    prose_bars: "m ā at G, ȳ" => r"$m \bar{a}$ at $G$, $\bar{y}$";
    prose_operators: "ΣM = r × F · n ≥ 0 ≠ 1" => r"$\Sigma M = r \times F \cdot n \geq 0 \neq 1$";
    prose_integral_and_subscript: "I_xy = ∫xy dm" => r"$I_{xy} = \int xy$ dm";
    prose_code_word_keeps_underscore: "dt_rel(H)" => r"dt\_rel(H)";
    prose_superscripts: "sin²θ, Rᵀ, 90°" => r"$\sin^{2}\theta$, $R^{T}$, $90^{\circ}$";
    prose_superscript_runs_are_one_script: "then E⁻¹ A, x₁₂ and y²³" => r"then $E^{-1} A$, $x_{12}$ and $y^{23}$";
    prose_primes_and_half: "I′ and ½ m v²" => r"$I'$ and $\tfrac{1}{2} m v^{2}$";
    prose_punctuation: "so — then – now … “quote” §3" => r"so --- then -- now \ldots{} ``quote'' \S{}3";
    prose_brackets_inside_a_formula: "steady when cos θ = m g L/(2 (I′ − J) Ω²)." => r"steady when $\cos \theta = m g L/(2 (I' - J) \Omega^{2})$.";
    prose_product_of_brackets: "stable when (J s + (C − A) Ω)(J s + (C − B) Ω) > 0 holds" => r"stable when $(J s + (C - A) \Omega)(J s + (C - B) \Omega) > 0$ holds";
    prose_bracket_before_a_formula_it_does_not_close: "(ω_z and more" => r"($\omega_{z}$ and more";
    prose_closing_bracket_then_relation: "ε̈_1 + k ε_1/(A B) = 0: stable" => r"$\ddot{\varepsilon}_{1} + k \varepsilon_{1}/(A B) = 0$: stable";
    prose_lone_letters_are_symbols: "A disk of mass m and moment I about O, G at L/2" => r"A disk of mass $m$ and moment $I$ about $O$, $G$ at $L/2$";
    prose_initials_stay_text: "J. R. Smith, Dynamics" => r"J. R. Smith, Dynamics";
    prose_capital_symbol_mid_sentence: "moments A, B and C" => r"moments $A$, $B$ and $C$";
    prose_latin1_kept: "Poincaré" => "Poincaré";
    prose_unknown_character: "snow ☃" => "snow [U+2603]";
    prose_arguments_stay_one_formula: "the form M(q) q̈ = f(q, q̇, t) that" => r"the form $M(q) \ddot{q} = f(q, \dot{q}, t)$ that";
    prose_comma_outside_brackets_ends_a_formula: "ω_x, ω_y and g(q̇, t)." => r"$\omega_{x}$, $\omega_{y}$ and $g(\dot{q}, t)$.";
}

/// A step labelled 0 whose equations differ in length, written for this
/// test: every equation reads `… = 0`, the long one broken over lines
/// too, never `0 = …` (a new user's rod pendulum had both in one block).
#[test]
fn equations_labelled_zero_read_equals_zero_when_broken() {
    let text = r#"
title = "A rod in a two-axis joint"
source = "Written for the notes test"
[symbols]
constants = ["I", "Ip", "m", "g", "l"]
time = ["phi", "theta"]
[[step]]
name = "eom"
label = "0"
doc = "Lagrange's equations"
value = """list(I*phi''*cos(theta)^2 + Ip*phi''*sin(theta)^2 - 2*I*phi'*theta'*sin(theta)
  + 2*Ip*phi'*theta'*sin(theta)*cos(theta), Ip*theta'' + m*g*l*sin(theta))"""
"#;
    let ds = vec![load_str("own/rod-joint.toml", text).unwrap_or_else(|e| panic!("{e}"))];
    let doc = Course::plain(&ds).document(&ds);
    for (what, tex) in [
        ("slides", notes::slides_document(&doc)),
        ("notes", notes::latex_document(&doc)),
    ] {
        let start = tex.find(r"\begin{align*}").unwrap();
        let end = tex[start..].find(r"\end{align*}").unwrap() + start;
        let block = &tex[start..end];
        assert!(!block.contains("0 &="), "{what}: {block}");
        // Two equations, each ending `= 0`.
        assert_eq!(block.matches("= 0").count(), 2, "{what}: {block}");
        for eq in block.split(r" \\").filter(|l| l.contains("= 0")) {
            assert!(eq.trim_end().ends_with("= 0"), "{what}: {eq}");
        }
    }
    // On a slide the long one is broken: its continuation ends `= 0`.
    let slides = notes::slides_document(&doc);
    assert!(
        slides.contains(r"\cos\theta = 0 \\") && slides.contains(r"&\quad {} + 2 I' "),
        "{slides}"
    );
}

/// A four-degree-of-freedom problem written for this test: its mass
/// matrix has long entries and its forcing four long components. On the
/// slides the matrix is set as a matrix, its long entries named and
/// defined below it (the symmetric pair under one name), and equations
/// taller than a frame continue on further frames, never overflowing one.
#[test]
fn slides_split_what_a_frame_cannot_hold() {
    let text = r#"
title = "A platform with a rotor in Eulerian angles"
source = "Written for the slides test"
[symbols]
constants = ["A", "B", "C", "J", "k"]
time = ["phi", "theta", "psi", "beta"]
[[step]]
name = "eqs"
label = "0"
doc = "Four equations linear in the accelerations"
value = """list(
  (A*cos(theta)^2 + B*sin(theta)^2*cos(psi)^2 + C*sin(psi)^2*sin(theta)^2 + J*cos(theta)^2)*phi''
    + (B - C)*sin(psi)*sin(theta)*cos(psi)*theta'' + (A + J)*cos(theta)*psi'' + J*cos(theta)*beta''
    + k*phi'*theta'*sin(theta)*cos(theta) + k*psi'*theta'*sin(theta)*cos(psi)^2 + k*phi'^2*sin(psi)*cos(theta),
  (B - C)*sin(psi)*sin(theta)*cos(psi)*phi'' + (B*sin(psi)^2 + C*cos(psi)^2)*theta''
    + k*phi'*psi'*sin(theta)*cos(psi)^2 - k*theta'^2*sin(psi)*cos(psi)*cos(theta) + k*phi'^2*sin(theta)*cos(theta),
  (A + J)*cos(theta)*phi'' + (A + J)*psi'' + J*beta''
    + k*phi'*theta'*sin(theta) - k*psi'*theta'*sin(psi)*cos(psi) + k*beta'*phi'*cos(theta)^2,
  J*cos(theta)*phi'' + J*psi'' + J*beta'' + k*phi'*theta'*sin(theta)*cos(psi) - k*beta'^2*cos(theta)
    + k*psi'^2*sin(psi)*sin(theta))"""
[[step]]
name = "M"
doc = "The mass matrix"
value = "mass_matrix(eqs, [phi'', theta'', psi'', beta''])"
[[step]]
name = "f"
doc = "The rest of the equations"
value = "eqs - M*list(phi'', theta'', psi'', beta'')"
"#;
    let ds = vec![load_str("own/platform.toml", text).unwrap_or_else(|e| panic!("{e}"))];
    let doc = Course::plain(&ds).document(&ds);
    let slides = notes::slides_document(&doc);
    let frames: Vec<&str> = slides
        .split(r"\begin{frame}")
        .skip(1)
        .map(|f| f.split(r"\end{frame}").next().unwrap())
        .collect();
    // The mass matrix: one frame, a 4 × 4 matrix whose long entries are
    // named (the symmetric pair M_12 = M_21 under the name above the
    // diagonal), then defined.
    let m: Vec<&&str> = frames
        .iter()
        .filter(|f| f.contains("The mass matrix"))
        .collect();
    assert_eq!(m.len(), 1, "{slides}");
    let matrix = m[0]
        .lines()
        .find(|l| l.starts_with(r"M &= \begin{bmatrix}"))
        .unwrap_or_else(|| panic!("{}", m[0]));
    let body = matrix
        .trim_start_matches(r"M &= \begin{bmatrix}")
        .split(r"\end{bmatrix}")
        .next()
        .unwrap();
    let rows: Vec<Vec<&str>> = body
        .split(r"\\")
        .map(|r| r.split('&').map(str::trim).collect())
        .collect();
    assert_eq!(rows.len(), 4, "{matrix}");
    assert!(rows.iter().all(|r| r.len() == 4), "{matrix}");
    assert_eq!(rows[0][0], "M_{11}", "{matrix}");
    assert_eq!(rows[0][1], "M_{12}", "{matrix}");
    assert_eq!(rows[1][0], "M_{12}", "{matrix}");
    assert_eq!(rows[1][2], "0", "{matrix}");
    assert_eq!(rows[3][3], "J", "{matrix}");
    assert!(m[0].contains(r"M_{11} &= "), "{}", m[0]);
    assert!(m[0].contains(r"M_{12} &= "), "{}", m[0]);
    assert!(!m[0].contains(r"M_{21} &= "), "{}", m[0]);
    // The long equations continue on a further frame, marked so; no frame
    // holds more lines than fit on it; the forcing, four lines, fits one.
    let parts: Vec<&&str> = frames
        .iter()
        .filter(|f| f.contains("Four equations linear"))
        .collect();
    assert!(parts.len() >= 2, "not split: {slides}");
    assert!(!parts[0].contains("(continued)"), "{}", parts[0]);
    for p in &parts[1..] {
        assert!(p.contains("(continued)"), "{p}");
    }
    for f in &frames {
        let lines = f.lines().filter(|l| l.ends_with(r" \\")).count() + 1;
        assert!(lines <= 9, "{lines} lines on one frame: {f}");
    }
    let f: Vec<&&str> = frames
        .iter()
        .filter(|f| f.contains("The rest of the equations"))
        .collect();
    assert_eq!(f.len(), 1, "{slides}");
    let eqs: String = frames
        .iter()
        .filter(|f| f.contains("Four equations linear"))
        .copied()
        .collect();
    assert_eq!(eqs.matches("= 0").count(), 4, "{eqs}");
    // The notes set the same matrix.
    let tex = notes::latex_document(&doc);
    assert!(tex.contains(r"M &= \begin{bmatrix}"), "{tex}");
}
