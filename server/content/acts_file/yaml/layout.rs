//! The layout of a YAML file as text, before and beside the parser: where the top-level list
//! items are, where tabs indent lines, and the line and column of a byte. (Slips the parser
//! notices lines later are found in `slips`.)

use std::sync::Arc;

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Pos;

/// One top-level list item: its 1-based lines (end exclusive) and bytes.
pub(super) struct Item {
    /// First line and the line after the last (1-based).
    pub lines: (u32, u32),
    /// Byte range in the source.
    pub bytes: std::ops::Range<usize>,
}

/// The top-level list items (each starting with `-` in column 1), or `None` when the file
/// is not laid out that way (something other than comments, `---` or directives before the
/// first item).
pub(super) fn top_level_items(source: &str) -> Option<Vec<Item>> {
    let mut items: Vec<Item> = Vec::new();
    let mut offset = 0;
    for (index, line) in source.split_inclusive('\n').enumerate() {
        let number = to_u32(index + 1);
        // `-Label: X` (the dash glued to the key) is a broken act start: still its own item,
        // so only that act is lost.
        let starts_item = is_act_start(line) || super::slips::glued_dash_key(line).is_some();
        if starts_item {
            if let Some(last) = items.last_mut() {
                last.lines.1 = number;
                last.bytes.end = offset;
            }
            items.push(Item {
                lines: (number, number + 1),
                bytes: offset..offset + line.len(),
            });
        } else if let Some(last) = items.last_mut() {
            last.lines.1 = number + 1;
            last.bytes.end = offset + line.len();
        } else {
            let trimmed = line.trim();
            let preamble = trimmed.is_empty()
                || trimmed.starts_with('#')
                || trimmed == "---"
                || trimmed.starts_with('%');
            if !preamble {
                return None;
            }
        }
        offset += line.len();
    }
    (!items.is_empty()).then_some(items)
}

/// Whether `line` starts a top-level list item: `-` in column 1, then a space or nothing.
pub(super) fn is_act_start(line: &str) -> bool {
    line.starts_with('-')
        && !line.starts_with("--")
        && line[1..].chars().next().is_none_or(char::is_whitespace)
}

/// The position of byte `offset` (1-based line, column in characters).
pub(super) fn position_of_byte(file: &Arc<str>, bytes: &[u8], offset: usize) -> Pos {
    let before = &bytes[..offset.min(bytes.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    Pos::new(file.clone(), to_u32(line), to_u32(column))
}

pub(super) fn to_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// (line, column) of the first tab in each line's leading whitespace.
pub(super) fn tab_positions(source: &str) -> Vec<(u32, u32)> {
    source
        .lines()
        .enumerate()
        .filter_map(|(i, line)| {
            // A blank line with a tab in it is harmless: only text lines are indented.
            let indent = line.find(|c: char| c != ' ' && c != '\t')?;
            let column = line[..indent].find('\t')?;
            Some((to_u32(i + 1), to_u32(column + 1)))
        })
        .collect()
}

/// The last `[` or `{` opened before `line`:`column` and not closed by then (outside quotes
/// and comments), as (line, column): where an "unclosed bracket" error really starts, since
/// the parser only notices it lines later.
pub(super) fn unclosed_bracket_before(source: &str, line: u32, column: u32) -> Option<(u32, u32)> {
    let mut open: Vec<(u32, u32)> = Vec::new();
    for (index, text) in source.lines().enumerate().take(line as usize) {
        let number = to_u32(index + 1);
        let mut quote: Option<char> = None;
        let mut previous = ' ';
        for (i, c) in text.chars().enumerate() {
            let col = to_u32(i + 1);
            if number == line && col >= column {
                break;
            }
            match (quote, c) {
                (Some('"'), '"') if previous != '\\' => quote = None,
                (Some('\''), '\'') => quote = None,
                (Some(_), _) => {}
                (None, '"' | '\'') if !open.is_empty() || previous.is_whitespace() => {
                    quote = Some(c)
                }
                (None, '#') if previous.is_whitespace() => break,
                (None, '[' | '{') => open.push((number, col)),
                (None, ']' | '}') => {
                    open.pop();
                }
                _ => {}
            }
            previous = c;
        }
    }
    open.last().copied()
}

/// Spaces that are not YAML's space: the no-break space a word processor or web page puts
/// in, and other typographic spaces.
fn is_odd_space(c: char) -> bool {
    matches!(
        c,
        '\u{a0}' | '\u{2000}'..='\u{200b}' | '\u{202f}' | '\u{205f}' | '\u{3000}'
    )
}

/// (line, column) of each typographic space where YAML needs a plain one: in a line's
/// indentation, after the `-` of a list item, or after the `:` of a key. Elsewhere, inside a
/// text, such a space is harmless.
pub(super) fn odd_space_positions(source: &str) -> Vec<(u32, u32)> {
    let mut found = Vec::new();
    for (i, line) in source.lines().enumerate() {
        if !line.contains(is_odd_space) {
            continue;
        }
        // Indentation and `- ` markers, then perhaps a key word and its `:`; then text.
        let mut in_indent = true;
        let mut in_key = false;
        let mut after_marker = false;
        for (column, c) in line.chars().enumerate() {
            if is_odd_space(c) && (in_indent || after_marker) {
                found.push((to_u32(i + 1), to_u32(column + 1)));
                break;
            }
            after_marker = false;
            match c {
                ' ' | '\t' if in_indent => {}
                '-' if in_indent => after_marker = true,
                ':' if in_key => {
                    after_marker = true;
                    in_key = false;
                }
                c if (in_indent || in_key) && (c.is_alphanumeric() || c == '_') => {
                    in_indent = false;
                    in_key = true;
                }
                _ => {
                    in_indent = false;
                    in_key = false;
                }
            }
        }
    }
    found
}

/// The error for each typographic space at a place where YAML needs a plain space.
pub(super) fn odd_space_diagnostics(file: &Arc<str>, places: &[(u32, u32)]) -> Vec<Diagnostic> {
    let message = "There is a no-break space here (typed by a word processor, or copied from a \
                   web page or e-mail). It looks like a space, but YAML needs a plain space at \
                   this place, so the line is not read as you see it. Delete it and type a \
                   normal space.";
    places
        .iter()
        .map(|&(line, column)| {
            let pos = Pos::new(file.clone(), line, column);
            Diagnostic::error(DiagnosticCode::NonBreakingSpace, &pos, message)
        })
        .collect()
}

/// Tabs are an error when the file did not parse (they are the likely cause); when YAML
/// still read the file they sit inside text or were ignored, so a warning suffices.
pub(super) fn tab_diagnostics(
    file: &Arc<str>,
    tabs: &[(u32, u32)],
    failed: bool,
) -> Vec<Diagnostic> {
    let message = "This line is indented with a tab. YAML allows only spaces for indentation: \
                   replace the tab with spaces (for example two spaces per level).";
    tabs.iter()
        .map(|&(line, column)| {
            let pos = Pos::new(file.clone(), line, column);
            if failed {
                Diagnostic::error(DiagnosticCode::YamlTab, &pos, message)
            } else {
                Diagnostic::warning(DiagnosticCode::YamlTab, &pos, message)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_top_level_items_after_a_preamble() {
        let items = top_level_items("# acts\n---\n- a\n  b\n\n- c\n").expect("items");
        let ranges: Vec<((u32, u32), std::ops::Range<usize>)> =
            items.into_iter().map(|i| (i.lines, i.bytes)).collect();
        assert_eq!(ranges, [((3, 6), 11..20), ((6, 7), 20..24)]);
        assert!(top_level_items("key: v\n- a\n").is_none());
        assert!(top_level_items("# only a comment\n").is_none());
    }

    #[test]
    fn finds_tabs_only_in_leading_whitespace() {
        assert_eq!(
            tab_positions("a:\n\tb: 1\n  \t- c\nd: \te\n"),
            [(2, 1), (3, 3)]
        );
    }

    #[test]
    fn finds_typographic_spaces_only_where_yaml_needs_a_plain_one() {
        let source = "- Label: A\n  Text:\u{a0}hi\n  Text:\n    -\u{a0}Hello\n\u{a0} - x\n  \
                      - ten\u{a0}am is fine\n";
        assert_eq!(odd_space_positions(source), [(2, 8), (4, 6), (5, 1)]);
    }

    #[test]
    fn finds_the_bracket_left_open() {
        let source = "home: x\ncontexts: [A, B\nkiosk:\n  idle: 2s\n";
        assert_eq!(unclosed_bracket_before(source, 4, 7), Some((2, 11)));
        assert_eq!(
            unclosed_bracket_before("a: [x, '[', \"]\"] # [\nb: c\n", 2, 2),
            None
        );
    }

    #[test]
    fn locates_a_byte_by_line_and_character() {
        let file: Arc<str> = Arc::from("acts.yaml");
        let pos = position_of_byte(&file, "ab\ncafé x".as_bytes(), 9);
        assert_eq!((pos.line, pos.column), (2, 6));
    }
}
