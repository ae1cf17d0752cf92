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
