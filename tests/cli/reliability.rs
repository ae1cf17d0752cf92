//! Reliability of the binary (issue 13): a closed stdout, output that
//! never destroys, bounded parsing, strict options, and an installed
//! binary that needs no source tree.

use std::process::{Command, Stdio};

use hdot_tests::{hdot_bin, repo_root};

use super::{hdot, text};

fn example(name: &str) -> String {
    repo_root()
        .join("docs/examples")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn a_closed_stdout_ends_every_command_quietly() {
    let notes = tempfile::tempdir().unwrap();
    let rod = example("rod-on-axle.toml");
    let commands: Vec<Vec<&str>> = vec![
        vec!["list"],
        vec!["check", "euler-principal", "fixed-axis"],
        vec!["derive", "euler-general"],
        vec!["inertia", &rod],
        vec!["dynamics", &rod],
        vec!["verify", "euler-principal", "--bodies", "2"],
        vec!["notes", "--out", notes.path().to_str().unwrap()],
    ];
    for args in commands {
        let mut child = Command::new(hdot_bin())
            .args(&args)
            .current_dir(repo_root())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Close the reading end before the command writes anything.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn a_closed_stderr_keeps_the_documented_exit_code() {
    let dir = tempfile::tempdir().unwrap();
    // a scene that does not parse: bad input, exit 2, its message on stderr
    let bad = dir.path().join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"x\"\n[[body]]\nshape = \"sphere\"\nmass = \"heavy\"\n",
    )
    .unwrap();
    let bad = bad.to_str().unwrap();
    let cases: Vec<(Vec<&str>, i32)> = vec![
        (vec!["simulate", bad], 2),
        (vec!["inertia", bad], 2),
        (vec!["dynamics", bad], 2),
        (vec!["derive", "no-such-derivation"], 2),
    ];
    for (args, code) in cases {
        let mut child = Command::new(hdot_bin())
            .args(&args)
            .current_dir(repo_root())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Close the reading end of stderr before the command reports.
        drop(child.stderr.take());
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(code), "{args:?}");
    }
}

#[test]
fn a_result_that_cannot_be_written_exits_1() {
    let out = hdot(&["derive", "euler-principal", "--out", "/dev/full"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let out = hdot(&[
        "derive",
        "euler-principal",
        "--out",
        "/proc/no/such/dir/x.tex",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    // Output to /dev/stdout is written in place.
    let out = hdot(&["derive", "euler-principal", "--out", "/dev/stdout"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("Euler"));
}

#[test]
fn deep_nesting_and_huge_literals_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let n = 10_000;
    for (what, value) in [
        (
            "parentheses",
            format!("{}a{}", "(".repeat(n), ")".repeat(n)),
        ),
        ("minus", format!("{}a", "-".repeat(n))),
        ("dt", format!("{}x{}", "dt(".repeat(n), ")".repeat(n))),
        (
            "cross",
            format!("{}a{}", "cross(a, ".repeat(n), ")".repeat(n)),
        ),
        (
            "subst",
            format!("{}x{}", "subst(".repeat(n), ", a = 1)".repeat(n)),
        ),
        ("literal", format!("{}*a", "7".repeat(1_000_000))),
    ] {
        let f = dir.path().join(format!("{what}.toml"));
        std::fs::write(
            &f,
            format!(
                "title = \"t\"\nsource = \"s\"\n[symbols]\nconstants = [\"a\"]\ntime = [\"x\"]\n[[step]]\nname = \"s\"\nvalue = \"{value}\"\n"
            ),
        )
        .unwrap();
        let out = hdot(&["derive", f.to_str().unwrap()]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{what}: {err}");
        assert!(
            err.contains("nests deeper than") || err.contains("digits"),
            "{what}: {err}"
        );
    }
}

#[test]
fn digits_are_bounded() {
    let rod = example("rod-on-axle.toml");
    for cmd in ["inertia", "dynamics"] {
        let out = hdot(&[cmd, &rod, "--digits", "65536"]);
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        assert!(text(&out.stderr).contains("--digits"), "{cmd}");
        let out = hdot(&[cmd, &rod, "--digits", "17"]);
        assert!(out.status.success(), "{cmd}: {}", text(&out.stderr));
    }
}

#[test]
fn outputs_never_destroy_inputs_or_leave_partial_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // derive F --out F is refused; F is unchanged.
    let f = d.join("mine.toml");
    let original =
        std::fs::read_to_string(repo_root().join("derivations/fixed-axis.toml")).unwrap();
    std::fs::write(&f, &original).unwrap();
    let out = hdot(&["derive", f.to_str().unwrap(), "--out", f.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("is an input"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(std::fs::read_to_string(&f).unwrap(), original);
    // … also through a link to it.
    let link = d.join("link.tex");
    std::os::unix::fs::symlink(&f, &link).unwrap();
    let out = hdot(&[
        "derive",
        f.to_str().unwrap(),
        "--out",
        link.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&f).unwrap(), original);

    // simulate S --output S is refused.
    let s = d.join("scene.toml");
    std::fs::copy(example("sim-shaft-unbalanced.toml"), &s).unwrap();
    let before = std::fs::read(&s).unwrap();
    let out = hdot(&[
        "simulate",
        s.to_str().unwrap(),
        "--output",
        s.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert_eq!(std::fs::read(&s).unwrap(), before);

    // --out through a link writes where the link points; new files follow
    // the umask (not 0600).
    let target = d.join("target.tex");
    let link = d.join("out-link.tex");
    std::os::unix::fs::symlink("target.tex", &link).unwrap();
    let out = hdot(&["derive", "euler-principal", "--out", link.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(std::fs::read_to_string(&target).unwrap().contains("Euler"));
    use std::os::unix::fs::PermissionsExt;
    let mode = std::fs::metadata(&target).unwrap().permissions().mode();
    assert_ne!(mode & 0o777, 0o600, "mode {mode:o}");

    // A failing run leaves no streamed rows behind (exit 1).
    let rows = d.join("rows.csv");
    let out = hdot(&[
        "simulate",
        &example("sim-heavy-top.toml"),
        "--method",
        "euler",
        "--dt",
        "1",
        "--t-end",
        "100000",
        "--output",
        rows.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(!rows.exists());

    // notes: the LaTeX is not written when the Markdown cannot be.
    let notes = d.join("notes");
    std::fs::create_dir_all(notes.join("hdot-notes.md")).unwrap();
    let out = hdot(&["notes", "--out", notes.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(!notes.join("hdot-notes.tex").exists());

    // work-precision: no CSV when the chart cannot be written.
    let wp = d.join("wp");
    std::fs::create_dir_all(wp.join("sim-shaft-unbalanced-work-precision.png")).unwrap();
    let out = hdot(&[
        "work-precision",
        &example("sim-shaft-unbalanced.toml"),
        "--out",
        wp.to_str().unwrap(),
        "--t-end",
        "0.01",
        "--min-time",
        "0",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(!wp.join("sim-shaft-unbalanced-work-precision.csv").exists());

    // No temporary file is left anywhere.
    for dir in [d, &notes, &wp] {
        for e in std::fs::read_dir(dir).unwrap() {
            let name = e.unwrap().file_name();
            assert!(!name.to_string_lossy().starts_with(".hdot-tmp"), "{name:?}");
        }
    }
}

/// Every file a command reads is an input no output may replace: the
/// derivation a scene names, a notes manifest, a derivation the notes are
/// made of (issue 21). Refused with exit 2, nothing written.
#[test]
fn files_a_command_reads_are_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let root = repo_root();
    let heavy_top = std::fs::read_to_string(root.join("derivations/heavy-top.toml")).unwrap();
    // simulate s.toml --output d.toml, the scene's derivation being d.toml.
    let derivation = d.join("d.toml");
    std::fs::write(&derivation, &heavy_top).unwrap();
    let scene = std::fs::read_to_string(example("sim-derived-heavy-top.toml"))
        .unwrap()
        .replace("file = \"heavy-top\"", "file = \"d.toml\"");
    assert!(scene.contains("d.toml"));
    let s = d.join("s.toml");
    std::fs::write(&s, scene).unwrap();
    let out = hdot(&[
        "simulate",
        s.to_str().unwrap(),
        "--t-end",
        "0.01",
        "--output",
        derivation.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("is an input"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(std::fs::read_to_string(&derivation).unwrap(), heavy_top);

    // notes in --manifest o/hdot-notes.md --out o.
    let input = d.join("in");
    std::fs::create_dir_all(&input).unwrap();
    std::fs::write(input.join("heavy-top.toml"), &heavy_top).unwrap();
    let o = d.join("o");
    std::fs::create_dir_all(&o).unwrap();
    let manifest = o.join("hdot-notes.md");
    let manifest_text = "title = \"t\"\nauthor = \"a\"\n[[chapter]]\ntitle = \"c\"\nderivations = [\"heavy-top\"]\n";
    std::fs::write(&manifest, manifest_text).unwrap();
    let out = hdot(&[
        "notes",
        input.to_str().unwrap(),
        "--manifest",
        manifest.to_str().unwrap(),
        "--out",
        o.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert_eq!(std::fs::read_to_string(&manifest).unwrap(), manifest_text);
    assert!(!o.join("hdot-notes.tex").exists());

    // A derivation at o/hdot-notes.tex, or at o/fragments/d.tex, with --out o.
    let as_notes = o.join("hdot-notes.tex");
    std::fs::write(&as_notes, &heavy_top).unwrap();
    let out = hdot(&[
        "notes",
        as_notes.to_str().unwrap(),
        "--out",
        o.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert_eq!(std::fs::read_to_string(&as_notes).unwrap(), heavy_top);
    std::fs::create_dir_all(o.join("fragments")).unwrap();
    let as_fragment = o.join("fragments/d.tex");
    std::fs::write(&as_fragment, &heavy_top).unwrap();
    let out = hdot(&[
        "notes",
        as_fragment.to_str().unwrap(),
        "--fragments",
        "--out",
        o.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert_eq!(std::fs::read_to_string(&as_fragment).unwrap(), heavy_top);
    for e in std::fs::read_dir(&o).unwrap() {
        let name = e.unwrap().file_name();
        assert!(!name.to_string_lossy().starts_with(".hdot-tmp"), "{name:?}");
    }
}

/// Files in the wrong encoding are located errors; `check` takes the
/// names `derive` takes (issue 21).
#[test]
fn encodings_are_located_and_check_takes_chain_names() {
    let dir = tempfile::tempdir().unwrap();
    let text_of = |name: &str| std::fs::read_to_string(repo_root().join(name)).unwrap();
    let euler = text_of("derivations/euler-principal.toml");
    let latin1 = dir.path().join("latin1.toml");
    std::fs::write(&latin1, [euler.as_bytes(), &b"# \xe9\n"[..]].concat()).unwrap();
    let out = hdot(&["derive", latin1.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let line = euler.lines().count() + 1;
    assert!(
        text(&out.stderr).contains(&format!("latin1.toml:{line}:3")),
        "{}",
        text(&out.stderr)
    );
    let scene = dir.path().join("utf16.toml");
    let le: Vec<u8> = [0xFF, 0xFE]
        .into_iter()
        .chain(
            text_of("docs/examples/sim-shaft-unbalanced.toml")
                .encode_utf16()
                .flat_map(u16::to_le_bytes),
        )
        .collect();
    std::fs::write(&scene, le).unwrap();
    for command in ["inertia", "simulate"] {
        let out = hdot(&[command, scene.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{command}");
        assert!(
            text(&out.stderr).contains("UTF-16") && text(&out.stderr).contains("utf16.toml"),
            "{command}: {}",
            text(&out.stderr)
        );
    }

    let out = hdot(&["check", "chain-2"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("chain-2"),
        "{}",
        text(&out.stdout)
    );
}

#[test]
fn empty_folders_and_crashing_files_do_not_pass_silently() {
    let dir = tempfile::tempdir().unwrap();
    for cmd in ["check", "verify", "list"] {
        let out = hdot(&[cmd, "--dir", dir.path().to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        assert!(text(&out.stderr).contains("no derivation files"), "{cmd}");
    }
}

#[test]
fn non_finite_results_are_errors_naming_the_quantity() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("fast.toml");
    std::fs::write(
        &f,
        "name = \"fast\"\n[[body]]\nshape = \"prism\"\na = 1.0\nb = 2.0\nc = 3.0\nmass = 2.0\n[motion]\nomega = [1e200, 0.0, 0.0]\n",
    )
    .unwrap();
    // Rates whose moments would leave f64's range are refused before any
    // result is formed, naming the field at its line (exit 2).
    let out = hdot(&["dynamics", f.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stdout));
    let err = text(&out.stderr);
    assert!(
        err.contains("motion.omega") && err.contains("fast.toml:9"),
        "{err}"
    );
    assert!(!text(&out.stdout).contains("inf"));
}

/// The binary copied away from the source tree, run from an empty folder:
/// the bundled derivations and scenes are embedded in it.
#[test]
fn an_installed_binary_needs_no_source_tree() {
    let dir = tempfile::tempdir().unwrap();
    let bin = dir.path().join("hdot");
    std::fs::copy(hdot_bin(), &bin).unwrap();
    let work = dir.path().join("work");
    std::fs::create_dir(&work).unwrap();
    // A binary copied while another test thread forks may still be open for
    // writing in that child until it execs, and running it then fails with
    // ETXTBSY ("Text file busy"; rust-lang/rust#114554): retry briefly.
    let run = |args: &[&str]| {
        let mut tries = 0;
        loop {
            match Command::new(&bin)
                .args(args)
                .current_dir(&work)
                .env_remove("HDOT_DERIVATIONS")
                .output()
            {
                Ok(out) => break out,
                Err(e) if e.raw_os_error() == Some(26) && tries < 50 => {
                    tries += 1;
                    std::thread::sleep(std::time::Duration::from_millis(20));
                }
                Err(e) => panic!("cannot run the copied binary: {e}"),
            }
        }
    };
    let out = run(&["list"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("euler-principal"));
    let out = run(&["check", "euler-principal", "fixed-axis"]);
    assert!(
        out.status.success(),
        "{}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    let out = run(&["verify", "euler-general", "--bodies", "2"]);
    assert!(
        out.status.success(),
        "{}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    let out = run(&["derive", "fixed-axis", "--format", "sympy"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let out = run(&["simulate", "sim-shaft-unbalanced", "--t-end", "0.1"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let out = run(&[
        "simulate",
        "docs/examples/sim-shaft-unbalanced.toml",
        "--t-end",
        "0.1",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
}

/// A CSV cloud a scene reads is an input too: neither `--output` nor
/// `--html` may replace it (issue 21 item 4), exit 2, the file unchanged.
#[test]
fn a_scene_s_cloud_is_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cloud_text = "x,y,z,m\n0,0,0.05,0.01\n";
    let cloud = d.join("c.csv");
    std::fs::write(&cloud, cloud_text).unwrap();
    let heavy_top = repo_root().join("derivations/heavy-top.toml");
    let scene = std::fs::read_to_string(example("sim-derived-heavy-top.toml"))
        .unwrap()
        .replace(
            "file = \"heavy-top\"",
            &format!("file = {:?}", heavy_top.to_str().unwrap()),
        )
        .replace("[initial]", "[[cloud]]\nfile = \"c.csv\"\n\n[initial]");
    assert!(scene.contains("[[cloud]]"));
    let s = d.join("s.toml");
    std::fs::write(&s, scene).unwrap();
    for flag in ["--output", "--html"] {
        let out = hdot(&[
            "simulate",
            s.to_str().unwrap(),
            "--t-end",
            "0.01",
            flag,
            cloud.to_str().unwrap(),
        ]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag}: {err}");
        assert!(err.contains("is an input of this command"), "{flag}: {err}");
        assert_eq!(std::fs::read_to_string(&cloud).unwrap(), cloud_text);
    }
    // work-precision refuses before its sweep: nothing is written, neither
    // the page nor the CSV and charts (a cloud named like its CSV too).
    let out_dir = d.join("wp");
    let wp_cloud = d.join("s-work-precision.csv");
    std::fs::write(&wp_cloud, cloud_text).unwrap();
    let with_two = std::fs::read_to_string(&s).unwrap().replace(
        "[initial]",
        "[[cloud]]\nfile = \"s-work-precision.csv\"\n\n[initial]",
    );
    std::fs::write(&s, with_two).unwrap();
    for extra in [
        &[
            "--out",
            out_dir.to_str().unwrap(),
            "--html",
            cloud.to_str().unwrap(),
        ][..],
        &["--out", d.to_str().unwrap()][..],
    ] {
        let mut args = vec!["work-precision", s.to_str().unwrap(), "--t-end", "0.01"];
        args.extend_from_slice(extra);
        let out = hdot(&args);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {err}");
        assert!(
            err.contains("is an input of this command"),
            "{extra:?}: {err}"
        );
        assert!(!out_dir.exists(), "{extra:?}: {err}");
        assert!(!d.join("s-work-precision.svg").exists(), "{extra:?}: {err}");
        assert_eq!(std::fs::read_to_string(&cloud).unwrap(), cloud_text);
        assert_eq!(std::fs::read_to_string(&wp_cloud).unwrap(), cloud_text);
    }
}

/// A derived scene names its derivation by a bare name, found in a
/// `derivations` folder at or above the scene's folder on disk: run from
/// the scene's own folder with the scene's bare file name (a path with no
/// folder in it), it finds the repository's `derivations/` two folders up.
#[test]
fn a_derived_scene_finds_its_derivation_from_its_own_folder() {
    let folder = repo_root().join("docs/examples");
    let out_dir = tempfile::tempdir().unwrap();
    let out_dir = out_dir.path().to_str().unwrap();
    for args in [
        &["simulate", "sim-derived-heavy-top.toml", "--t-end", "0.01"][..],
        &["stability", "stability-bicycle.toml", "--out", out_dir][..],
    ] {
        let out = Command::new(hdot_bin())
            .args(args)
            .current_dir(&folder)
            .env_remove("HDOT_DERIVATIONS")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}{}",
            text(&out.stdout),
            text(&out.stderr)
        );
    }
}
