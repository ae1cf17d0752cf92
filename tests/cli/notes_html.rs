//! `hdot notes --html DIR` (issue 23): the notes as a site — the bundled
//! course and a lecturer's own folder — checked as files (the course's
//! order, navigation, anchors, one `<math>` per equation of the document
//! model, LaTeX as `alttext`, hostile strings escaped, nothing fetched)
//! and then in headless Chromium by `scripts/check_pages.py` (no console
//! error, every equation rendered with a size, no horizontal overflow at
//! 1280 and 400 px, each page < 1 MB); a folder that is not hdot's output
//! is refused.

use std::path::{Path, PathBuf};

use super::html::browser_check;
use super::{hdot, text};

/// The budget of one page of the notes.
const PAGE_BUDGET: u64 = 1 << 20;

/// The `href`s of a page's links, in order.
fn links(page: &str) -> Vec<String> {
    page.split("href=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_owned())
        .collect()
}

/// The value of `data-equations` on the page's `<main>`.
fn stated_equations(page: &str) -> usize {
    let at = page.find("<main data-equations=\"").expect("main") + 22;
    page[at..at + page[at..].find('"').unwrap()]
        .parse()
        .unwrap()
}

/// Writes the site of `args` into a new folder; the pages, in the index's
/// order, after the index itself.
fn site(args: &[&str], dir: &Path) -> Vec<PathBuf> {
    let mut all = vec!["notes"];
    all.extend_from_slice(args);
    all.extend(["--html", dir.to_str().unwrap()]);
    let out = hdot(&all);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let mut pages = vec![dir.join("index.html")];
    for l in links(&index) {
        if l.ends_with(".html") {
            pages.push(dir.join(l));
        }
    }
    pages
}

/// What every page must be as a file.
fn check_page_file(path: &Path) {
    let page = std::fs::read_to_string(path).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"), "{}", path.display());
    assert!((page.len() as u64) < PAGE_BUDGET, "{}", path.display());
    for fetch in [
        "<script",
        "src=\"http",
        "href=\"http",
        "url(",
        "@import",
        "src=\"//",
    ] {
        assert!(!page.contains(fetch), "{}: {fetch}", path.display());
    }
    assert_eq!(
        page.matches("<math").count(),
        stated_equations(&page),
        "{}",
        path.display()
    );
    // Every equation carries its LaTeX.
    assert_eq!(
        page.matches("<math").count(),
        page.matches("alttext=\"").count(),
        "{}",
        path.display()
    );
}

#[test]
fn the_bundled_course_is_a_site_the_browser_accepts() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("site");
    let pages = site(&[], &out);
    // The derivations in the manifest's order (each named first in its
    // chapter list).
    let manifest =
        std::fs::read_to_string(super::repo_root().join("derivations/notes.toml")).unwrap();
    let position = |p: &PathBuf| {
        let stem = p.file_stem().unwrap().to_str().unwrap();
        manifest
            .find(&format!("\"{stem}\""))
            .unwrap_or_else(|| panic!("{stem} not in the manifest"))
    };
    let order: Vec<usize> = pages[1..].iter().map(position).collect();
    assert!(order.is_sorted(), "{pages:?}");
    let files = std::fs::read_dir(super::repo_root().join("derivations"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml") && !p.ends_with("notes.toml"))
        .count();
    assert_eq!(pages.len(), 1 + files, "{pages:?}");
    // Previous and next lead along the same order; every page leads back to
    // the contents.
    for (k, p) in pages.iter().enumerate().skip(1) {
        let page = std::fs::read_to_string(p).unwrap();
        let ls = links(&page);
        assert!(ls.contains(&"index.html".to_owned()), "{}", p.display());
        if k + 1 < pages.len() {
            let next = pages[k + 1].file_name().unwrap().to_str().unwrap();
            assert!(
                page.contains(&format!("rel=\"next\" href=\"{next}\"")),
                "{}",
                p.display()
            );
        }
        if k > 1 {
            let prev = pages[k - 1].file_name().unwrap().to_str().unwrap();
            assert!(
                page.contains(&format!("rel=\"prev\" href=\"{prev}\"")),
                "{}",
                p.display()
            );
        }
        // Every step has an anchor its heading links to.
        let steps = page.matches("<section class=\"step\" id=\"").count();
        assert!(steps > 0, "{}", p.display());
        assert_eq!(steps, page.matches("<h3><a href=\"#step-").count());
        assert!(page.contains("<math display=\"block\""), "{}", p.display());
    }
    for p in &pages {
        check_page_file(p);
    }
    assert!(out.join("hdot-notes.css").is_file());
    // Written again into its own output: allowed.
    let again = hdot(&["notes", "--html", out.to_str().unwrap()]);
    assert!(again.status.success(), "{}", text(&again.stderr));
    browser_check(&pages, Some(PAGE_BUDGET));
}

#[test]
fn a_lecturers_folder_is_a_site_with_its_strings_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let course = dir.path().join("course");
    std::fs::create_dir(&course).unwrap();
    let hostile = r#"<script>alert(1)</script> & \"q\" <img src=x onerror=alert(2)>"#;
    std::fs::write(
        course.join("spin.toml"),
        format!(
            r#"title = "Spin of a sphere {hostile}"
source = "{hostile}"
summary = "The angular momentum ω_x of a sphere. {hostile}"
assumptions = ["{hostile}"]
[symbols]
constants = ["I"]
time = ["w_x", "w_y", "w_z"]
[[frame]]
name = "B"
doc = "{hostile}"
angular_velocity = "[w_x, w_y, w_z]"
[[step]]
name = "H"
doc = "{hostile}"
value = "principal(I, I, I) * angvel(B)"
expect = ["I*w_x", "I*w_y", "I*w_z"]
"#
        ),
    )
    .unwrap();
    std::fs::write(
        course.join("energy.toml"),
        r#"title = "Kinetic energy of a sphere"
source = "a lecture"
[symbols]
constants = ["I"]
time = ["w_x", "w_y", "w_z"]
[[step]]
name = "T"
value = "1/2*I*(w_x^2 + w_y^2 + w_z^2)"
expect = "I/2*(w_x^2 + w_y^2 + w_z^2)"
"#,
    )
    .unwrap();
    std::fs::write(
        course.join("notes.toml"),
        format!(
            "title = \"My course {hostile}\"\nauthor = \"{hostile}\"\n\
             [[chapter]]\ntitle = \"First {hostile}\"\nderivations = [\"spin\"]\n\
             [[chapter]]\ntitle = \"Second\"\nderivations = [\"energy\"]\n"
        ),
    )
    .unwrap();
    let out = dir.path().join("site");
    let pages = site(&[course.to_str().unwrap()], &out);
    let names: Vec<&str> = pages
        .iter()
        .map(|p| p.file_name().unwrap().to_str().unwrap())
        .collect();
    assert_eq!(names, ["index.html", "spin.html", "energy.html"]);
    for p in &pages {
        check_page_file(p);
        let page = std::fs::read_to_string(p).unwrap();
        for raw in ["<script", "<img", "\"q\""] {
            assert!(
                !page.contains(raw),
                "{}: {raw} reached the page",
                p.display()
            );
        }
    }
    let spin = std::fs::read_to_string(&pages[1]).unwrap();
    assert!(spin.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
    // Constants, functions of time, frame B's Ω, the step's heading and
    // its result.
    assert_eq!(stated_equations(&spin), 5);
    browser_check(&pages, Some(PAGE_BUDGET));
}

#[test]
fn a_folder_that_is_not_hdots_output_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("index.html"), "<p>my own page</p>").unwrap();
    let out = hdot(&["notes", "--html", mine.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("not a site written by hdot notes"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(mine.join("index.html")).unwrap(),
        "<p>my own page</p>"
    );
    assert_eq!(std::fs::read_dir(&mine).unwrap().count(), 1);
    // A file in place of the folder.
    let file = dir.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let out = hdot(&["notes", "--html", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("not a folder"),
        "{}",
        text(&out.stderr)
    );
}
