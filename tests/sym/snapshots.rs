//! Every derivation file in every output format, as insta snapshots
//! (`glob!` over `derivations/`): a changed derivation is a readable diff.

use hdot_sym::derivation::load_str;
use hdot_sym::render::{Format, render};

#[test]
fn every_derivation_in_every_format() {
    insta::glob!("../../derivations", "*.toml", |path| {
        let text = std::fs::read_to_string(path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        let shown = format!("derivations/{name}");
        let d = load_str(&shown, &text).unwrap_or_else(|e| panic!("{e}"));
        assert!(d.all_hold(), "{shown}: {:?}", d.failures());
        for (tag, format) in [
            ("unicode", Format::Unicode),
            ("latex", Format::Latex),
            ("markdown", Format::Markdown),
            ("sympy", Format::Sympy),
            ("json", Format::Json),
        ] {
            insta::assert_snapshot!(tag, render(&d, format));
        }
    });
}
