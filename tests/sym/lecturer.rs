//! Forms a lecturer writes (issue 21, items 14 and 16), each on a file
//! written for it in `tests/sym/lecturer/`: a power of a rate solved for as
//! written (the conical pendulum's φ̇²), and prose that names declared
//! symbols as formulas do (`theta'`, `omega_z`, `I'`, `beta`, `Omega`),
//! typeset as those symbols in every format.

use hdot_sym::derivation::{Derivation, load, load_str};
use hdot_sym::document::Course;
use hdot_sym::notes;
use hdot_sym::render::{Format, render};

fn file(name: &str) -> Derivation {
    let path = hdot_tests::repo_root()
        .join("tests/sym/lecturer")
        .join(name);
    load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_power_of_a_rate_is_solved_for_as_written() {
    let d = file("conical-pendulum.toml");
    assert!(d.failures().is_empty(), "{:?}", d.failures());
    let rate = d.steps.iter().find(|s| s.name == "rate").unwrap();
    // φ̇² itself, not φ̇: its square is the value, derived exactly.
    let want = d
        .symbols
        .poly("3*g/(2*L)")
        .unwrap()
        .div_exact(&d.symbols.poly("cos(theta)").unwrap())
        .unwrap();
    assert_eq!(rate.values(), vec![&want]);
    let text = render(&d, Format::Unicode);
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("φ̇² ="))
        .unwrap_or_else(|| panic!("no line φ̇² = …:\n{text}"));
    assert!(line.contains("g") && line.contains("cos θ"), "{line}");
    assert!(render(&d, Format::Latex).contains(r"\dot{\phi}^{2} &="));
}

/// The conical pendulum's file with its last step's value and label
/// replaced.
fn variant(value: &str, label: &str) -> String {
    let path = hdot_tests::repo_root().join("tests/sym/lecturer/conical-pendulum.toml");
    std::fs::read_to_string(path)
        .unwrap()
        .replace("solve(steady.y, phi'^2)", value)
        .replace("label = \"phi'^2\"", &format!("label = \"{label}\""))
        .replace("expect = \"3*g/(2*L*cos(theta))\"\n", "")
}

#[test]
fn a_power_solve_refuses_what_it_cannot_solve_at_the_call() {
    for (value, label, fragment) in [
        (
            "solve(steady.y + phi'*m*g, phi'^2)",
            "phi'^2",
            "`phi'` occurs to the power 1 in the equation",
        ),
        ("solve(steady, phi'^2)", "rate", "needs one scalar equation"),
        (
            "solve(steady.y, theta'^2)",
            "rate",
            "`theta'^2` does not occur",
        ),
        (
            "solve(steady.y, phi'^2)",
            "phi'",
            "is not what the step solves for",
        ),
    ] {
        let text = variant(value, label);
        let e = load_str("cone.toml", &text).expect_err(value);
        assert!(e.line > 0, "{value}: {e}");
        assert!(e.message.contains(fragment), "{value}: {e}");
    }
}

#[test]
fn symbols_named_in_prose_as_in_formulas_are_typeset_as_symbols() {
    let d = file("prose-symbols.toml");
    let unicode = render(&d, Format::Unicode);
    for s in [
        "The spin ω_z = ψ̇ + φ̇ cos(θ) of a top whose transverse moment is I′",
        "θ̇ and φ̇ change; β and Ω are constants",
        "makes the angle θ with the vertical; β is fixed",
        "the spin: ψ̇ + φ̇ cos(θ)",
        "N turned by φ at the rate φ̇",
        "I ω_z, with Ω and β constant",
        // A word that only contains a symbol's name stays a word.
        "The top's axis",
    ] {
        assert!(unicode.contains(s), "`{s}` not in:\n{unicode}");
    }
    let latex = render(&d, Format::Latex);
    for s in [
        r"$\omega_{z} = \dot{\psi} + \dot{\phi} \cos(\theta)$",
        r"$I'$",
        r"$\dot{\theta}$ and $\dot{\phi}$ change; $\beta$ and $\Omega$ are constants",
    ] {
        assert!(latex.contains(s), "`{s}` not in:\n{latex}");
    }
    let markdown = render(&d, Format::Markdown);
    assert!(
        markdown.contains(r"$\dot{\theta}$ and $\dot{\phi}$ change; $\beta$ and $\Omega$"),
        "{markdown}"
    );
    // The web page: the same symbols, never the ASCII names.
    let doc = Course::plain(std::slice::from_ref(&d)).document(std::slice::from_ref(&d));
    let page = notes::html_site(&doc)
        .into_iter()
        .find(|p| p.text.contains("transverse moment"))
        .expect("the derivation's page");
    let prose: String = page
        .text
        .lines()
        .filter(|l| l.contains("transverse moment") || l.contains("change;"))
        .collect();
    for s in ["ω<sub>z</sub> = ψ̇ + φ̇ cos(θ)", ">θ̇<", ">β<", ">Ω<", ">I′<"] {
        assert!(prose.contains(s), "`{s}` not in the page's prose:\n{prose}");
    }
    for ascii in ["theta'", "omega_z", "beta", "Omega", "I'"] {
        assert!(
            !prose.contains(ascii),
            "`{ascii}` in the page's prose:\n{prose}"
        );
    }
}
