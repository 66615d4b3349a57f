//! Slips at the start of an act or of a list of texts that YAML notices only lines later,
//! found from the line the parser blames: a dash glued to `Label:` or missing before it, a
//! first text without its `- `, texts under `Label:` without their `Text:` line. Reported
//! there, where the author fixes them (`recovery`), instead of where the parser stopped.

use super::layout::{is_act_start, to_u32};

/// `Label` for `-Label: X` or `-Label:`: a key with the list item's dash glued to it.
pub(super) fn glued_dash_key(content: &str) -> Option<&str> {
    let rest = content.strip_prefix('-')?;
    if !rest.starts_with(char::is_alphabetic) {
        return None;
    }
    let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_'))?;
    let after = &rest[end..];
    let is_key =
        after.starts_with(':') && after[1..].chars().next().is_none_or(char::is_whitespace);
    is_key.then(|| &rest[..end])
}

/// A slip at the start of an act that YAML notices only lines later.
#[derive(Debug, PartialEq, Eq)]
pub(super) enum ActStart {
    /// `-Label: X`: the dash glued to the key (1-based line and column of the dash).
    GluedDash {
        line: u32,
        column: u32,
        key: String,
        fixed: String,
    },
    /// `Label: X` in column 1 with no dash in front.
    NoDash { line: u32, fixed: String },
}

/// The slip that starts the act holding `line`: looking up from `line` to the last proper
/// act start (`- ` in column 1), a key with the dash glued to it, or `Label:` in column 1
/// without its dash. The parser's own place (the line after, or a vague "indentation")
/// points away from it.
pub(super) fn act_start_slip(source: &str, line: u32, first_line: u32) -> Option<ActStart> {
    let lines: Vec<&str> = source.lines().take(line as usize).collect();
    for (index, text) in lines.iter().enumerate().rev() {
        if is_act_start(text) {
            return None;
        }
        let number = to_u32(index + 1) + first_line;
        let content = text.trim_start_matches(' ');
        if let Some(key) = glued_dash_key(content) {
            return Some(ActStart::GluedDash {
                line: number,
                column: to_u32(text.len() - content.len() + 1),
                key: key.to_owned(),
                fixed: format!("- {}", content[1..].trim_end()),
            });
        }
        if text.starts_with("Label:") {
            return Some(ActStart::NoDash {
                line: number,
                fixed: format!("- {}", text.trim_end()),
            });
        }
    }
    None
}

/// What is missing above a list of `- ` texts that YAML stumbled over.
#[derive(Debug, PartialEq, Eq)]
pub(super) enum ListStart {
    /// The first text has no `- ` (1-based line and column of the text).
    NoDash {
        line: u32,
        column: u32,
        text: String,
    },
    /// The `- ` lines sit right under `Label: X`, the `Text:` line forgotten (line and
    /// column of the first `- `).
    NoTextKey {
        line: u32,
        column: u32,
        label: String,
    },
}

/// For a parse error on `line`, a `- ` text: whether the list it belongs to lost its start.
/// A first text without its `- ` (or texts under `Label:` without `Text:`) makes YAML read the
/// following `- ` lines as part of one text, until one of them (a quoted one, one with `: `)
/// cannot be; the parser then blames that line.
pub(super) fn list_start_slip(source: &str, line: u32, first_line: u32) -> Option<ListStart> {
    let lines: Vec<&str> = source.lines().take(line as usize).collect();
    let indent = |text: &str| text.len() - text.trim_start_matches(' ').len();
    let (last, above) = lines.split_last()?;
    let column = indent(last);
    if !last[column..].starts_with("- ") {
        return None;
    }
    let mut first_item = lines.len();
    let mut previous = None;
    for (index, text) in above.iter().enumerate().rev() {
        if text.trim().is_empty() {
            continue;
        }
        if indent(text) == column && text[column..].starts_with("- ") {
            first_item = index + 1;
            continue;
        }
        previous = Some((index, *text));
        break;
    }
    let (index, text) = previous?;
    let content = text.trim_start_matches(' ').trim_end();
    if indent(text) == column && !is_key_line(content) && !content.starts_with('#') {
        // A text without its dash, opening the list right under a key.
        let key_above = above[..index]
            .iter()
            .rev()
            .find(|l| !l.trim().is_empty())
            .is_some_and(|l| indent(l) < column && l.trim_end().ends_with(':'));
        return key_above.then(|| ListStart::NoDash {
            line: to_u32(index + 1) + first_line,
            column: to_u32(column + 1),
            text: content.to_owned(),
        });
    }
    let label = content
        .trim_start_matches("- ")
        .strip_prefix("Label:")?
        .trim();
    (indent(text) < column && !label.is_empty()).then(|| ListStart::NoTextKey {
        line: to_u32(first_item) + first_line,
        column: to_u32(column + 1),
        label: label.to_owned(),
    })
}

/// `Text:` or `Label: X`: a word and a colon starting the line.
fn is_key_line(content: &str) -> bool {
    content.split_once(':').is_some_and(|(key, rest)| {
        !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_alphanumeric() || c == '_' || c == '@')
            && (rest.is_empty() || rest.starts_with(' '))
    })
}

#[cfg(test)]
mod tests {
    use super::super::layout::top_level_items;
    use super::*;

    #[test]
    fn a_dash_glued_to_a_key_starts_an_item_of_its_own_and_is_the_slip() {
        let source = "-Label: A\n  Text:\n    - hi\n\n- Label: B\n  Text: b\n";
        let items = top_level_items(source).expect("items");
        let lines: Vec<(u32, u32)> = items.iter().map(|i| i.lines).collect();
        assert_eq!(lines, [(1, 5), (5, 7)]);
        assert_eq!(
            act_start_slip(source, 2, 0),
            Some(ActStart::GluedDash {
                line: 1,
                column: 1,
                key: "Label".to_owned(),
                fixed: "- Label: A".to_owned(),
            })
        );
        assert_eq!(act_start_slip(source, 6, 0), None);
        assert_eq!(
            act_start_slip("- Label: A\n  Text: a\nLabel: B\n  Text: b\n", 4, 0),
            Some(ActStart::NoDash {
                line: 3,
                fixed: "- Label: B".to_owned(),
            })
        );
        // A text starting with a dash is not a key: `-20 degrees`, `-Hello`.
        assert_eq!(glued_dash_key("-20: x"), None);
        assert_eq!(glued_dash_key("-Hello there"), None);
        assert_eq!(glued_dash_key("-Text:"), Some("Text"));
    }

    #[test]
    fn a_list_of_texts_that_lost_its_start_is_found_from_the_line_yaml_blames() {
        let no_dash = "- Label: A\n  Text:\n    Hi there\n    - Hello\n    - \"Yes: no\"\n";
        assert_eq!(
            list_start_slip(no_dash, 5, 0),
            Some(ListStart::NoDash {
                line: 3,
                column: 5,
                text: "Hi there".to_owned(),
            })
        );
        let no_text = "- Label: A\n    - Hello\n    - \"Yes: no\"\n";
        assert_eq!(
            list_start_slip(no_text, 3, 0),
            Some(ListStart::NoTextKey {
                line: 2,
                column: 5,
                label: "A".to_owned(),
            })
        );
        let fine_start = "- Label: A\n  Text:\n    - Hi\n    - Hello: there\n";
        assert_eq!(list_start_slip(fine_start, 4, 0), None);
    }
}
