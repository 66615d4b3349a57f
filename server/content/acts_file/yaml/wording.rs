//! YAML parser errors re-worded for museum staff: what happened at this place and how to fix
//! it, without parser jargon. The parser's own words are kept only as a last resort.

use serde_saphyr::Error;

/// A plain-language message for a parse error.
pub(super) fn describe(err: &Error) -> String {
    match err.without_snippet() {
        Error::AliasError { error, .. } => describe(error),
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
        other => describe_parser_message(&message_of(other)),
    }
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
        describe(&err)
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
    }
}
