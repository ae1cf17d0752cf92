//! models/mod.rs: the registry of models is complete — the docs table and
//! the `--model` help list every entry, and every name resolves to its
//! entry.

use hdot_sim::models::{self, MODELS};
use hdot_sim::run::Model;

/// The models table of docs/simulation.md is the registry's.
#[test]
fn docs_list_every_model_of_the_registry() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/simulation.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let (begin, end) = ("<!-- models:begin -->\n", "<!-- models:end -->");
    let a = doc.find(begin).expect("models:begin marker") + begin.len();
    let b = doc.find(end).expect("models:end marker");
    let table = models::docs_table();
    for e in MODELS {
        assert!(
            table.contains(&format!("| `{}` |", e.name())),
            "{}",
            e.name()
        );
    }
    if doc[a..b] != table {
        if std::env::var_os("HDOT_UPDATE_DOCS").is_some() {
            std::fs::write(&path, format!("{}{}{}", &doc[..a], table, &doc[b..])).unwrap();
        } else {
            panic!(
                "docs/simulation.md's models table differs from the registry; rerun with \
                 HDOT_UPDATE_DOCS=1 to regenerate it:\n{table}"
            );
        }
    }
}

/// The `--model` help names every entry, in the registry's order, and
/// every name parses back to its entry.
#[test]
fn help_and_names_cover_every_model() {
    let help = models::help();
    let mut at = 0;
    for e in MODELS {
        let k = help[at..]
            .find(e.name())
            .unwrap_or_else(|| panic!("{} missing from {help}", e.name()));
        at += k + e.name().len();
        let m: Model = e.name().parse().unwrap();
        assert_eq!(m.name(), e.name());
    }
    assert_eq!(Model::all().count(), MODELS.len());
    let names: std::collections::BTreeSet<_> = MODELS.iter().map(|e| e.name()).collect();
    assert_eq!(names.len(), MODELS.len(), "two entries share a name");
    let err = "no-such-model".parse::<Model>().unwrap_err().to_string();
    for e in MODELS {
        assert!(err.contains(e.name()), "{err}");
    }
}
