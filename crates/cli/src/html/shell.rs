//! The shell every page of a run or a sweep shares (`simulate`,
//! `stability` and `work-precision --html`): the document around a page's
//! sections — the head with the one stylesheet (`page.css`), the header,
//! the footer — and the pieces several pages hold (a report as a table of
//! keys and values, a chart's SVG inline).

use std::fmt::Write;

use super::escape;

/// The stylesheet of every page the shell writes, written in this project.
const PAGE_CSS: &str = include_str!("page.css");

/// What the shell says about a page: its title, the command that wrote
/// it, a sentence on what it is, and a line of detail (the file read).
/// Text is given plain and escaped here.
#[derive(Debug, Clone)]
pub struct Shell<'a> {
    /// The title (`<title>` and `<h1>`): the scene's name.
    pub title: &'a str,
    /// The command that wrote the page (`hdot simulate`).
    pub command: &'a str,
    /// The scene's description.
    pub description: &'a str,
    /// A line of detail under it (the scene file, the kind of run).
    pub detail: String,
}

/// # Construction
impl Shell<'_> {
    /// The page: the shell around `sections` (HTML, written by the
    /// caller), then `scripts` (HTML: `<script>` elements, or empty) at the
    /// end of the body.
    pub fn page(&self, sections: &str, scripts: &str) -> String {
        let title = escape(self.title);
        let mut s = String::with_capacity(sections.len() + scripts.len() + PAGE_CSS.len() + 1024);
        let _ = write!(
            s,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <title>{title} — {command}</title>\n<style>\n{PAGE_CSS}</style>\n</head>\n<body>\n<main>\n\
             <header><h1>{title}</h1><p>{}</p><p class=\"file\">{}</p></header>\n",
            escape(self.description),
            escape(&self.detail),
            command = escape(self.command),
        );
        s.push_str(sections);
        let _ = write!(
            s,
            "<footer>Written by hdot {} (<code>{} --html</code>).</footer>\n</main>\n{scripts}</body>\n</html>\n",
            env!("CARGO_PKG_VERSION"),
            escape(self.command)
        );
        s
    }
}

/// A report of `key: value` lines (what the command prints) as a table
/// of keys and values; a line without a colon is a value alone.
pub fn report_table(text: &str) -> String {
    let mut s = String::from("<table class=\"report\">\n");
    for line in text.lines() {
        let (k, v) = line.split_once(':').unwrap_or(("", line));
        let _ = writeln!(
            s,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(k.trim()),
            escape(v.trim())
        );
    }
    s.push_str("</table>\n");
    s
}

/// A chart's SVG (as `hdot_num::chart` writes it) for a page: without an
/// XML prolog, inside a `<figure>` scaled to the column's width.
pub fn chart(svg: &str, caption: &str) -> String {
    let svg = match svg.trim_start().strip_prefix("<?xml") {
        Some(rest) => rest.split_once("?>").map_or(rest, |(_, r)| r),
        None => svg,
    };
    format!(
        "<figure class=\"chart\">\n{}\n<figcaption>{}</figcaption>\n</figure>\n",
        svg.trim(),
        escape(caption)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shell_escapes_and_holds_its_sections() {
        let page = Shell {
            title: "a <b>",
            command: "hdot stability",
            description: "x & y",
            detail: "f.toml".into(),
        }
        .page("<section>S</section>\n", "");
        assert!(page.starts_with("<!DOCTYPE html>"));
        assert!(page.contains("<title>a &lt;b&gt; — hdot stability</title>"));
        assert!(page.contains("<p>x &amp; y</p>"));
        assert!(page.contains("<section>S</section>\n<footer>"));
        assert!(page.contains("<code>hdot stability --html</code>"));
        assert_eq!(page.matches("<style>").count(), 1);
    }

    #[test]
    fn report_lines_become_rows() {
        assert_eq!(
            report_table("scene:  top (t.toml)\nplain"),
            "<table class=\"report\">\n<tr><th>scene</th><td>top (t.toml)</td></tr>\n\
             <tr><th></th><td>plain</td></tr>\n</table>\n"
        );
    }

    #[test]
    fn a_chart_loses_its_prolog() {
        let c = chart("<?xml version=\"1.0\"?>\n<svg></svg>", "E");
        assert_eq!(
            c,
            "<figure class=\"chart\">\n<svg></svg>\n<figcaption>E</figcaption>\n</figure>\n"
        );
    }
}
