//! The cells that refuse a whole import. A table edited in a spreadsheet can go wrong in ways
//! that leave every cell looking fine: a row sorted on its own, a cell deleted with "shift
//! cells up", a formula whose row moved (`#REF!`), a segment a CAT tool copied from the
//! source. Imported, such a table writes translations under the wrong acts over good ones, so
//! any of these refuses the table as a whole: the import names each cell (CSV: the row, the
//! cell as the spreadsheet calls it, and the file's line and column; XLIFF: the line of the
//! unit) with what to do, and writes nothing (docs/AUTHORING.md, "Working with a translator").
//!
//! An empty cell is not one of them: it is a text not translated yet, skipped.

use crate::spreadsheet::{error_value, formula_start};
use crate::{Bundle, Language};

use super::same::may_stay_the_same;
use super::table::TextKey;
use super::{Entry, Place};

/// Which cell of a row a message is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The key.
    Key,
    /// The original.
    Source,
    /// The translation.
    Target,
}

/// Where `part` of `entry` is, as a message starts: `5:3: row 4, cell C4` (CSV: the file's
/// line and the cell's column, then the spreadsheet's row and cell) or `9: unit KEY` (XLIFF:
/// the line of the unit).
pub fn at(entry: &Entry, part: Part) -> String {
    let Some(columns) = entry.columns else {
        return format!("{}: unit {}", entry.line, entry.key);
    };
    let column = match part {
        Part::Key => columns.key,
        Part::Source => columns.source.unwrap_or(columns.key),
        Part::Target => columns.target,
    };
    let row = match entry.place {
        Place::Row(row) | Place::Line(row) => row,
    };
    format!(
        "{}:{}: row {row}, cell {}{row}",
        entry.line,
        column + 1,
        letters(column)
    )
}

/// A 0-based column as a spreadsheet names it: A … Z, AA, AB …
fn letters(column: usize) -> String {
    let mut n = column + 1;
    let mut name = Vec::new();
    while n > 0 {
        let digit = u8::try_from((n - 1) % 26).unwrap_or_default();
        name.push(char::from(b'A' + digit));
        n = (n - 1) / 26;
    }
    name.iter().rev().collect()
}

/// Why `entry`'s translation (not empty) of `key`, whose original is `original`, cannot be
/// imported, if it cannot. `target` names the translations' language (`German`), `default`
/// the originals' (`English`).
pub fn target(
    entry: &Entry,
    key: &TextKey,
    original: &str,
    (default, target): (&str, &str),
) -> Option<String> {
    let here = at(entry, Part::Target);
    let translation = &entry.translation;
    if let Some(error) = error_value(translation) {
        return Some(format!(
            "{here}: the {target} translation of {key} is `{error}`, the error a spreadsheet \
             shows where a formula failed (often because a row or column it read was moved or \
             deleted), not a text. Type the translation itself into the cell, or paste it with \
             \"paste special → values only\"."
        ));
    }
    if let Some(start) = refused_start(translation) {
        return Some(format!(
            "{here}: the {target} translation of {key} starts with {start}, which a \
             spreadsheet runs as a formula (a spoken text never starts so). Write the text \
             without it."
        ));
    }
    if let Some(state) = &entry.unfinished {
        return Some(format!(
            "{here}: the target of {key} is marked state=\"{state}\": the CAT tool says it is \
             not translated yet, though it holds a text. Finish (confirm) the segment in the \
             CAT tool, or empty its target, and export the file from the tool again."
        ));
    }
    if translation.trim() == entry.key || is_place(translation) {
        return Some(format!(
            "{here}: the {target} cell of {key} holds `{}`, a key or the place of an original \
             (the `key` or `where` column), not a translation: the headings and the columns \
             under them look moved apart. Keep each heading above its own column, as Docent \
             wrote the table.",
            translation.trim()
        ));
    }
    let breaks = |t: &str| t.contains(['\n', '\r']);
    if breaks(translation) && !breaks(original) {
        return Some(format!(
            "{here}: the {target} translation of {key} has a line break, and its {default} \
             original has none: often two cells pasted into one, or Alt+Enter (Excel) or \
             Ctrl+Enter (LibreOffice) pressed by mistake. Remove the line break, and check \
             the rows below it."
        ));
    }
    if translation.trim() == original.trim() && !may_stay_the_same(original) {
        return Some(format!(
            "{here}: the {target} translation of {key} is its {default} original itself \
             (\"{original}\"): copied, not translated. Translate it, or empty the cell to leave \
             the text untranslated for now (a name or a number may stay the same)."
        ));
    }
    None
}

/// Whether `cell` is what the `where` column holds: an acts file and a line (`acts.yaml:3`).
fn is_place(cell: &str) -> bool {
    let Some((file, line)) = cell.trim().rsplit_once(':') else {
        return false;
    };
    let yaml = [".yaml", ".yml"]
        .iter()
        .any(|e| file.to_ascii_lowercase().ends_with(e));
    yaml && !line.is_empty() && line.bytes().all(|b| b.is_ascii_digit())
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

/// The bundle's translation into `language` of the text `key` names, if it has one.
pub fn existing<'b>(bundle: &'b Bundle, language: &Language, key: &str) -> Option<&'b str> {
    let key = TextKey::parse(key)?;
    let act = &bundle.acts[*bundle.index.get(&key.label)?];
    let variant = act.variants.iter().find(|v| v.name == key.variant)?;
    let translation = variant.translations.get(language)?;
    let text = translation.alternatives.get(key.number.checked_sub(1)?)?;
    Some(text.value.as_str())
}

/// Whether the translation of `entries[i]` is the one the bundle already has for the key of
/// the row above or below it (and not its own): the translations' column slid against the
/// keys (a cell deleted or inserted with "shift cells up/down", a column sorted on its own).
pub fn shifted(
    bundle: &Bundle,
    language: &Language,
    entries: &[Entry],
    i: usize,
    target: &str,
) -> Option<String> {
    let entry = &entries[i];
    let translation = entry.translation.trim();
    if translation.is_empty() || may_stay_the_same(translation) {
        return None;
    }
    if existing(bundle, language, &entry.key).is_some_and(|own| own.trim() == translation) {
        return None;
    }
    let neighbours = [i.checked_sub(1), i.checked_add(1)];
    let (neighbour, which) = neighbours
        .into_iter()
        .zip(["above", "below"])
        .filter_map(|(j, which)| Some((entries.get(j?)?, which)))
        .find(|(other, _)| {
            // Two rows with the same original may rightly share a translation.
            other.key != entry.key
                && other.source != entry.source
                && existing(bundle, language, &other.key).is_some_and(|t| t.trim() == translation)
        })?;
    Some(format!(
        "{}: the {target} cell of {} holds \"{translation}\", the bundle's translation of {}, \
         the row {which}: the translations look shifted against the keys by a row (a cell \
         deleted or inserted with \"shift cells up/down\", or one column sorted on its own). \
         Undo that in the spreadsheet so that each translation stands beside its own original.",
        at(entry, Part::Target),
        entry.key,
        neighbour.key
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::translations::Columns;

    #[test]
    fn the_place_of_an_original_is_told_from_a_text() {
        for place in ["acts.yaml:3", "tour/rooms.YML:120"] {
            assert!(is_place(place), "{place}");
        }
        for text in ["acts.yaml", "Open 10:00", "see acts.yaml: 3", "a.yaml:"] {
            assert!(!is_place(text), "{text}");
        }
    }

    #[test]
    fn columns_are_named_as_a_spreadsheet_does() {
        let names: Vec<String> = [0, 2, 25, 26, 27, 51, 52].map(letters).to_vec();
        assert_eq!(names, ["A", "C", "Z", "AA", "AB", "AZ", "BA"]);
    }

    #[test]
    fn a_cell_is_told_by_line_and_column_then_row_and_cell() {
        let entry = Entry {
            place: Place::Row(4),
            line: 6,
            columns: Some(Columns {
                key: 0,
                source: Some(1),
                target: 2,
            }),
            unfinished: None,
            key: "A/Text/1".to_owned(),
            source: None,
            translation: String::new(),
        };
        assert_eq!(at(&entry, Part::Target), "6:3: row 4, cell C4");
        assert_eq!(at(&entry, Part::Key), "6:1: row 4, cell A4");
        let unit = Entry {
            place: Place::Line(9),
            line: 9,
            columns: None,
            ..entry
        };
        assert_eq!(at(&unit, Part::Target), "9: unit A/Text/1");
    }
}
