//! A table read back, checked against the bundle: each row is matched by its key and its
//! original compared with the bundle's current one, and which variants the table translates
//! completely. Any cell that could put a text under the wrong act or write a text that is no
//! translation (`refuse.rs`) refuses the whole table ([`Plan::refusals`]): nothing is written.
//! An empty cell is a text not translated yet: reported, skipped. A translation must have as
//! many texts as its original, so a variant with a text missing keeps what it has (never a
//! half list).
//!
//! A translation that starts with `=`, `@`, a tab or a carriage return is refused: a
//! spreadsheet runs such a cell as a formula (CSV injection), and a spoken text never starts
//! so. The `'` Docent's own CSV puts before such a cell is already gone (`csv.rs`); a text
//! starting with `-` or `+` (`-20 % today`) is a text and is imported.

use std::collections::BTreeMap;

use crate::language::LANGUAGE_USAGE;
use crate::{Bundle, Language, Languages};

use super::refuse::{self, Part, at};
use super::table::TextKey;
use super::{Entry, Place, ReadTable};

/// What an import will do.
#[derive(Debug, Default)]
pub struct Plan {
    /// The translations to write, in the bundle's order.
    pub changes: Vec<Change>,
    /// Translations the table has exactly as the bundle already does.
    pub unchanged: usize,
    /// Everything reported: rows not translated yet, incomplete variants.
    pub problems: Vec<String>,
    /// Cells that refuse the whole table, each starting with its place (`5:3: row 4, cell
    /// C4: …`, `9: unit KEY: …`; the file's name goes before): when there is one, nothing may
    /// be written.
    pub refusals: Vec<String>,
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
    for (i, entry) in table.entries.iter().enumerate() {
        let Some((key, act_index, variant_index, original)) =
            matched(bundle, entry, &default, &mut plan.refusals)
        else {
            continue;
        };
        let count = bundle.acts[act_index].variants[variant_index]
            .alternatives
            .len();
        let slot = slots
            .entry((act_index, variant_index))
            .or_insert_with(|| Slots {
                texts: vec![None; count],
            });
        if entry.translation.trim().is_empty() {
            let empty = match entry.place {
                Place::Row(_) => "the cell is empty",
                Place::Line(_) => "its target is empty",
            };
            plan.problems.push(format!(
                "{}: {key} has no {target} translation ({empty}).",
                entry.place
            ));
            continue;
        }
        let refused = refuse::target(entry, &key, original, (&default, &target))
            .or_else(|| refuse::shifted(bundle, language, &table.entries, i, &target));
        if let Some(refusal) = refused {
            plan.refusals.push(refusal);
            continue;
        }
        match &slot.texts[key.number - 1] {
            Some((_, first_at)) => plan.refusals.push(format!(
                "{}: {key} is given a second time (first in {first_at}): a row copied or \
                 moved in the spreadsheet. Keep one row for each key and delete the other.",
                at(entry, Part::Key)
            )),
            None => slot.texts[key.number - 1] = Some((entry.translation.clone(), entry.place)),
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

/// The text `entry` names, as (key, act index, variant index, the bundle's original), if
/// its key is one of the bundle's and its original the bundle's current one; else why not is
/// added to `refusals` (nothing for a row with neither key nor translation: a remark).
fn matched<'b>(
    bundle: &'b Bundle,
    entry: &Entry,
    default: &str,
    refusals: &mut Vec<String>,
) -> Option<(TextKey, usize, usize, &'b str)> {
    let here = at(entry, Part::Key);
    let again = "Export the table again and copy the translations into it, or correct the key \
                 as Docent wrote it";
    if entry.key.is_empty() {
        if !entry.translation.trim().is_empty() {
            refusals.push(format!(
                "{here}: this row has a translation but no key: the rows or columns look \
                 shifted in the spreadsheet. Undo the move, so that each translation stands in \
                 the row of its key and original."
            ));
        }
        return None;
    }
    let Some(key) = TextKey::parse(&entry.key) else {
        refusals.push(format!(
            "{here}: `{}` is not a text key (keys look like LABEL/Variant/N, e.g. \
             GREETING/Text/1): the columns look shifted, or the key was edited. Keep the `key` \
             column as Docent wrote it.",
            entry.key
        ));
        return None;
    };
    let stale =
        |why: String| format!("{here}: {key}: {why}; the table is older than the bundle. {again}.");
    let Some(&act_index) = bundle.index.get(&key.label) else {
        refusals.push(stale(format!(
            "the bundle has no act `{}` (renamed or removed since the table was made?)",
            key.label
        )));
        return None;
    };
    let act = &bundle.acts[act_index];
    let Some(variant_index) = act.variants.iter().position(|v| v.name == key.variant) else {
        let why = format!("the act `{}` has no `{}`", key.label, key.variant);
        refusals.push(stale(why));
        return None;
    };
    let count = act.variants[variant_index].alternatives.len();
    if key.number > count {
        refusals.push(stale(format!(
            "`{}` of `{}` has {count} text(s), so there is no number {}",
            key.variant, key.label, key.number
        )));
        return None;
    }
    let original = act.variants[variant_index].alternatives[key.number - 1]
        .value
        .as_str();
    match &entry.source {
        Some(source) if !same_text(source, original) => {
            refusals.push(format!(
                "{}: the {default} original of {key} in the table is \"{source}\", the bundle's \
                 is \"{original}\": the row was moved or sorted apart from its key, or the \
                 original changed since the table was made. Put the row back beside its key, or \
                 export the table again and check this translation against the new original.",
                at(entry, Part::Source)
            ));
            None
        }
        None => {
            refusals.push(format!(
                "{here}: {key} has no {default} original (`<source>`), so Docent cannot check \
                 that the translation belongs to it. Keep each unit's source as exported."
            ));
            None
        }
        Some(_) => Some((key, act_index, variant_index, original)),
    }
}

/// Whether a table's cell holds `original`: the same but for spaces at either end and the
/// CRLF line breaks some spreadsheets save inside a cell.
fn same_text(cell: &str, original: &str) -> bool {
    cell.trim().replace("\r\n", "\n") == original.trim().replace("\r\n", "\n")
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
