//! The work budget: deterministic counts of symbolic work
//! ([`hdot_sym::work`]) on reference workloads, held to the figures
//! committed in `tests/sym/work_budget.toml`.
//!
//! A workload is what `hdot derive NAME --format latex` does: load (parse,
//! derive, check every expectation), present and print. A figure more than
//! 20 % over its committed value fails the test, so a pass that makes the
//! engine or the presentation several times dearer is caught in the change
//! that adds it, whatever the load of the machine that runs the tests.

use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::render::{Format, render};
use hdot_sym::work::{Work, measure};

/// How far a figure may rise over the committed one.
const TOLERANCE: f64 = 1.20;

const BUDGET_FILE: &str = "tests/sym/work_budget.toml";

fn load(name: &str) -> Derivation {
    if let Some(k) = hdot_sym::chain::parse_name(name) {
        return hdot_sym::chain::derivation(k).unwrap_or_else(|e| panic!("{e}"));
    }
    let path = hdot_tests::repo_root().join(format!("derivations/{name}.toml"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
    load_str(&format!("derivations/{name}.toml"), &text).unwrap_or_else(|e| panic!("{e}"))
}

/// The work of one workload: load, then print in LaTeX.
fn work_of(name: &str) -> (Work, usize) {
    let (out, w) = measure(|| render(&load(name), Format::Latex));
    assert!(!out.is_empty(), "{name}: empty output");
    (w, out.len())
}

#[test]
fn reference_workloads_stay_within_their_committed_work() {
    let path = hdot_tests::repo_root().join(BUDGET_FILE);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{BUDGET_FILE}: {e}"));
    let table: toml::Table = text
        .parse()
        .unwrap_or_else(|e| panic!("{BUDGET_FILE}: {e}"));
    let workloads = table
        .get("workload")
        .and_then(|w| w.as_array())
        .unwrap_or_else(|| panic!("{BUDGET_FILE}: no [[workload]] tables"));
    assert!(workloads.len() >= 5, "{BUDGET_FILE}: too few workloads");
    let mut over = Vec::new();
    let mut report = String::new();
    for w in workloads {
        let field = |k: &str| {
            w.get(k)
                .unwrap_or_else(|| panic!("{BUDGET_FILE}: a workload without `{k}`"))
        };
        let name = field("name").as_str().expect("name is a string");
        let reason = field("reason").as_str().expect("reason is a string");
        assert!(
            !reason.trim().is_empty(),
            "{BUDGET_FILE}: {name} has no reason"
        );
        let (measured, bytes) = work_of(name);
        report.push_str(&format!(
            "[[workload]]\nname = \"{name}\"\nmonomial_products = {}\nterms_accumulated = {}\npresented_nodes = {}\nreason = \"{reason}\"\n# output: {bytes} bytes of LaTeX\n\n",
            measured.monomial_products, measured.terms_accumulated, measured.presented_nodes
        ));
        for (key, value) in [
            ("monomial_products", measured.monomial_products),
            ("terms_accumulated", measured.terms_accumulated),
            ("presented_nodes", measured.presented_nodes),
        ] {
            let budget = field(key)
                .as_integer()
                .unwrap_or_else(|| panic!("{BUDGET_FILE}: {name}.{key} is not an integer"));
            assert!(budget > 0, "{BUDGET_FILE}: {name}.{key} must be positive");
            if value as f64 > budget as f64 * TOLERANCE {
                over.push(format!(
                    "{name}: {key} = {value}, {:.0} % of the committed {budget}",
                    100.0 * value as f64 / budget as f64
                ));
            }
        }
    }
    assert!(
        over.is_empty(),
        "work over budget (more than {:.0} % of the committed figure):\n  {}\n\n\
         If the extra work is intended (a new rule that needs it), raise the figures in \
         {BUDGET_FILE} to the measured ones below and say why in `reason`; otherwise find \
         the pass that grew (docs/performance.md, `perf record`).\n\nMeasured:\n\n{report}",
        TOLERANCE * 100.0,
        over.join("\n  ")
    );
    // `cargo test -p hdot-tests --test sym work_budget -- --nocapture`
    // prints the figures measured, ready to paste.
    println!("{report}");
}

/// The counters count work, not time: the same workload twice gives the
/// same figures.
#[test]
fn the_work_of_a_workload_is_repeatable() {
    let (a, _) = work_of("gyroscope");
    let (b, _) = work_of("gyroscope");
    assert_eq!(a, b);
    assert!(a.monomial_products > 0 && a.terms_accumulated > 0 && a.presented_nodes > 0);
}

/// A sum of n distinct constants (`hdot_sym::chain::sum_source`, made
/// here, never stored) costs work linear in n: every pass from the file to
/// the LaTeX sees n terms, so twice the terms may cost at most 2.2 times
/// the work. Adding the terms one at a time (each addition merging the
/// whole sum so far) cost n²/2 and failed this.
#[test]
fn a_long_sum_costs_work_linear_in_its_length() {
    let work = |n: usize| {
        let (out, w) = measure(|| {
            let d = load_str(&format!("sum-{n}.toml"), &hdot_sym::chain::sum_source(n))
                .unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(d.steps[0].values()[0].len(), n, "sum-{n}: terms");
            render(&d, Format::Latex)
        });
        assert!(
            out.contains(&format!("c_{{{n}}}")),
            "sum-{n}: last term not printed"
        );
        assert!(w.terms_accumulated >= n as u64, "sum-{n}: {w:?}");
        assert!(w.presented_nodes >= n as u64, "sum-{n}: {w:?}");
        w
    };
    let n = 4_000;
    let (one, two) = (work(n), work(2 * n));
    for (key, a, b) in [
        (
            "monomial_products",
            one.monomial_products,
            two.monomial_products,
        ),
        (
            "terms_accumulated",
            one.terms_accumulated,
            two.terms_accumulated,
        ),
        ("presented_nodes", one.presented_nodes, two.presented_nodes),
    ] {
        assert!(
            b as f64 <= 2.2 * a as f64,
            "{key}: {a} for {n} terms, {b} for {} — more than linear",
            2 * n
        );
    }
}
