//! `hdot stability`: the files it writes, its report, its page, and bad
//! input with exit code 2.

use super::{hdot, text};

/// The example scene: CSV (a header, one line per value), chart, page
/// and the threshold in the report.
#[test]
fn stability_writes_the_sweep_chart_and_page() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let page = dir.path().join("top.html");
    let out = hdot(&[
        "stability",
        "docs/examples/stability-sleeping-top.toml",
        "--out",
        out_dir.to_str().unwrap(),
        "--html",
        page.to_str().unwrap(),
    ]);
    let so = text(&out.stdout);
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
    let csv = std::fs::read_to_string(out_dir.join("eigenvalues.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("omega,re_1,im_1,re_2,im_2,re_3,im_3,re_4,im_4")
    );
    assert_eq!(lines.count(), 1000);
    for ext in ["svg", "png"] {
        assert!(out_dir.join(format!("eigenvalues.{ext}")).is_file());
    }
    // The closed form 2 √(I′ m g l) / I, in the report's digits.
    let want = 2.0 * (0.05f64 * 1.5 * 9.81 * 0.1).sqrt() / 0.02;
    let line = so
        .lines()
        .find(|l| l.starts_with("not unstable"))
        .unwrap_or_else(|| panic!("{so}"));
    let found: f64 = line
        .split("omega in [")
        .nth(1)
        .and_then(|r| r.split(',').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    assert!(
        (found - want).abs() <= 1e-8 * want,
        "{found} against {want}"
    );
    assert!(
        so.contains("stable (every real part below -1e-12 |A|): nowhere in the sweep"),
        "{so}"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("<svg") && html.contains("not unstable"),
        "{html}"
    );
}

/// A bad scene exits 2 naming the field and line; a simulation scene is
/// not a stability scene.
#[test]
fn stability_refuses_bad_scenes_with_a_location() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    let example = std::fs::read_to_string(
        hdot_tests::repo_root().join("docs/examples/stability-sleeping-top.toml"),
    )
    .unwrap()
    .replace(
        "file = \"sleeping-top\"",
        "file = \"../derivations/sleeping-top.toml\"",
    )
    .replace("count = 1000", "count = 0");
    std::fs::write(&scene, example).unwrap();
    let out = hdot(&[
        "stability",
        scene.to_str().unwrap(),
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let se = text(&out.stderr);
    assert!(
        se.contains("`sweep.count`") && se.contains("line 27"),
        "{se}"
    );
    assert!(!dir.path().join("eigenvalues.csv").exists());
    let out = hdot(&["stability", "docs/examples/sim-heavy-top.toml"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
}

/// `hdot simulate` on a stability scene says which command runs it.
#[test]
fn simulate_points_a_stability_scene_to_its_command() {
    let out = hdot(&["simulate", "docs/examples/stability-sleeping-top.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("run `hdot stability"),
        "{}",
        text(&out.stderr)
    );
}

/// Issue 24's trial: a sweep from 0 to 10 in 101 values wrote its tenth
/// value as `0.8999999999999999`; each value is the decimal meant (the
/// double nearest to it, which the CSV's shortest form prints as such).
#[test]
fn stability_csv_values_are_the_decimals_of_the_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let example = super::repo_root().join("docs/examples/stability-sleeping-top.toml");
    let derivation = super::repo_root().join("docs/examples/derivations/sleeping-top.toml");
    let text_of = std::fs::read_to_string(&example).unwrap();
    let edited = text_of
        .replace(
            "file = \"sleeping-top\"",
            &format!("file = {:?}", derivation.to_str().unwrap()),
        )
        .replace("to = 200.0\ncount = 1000", "to = 10.0\ncount = 101");
    assert_eq!(edited.matches("10.0").count(), 1, "{edited}");
    let scene = dir.path().join("top.toml");
    std::fs::write(&scene, edited).unwrap();
    let out_dir = dir.path().join("out");
    let out = hdot(&[
        "stability",
        scene.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let csv = std::fs::read_to_string(out_dir.join("eigenvalues.csv")).unwrap();
    let values: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    let want: Vec<String> = (0..=100)
        .map(|k| format!("{:?}", k as f64 / 10.0))
        .collect();
    assert_eq!(values, want);
    assert_eq!(values[9], "0.9");
}
