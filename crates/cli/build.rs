//! Embeds the bundled derivations (`derivations/*.toml`) and example
//! scenes (`docs/examples/*.toml`) in the binary, so that an installed
//! `hdot` works without the source tree it was built from; and links the
//! binary as a position-dependent executable (below).

use std::fmt::Write;
use std::path::Path;

fn main() {
    // A position-dependent executable: the dynamic loader then applies
    // ~150 relocations at start instead of ~11,000 (and copies no page of
    // pointers to write them), a tenth of a small run's time
    // (docs/performance.md, Engine). The crates' code is unchanged.
    // Only where the linker is GNU's (a Linux target's `cc`): elsewhere the
    // flag is unknown, and the binary is linked as the platform does.
    let var = |k: &str| std::env::var(k).unwrap_or_default();
    if var("CARGO_CFG_TARGET_OS") == "linux" && var("CARGO_CFG_TARGET_ENV") == "gnu" {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut out = String::new();
    for (konst, dir) in [("DERIVATIONS", "derivations"), ("SCENES", "docs/examples")] {
        let dir = root.join(dir);
        println!("cargo:rerun-if-changed={}", dir.display());
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .map(|rd| {
                rd.filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                    .collect()
            })
            .unwrap_or_default();
        files.sort();
        let _ = writeln!(out, "pub const {konst}: &[(&str, &str)] = &[");
        for f in files {
            println!("cargo:rerun-if-changed={}", f.display());
            let stem = f.file_stem().expect("a file name").to_string_lossy();
            let abs = f.canonicalize().expect("a readable file");
            let _ = writeln!(
                out,
                "    ({stem:?}, include_str!({:?})),",
                abs.display().to_string()
            );
        }
        let _ = writeln!(out, "];");
    }
    let dest = Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("bundled.rs");
    std::fs::write(dest, out).expect("write bundled.rs");
}
