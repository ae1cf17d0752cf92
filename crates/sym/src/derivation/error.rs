//! Errors of derivation files, located at file:line:column with a snippet.

use std::fmt;

use crate::escape::terminal;

/// An error in a derivation file, with its location and a caret snippet.
///
/// `Display` prints it the way compilers do:
///
/// ```text
/// error: unknown symbol `I_w`; declare it under [symbols]
///   --> derivations/euler.toml:14:12
///    |
/// 14 | value = "I_w*omega_x"
///    |          ^^^
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct Diagnostic {
    /// The file, as given.
    pub path: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// What went wrong.
    pub message: String,
    /// The text of the offending line.
    pub source_line: String,
    /// Width of the caret underline, in characters (at least 1).
    pub width: usize,
}

impl Diagnostic {
    /// Builds a diagnostic for the byte range `start..end` of `text`.
    pub fn at(
        path: &str,
        text: &str,
        start: usize,
        end: usize,
        message: impl Into<String>,
    ) -> Diagnostic {
        // Offsets inside a string with escapes (`\"`, `\u00e9`) are offsets
        // into its unescaped value and can land inside a multibyte
        // character of the file: step back to a character boundary.
        let floor = |mut i: usize| {
            i = i.min(text.len());
            while !text.is_char_boundary(i) {
                i -= 1;
            }
            i
        };
        let start = floor(start);
        let end = floor(end.max(start));
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let line = text[..start].matches('\n').count() + 1;
        let column = text[line_start..start].chars().count() + 1;
        let width = text[start..end.min(line_end)].chars().count().max(1);
        Diagnostic {
            path: path.to_owned(),
            line,
            column,
            message: message.into(),
            source_line: text[line_start..line_end].trim_end_matches('\r').to_owned(),
            width,
        }
    }

    /// A file that could not be read or decoded ([`crate::textfile`]): at
    /// its first byte that is not UTF-8, or about the file as a whole.
    pub fn read(path: &str, e: crate::textfile::ReadError) -> Diagnostic {
        match &e.at {
            Some((offset, text)) => Diagnostic::at(path, text, *offset, offset + 1, e.message),
            None => Diagnostic::file(path, e.message),
        }
    }

    /// A diagnostic about a file as a whole (no line to show).
    pub fn file(path: &str, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            path: path.to_owned(),
            line: 0,
            column: 0,
            message: message.into(),
            source_line: String::new(),
            width: 0,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // What the file holds is quoted, never obeyed by the terminal.
        let path = terminal(&self.path);
        writeln!(f, "error: {}", terminal(&self.message))?;
        if self.line == 0 {
            return write!(f, "  --> {path}");
        }
        let n = self.line.to_string();
        let pad = " ".repeat(n.len());
        writeln!(f, "{pad}--> {path}:{}:{}", self.line, self.column)?;
        writeln!(f, "{pad} |")?;
        // One character for one, so that the caret stays under its column.
        let line: String = self
            .source_line
            .chars()
            .map(|c| {
                if c.is_control() && c != '\t' {
                    '\u{FFFD}'
                } else {
                    c
                }
            })
            .collect();
        writeln!(f, "{n} | {line}")?;
        let lead: String = self
            .source_line
            .chars()
            .take(self.column - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        write!(f, "{pad} | {lead}{}", "^".repeat(self.width))
    }
}
