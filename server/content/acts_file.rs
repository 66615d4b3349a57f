//! Reading one acts file (the paper's Fig. 4 format): a YAML list of acts, each a mapping
//! with `Label`, `Text`, any number of `Text...` variant keys and `Cmds`.
//!
//! The file is first read into a located tree (`yaml`), then walked here so that every
//! problem gets its own diagnostic at its own place. A single string where a list is
//! expected is accepted. Commands are only collected here; `commands` checks them once the
//! site settings are known.

use std::sync::Arc;

use crate::content::commands::WrittenCommand;
use crate::content::diagnostic::Diagnostic;
use crate::content::model::{DEFAULT_VARIANT, Located, Pos, Variant};
use crate::content::suggest::closest;

pub(in crate::content) mod yaml;

use yaml::{Kind, Node, Recovery};

/// One act as written, before labels are compared across files and commands are checked.
#[derive(Debug)]
pub(crate) struct WrittenAct {
    /// The label, when one was written and usable.
    pub label: Option<Located<String>>,
    /// Text variants with at least one usable alternative, in written order.
    pub variants: Vec<Variant>,
    /// Command strings in written order.
    pub commands: Vec<WrittenCommand>,
}

/// Everything read from one acts file.
pub(crate) struct ActsFile {
    /// The acts that could be read.
    pub acts: Vec<WrittenAct>,
    /// Problems found.
    pub diagnostics: Vec<Diagnostic>,
    /// Labels seen in parts skipped because of YAML errors: not checked, but pages naming
    /// them should not be reported as naming unknown acts.
    pub unread_labels: Vec<String>,
}

/// The keys an act may have besides `Text...` variants, for suggestions.
const KEYS: [&str; 3] = ["Label", DEFAULT_VARIANT, "Cmds"];

/// Reads the acts file `file` (named relative to the bundle root) from its bytes.
pub(crate) fn read_acts_file(file: &Arc<str>, bytes: &[u8]) -> ActsFile {
    let parsed = yaml::parse(file, bytes, "yaml-syntax", Recovery::SkipBrokenItems);
    let mut out = ActsFile {
        acts: Vec::new(),
        diagnostics: parsed.diagnostics,
        unread_labels: Vec::new(),
    };
    if !parsed.skipped_lines.is_empty() {
        let source = String::from_utf8_lossy(bytes);
        out.unread_labels = labels_in_lines(&source, &parsed.skipped_lines);
    }
    let Some(root) = parsed.root else { return out };
    match &root.kind {
        Kind::Seq(items) => {
            for item in items {
                if let Some(act) = read_act(item, &mut out.diagnostics) {
                    out.acts.push(act);
                }
            }
        }
        Kind::Null if out.diagnostics.iter().all(|d| !d.is_error()) => {
            let message = "This acts file has no acts. Add acts (a list of `- Label: ...` entries) or delete the file.";
            out.diagnostics.push(Diagnostic::warning(
                "empty-file",
                &Pos::new(file.clone(), 0, 0),
                message,
            ));
        }
        Kind::Null => {}
        _ => out.diagnostics.push(Diagnostic::error(
            "not-a-list",
            &root.pos,
            file_not_a_list_message(file, &root),
        )),
    }
    out
}

fn file_not_a_list_message(file: &str, root: &Node) -> String {
    let looks_like_one_act = matches!(&root.kind, Kind::Map(entries) if entries.iter().any(|(k, _)| k.as_text() == Some("Label")));
    let hint = if looks_like_one_act {
        " Start each act with a dash: `- Label: WELCOME`, and indent its other keys by two spaces."
    } else if file
        .trim_end_matches(".yml")
        .trim_end_matches(".yaml")
        .eq_ignore_ascii_case("docent")
    {
        " If this file holds the site settings, name it exactly `docent.yaml`."
    } else {
        ""
    };
    format!(
        "An acts file must be a list of acts, each starting with `- `, but this file is {}.{hint}",
        root.describe()
    )
}

/// One act; `None` (after reporting) when it is not a mapping or has no usable label.
fn read_act(node: &Node, out: &mut Vec<Diagnostic>) -> Option<WrittenAct> {
    let Kind::Map(entries) = &node.kind else {
        let message = format!(
            "Each act must be a set of keys (`Label:`, `Text:`, `Cmds:`), but this one is {}. \
             Check the indentation: the act's keys belong under its `- `.",
            node.describe()
        );
        out.push(Diagnostic::error("not-a-list", &node.pos, message));
        return None;
    };
    let mut act = WrittenAct {
        label: None,
        variants: Vec::new(),
        commands: Vec::new(),
    };
    let mut seen: Vec<(&str, &Pos)> = Vec::new();
    let mut wrote_content = false;
    for (key, value) in entries {
        let Some(name) = key.as_text() else {
            out.push(Diagnostic::error(
                "unknown-key",
                &key.pos,
                format!(
                    "A key must be a word such as `Label`, `Text` or `Cmds`, but this one is {}.",
                    key.describe()
                ),
            ));
            continue;
        };
        if let Some((_, first)) = seen.iter().find(|(k, _)| *k == name) {
            let message = format!(
                "`{name}` appears twice in this act (first at line {}). Keep one: put all its \
                 entries in a single list.",
                first.line
            );
            out.push(Diagnostic::error("duplicate-key", &key.pos, message));
            continue;
        }
        seen.push((name, &key.pos));
        match name {
            "Label" => act.label = read_label(value, out),
            "Cmds" => {
                wrote_content |= match &value.kind {
                    Kind::Null => false,
                    Kind::Seq(items) => !items.is_empty(),
                    _ => true,
                };
                act.commands = read_commands(value, out);
            }
            _ if is_variant_key(name) => {
                wrote_content = true;
                let alternatives = read_alternatives(name, value, out);
                if !alternatives.is_empty() {
                    act.variants.push(Variant {
                        name: name.to_owned(),
                        pos: key.pos.clone(),
                        alternatives,
                    });
                }
            }
            _ => out.push(Diagnostic::error(
                "unknown-key",
                &key.pos,
                unknown_key_message(name),
            )),
        }
    }
    let Some(label) = &act.label else {
        if !seen.iter().any(|(k, _)| *k == "Label") {
            out.push(Diagnostic::error("missing-label", &node.pos, "This act has no `Label`. Add a line `Label: SOME_NAME` so pages and people can trigger it."));
        }
        return None;
    };
    if !wrote_content {
        let message = format!(
            "The act `{}` has no text and no commands, so triggering it does nothing. Add `Text:` or `Cmds:`.",
            label.value
        );
        out.push(Diagnostic::warning("empty-act", &node.pos, message));
    }
    Some(act)
}

/// `Text` itself, or `Text` followed by a name (`TextGroup`, `TextChild`, `Text2`).
fn is_variant_key(name: &str) -> bool {
    name.strip_prefix(DEFAULT_VARIANT)
        .is_some_and(|rest| rest.chars().all(|c| c.is_alphanumeric() || c == '_'))
}

fn unknown_key_message(name: &str) -> String {
    let suggestion = match name.get(..4) {
        // `textGroup`, `TEXTGROUP`: a variant key with the wrong capitals.
        Some(head) if head.eq_ignore_ascii_case(DEFAULT_VARIANT) && name.len() > 4 => {
            let rest = &name[4..];
            let mut chars = rest.chars();
            let first = chars
                .next()
                .map(|c| c.to_uppercase().collect::<String>())
                .unwrap_or_default();
            Some(format!(
                "{DEFAULT_VARIANT}{first}{}",
                chars.as_str().to_lowercase()
            ))
        }
        _ => closest(name, KEYS).map(str::to_owned),
    };
    let hint = suggestion.map_or_else(String::new, |s| format!(" Did you mean `{s}`?"));
    format!(
        "`{name}` is not a key Docent knows.{hint} An act has `Label`, `Text` (and variants \
         starting with `Text`, such as `TextGroup`) and `Cmds`; upper and lower case matter."
    )
}

fn read_label(value: &Node, out: &mut Vec<Diagnostic>) -> Option<Located<String>> {
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
fn read_alternatives(key: &str, value: &Node, out: &mut Vec<Diagnostic>) -> Vec<Located<String>> {
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
            out.push(Diagnostic::error("empty-text", &value.pos, format!("`{key}` has no text. Write the text after `{key}:` or as a list below it, or remove `{key}`.")));
            Vec::new()
        }
        Kind::Map(_) => {
            let message = format!(
                "The text of `{key}` was read as keys and values, because it contains a colon \
                 followed by a space (`: `). Put the whole text in quotes, e.g. `{key}: \"Note: this is splendid\"`."
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
            out.push(Diagnostic::error("bad-value", &item.pos, "This is a list inside the list of texts. Each alternative must be a single text; if it starts with `-` or `[`, put it in quotes."));
            return None;
        }
    };
    Some(Located {
        value: text,
        pos: item.pos.clone(),
    })
}

/// Commands; a single string counts as a list of one, and `Cmds:` left empty as none.
fn read_commands(value: &Node, out: &mut Vec<Diagnostic>) -> Vec<WrittenCommand> {
    let items: Vec<&Node> = match &value.kind {
        Kind::Seq(items) => items.iter().collect(),
        Kind::Null => Vec::new(),
        _ => vec![value],
    };
    let mut commands = Vec::with_capacity(items.len());
    for item in items {
        match &item.kind {
            Kind::Str { value: text, verbatim_at } => {
                commands.push(WrittenCommand { text: text.clone(), pos: item.pos.clone(), verbatim_at: *verbatim_at });
            }
            Kind::Guessed(text) => commands.push(WrittenCommand { text: text.clone(), pos: item.pos.clone(), verbatim_at: Some(0) }),
            Kind::Null => out.push(Diagnostic::error("bad-value", &item.pos, "This command is empty. Write a command such as `SAY Hello`, or remove the line.")),
            Kind::Map(entries) => out.push(Diagnostic::error("bad-value", &item.pos, colon_message("command", entries))),
            Kind::Seq(_) => out.push(Diagnostic::error("bad-value", &item.pos, "This is a list inside the list of commands. Write each command as one line, e.g. `- SAY Hello`.")),
        }
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

/// Labels written in `Label: NAME` lines within the skipped line ranges.
fn labels_in_lines(source: &str, ranges: &[(u32, u32)]) -> Vec<String> {
    source
        .lines()
        .enumerate()
        .filter(|(i, _)| {
            let line = u32::try_from(i + 1).unwrap_or(u32::MAX);
            ranges
                .iter()
                .any(|&(start, end)| (start..end).contains(&line))
        })
        .filter_map(|(_, line)| {
            let rest = line
                .trim_start()
                .trim_start_matches("- ")
                .trim_start()
                .strip_prefix("Label:")?;
            let label = rest
                .split(" #")
                .next()
                .unwrap_or_default()
                .trim()
                .trim_matches(['"', '\'']);
            (!label.is_empty()).then(|| label.to_owned())
        })
        .collect()
}
