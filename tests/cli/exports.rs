//! Matrices in the exports: `derive --format json` gives every matrix,
//! array and list of a step as `value.rows`, an array of rows in source
//! syntax, and `scripts/check_sympy.py` compares them entry by entry with
//! the SymPy export's `Matrix` objects.

use std::process::Command;

use super::{hdot, text};
use hdot_tests::{hdot_bin, repo_root};

fn json(name: &str) -> serde_json::Value {
    let out = hdot(&["derive", name, "--format", "json"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn step<'a>(d: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    d["steps"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == name)
        .unwrap_or_else(|| panic!("no step {name}"))
}

/// The rows of a step, and its components' canonical forms in order: the
/// rows read row by row are the components.
fn rows_and_components(s: &serde_json::Value) -> (Vec<Vec<String>>, Vec<String>) {
    let rows: Vec<Vec<String>> = serde_json::from_value(s["value"]["rows"].clone())
        .unwrap_or_else(|e| panic!("{}: no rows: {e}", s["name"]));
    let comps = s["components"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["canonical"].as_str().unwrap().to_owned())
        .collect();
    (rows, comps)
}

#[test]
fn the_json_export_gives_matrices_as_arrays_of_rows() {
    // The heavy top's mass matrix (3 × 3) and forcing (a column). The
    // rows are the values with abbreviations expanded (the forcing's
    // components fold ω_z, its rows do not).
    let d = json("heavy-top");
    for (name, kind, shape) in [
        ("mass_matrix", "array", (3, 3)),
        ("forcing", "list", (3, 1)),
    ] {
        let s = step(&d, name);
        assert_eq!(s["value"]["kind"], kind);
        let (rows, comps) = rows_and_components(s);
        assert_eq!((rows.len(), rows[0].len()), shape, "{name}");
        if name == "mass_matrix" {
            assert_eq!(rows.concat(), comps, "{name}");
        } else {
            assert!(
                rows.concat().iter().all(|r| !r.contains("omega_z")),
                "{rows:?}"
            );
            assert!(comps.iter().any(|c| c.contains("omega_z")), "{comps:?}");
        }
    }
    // The bicycle's linearized matrices, 2 × 2 each; M is symmetric.
    let d = json("bicycle");
    for name in ["M", "C_1", "K_0", "K_2"] {
        let s = step(&d, name);
        let (rows, comps) = rows_and_components(s);
        assert!(
            rows.iter().all(|r| r.len() == 2) && rows.len() == 2,
            "{name}"
        );
        assert_eq!(rows.concat(), comps, "{name}");
    }
    let (m, _) = rows_and_components(step(&d, "M"));
    assert_eq!(m[0][1], m[1][0]);
    // An inertia tensor (3 × 3 matrix) too; a vector has no rows.
    let d = json("parallel-axis");
    let kinds: Vec<(&str, bool)> = d["steps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["value"]["kind"].as_str().unwrap(),
                s["value"].get("rows").is_some(),
            )
        })
        .collect();
    assert!(kinds.contains(&("matrix", true)), "{kinds:?}");
    assert!(
        kinds
            .iter()
            .all(|&(k, r)| r == matches!(k, "matrix" | "list" | "array")),
        "{kinds:?}"
    );
}

/// Python with SymPy, or `None` (with a note) when there is none outside
/// CI; under `CI=true` it must be there.
fn python_with_sympy() -> Option<String> {
    let python = std::env::var("HDOT_PYTHON").unwrap_or_else(|_| "python3".into());
    let ok = Command::new(&python)
        .args(["-c", "import sympy"])
        .output()
        .is_ok_and(|o| o.status.success());
    match ok {
        true => Some(python),
        false if std::env::var("CI").as_deref() != Ok("true") => {
            eprintln!("SymPy check skipped: {python} cannot import sympy");
            None
        }
        false => panic!("CI=true: the SymPy check must run, but {python} cannot import sympy"),
    }
}

#[test]
fn check_sympy_compares_the_exported_matrices() {
    let Some(python) = python_with_sympy() else {
        return;
    };
    let script = repo_root().join("scripts/check_sympy.py");
    let out = Command::new(&python)
        .arg(&script)
        .arg(hdot_bin())
        .args(["heavy-top", "bicycle"])
        .current_dir(repo_root())
        .output()
        .unwrap();
    let so = text(&out.stdout);
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
    assert!(so.contains(", 0 failed"), "{so}");
    // A wrong entry is found, and a right one passes: the comparison can
    // fail.
    let probe = r#"
import sys
sys.path.insert(0, sys.argv[1])
import check_sympy as c
from sympy import Eq, Function, Matrix, Symbol, cos
t = Symbol("t")
a, q = Symbol("a"), Function("q")(t)
table = {"a": a, "q": q, "t": t}
eqs = [Eq(Symbol("M_11"), a*q.diff(t, 2)), Eq(Symbol("M_21"), cos(q)/2)]
good = [["a*q''"], ["1/2*cos(q)"]]
bad = [["a*q''"], ["cos(q)"]]
m = Matrix([a*q.diff(t, 2), cos(q)/2])
print(len(c.compare_matrices("M", good, eqs, m, table, {})),
      len(c.compare_matrices("M", bad, eqs, m, table, {})))
"#;
    let out = Command::new(&python)
        .args(["-c", probe])
        .arg(repo_root().join("scripts"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout).trim(), "0 2");
}
