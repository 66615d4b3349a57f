//! Generic readers for settings: a mapping's entries (reporting unknown and repeated keys
//! with suggestions), a value parsed from text, a choice among fixed words. Each reports a
//! located, plain-language problem and returns `None` so the default stays in force.

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::diagnostic::Diagnostic;
use crate::model::{Located, Pos};
use crate::schedule::CalendarDate;
use crate::suggest::did_you_mean;

use super::section::{Field, Section, Shape};

/// Collects the problems found while reading `docent.yaml`.
pub(super) struct Reader {
    /// Problems so far, in the order found.
    pub diagnostics: Vec<Diagnostic>,
    /// The pages and acts the kiosk's attract loops and schedule name, checked later.
    pub screen_refs: super::attract::ScreenRefs,
    /// Each special day's date with its place (checked against today by the loader).
    pub special_dates: Vec<Located<CalendarDate>>,
}

impl Reader {
    /// The value parsed from its (trimmed) text, or `None` after reporting `usage`.
    pub(super) fn setting<T>(
        &mut self,
        node: &Node,
        usage: &str,
        parse: impl FnOnce(&str) -> Option<T>,
    ) -> Option<T> {
        let parsed = node
            .as_text()
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .and_then(parse);
        if parsed.is_none() {
            self.bad(node, usage);
        }
        parsed
    }

    pub(super) fn choice<T: Copy>(
        &mut self,
        node: &Node,
        what: &str,
        options: &[(&str, T)],
    ) -> Option<T> {
        let written = node.as_text().unwrap_or_default();
        if let Some((_, value)) = options.iter().find(|(name, _)| *name == written) {
            return Some(*value);
        }
        let names: Vec<&str> = options.iter().map(|(name, _)| *name).collect();
        let hint = did_you_mean(written, names.iter().copied());
        self.bad(
            node,
            &format!("The {what} must be one of: {}.{hint}", names.join(", ")),
        );
        None
    }

    /// The value of a [`Shape::Bool`] or [`Shape::Choice`] setting: the word written, mapped
    /// to `values` in the order of the shape's words (`true`, `false` for a switch).
    pub(super) fn pick<T: Copy>(
        &mut self,
        node: &Node,
        what: &str,
        shape: &Shape,
        values: &[T],
    ) -> Option<T> {
        let words = shape.words();
        debug_assert_eq!(words.len(), values.len(), "one value per word");
        let options: Vec<(&str, T)> = words.iter().copied().zip(values.iter().copied()).collect();
        self.choice(node, what, &options)
    }

    /// Reports a `config-bad-value` at `node`, saying what was found there.
    pub(super) fn bad(&mut self, node: &Node, message: &str) {
        let found = match node.as_text() {
            Some(text) => format!("`{text}`"),
            None => node.describe().to_owned(),
        };
        let message = format!("{message} Found: {found}.");
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::ConfigBadValue,
            &node.pos,
            message,
        ));
    }

    /// The entries of a settings mapping with the fields `section` defines, reporting
    /// unknown, duplicate and non-text keys. A null section (`speech:` alone) has no entries.
    pub(super) fn entries<'n>(
        &mut self,
        node: &'n Node,
        definition: &'static Section,
    ) -> Vec<(&'static Field, &'n Node)> {
        let known = definition.keys();
        let section = definition.name;
        let entries = match &node.kind {
            Kind::Map(entries) => entries,
            Kind::Null => return Vec::new(),
            _ => {
                self.bad(
                    node,
                    &format!(
                        "`{section}` must be a set of settings ({}).",
                        known.join(", ")
                    ),
                );
                return Vec::new();
            }
        };
        let mut seen: Vec<(&str, &Pos)> = Vec::new();
        let mut out: Vec<(&'static Field, &'n Node)> = Vec::new();
        for (key, value) in entries {
            let name = key.as_text().unwrap_or_default();
            if let Some((_, first)) = seen.iter().find(|(k, _)| *k == name) {
                let message = format!(
                    "`{name}` is set twice here (first on line {}). Keep one.",
                    first.line
                );
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::DuplicateKey,
                    &key.pos,
                    message,
                ));
                continue;
            }
            seen.push((name, &key.pos));
            if let Some(field) = definition.field(name) {
                out.push((field, value));
                continue;
            }
            if let Some(message) = out
                .last()
                .and_then(|&(above, v)| not_indented(name, above, v))
            {
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::ConfigUnknownKey,
                    &key.pos,
                    message,
                ));
                continue;
            }
            let hint = did_you_mean(name, known.iter().copied());
            let message = format!(
                "`{name}` is not a setting Docent knows in {section}.{hint} Known settings \
                 here: {}.",
                known.join(", ")
            );
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::ConfigUnknownKey,
                &key.pos,
                message,
            ));
        }
        out
    }
}

/// `corpus:`, then `record: none` in the same column: a setting of the section above, not
/// indented under it (after the section's other settings, or right under its key). The
/// message for `name`, if that is what happened.
fn not_indented(name: &str, above: &Field, value: &Node) -> Option<String> {
    let Shape::Nested(section) = above.shape else {
        return None;
    };
    let a_section = matches!(value.kind, Kind::Null | Kind::Map(_));
    if !a_section || section.field(name).is_none() {
        return None;
    }
    let parent = above.key;
    Some(format!(
        "`{name}` is a setting of `{parent}:` above, but it starts in the same column as \
         `{parent}:`, so Docent reads it as a setting of its own. Indent it by two spaces, \
         under `{parent}:`."
    ))
}
