//! `hdot simulate --html` (issue 23): a page for every bundled example
//! scene, checked as a file (self-contained, within its weight) and then in
//! headless Chromium by `scripts/check_pages.py` (no console error, no
//! horizontal overflow at 1280 and 400 px, the canvas moving, < 2 MB).

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
fn view_data(page: &str) -> serde_json::Value {
    let open = "<script id=\"motion\" type=\"application/json\">";
    let start = page.find(open).expect("the view's data") + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    serde_json::from_str(&page[start..end]).expect("the view's data parse")
}

/// Checks what a page must be as a file; returns its size.
fn check_page_file(path: &Path) -> u64 {
    let page = std::fs::read_to_string(path).unwrap();
    let size = page.len() as u64;
    assert!(size < PAGE_BUDGET, "{}: {size} bytes", path.display());
    assert!(page.starts_with("<!DOCTYPE html>"), "{}", path.display());
    assert!(page.contains("<canvas id=\"view\""));
    // Self-contained: nothing is fetched (no external script, style, image or font).
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
    let data = view_data(&page);
    assert_eq!(data["t"].as_array().unwrap().len(), FRAMES + 1);
    let groups = data["groups"].as_array().unwrap();
    assert!(!groups.is_empty(), "{}: nothing drawn", path.display());
    for g in groups {
        assert!(!g["parts"].as_array().unwrap().is_empty());
        assert_eq!(g["rot"].as_array().unwrap().len(), 9 * (FRAMES + 1));
    }
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
    // Built-in models of every kind and derived ones: no scene dropped
    // silently by the filter.
    for must in [
        "sim-heavy-top.toml",
        "sim-torque-free-asymmetric.toml",
        "sim-shaft-unbalanced.toml",
        "sim-derived-heavy-top.toml",
        "sim-gimballed-gyroscope.toml",
        "sim-rolling-disk.toml",
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
