//! Checks of what the operator console uses against the whole bundle: the keys acts bind
//! (one act per key), the map picture (it must exist, and the robot can only be placed on it
//! with `drive: bounds`), and the contexts the visitor groups switch to.

use std::collections::{BTreeMap, HashMap};

use crate::DiagnosticCode;
use crate::commands::{CommandChecker, path_error_code};
use crate::config::SiteConfig;
use crate::config_file::operator::{VISITOR_GROUPS, default_context};
use crate::diagnostic::Diagnostic;
use crate::model::{Located, Pos};
use crate::paths::BundleArea;
use crate::suggest::did_you_mean;

/// The acts' `Key`s seen so far, in loading order, each with the first act that took it.
#[derive(Default)]
pub(crate) struct KeyBindings {
    first: HashMap<char, (String, Pos)>,
}

impl KeyBindings {
    /// Binds `key` to the act `label`, or reports the act that already has it.
    pub fn bind(&mut self, label: &str, key: &Located<char>, out: &mut Vec<Diagnostic>) {
        let Some((first_label, first)) = self.first.get(&key.value) else {
            self.first
                .insert(key.value, (label.to_owned(), key.pos.clone()));
            return;
        };
        let message = format!(
            "The key `{k}` is already given to the act `{first_label}` at {}:{}, so Alt+{k} \
             cannot also fire `{label}`. Each key fires one act: choose another `Key` for one \
             of them, or remove it.",
            first.file,
            first.line,
            k = key.value
        );
        out.push(Diagnostic::error(
            DiagnosticCode::DuplicateKeyBinding,
            &key.pos,
            message,
        ));
    }
}

/// The map set in `operator: map:` must be a file of the bundle, and needs `drive: bounds`.
pub(crate) fn check_map(
    checker: &CommandChecker<'_>,
    config: &SiteConfig,
    map: Option<&Located<String>>,
    out: &mut Vec<Diagnostic>,
) {
    let Some(Located { value, pos }) = map else {
        return;
    };
    let located = [BundleArea::Pages, BundleArea::Media]
        .into_iter()
        .find_map(|area| {
            Some((
                area,
                value.strip_prefix(area.dir_name())?.strip_prefix('/')?,
            ))
        });
    // The settings reader accepts only paths under pages/ or media/.
    let Some((area, rel)) = located else { return };
    if let Some((err, problem)) = checker.path_problem(area, rel) {
        let message = format!(
            "{problem} The operator console shows this picture as the map: correct `map:` \
             in docent.yaml, or add the file."
        );
        out.push(Diagnostic::error(path_error_code(&err), pos, message));
    }
    if config.drive.bounds.is_none() {
        let message = "The operator console places the robot on the map using `drive: bounds` \
                       (the corners of the area the picture shows), and docent.yaml sets none. \
                       Add them, e.g. `drive: { bounds: { min_x: 0, min_y: 0, max_x: 20, \
                       max_y: 12 } }`, or remove `map:`.";
        out.push(Diagnostic::error(
            DiagnosticCode::MapNeedsBounds,
            pos,
            message,
        ));
    }
}

/// Each visitor group's context: the one written when the bundle has it (else an
/// `unknown-context` error), otherwise the default when the bundle has that.
pub(crate) fn visitor_groups(
    contexts: &[String],
    written: &[(&'static str, Located<String>)],
    out: &mut Vec<Diagnostic>,
) -> BTreeMap<String, String> {
    let mut groups = BTreeMap::new();
    for group in VISITOR_GROUPS.keys() {
        let context = match written.iter().find(|(g, _)| *g == group) {
            Some((_, Located { value, pos })) => {
                if !contexts.contains(value) {
                    let hint = did_you_mean(value, contexts.iter().map(String::as_str));
                    let message = format!(
                        "The visitor group `{group}` switches to the context `{value}`, but this \
                         bundle has no such context (it has {}).{hint} Name one of those, or \
                         write acts with `{value}` texts.",
                        contexts.join(", ")
                    );
                    out.push(Diagnostic::error(
                        DiagnosticCode::UnknownContext,
                        pos,
                        message,
                    ));
                    continue;
                }
                value.as_str()
            }
            None => {
                let default = default_context(group);
                if !contexts.iter().any(|c| c == default) {
                    continue;
                }
                default
            }
        };
        groups.insert(group.to_owned(), context.to_owned());
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| (*s).to_owned()).collect()
    }

    fn at(line: u32, column: u32) -> Pos {
        Pos::new("docent.yaml", line, column)
    }

    #[test]
    fn visitor_groups_default_to_the_contexts_the_bundle_has() {
        let mut out = Vec::new();
        let groups = visitor_groups(&names(&["Text", "TextChild"]), &[], &mut out);
        assert!(out.is_empty());
        assert_eq!(
            groups,
            BTreeMap::from([
                ("children".to_owned(), "TextChild".to_owned()),
                ("single".to_owned(), "Text".to_owned()),
            ])
        );
    }

    #[test]
    fn a_written_visitor_group_must_name_a_context_of_the_bundle() {
        let written = [
            (
                "group",
                Located {
                    value: "TextGrop".to_owned(),
                    pos: at(3, 12),
                },
            ),
            (
                "single",
                Located {
                    value: "TextFormal".to_owned(),
                    pos: at(4, 13),
                },
            ),
        ];
        let mut out = Vec::new();
        let contexts = names(&["Text", "TextGroup", "TextFormal"]);
        let groups = visitor_groups(&contexts, &written, &mut out);
        assert_eq!(
            groups,
            BTreeMap::from([("single".to_owned(), "TextFormal".to_owned())])
        );
        assert_eq!(out.len(), 1);
        assert_eq!(
            (out[0].code.as_str(), out[0].line, out[0].column),
            ("unknown-context", 3, 12)
        );
        assert!(
            out[0].message.contains("Did you mean `TextGroup`?"),
            "{}",
            out[0].message
        );
    }

    #[test]
    fn a_key_taken_twice_is_reported_at_the_second_naming_the_first() {
        let mut keys = KeyBindings::default();
        let mut out = Vec::new();
        let key = |line| Located {
            value: 'W',
            pos: Pos::new("smalltalk.yaml", line, 8),
        };
        keys.bind("WELCOME", &key(3), &mut out);
        keys.bind("WAVE", &key(9), &mut out);
        assert_eq!(out.len(), 1);
        assert_eq!(
            (out[0].code.as_str(), out[0].line, out[0].column),
            ("duplicate-key-binding", 9, 8)
        );
        assert!(
            out[0].message.contains("`WELCOME` at smalltalk.yaml:3"),
            "{}",
            out[0].message
        );
        assert!(out[0].message.contains("Alt+W cannot also fire `WAVE`"));
    }
}
