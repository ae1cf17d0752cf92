//! The pages of a run or a sweep (issue 23): `hdot simulate --html` for
//! every bundled example scene, `hdot stability --html` and `hdot
//! work-precision --html`, checked as files (self-contained, within their
//! weight, one shell and stylesheet) and then in headless Chromium by
//! `scripts/check_pages.py` (no console error, no horizontal overflow at
//! 1280 and 400 px, every chart drawn, a simulation's canvas moving, < 2 MB);
//! and the paths a page is refused at.

use std::path::{Path, PathBuf};
use std::process::Command;

use hdot_tests::repo_root;

use super::{hdot, text};

/// The budget of a simulation page, whatever the run's length.
const PAGE_BUDGET: u64 = 2 << 20;

/// Frames of the animation (`crates/cli/src/html/motion.rs`): the data
/// hold one time per frame plus the start.
const FRAMES: usize = 1200;

/// The bundled example scenes `hdot simulate` accepts (those a simulation
/// scene parses), by path.
fn simulation_scenes() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(repo_root().join("docs/examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| hdot_sim::scene::Scene::from_file(p).is_ok())
        .collect();
    out.sort();
    out
}

/// The JSON data of a page's view.
pub(super) fn view_data(page: &str) -> serde_json::Value {
    let open = "<script id=\"motion\" type=\"application/json\">";
    let start = page.find(open).expect("the view's data") + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    serde_json::from_str(&page[start..end]).expect("the view's data parse")
}

/// Checks what every page must be as a file (within the budget, one
/// document, self-contained: no external script, style, image or font);
/// returns its text.
fn check_self_contained(path: &Path) -> String {
    let page = std::fs::read_to_string(path).unwrap();
    let size = page.len() as u64;
    assert!(size < PAGE_BUDGET, "{}: {size} bytes", path.display());
    assert!(page.starts_with("<!DOCTYPE html>"), "{}", path.display());
    for fetch in [
        "src=\"http",
        "href=\"http",
        "url(http",
        "@import",
        "<link",
        "src=\"//",
    ] {
        assert!(!page.contains(fetch), "{}: {fetch}", path.display());
    }
    page
}

/// The one stylesheet of the pages of runs and sweeps.
const PAGE_CSS: &str = include_str!("../../crates/cli/src/html/page.css");

/// Asserts that the page's one `<style>` element is the shared stylesheet
/// (no second copy of it, no style of its own).
fn check_stylesheet(path: &Path, page: &str) {
    assert_eq!(page.matches("<style>").count(), 1, "{}", path.display());
    let start = page.find("<style>").unwrap() + "<style>".len();
    let end = page.find("</style>").unwrap();
    assert_eq!(
        page[start..end].trim(),
        PAGE_CSS.trim(),
        "{}",
        path.display()
    );
    assert!(!page.contains(" style=\""), "{}", path.display());
}

/// Checks what a simulation page must be as a file; returns its size.
fn check_page_file(path: &Path) -> u64 {
    let page = check_self_contained(path);
    check_stylesheet(path, &page);
    let size = page.len() as u64;
    assert!(page.contains("<canvas id=\"view\""));
    let data = view_data(&page);
    assert_eq!(data["t"].as_array().unwrap().len(), FRAMES + 1);
    let groups = data["groups"].as_array().unwrap();
    assert!(!groups.is_empty(), "{}: nothing drawn", path.display());
    for g in groups {
        assert!(!g["parts"].as_array().unwrap().is_empty());
        assert_eq!(g["rot"].as_array().unwrap().len(), 9 * (FRAMES + 1));
        // A body's place at each frame, or none (drawn at the origin).
        if let Some(pos) = g["pos"].as_array() {
            assert_eq!(pos.len(), 3 * (FRAMES + 1));
        }
    }
    // The view's turn (up to the canvas' up) is a rotation.
    let v: Vec<f64> = data["view"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let v = nalgebra::Matrix3::from_row_slice(&v);
    assert!((v.transpose() * v - nalgebra::Matrix3::identity()).norm() < 1e-5);
    assert!((v.determinant() - 1.0).abs() < 1e-5);
    assert!(data["scale"].as_f64().unwrap() > 0.0);
    size
}

/// Runs the browser check on `pages`, each within `budget` bytes (the
/// script's default, 2 MB, when `None`); skipped with a note without
/// Python or Chromium, except under `CI=true`, where the script fails.
pub(super) fn browser_check(pages: &[PathBuf], budget: Option<u64>) {
    let python = std::env::var("HDOT_PYTHON").unwrap_or_else(|_| "python3".into());
    let mut cmd = Command::new(&python);
    cmd.arg(repo_root().join("scripts/check_pages.py"));
    if let Some(b) = budget {
        cmd.args(["--max-bytes", &b.to_string()]);
    }
    let out = cmd.args(pages).output();
    let out = match out {
        Ok(o) => o,
        Err(e) if std::env::var("CI").as_deref() != Ok("true") => {
            eprintln!("browser check skipped: cannot run {python}: {e}");
            return;
        }
        Err(e) => panic!("CI=true: the browser check must run, but {python} cannot: {e}"),
    };
    let so = text(&out.stdout);
    eprintln!("{so}");
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
}

#[test]
fn every_bundled_scene_writes_a_page_the_browser_accepts() {
    let scenes = simulation_scenes();
    // Every bundled simulation example (`sim-*.toml`) parses as a scene.
    for e in std::fs::read_dir(repo_root().join("docs/examples")).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_str().unwrap();
        if name.starts_with("sim-") && name.ends_with(".toml") {
            assert!(scenes.contains(&p), "{name} is not a simulation scene");
        }
    }
    // Built-in models of every kind and derived ones: no scene dropped
    // silently by the filter.
    for must in [
        "sim-heavy-top.toml",
        "sim-torque-free-asymmetric.toml",
        "sim-shaft-unbalanced.toml",
        "sim-derived-heavy-top.toml",
        "sim-gimballed-gyroscope.toml",
        "sim-rolling-disk.toml",
        "sim-bicycle-nonlinear.toml",
    ] {
        assert!(
            scenes.iter().any(|p| p.ends_with(must)),
            "{must} missing from {scenes:?}"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let mut pages = vec![];
    for scene in &scenes {
        let stem = scene.file_stem().unwrap().to_str().unwrap();
        let page = dir.path().join(format!("{stem}.html"));
        let out = hdot(&[
            "simulate",
            scene.to_str().unwrap(),
            "--html",
            page.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{stem}: {}", text(&out.stderr));
        // The report still goes to standard output, without the trajectory.
        assert!(text(&out.stdout).contains("model:"), "{stem}");
        check_page_file(&page);
        pages.push(page);
    }
    // A long run (the heavy top for 60 × its 5 s): the page stays small.
    let long = dir.path().join("long-heavy-top.html");
    let out = hdot(&[
        "simulate",
        "docs/examples/sim-heavy-top.toml",
        "--t-end",
        "300",
        "--html",
        long.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let short = std::fs::metadata(dir.path().join("sim-heavy-top.html"))
        .unwrap()
        .len();
    let size = check_page_file(&long);
    assert!(
        size < 2 * short,
        "a run 60 times longer: {size} bytes against {short}"
    );
    pages.push(long);
    // A body of a tenth of a millimetre and one of ten kilometres: the view
    // is scaled to each (its scale within a factor 2 of the body's size).
    for (name, size) in [("tiny", 1e-4f64), ("huge", 1e4)] {
        let scene = dir.path().join(format!("{name}.toml"));
        std::fs::write(
            &scene,
            format!(
                "name = \"{name} box\"\nkind = \"free\"\nt_end = 5.0\n[[body]]\nshape = \"prism\"\n\
                 a = {}\nb = {}\nc = {}\nmass = {}\n[initial]\nangular_velocity = [0.3, 2.0, 0.1]\n",
                3.0 * size,
                2.0 * size,
                size,
                size.powi(3)
            ),
        )
        .unwrap();
        let page = dir.path().join(format!("{name}.html"));
        let out = hdot(&[
            "simulate",
            scene.to_str().unwrap(),
            "--html",
            page.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        check_page_file(&page);
        let scale = view_data(&std::fs::read_to_string(&page).unwrap())["scale"]
            .as_f64()
            .unwrap();
        // The box's half-diagonal is √14/2 = 1.87 sizes.
        assert!(
            (size..=4.0 * size).contains(&scale),
            "{name}: scale {scale} for a size {size}"
        );
        pages.push(page);
    }
    browser_check(&pages, None);
}

#[test]
fn the_page_never_overwrites_an_input() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("top.toml");
    let original =
        std::fs::read_to_string(repo_root().join("docs/examples/sim-heavy-top.toml")).unwrap();
    std::fs::write(&scene, &original).unwrap();
    let s = scene.to_str().unwrap();
    let out = hdot(&["simulate", s, "--html", s]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("is an input"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), original);
    let same = dir.path().join("out");
    let same = same.to_str().unwrap();
    let out = hdot(&["simulate", s, "--html", same, "--output", same]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(!Path::new(same).exists());
}

/// Every row of a table body (`<tr><td>` … `</td></tr>`) of a page.
fn body_rows(page: &str) -> usize {
    page.matches("<tr><td>").count()
}

#[test]
fn sweep_pages_hold_their_charts_and_tables_and_the_browser_accepts_them() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let o = out_dir.to_str().unwrap();
    let stability = dir.path().join("stability.html");
    let out = hdot(&[
        "stability",
        "docs/examples/stability-sleeping-top.toml",
        "--out",
        o,
        "--html",
        stability.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let page = check_self_contained(&stability);
    check_stylesheet(&stability, &page);
    // The report as a table, the chart inline (the SVG the command wrote).
    let report = text(&out.stdout);
    let verdict = report
        .lines()
        .find(|l| l.starts_with("not unstable"))
        .unwrap();
    let (_, intervals) = verdict.split_once(':').unwrap();
    assert!(page.contains(intervals.trim()), "{verdict}");
    let svg = std::fs::read_to_string(out_dir.join("eigenvalues.svg")).unwrap();
    assert!(page.contains(svg.trim()), "the chart is not inline");
    assert_eq!(page.matches("<svg").count(), 1);

    let wp = dir.path().join("work-precision.html");
    let out = hdot(&[
        "work-precision",
        "docs/examples/sim-torque-free-asymmetric.toml",
        "--t-end",
        "1",
        "--min-time",
        "0",
        "--out",
        o,
        "--html",
        wp.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let page = check_self_contained(&wp);
    check_stylesheet(&wp, &page);
    let stem = out_dir.join("sim-torque-free-asymmetric-work-precision");
    let svg = std::fs::read_to_string(stem.with_extension("svg")).unwrap();
    assert!(page.contains(svg.trim()), "the chart is not inline");
    // One row of the table per run of the CSV, the failed ones included.
    let csv = std::fs::read_to_string(stem.with_extension("csv")).unwrap();
    let runs = csv.lines().count() - 1;
    assert!(runs > 20, "{csv}");
    assert_eq!(body_rows(&page), runs);
    for method in ["euler", "rk4", "dop853", "split4"] {
        assert!(page.contains(&format!("<tr><td>{method}</td>")), "{method}");
    }
    browser_check(&[stability, wp], None);
}

/// A page is refused (exit 2, nothing written, before any run) at a
/// directory, at an input of the command and at another file it writes.
#[test]
fn a_page_is_refused_at_a_directory_an_input_or_another_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    let scene = dir.path().join("top.toml");
    let original =
        std::fs::read_to_string(repo_root().join("docs/examples/sim-heavy-top.toml")).unwrap();
    std::fs::write(&scene, &original).unwrap();
    let s = scene.to_str().unwrap();
    let csv = dir.path().join("top-work-precision.csv");
    let eigen = dir.path().join("eigenvalues.svg");
    let cases: [(&[&str], &str); 7] = [
        (&["simulate", s, "--html", d], "is a directory"),
        (
            &["work-precision", s, "--out", d, "--html", d],
            "is a directory",
        ),
        (
            &["work-precision", s, "--out", d, "--html", s],
            "is an input",
        ),
        (
            &[
                "work-precision",
                s,
                "--out",
                d,
                "--html",
                csv.to_str().unwrap(),
            ],
            "name the same file",
        ),
        (
            &[
                "stability",
                "docs/examples/stability-sleeping-top.toml",
                "--out",
                d,
                "--html",
                d,
            ],
            "is a directory",
        ),
        (
            &[
                "stability",
                "docs/examples/stability-sleeping-top.toml",
                "--out",
                d,
                "--html",
                eigen.to_str().unwrap(),
            ],
            "name the same file",
        ),
        (
            &[
                "stability",
                "docs/examples/stability-sleeping-top.toml",
                "--out",
                d,
                "--html",
                "docs/examples/stability-sleeping-top.toml",
            ],
            "is an input",
        ),
    ];
    let before =
        std::fs::read_to_string(repo_root().join("docs/examples/stability-sleeping-top.toml"))
            .unwrap();
    for (args, why) in cases {
        let out = hdot(args);
        let se = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {se}");
        assert!(se.contains(why), "{args:?}: {se}");
    }
    // Nothing was written: the folder holds the scene alone, the inputs are whole.
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["top.toml"]);
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), original);
    assert_eq!(
        std::fs::read_to_string(repo_root().join("docs/examples/stability-sleeping-top.toml"))
            .unwrap(),
        before
    );
}

/// Issue 23 item 5: a run whose state stops being finite writes no page
/// (nor a temporary file beside it), exits 1 and says when and at which
/// step — the page's own refusal of a non-finite sample
/// (`a_non_finite_sample_is_refused_and_located`) is the last guard
/// behind this one.
#[test]
fn a_run_that_is_not_finite_writes_no_page_and_says_where() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("top.html");
    let top = repo_root().join("docs/examples/sim-heavy-top.toml");
    let out = hdot(&[
        "simulate",
        top.to_str().unwrap(),
        "--method",
        "rk4",
        "--dt",
        "0.5",
        "--t-end",
        "2000",
        "--html",
        page.to_str().unwrap(),
    ]);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("state not finite at t = 1.5 (step 3)"),
        "{err}"
    );
    assert!(!page.exists(), "a page was written: {err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}
