//! Printed forms a textbook would use, each on a file written for it
//! (`tests/sym/textbook/*.toml`): an abbreviation's own component prints
//! its definition, a constant ratio prints one way in every solve, like
//! terms are grouped, and the terms of what the file solves for come
//! first, the known terms from the lowest degree in the rates; a
//! coefficient that is a sum of positive constants is divided by and
//! prints as a fraction over the sum. The files' printed forms are insta
//! snapshots,
//! and every presented component expands back to its derived value.

use hdot_num::eval::Tape;
use hdot_sym::atom::{Atom, AtomKind};
use hdot_sym::derivation::{Derivation, Value, load_str};
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

/// Issue 21 item 13: unknowns declared as functions of time (a shaft's
/// reactions A_x(t), B_x(t), as welded-rod-on-shaft.toml declares them)
/// are grouped over their common coefficient as constant unknowns are:
/// the moment equation prints as rod.toml's, whose reactions are
/// constants.
#[test]
fn unknowns_of_time_are_grouped_as_constant_unknowns() {
    let of_time = derived("reactions-of-time.toml");
    assert_eq!(
        printed(&of_time, "moment"),
        ["a (A_x − B_x) + (1/2) m g L sin β + I′ φ\u{307}² sin β cos β"]
    );
    assert_eq!(
        printed(&of_time, "moment"),
        printed(&derived("rod.toml"), "moment")
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

/// Issue 21 item 16: a coefficient that is a sum of constants whose terms
/// are positive for the constants declared `positive` is divided by
/// exactly; the result prints as a fraction over the sum, the sum's
/// terms free of fractions (a = m g r² sin β/(I + m r²), the textbook's
/// g sin β/(1 + I/(m r²)), which the file expects; the sum presented as
/// a textbook writes it, J + R² (m_1 + m_2)), and equals what
/// another route gives.
#[test]
fn a_sum_of_positive_constants_is_divided_by() {
    let d = derived("sums.toml");
    assert_eq!(printed(&d, "a_disk"), ["m g r² sin β/(I + m r²)"]);
    assert_eq!(
        printed(&d, "a_pulley"),
        ["g R² (m_1 − m_2)/(J + R² (m_1 + m_2))"]
    );
    assert_eq!(printed(&d, "alpha"), ["M_a r²/(I L² + I′ r²)"]);
    let checks: Vec<_> = d.steps.iter().flat_map(|s| &s.checks).collect();
    assert_eq!(checks.len(), 3);
    assert!(checks.iter().all(|c| c.holds()));
    // The value, by the polynomial and by the compiled tape, is the
    // textbook's g sin β/(1 + I/(m r²)).
    let (m, g, r, i, beta) = (2.0, 9.81, 0.3, 0.05, 0.4f64);
    let known = |a: Atom| match a.name() {
        "m" => Some(m),
        "g" => Some(g),
        "r" => Some(r),
        "I" => Some(i),
        "beta" => Some(beta),
        _ => None,
    };
    let Value::Scalar(a) = &d.steps.iter().find(|s| s.name == "a_disk").unwrap().value else {
        panic!("a scalar")
    };
    let exact = g * beta.sin() / (1.0 + i / (m * r * r));
    let by_poly = a.eval(&mut |x| match x.kind() {
        AtomKind::Sin(q) => known(q).unwrap().sin(),
        AtomKind::Cos(q) => known(q).unwrap().cos(),
        _ => known(x).unwrap(),
    });
    let tape = Tape::compile_with(std::slice::from_ref(a), &mut |x| match x.kind() {
        AtomKind::Sin(q) => known(q).map(f64::sin),
        AtomKind::Cos(q) => known(q).map(f64::cos),
        _ => known(x),
    });
    assert!(
        tape.atoms().is_empty(),
        "every atom folded: {:?}",
        tape.atoms()
    );
    let mut by_tape = [0.0];
    tape.eval(&[], &mut by_tape);
    for v in [by_poly, by_tape[0]] {
        assert!(
            (v - exact).abs() <= 8.0 * f64::EPSILON * exact.abs(),
            "{v} against {exact}"
        );
    }
}

/// Issue 21 item 16: a sum that could be zero is not divided by: the
/// error is located at the `solve` and says which sum and why.
#[test]
fn a_sum_that_could_be_zero_is_a_located_error() {
    let file = |positive: &str| {
        format!(
            "title = \"t\"\nsource = \"written for the test\"\n[symbols]\nconstants = [\"I\", \"J\", \"M\"]\n\
             time = [\"phi\"]\npositive = [{positive}]\n[[step]]\nname = \"a\"\n\
             value = \"solve(I*phi'' - J*phi'' - M, phi'')\"\n"
        )
    };
    let e = load_str("t.toml", &file("\"I\", \"J\"")).unwrap_err();
    assert_eq!((e.line, e.column), (9, 16), "{e}");
    assert!(e.message.contains("could be zero"), "{e}");
    assert!(e.message.contains("I - J"), "{e}");
    // A sum whose sign is not known because nothing is declared positive.
    let text = file("").replace("I*phi'' - J*phi''", "I*phi'' + J*phi''");
    let e = load_str("t.toml", &text).unwrap_err();
    assert!(e.message.contains("could be zero"), "{e}");
    // Declared positive, the sum I + J divides.
    let text = file("\"I\", \"J\"").replace("I*phi'' - J*phi''", "I*phi'' + J*phi''");
    let d = load_str("t.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(printed(&d, "a"), ["M/(I + J)"]);
}
