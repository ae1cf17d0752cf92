//! Broken derivation files. Each file in `tests/sym/broken/` starts with a
//! comment `# expect: LINE:COLUMN: MESSAGE FRAGMENT`; loading it must fail
//! with that location and a message containing the fragment, never panic.

use hdot_sym::derivation::load_str;

#[test]
fn each_broken_file_reports_its_location() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("sym/broken");
    let mut n = 0;
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let text = std::fs::read_to_string(&path).unwrap();
        let first = text.lines().next().unwrap();
        let spec = first
            .strip_prefix("# expect: ")
            .unwrap_or_else(|| panic!("{}: no `# expect:` line", path.display()));
        let mut parts = spec.splitn(3, ':');
        let line: usize = parts.next().unwrap().trim().parse().unwrap();
        let col: usize = parts.next().unwrap().trim().parse().unwrap();
        let fragment = parts.next().unwrap().trim();
        let name = format!("broken/{}", path.file_name().unwrap().to_string_lossy());
        let err = load_str(&name, &text).expect_err(&name);
        assert_eq!(
            (err.line, err.column),
            (line, col),
            "{name}: wrong location\n{err}"
        );
        assert!(
            err.message.contains(fragment),
            "{name}: message `{}` lacks `{fragment}`",
            err.message
        );
        let shown = err.to_string();
        assert!(
            shown.contains(&format!("--> {name}:{line}:{col}")),
            "{shown}"
        );
        assert!(
            shown
                .lines()
                .last()
                .unwrap()
                .trim_start_matches(|c: char| c.is_ascii_digit() || c == ' ')
                .starts_with('|')
        );
        n += 1;
    }
    assert!(n >= 8, "only {n} broken files found");
}

#[test]
fn a_wrong_expectation_names_the_component_and_the_difference() {
    let text = r#"
title = "wrong"
source = "test"
[symbols]
constants = ["I_x", "I_y", "I_z"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "B"
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "M"
value = "dt(principal(I_x, I_y, I_z) * angvel(B))"
expect = ["I_x*w_x' - (I_y - I_z)*w_y*w_z", "I_y*w_y' + (I_z - I_x)*w_z*w_x", "I_z*w_z' - (I_x - I_y)*w_x*w_y"]
"#;
    let d = load_str("wrong.toml", text).unwrap();
    let f = d.failures();
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].1.component, "y");
    assert_eq!(
        f[0].1.difference,
        hdot_sym::Symbols::parse_decl(&["I_x", "I_z"], &["w_x", "w_z"])
            .poly("-2*(I_z - I_x)*w_z*w_x")
            .unwrap()
    );
}

#[test]
fn the_caret_snippet_reads_like_a_compiler_error() {
    let text = "title = \"t\"\nsource = \"s\"\n[symbols]\nconstants = [\"m\"]\n[[step]]\nname = \"x\"\nvalue = \"m * q\"\n";
    let err = load_str("d.toml", text).unwrap_err();
    insta::assert_snapshot!(err.to_string());
}

/// `linearize` treats a small angle as first order: sin ε → ε, cos ε → 1,
/// so `sin ε · ε` is second order and dropped.
#[test]
fn linearize_expands_sines_and_cosines_of_small_angles() {
    let text = r#"
title = "small angles"
source = "test"
[symbols]
constants = ["A"]
small = ["e"]
[[step]]
name = "x"
value = "linearize(A*cos(e) + A*sin(e) + sin(e)*e + cos(e)*e)"
expect = "A + A*e + e"
"#;
    let d = load_str("small.toml", text).unwrap();
    assert!(d.all_hold(), "{:?}", d.failures());
}

/// A file that is not UTF-8 is an error at the line and column of its
/// first bad byte; a UTF-16 file is named as such (issue 21).
#[test]
fn a_file_in_the_wrong_encoding_is_a_located_error() {
    let dir = tempfile::tempdir().unwrap();
    let text = "title = \"t\"\nsource = \"s\"\n[symbols]\nconstants = [\"a\"]\n";
    let latin1 = dir.path().join("latin1.toml");
    let mut bytes = text.as_bytes().to_vec();
    bytes.extend(b"# caf\xe9\n");
    std::fs::write(&latin1, &bytes).unwrap();
    let e = hdot_sym::derivation::load(&latin1).unwrap_err();
    assert_eq!((e.line, e.column), (5, 6), "{e}");
    assert!(
        e.message.contains("not UTF-8") && e.message.contains("0xE9"),
        "{e}"
    );
    assert!(e.to_string().contains("latin1.toml:5:6"), "{e}");

    let utf16 = dir.path().join("utf16.toml");
    let le: Vec<u8> = [0xFF, 0xFE]
        .into_iter()
        .chain(text.encode_utf16().flat_map(u16::to_le_bytes))
        .collect();
    std::fs::write(&utf16, le).unwrap();
    let e = hdot_sym::derivation::load(&utf16).unwrap_err();
    assert!(
        e.message.contains("the file is UTF-16") && e.message.contains("save it as UTF-8"),
        "{e}"
    );
}

/// Issue 21 item 10: a caret stays under its column after tabs — the
/// snippet's lead copies each tab of the line (a terminal widens both
/// alike) and a space for every other character.
#[test]
fn the_caret_stays_under_its_column_after_tabs() {
    let text = "title = \"t\"\nsource = \"s\"\n[symbols]\nconstants = [\"m\"]\n[[step]]\nname = \"x\"\n\tvalue\t=\t\"m * q\"\n";
    let err = load_str("d.toml", text).unwrap_err();
    assert_eq!(err.line, 7, "{err}");
    let shown = err.to_string();
    let lines: Vec<&str> = shown.lines().collect();
    let source = lines
        .iter()
        .find(|l| l.starts_with("7 | "))
        .unwrap_or_else(|| panic!("no source line:\n{shown}"));
    let caret = lines
        .iter()
        .find(|l| l.contains('^'))
        .unwrap_or_else(|| panic!("no caret:\n{shown}"));
    let source = &source["7 | ".len()..];
    let caret = &caret["  | ".len()..];
    let lead: String = caret.chars().take_while(|&c| c != '^').collect();
    // The lead is the source line up to `q` with every character but a
    // tab turned into a space.
    let at = source.find('q').expect("q on the line");
    let expected: String = source[..at]
        .chars()
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    assert_eq!(lead, expected, "{shown}");
    assert_eq!(lead.matches('\t').count(), 3, "{shown}");
}
