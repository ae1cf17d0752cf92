//! Speed of the derivation engine (issue 3, §3 "Speed, side by side").
//!
//! * `file/<name>`: one benchmark per file in `derivations/`, timing the
//!   whole path a user waits for — read, parse, derive, check and print in
//!   Unicode (`render(&load(path)?, Format::Unicode)`). Target: < 1 ms.
//! * `chain/derive/K` and `chain/derive+print/K`: the scaling family
//!   `chain-K` for K = 1…6 (generate the file text, derive; then also print
//!   in Unicode). Target: `chain-6` < 0.1 s, time growing with the size of
//!   the result.
//!
//! Sample counts and measurement times are kept small so that
//! `cargo bench -p hdot-sym` finishes in a few minutes on a loaded 2-core
//! machine. The numbers and the comparison with SymPy are in
//! `docs/performance.md`.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hdot_sym::chain;
use hdot_sym::derivation::load;
use hdot_sym::render::{Format, render};

/// The largest K benchmarked (the SymPy comparison goes to the same K).
const MAX_K: usize = 6;

/// The derivation files, sorted by name.
fn derivation_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../derivations");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n != hdot_sym::course::MANIFEST_FILE)
        })
        .collect();
    files.sort();
    files
}

/// Parse + derive + check + print in Unicode, for each seed derivation.
fn files(c: &mut Criterion) {
    let mut group = c.benchmark_group("file");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for path in derivation_files() {
        let name = path
            .file_stem()
            .expect("file name")
            .to_string_lossy()
            .into_owned();
        // Fail loudly, outside the timing, if a file does not load or check.
        let d = load(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(d.all_hold(), "{name}: an expectation does not hold");
        group.bench_function(&name, |b| {
            b.iter(|| {
                let d = load(black_box(&path)).expect("loads");
                render(&d, Format::Unicode)
            })
        });
    }
    group.finish();
}

/// `chain-K`, derive only and derive + print, K = 1…6.
fn chains(c: &mut Criterion) {
    let mut group = c.benchmark_group("chain");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for k in 1..=MAX_K {
        group.bench_with_input(BenchmarkId::new("derive", k), &k, |b, &k| {
            b.iter(|| chain::derivation(black_box(k)).expect("chain-K derives"))
        });
        group.bench_with_input(BenchmarkId::new("derive+print", k), &k, |b, &k| {
            b.iter(|| {
                let d = chain::derivation(black_box(k)).expect("chain-K derives");
                render(&d, Format::Unicode)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, files, chains);
criterion_main!(benches);
