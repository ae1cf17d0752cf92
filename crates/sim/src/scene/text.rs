//! Where a key is written in a scene's text: its line, for messages that
//! name the line of a field the table reader does not locate.

/// The 1-based line of the first `key = …` in `text` (at a line's start or
/// inside an inline table), if any.
pub(super) fn line_of(text: &str, key: &str) -> Option<usize> {
    line_of_after(text, key, "")
}

/// [`line_of`] among the lines that also contain `context`.
pub(super) fn line_of_after(text: &str, key: &str, context: &str) -> Option<usize> {
    text.lines()
        .position(|l| {
            l.contains(context)
                && l.match_indices(key).any(|(i, _)| {
                    let before = l[..i].chars().next_back();
                    let after = l[i + key.len()..].trim_start();
                    before.is_none_or(|c| c.is_whitespace() || c == '{' || c == ',')
                        && after.starts_with('=')
                })
        })
        .map(|k| k + 1)
}

/// The 1-based line of a scene field `table.key` (or of the table header
/// `[table]` when the field is a table): the `key = …` line inside that
/// table, else the table's header, else the first line naming the key.
pub(super) fn line_of_field(text: &str, field: &str) -> Option<usize> {
    let (table, key) = match field.split_once('.') {
        Some((t, k)) => (t, k.split('.').next().unwrap_or(k)),
        None => (field, ""),
    };
    let mut current = "";
    let mut header = None;
    for (i, l) in text.lines().enumerate() {
        let t = l.trim_start();
        if t.starts_with('[') {
            let name = t.trim_start_matches('[');
            if let Some(end) = name.find(']') {
                current = name[..end].trim();
                if current == table && header.is_none() {
                    header = Some(i + 1);
                }
                continue;
            }
        }
        if current == table
            && !key.is_empty()
            && t.strip_prefix(key)
                .is_some_and(|rest| rest.trim_start().starts_with('='))
        {
            return Some(i + 1);
        }
    }
    header.or_else(|| line_of(text, if key.is_empty() { table } else { key }))
}

/// `"line N: "` for the line of the scene field `table.key` (see
/// [`line_of_field`]), or nothing when it is not written.
pub(super) fn at_field_line(text: &str, field: &str) -> String {
    line_of_field(text, field).map_or(String::new(), |n| format!("line {n}: "))
}

/// `line N: ` for the line of `key`, or nothing when it is not found.
pub(super) fn at_line(text: &str, key: &str) -> String {
    at_line_after(text, key, "")
}

/// [`at_line`] among the lines that also contain `context`.
pub(super) fn at_line_after(text: &str, key: &str, context: &str) -> String {
    line_of_after(text, key, context)
        .or_else(|| line_of(text, key))
        .map_or(String::new(), |n| format!("line {n}: "))
}
