//! Shared helpers of the integration tests.

pub mod fixtures;
pub mod pendulum;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The eigenvalues (re, im) of the Whipple bicycle's linearized lean–steer
/// equations at rest and at 5 m/s: Table 2 of Meijaard, Papadopoulos, Ruina
/// & Schwab, *Proc. R. Soc. A* 463 (2007). Expectations only — the
/// derivations compute them; the linear and the nonlinear bicycle's tests
/// both compare with this one table.
pub const WHIPPLE_EIGENVALUES: [(f64, [(f64, f64); 4]); 2] = [
    (
        0.0,
        [
            (-5.53094371765393, 0.0),
            (-3.13164324790656, 0.0),
            (3.13164324790656, 0.0),
            (5.53094371765393, 0.0),
        ],
    ),
    (
        5.0,
        [
            (-14.07838969279822, 0.0),
            (-0.77534188219585, -4.46486771378823),
            (-0.77534188219585, 4.46486771378823),
            (-0.32286642900409, 0.0),
        ],
    ),
];

/// The seed of every property test that names none: fixed, so that a run —
/// CI's included — draws the same inputs as the last and a failure repeats.
pub const PROPTEST_SEED: u64 = 0x68_64_6f_74; // "hdot"

/// The proptest configuration of a property test: `cases` cases unless
/// `PROPTEST_CASES` gives another number, drawn from [`PROPTEST_SEED`]
/// unless `PROPTEST_RNG_SEED` gives another seed. A long run that explores
/// further than CI:
///
/// ```text
/// PROPTEST_RNG_SEED=$RANDOM PROPTEST_CASES=100000 cargo test --release -p hdot-tests --test fuzz
/// ```
pub fn proptest_config(cases: u32) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, RngSeed};
    // `Config::default()` reads the `PROPTEST_*` variables.
    let mut c = Config::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = cases;
    }
    if c.rng_seed == RngSeed::Random {
        c.rng_seed = RngSeed::Fixed(PROPTEST_SEED);
    }
    c
}

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

/// Hostile strings, and reading what hdot wrote for them as LaTeX,
/// Markdown or HTML, for the tests that feed them to every field
/// (`tests/sym/injection.rs`, `tests/fuzz/hostile.rs`): one table of
/// strings, one TOML quoting, one pdflatex run.
pub mod markup {
    use std::path::Path;
    use std::process::Command;

    /// Strings of issue 21 that mean something to TeX, HTML or Markdown:
    /// control words that read files or loop, unbalanced braces, blank lines, `^^`
    /// character codes, tags, entities, code fences.
    pub const TEX_HTML: &[&str] = &[
        r"\input\x",
        r"\end{document}",
        r"\immediate\write18{id}",
        r"\def\x{\x}\x",
        r"{{{ unbalanced \x",
        r"}} unbalanced \x{",
        r"100% # $ & ~ ^ _ ^^5c ^^M \\ \x",
        r"$\input{x}$ and $x^^5cinput$ and $x_$",
        "</math></mi><script>alert(1)</script>",
        "&amp; &lt;b onload=\"x\"> <img src=x onerror=alert(1)> 'single' \"double\"",
        "``` \\x ` <!-- [link](javascript:x) *em* _u_",
        r"``` \x <script>alert(1)</script> ` %% & # ~ ^ _",
        // A backtick in a formula: math, where Markdown must not see a
        // code span open.
        "<`= and θ`<x and $a`<b/c$ then `top.toml`",
        // A blank line is a paragraph break, which a heading cannot hold.
        "a paragraph\n\nbreak \\x\n\n",
    ];

    /// Strings that mean something to a terminal or to a text's direction:
    /// bidirectional overrides, escape sequences, NUL, line separators.
    pub const TERMINAL: &[&str] = &[
        "bidi \u{202E}\\input\\x\u{202C} \u{2066}iso\u{2069} \u{200F}rtl",
        "control \u{1b}[31m red \u{7} bell \u{0} nul \u{8} \r carriage \u{85} \u{2028} end",
    ];

    /// Strings that would end a Python comment or string literal early.
    pub const PYTHON: &[&str] = &[
        "x\nimport os; os.system('id')",
        "it's \"quoted\" ''' \"\"\" \\",
        "back\\slash\\\nnew line\\",
        "\r\n# carriage\u{2028}separator\u{85}next\u{b}\u{c}",
        "\u{0}nul and \u{1b}[31m escape",
    ];

    /// [`TEX_HTML`] and [`TERMINAL`], and one long string of unbalanced
    /// control words (past TeX's grouping and input stacks).
    pub fn hostile() -> Vec<String> {
        let mut v: Vec<String> = TEX_HTML
            .iter()
            .chain(TERMINAL)
            .map(|s| (*s).to_owned())
            .collect();
        v.push(r"\input\x{".repeat(1500) + "$ </math>");
        v
    }

    /// A TOML basic string holding `s` (control characters as `\uXXXX`).
    pub fn toml_str(s: &str) -> String {
        let mut o = String::from('"');
        for c in s.chars() {
            match c {
                '"' => o.push_str("\\\""),
                '\\' => o.push_str("\\\\"),
                c if c.is_control() => o.push_str(&format!("\\u{:04X}", c as u32)),
                c => o.push(c),
            }
        }
        o.push('"');
        o
    }

    /// Whether a command runs; when it does not, the test says so and goes
    /// on (unless `CI=true`, where a missing tool fails).
    pub fn have(cmd: &str, args: &[&str], why: &str) -> bool {
        let ok = Command::new(cmd)
            .args(args)
            .output()
            .is_ok_and(|o| o.status.success());
        if !ok {
            assert!(
                std::env::var("CI").as_deref() != Ok("true"),
                "{cmd} is needed on CI: {why}"
            );
            eprintln!("{cmd} not usable: {why} skipped");
        }
        ok
    }

    /// `tex` (what was written for `what`) compiles with pdflatex in
    /// `dir`, shell escape off.
    pub fn compile(what: &str, dir: &Path, tex: &str) {
        std::fs::write(dir.join("n.tex"), tex).unwrap();
        let out = Command::new("pdflatex")
            .args([
                "-no-shell-escape",
                "-interaction=nonstopmode",
                "-halt-on-error",
                "n.tex",
            ])
            .current_dir(dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{what} does not compile:\n{}",
            String::from_utf8_lossy(&out.stdout)
        );
    }

    /// Only ASCII and Latin-1 letters reach pdflatex (comments aside).
    pub fn assert_pdflatex_characters(h: &str, tex: &str) {
        for l in uncommented(tex).lines() {
            assert!(
                l.chars().all(|c| c.is_ascii() || matches!(c, 'À'..='ÿ')),
                "LaTeX of {h:?}: a character pdflatex cannot set, written raw:\n{l}"
            );
        }
    }

    /// Control words hdot never writes of its own.
    pub const FORBIDDEN: &[&str] = &[
        "input",
        "include",
        "immediate",
        "write",
        "def",
        "x",
        "catcode",
        "csname",
        "openout",
    ];

    /// LaTeX without its comments: each line up to its first `%` that is
    /// not escaped as `\%`.
    pub fn uncommented(tex: &str) -> String {
        let mut o = String::with_capacity(tex.len());
        for line in tex.lines() {
            let mut escaped = false;
            for c in line.chars() {
                if c == '%' && !escaped {
                    break;
                }
                escaped = c == '\\' && !escaped;
                o.push(c);
            }
            o.push('\n');
        }
        o
    }

    /// The LaTeX `tex` written for `h` holds none of [`FORBIDDEN`], braces
    /// that balance, `documents` times `\end{document}` and no `^^`
    /// character code (outside comments).
    pub fn assert_safe(what: &str, h: &str, tex: &str, documents: usize) {
        let (words, balanced) = control_words(tex);
        for w in FORBIDDEN {
            assert!(
                !words.iter().any(|x| x == w),
                "{what} of {h:?}: the control word \\{w} survives:\n{tex}"
            );
        }
        assert!(balanced, "{what} of {h:?}: braces do not balance:\n{tex}");
        let uncommented = uncommented(tex);
        assert_eq!(
            uncommented.matches(r"\end{document}").count(),
            documents,
            "{what} of {h:?}: \\end{{document}} written by the input:\n{tex}"
        );
        assert!(
            !uncommented.contains("^^"),
            "{what} of {h:?}: a ^^ character code:\n{tex}"
        );
    }

    /// No HTML tag of the input in Markdown outside code: every `<` before
    /// a letter or `/` is escaped (hdot's own anchors aside).
    pub fn assert_no_html(what: &str, h: &str, md: &str) {
        let text = without_code(md);
        for (k, _) in text.match_indices('<') {
            let after = &text[k + 1..];
            let tag = after.starts_with(|c: char| c.is_alphabetic() || c == '/');
            let escaped = text[..k].ends_with('\\');
            assert!(
                !tag || escaped || after.starts_with("a id=") || after.starts_with("/a>"),
                "{what} of {h:?}: an HTML tag at {}",
                &text[k..(k + 20).min(text.len())]
            );
        }
    }

    /// The control words of LaTeX text (escaped characters such as `\{`
    /// and `\\` skipped), and whether its braces balance, comments left out.
    pub fn control_words(tex: &str) -> (Vec<String>, bool) {
        let mut words = Vec::new();
        let mut depth = 0i64;
        let mut balanced = true;
        for line in tex.lines() {
            let mut cs = line.chars().peekable();
            while let Some(c) = cs.next() {
                match c {
                    '\\' => {
                        let mut w = String::new();
                        while let Some(&n) = cs.peek().filter(|n| n.is_ascii_alphabetic()) {
                            w.push(n);
                            cs.next();
                        }
                        if w.is_empty() {
                            cs.next();
                        } else {
                            words.push(w);
                        }
                    }
                    '%' => break,
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        balanced &= depth >= 0;
                    }
                    _ => {}
                }
            }
        }
        (words, balanced && depth == 0)
    }

    /// Markdown without its code spans (which show their text as written).
    /// A backtick after a backslash (`` \` ``) is a literal backtick, not
    /// a fence (CommonMark's backslash escapes).
    pub fn without_code(md: &str) -> String {
        // The first backtick of `s` that an odd run of backslashes does
        // not escape.
        fn fence_at(s: &str) -> Option<usize> {
            s.match_indices('`')
                .map(|(k, _)| k)
                .find(|&k| s[..k].bytes().rev().take_while(|&b| b == b'\\').count() % 2 == 0)
        }
        let mut o = String::new();
        let mut rest = md;
        while let Some(k) = fence_at(rest) {
            o.push_str(&rest[..k]);
            let run = rest[k..].chars().take_while(|&c| c == '`').count();
            let fence = "`".repeat(run);
            let after = &rest[k + run..];
            // The closing fence: a run of exactly as many backticks.
            let close = after.match_indices(&fence).find(|(i, _)| {
                !after[i + run..].starts_with('`') && (*i == 0 || !after[..*i].ends_with('`'))
            });
            match close {
                Some((i, _)) => rest = &after[i + run..],
                None => {
                    o.push_str(&fence);
                    rest = after;
                }
            }
        }
        o.push_str(rest);
        o
    }

    /// The tags of an HTML page in order, each as its name (lower case, a
    /// closing tag with its `/`) and the names of its attributes; text,
    /// comments and the contents of `<script>`/`<style>` elements skipped.
    pub fn html_tags(page: &str) -> Vec<(String, Vec<String>)> {
        let mut tags = Vec::new();
        let mut rest = page;
        while let Some(k) = rest.find('<') {
            rest = &rest[k + 1..];
            if let Some(r) = rest.strip_prefix("!--") {
                rest = r.find("-->").map_or("", |e| &r[e + 3..]);
                continue;
            }
            let closing = rest.starts_with('/');
            let body = rest.trim_start_matches('/');
            let name: String = body
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '-' || *c == '!')
                .collect();
            if name.is_empty() {
                continue;
            }
            let mut attrs = Vec::new();
            let mut cs = body[name.len()..].char_indices().peekable();
            let mut end = body.len();
            while let Some((i, c)) = cs.next() {
                match c {
                    '>' => {
                        end = i + name.len();
                        break;
                    }
                    '"' | '\'' => {
                        for (_, d) in cs.by_ref() {
                            if d == c {
                                break;
                            }
                        }
                    }
                    c if c.is_ascii_alphabetic() => {
                        let mut a = String::from(c);
                        while let Some(&(_, d)) = cs.peek() {
                            if d.is_ascii_alphanumeric() || d == '-' || d == ':' {
                                a.push(d);
                                cs.next();
                            } else {
                                break;
                            }
                        }
                        attrs.push(a.to_ascii_lowercase());
                    }
                    _ => {}
                }
            }
            rest = &body[(end + 1).min(body.len())..];
            let lower = name.to_ascii_lowercase();
            if !closing && (lower == "script" || lower == "style") {
                let close = format!("</{lower}");
                rest = rest.find(&close).map_or("", |e| &rest[e..]);
            }
            tags.push((if closing { format!("/{lower}") } else { lower }, attrs));
        }
        tags
    }
}
