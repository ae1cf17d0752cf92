//! Shared helpers of the integration tests.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The repository root.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ has a parent")
        .to_owned()
}

/// The `hdot` binary of this build, built on first use if it is missing
/// (when only this test package was asked for) or older than the sources
/// (a binary left by an earlier build would test old code).
///
/// `cargo test --workspace` builds the binary first, so this only runs
/// cargo when a single test package is asked for after an edit.
pub fn hdot_bin() -> PathBuf {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        // target/<profile>/deps/<test-binary> → target/<profile>/hdot
        let exe = std::env::current_exe().expect("current exe");
        let dir = exe
            .parent()
            .and_then(Path::parent)
            .expect("target/<profile>");
        let bin = dir.join(format!("hdot{}", std::env::consts::EXE_SUFFIX));
        let stale = match std::fs::metadata(&bin).and_then(|m| m.modified()) {
            Ok(built) => newest_source().is_some_and(|src| src > built),
            Err(_) => true,
        };
        if stale {
            let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
            let profile = if dir.ends_with("release") {
                vec!["--release"]
            } else {
                vec![]
            };
            let st = std::process::Command::new(cargo)
                .args(["build", "-p", "hdot", "--quiet"])
                .args(profile)
                .current_dir(repo_root())
                .status()
                .expect("run cargo build");
            assert!(st.success(), "building the hdot binary failed");
        }
        bin
    })
    .clone()
}

/// The newest modification time of the files the binary is built from:
/// `Cargo.toml`, `Cargo.lock`, and each crate's `Cargo.toml` and `src/`,
/// `data/` and `assets/` folders (not its tests or benches, which the
/// binary does not contain: editing one would otherwise ask cargo on
/// every run to rebuild a binary that does not change).
fn newest_source() -> Option<std::time::SystemTime> {
    fn walk(dir: &Path, newest: &mut Option<std::time::SystemTime>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, newest);
            } else if let Ok(t) = entry.metadata().and_then(|m| m.modified()) {
                *newest = (*newest).max(Some(t));
            }
        }
    }
    let root = repo_root();
    let mut newest = None;
    for f in ["Cargo.toml", "Cargo.lock"] {
        if let Ok(t) = std::fs::metadata(root.join(f)).and_then(|m| m.modified()) {
            newest = newest.max(Some(t));
        }
    }
    let crates = std::fs::read_dir(root.join("crates")).into_iter().flatten();
    for krate in crates.flatten().map(|e| e.path()) {
        if let Ok(t) = std::fs::metadata(krate.join("Cargo.toml")).and_then(|m| m.modified()) {
            newest = newest.max(Some(t));
        }
        for dir in ["src", "data", "assets"] {
            walk(&krate.join(dir), &mut newest);
        }
    }
    newest
}
