//! The values of an act's keys: the label, text alternatives and command strings. YAML's
//! surprises are caught here: a text with `: ` that became a mapping, an unquoted `yes` that
//! became a boolean, an empty list item that became null.

use crate::commands::WrittenCommand;
use crate::diagnostic::Diagnostic;
use crate::model::Located;

use crate::DiagnosticCode;
use crate::speech::{SpokenText, check_spoken};

use super::Reading;
use super::texts::{Source, check_written, label_swallowed_texts};
use super::yaml::{Kind, Node};

/// The label, or `None` after reporting why it is unusable.
pub(super) fn read_label(
    value: &Node,
    source: &Source<'_>,
    out: &mut Vec<Diagnostic>,
) -> Option<Located<String>> {
    let label = match &value.kind {
        Kind::Str { value: text, .. } if !text.trim().is_empty() => {
            label_swallowed_texts(source, value, out).unwrap_or_else(|| text.clone())
        }
        Kind::Guessed(text) => {
            out.push(unquoted_warning(value, text));
            text.clone()
        }
        Kind::Str { .. } | Kind::Null => {
            out.push(Diagnostic::error(
                DiagnosticCode::EmptyLabel,
                &value.pos,
                "The label is empty. Write a name after `Label:`, e.g. `Label: WELCOME`.",
            ));
            return None;
        }
        _ => {
            let message = format!(
                "A label must be a single name such as `WELCOME`, but this one is {}.",
                value.describe()
            );
            out.push(Diagnostic::error(
                DiagnosticCode::BadValue,
                &value.pos,
                message,
            ));
            return None;
        }
    };
    Some(Located {
        value: label,
        pos: value.pos.clone(),
    })
}

/// The console group: a name, trimmed; `None` after reporting an empty or shapeless one.
pub(super) fn read_group(value: &Node, out: &mut Vec<Diagnostic>) -> Option<String> {
    match &value.kind {
        Kind::Str { value: text, .. } if !text.trim().is_empty() => Some(text.trim().to_owned()),
        Kind::Guessed(text) => {
            out.push(unquoted_warning(value, text));
            Some(text.clone())
        }
        Kind::Str { .. } | Kind::Null => {
            let message = "`Group` is empty. Write the name of the group the operator console \
                           shows this act in, e.g. `Group: Small talk`, or remove the line (the \
                           act is then shown under its file's name).";
            out.push(Diagnostic::error(
                DiagnosticCode::BadValue,
                &value.pos,
                message,
            ));
            None
        }
        _ => {
            let message = format!(
                "A group must be a single name such as `Small talk`, but this one is {}.",
                value.describe()
            );
            out.push(Diagnostic::error(
                DiagnosticCode::BadValue,
                &value.pos,
                message,
            ));
            None
        }
    }
}

/// The console shortcut: one letter `A`-`Z` (either case, stored upper case) or digit; `None`
/// after reporting a `bad-key`.
pub(super) fn read_key(value: &Node, out: &mut Vec<Diagnostic>) -> Option<Located<char>> {
    const USAGE: &str = "Write one letter (A to Z) or digit (0 to 9), e.g. `Key: W`: the \
                         operator console then fires this act with Alt+W.";
    let message = match value.as_text().map(str::trim) {
        Some(text) => {
            let mut chars = text.chars();
            match (chars.next(), chars.next()) {
                (Some(c), None) if c.is_ascii_alphanumeric() => {
                    return Some(Located {
                        value: c.to_ascii_uppercase(),
                        pos: value.pos.clone(),
                    });
                }
                (None, _) => format!("`Key` is empty. {USAGE} Or remove the line."),
                _ => match modified_key(text) {
                    Some(c) => format!(
                        "Write only the letter or digit, without Alt or other keys: `Key: {c}`. \
                         The operator console adds Alt itself (Alt+{c})."
                    ),
                    None => format!("`{text}` is not one letter or digit. {USAGE}"),
                },
            }
        }
        None if matches!(value.kind, Kind::Null) => {
            format!("`Key` is empty. {USAGE} Or remove the line.")
        }
        None => format!(
            "A key must be one letter or digit, but this one is {}. {USAGE}",
            value.describe()
        ),
    };
    out.push(Diagnostic::error(
        DiagnosticCode::BadKey,
        &value.pos,
        message,
    ));
    None
}

/// The letter or digit of a written combination such as `Alt+W`, `alt-w` or `Ctrl W`.
fn modified_key(text: &str) -> Option<char> {
    let (modifiers, last) = text.rsplit_once(['+', '-', ' '])?;
    let mut chars = last.chars();
    let (Some(c), None) = (chars.next(), chars.next()) else {
        return None;
    };
    let named = ["alt", "ctrl", "control", "shift", "altgr", "meta"];
    let modifiers_named = modifiers
        .split(['+', '-', ' '])
        .filter(|m| !m.is_empty())
        .all(|m| named.contains(&m.to_ascii_lowercase().as_str()));
    (c.is_ascii_alphanumeric() && modifiers_named).then(|| c.to_ascii_uppercase())
}

/// The alternatives of one variant; a single string counts as a list of one.
pub(super) fn read_alternatives(
    key: &str,
    value: &Node,
    reading: &Reading<'_>,
    out: &mut Vec<Diagnostic>,
) -> Vec<Located<String>> {
    match &value.kind {
        Kind::Seq(items) if items.is_empty() => {
            out.push(Diagnostic::error(
                DiagnosticCode::EmptyText,
                &value.pos,
                format!("`{key}` has no text. Write at least one alternative, or remove `{key}`."),
            ));
            Vec::new()
        }
        Kind::Seq(items) => items
            .iter()
            .filter_map(|item| read_alternative(item, reading, out))
            .collect(),
        Kind::Null => {
            let message = format!(
                "`{key}` has no text. Write the text after `{key}:` or as a list below it, or \
                 remove `{key}`."
            );
            out.push(Diagnostic::error(
                DiagnosticCode::EmptyText,
                &value.pos,
                message,
            ));
            Vec::new()
        }
        Kind::Map(_) => {
            let message = format!(
                "The text of `{key}` was read as keys and values, because it contains a colon \
                 followed by a space (`: `). Put the whole text in quotes, e.g. \
                 `{key}: \"Note: this is splendid\"`."
            );
            out.push(Diagnostic::error(
                DiagnosticCode::BadValue,
                &value.pos,
                message,
            ));
            Vec::new()
        }
        _ => read_alternative(value, reading, out).into_iter().collect(),
    }
}

fn read_alternative(
    item: &Node,
    reading: &Reading<'_>,
    out: &mut Vec<Diagnostic>,
) -> Option<Located<String>> {
    let (text, verbatim_at) = match &item.kind {
        Kind::Str { value, verbatim_at } if !value.trim().is_empty() => {
            (value.clone(), *verbatim_at)
        }
        Kind::Guessed(text) => {
            out.push(unquoted_warning(item, text));
            (text.clone(), Some(0))
        }
        Kind::Str { .. } | Kind::Null => {
            out.push(Diagnostic::error(
                DiagnosticCode::EmptyText,
                &item.pos,
                "This alternative is empty. Write the text after the `- `, or remove the line.",
            ));
            return None;
        }
        Kind::Map(entries) => {
            out.push(Diagnostic::error(
                DiagnosticCode::BadValue,
                &item.pos,
                colon_message("text", entries),
            ));
            return None;
        }
        Kind::Seq(_) => {
            let message = "This is a list inside the list of texts. Each alternative must be \
                           a single text; if it starts with `-` or `[`, put it in quotes.";
            out.push(Diagnostic::error(
                DiagnosticCode::BadValue,
                &item.pos,
                message,
            ));
            return None;
        }
    };
    check_written(&reading.source, item, &text, out);
    let spoken = SpokenText {
        text: &text,
        pos: &item.pos,
        verbatim_at,
    };
    check_spoken(&spoken, reading.speech, out);
    Some(Located {
        value: text,
        pos: item.pos.clone(),
    })
}

/// Commands; a single string counts as a list of one, and `Cmds:` left empty as none.
pub(super) fn read_commands(value: &Node, out: &mut Vec<Diagnostic>) -> Vec<WrittenCommand> {
    let items: Vec<&Node> = match &value.kind {
        Kind::Seq(items) => items.iter().collect(),
        Kind::Null => Vec::new(),
        _ => vec![value],
    };
    let mut commands = Vec::with_capacity(items.len());
    for item in items {
        let (text, verbatim_at) = match &item.kind {
            Kind::Str { value, verbatim_at } => (value.clone(), *verbatim_at),
            // An unquoted scalar is always verbatim; its verb check will explain the rest.
            Kind::Guessed(text) => (text.clone(), Some(0)),
            Kind::Null => {
                let message = "This command is empty. Write a command such as `SAY Hello`, or \
                               remove the line.";
                out.push(Diagnostic::error(
                    DiagnosticCode::BadValue,
                    &item.pos,
                    message,
                ));
                continue;
            }
            Kind::Map(entries) => {
                let message = colon_message("command", entries);
                out.push(Diagnostic::error(
                    DiagnosticCode::BadValue,
                    &item.pos,
                    message,
                ));
                continue;
            }
            Kind::Seq(_) => {
                let message = "This is a list inside the list of commands. Write each command \
                               on its own line, e.g. `- SAY Hello`.";
                out.push(Diagnostic::error(
                    DiagnosticCode::BadValue,
                    &item.pos,
                    message,
                ));
                continue;
            }
        };
        let pos = item.pos.clone();
        commands.push(WrittenCommand {
            text,
            pos,
            verbatim_at,
        });
    }
    commands
}

/// For `- Note: splendid`: YAML made a mapping of it. Rebuild the text for the hint.
fn colon_message(what: &str, entries: &[(Node, Node)]) -> String {
    let written = match entries {
        [(k, v)] => k
            .as_text()
            .zip(v.as_text())
            .map(|(k, v)| format!("{k}: {v}")),
        _ => None,
    };
    let example = written.unwrap_or_else(|| "Note: this is splendid".to_owned());
    // `- “Opening hours: ten to six.”`: quoted, but by an editor's curly quotes.
    let curly = ['“', '”', '„', '‘', '’', '«', '»'];
    let inner = example.trim_matches(|c: char| curly.contains(&c));
    if inner.len() < example.len() {
        return format!(
            "This {what} was read as a key and a value, because it contains a colon followed \
             by a space (`: `) and its quotes are curly quotes (“ ”), typed by the editor, \
             which YAML does not take as quotes. Replace them with straight quotes: \
             `- \"{inner}\"`."
        );
    }
    format!(
        "This {what} was read as a key and a value, because it contains a colon followed by a \
         space (`: `). Put the whole {what} in quotes: `- \"{example}\"`."
    )
}

fn unquoted_warning(node: &Node, text: &str) -> Diagnostic {
    let message = format!(
        "`{text}` without quotes is read by YAML as a yes/no value or a number. Docent keeps the \
         text as written, but other tools may not: write it in quotes, `\"{text}\"`."
    );
    Diagnostic::warning(DiagnosticCode::UnquotedScalar, &node.pos, message)
}
