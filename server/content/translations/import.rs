//! A table read back, checked against the bundle: which rows name a text, which originals
//! changed since the table was made, and which variants the table translates completely.
//! A translation must have as many texts as its original, so a variant with a text missing
//! keeps what it has (never a half list); every row left out is reported in words.
//!
//! A translation that starts with `=`, `@`, a tab or a carriage return is refused: a
//! spreadsheet runs such a cell as a formula (CSV injection), and a spoken text never starts
//! so. The `'` Docent's own CSV puts before such a cell is already gone (`csv.rs`); a text
//! starting with `-` or `+` (`-20 % today`) is a text and is imported.

use std::collections::BTreeMap;

use crate::language::LANGUAGE_USAGE;
use crate::spreadsheet::formula_start;
use crate::{Bundle, Language, Languages};

use super::table::TextKey;
use super::{Place, ReadTable};

/// What an import will do.
#[derive(Debug, Default)]
pub struct Plan {
    /// The translations to write, in the bundle's order.
    pub changes: Vec<Change>,
    /// Translations the table has exactly as the bundle already does.
    pub unchanged: usize,
    /// Everything reported: rows not imported, originals changed, incomplete variants.
    pub problems: Vec<String>,
}

/// One variant's whole translation to write.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Change {
    /// The act's index in the bundle.
    pub act: usize,
    /// The variant's name (`TextChild`).
    pub variant: String,
    /// The texts, one per alternative of the original.
    pub texts: Vec<String>,
    /// Where each text was read in the table, in the same order.
    pub places: Vec<Place>,
    /// Whether it replaces an existing list of that language.
    pub replaces: bool,
}

/// The language `written` names, if it is one the bundle's texts are translated into.
pub fn target_language(written: &str, languages: &Languages) -> Result<Language, String> {
    let Some(language) = Language::parse(written) else {
        return Err(format!(
            "`{written}` is not a language tag. {LANGUAGE_USAGE}"
        ));
    };
    let translated: Vec<&str> = languages
        .translated()
        .iter()
        .map(Language::as_str)
        .collect();
    let listed = languages.listed();
    let named = if translated.is_empty() {
        format!(
            "The bundle has no other language yet: add one to `languages:` in docent.yaml \
             (`languages: [{listed}, de]`)."
        )
    } else {
        format!("Name one it is translated into: {}.", translated.join(", "))
    };
    if language == *languages.default_language() {
        return Err(format!(
            "`{language}` is the bundle's default language: its texts are the originals \
             (`Text:`), not translations. {named}"
        ));
    }
    if !languages.translated().contains(&language) {
        let next = if translated.is_empty() {
            format!("(`languages: [{listed}, {language}]`).")
        } else {
            format!("first. {named}")
        };
        return Err(format!(
            "`{language}` is not one of the bundle's languages ({listed}). Add it to \
             `languages:` in docent.yaml {next}"
        ));
    }
    Ok(language)
}

/// A language's name in English for messages, or its tag in backticks.
pub fn language_name(language: &Language) -> String {
    const NAMES: [(&str, &str); 24] = [
        ("ar", "Arabic"),
        ("cs", "Czech"),
        ("da", "Danish"),
        ("de", "German"),
        ("el", "Greek"),
        ("en", "English"),
        ("es", "Spanish"),
        ("fi", "Finnish"),
        ("fr", "French"),
        ("hu", "Hungarian"),
        ("it", "Italian"),
        ("ja", "Japanese"),
        ("ko", "Korean"),
        ("nb", "Norwegian"),
        ("nl", "Dutch"),
        ("no", "Norwegian"),
        ("pl", "Polish"),
        ("pt", "Portuguese"),
        ("ru", "Russian"),
        ("sv", "Swedish"),
        ("tr", "Turkish"),
        ("uk", "Ukrainian"),
        ("zh", "Chinese"),
        ("la", "Latin"),
    ];
    let primary = language.as_str().split('-').next().unwrap_or_default();
    (NAMES.iter().find(|(tag, _)| *tag == primary))
        .map_or_else(|| format!("`{language}`"), |(_, name)| (*name).to_owned())
}

/// A variant's texts as the table gives them, by number.
struct Slots {
    /// Each alternative's translation and where it was read; `None` when missing or empty.
    texts: Vec<Option<(String, Place)>>,
    /// Some text was given twice, differently.
    conflicting: bool,
}

/// Checks `table` against `bundle` for `language` (already checked with
/// [`target_language`]).
pub fn plan(bundle: &Bundle, language: &Language, table: &ReadTable) -> Plan {
    let default = language_name(bundle.config.languages.default_language());
    let target = language_name(language);
    let mut plan = Plan {
        problems: table.notes.clone(),
        ..Plan::default()
    };
    // By (act index, variant index): the bundle's order.
    let mut slots: BTreeMap<(usize, usize), Slots> = BTreeMap::new();
    for entry in &table.entries {
        let at = entry.place;
        let Some(key) = TextKey::parse(&entry.key) else {
            plan.problems.push(format!(
                "{at}: `{}` is not a text key (keys look like LABEL/Variant/N, e.g. \
                 GREETING/Text/1); the row is not imported.",
                entry.key
            ));
            continue;
        };
        let Some(&act_index) = bundle.index.get(&key.label) else {
            plan.problems.push(format!(
                "{at}: {key}: the bundle has no act `{}` (renamed or removed since the table \
                 was made?); the row is not imported.",
                key.label
            ));
            continue;
        };
        let act = &bundle.acts[act_index];
        let Some(variant_index) = act.variants.iter().position(|v| v.name == key.variant) else {
            plan.problems.push(format!(
                "{at}: {key}: the act `{}` has no `{}`; the row is not imported.",
                key.label, key.variant
            ));
            continue;
        };
        let variant = &act.variants[variant_index];
        let count = variant.alternatives.len();
        if key.number > count {
            plan.problems.push(format!(
                "{at}: {key}: `{}` of `{}` has {count} text(s), so there is no number {}; the \
                 row is not imported.",
                key.variant, key.label, key.number
            ));
            continue;
        }
        let original = &variant.alternatives[key.number - 1].value;
        if let Some(source) = &entry.source
            && source != original
        {
            plan.problems.push(format!(
                "{at}: the {default} text of {key} changed since this table was made; check the \
                 translation (the table has \"{source}\", the bundle now \"{original}\")."
            ));
        }
        let slot = slots
            .entry((act_index, variant_index))
            .or_insert_with(|| Slots {
                texts: vec![None; count],
                conflicting: false,
            });
        if entry.translation.trim().is_empty() {
            let empty = match at {
                Place::Row(_) => "the cell is empty",
                Place::Line(_) => "its target is empty",
            };
            plan.problems.push(format!(
                "{at}: {key} has no {target} translation ({empty})."
            ));
            continue;
        }
        if let Some(start) = refused_start(&entry.translation) {
            plan.problems.push(format!(
                "{at}: the {target} translation of {key} starts with {start}, which a \
                 spreadsheet runs as a formula (a spoken text never starts so); it is not \
                 imported. Write the text without it."
            ));
            continue;
        }
        match &slot.texts[key.number - 1] {
            Some((first, first_at)) => {
                let differs = *first != entry.translation;
                slot.conflicting |= differs;
                let outcome = if differs {
                    "with another translation, so neither is imported"
                } else {
                    "with the same translation"
                };
                plan.problems.push(format!(
                    "{at}: {key} is given a second time (first at {first_at}) {outcome}."
                ));
            }
            None => slot.texts[key.number - 1] = Some((entry.translation.clone(), at)),
        }
    }
    for ((act_index, variant_index), slot) in slots {
        settle(
            bundle,
            language,
            (act_index, variant_index),
            slot,
            &target,
            &mut plan,
        );
    }
    plan
}

/// The start of `translation` that makes it a formula to a spreadsheet, in words, unless it
/// is `-` or `+`, with which a text may start.
fn refused_start(translation: &str) -> Option<&'static str> {
    match formula_start(translation)? {
        '=' => Some("`=`"),
        '@' => Some("`@`"),
        '\t' => Some("a tab"),
        '\r' => Some("a carriage return"),
        _ => None,
    }
}

/// One variant's slots become a change, an unchanged translation or a problem.
fn settle(
    bundle: &Bundle,
    language: &Language,
    (act_index, variant_index): (usize, usize),
    slot: Slots,
    target: &str,
    plan: &mut Plan,
) {
    let act = &bundle.acts[act_index];
    let variant = &act.variants[variant_index];
    let existing = variant.translations.get(language);
    let keeps = if existing.is_some() {
        format!("keeps its current {target} texts")
    } else {
        "stays untranslated".to_owned()
    };
    let name = format!("{}/{}", act.label, variant.name);
    if slot.conflicting {
        plan.problems.push(format!(
            "{name} {keeps}: the table gives one of its texts twice, differently."
        ));
        return;
    }
    let given: Vec<usize> = (slot.texts.iter().enumerate())
        .filter(|(_, t)| t.is_some())
        .map(|(i, _)| i + 1)
        .collect();
    let count = slot.texts.len();
    if given.is_empty() {
        return; // every row empty: each already reported
    }
    if given.len() < count {
        let missing: Vec<String> = (1..=count)
            .filter(|n| !given.contains(n))
            .map(|n| format!("{name}/{n}"))
            .collect();
        plan.problems.push(format!(
            "{name} {keeps}: it has {count} texts, and a translation needs all of them, but the \
             table has none for {}.",
            missing.join(", ")
        ));
        return;
    }
    let (texts, places): (Vec<String>, Vec<Place>) = slot.texts.into_iter().flatten().unzip();
    let same = existing.is_some_and(|e| {
        e.alternatives.len() == texts.len()
            && e.alternatives
                .iter()
                .zip(&texts)
                .all(|(a, t)| a.value == *t)
    });
    if same {
        plan.unchanged += 1;
    } else {
        plan.changes.push(Change {
            act: act_index,
            variant: variant.name.clone(),
            texts,
            places,
            replaces: existing.is_some(),
        });
    }
}
