//! Tests of the `hdot` binary: exit codes, messages, atomic output.

use std::process::Command;

use hdot_tests::{hdot_bin, repo_root};

mod budgets;
mod derived_errors;
mod exports;
mod html;
mod notes_html;
mod page_places;
mod reliability;
mod review;
mod stability;
mod wrong_file;

fn hdot(args: &[&str]) -> std::process::Output {
    Command::new(hdot_bin())
        .args(args)
        .current_dir(repo_root())
        .output()
        .expect("run hdot")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn check_passes_on_the_bundled_derivations() {
    let out = hdot(&["check"]);
    let so = text(&out.stdout);
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
    for name in [
        "angular-momentum",
        "euler-principal",
        "euler-general",
        "fixed-axis",
    ] {
        let line = so
            .lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("{name} missing:\n{so}"));
        assert!(line.trim_end().ends_with("ok"), "{line}");
    }
}

#[test]
fn derive_prints_eulers_equations_in_latex() {
    let out = hdot(&["derive", "euler-principal", "--format", "latex"]);
    assert!(out.status.success());
    let so = text(&out.stdout);
    assert!(
        so.contains(
            r"\Sigma M_{x} &= I_x \dot{\omega}_x - \left(I_y - I_z\right) \omega_y \omega_z"
        ),
        "{so}"
    );
}

#[test]
fn unknown_names_and_broken_files_exit_2_with_a_location() {
    let out = hdot(&["derive", "no-such-derivation"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("unknown derivation `no-such-derivation`"));

    let out = hdot(&["derive", "tests/sym/broken/02-unknown-symbol.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("02-unknown-symbol.toml:9:24"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn a_failing_expectation_exits_1_and_names_the_component() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("wrong.toml");
    std::fs::write(
        &f,
        "title = \"w\"\nsource = \"s\"\n[symbols]\nconstants = [\"m\"]\ntime = [\"x\"]\n[[step]]\nname = \"p\"\nvalue = \"m*x'\"\nexpect = \"m*x\"\n",
    )
    .unwrap();
    let out = hdot(&["check", f.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let so = text(&out.stdout);
    assert!(
        so.contains("FAILED (1 of 1)") && so.contains("p: derived − expected = -m*x + m*x'"),
        "{so}"
    );
}

#[test]
fn out_is_written_whole_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("euler.tex");
    let out = hdot(&[
        "derive",
        "euler-principal",
        "--format",
        "latex",
        "--out",
        good.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert!(
        std::fs::read_to_string(&good)
            .unwrap()
            .contains(r"\begin{align*}")
    );

    let bad = dir.path().join("broken.tex");
    let out = hdot(&[
        "derive",
        "tests/sym/broken/05-unknown-function.toml",
        "--out",
        bad.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!bad.exists(), "nothing may be written on error");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "no temporary file left behind"
    );
}

#[test]
fn every_command_has_help() {
    for cmd in ["list", "derive", "check", "verify"] {
        let out = hdot(&[cmd, "--help"]);
        assert!(out.status.success(), "{cmd} --help");
        assert!(text(&out.stdout).contains("Usage: hdot"), "{cmd}");
    }
}

/// `hdot simulate --help` lists every model of the registry.
#[test]
fn simulate_help_lists_every_model() {
    let out = hdot(&["simulate", "--help"]);
    assert!(out.status.success());
    let help = text(&out.stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    for e in hdot_sim::models::MODELS {
        assert!(help.contains(e.name()), "{} missing from: {help}", e.name());
    }
}

#[test]
fn verify_passes_on_every_bundled_derivation() {
    let out = hdot(&["verify", "--bodies", "20"]);
    let so = text(&out.stdout);
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
    let results: Vec<&str> = so.lines().skip(1).filter(|l| !l.starts_with(' ')).collect();
    let bundled = std::fs::read_dir(hdot_tests::repo_root().join("derivations"))
        .expect("derivations folder")
        .filter(|e| {
            e.as_ref().is_ok_and(|e| {
                e.path().extension().is_some_and(|x| x == "toml") && e.file_name() != "notes.toml"
            })
        })
        .count();
    assert_eq!(results.len(), bundled, "{so}");
    for l in results {
        assert!(l.trim_end().ends_with("pass"), "{l}");
    }
    // Steps that are not compared, and kinematic ones, are said so.
    assert!(so.contains("not compared (no meaning): Ix_P, Iy_P"), "{so}");
    // Declared files list their steps without a meaning.
    assert!(so.contains("not compared (no meaning): M_forces"), "{so}");
}

#[test]
fn verify_fails_on_a_wrong_derivation_and_rejects_unknown_names() {
    // plane-motion with the products of inertia entering with a plus sign.
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("plane-motion.toml");
    let good = std::fs::read_to_string(repo_root().join("derivations/plane-motion.toml")).unwrap();
    let wrong = good.replace(
        "value = \"inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx) * angvel(B)\"",
        "value = \"inertia(I_x, I_y, I_z, -I_xy, -I_yz, -I_zx) * angvel(B)\"",
    );
    assert_ne!(good, wrong);
    std::fs::write(&f, wrong).unwrap();
    let out = hdot(&["verify", f.to_str().unwrap(), "--bodies", "5"]);
    assert_eq!(out.status.code(), Some(1));
    let so = text(&out.stdout);
    assert!(so.contains("FAIL at H."), "{so}");

    let out = hdot(&["verify", "no-such-derivation"]);
    assert_eq!(out.status.code(), Some(2));

    // A file that does not load: its diagnostic once, with one `error:`.
    let out = hdot(&["verify", "tests/sym/broken/02-unknown-symbol.toml"]);
    assert_eq!(out.status.code(), Some(2));
    let se = text(&out.stderr);
    assert!(
        se.starts_with("error: ") && !se.contains("error: error"),
        "{se}"
    );
    assert!(se.contains("02-unknown-symbol.toml:9:24"), "{se}");

    // Zero bodies would pass without checking anything: refused.
    let out = hdot(&["verify", "euler-general", "--bodies", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("--bodies"),
        "{}",
        text(&out.stderr)
    );
}

/// Verification reads what a file declares, not its name: heavy-top copied
/// under another name gives the same report; a wrong step fails naming
/// it; a file that compares nothing exits 1 under `--require`.
#[test]
fn verify_reads_declarations_under_any_name() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read_to_string(repo_root().join("derivations/heavy-top.toml")).unwrap();
    let copy = dir.path().join("my-own-top.toml");
    std::fs::write(&copy, &good).unwrap();
    let run = |p: &str| {
        let out = hdot(&["verify", p, "--bodies", "4", "--steps"]);
        let so = text(&out.stdout);
        (
            out.status.code(),
            so.lines().skip(2).map(str::to_owned).collect::<Vec<_>>(),
            so,
        )
    };
    let (code, lines, so) = run(copy.to_str().unwrap());
    assert_eq!(code, Some(0), "{so}");
    let (code0, lines0, _) = run("heavy-top");
    assert_eq!((code, &lines), (code0, &lines0));
    assert!(so.contains("M_weight: weight_moment(top, O)"), "{so}");

    let wrong = dir.path().join("wrong.toml");
    std::fs::write(
        &wrong,
        good.replace("value = \"dot(omega, H)/2\"", "value = \"dot(omega, H)\""),
    )
    .unwrap();
    let out = hdot(&["verify", wrong.to_str().unwrap(), "--bodies", "4"]);
    assert_eq!(out.status.code(), Some(1));
    let so = text(&out.stdout);
    assert!(so.contains("FAIL at "), "{so}");
    assert!(
        so.lines()
            .any(|l| l.trim_start().starts_with("T: kinetic_energy(top)") && l.ends_with("FAIL")),
        "{so}"
    );

    let plain = dir.path().join("plain.toml");
    std::fs::write(&plain, "title = \"p\"\nsource = \"s\"\n[symbols]\nconstants = [\"a\"]\n[[step]]\nname = \"x\"\nvalue = \"2*a\"\n").unwrap();
    let out = hdot(&["verify", plain.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        text(&out.stdout).contains("[[body]]"),
        "{}",
        text(&out.stdout)
    );
    let out = hdot(&["verify", plain.to_str().unwrap(), "--require"]);
    assert_eq!(out.status.code(), Some(1));
}

/// Every bundled file that declares its model gives the same verification
/// report copied under another name as under its own (nothing is looked
/// up by file name).
#[test]
fn every_declared_bundled_file_verifies_the_same_under_another_name() {
    let dir = tempfile::tempdir().unwrap();
    let mut compared = 0;
    for e in std::fs::read_dir(repo_root().join("derivations")).unwrap() {
        let path = e.unwrap().path();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.extension().is_none_or(|x| x != "toml") || stem == "notes" {
            continue;
        }
        let text_in = std::fs::read_to_string(&path).unwrap();
        if !text_in.contains("\nmeans = ") {
            continue;
        }
        let copy = dir.path().join("renamed-copy.toml");
        std::fs::write(&copy, &text_in).unwrap();
        // The report, words only (the name column's padding differs).
        let run = |p: &str| {
            let out = hdot(&["verify", p, "--bodies", "3", "--steps"]);
            let words = text(&out.stdout)
                .replace("renamed-copy", &stem)
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ");
            (out.status.code(), words)
        };
        let (code0, so0) = run(&stem);
        assert_eq!(code0, Some(0), "{so0}");
        assert!(so0.contains(" pass "), "{so0}");
        assert_eq!(run(copy.to_str().unwrap()), (code0, so0), "{stem}");
        compared += 1;
    }
    assert!(compared >= 21, "{compared} files declare their model");
}

/// A folder argument to `check` and `verify` stands for every derivation
/// file in it (a lecturer's own folder); `derive` names one file and says so.
#[test]
fn check_and_verify_take_a_folder_of_derivations() {
    let dir = tempfile::tempdir().unwrap();
    let mut copied = Vec::new();
    for name in ["turntable", "askew-disk"] {
        let from = repo_root().join(format!("derivations/{name}.toml"));
        let to = dir.path().join(format!("mine-{name}.toml"));
        std::fs::copy(from, &to).unwrap();
        copied.push(format!("mine-{name}"));
    }
    let folder = dir.path().to_str().unwrap();
    let check = hdot(&["check", folder]);
    let so = text(&check.stdout);
    assert_eq!(check.status.code(), Some(0), "{so}{}", text(&check.stderr));
    let verify = hdot(&["verify", folder, "--bodies", "3"]);
    let sv = text(&verify.stdout);
    assert_eq!(
        verify.status.code(),
        Some(0),
        "{sv}{}",
        text(&verify.stderr)
    );
    for n in &copied {
        assert!(so.contains(n.as_str()), "check lists {n}: {so}");
        assert!(sv.contains(n.as_str()), "verify lists {n}: {sv}");
    }
    let derive = hdot(&["derive", folder]);
    assert_eq!(derive.status.code(), Some(2));
    assert!(
        text(&derive.stderr).contains("is a folder"),
        "{}",
        text(&derive.stderr)
    );
}

/// Issue 11: non-finite and overflowing input refused (exit 2), a requested
/// error that is not met is a failure (exit 1), closed forms report an
/// estimate.
#[test]
fn simulate_refuses_what_f64_cannot_carry_and_reports_estimates() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, initial: &str| {
        let p = dir.path().join(name);
        std::fs::write(
            &p,
            format!(
                "name = \"t\"\nkind = \"free\"\nt_end = 10.0\n[[body]]\nprincipal_moments = [1.0, 2.0, 3.0]\nmass = 1.0\n[initial]\n{initial}\n"
            ),
        )
        .unwrap();
        p.to_string_lossy().into_owned()
    };
    let big = write("big.toml", "angular_momentum = [1e200, 1.0, 1.0]");
    let out = hdot(&["simulate", &big]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("initial.angular_momentum"));
    let near = write("near.toml", "angular_velocity = [1e-6, 1.0, 1e-6]");
    for t in ["inf", "1e308", "nan"] {
        let out = hdot(&["simulate", &near, "--t-end", t]);
        assert_eq!(
            out.status.code(),
            Some(2),
            "--t-end {t}: {}",
            text(&out.stderr)
        );
    }
    let out = hdot(&[
        "work-precision",
        &near,
        "--min-time",
        "inf",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    let out = hdot(&["simulate", &near, "--check"]);
    let so = text(&out.stdout);
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
    assert!(so.contains("(estimated:") && so.contains("check:"), "{so}");
    assert!(!so.contains("this is the reference"), "{so}");
    let out = hdot(&["simulate", &near, "--tol", "1e-20"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("not met"));
}

/// Issue 21 item 10: `work-precision` on a body at rest (every method
/// exact, no positive error to draw on a log scale) exited 1 on the
/// chart; it writes the CSV, says why there is no chart, and exits 0.
#[test]
fn work_precision_on_a_body_at_rest_succeeds() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("rest.toml");
    std::fs::write(
        &scene,
        "name = \"rest\"\nkind = \"free\"\nt_end = 1.0\n[[body]]\nprincipal_moments = [1.0, 2.0, 2.5]\n\
         mass = 1.0\n[initial]\nangular_velocity = [0.0, 0.0, 0.0]\n",
    )
    .unwrap();
    let out = hdot(&[
        "work-precision",
        scene.to_str().unwrap(),
        "--min-time",
        "0",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let so = text(&out.stdout);
    assert!(out.status.success(), "{so}{}", text(&out.stderr));
    assert!(so.contains("no chart"), "{so}");
    // The rows on stderr come under the CSV's header line (issue 24's
    // trial: they had none).
    let se = text(&out.stderr);
    let mut rows = se.lines();
    assert_eq!(rows.next(), Some(hdot_sim::run::CSV_HEADER), "{se}");
    let columns = hdot_sim::run::CSV_HEADER.split(',').count();
    assert!(
        rows.next().is_some_and(|r| r.split(',').count() == columns),
        "{se}"
    );
    assert!(dir.path().join("rest-work-precision.csv").is_file());
    assert!(!dir.path().join("rest-work-precision.svg").exists());
}

/// A derived scene run without --tol and --method fits its tolerance to
/// the default target 1e-8, tightening it while its pilots miss. When no
/// tolerance reaches it (an inverted pendulum started at its top, written
/// for the test, whose state at T depends on the smallest error), the run
/// is reported with a note and exits 0 — the user asked for no error
/// (issue 24's trial: it exited 1); `--tol 1e-8`, asked for, exits 1.
#[test]
fn simulate_derived_default_target_not_met_is_a_note() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("top.toml"),
        "title = \"inverted pendulum\"\nsource = \"written for the test\"\n[symbols]\nconstants = [\"k\"]\n\
         time = [\"x\"]\n[[step]]\nname = \"acc\"\nvalue = \"solve(list(x'' - k*sin(x)), [x''])\"\n",
    )
    .unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(
        &scene,
        "name = \"top\"\nkind = \"derived\"\nt_end = 12.0\n[derivation]\nfile = \"top.toml\"\n\
         accelerations = \"acc\"\n[constants]\nk = 100.0\n[initial]\n\
         coordinates = { x = 3.141592653589793 }\nrates = { x = 0.0 }\n",
    )
    .unwrap();
    let scene = scene.to_str().unwrap();
    let default = hdot(&["simulate", scene]);
    let se = text(&default.stderr);
    assert_eq!(default.status.code(), Some(0), "{se}");
    assert!(
        se.contains("note: the default error 1e-8 (no --tol given) is not reached"),
        "{se}"
    );
    assert!(
        text(&default.stdout).contains("a pilot at tol="),
        "{}",
        text(&default.stdout)
    );
    let explicit = hdot(&["simulate", scene, "--tol", "1e-8"]);
    let se = text(&explicit.stderr);
    assert_eq!(explicit.status.code(), Some(1), "{se}");
    assert!(se.contains("the requested error 1e-8 is not met"), "{se}");
}

/// A derived scene whose derivation declares a step conserved that its
/// equations do not conserve (a pendulum's rate, written for the test)
/// fails: the drift is far above the error at T, so `simulate` exits 1
/// naming the step; the energy alone, truly conserved, passes.
#[test]
fn simulate_fails_on_a_false_conservation_claim() {
    let dir = tempfile::tempdir().unwrap();
    let derivation = |extra: &str| {
        format!(
            "title = \"pendulum\"\nsource = \"written for the test\"\n[symbols]\nconstants = [\"k\"]\n\
             time = [\"x\"]\n[[step]]\nname = \"acc\"\nvalue = \"solve(list(x'' + k*sin(x)), [x''])\"\n\
             [[step]]\nname = \"energy\"\nvalue = \"x'^2/2 - k*cos(x)\"\nconserved = true\n{extra}"
        )
    };
    let scene = dir.path().join("scene.toml");
    std::fs::write(
        &scene,
        "name = \"pendulum\"\nkind = \"derived\"\nt_end = 3.0\n[derivation]\nfile = \"p.toml\"\n\
         accelerations = \"acc\"\n[constants]\nk = 4.0\n[initial]\n\
         coordinates = { x = 1.0 }\nrates = { x = 0.0 }\n",
    )
    .unwrap();
    let scene = scene.to_str().unwrap();
    std::fs::write(dir.path().join("p.toml"), derivation("")).unwrap();
    let good = hdot(&["simulate", scene]);
    assert!(
        good.status.success(),
        "{}{}",
        text(&good.stdout),
        text(&good.stderr)
    );
    std::fs::write(
        dir.path().join("p.toml"),
        derivation("[[step]]\nname = \"swing\"\nvalue = \"x'\"\nconserved = true\n"),
    )
    .unwrap();
    let bad = hdot(&["simulate", scene]);
    assert_eq!(bad.status.code(), Some(1), "{}", text(&bad.stdout));
    assert!(
        text(&bad.stderr).contains("step `swing` is declared conserved"),
        "{}",
        text(&bad.stderr)
    );
    assert!(text(&bad.stdout).contains("FAIL"), "{}", text(&bad.stdout));
}
