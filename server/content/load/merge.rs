//! The acts of every file merged into one list: labels across files (a translated copy told
//! once, not label by label), operator keys, and the labels the pages trigger.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

use crate::DiagnosticCode;
use crate::config::{Language, SiteConfig};
use crate::diagnostic::Diagnostic;
use crate::gather::{CheckedAct, CheckedFile};
use crate::model::{Act, Located, Pos};
use crate::operator_check::KeyBindings;
use crate::pages::{PageLabels, check_reachable_languages};
use crate::suggest::did_you_mean;
use crate::translated_copy::TranslatedCopies;

/// The acts of all files merged, with everything that needs them all.
#[derive(Default)]
pub(super) struct Merged {
    pub(super) acts: Vec<Act>,
    pub(super) index: HashMap<String, usize>,
    pub(super) unread_labels: HashSet<String>,
    /// An acts file could not be read at all: any label may be in it, so none is called
    /// unknown (the file's own error comes first).
    pub(super) incomplete: bool,
    pub(super) page_acts: Vec<String>,
    pub(super) page_offers: Vec<Located<String>>,
    pub(super) page_languages: Vec<(String, Language)>,
}

impl Merged {
    /// Whether `label` is an act, or may be one in a part of the acts that could not be read.
    pub(super) fn knows(&self, label: &str) -> bool {
        self.incomplete || self.index.contains_key(label) || self.unread_labels.contains(label)
    }
}

pub(super) fn merge_acts(
    files: Vec<CheckedFile>,
    copies: &TranslatedCopies,
    out: &mut Vec<Diagnostic>,
) -> Merged {
    let mut merged = Merged::default();
    let mut keys = KeyBindings::default();
    // Later places of each label used more than once, reported at the first place at the end.
    let mut again: Vec<(usize, Pos)> = Vec::new();
    for file in files {
        merged.unread_labels.extend(file.unread_labels);
        merged.incomplete |= file.unreadable;
        for act in file.acts {
            let CheckedAct {
                label,
                variants,
                commands,
                group,
                key,
                keywords,
            } = act;
            // A translation in a file of its own is told once, not as a duplicate per act.
            if copies.leaves_out(&label.pos.file, &label.value) {
                continue;
            }
            if let Some(&first) = merged.index.get(&label.value) {
                let first_pos = &merged.acts[first].pos;
                let message = format!(
                    "The label `{}` is already used at {}:{}. Labels must be unique: rename \
                     one of the two acts.",
                    label.value, first_pos.file, first_pos.line
                );
                out.push(Diagnostic::error(
                    DiagnosticCode::DuplicateLabel,
                    &label.pos,
                    message,
                ));
                again.push((first, label.pos));
                continue;
            }
            if let Some(key) = &key {
                keys.bind(&label.value, key, out);
            }
            merged.index.insert(label.value.clone(), merged.acts.len());
            merged.acts.push(Act {
                label: label.value,
                pos: label.pos,
                variants,
                commands,
                group,
                key: key.map(|k| k.value),
                keywords,
            });
        }
    }
    let mut by_first: BTreeMap<usize, Vec<Pos>> = BTreeMap::new();
    for (first, pos) in again {
        by_first.entry(first).or_default().push(pos);
    }
    for (first, places) in by_first {
        let act = &merged.acts[first];
        let places: Vec<String> = places
            .iter()
            .map(|p| format!("{}:{}", p.file, p.line))
            .collect();
        let message = format!(
            "The label `{}` is used again at {}. Labels must be unique: rename one of the acts.",
            act.label,
            places.join(" and ")
        );
        out.push(Diagnostic::error(
            DiagnosticCode::DuplicateLabel,
            &act.pos,
            message,
        ));
    }
    merged
}

/// The act labels the pages use: every `data-act` value and `docent.trigger` literal must
/// name an act, and a triggered act must be one a kiosk may trigger (offered by some page's
/// `data-act`, or the idle act).
pub(super) fn check_page_labels(
    labels: PageLabels,
    config: &SiteConfig,
    merged: &mut Merged,
    out: &mut Vec<Diagnostic>,
) {
    let PageLabels {
        offered,
        triggered,
        languages,
    } = labels;
    check_reachable_languages(config, &languages, out);
    merged.page_languages = languages;
    let known = |label: &str| merged.knows(label);
    for Located { value, pos } in &offered {
        if known(value) {
            continue;
        }
        let hint = did_you_mean(value, merged.index.keys().map(String::as_str));
        let message = format!(
            "This page triggers the act `{value}`, but no act has that label.{hint} Fix the \
             `data-act` value or add the act."
        );
        out.push(Diagnostic::error(DiagnosticCode::UnknownAct, pos, message));
    }
    let labels: BTreeSet<String> = offered.iter().map(|r| r.value.clone()).collect();
    for Located { value, pos } in &triggered {
        if !known(value) {
            let hint = did_you_mean(value, merged.index.keys().map(String::as_str));
            let message = format!(
                "This page script triggers the act `{value}`, but no act has that label.\
                 {hint} Fix the label in `docent.trigger(...)` or add the act."
            );
            out.push(Diagnostic::error(DiagnosticCode::UnknownAct, pos, message));
        } else if !labels.contains(value) && !config.kiosk_own_acts().any(|a| a == value) {
            let message = format!(
                "This page script triggers the act `{value}`, but no page offers it with \
                 `data-act`, so the touchscreen is refused it and nothing happens. Add a \
                 button with `data-act=\"{value}\"` to a page (it may be hidden: \
                 `<span data-act=\"{value}\" hidden></span>`), or trigger an act a page \
                 offers."
            );
            out.push(Diagnostic::error(
                DiagnosticCode::TriggerNotOffered,
                pos,
                message,
            ));
        }
    }
    merged.page_acts = labels.into_iter().collect();
    merged.page_offers = offered;
}
