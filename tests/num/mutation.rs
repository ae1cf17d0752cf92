//! Verification catches wrong derivations on its own (issue 9, item 6).
//!
//! For every bundled file verified through its declarations, with its
//! expectations removed, small mutations of the *derivation* — a sign in a
//! step, the axis of a frame's rotation, two arguments of an inertia
//! tensor swapped — are applied while the declared model (bodies, points,
//! the frames' motion, `[motion]`) stays the original one. Every mutant
//! whose derived output differs from the original in a step with a
//! meaning — along the motions that step is compared on (`[motion]`'s
//! rules and its `given` substituted) — must be rejected by
//! `hdot_num::verify::check` (a failed comparison, or an error). A mutant
//! that changes only steps without a meaning, or nothing there, is
//! equivalent as far as any measurement can tell and is skipped.
//!
//! Seeded; a bounded number of mutants per file. With the `slow-tests`
//! feature every mutant is tried.

use std::collections::BTreeMap;
use std::path::Path;

use hdot_num::verify::{Options, check};
use hdot_sym::atom::AtomKind;
use hdot_sym::derivation::physics::{Rule, RuleValue};
use hdot_sym::derivation::{Derivation, load_str};
use hdot_sym::poly::Poly;
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;

/// Mutants tried per file without `slow-tests`.
const PER_FILE: usize = 10;

fn bundled() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../derivations");
    let mut out: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n != hdot_sym::course::MANIFEST_FILE)
        })
        .map(|p| {
            (
                p.file_stem().unwrap().to_string_lossy().into_owned(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    out.sort();
    out
}

/// The section a line is in (`step`, `frame`, …), by the last table header.
fn sections(text: &str) -> Vec<String> {
    let mut at = String::new();
    text.lines()
        .map(|l| {
            let t = l.trim();
            if t.starts_with('[') {
                at = t.trim_matches(|c| c == '[' || c == ']').to_string();
            }
            at.clone()
        })
        .collect()
}

/// The quoted string of a `key = "…"` line: (prefix, contents).
fn quoted<'a>(line: &'a str, key: &str) -> Option<(&'a str, &'a str)> {
    let rest = line.strip_prefix(key)?.trim_start().strip_prefix('=')?;
    let start = line.len() - rest.len() + rest.find('"')? + 1;
    let end = line.rfind('"')?;
    (end > start).then(|| (&line[..start], &line[start..end]))
}

/// Arguments of the call starting at `open` (the index of its `(`), as
/// byte ranges without the spaces around them.
fn arguments(s: &str, open: usize) -> Vec<(usize, usize)> {
    raw_arguments(s, open)
        .into_iter()
        .map(|(a, b)| {
            let t = &s[a..b];
            let a = a + (t.len() - t.trim_start().len());
            (a, a + t.trim().len())
        })
        .collect()
}

fn raw_arguments(s: &str, open: usize) -> Vec<(usize, usize)> {
    let mut depth = 0;
    let mut out = Vec::new();
    let mut start = open + 1;
    for (i, c) in s.char_indices().skip_while(|(i, _)| *i < open) {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => {
                depth -= 1;
                if depth == 0 {
                    out.push((start, i));
                    break;
                }
            }
            ',' if depth == 1 => {
                out.push((start, i));
                start = i + 1;
            }
            _ => {}
        }
    }
    out
}

/// Every mutant of `text`: (what was changed, the mutated text).
fn mutants(text: &str) -> Vec<(String, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let sec = sections(text);
    let mut out = Vec::new();
    let with_line = |k: usize, new: String| -> String {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        l[k] = new;
        l.join("\n") + "\n"
    };
    for (k, line) in lines.iter().enumerate() {
        if sec[k] == "step"
            && let Some((prefix, v)) = quoted(line, "value")
        {
            // A sign: each binary + or − flipped; the whole step negated.
            for (i, _) in v.match_indices(" + ").chain(v.match_indices(" - ")) {
                let flipped = if &v[i..i + 3] == " + " { " - " } else { " + " };
                let m = format!("{}{flipped}{}", &v[..i], &v[i + 3..]);
                out.push((
                    format!("line {}: `{}` → `{m}`", k + 1, v),
                    with_line(k, format!("{prefix}{m}\"")),
                ));
            }
            let m = format!("-({v})");
            out.push((
                format!("line {}: negated", k + 1),
                with_line(k, format!("{prefix}{m}\"")),
            ));
            // Two arguments of an inertia tensor swapped.
            for f in ["principal(", "inertia(", "diag("] {
                for (at, _) in v.match_indices(f) {
                    if at > 0 && v[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                        continue;
                    }
                    let args = arguments(v, at + f.len() - 1);
                    for a in 0..args.len() {
                        for b in a + 1..args.len() {
                            let (x, y) = (&v[args[a].0..args[a].1], &v[args[b].0..args[b].1]);
                            if x.trim() == y.trim() {
                                continue;
                            }
                            let m = format!(
                                "{}{}{}{}{}",
                                &v[..args[a].0],
                                y,
                                &v[args[a].1..args[b].0],
                                x,
                                &v[args[b].1..]
                            );
                            out.push((
                                format!("line {}: `{}` → `{m}`", k + 1, v),
                                with_line(k, format!("{prefix}{m}\"")),
                            ));
                        }
                    }
                }
            }
        }
        if sec[k] == "frame"
            && let Some((prefix, v)) = quoted(line, "rotation")
            && let Some(open) = v.find('(')
        {
            // The rotation's axis, among x, y, z (or 1, 2, 3).
            let axis = &v[..open];
            let family: &[&str] = if ["1", "2", "3"].contains(&axis) {
                &["1", "2", "3"]
            } else {
                &["x", "y", "z"]
            };
            for other in family.iter().filter(|a| **a != axis) {
                let m = format!("{other}{}", &v[open..]);
                out.push((
                    format!("line {}: rotation `{v}` → `{m}`", k + 1),
                    with_line(k, format!("{prefix}{m}\"")),
                ));
            }
        }
    }
    out
}

/// `p` along the motions a step is compared on: `[motion]`'s rules and the
/// step's `given` substituted (rules in a rate: `q' = e` replaces q̇, q̈, …;
/// rules setting an angle to a quarter turn evaluate its sine and cosine).
fn along_motion(p: &Poly, rules: &[&Rule]) -> Poly {
    let mut p = p.clone();
    for r in rules {
        let (target, from) = (r.target.base(), r.target.order());
        p = match &r.value {
            RuleValue::Expr(e) => p.subst(&mut |a| match a.kind() {
                AtomKind::Var { .. } if a.base() == target && a.order() >= from => {
                    Some(e.dt_n(a.order() - from))
                }
                _ => None,
            }),
            RuleValue::QuarterTurns(t) => p.subst_quarter_turns(target, *t).unwrap_or(p),
        };
    }
    p
}

/// The unfolded values of each step with a meaning, along the motions it
/// is compared on: a mutant equal to the original there is equivalent as
/// far as any measurement can tell (a rolling disk's contact velocity is
/// zero along every rolling motion, whatever its sign).
fn meaningful(d: &Derivation) -> BTreeMap<String, Vec<Poly>> {
    d.steps
        .iter()
        .filter_map(|s| s.meaning.as_ref().map(|m| (s, m)))
        .map(|(s, m)| {
            let rules: Vec<&Rule> = d.physics.motion.iter().chain(&m.given).collect();
            (
                s.name.clone(),
                s.values()
                    .into_iter()
                    .map(|p| along_motion(&d.unfold(p), &rules))
                    .collect(),
            )
        })
        .collect()
}

#[test]
fn verification_rejects_every_mutant_that_changes_a_step_with_a_meaning() {
    let all = cfg!(feature = "slow-tests");
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut files = 0;
    let mut missed = Vec::new();
    for (name, text) in bundled() {
        let path = format!("{name}.toml");
        let original = load_str(&path, &text).unwrap_or_else(|e| panic!("{e}"));
        if original.steps.iter().all(|s| s.meaning.is_none()) {
            continue;
        }
        files += 1;
        let reference = meaningful(&original);
        let mut ms = mutants(&text);
        ms.shuffle(&mut rng);
        let mut tried = 0;
        for (what, mutated) in ms {
            if !all && tried == PER_FILE {
                break;
            }
            // Not a derivation (a sign that does not parse, an axis the
            // engine refuses): not a mutant.
            let Ok(mut m) = load_str(&path, &mutated) else {
                continue;
            };
            // The expectations removed; the declared model the original.
            for s in &mut m.steps {
                s.checks.clear();
            }
            m.physics = original.physics.clone();
            if meaningful(&m) == reference {
                continue;
            }
            tried += 1;
            let rejected = match check(&m, &Options { draws: 8, seed: 3 }) {
                Ok(r) => !r.passed(),
                Err(_) => true,
            };
            if !rejected {
                missed.push(format!("{name}: {what}"));
            }
        }
        assert!(tried > 0, "{name}: no mutant changed a step with a meaning");
    }
    assert!(
        missed.is_empty(),
        "mutants that verify accepts:\n{}",
        missed.join("\n")
    );
    assert!(
        files >= 10,
        "only {files} files are verified through declarations"
    );
}

#[test]
fn the_mutations_change_what_they_say() {
    let text = "[[frame]]\nname = \"F\"\nrotation = \"z(phi)\"\n[[step]]\nvalue = \"principal(A, B, C) * w + v\"\n";
    let ms: Vec<String> = mutants(text).into_iter().map(|(_, t)| t).collect();
    for expected in [
        "rotation = \"x(phi)\"",
        "rotation = \"y(phi)\"",
        "value = \"principal(A, B, C) * w - v\"",
        "value = \"-(principal(A, B, C) * w + v)\"",
        "value = \"principal(B, A, C) * w + v\"",
        "value = \"principal(A, C, B) * w + v\"",
        "value = \"principal(C, B, A) * w + v\"",
    ] {
        assert!(ms.iter().any(|t| t.contains(expected)), "{expected}");
    }
    assert_eq!(ms.len(), 7);
}
