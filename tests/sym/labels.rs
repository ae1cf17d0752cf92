//! Step labels as a lecturer writes them (issue 21, item 15): words kept
//! apart (`m a_G`, never `ma_G`), and formulas of declared symbols and
//! earlier steps with `|…|`, powers and a number in front (`|H_G|^2`,
//! `H_G^2`, `2T`); a formula naming something undeclared is refused at
//! the label.

use hdot_sym::derivation::load_str;
use hdot_sym::render::{Format, render};

const FILE: &str = r#"
title = "labels"
source = "a lecturer"
[symbols]
constants = ["m"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "B"
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "H_G"
value = "m*angvel(B)"
[[step]]
name = "HG2"
label = "|H_G|^2"
value = "dot(H_G, H_G)"
[[step]]
name = "H2"
label = "H_G^2"
value = "dot(H_G, H_G)"
[[step]]
name = "T"
value = "dot(H_G, angvel(B))/2"
[[step]]
name = "twoT"
label = "2T"
value = "2*T"
[[step]]
name = "ma"
label = "m a_G"
value = "m*w_x"
[[step]]
name = "minusT"
label = "-T"
value = "-T"
[[step]]
name = "minus2"
label = "− m H_G"
value = "-m*H_G"
"#;

#[test]
fn labels_are_words_apart_and_formulas_of_symbols_and_steps() {
    let d = load_str("labels.toml", FILE).unwrap_or_else(|e| panic!("{e}"));
    let text = render(&d, Format::Unicode);
    for line in [
        "   |H_G|² = m² (w_x² + w_y² + w_z²)",
        "   H_G² = m² (w_x² + w_y² + w_z²)",
        "   2T = m (w_x² + w_y² + w_z²)",
        "   m a_G = m w_x",
    ] {
        assert!(
            text.lines().any(|l| l == line),
            "no line `{line}` in\n{text}"
        );
    }
    let latex = render(&d, Format::Latex);
    for line in [
        r"{\left|H_G\right|}^{2} &= m^{2} \left(w_x^{2} + w_y^{2} + w_z^{2}\right)",
        r"{H_G}^{2} &= m^{2} \left(w_x^{2} + w_y^{2} + w_z^{2}\right)",
        r"2\,T &= m \left(w_x^{2} + w_y^{2} + w_z^{2}\right)",
        r"m a_G &= m w_x",
    ] {
        assert!(
            latex
                .lines()
                .any(|l| l.trim_end_matches([' ', '\\']) == line),
            "no line `{line}` in\n{latex}"
        );
    }
}

#[test]
fn a_label_formula_names_only_symbols_and_earlier_steps() {
    for (label, says) in [
        ("|K|^2", "`K` is neither a declared symbol nor a step"),
        ("|H_G^2", "without its closing"),
        ("H_G|^2", "cannot be written in a label formula"),
        ("|H_G|^0", "whole number from 1 to 99"),
        (r"|\input|", "cannot be written in a label formula"),
        ("2later", "`later` is neither"),
    ] {
        let file = FILE.replace("label = \"2T\"", &format!("label = {label:?}"));
        let file = format!("{file}\n[[step]]\nname = \"later\"\nvalue = \"m\"\n");
        let e = load_str("labels.toml", &file).expect_err(label);
        assert!(
            e.message.contains("field `label`") && e.message.contains(says),
            "{label}: {}",
            e.message
        );
        assert_eq!(e.line, 26, "{label}: {e}");
    }
}

/// A label formula is what it evaluates to (issue 21, item 15): `|v|^2` is
/// v·v, `H^2` of a vector likewise, `2T` twice the step `T`, words that are
/// all symbols or steps (`m a_G`) their product, a bare `|x|` compared
/// through squares, a step's own name its value; each holds here.
const HOLDS: &str = r#"
title = "labels that hold"
source = "written for the test"
[symbols]
constants = ["m", "k"]
time = ["x", "theta"]
[[frame]]
name = "B"
parent = "N"
rotation = "z(theta)"
[[step]]
name = "a_G"
value = "[x'', 0, 0] in B"
[[step]]
name = "F"
label = "m a_G"
value = "express([m*x'', 0, 0] in B, N)"
[[step]]
name = "v2"
label = "|a_G|^2"
value = "x''^2"
[[step]]
name = "T"
value = "m*x'^2/2"
[[step]]
name = "twoT"
label = "2T"
value = "m*x'^2"
[[step]]
name = "mag"
label = "|k x|"
value = "-k*x"
[[step]]
name = "sq"
label = "sq^1"
value = "k*x^2"
"#;

#[test]
fn a_label_formula_holds_when_it_is_the_value() {
    let d = load_str("holds.toml", HOLDS).unwrap_or_else(|e| panic!("{e}"));
    assert!(d.all_hold(), "{:?}", d.failures());
}

#[test]
fn a_label_formula_that_is_not_the_value_is_a_located_error() {
    for (from, to, says) in [
        // |a_G|² = ẍ² + 1 is false.
        (
            "value = \"x''^2\"",
            "value = \"x''^2 + 1\"",
            "their difference is 1",
        ),
        // m a_G with a different value, in another frame.
        (
            "value = \"express([m*x'', 0, 0] in B, N)\"",
            "value = \"express([m*x'', m, 0] in B, N)\"",
            "`m a_G` means",
        ),
        // 2T with the value of T.
        ("value = \"m*x'^2\"", "value = \"m*x'^2/2\"", "`2T` means"),
        // |k x| squared is k² x², not k x².
        ("value = \"-k*x\"", "value = \"k*x^2\"", "squared"),
        // The step's own name stands for its value: sq¹ = 2 sq is false.
        ("label = \"sq^1\"", "label = \"2sq\"", "`2sq` means"),
        // A vector is no scalar.
        ("label = \"|a_G|^2\"", "label = \"a_G\"", ""),
    ] {
        let file = HOLDS.replace(from, to);
        assert_ne!(file, HOLDS, "{from}");
        match load_str("holds.toml", &file) {
            Err(e) => {
                assert!(
                    e.message.contains("field `label`") && e.message.contains(says),
                    "{to}: {}",
                    e.message
                );
                assert!(e.line > 0 && e.column > 0, "{to}: {e}");
            }
            // A single word that names a step stays a name.
            Ok(_) => assert_eq!(to, "label = \"a_G\"", "{to} was accepted"),
        }
    }
}

#[test]
fn a_label_formula_of_two_vectors_side_by_side_is_refused() {
    let file = HOLDS.replace("label = \"m a_G\"", "label = \"a_G a_G\"");
    let e = load_str("holds.toml", &file).expect_err("two vectors");
    assert!(
        e.message.contains("two vectors side by side"),
        "{}",
        e.message
    );
}

/// A name with several underscores (issue 24): the first starts the
/// subscript, each further one separates an index; indices print with
/// commas, braced in Unicode (`A_{c,rate}`, never `A_c,rate`); one index
/// prints as before; the SymPy export keeps the name, a valid identifier.
#[test]
fn a_name_with_several_underscores_prints_its_indices_apart() {
    use hdot_sym::print::{latex_symbol, unicode_symbol};
    for (name, order, unicode, latex) in [
        ("A_c_rate", 0, "A_{c,rate}", "A_{c,rate}"),
        (
            "R_B_steady",
            1,
            "R\u{307}_{B,steady}",
            r"\dot{R}_{B,steady}",
        ),
        ("omega_B_theta", 0, "ω_{B,θ}", r"\omega_{B,\theta}"),
        ("omega_x", 0, "ω_x", r"\omega_x"),
        ("I_xy", 0, "I_xy", "I_{xy}"),
    ] {
        assert_eq!(unicode_symbol(name, order), unicode, "{name}");
        assert_eq!(latex_symbol(name, order), latex, "{name}");
    }
    let file = r#"
title = "names"
source = "written for the test"
[symbols]
constants = ["A_c_rate", "k"]
[[step]]
name = "b_c_rate"
value = "k*A_c_rate"
"#;
    let d = load_str("names.toml", file).unwrap_or_else(|e| panic!("{e}"));
    let text = render(&d, Format::Unicode);
    assert!(text.contains("= A_{c,rate} k"), "{text}");
    assert!(!text.contains("A_c,rate"), "{text}");
    let sympy = render(&d, Format::Sympy);
    assert!(sympy.contains("Symbol('A_c_rate')"), "{sympy}");
    // Every variable the export binds is a Python identifier.
    for line in sympy.lines() {
        if let Some((lhs, _)) = line.split_once(" = ")
            && !lhs.starts_with([' ', '#'])
        {
            for v in lhs.split(", ") {
                assert!(
                    v.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                        && !v.starts_with(|c: char| c.is_ascii_digit()),
                    "`{v}` in {line}"
                );
            }
        }
    }
}
