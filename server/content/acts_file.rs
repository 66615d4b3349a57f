//! Reading one acts file (the paper's Fig. 4 format): a YAML list of acts, each a mapping
//! with `Label`, `Text`, any number of `Text...` variant keys and `Cmds`.
//!
//! The file is first read into a located tree (`yaml`), then walked here so that every
//! problem gets its own diagnostic at its own place. A single string where a list is
//! expected is accepted. Commands are only collected here; `commands` checks them once the
//! site settings are known.

use std::collections::BTreeSet;
use std::sync::Arc;

use crate::DiagnosticCode;
use crate::commands::WrittenCommand;
use crate::config::{Languages, SpeechConfig};
use crate::diagnostic::Diagnostic;
use crate::language::Language;
use crate::model::{DEFAULT_VARIANT, Located, Pos, Variant};
use crate::suggest::closest;

mod keywords;
mod texts;
mod translations;
mod values;
pub(crate) mod yaml;

use keywords::read_keywords;
use values::{read_alternatives, read_commands, read_group, read_key, read_label};
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
    /// The console group (`Group:`), when written and usable.
    pub group: Option<String>,
    /// The console shortcut (`Key:`), upper case, with the place of its value.
    pub key: Option<Located<char>>,
    /// Words the console's search also finds the act by (`Keywords:`), in written order.
    pub keywords: Vec<String>,
    /// Every language written after the `@` of its text keys (`Text@de:`), the default
    /// language's too: what tells a `languages:` list written the wrong way round.
    pub tagged: BTreeSet<Language>,
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
    /// Nothing of the file could be read (an encoding or size problem): its labels are unknown.
    pub unreadable: bool,
}

/// The keys an act may have besides `Text...` variants, for suggestions.
pub(crate) const KEYS: [&str; 6] = ["Label", DEFAULT_VARIANT, "Cmds", "Group", "Key", "Keywords"];

/// What reading the texts of one file needs besides its tree.
pub(crate) struct Reading<'a> {
    /// The file and its text, to compare what YAML read with what was written.
    pub source: texts::Source<'a>,
    /// The speech settings, for the length of spoken texts.
    pub speech: &'a SpeechConfig,
    /// The bundle's languages, for the `@de` of translated texts.
    pub languages: &'a Languages,
}

/// Reads the acts file `file` (named relative to the bundle root) from its bytes; spoken
/// texts are checked against `speech`, translations against `languages`.
pub(crate) fn read_acts_file(
    file: &Arc<str>,
    bytes: &[u8],
    speech: &SpeechConfig,
    languages: &Languages,
) -> ActsFile {
    let parsed = yaml::parse(
        file,
        bytes,
        DiagnosticCode::YamlSyntax,
        Recovery::SkipBrokenItems,
    );
    let reading = Reading {
        source: texts::Source {
            text: std::str::from_utf8(bytes).unwrap_or_default(),
        },
        speech,
        languages,
    };
    let mut out = ActsFile {
        acts: Vec::new(),
        diagnostics: parsed.diagnostics,
        unread_labels: Vec::new(),
        unreadable: false,
    };
    if !parsed.skipped_lines.is_empty() {
        let source = String::from_utf8_lossy(bytes);
        out.unread_labels = labels_in_lines(&source, &parsed.skipped_lines);
    }
    let Some(root) = parsed.root else {
        out.unreadable = out.diagnostics.iter().any(Diagnostic::is_error);
        return out;
    };
    match &root.kind {
        Kind::Seq(items) => {
            for item in items {
                if let Some(act) = read_act(item, &reading, &mut out.diagnostics) {
                    out.acts.push(act);
                }
            }
        }
        Kind::Null if out.diagnostics.iter().all(|d| !d.is_error()) => {
            let message = "This acts file has no acts. Add acts (a list of `- Label: ...` \
                           entries) or delete the file.";
            out.diagnostics.push(Diagnostic::warning(
                DiagnosticCode::EmptyFile,
                &Pos::start_of(file.clone()),
                message,
            ));
        }
        Kind::Null => {}
        _ => out.diagnostics.push(Diagnostic::error(
            DiagnosticCode::NotAList,
            &root.pos,
            file_not_a_list_message(file, &root),
        )),
    }
    out
}

fn file_not_a_list_message(file: &str, root: &Node) -> String {
    let looks_like_one_act = match &root.kind {
        Kind::Map(entries) => entries.iter().any(|(k, _)| k.as_text() == Some("Label")),
        _ => false,
    };
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
fn read_act(node: &Node, reading: &Reading<'_>, out: &mut Vec<Diagnostic>) -> Option<WrittenAct> {
    let Kind::Map(entries) = &node.kind else {
        let message = format!(
            "Each act must be a set of keys (`Label:`, `Text:`, `Cmds:`), but this one is {}. \
             Check the indentation: the act's keys belong under its `- `.",
            node.describe()
        );
        out.push(Diagnostic::error(
            DiagnosticCode::NotAList,
            &node.pos,
            message,
        ));
        return None;
    };
    let mut act = WrittenAct {
        label: None,
        variants: Vec::new(),
        commands: Vec::new(),
        group: None,
        key: None,
        keywords: Vec::new(),
        tagged: BTreeSet::new(),
    };
    let mut seen: Vec<(&str, &Pos)> = Vec::new();
    let mut wrote_content = false;
    let mut pending = translations::Pending::default();
    for (key, value) in entries {
        let Some(name) = key.as_text() else {
            out.push(Diagnostic::error(
                DiagnosticCode::UnknownKey,
                &key.pos,
                format!(
                    "A key must be a word such as `Label`, `Text` or `Cmds`, but this one is {}.",
                    key.describe()
                ),
            ));
            continue;
        };
        // `Text@de`: a translation; `Text@en` in an English bundle: the original itself.
        let mut translated = None;
        let written = name;
        let name = match name.split_once('@') {
            Some((base, tag)) if is_variant_key(base) => {
                act.tagged.extend(Language::parse(tag));
                match translations::suffix(name, tag, &key.pos, reading.languages, out) {
                    translations::Suffix::Default => base,
                    translations::Suffix::Other(language) => {
                        translated = Some(language);
                        name
                    }
                    translations::Suffix::Refused => continue,
                }
            }
            _ => name,
        };
        if let Some((_, first)) = seen.iter().find(|(k, _)| *k == name) {
            let message = format!(
                "`{written}` appears twice in this act (first at line {}; `{name}` and \
                 `{name}@{default}` are the same key, because `{default}` is the default \
                 language, the first in `languages:`). Keep one: put all its entries in a \
                 single list.",
                first.line,
                default = reading.languages.default_language()
            );
            out.push(Diagnostic::error(
                DiagnosticCode::DuplicateKey,
                &key.pos,
                message,
            ));
            continue;
        }
        seen.push((name, &key.pos));
        if let Some(language) = translated {
            let (base, _) = name.split_once('@').unwrap_or((name, ""));
            let alternatives = read_alternatives(name, value, reading, out);
            pending.add(base, language, name, key.pos.clone(), alternatives);
            continue;
        }
        match name {
            "Label" => {
                let before = out.len();
                act.label = read_label(value, &reading.source, out);
                // Texts swallowed by the label were written: the act is not empty, only broken.
                wrote_content |= out[before..]
                    .iter()
                    .any(|d| d.code == DiagnosticCode::JoinedLines);
            }
            "Group" => act.group = read_group(value, out),
            "Key" => act.key = read_key(value, out),
            "Keywords" => act.keywords = read_keywords(value, out),
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
                let alternatives = read_alternatives(name, value, reading, out);
                if !alternatives.is_empty() {
                    act.variants.push(Variant {
                        name: name.to_owned(),
                        pos: key.pos.clone(),
                        alternatives,
                        translations: std::collections::BTreeMap::new(),
                    });
                }
            }
            _ => out.push(Diagnostic::error(
                DiagnosticCode::UnknownKey,
                &key.pos,
                unknown_key_message(name),
            )),
        }
    }
    if let Some(label) = &act.label {
        pending.settle(&label.value, &mut act.variants, reading.languages, out);
    }
    let Some(label) = &act.label else {
        if !seen.iter().any(|(k, _)| *k == "Label") {
            let message = "This act has no `Label`. Add a line `Label: SOME_NAME` so pages \
                           and people can trigger it.";
            out.push(Diagnostic::error(
                DiagnosticCode::MissingLabel,
                &node.pos,
                message,
            ));
        }
        return None;
    };
    if !wrote_content {
        let message = format!(
            "The act `{}` has no text and no commands, so triggering it does nothing. \
             Add `Text:` or `Cmds:`.",
            label.value
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::EmptyAct,
            &node.pos,
            message,
        ));
    }
    // The paper: "Text is the default and has to exist for all dialog acts where text
    // utterance is desired"; without it the act is silent in every other context.
    if let Some(first) = act.variants.first()
        && !act.variants.iter().any(|v| v.name == DEFAULT_VARIANT)
    {
        let message = format!(
            "The act `{}` has `{}` but no `Text`, so it says nothing in any other context. \
             Add a `Text:` list as the default.",
            label.value, first.name
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::NoDefaultText,
            &first.pos,
            message,
        ));
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
         starting with `Text`, such as `TextGroup`), `Cmds`, and for the operator console \
         `Group` and `Key`; upper and lower case matter."
    )
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
                .trim_start_matches('-')
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

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> ActsFile {
        let config = crate::config::SiteConfig::default();
        read_acts_file(
            &Arc::from("acts.yaml"),
            text.as_bytes(),
            &config.speech,
            &config.languages,
        )
    }

    #[test]
    fn variant_keys_start_with_text_exactly() {
        for key in ["Text", "TextGroup", "TextChild", "Text2", "Text_formal"] {
            assert!(is_variant_key(key), "{key}");
        }
        for key in ["text", "TEXT", "Texts and more", "Txt", "Label"] {
            assert!(!is_variant_key(key), "{key}");
        }
    }

    #[test]
    fn miscapitalised_variant_keys_get_the_right_suggestion() {
        assert!(unknown_key_message("textGroup").contains("Did you mean `TextGroup`?"));
        assert!(unknown_key_message("TEXTCHILD").contains("Did you mean `TextChild`?"));
        assert!(unknown_key_message("Lable").contains("Did you mean `Label`?"));
        assert!(unknown_key_message("Grup").contains("Did you mean `Group`?"));
        assert!(unknown_key_message("group").contains("Did you mean `Group`?"));
        assert!(unknown_key_message("key").contains("Did you mean `Key`?"));
        assert!(unknown_key_message("Keys").contains("Did you mean `Key`?"));
        assert!(!unknown_key_message("Colour").contains("Did you mean"));
    }

    #[test]
    fn reads_commands_with_their_verbatim_offsets() {
        let file = read(
            "- Label: A\n  Cmds:\n    - SAY hi\n    - 'WAIT 2s'\n    - >-\n      SAY folded\n",
        );
        let commands: Vec<(&str, u32, u32, Option<u32>)> = file.acts[0]
            .commands
            .iter()
            .map(|c| (c.text.as_str(), c.pos.line, c.pos.column, c.verbatim_at))
            .collect();
        assert_eq!(
            commands,
            [
                ("SAY hi", 3, 7, Some(0)),
                ("WAIT 2s", 4, 7, Some(1)),
                ("SAY folded", 6, 7, None)
            ]
        );
    }

    #[test]
    fn labels_of_skipped_acts_are_still_known() {
        let file = read("- Label: GOOD\n  Text: fine\n- Label: \"BROKEN\"\n  Text: [oops\n");
        assert_eq!(file.acts.len(), 1);
        assert_eq!(file.unread_labels, ["BROKEN"]);
        assert_eq!(file.diagnostics.len(), 1);
    }
}
