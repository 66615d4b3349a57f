//! YAML parser errors re-worded for museum staff: what happened at this place and how to fix
//! it, without parser jargon. The parser's own words are kept only as a last resort.

use std::sync::Arc;

use serde_saphyr::Error;

use super::slips::{ActStart, ListStart};
use crate::model::Pos;

/// A plain-language message for a parse error found on `line` (the text of the line the
/// parser stopped at; `above`, the last line with text before it).
pub(super) fn describe(err: &Error, line: &str, above: &str) -> String {
    match err.without_snippet() {
        Error::AliasError { error, .. } => describe(error, line, above),
        Error::Budget { .. }
        | Error::AliasReplayLimitExceeded { .. }
        | Error::AliasExpansionLimitExceeded { .. }
        | Error::AliasReplayStackDepthExceeded { .. }
        | Error::AliasReplayCounterOverflow { .. } => {
            "This file is too large or too deeply nested \
            for Docent to read safely. Split it into several files, and keep lists and keys \
            only a few levels deep."
                .to_owned()
        }
        Error::UnknownAnchor { .. } => "A value starting with `*` is read by YAML as a reference \
            to an `&name` defined elsewhere, and there is none. If this is text, put it in \
            quotes, for example \"*Welcome*\"."
            .to_owned(),
        Error::MultipleDocuments { .. } => "A line `---` here starts a second document in the \
            same file. Remove it and keep everything in one list (or move the rest into \
            another file)."
            .to_owned(),
        Error::Eof { .. } => "The file ends in the middle of something. Check for a quote or a \
            bracket that is opened but never closed."
            .to_owned(),
        other => {
            let message = message_of(other);
            describe_at_line(&message, line, above)
                .unwrap_or_else(|| describe_parser_message(&message))
        }
    }
}

/// Advice from the line itself, for the mistakes the parser's message alone does not tell
/// apart: a dash without its space, a missing `- ` or colon, a key indented too far, quotes
/// closed too early.
fn describe_at_line(msg: &str, line: &str, above: &str) -> Option<String> {
    let lower = msg.to_lowercase();
    let content = line.trim_start();
    // `    Text: hi`: one key and its value (a text with its own `: ` is the other mistake).
    let colons = content.matches(": ").count() + usize::from(content.ends_with(':'));
    let indented_key = colons == 1
        && content
            .split_once(':')
            .is_some_and(|(key, _)| key.chars().all(|c| c.is_alphanumeric() || c == '_'));
    if lower.contains("trailing content after single-quoted") {
        return Some(
            "The text in single quotes ends at the next `'`, such as the apostrophe in \
             `it's`, and YAML does not expect more after it. Inside single quotes write an \
             apostrophe twice (`'it''s here'`), or put the text in double quotes instead."
                .to_owned(),
        );
    }
    if lower.contains("trailing content after double-quoted") {
        return Some(
            "The text in double quotes ends at the next `\"`, and YAML does not expect more \
             after it. For quotation marks inside the text, put the whole text in single \
             quotes ('say \"hi\" now'), or write \\\" for each inner quote."
                .to_owned(),
        );
    }
    if lower.contains("block sequence entries are not allowed") {
        return Some(
            "A list item (`- `) cannot start on the same line as its key. Move it to the next \
             line, indented under the key, or drop the dash for a single text \
             (`Text: Hello`)."
                .to_owned(),
        );
    }
    if lower.contains("mapping keys are not allowed") || content.starts_with("? ") {
        return Some(
            "A `?` followed by a space has a special meaning in YAML. If this is text, put it \
             in quotes."
                .to_owned(),
        );
    }
    if lower.contains("mapping values are not allowed")
        && let Some((parent, setting)) = settings_on_one_line(content)
    {
        return Some(format!(
            "Two settings are written on one line: `{parent}:` and `{setting}`. Each setting goes \
             on its own line: put `{setting}` on the next line, two spaces further in than \
             `{parent}:`."
        ));
    }
    if lower.contains("mapping values are not allowed") && indented_key && !content.starts_with('-')
    {
        return Some(
            "This key is indented differently from the keys above it. Keys of the same act \
             (Label, Text, Cmds) must start in exactly the same column, two spaces in from \
             the act's `- `."
                .to_owned(),
        );
    }
    if lower.contains("simple key expected") || lower.contains("could not find expected ':'") {
        if content.starts_with('-') && !content[1..].starts_with([' ', '\t']) {
            return Some(format!(
                "A dash needs a space after it to start a list item: `- {}`.",
                content[1..].trim_start()
            ));
        }
        if let Some(message) = missing_dash_below_item(line, above) {
            return Some(message);
        }
        let word = content.trim_end();
        let act_key = ["Label", "Text", "Cmds", "Group", "Key"]
            .iter()
            .any(|key| word.starts_with(key))
            && word
                .chars()
                .all(|c| c.is_alphanumeric() || c == '_' || c == '@');
        if act_key {
            return Some(format!(
                "`{word}` has no colon after it, so YAML cannot read it as a key with the \
                 lines under it as its value. Write `{word}:`."
            ));
        }
        return Some(
            "YAML expected a key with a colon here (such as `Text:`) or a list item starting \
             with `- `. If this line is another alternative, start it with `- ` in the same \
             column as the others; if it is a key, add the colon; if it goes on with the text \
             above, indent it further."
                .to_owned(),
        );
    }
    None
}

/// `corpus: record: none`: a section and its setting on one line, as (`corpus`,
/// `record: none`). Settings of `docent.yaml` are lower-case words; an act's keys are
/// capitalised (`Text: Note: this` is a text needing quotes, not this).
fn settings_on_one_line(content: &str) -> Option<(&str, &str)> {
    let is_setting = |key: &str| {
        !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
    };
    let (parent, rest) = content.split_once(": ")?;
    let rest = rest.trim();
    let (setting, _) = rest.split_once(':')?;
    (is_setting(parent) && is_setting(setting)).then_some((parent, rest))
}

/// `    Welcome!` under `    - Hello!`: an alternative after the first without its `- `.
fn missing_dash_below_item(line: &str, above: &str) -> Option<String> {
    let content = line.trim_start_matches(' ');
    let above_content = above.trim_start_matches(' ');
    let same_column = line.len() - content.len() == above.len() - above_content.len();
    if !same_column || !above_content.starts_with("- ") || content.starts_with('-') {
        return None;
    }
    Some(format!(
        "This line has no `- ` in front, unlike the `- ` line above it, so YAML cannot read it \
         as another text of the list. Put a dash and a space in front of it, in the same column \
         as the `- ` above: `- {}`.",
        content.trim_end()
    ))
}

/// Where and how to tell a slip at the start of an act (see [`ActStart`]).
pub(super) fn act_start(file: &Arc<str>, slip: &ActStart) -> (Pos, String) {
    match slip {
        ActStart::GluedDash {
            line,
            column,
            key,
            fixed,
        } => (
            Pos::new(file.clone(), *line, *column),
            format!(
                "This line starts with a dash glued to `{key}:`, so YAML does not see a new \
                 item here and cannot read the lines below it. Put a space after the `-`: \
                 `{fixed}`."
            ),
        ),
        ActStart::NoDash { line, fixed } => (
            Pos::new(file.clone(), *line, 1),
            format!(
                "This act has no `- ` in front of `Label:`, so YAML cannot tell where it \
                 begins. Every act starts with a dash and a space: `{fixed}`."
            ),
        ),
    }
}

/// Where and how to tell a list of texts that lost its start (see [`ListStart`]), in the
/// words of the same slips found when YAML could read the file (`texts.rs`).
pub(super) fn list_start(file: &Arc<str>, slip: &ListStart) -> (Pos, String) {
    match slip {
        ListStart::NoDash { line, column, text } => (
            Pos::new(file.clone(), *line, *column),
            format!(
                "This line has no `- ` in front, but the lines below it start with `- `, so \
                 YAML reads them as part of this text and cannot read the act. Put a \
                 dash and a space in front of it, in the same column as the `- ` below: \
                 `- {text}`."
            ),
        ),
        ListStart::NoTextKey {
            line,
            column,
            label,
        } => (
            Pos::new(file.clone(), *line, *column),
            format!(
                "This line starts with `- ` right under `Label: {label}`, with no `Text:` line \
                 between, so YAML reads it as part of the label and cannot read the act. \
                 Add a line `Text:` above it, in the same column as `Label`."
            ),
        ),
    }
}

/// The message for a `[` or `{` that is never closed, reported at the bracket.
pub(super) const UNCLOSED_BRACKET: &str = "This bracket is opened but never closed, so YAML reads \
    everything after it as part of the list. Add the closing `]` (or `}`) at the end of the \
    list, on this line, or put a text with brackets in quotes.";

/// Whether the parser's complaint may come from a bracket opened earlier and never closed.
pub(super) fn about_brackets(err: &Error) -> bool {
    let lower = message_of(err.without_snippet()).to_lowercase();
    [
        "placement of ':'",
        "expected ',' or ']'",
        "expected ',' or '}'",
        "bracket",
    ]
    .iter()
    .any(|needle| lower.contains(needle))
        || matches!(err.without_snippet(), Error::Eof { .. })
}

/// Budget and alias-limit breaches repeat on every attempt; skipping an item cannot help.
pub(super) fn recoverable(err: &Error) -> bool {
    !matches!(
        err.without_snippet(),
        Error::Budget { .. }
            | Error::AliasReplayLimitExceeded { .. }
            | Error::AliasExpansionLimitExceeded { .. }
            | Error::AliasReplayStackDepthExceeded { .. }
            | Error::AliasReplayCounterOverflow { .. }
            | Error::InvalidUtf8Input
    )
}

/// The parser's message without the " at line L, column C" it appends.
fn message_of(err: &Error) -> String {
    match err {
        Error::ExternalMessage { msg, .. } | Error::Message { msg, .. } => msg.clone(),
        other => {
            let text = other.to_string();
            match text.rfind(" at line ") {
                Some(cut) => text[..cut].to_owned(),
                None => text,
            }
        }
    }
}

/// Known parser messages, from the most to the least specific.
fn describe_parser_message(msg: &str) -> String {
    const RULES: &[(&[&str], &str)] = &[
        (
            &["tabs ", "a tab"],
            "A tab character is used here where YAML needs spaces. Replace the tab with spaces.",
        ),
        (
            &["placement of ':'"],
            "YAML does not allow a colon at this place. This usually comes from a `[` or `{` \
             opened earlier and never closed, or from a text containing `: ` that needs quotes \
             around it.",
        ),
        (
            &["mapping values are not allowed"],
            "YAML read a colon followed by a space (`: `) here as the start of a new key, which \
             is not allowed at this place. If this is text, put the whole text in quotes, for \
             example \"Note: this is splendid\".",
        ),
        (
            &[
                "did not find expected key",
                "expected '-' indicator",
                "expected <document start>",
            ],
            "This line is not indented like the lines around it. Keys of the same act (Label, \
             Text, Cmds) must start in the same column, and the items of a list too. Use spaces \
             only.",
        ),
        (
            &[
                "unclosed quote",
                "quoted scalar, found unexpected",
                "end of stream while scanning a quoted",
            ],
            "A quote opened here is never closed. Add the matching closing quote (\" or '), or \
             if the text itself contains a quote, see the YAML quoting rules in the docs.",
        ),
        (
            &["escape", "hexadecimal", "surrogate"],
            "Inside double quotes a backslash starts a special sequence such as \\n, and this one \
             is not valid. Write \\\\ for a backslash, or use single quotes instead.",
        ),
        (
            &["recursion limit", "nesting depth", "too deep"],
            "Brackets or indented lists here are nested inside one another far deeper than acts \
             ever need (YAML reads at most 64 levels). Was something pasted here? Acts need only \
             a few levels: check for stray `[` or `{`, or put the text in quotes.",
        ),
        (
            &["expected ',' or ']'", "bracket '['"],
            "A list in square brackets [ ] is not closed properly. Check for a missing `]` or a \
             missing comma, or put text containing brackets in quotes.",
        ),
        (
            &["expected ',' or '}'", "bracket '{'"],
            "A set of keys in curly braces { } is not closed properly. Check for a missing `}` \
             or a missing comma, or put text containing braces in quotes.",
        ),
        (
            &["anchor or alias"],
            "A value starting with `&` or `*` has a special meaning in YAML. If this is text, put \
             it in quotes.",
        ),
        (
            &[
                "cannot start any token",
                "expected node content",
                "unexpected character",
            ],
            "This value starts with a character that YAML reserves (such as @, `, %, | or >). If \
             this is text, put it in quotes.",
        ),
        (
            &["block scalar"],
            "A text block started with | or > is not laid out correctly: put the text on the \
             following lines, indented more than the key above.",
        ),
        (
            &["tag"],
            "A value starting with `!` is read by YAML as a type tag. If this is text, put it in \
             quotes.",
        ),
    ];
    let lower = msg.to_lowercase();
    match RULES
        .iter()
        .find(|(needles, _)| needles.iter().any(|n| lower.contains(n)))
    {
        Some((_, advice)) => (*advice).to_owned(),
        None => format!(
            "YAML cannot read the file from here ({msg}). Check the indentation and the quotes \
             around this place."
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(yaml: &str) -> String {
        let err =
            serde_saphyr::from_str::<serde::de::IgnoredAny>(yaml).expect_err("should not parse");
        let mut lines = yaml.lines().rev();
        let line = lines.next().unwrap_or_default();
        describe(&err, line, lines.next().unwrap_or_default())
    }

    #[test]
    fn common_mistakes_get_advice_instead_of_parser_words() {
        assert!(message("Text: Note: this\n").contains("put the whole text in quotes"));
        assert!(message("Text: \"open\n").contains("never closed"));
        assert!(message("Text: [a, b\n").contains("square brackets"));
        assert!(message("Text: [a\n  - b\nKey: c\n").contains("never closed"));
        assert!(message("Text: *bold*\n").contains("`*`"));
        assert!(message("a: 1\n---\nb: 2\n").contains("second document"));
        assert!(message("Text: @home\n").contains("put it in quotes"));
        assert!(message("a:\n  - b\n c: d\n").contains("indented"));
        assert!(message("a: b\n    c: d\n").contains("indented differently"));
        assert!(message("corpus: record: none\n").contains("put `record: none` on the next line"));
        assert!(message("Text: Note: this\n").contains("put the whole text in quotes"));
        assert!(message("a: 'it's'\n").contains("apostrophe twice"));
        assert!(message("a: \"say \"hi\" now\"\n").contains("single quotes"));
        assert!(message("a:\n  - b\n  -c\n").contains("`- c`"));
        assert!(message("a: - b\n").contains("same line as its key"));
        assert!(message("a:\n  - b\n  c\n").contains("unlike the `- ` line above it"));
        assert!(message("a:\n  - b\n  c\n").contains("`- c`"));
    }
}
