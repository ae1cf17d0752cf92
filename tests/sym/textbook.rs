//! Printed forms a textbook would use, each on a file written for it
//! (`tests/sym/textbook/*.toml`): an abbreviation's own component prints
//! its definition, a constant ratio prints one way in every solve, like
//! terms are grouped, and the terms of what the file solves for come
//! first. The files' printed forms are insta snapshots,
//! and every presented component expands back to its derived value.

use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::render::{Format, render};

/// A file of `tests/sym/textbook/`, derived.
fn derived(name: &str) -> Derivation {
    let path = hdot_tests::repo_root()
        .join("tests/sym/textbook")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    load_str(&format!("tests/sym/textbook/{name}"), &text).unwrap_or_else(|e| panic!("{e}"))
}

/// The printed components of step `step`, in Unicode.
fn printed(d: &Derivation, step: &str) -> Vec<String> {
    let s = d
        .steps
        .iter()
        .find(|s| s.name == step)
        .unwrap_or_else(|| panic!("no step {step}"));
    s.components()
        .iter()
        .map(|(_, e)| hdot_sym::print::unicode(e))
        .collect()
}

#[test]
fn textbook_files_in_unicode_and_latex() {
    insta::glob!("textbook", "*.toml", |path| {
        let name = path.file_name().unwrap().to_string_lossy();
        let d = derived(&name);
        assert!(crate::presentation::assert_exact(&d) > 0, "{name}");
        insta::assert_snapshot!("unicode", render(&d, Format::Unicode));
        insta::assert_snapshot!("latex", render(&d, Format::Latex));
    });
}

/// Issue 21 item 11: the component an abbreviation defines is printed as
/// its definition, never as the abbreviation itself (ω_z = ω_z); the
/// other components and steps still fold it.
#[test]
fn an_abbreviation_prints_its_definition_where_it_defines_it() {
    let d = derived("top.toml");
    assert_eq!(
        printed(&d, "omega"),
        ["−φ\u{307} sin θ", "θ\u{307}", "φ\u{307} cos θ + ψ\u{307}"]
    );
    assert_eq!(printed(&d, "H")[2], "I ω_z");
}

/// Issue 21 item 12: one rule for a constant ratio. The nutation equation
/// solved alone prints as it does in the list solved for all three
/// accelerations; and a term does not take one style of ratio beside
/// another style in the same line (the rod's reactions).
#[test]
fn a_constant_ratio_prints_one_way_everywhere() {
    let d = derived("top.toml");
    let theta = "φ\u{307}² sin θ cos θ − (I/I′) ω_z φ\u{307} sin θ + (m g l/I′) sin θ";
    assert_eq!(printed(&d, "accelerations")[1], theta);
    assert_eq!(printed(&d, "nutation"), [theta]);
    let d = derived("rod.toml");
    assert_eq!(
        printed(&d, "reactions")[0],
        "−(1/12) (3 m L sin β + (2 m L²/a) sin β cos β) φ\u{307}² − (m g L/(4 a)) sin β"
    );
}

/// Issue 21 item 13: like terms grouped — terms with the same constants
/// and rates that differ in sin and cos are one term with a bracket of
/// those; unknowns with one coefficient are one term, and a half is not
/// pulled over a bracket of doubles.
#[test]
fn like_terms_are_grouped() {
    let d = derived("top.toml");
    assert_eq!(
        printed(&d, "accelerations")[2],
        "(I′ φ\u{307} (1 + cos² θ) − I ω_z cos θ) θ\u{307}/(I′ sin θ)"
    );
    let d = derived("rod.toml");
    assert_eq!(
        printed(&d, "moment"),
        ["a (A_x − B_x) + (1/2) m g L sin β + I′ φ\u{307}² sin β cos β"]
    );
}

/// Issue 21 item 13: the terms of what the file solves for come first in
/// every step that holds them, even in an equation written before its
/// `solve` (the rod's reactions A_x and B_x); a file that solves for
/// nothing keeps the order of the other rules.
#[test]
fn unknowns_come_first() {
    let d = derived("rod.toml");
    assert_eq!(
        printed(&d, "force"),
        ["A_x + B_x + (1/2) m L φ\u{307}² sin β"]
    );
    let path = hdot_tests::repo_root().join("tests/sym/textbook/rod.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let (unsolved, _) = text.split_once("[[step]]\nname = \"reactions\"").unwrap();
    let d = load_str("rod.toml", unsolved).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        printed(&d, "force"),
        ["(1/2) m L φ\u{307}² sin β + A_x + B_x"]
    );
}
