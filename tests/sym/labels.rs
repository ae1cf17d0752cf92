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
