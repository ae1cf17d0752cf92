//! Verification catches wrong derivations on its own (issue 9, item 6;
//! issue 20, item 5).
//!
//! For every bundled file verified through its declarations, and the files
//! written for this test, with the expectations removed, small mutations of
//! the *derivation* — the slips a lecturer makes: a sign in a step, the axis
//! of a frame's rotation, two arguments of an inertia tensor or of `cross`
//! swapped, a factor 2 ↔ 3 or ½ ↔ 1, a vector expressed in another frame,
//! `dt` for `dt_rel`, a term of a sum left out — are applied while the declared model (bodies, points,
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

/// The bundled files and those written for this test
/// (`tests/num/derivations/`).
fn bundled() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out: Vec<(String, String)> =
        [root.join("../derivations"), root.join("num/derivations")]
            .iter()
            // The folder of files written for the test may be empty (absent).
            .filter_map(|dir| std::fs::read_dir(dir).ok())
            .flatten()
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
    // The frames a vector may be expressed in: N and every declared one.
    let frames: Vec<String> = std::iter::once("N".to_string())
        .chain(lines.iter().enumerate().filter_map(|(k, l)| {
            (sec[k] == "frame")
                .then(|| quoted(l, "name").map(|(_, n)| n.to_string()))
                .flatten()
        }))
        .collect();
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
                format!("line {}: `{v}` negated", k + 1),
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
        if sec[k] == "step"
            && let Some((prefix, v)) = quoted(line, "value")
        {
            for (what, m) in lecturer_slips(v, &frames) {
                out.push((
                    format!("line {}: {what}: `{v}` → `{m}`", k + 1),
                    with_line(k, format!("{prefix}{m}\"")),
                ));
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

/// The kind of a mutant no measurement can tell from the original: a
/// step's whole value expressed in other axes is the same vector, and a
/// vector step is compared in its own axes. Such mutants are counted and
/// skipped, not tried.
const EQUIVALENT: &str = "the whole value in another frame (the same vector)";

/// Mutants of particular files that no measurement can tell from the
/// original, each with the reason: (file, the mutated text, why).
const LISTED: &[(&str, &str, &str)] = &[(
    "steady-precession",
    "principal(Ip, Ip, I) * express(angvel(R), R)",
    "the rotor is axisymmetric about z, which R and F share: principal(Ip, Ip, I) is the same tensor in both axes, so [I]ω in R's axes is the same H",
)];

/// Steps whose value is zero along every motion the file's constraints
/// allow (a contact's velocity, a configuration constraint): negated, they
/// are the same constraint and measure the same zero, so verify cannot
/// and need not tell them apart.
const VANISHING: &[(&str, &str, &str)] = &[
    (
        "bicycle",
        "express(rolling(rear_wheel, P), A)",
        "the rear contact's velocity, zero along every rolling motion whatever its sign",
    ),
    (
        "disk-on-its-rim",
        "express(rolling(disk, C), A)",
        "the contact's velocity, zero along every rolling motion whatever its sign",
    ),
    (
        "disk-rolling-on-plane",
        "express(rolling(disk, C), A)",
        "the contact's velocity, zero along every rolling motion whatever its sign",
    ),
    (
        "disk-rolling-on-plane",
        "list(contact.x, contact.y)",
        "the no-slip rows, zero along every rolling motion whatever their sign",
    ),
    (
        "disk-on-its-rim",
        "h - r*cos(theta)",
        "the configuration constraint, zero at every drawn configuration; −f = 0 is f = 0",
    ),
];

/// Where each call of `f` (a whole name: `cross(` not `xcross(`) opens.
fn calls<'a>(v: &'a str, f: &'a str) -> impl Iterator<Item = usize> + 'a {
    v.match_indices(f)
        .filter(move |(at, _)| {
            *at == 0 || !v[..*at].ends_with(|c: char| c.is_alphanumeric() || c == '_')
        })
        .map(move |(at, _)| at + f.len() - 1)
}

/// The slips a lecturer makes in a step's formula, each with its kind:
/// the arguments of `cross` swapped, a factor 2 ↔ 3 or ½ ↔ 1, a vector
/// expressed in another frame, `dt` for `dt_rel`, a term of a sum left
/// out.
fn lecturer_slips(v: &str, frames: &[String]) -> Vec<(&'static str, String)> {
    let mut out = Vec::new();
    let splice = |a: usize, b: usize, with: &str| format!("{}{with}{}", &v[..a], &v[b..]);
    for open in calls(v, "cross(") {
        if let [a, b] = arguments(v, open).as_slice() {
            let (x, y) = (&v[a.0..a.1], &v[b.0..b.1]);
            out.push((
                "cross swapped",
                format!("{}{y}{}{x}{}", &v[..a.0], &v[a.1..b.0], &v[b.1..]),
            ));
        }
    }
    for (at, _) in v.match_indices("/2") {
        out.push(("factor 1/2 to 1", splice(at, at + 2, "")));
        out.push(("factor 2 to 3", splice(at, at + 2, "/3")));
    }
    for (at, _) in v.match_indices("2*") {
        if at == 0 || !v[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == '^') {
            out.push(("factor 2 to 3", splice(at, at + 2, "3*")));
        }
    }
    for open in calls(v, "express(") {
        if let [_, f] = arguments(v, open).as_slice() {
            let frame = v[f.0..f.1].trim();
            // The whole value in other axes is the same vector: true, and
            // compared in its own axes (an equivalent mutant, listed).
            let whole = open + 1 == "express(".len() && v[f.1..].trim() == ")";
            let kind = if whole {
                EQUIVALENT
            } else {
                "another frame in express"
            };
            for other in frames.iter().filter(|o| o.as_str() != frame) {
                out.push((kind, splice(f.0, f.1, other)));
            }
        }
    }
    for open in calls(v, "dt_rel(") {
        out.push(("dt for dt_rel", splice(open - 6, open, "dt")));
    }
    // A term of the top-level sum left out.
    let mut depth = 0i32;
    let mut cuts = vec![0];
    for (i, c) in v.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            '+' | '-' if depth == 0 && i > 0 && v[..i].ends_with(' ') => cuts.push(i),
            _ => {}
        }
    }
    if cuts.len() > 1 {
        cuts.push(v.len());
        for w in cuts.windows(2) {
            let m = splice(w[0], w[1], "");
            let m = m.trim().trim_start_matches('+').trim();
            if !m.is_empty() {
                out.push(("a term left out", m.to_string()));
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
            if what.contains(EQUIVALENT)
                || LISTED
                    .iter()
                    .any(|(f, m, _)| name == *f && what.contains(&format!("→ `{m}`")))
                || VANISHING
                    .iter()
                    .any(|(f, v, _)| name == *f && what.ends_with(&format!("`{v}` negated")))
            {
                continue;
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
        "value = \"principal(A, B, C) * w\"",
        "value = \"v\"",
    ] {
        assert!(ms.iter().any(|t| t.contains(expected)), "{expected}");
    }
    assert_eq!(ms.len(), 9);
}

#[test]
fn the_lecturers_slips_change_what_they_say() {
    let frames = ["N".to_string(), "F".to_string()];
    let got = lecturer_slips("dt_rel(H) + cross(w, H)/2 - 2*express(v, F)", &frames);
    for (kind, expected) in [
        (
            "cross swapped",
            "dt_rel(H) + cross(H, w)/2 - 2*express(v, F)",
        ),
        (
            "factor 1/2 to 1",
            "dt_rel(H) + cross(w, H) - 2*express(v, F)",
        ),
        (
            "factor 2 to 3",
            "dt_rel(H) + cross(w, H)/3 - 2*express(v, F)",
        ),
        (
            "factor 2 to 3",
            "dt_rel(H) + cross(w, H)/2 - 3*express(v, F)",
        ),
        (
            "another frame in express",
            "dt_rel(H) + cross(w, H)/2 - 2*express(v, N)",
        ),
        ("dt for dt_rel", "dt(H) + cross(w, H)/2 - 2*express(v, F)"),
        ("a term left out", "cross(w, H)/2 - 2*express(v, F)"),
        ("a term left out", "dt_rel(H) - 2*express(v, F)"),
        ("a term left out", "dt_rel(H) + cross(w, H)/2"),
    ] {
        assert!(
            got.iter().any(|(k, m)| *k == kind && m == expected),
            "{kind}: {expected} not in {got:#?}"
        );
    }
    assert_eq!(got.len(), 9, "{got:#?}");
}
