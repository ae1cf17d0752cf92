//! TeX- and HTML-hostile strings in every text field (issue 21, item 3):
//! of a derivation file (title, source, summary, assumptions, symbol,
//! abbreviation, frame, axis, point and body names and docs, step names,
//! labels, docs and meanings, `[[load]]`, `gravity`, the file's own name),
//! of a notes manifest (title, author, intros, chapter titles) and of a
//! simulation scene (name, description, bodies, the derivation it names).
//!
//! Each string, in each field alone, is refused with a located error or
//! accepted; an accepted file's outputs hold it escaped: the LaTeX holds
//! none of its control words, braces balance, no `^^` code; Markdown holds
//! no HTML tag; every HTML page only hdot's own tags and attributes; the
//! JSON parses; no control character reaches any other output. Then, per string,
//! every field that accepted it carries it at once, and the notes of all
//! those files are one LaTeX document compiled once with pdflatex, one
//! web site and one Python program parsed once — where pdflatex and
//! python3 are installed (`CI=true` requires them).
//!
//! A proptest target draws strings from the same pieces, glued at random,
//! into random fields.

use std::collections::BTreeSet;
use std::process::Command;

use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::notes;
use hdot_sym::render::{Format, render};
use hdot_tests::markup::{
    FORBIDDEN, assert_no_html, assert_pdflatex_characters, assert_safe, compile, control_words,
    have, hostile, html_tags, toml_str, without_code,
};
use proptest::prelude::*;

/// The text fields of [`TEMPLATE`]: `@NAME@` and its value when the field
/// is not the one under test.
const FIELDS: &[(&str, &str)] = &[
    ("TITLE", "\"A heavy top\""),
    ("SOURCE", "\"a textbook\""),
    ("SUMMARY", "\"The top turns about O.\""),
    ("ASSUMPTION", "\"O is fixed.\""),
    ("CONSTANT", "\"k\""),
    ("ABBREV", "\"spin\""),
    ("ABBREV_DOC", "\"spin component\""),
    ("FRAME", "\"P\""),
    ("FRAME_DOC", "\"precession frame\""),
    ("AXIS", "\"x\""),
    ("POINT", "\"Q\""),
    ("POINT_DOC", "\"a second fixed point\""),
    ("BODY", "\"twin\""),
    ("BODY_DOC", "\"a second top\""),
    ("GRAVITY", "\"[0, 0, -g] in N\""),
    ("TORQUE", "\"[0, 0, M] in R\""),
    ("LOAD_FRAME", "\"R\""),
    ("KNOWN", "\"angular_momentum(top, O)\""),
    ("STEP", "\"last\""),
    ("LABEL", "\"H_O\""),
    ("STEP_DOC", "\"angular momentum about O\""),
    ("MEANS", "\"angular_momentum(top, O)\""),
    ("EXPECT", "\"m*g\""),
    ("COLLECT", "\"m\""),
];

/// A derivation using every kind of declaration, its text fields as
/// `@NAME@` (see [`FIELDS`]).
const TEMPLATE: &str = r#"
title = @TITLE@
source = @SOURCE@
summary = @SUMMARY@
assumptions = [@ASSUMPTION@]
gravity = @GRAVITY@
[symbols]
constants = ["I", "Ip", "m", "g", "l", "M", "h_x", "h_y", "h_z", @CONSTANT@]
time = ["phi", "theta", "psi"]
[[abbreviation]]
name = "omega_z"
value = "psi' + phi'*cos(theta)"
doc = @ABBREV_DOC@
[[abbreviation]]
name = @ABBREV@
value = "psi'"
[[frame]]
name = "F"
parent = "N"
rotation = "z(phi)"
doc = @FRAME_DOC@
axes = [@AXIS@, "y", "z"]
[[frame]]
name = "R"
parent = "F"
rotation = "y(theta)"
[[frame]]
name = @FRAME@
parent = "N"
rotation = "z(psi)"
[[point]]
name = "O"
doc = @POINT_DOC@
fixed = true
[[point]]
name = @POINT@
fixed = true
[[body]]
name = "top"
doc = @BODY_DOC@
frame = "R"
point = "O"
mass = "m"
mass_centre = "[0, 0, l] in R"
inertia = "principal(Ip, Ip, I)"
symmetry = "axisymmetric z"
[[body]]
name = @BODY@
frame = "R"
point = "O"
mass = "m"
mass_centre = "[0, 0, l] in R"
inertia = "principal(Ip, Ip, I)"
[[load]]
frame = @LOAD_FRAME@
torque = @TORQUE@
[[known]]
value = "[h_x, h_y, h_z] in R"
means = @KNOWN@
[[step]]
name = "H"
label = @LABEL@
value = "principal(Ip, Ip, I) * angvel(R)"
means = @MEANS@
doc = @STEP_DOC@
[[step]]
name = @STEP@
label = "W"
value = "m*g"
expect = @EXPECT@
collect = [@COLLECT@]
"#;

/// The template with `hostile` (a TOML string) in `fields` and the
/// defaults elsewhere.
fn file(fields: &[&str], hostile: &str) -> String {
    let mut t = TEMPLATE.to_owned();
    for (name, default) in FIELDS {
        let v = if fields.contains(name) {
            hostile
        } else {
            default
        };
        t = t.replace(&format!("@{name}@"), v);
    }
    t
}

/// The file name of a derivation carrying `h` (a file name holds no `/`
/// or NUL, and at most 255 bytes).
fn file_name(h: &str) -> String {
    let mut s: String = h.chars().filter(|c| !matches!(c, '/' | '\0')).collect();
    while s.len() > 200 {
        s.pop();
    }
    format!("{s}.toml")
}

/// No control character but line breaks and tabs in what hdot writes.
fn assert_no_control(what: &str, h: &str, out: &str) {
    if let Some(c) = out
        .chars()
        .find(|&c| c.is_control() && !matches!(c, '\n' | '\t'))
    {
        panic!("{what} of {h:?}: the control character {c:?} written raw");
    }
}

/// What `derive` writes for `d` in every format holds `h` escaped.
fn assert_derive_safe(h: &str, d: &Derivation) {
    let tex = render(d, Format::Latex);
    assert_safe("derive --format latex", h, &tex, 0);
    assert_pdflatex_characters(h, &tex);
    let md = render(d, Format::Markdown);
    let (words, _) = control_words(&without_code(&md));
    for w in FORBIDDEN {
        assert!(
            !words.iter().any(|x| x == w),
            "derive --format markdown of {h:?}: \\{w} survives:\n{md}"
        );
    }
    assert_no_html("derive --format markdown", h, &md);
    // JSON holds any string as a valid literal (serde_json escapes what
    // must be): it must parse.
    let json = render(d, Format::Json);
    if let Err(e) = serde_json::from_str::<serde_json::Value>(&json) {
        panic!("derive --format json of {h:?} does not parse: {e}\n{json}");
    }
    for (what, out) in [
        ("latex", &tex),
        ("markdown", &md),
        ("unicode", &render(d, Format::Unicode)),
        ("sympy", &render(d, Format::Sympy)),
    ] {
        assert_no_control(what, h, out);
    }
}

/// Loads the template with `h` in `fields`; an error must be located.
fn load(fields: &[&str], h: &str) -> Option<Derivation> {
    let path = if fields.contains(&"FILE") {
        file_name(h)
    } else {
        "top.toml".into()
    };
    match load_str(&path, &file(fields, &toml_str(h))) {
        Ok(d) => Some(d),
        Err(e) => {
            assert!(
                e.line > 0 && e.column > 0 && !e.message.is_empty(),
                "{fields:?} = {h:?}: refused without a place: {e}"
            );
            assert_no_control("the error", h, &e.to_string());
            None
        }
    }
}

/// The tags and attributes an HTML page of the notes may hold: those of a
/// page made from harmless text, the scripts of prose formulas, and
/// MathML's.
fn allowed_tags(pages: &[notes::SitePage]) -> BTreeSet<String> {
    let mut s: BTreeSet<String> = ["sub", "sup"].map(str::to_owned).into();
    for p in pages {
        for (tag, attrs) in html_tags(&p.text) {
            s.insert(tag.trim_start_matches('/').to_owned());
            for a in attrs {
                s.insert(format!("@{a}"));
            }
        }
    }
    s
}

fn assert_tags_within(what: &str, h: &str, page: &str, allowed: &BTreeSet<String>) {
    for (tag, attrs) in html_tags(page) {
        let name = tag.trim_start_matches('/');
        let mathml = name.starts_with('m') && name != "meta" && name != "main"
            || ["math", "semantics", "annotation"].contains(&name);
        assert!(
            mathml || allowed.contains(name),
            "{what} of {h:?}: the tag <{tag}> is not hdot's"
        );
        for a in attrs {
            assert!(
                allowed.contains(&format!("@{a}")) || mathml,
                "{what} of {h:?}: the attribute {a} on <{tag}> is not hdot's"
            );
        }
    }
    assert!(
        !page.to_ascii_lowercase().contains("<script"),
        "{what} of {h:?}: a script"
    );
    assert_eq!(
        page.matches("<math").count(),
        page.matches("</math>").count(),
        "{what} of {h:?}: MathML elements do not close as opened"
    );
}

/// A manifest of `ds` with `h` in its title, author, intros and chapter.
fn manifest(h: &str, ds: &[Derivation]) -> String {
    let t = toml_str(h);
    let names: Vec<String> = ds.iter().map(|d| toml_str(&d.name)).collect();
    format!(
        "title = {t}\nauthor = {t}\nintro = {t}\n[[chapter]]\ntitle = {t}\nintro = {t}\nderivations = [{}]\n",
        names.join(", ")
    )
}

#[test]
fn hostile_strings_in_every_field_are_refused_or_escaped_and_the_notes_compile() {
    let fields: Vec<&str> = FIELDS.iter().map(|(n, _)| *n).chain(["FILE"]).collect();
    let harmless = load_str("top.toml", &file(&[], "\"harmless\""))
        .unwrap_or_else(|e| panic!("the template loads: {e}"));
    let course = hdot_sym::document::Course::plain(std::slice::from_ref(&harmless));
    let allowed = allowed_tags(&notes::html_site(
        &course.document(std::slice::from_ref(&harmless)),
    ));
    let pdflatex = have("pdflatex", &["--version"], "compiling the hostile notes");
    let python = have("python3", &["-c", "import ast"], "parsing the SymPy export");
    let dir = tempfile::tempdir().unwrap();
    let mut tex = String::new();
    let mut python_files = Vec::new();
    for (k, h) in hostile().iter().enumerate() {
        // Each field alone.
        let mut accepting = Vec::new();
        for f in &fields {
            if let Some(d) = load(&[f], h) {
                assert_derive_safe(h, &d);
                if *f != "FILE" {
                    accepting.push(*f);
                }
            }
        }
        for f in ["TITLE", "SUMMARY", "STEP_DOC", "BODY_DOC"] {
            assert!(accepting.contains(&f), "{f} refused {h:?}");
        }
        // Every accepting field at once, the file named after the string.
        let mut all = accepting.clone();
        all.push("FILE");
        if all.contains(&"FRAME") {
            // A step may not be named like a frame.
            all.retain(|f| *f != "STEP");
        }
        let d = load(&all, h).unwrap_or_else(|| panic!("{h:?} in {all:?} at once"));
        assert_derive_safe(h, &d);
        let ds = [d, harmless.clone()];
        let course = hdot_sym::course::parse("notes.toml", &manifest(h, &ds), &ds)
            .unwrap_or_else(|e| panic!("the manifest of {h:?}: {e}"));
        let doc = course.document(&ds);
        let latex = notes::latex_document(&doc);
        assert_safe("notes", h, &latex, 1);
        assert_pdflatex_characters(h, &latex);
        assert_safe("slides", h, &notes::slides_document(&doc), 1);
        assert_no_html("markdown notes", h, &notes::markdown_document(&doc));
        for p in notes::html_site(&doc) {
            assert_tags_within("notes --html", h, &p.text, &allowed);
            assert_no_control("notes --html", h, &p.text);
        }
        // One document to compile: every course's body, in one preamble.
        let body_start = latex.find(r"\begin{document}").expect("a document") + 16;
        let body_end = latex.rfind(r"\end{document}").expect("an end");
        if tex.is_empty() {
            tex.push_str(&latex[..body_start]);
        }
        // One table of contents (each opens a file for writing: TeX has 16).
        let body = &latex[body_start..body_end];
        if tex.contains(r"\tableofcontents") {
            tex.push_str(&body.replace(r"\tableofcontents", ""));
        } else {
            tex.push_str(body);
        }
        tex.push_str("\n\\clearpage\n");
        let py = dir.path().join(format!("d{k}.py"));
        std::fs::write(&py, render(&ds[0], Format::Sympy)).unwrap();
        python_files.push(py);
    }
    tex.push_str("\\end{document}\n");
    if pdflatex {
        compile("the hostile notes", dir.path(), &tex);
    }
    if python {
        let check = "import ast, sys\nfor f in sys.argv[1:]:\n    tree = ast.parse(open(f, encoding='utf-8').read())\n    kinds = {type(s).__name__ for s in tree.body}\n    assert kinds <= {'ImportFrom', 'Assign'}, (f, kinds)\n";
        let out = Command::new("python3")
            .args(["-c", check])
            .args(&python_files)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "a SymPy export does not parse:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

// ------------------------------------------------------------ scenes --

/// A derived scene naming a derivation file and a CSV cloud called after
/// `h`, with `h` in its name, description and body name; `hdot simulate --html` either
/// refuses it (exit 2, a located error) or writes a page holding `h`
/// escaped.
#[test]
fn hostile_strings_in_scenes_reach_the_simulation_page_escaped() {
    let bin = hdot_tests::hdot_bin();
    let root = hdot_tests::repo_root();
    let derivation = std::fs::read_to_string(root.join("derivations/heavy-top.toml")).unwrap();
    let scene = std::fs::read_to_string(root.join("docs/examples/sim-derived-heavy-top.toml"))
        .unwrap()
        .replace("t_end = 5.0", "t_end = 0.05");
    let mut allowed: Option<BTreeSet<String>> = None;
    let mut scripts = 0;
    for h in std::iter::once("harmless".to_owned()).chain(hostile()) {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(file_name(&h)), &derivation).unwrap();
        let csv = file_name(&h).replace(".toml", ".csv");
        std::fs::write(dir.path().join(&csv), "x,y,z,m\n0,0,0.05,0.01\n").unwrap();
        let t = toml_str(&h);
        let text = scene
            .replace(
                "name = \"heavy top, derived in Eulerian angles\"",
                &format!("name = {t}"),
            )
            .replace(
                "description = \"The derivation's solved accelerations, integrated; compare with sim-heavy-top.toml.\"",
                &format!("description = {t}"),
            )
            .replace(
                "file = \"heavy-top\"",
                &format!("file = {}", toml_str(&file_name(&h))),
            )
            .replace("[[body]]\n", &format!("[[body]]\nname = {t}\n"))
            .replace(
                "[initial]",
                &format!("[[cloud]]\nfile = {}\n\n[initial]", toml_str(&csv)),
            );
        let path = dir.path().join("s.toml");
        std::fs::write(&path, &text).unwrap();
        let page = dir.path().join("page.html");
        let out = Command::new(&bin)
            .args(["simulate", "s.toml", "--html", "page.html"])
            .current_dir(dir.path())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_no_control("simulate", &h, &stdout);
        match out.status.code() {
            Some(0) => {}
            Some(2) if allowed.is_some() => {
                assert!(
                    stderr.contains("s.toml:"),
                    "{h:?}: refused without a place: {stderr}"
                );
                continue;
            }
            c => panic!("{h:?}: exit {c:?}: {stderr}"),
        }
        let html = std::fs::read_to_string(&page).unwrap();
        let tags = html_tags(&html);
        match &allowed {
            None => {
                let mut s = BTreeSet::new();
                for (tag, attrs) in tags {
                    s.insert(tag);
                    s.extend(attrs.into_iter().map(|a| format!("@{a}")));
                }
                allowed = Some(s);
                scripts = html.matches("<script").count();
            }
            Some(allowed) => {
                for (tag, attrs) in tags {
                    assert!(
                        allowed.contains(&tag),
                        "{h:?}: the tag <{tag}> is not hdot's"
                    );
                    for a in attrs {
                        assert!(
                            allowed.contains(&format!("@{a}")),
                            "{h:?}: the attribute {a} on <{tag}> is not hdot's"
                        );
                    }
                }
                assert_eq!(
                    html.matches("<script").count(),
                    scripts,
                    "{h:?}: a script of the input"
                );
                assert_no_control("simulate --html", &h, &html);
            }
        }
    }
}

// ---------------------------------------------------------- proptest --

/// Pieces of hostile strings, glued at random.
fn piece() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "\\", "\\input", "\\x", "{", "}", "%", "#", "$", "&", "~", "^", "^^5c", "_", "<", ">",
            "</math>", "<script>", "&amp;", "\"", "'", "`", "```", "*", "[", "]", "(", ")", "|",
            "\u{202E}", "\u{2066}", "\u{1b}", "\u{7}", "\u{0}", "\u{85}", "\u{2028}", "\n", "\t",
            " ", "θ", "ω_z", "θ'", "Σ", "é", "日本", "a", "x", "1",
        ])
        .prop_map(str::to_owned),
        "\\PC{0,4}",
    ]
}

proptest! {
    #![proptest_config(crate::config())]

    /// A random hostile string in one or two random fields: refused with a
    /// located error, or escaped in every `derive` format.
    #[test]
    fn random_hostile_strings_are_refused_or_escaped(
        pieces in prop::collection::vec(piece(), 1..12),
        a in 0..FIELDS.len(),
        b in 0..FIELDS.len(),
    ) {
        let h = pieces.concat();
        if let Some(d) = load(&[FIELDS[a].0, FIELDS[b].0], &h) {
            assert_derive_safe(&h, &d);
        }
    }
}
