//! The snapshot file of a derivation: what it derives, readable on its own
//! and in a diff — the verdicts of check and verify, then every step's
//! equations in textbook form, one per line, each followed by its
//! canonical form — and nothing that changes between runs (no times, no
//! absolute paths, no measured errors). It is also read back, so that a
//! changed snapshot is reported as a semantic diff.

use std::fmt::Write;

use hdot_sym::Symbols;
use hdot_sym::derivation::Derivation;

use super::compare::{Component, StepView, Version, one_line};

/// The first line's opening: what recognises a snapshot file.
pub const HEADER: &str = "# hdot snapshot of ";

/// The extension of snapshot files (`NAME.hdot.txt`).
pub const EXTENSION: &str = ".hdot.txt";

/// Marks the canonical form below an equation.
const CANONICAL: &str = "    canonical";

/// The verdict of `hdot verify` on a derivation, as a snapshot states it.
pub fn verify_line(d: &Derivation, draws: usize) -> String {
    let options = hdot_num::verify::Options { draws, seed: 0 };
    match hdot_num::verify::check(d, &options) {
        Err(e) => format!("verify: error: {e}"),
        Ok(r) if r.steps.is_empty() => "verify: nothing compared".to_owned(),
        Ok(r) => {
            let steps: Vec<String> = r
                .steps
                .iter()
                .map(|s| {
                    format!(
                        "{} ({}){}",
                        s.step,
                        s.means,
                        if s.passed { "" } else { " FAILS" }
                    )
                })
                .collect();
            format!(
                "verify: {} — compared with particle sums: {}",
                if r.passed() { "pass" } else { "FAIL" },
                steps.join(", ")
            )
        }
    }
}

/// The verdict of `hdot check`.
fn check_line(d: &Derivation) -> String {
    let n = d.check_count();
    let failures = d.failures();
    if n == 0 {
        "check: no expectations".to_owned()
    } else if failures.is_empty() {
        format!("check: ok, {n} expectations hold")
    } else {
        let which: Vec<String> = failures
            .iter()
            .map(|(s, c)| {
                if c.component.is_empty() {
                    (*s).to_owned()
                } else {
                    format!("{s}.{}", c.component)
                }
            })
            .collect();
        format!(
            "check: FAILED, {} of {n} expectations do not hold: {}",
            failures.len(),
            which.join(", ")
        )
    }
}

/// The snapshot text of `d`, shown as coming from `shown_path` (relative),
/// with the verify verdict `verify`.
pub fn render(d: &Derivation, shown_path: &str, verify: &str) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{HEADER}{shown_path} — written by `hdot snapshot --accept`; review it in the diff"
    );
    let _ = writeln!(o, "title: {}", one_line(&d.title));
    let _ = writeln!(o, "{}", check_line(d));
    let _ = writeln!(o, "{verify}");
    let by_step = Version::of(d);
    for (s, view) in d.steps.iter().zip(&by_step.steps) {
        let _ = writeln!(o);
        let _ = writeln!(
            o,
            "step {}{}: {}",
            s.name,
            if s.show { "" } else { " (not shown)" },
            one_line(&s.formula)
        );
        for c in &view.components {
            let _ = writeln!(o, "  {}", c.text);
            let label = if c.label.is_empty() {
                String::new()
            } else {
                format!(" {}", c.label)
            };
            let _ = writeln!(o, "{CANONICAL}{label}: {}", c.canonical_text);
        }
        let fails: Vec<_> = s.checks.iter().filter(|c| !c.holds()).collect();
        if !s.checks.is_empty() && fails.is_empty() {
            let _ = writeln!(o, "  ✓ equals the expected form");
        }
        for c in fails {
            let _ = writeln!(
                o,
                "  ✗ expected {}{}; derived − expected = {}",
                c.expected_text.trim(),
                if c.component.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", c.component)
                },
                c.difference.to_source()
            );
        }
    }
    o
}

/// Whether `text` is a snapshot file.
pub fn is_snapshot(text: &str) -> bool {
    text.starts_with(HEADER)
}

/// The lines of a snapshot before its first step (title and verdicts).
pub fn head(text: &str) -> Vec<&str> {
    text.lines()
        .skip(1)
        .take_while(|l| !l.starts_with("step "))
        .filter(|l| !l.is_empty())
        .collect()
}

/// Reads the steps of a snapshot back, the canonical forms in the
/// symbols of `symbols` (a form naming a symbol no longer declared reads
/// as `None`, compared by its text).
pub fn read(text: &str, symbols: &Symbols) -> Version {
    let mut steps: Vec<StepView> = Vec::new();
    let mut last_equation: Option<&str> = None;
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("step ") {
            let (head, formula) = rest.split_once(": ").unwrap_or((rest, ""));
            let (name, shown) = match head.strip_suffix(" (not shown)") {
                Some(n) => (n, false),
                None => (head, true),
            };
            steps.push(StepView {
                name: name.to_owned(),
                formula: formula.to_owned(),
                shown,
                components: Vec::new(),
            });
            last_equation = None;
        } else if let Some(rest) = line.strip_prefix(CANONICAL) {
            let (label, canonical) = rest.split_once(": ").unwrap_or(("", rest));
            if let (Some(step), Some(eq)) = (steps.last_mut(), last_equation.take()) {
                step.components.push(Component {
                    label: label.trim().to_owned(),
                    text: eq.to_owned(),
                    latex: None,
                    canonical: symbols.poly(canonical).ok(),
                    canonical_text: canonical.to_owned(),
                });
            }
        } else if let Some(eq) = line.strip_prefix("  ") {
            last_equation = Some(eq);
        }
    }
    Version { steps }
}
