//! Review in pull requests (issue 22): `hdot diff` between two files and
//! against a git revision, classified step by step by canonical equality.

use std::path::Path;
use std::process::{Command, Output};

use hdot_tests::{hdot_bin, repo_root};

use super::text;

/// Runs `hdot ARGS` in `dir`.
fn hdot_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(hdot_bin())
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run hdot")
}

/// The bundled Euler's equations, the file the changes below are made to.
fn euler() -> String {
    std::fs::read_to_string(repo_root().join("derivations/euler-principal.toml")).unwrap()
}

/// The transport theorem written as `dt` (same mathematics) and the
/// collected rates in another order (a new presentation).
fn presentation_only(text: &str) -> String {
    let t = text.replace(
        r#"value = "dt_rel(H) + cross(angvel(B), H)""#,
        r#"value = "dt(H)""#,
    );
    let at = t
        .find("collect = [\"omega_x'\"")
        .expect("the M step collects");
    let end = at + t[at..].find('\n').unwrap();
    format!(
        "{}collect = [\"omega_z\", \"omega_y\", \"omega_x\"]{}",
        &t[..at],
        &t[end..]
    )
}

/// A sign error in the transport theorem: ΣM = (Ḣ)_rel − Ω × H, so that
/// NEW − OLD = −2 Ω × H.
fn sign_error(text: &str) -> String {
    let t = text.replace(
        r#"value = "dt_rel(H) + cross(angvel(B), H)""#,
        r#"value = "dt_rel(H) - cross(angvel(B), H)""#,
    );
    assert_ne!(t, text, "the transport step is where the test expects it");
    t
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

fn json(out: &Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}{}", text(&out.stdout), text(&out.stderr)))
}

/// The step called `name` of the file's report.
fn step<'a>(file: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    file["steps"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == name)
        .unwrap_or_else(|| panic!("no step {name} in {file}"))
}

#[test]
fn diff_tells_a_new_presentation_from_new_mathematics() {
    let dir = tempfile::tempdir().unwrap();
    let old = write(dir.path(), "old.toml", &euler());
    let pres = write(dir.path(), "pres.toml", &presentation_only(&euler()));
    let wrong = write(dir.path(), "wrong.toml", &sign_error(&euler()));

    // Same file: unchanged, exit 0, every step listed.
    let out = hdot_in(dir.path(), &["diff", &old, &old, "--format", "json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r = json(&out);
    assert_eq!(r["files"][0]["change"], "unchanged");
    assert!(r["files"][0]["steps"].as_array().unwrap().len() >= 4);

    // Presentation only: exit 0, and 1 under --fail-on presentation.
    let out = hdot_in(dir.path(), &["diff", &old, &pres, "--format", "json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r = json(&out);
    let m = step(&r["files"][0], "M");
    assert_eq!(m["change"], "presentation", "{m}");
    assert_eq!(m["formula"]["new"], "dt(H)");
    for c in m["components"].as_array().unwrap() {
        assert_eq!(c["change"], "presentation", "{c}");
        assert_eq!(c["old"]["canonical"], c["new"]["canonical"]);
        assert_ne!(c["old"]["text"], c["new"]["text"]);
    }
    assert_eq!(step(&r["files"][0], "H")["change"], "unchanged");
    let out = hdot_in(
        dir.path(),
        &["diff", &old, &pres, "--fail-on", "presentation"],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stdout).contains("same mathematics, new presentation"));

    // A sign error: exit 1; the step, each component and NEW − OLD.
    let out = hdot_in(dir.path(), &["diff", &old, &wrong, "--format", "json"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let r = json(&out);
    assert_eq!(r["files"][0]["change"], "mathematics");
    assert_eq!(r["mathematics_differs"], true);
    let m = step(&r["files"][0], "M");
    assert_eq!(m["change"], "mathematics");
    let d =
        hdot_sym::derivation::load(&repo_root().join("derivations/euler-principal.toml")).unwrap();
    // −2 (Ω × H) in principal axes, component by component.
    let expected = [
        ("x", "2*(I_y - I_z)*omega_y*omega_z"),
        ("y", "2*(I_z - I_x)*omega_z*omega_x"),
        ("z", "2*(I_x - I_y)*omega_x*omega_y"),
    ];
    for (c, want) in expected {
        let comp = m["components"]
            .as_array()
            .unwrap()
            .iter()
            .find(|x| x["component"] == c)
            .unwrap();
        assert_eq!(comp["change"], "mathematics");
        let got = d
            .symbols
            .poly(comp["difference"]["canonical"].as_str().unwrap());
        assert_eq!(got.unwrap(), d.symbols.poly(want).unwrap(), "{comp}");
    }

    // Text names the step, the component and the difference in textbook form.
    let out = hdot_in(dir.path(), &["diff", &old, &wrong]);
    let so = text(&out.stdout);
    assert!(so.contains("step M: different mathematics"), "{so}");
    assert!(so.contains("new − old = 2 (I_y − I_z) ω_y ω_z"), "{so}");
    // Markdown: inline $…$ LaTeX.
    let out = hdot_in(dir.path(), &["diff", &old, &wrong, "--format", "markdown"]);
    let so = text(&out.stdout);
    assert!(
        so.contains(r"new − old: $2 \left(I_y - I_z\right) \omega_y \omega_z$"),
        "{so}"
    );
}

#[test]
fn diff_reports_added_and_removed_steps() {
    let dir = tempfile::tempdir().unwrap();
    let old = write(dir.path(), "old.toml", &euler());
    let more = format!(
        "{}\n[[step]]\nname = \"T\"\nlabel = \"T\"\nvalue = \"dot(omega, H)/2\"\n",
        euler()
    );
    let new = write(dir.path(), "new.toml", &more);
    let out = hdot_in(dir.path(), &["diff", &old, &new, "--format", "json"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert_eq!(step(&json(&out)["files"][0], "T")["change"], "added");
    let out = hdot_in(dir.path(), &["diff", &new, &old, "--format", "json"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(step(&json(&out)["files"][0], "T")["change"], "removed");
}

#[test]
fn diff_refuses_bad_input_and_says_which_version() {
    let dir = tempfile::tempdir().unwrap();
    let good = write(dir.path(), "good.toml", &euler());
    let bad = write(
        dir.path(),
        "bad.toml",
        &euler().replace("angvel(B), H)\"", "angvel(B), Q)\""),
    );
    let out = hdot_in(dir.path(), &["diff", &good, &bad]);
    assert_eq!(out.status.code(), Some(2));
    let se = text(&out.stderr);
    assert!(se.contains("bad.toml:"), "{se}");
    assert!(se.contains("the new version"), "{se}");
    assert!(out.stdout.is_empty());
    let out = hdot_in(dir.path(), &["diff", &bad, &good]);
    assert!(text(&out.stderr).contains("the old version"));
    assert_eq!(out.status.code(), Some(2));
    let out = hdot_in(dir.path(), &["diff", &good]);
    assert_eq!(out.status.code(), Some(2));
    let out = hdot_in(dir.path(), &["diff", &good, "missing.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("missing.toml"));
}

/// Runs `git ARGS` in `dir`, which must succeed.
fn git(dir: &Path, args: &[&str]) {
    let out = Command::new("git")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run git");
    assert!(out.status.success(), "git {args:?}: {}", text(&out.stderr));
}

/// A lecturer's repository: a derivation, a scene and a notes manifest in
/// one folder, committed once.
fn lecturer_repo() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    git(d, &["init", "-q"]);
    git(d, &["config", "user.email", "lecturer@example.invalid"]);
    git(d, &["config", "user.name", "Lecturer"]);
    git(d, &["config", "commit.gpgsign", "false"]);
    write(d, "derivations/euler-principal.toml", &euler());
    let scene = std::fs::read_to_string(repo_root().join("docs/examples/sim-heavy-top.toml"));
    write(d, "derivations/heavy-top-scene.toml", &scene.unwrap());
    write(
        d,
        "derivations/notes.toml",
        "title = \"Rigid bodies\"\n\n[[chapter]]\ntitle = \"Euler\"\nderivations = [\"euler-principal\"]\n",
    );
    git(d, &["add", "."]);
    git(d, &["commit", "-q", "-m", "derivations"]);
    dir
}

#[test]
fn diff_against_a_git_revision() {
    let repo = lecturer_repo();
    let d = repo.path();
    let out = hdot_in(d, &["diff", "--git", "HEAD"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("nothing changed: 1 derivation file compared"));

    write(d, "derivations/euler-principal.toml", &sign_error(&euler()));
    let out = hdot_in(&d.join("derivations"), &["diff", "--git", "HEAD", "."]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let so = text(&out.stdout);
    assert!(
        so.contains("derivations/euler-principal.toml: different mathematics"),
        "{so}"
    );

    // Bad input: no such revision, a path outside, not a repository.
    let out = hdot_in(d, &["diff", "--git", "no-such-branch"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no such revision `no-such-branch`"));
    let out = hdot_in(d, &["diff", "--git", "HEAD", ".."]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("outside the repository"));
    let elsewhere = tempfile::tempdir().unwrap();
    let out = hdot_in(elsewhere.path(), &["diff", "--git", "HEAD"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("needs a git repository"));

    // A file that does not load at the revision or now: which, and where.
    write(
        d,
        "derivations/euler-principal.toml",
        "title = \"x\"\n[[step]]\nname = \n",
    );
    let out = hdot_in(d, &["diff", "--git", "HEAD"]);
    assert_eq!(out.status.code(), Some(2));
    let se = text(&out.stderr);
    assert!(se.contains("derivations/euler-principal.toml:3"), "{se}");
    assert!(se.contains("the new version"), "{se}");
}

#[test]
fn check_and_snapshot_skip_a_scene_and_the_manifest_beside_derivations() {
    let repo = lecturer_repo();
    let d = repo.path();
    let out = hdot_in(d, &["check", "derivations"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    assert!(
        text(&out.stdout).contains("1 derivations"),
        "{}",
        text(&out.stdout)
    );
    let out = hdot_in(d, &["snapshot", "derivations", "--accept", "--bodies", "4"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let names: Vec<String> = std::fs::read_dir(d.join("snapshots"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["euler-principal.hdot.txt"]);
}

#[test]
fn snapshot_files_are_deterministic_and_hold_no_absolute_path() {
    let repo = lecturer_repo();
    let d = repo.path();
    let run = || {
        let out = hdot_in(d, &["snapshot", "derivations", "--accept", "--bodies", "4"]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        std::fs::read_to_string(d.join("snapshots/euler-principal.hdot.txt")).unwrap()
    };
    let first = run();
    std::fs::remove_dir_all(d.join("snapshots")).unwrap();
    assert_eq!(run(), first);
    assert!(!first.contains(&d.display().to_string()), "{first}");
    assert!(
        first.contains("of derivations/euler-principal.toml"),
        "{first}"
    );
    // Every shown equation of `derive`, one per line, then its canonical form.
    let derived = hdot_in(d, &["derive", "derivations/euler-principal.toml"]);
    let eq = "ΣM_y = I_y ω̇_y − (I_z − I_x) ω_z ω_x";
    assert!(text(&derived.stdout).contains(eq));
    let lines: Vec<&str> = first.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.trim() == eq)
        .expect("the equation");
    assert!(
        lines[at + 1].trim_start().starts_with("canonical y: "),
        "{}",
        lines[at + 1]
    );
    assert!(first.contains("check: ok"));
    assert!(first.contains("verify: pass"));
}

#[test]
fn snapshot_refuses_a_folder_that_is_a_file_and_a_file_that_does_not_load() {
    let repo = lecturer_repo();
    let d = repo.path();
    write(d, "snapfile", "not a folder");
    let out = hdot_in(
        d,
        &["snapshot", "derivations", "--check", "--dir", "snapfile"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("snapfile is a file"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(d.join("snapfile")).unwrap(),
        "not a folder"
    );
    write(
        d,
        "derivations/broken.toml",
        "title = \"b\"\n[[step]]\nname = \"x\"\nvalue = \"q +\"\n",
    );
    let out = hdot_in(d, &["snapshot", "derivations", "--accept"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("broken.toml:"),
        "{}",
        text(&out.stderr)
    );
    assert!(!d.join("snapshots").exists(), "nothing written");
}

/// The `hdot` command lines of the CI recipe (docs/ci/hdot-review.yml),
/// for a pull request into `main`.
fn workflow_commands() -> Vec<String> {
    let yml = std::fs::read_to_string(repo_root().join("docs/ci/hdot-review.yml")).unwrap();
    let v: Vec<String> = yml
        .lines()
        .filter_map(|l| l.trim().strip_prefix("run: "))
        .filter(|c| c.starts_with("hdot "))
        .map(|c| c.replace("${{ github.base_ref }}", "main"))
        .collect();
    assert!(v.len() >= 5, "{v:?}");
    v
}

/// Runs each workflow command in `dir` (with this build's `hdot` first on
/// PATH): (command, exit code, stdout).
fn run_workflow(dir: &Path) -> Vec<(String, Option<i32>, String)> {
    let bin = hdot_bin();
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    workflow_commands()
        .into_iter()
        .map(|c| {
            let out = Command::new("sh")
                .args(["-c", &c])
                .env("PATH", &path)
                .current_dir(dir)
                .output()
                .expect("run sh");
            let so = format!("{}{}", text(&out.stdout), text(&out.stderr));
            (c, out.status.code(), so)
        })
        .collect()
}

/// The exit code and output of the workflow command starting with `start`.
fn outcome<'a>(
    results: &'a [(String, Option<i32>, String)],
    start: &str,
) -> &'a (String, Option<i32>, String) {
    results
        .iter()
        .find(|(c, ..)| c.starts_with(start))
        .unwrap_or_else(|| panic!("no `{start}` in the workflow"))
}

/// Issue 22's loop on a lecturer's repository, with the CI recipe's own
/// commands: a presentation-only commit passes every step and is reported
/// as such; a commit that changes the mathematics fails `snapshot --check`
/// (and `check`), and the review text names the step, the component and
/// the difference.
#[test]
fn a_lecturers_repository_goes_through_the_review_loop() {
    let repo = lecturer_repo();
    let d = repo.path();
    let accept = || {
        let out = hdot_in(d, &["snapshot", "derivations", "--accept"]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    };
    let publish = || {
        git(d, &["add", "derivations", "snapshots"]);
        git(d, &["commit", "-q", "-m", "reviewed"]);
        git(d, &["update-ref", "refs/remotes/origin/main", "HEAD"]);
    };
    accept();
    publish();

    // Commit 1: the same mathematics, presented differently.
    write(
        d,
        "derivations/euler-principal.toml",
        &presentation_only(&euler()),
    );
    git(
        d,
        &[
            "commit",
            "-q",
            "-am",
            "transport theorem as dt(H); rates last",
        ],
    );
    let results = run_workflow(d);
    for (c, code, so) in &results {
        assert_eq!(*code, Some(0), "{c}: {so}");
    }
    assert!(
        outcome(&results, "hdot snapshot")
            .2
            .contains("differ in presentation only")
    );
    let review = std::fs::read_to_string(d.join("hdot-review.md")).unwrap();
    assert!(
        review.contains("same mathematics, new presentation"),
        "{review}"
    );
    assert!(!review.contains(": different mathematics"), "{review}");
    assert!(d.join("build/notes/hdot-slides.tex").is_file());
    accept();
    publish();

    // Commit 2: a sign error in the transport theorem.
    write(
        d,
        "derivations/euler-principal.toml",
        &presentation_only(&sign_error(&euler())),
    );
    git(d, &["commit", "-q", "-am", "sign"]);
    let results = run_workflow(d);
    assert_eq!(
        outcome(&results, "hdot diff").1,
        Some(0),
        "the review text is written"
    );
    assert_eq!(outcome(&results, "hdot check").1, Some(1));
    let (_, code, so) = outcome(&results, "hdot snapshot");
    assert_eq!(*code, Some(1), "{so}");
    assert!(so.contains("step M: different mathematics"), "{so}");
    assert!(so.contains("component y: different mathematics"), "{so}");
    assert!(so.contains("new − old = 2 (I_z − I_x) ω_z ω_x"), "{so}");
    assert!(so.contains("check: FAILED"), "{so}");
    let review = std::fs::read_to_string(d.join("hdot-review.md")).unwrap();
    assert!(
        review.contains("### `derivations/euler-principal.toml`: different mathematics"),
        "{review}"
    );
    assert!(
        review.contains("- **step `M`**: different mathematics"),
        "{review}"
    );
    assert!(
        review.contains(r"new − old: $2 \left(I_z - I_x\right) \omega_z \omega_x$"),
        "{review}"
    );
    let out = hdot_in(d, &["diff", "--git", "origin/main", "--format", "json"]);
    assert_eq!(out.status.code(), Some(1));
    let r = json(&out);
    assert_eq!(step(&r["files"][0], "M")["change"], "mathematics");
    assert_eq!(
        r["files"][0]["old"],
        "origin/main:derivations/euler-principal.toml"
    );
}
