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
/// (when only this test package was asked for).
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
        if !bin.is_file() {
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
