//! The derivation parser and evaluator on random expressions and files.

use hdot_sym::derivation::load_str_with;
use hdot_sym::limits::Limits;
use proptest::prelude::*;

/// Small limits: every random case stays fast.
const SMALL: Limits = Limits {
    max_terms: 20_000,
    max_work: 2_000_000,
    max_exponent: 200,
    max_bits: 4_000,
};

/// A derivation with one step whose value is `expr`.
fn file_with(expr: &str) -> String {
    let quoted = expr.replace('\\', "\\\\").replace('"', "\\\"");
    format!(
        "title = \"fuzz\"\nsource = \"fuzz\"\n[symbols]\nconstants = [\"a\", \"b\", \"m\"]\ntime = [\"x\", \"theta\"]\n[[frame]]\nname = \"N\"\nangular_velocity = \"[0, 0, x']\"\n[[step]]\nname = \"v\"\nvalue = \"[a, x, b]\"\n[[step]]\nname = \"s\"\nvalue = \"{quoted}\"\nexpect = \"{quoted}\"\n"
    )
}

/// Tokens of the expression language, and some that are not.
fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "a",
            "b",
            "m",
            "x",
            "theta",
            "v",
            "N",
            "x'",
            "x''",
            "omega",
            "+",
            "-",
            "*",
            "/",
            "^",
            "(",
            ")",
            "[",
            "]",
            ",",
            ".",
            ".x",
            "'",
            "=",
            "×",
            "·",
            "dt(",
            "sin(",
            "cos(",
            "cross(",
            "subst(",
            "angvel(N)",
            "inertia(",
            "in N",
            "0",
            "1",
            "2",
            "3/2",
            "1.5",
            "%",
            "é",
            "\\u00e9",
            "\"",
            "\\",
        ])
        .prop_map(str::to_owned),
        (0u64..1_000_000_000).prop_map(|n| n.to_string()),
        "[a-z_]{1,3}".prop_map(|s| s),
    ]
}

/// A well-formed expression of bounded size (so that the evaluator, not
/// only the parser, is exercised).
fn expr() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        prop::sample::select(vec![
            "a", "b", "m", "x", "x'", "theta", "1", "2", "1/3", "0"
        ])
        .prop_map(str::to_owned),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p} + {q})")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p} - {q})")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("{p} * {q}")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p}) / ({q})")),
            (inner.clone(), 0u32..6).prop_map(|(p, k)| format!("({p})^{k}")),
            inner.clone().prop_map(|p| format!("-({p})")),
            inner.clone().prop_map(|p| format!("dt({p})")),
            inner.clone().prop_map(|p| format!("sin({p})")),
            inner.clone().prop_map(|p| format!("cos(theta) * {p}")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("subst({p}, x = {q})")),
            (inner.clone(), inner).prop_map(|(p, q)| format!("cross([{p}, 0, 1], [1, {q}, 0]).x")),
        ]
    })
}

proptest! {
    #![proptest_config(crate::config())]

    /// Token soup: parsed, evaluated or refused — never a panic.
    #[test]
    fn token_soup_never_panics(tokens in prop::collection::vec(token(), 0..30), glue in any::<bool>()) {
        let text = tokens.join(if glue { "" } else { " " });
        let _ = load_str_with("fuzz.toml", &file_with(&text), SMALL);
    }

    /// Well-formed expressions: derived (and checked equal to themselves)
    /// or refused with a located error.
    #[test]
    fn expressions_derive_or_fail_cleanly(e in expr()) {
        match load_str_with("fuzz.toml", &file_with(&e), SMALL) {
            Ok(d) => prop_assert!(d.failures().is_empty(), "{e}: not equal to itself"),
            Err(diag) => prop_assert!(diag.line > 0, "{e}: {diag}"),
        }
    }

    /// Whole files of arbitrary text, and derivation files with a few
    /// bytes changed.
    #[test]
    fn arbitrary_files_never_panic(text in "\\PC{0,200}", cut in 0usize..400, junk in "\\PC{0,8}") {
        let _ = load_str_with("fuzz.toml", &text, SMALL);
        let good = file_with("a*x' + b");
        let mut cut = cut.min(good.len());
        while !good.is_char_boundary(cut) {
            cut -= 1;
        }
        let mutated = format!("{}{junk}{}", &good[..cut], &good[cut..]);
        let _ = load_str_with("fuzz.toml", &mutated, SMALL);
    }
}
