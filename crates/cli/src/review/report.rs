//! A review of changed derivation files, rendered for a terminal (text), a
//! pull-request comment (Markdown with `$…$` math that GitHub renders) or a
//! program (JSON).

use std::fmt::Write;

use serde_json::{Value as Json, json};

use super::compare::{Change, Component, ComponentDiff, StepDiff};

/// One derivation file compared.
#[derive(Clone, Debug)]
pub struct FileDiff {
    /// How the old version is named (a path, or `REV:path`); `None` for a
    /// new file.
    pub old: Option<String>,
    /// How the new version is named; `None` for a removed file.
    pub new: Option<String>,
    /// What happened to the file as a whole.
    pub change: Change,
    /// Its steps compared (empty for an unchanged file).
    pub steps: Vec<StepDiff>,
}

impl FileDiff {
    /// The name to head the file's part of the report.
    pub fn title(&self) -> &str {
        self.new.as_deref().or(self.old.as_deref()).unwrap_or("")
    }
}

/// The output formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ReportFormat {
    /// Text for a terminal.
    Text,
    /// Markdown with `$…$` math (a pull-request comment).
    Markdown,
    /// Machine-readable JSON.
    Json,
}

/// Renders `files` in `format`.
pub fn render(files: &[FileDiff], format: ReportFormat) -> String {
    match format {
        ReportFormat::Text => text(files),
        ReportFormat::Markdown => markdown(files),
        ReportFormat::Json => {
            serde_json::to_string_pretty(&json_report(files)).expect("JSON of plain data") + "\n"
        }
    }
}

/// Counts of files by change, for the summary line.
fn summary(files: &[FileDiff]) -> String {
    if files.is_empty() {
        return "no derivation files to compare".to_owned();
    }
    let count = |f: &dyn Fn(Change) -> bool| files.iter().filter(|x| f(x.change)).count();
    let math = count(&|c| c.is_mathematical());
    let pres = count(&|c| c == Change::Presentation);
    let same = count(&|c| c == Change::Unchanged);
    let verdict = if math > 0 {
        "the mathematics differs"
    } else if pres > 0 {
        "same mathematics, new presentation"
    } else {
        "nothing changed"
    };
    format!(
        "{verdict}: {} derivation file{} compared, {math} with different mathematics, {pres} with a new presentation only, {same} unchanged",
        files.len(),
        if files.len() == 1 { "" } else { "s" }
    )
}

fn label_suffix(label: &str) -> String {
    if label.is_empty() {
        String::new()
    } else {
        format!(" {label}")
    }
}

fn text(files: &[FileDiff]) -> String {
    let mut o = String::new();
    for f in files.iter().filter(|f| f.change != Change::Unchanged) {
        let _ = writeln!(o, "{}: {}", f.title(), f.change.phrase());
        if let (Some(old), Some(new)) = (&f.old, &f.new)
            && old != new
        {
            let _ = writeln!(o, "  (old: {old})");
        }
        let mut unchanged = Vec::new();
        for s in &f.steps {
            if s.change == Change::Unchanged {
                unchanged.push(s.name.as_str());
                continue;
            }
            let _ = writeln!(o, "  step {}: {}", s.name, s.change.phrase());
            if let Some((a, b)) = &s.formula {
                let _ = writeln!(o, "    formula  old: {}", a.trim());
                let _ = writeln!(o, "             new: {}", b.trim());
            }
            if let Some((a, b)) = s.shown {
                let _ = writeln!(o, "    shown    old: {a}, new: {b}");
            }
            for c in s
                .components
                .iter()
                .filter(|c| c.change != Change::Unchanged)
            {
                text_component(&mut o, s, c);
            }
        }
        if !unchanged.is_empty() {
            let _ = writeln!(o, "  unchanged: {}", unchanged.join(", "));
        }
        let _ = writeln!(o);
    }
    let _ = writeln!(o, "{}", summary(files));
    o
}

fn text_component(o: &mut String, s: &StepDiff, c: &ComponentDiff) {
    // A whole added or removed step has its reason on the step line.
    if c.change != s.change || !matches!(c.change, Change::Added | Change::Removed) {
        let _ = writeln!(
            o,
            "    component{}: {}",
            label_suffix(&c.label),
            c.change.phrase()
        );
    }
    if let Some(a) = &c.old {
        let _ = writeln!(o, "      old: {}", a.text);
    }
    if let Some(b) = &c.new {
        let _ = writeln!(o, "      new: {}", b.text);
    }
    if c.change == Change::Mathematics {
        match &c.difference {
            Some(d) => {
                let _ = writeln!(o, "      new − old = {}", d.text);
            }
            None => {
                let _ = writeln!(
                    o,
                    "      new − old: not computed (the old form names a symbol the new file does not declare)"
                );
            }
        }
    }
}

/// Inline math GitHub renders: `$…$` around LaTeX (no space inside the
/// dollars); a side without LaTeX is shown as code.
fn math(latex: Option<&str>, text: &str) -> String {
    match latex {
        Some(l) => format!("${}$", l.trim()),
        None => format!("`{text}`"),
    }
}

fn md_eq(c: &Component) -> String {
    math(c.latex.as_deref(), &c.text)
}

fn markdown(files: &[FileDiff]) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "## hdot review\n\n{}\n", summary(files));
    for f in files.iter().filter(|f| f.change != Change::Unchanged) {
        let _ = writeln!(o, "### `{}`: {}\n", f.title(), f.change.phrase());
        let mut unchanged = Vec::new();
        for s in &f.steps {
            if s.change == Change::Unchanged {
                unchanged.push(format!("`{}`", s.name));
                continue;
            }
            let _ = writeln!(o, "- **step `{}`**: {}", s.name, s.change.phrase());
            if let Some((a, b)) = &s.formula {
                let _ = writeln!(o, "  - formula, old: `{}`", a.trim());
                let _ = writeln!(o, "  - formula, new: `{}`", b.trim());
            }
            if let Some((a, b)) = s.shown {
                let _ = writeln!(o, "  - shown: {a} → {b}");
            }
            for c in s
                .components
                .iter()
                .filter(|c| c.change != Change::Unchanged)
            {
                if c.change != s.change || !matches!(c.change, Change::Added | Change::Removed) {
                    let _ = writeln!(
                        o,
                        "  - component{}: {}",
                        if c.label.is_empty() {
                            String::new()
                        } else {
                            format!(" `{}`", c.label)
                        },
                        c.change.phrase()
                    );
                }
                if let Some(a) = &c.old {
                    let _ = writeln!(o, "    - old: {}", md_eq(a));
                }
                if let Some(b) = &c.new {
                    let _ = writeln!(o, "    - new: {}", md_eq(b));
                }
                if let Some(d) = &c.difference {
                    let _ = writeln!(o, "    - new − old: {}", math(Some(&d.latex), &d.text));
                }
            }
        }
        if !unchanged.is_empty() {
            let _ = writeln!(o, "- unchanged: {}", unchanged.join(", "));
        }
        let _ = writeln!(o);
    }
    o
}

fn json_component(c: &Component) -> Json {
    json!({
        "text": c.text,
        "latex": c.latex,
        "canonical": c.canonical_text,
    })
}

fn json_report(files: &[FileDiff]) -> Json {
    let files: Vec<Json> = files
        .iter()
        .map(|f| {
            let steps: Vec<Json> = f
                .steps
                .iter()
                .map(|s| {
                    let comps: Vec<Json> = s
                        .components
                        .iter()
                        .map(|c| {
                            json!({
                                "component": c.label,
                                "change": c.change.key(),
                                "old": c.old.as_ref().map(json_component),
                                "new": c.new.as_ref().map(json_component),
                                "difference": c.difference.as_ref().map(|d| json!({
                                    "text": d.text,
                                    "latex": d.latex,
                                    "canonical": d.canonical,
                                })),
                            })
                        })
                        .collect();
                    json!({
                        "name": s.name,
                        "change": s.change.key(),
                        "formula": s.formula.as_ref().map(|(a, b)| json!({"old": a, "new": b})),
                        "shown": s.shown.map(|(a, b)| json!({"old": a, "new": b})),
                        "components": comps,
                    })
                })
                .collect();
            json!({
                "old": f.old,
                "new": f.new,
                "change": f.change.key(),
                "steps": steps,
            })
        })
        .collect();
    let mathematical = files
        .iter()
        .any(|f| f["change"] != "unchanged" && f["change"] != "presentation");
    json!({
        "files": files,
        "mathematics_differs": mathematical,
        "summary": summary_of(&files),
    })
}

fn summary_of(files: &[Json]) -> Json {
    let count = |k: &str| files.iter().filter(|f| f["change"] == k).count();
    json!({
        "unchanged": count("unchanged"),
        "presentation": count("presentation"),
        "mathematics": count("mathematics"),
        "added": count("added"),
        "removed": count("removed"),
    })
}
