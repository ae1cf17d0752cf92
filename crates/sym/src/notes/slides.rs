//! The slides backend: the notes as LaTeX Beamer slides, a frame per
//! derivation's opening and per step, frames taller than a slide (as
//! estimated from the printed lines) continued on further frames.

use std::fmt::Write;

use super::latex::generated_comment;
use super::layout::{named_list, step_groups};
use super::words::{named_text, sentence, step_title, vanishes_text};
use super::{SLIDE_BUDGET, has_chapters};
use crate::document::{Backend, Chapter, Document, Section, StepBlock, Verdict};
use crate::prose;

/// The slides backend: a section is its frames, a document a Beamer
/// presentation.
pub struct Slides;

impl Backend for Slides {
    fn name(&self) -> &'static str {
        "slides"
    }

    fn section(&self, s: &Section) -> String {
        let mut o = String::new();
        slides_section(&mut o, s);
        o
    }

    fn document(&self, doc: &Document) -> Option<String> {
        Some(slides_document(doc))
    }
}

// -------------------------------------------------------------- slides --

pub(super) const SLIDES_PREAMBLE: &str = r"\documentclass[11pt]{beamer}
\usepackage[T1]{fontenc}
\usepackage[utf8]{inputenc}
\usepackage{lmodern}
\usepackage{amsmath}
\usepackage{amssymb}
\usetheme{default}
\setbeamertemplate{navigation symbols}{}
\setbeamertemplate{footline}[frame number]
\tracinglostchars=2
";

/// Options of every frame: top-aligned, and shrunk only as far as needed
/// when its content is taller than the slide, with a warning that
/// `scripts/build_notes` turns into a failure: a safety net, since a
/// frame that would not fit is split ([`slides_step`], [`slides_intro`]);
/// a frame that fits is set as it is.
pub(super) const FRAME_OPTIONS: &str = "t,shrink=0";

/// The notes as LaTeX Beamer slides: a title frame, a frame of contents,
/// then for each derivation a frame with its summary and what is assumed,
/// and one frame per shown step with its result in textbook form; a
/// frame that would be taller than the slide (estimated from the printed
/// lines) continues on further frames.
pub fn slides_document(doc: &Document) -> String {
    let mut o = String::new();
    generated_comment(&mut o);
    o.push_str(SLIDES_PREAMBLE);
    let _ = writeln!(o, "\\title{{{}}}", prose::latex_line(&doc.title));
    let _ = writeln!(o, "\\author{{{}}}", prose::latex_line(&doc.author));
    let _ = writeln!(o, "\\date{{}}\n");
    let _ = writeln!(
        o,
        "\\begin{{document}}\n\\begin{{frame}}\n\\titlepage\n\\end{{frame}}\n"
    );
    if has_chapters(doc) {
        let _ = writeln!(
            o,
            "\\begin{{frame}}{{Contents}}\n\\tableofcontents\n\\end{{frame}}\n"
        );
    }
    for c in &doc.chapters {
        slides_chapter(&mut o, c);
    }
    o.push_str("\\end{document}\n");
    o
}

pub(super) fn frame_title(title: &str) -> String {
    prose::latex_line(title)
}

pub(super) fn slides_chapter(o: &mut String, c: &Chapter) {
    if !c.title.is_empty() {
        let _ = writeln!(o, "\\section{{{}}}", latex_heading_plain(&c.title));
    }
    for s in &c.sections {
        if c.title.is_empty() {
            let _ = writeln!(o, "\\section{{{}}}", latex_heading_plain(&s.title));
        }
        slides_section(o, s);
    }
}

/// The frames of one derivation: its opening, then its steps.
fn slides_section(o: &mut String, s: &Section) {
    slides_intro(o, s);
    for st in &s.steps {
        slides_step(o, &s.title, st);
    }
}

// The height of a frame, estimated from the expression trees' printed
// lines (an 11pt Beamer frame, 128 mm × 96 mm), in units of one line of
// plain math in an `align*` block (about 18pt).

/// The text height of a frame below a one-line title.
pub(super) const FRAME_HEIGHT: f32 = 11.6;
/// What a step's frame holds besides its equations: the line saying what
/// the step does, the verdict, the space around the `align*` block, and
/// a margin for the estimate.
pub(super) const FRAME_FIXED: f32 = 2.9;
/// Characters of a frame title per line (it wraps beyond).
pub(super) const TITLE_CHARS: usize = 48;
/// Characters of small prose per line.
pub(super) const NOTE_CHARS: usize = 85;
/// The height of a line of small prose.
pub(super) const NOTE_HEIGHT: f32 = 0.55;

/// Characters of a summary or assumption (`\\small`) per line.
pub(super) const SMALL_CHARS: usize = 72;
/// The height of a line of a summary or assumption.
pub(super) const SMALL_HEIGHT: f32 = 0.62;

/// The frame that opens a derivation: its source, summary and
/// assumptions; assumptions that do not fit below the summary continue on
/// a further frame.
pub(super) fn slides_intro(o: &mut String, s: &Section) {
    let title = frame_title(&s.title);
    let room =
        FRAME_HEIGHT - (text_lines(prose::ascii(&s.title).chars().count(), TITLE_CHARS) - 1.0);
    let small = |t: &str, chars: usize| text_lines(t.chars().count(), chars) * SMALL_HEIGHT;
    let mut used = text_lines(s.source.chars().count(), NOTE_CHARS) * NOTE_HEIGHT + 0.4;
    let _ = writeln!(
        o,
        "\\begin{{frame}}[{FRAME_OPTIONS}]{{{title}}}\n{{\\footnotesize {}\\par}}\\medskip",
        prose::latex(&s.source)
    );
    if !s.summary.is_empty() {
        let _ = writeln!(o, "{{\\small {}\\par}}", prose::latex(&s.summary));
        used += small(&s.summary, SMALL_CHARS);
    }
    let heights: Vec<f32> = s
        .assumptions
        .iter()
        .map(|a| small(a, SMALL_CHARS - 6) + 0.15)
        .collect();
    let next_frame = |o: &mut String, what: &str| {
        let _ = writeln!(
            o,
            "\\end{{frame}}\n\n\\begin{{frame}}[{FRAME_OPTIONS}]{{{title}}}\n\
             {{\\footnotesize {what}\\par}}"
        );
    };
    if !s.assumptions.is_empty() {
        // The list stays below the summary when it fits there whole.
        if used + 0.5 + heights.iter().sum::<f32>() > room && !s.summary.is_empty() {
            next_frame(o, "What is assumed");
            used = NOTE_HEIGHT;
        }
        let _ = writeln!(o, "\\begin{{itemize}}\\small");
        used += 0.5;
        let mut on_frame = 0;
        for (a, h) in s.assumptions.iter().zip(&heights) {
            if used + h > room && on_frame > 0 {
                let _ = writeln!(o, "\\end{{itemize}}");
                next_frame(o, "What is assumed (continued)");
                let _ = writeln!(o, "\\begin{{itemize}}\\small");
                used = NOTE_HEIGHT + 0.5;
                on_frame = 0;
            }
            let _ = writeln!(o, "  \\item {}", prose::latex(a));
            used += h;
            on_frame += 1;
        }
        let _ = writeln!(o, "\\end{{itemize}}");
    }
    let _ = writeln!(o, "\\end{{frame}}\n");
}

/// The estimated height of one line of an `align*` block: a line with a
/// fraction is taller (display style), a matrix counts its rows, and a
/// line whose sized brackets hold a superscript (`\left(c^{2} - r^{2}\right)`)
/// a little taller than one of plain math.
pub(super) fn line_height(l: &str) -> f32 {
    let frac = |t: &str| t.contains(r"\frac");
    if let Some(k) = l.find(r"\begin{bmatrix}") {
        let body = &l[k..];
        return 0.3
            + body
                .split(r"\\")
                .map(|row| if frac(row) { 1.25 } else { 0.75 })
                .sum::<f32>();
    }
    if frac(l) {
        1.6
    } else if l.contains(r"\left(") && l.contains("^{") {
        1.1
    } else {
        1.0
    }
}

/// Lines of `chars` characters a text of `n` characters takes.
pub(super) fn text_lines(n: usize, chars: usize) -> f32 {
    n.div_ceil(chars).max(1) as f32
}

/// The groups of lines of a step split into frames: as few frames as the
/// room on one allows, filled evenly, an equation kept on one frame
/// unless it is taller than a frame alone (then its lines continue on the
/// next).
pub(super) fn frames_of(groups: Vec<Vec<String>>, room: f32) -> Vec<Vec<String>> {
    let mut pieces: Vec<(Vec<String>, f32)> = Vec::new();
    for g in groups {
        let mut piece: (Vec<String>, f32) = (Vec::new(), 0.0);
        for l in g {
            let h = line_height(&l);
            if !piece.0.is_empty() && piece.1 + h > room {
                pieces.push(std::mem::take(&mut piece));
            }
            piece.0.push(l);
            piece.1 += h;
        }
        pieces.push(piece);
    }
    let total: f32 = pieces.iter().map(|p| p.1).sum();
    let target = total / (total / room).ceil().max(1.0);
    let mut frames: Vec<(Vec<String>, f32)> = Vec::new();
    for (lines, h) in pieces {
        match frames.last_mut() {
            Some(f) if f.1 + h <= room && f.1 + h / 2.0 <= target => {
                f.0.extend(lines);
                f.1 += h;
            }
            _ => frames.push((lines, h)),
        }
    }
    frames.into_iter().map(|f| f.0).collect()
}

/// The frames of one step: its equations in textbook form, split into
/// continuation frames (the step's line marked *continued*) when they are
/// taller than a frame; the verdict on the last.
pub(super) fn slides_step(o: &mut String, section_title: &str, st: &StepBlock) {
    let title = frame_title(section_title);
    let mut note = if st.doc.trim().is_empty() {
        step_title(0, st)
    } else {
        prose::latex(&sentence(&st.doc))
    };
    let mut note_chars = if st.doc.trim().is_empty() {
        8
    } else {
        st.doc.chars().count()
    };
    if !st.condition.is_empty() {
        note = format!("{note} (for {})", prose::latex(&st.condition));
        note_chars += 6 + prose::unicode(&st.condition).chars().count();
    }
    // The equations written by name: a line saying so on the last frame.
    let named = named_list(st).map(|(names, terms)| {
        let chars = names.len() / 3 + 90;
        (named_text(&names, terms, false, true), chars)
    });
    let room = FRAME_HEIGHT
        - FRAME_FIXED
        - (text_lines(prose::ascii(section_title).chars().count(), TITLE_CHARS) - 1.0)
        - (text_lines(note_chars + 12, NOTE_CHARS) - 1.0) * NOTE_HEIGHT
        - named.as_ref().map_or(0.0, |(_, chars)| {
            text_lines(*chars, NOTE_CHARS) * NOTE_HEIGHT
        });
    let mut groups = if st.vanishes() {
        Vec::new()
    } else {
        step_groups(st, SLIDE_BUDGET)
    };
    // A matrix with entries written by name shows the matrix alone: the
    // definitions of its entries are in the notes.
    if named.is_some()
        && groups
            .first()
            .is_some_and(|g| g[0].contains(r"\begin{bmatrix}"))
    {
        groups.truncate(1);
    }
    let frames = if groups.is_empty() {
        vec![Vec::new()]
    } else {
        frames_of(groups, room)
    };
    let last = frames.len() - 1;
    for (k, lines) in frames.iter().enumerate() {
        let cont = if k > 0 { " (continued)" } else { "" };
        let _ = writeln!(
            o,
            "\\begin{{frame}}[{FRAME_OPTIONS}]{{{title}}}\n{{\\footnotesize {note}{cont}\\par}}"
        );
        if st.vanishes() {
            let _ = writeln!(o, "{}\\par", vanishes_text(false));
        } else if !lines.is_empty() {
            let _ = writeln!(
                o,
                "\\begin{{align*}}\n{}\n\\end{{align*}}",
                lines.join(" \\\\\n")
            );
        }
        if k == last {
            if let Some((text, _)) = &named {
                let _ = writeln!(o, "{{\\footnotesize {text}\\par}}");
            }
            match &st.verdict {
                Verdict::NoExpectation => {}
                Verdict::Holds => {
                    let _ = writeln!(o, "{{\\footnotesize $\\checkmark$ the textbook form\\par}}");
                }
                Verdict::Fails(_) => {
                    let _ = writeln!(
                        o,
                        "{{\\footnotesize\\textbf{{{}}}\\par}}",
                        sentence(Verdict::FAILS)
                    );
                }
            }
        }
        let _ = writeln!(o, "\\end{{frame}}\n");
    }
}

/// A heading for Beamer's outline (which cannot hold every construct): the
/// prose as LaTeX, protected.
pub(super) fn latex_heading_plain(title: &str) -> String {
    let tex = prose::latex_line(title);
    let plain = prose::ascii(&prose::one_line(title));
    if tex == plain {
        tex
    } else {
        format!("\\texorpdfstring{{{tex}}}{{{plain}}}")
    }
}
