//! A file that is not a derivation given where one is expected — the
//! course's notes manifest, a scene — is named for what it is, with the
//! command that takes it (issue 21: `hdot verify derivations/notes.toml`
//! said "unknown field `author`").

use super::{hdot, text};

#[test]
fn a_notes_manifest_given_as_a_derivation_says_it_is_one() {
    for command in ["verify", "derive", "check"] {
        let out = hdot(&[command, "derivations/notes.toml"]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command}: {err}");
        assert!(
            err.contains("`derivations/notes.toml` is a notes manifest")
                && err.contains("hdot notes derivations"),
            "{command}: {err}"
        );
        assert!(!err.contains("unknown field"), "{command}: {err}");
    }
}

#[test]
fn a_scene_given_as_a_derivation_says_it_is_one() {
    let out = hdot(&["derive", "docs/examples/sim-heavy-top.toml"]);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("is a scene") && err.contains("hdot simulate"),
        "{err}"
    );
}
