//! The values of an act's keys: the label, text alternatives and command strings. YAML's
//! surprises are caught here: a text with `: ` that became a mapping, an unquoted `yes` that
//! became a boolean, an empty list item that became null.

use crate::content::commands::WrittenCommand;
use crate::content::diagnostic::Diagnostic;
use crate::content::model::Located;

use super::yaml::{Kind, Node};

/// The label, or `None` after reporting why it is unusable.
pub(super) fn read_label(value: &Node, out: &mut Vec<Diagnostic>) -> Option<Located<String>> {
    let label = match &value.kind {
        Kind::Str { value: text, .. } if !text.trim().is_empty() => text.clone(),
        Kind::Guessed(text) => {
            out.push(unquoted_warning(value, text));
            text.clone()
        }
        Kind::Str { .. } | Kind::Null => {
            out.push(Diagnostic::error(
                "empty-label",
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
            out.push(Diagnostic::error("bad-value", &value.pos, message));
            return None;
        }
    };
    Some(Located {
        value: label,
        pos: value.pos.clone(),
    })
}

/// The alternatives of one variant; a single string counts as a list of one.
pub(super) fn read_alternatives(
    key: &str,
    value: &Node,
    out: &mut Vec<Diagnostic>,
) -> Vec<Located<String>> {
    match &value.kind {
        Kind::Seq(items) if items.is_empty() => {
            out.push(Diagnostic::error(
                "empty-text",
                &value.pos,
                format!("`{key}` has no text. Write at least one alternative, or remove `{key}`."),
            ));
            Vec::new()
        }
        Kind::Seq(items) => items
            .iter()
            .filter_map(|item| read_alternative(item, out))
            .collect(),
        Kind::Null => {
            let message = format!(
                "`{key}` has no text. Write the text after `{key}:` or as a list below it, or \
                 remove `{key}`."
            );
            out.push(Diagnostic::error("empty-text", &value.pos, message));
            Vec::new()
        }
        Kind::Map(_) => {
            let message = format!(
                "The text of `{key}` was read as keys and values, because it contains a colon \
                 followed by a space (`: `). Put the whole text in quotes, e.g. \
                 `{key}: \"Note: this is splendid\"`."
            );
            out.push(Diagnostic::error("bad-value", &value.pos, message));
            Vec::new()
        }
        _ => read_alternative(value, out).into_iter().collect(),
    }
}

fn read_alternative(item: &Node, out: &mut Vec<Diagnostic>) -> Option<Located<String>> {
    let text = match &item.kind {
        Kind::Str { value, .. } if !value.trim().is_empty() => value.clone(),
        Kind::Guessed(text) => {
            out.push(unquoted_warning(item, text));
            text.clone()
        }
        Kind::Str { .. } | Kind::Null => {
            out.push(Diagnostic::error(
                "empty-text",
                &item.pos,
                "This alternative is empty. Write the text after the `- `, or remove the line.",
            ));
            return None;
        }
        Kind::Map(entries) => {
            out.push(Diagnostic::error(
                "bad-value",
                &item.pos,
                colon_message("text", entries),
            ));
            return None;
        }
        Kind::Seq(_) => {
            let message = "This is a list inside the list of texts. Each alternative must be \
                           a single text; if it starts with `-` or `[`, put it in quotes.";
            out.push(Diagnostic::error("bad-value", &item.pos, message));
            return None;
        }
    };
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
                out.push(Diagnostic::error("bad-value", &item.pos, message));
                continue;
            }
            Kind::Map(entries) => {
                let message = colon_message("command", entries);
                out.push(Diagnostic::error("bad-value", &item.pos, message));
                continue;
            }
            Kind::Seq(_) => {
                let message = "This is a list inside the list of commands. Write each command \
                               on its own line, e.g. `- SAY Hello`.";
                out.push(Diagnostic::error("bad-value", &item.pos, message));
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
    Diagnostic::warning("unquoted-scalar", &node.pos, message)
}
