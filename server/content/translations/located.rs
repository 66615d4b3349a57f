//! The in-memory load's diagnostics traced back to the table. A diagnostic inside a text the
//! import wrote is told by that text's row (CSV) or unit line (XLIFF) and key, in the
//! diagnostic's own words: the line of an acts file as it would be after the import exists
//! only in memory, so it would send the translator nowhere.

use std::collections::BTreeMap;
use std::ops::Range;

use crate::Diagnostic;

use super::Place;

/// One text the import writes, and where it is in its edited acts file.
#[derive(Clone, Debug)]
pub struct WrittenText {
    /// The acts file, as diagnostics name it.
    pub file: String,
    /// Its bytes in the edited file, quotes included.
    pub range: Range<usize>,
    /// The index of its change in the changes written.
    pub change: usize,
    /// Its key (`GREETING/Text/2`).
    pub key: String,
    /// Where the table has it.
    pub place: Place,
}

/// The written text `diagnostic` points into, if any. `files` are the edited acts files' texts.
pub fn written_text_of<'a>(
    diagnostic: &Diagnostic,
    files: &BTreeMap<String, String>,
    written: &'a [WrittenText],
) -> Option<&'a WrittenText> {
    let text = files.get(&diagnostic.file)?;
    let at = offset_of(text, diagnostic.line, diagnostic.column)?;
    written
        .iter()
        .find(|w| w.file == diagnostic.file && w.range.contains(&at))
}

/// The byte offset of 1-based `line` and `column` (in characters) in `text`.
fn offset_of(text: &str, line: u32, column: u32) -> Option<usize> {
    let index = usize::try_from(line).ok()?.checked_sub(1)?;
    let start = if index == 0 {
        0
    } else {
        text.match_indices('\n').nth(index - 1)?.0 + 1
    };
    let skip = usize::try_from(column).ok()?.checked_sub(1)?;
    let rest = text.get(start..)?;
    match rest.char_indices().nth(skip) {
        Some((at, _)) => Some(start + at),
        None => Some(text.len()),
    }
}

/// `row 12 (GOODBYE/Text/2): error[speech-placeholder]: …` and, for an error, what became of
/// the variant (`outcome`).
pub fn told_by_row(diagnostic: &Diagnostic, text: &WrittenText, outcome: Option<&str>) -> String {
    let kind = diagnostic.severity;
    let mut said = format!(
        "{} ({}): {kind}[{}]: {}",
        text.place, text.key, diagnostic.code, diagnostic.message
    );
    if let Some(outcome) = outcome {
        said.push(' ');
        said.push_str(outcome);
    }
    said
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_and_column_in_characters_is_a_byte_offset() {
        let text = "a\nÄb{x}\n";
        assert_eq!(offset_of(text, 1, 1), Some(0));
        assert_eq!(offset_of(text, 2, 1), Some(2));
        assert_eq!(offset_of(text, 2, 3), Some(5), "Ä is two bytes");
        assert_eq!(offset_of(text, 4, 1), None);
    }

    #[test]
    fn a_diagnostic_is_found_in_the_text_that_holds_it() {
        let files = BTreeMap::from([("acts.yaml".to_owned(), "- A: x\n  B: [y {z}]\n".to_owned())]);
        let written = [WrittenText {
            file: "acts.yaml".to_owned(),
            range: 13..18,
            change: 0,
            key: "A/B/1".to_owned(),
            place: Place::Row(3),
        }];
        let pos = crate::Pos::new("acts.yaml", 2, 10);
        let inside = Diagnostic::error(crate::DiagnosticCode::SpeechPlaceholder, &pos, "`{z}` …");
        let found = written_text_of(&inside, &files, &written).expect("in the text");
        assert_eq!(
            told_by_row(&inside, found, Some("Not imported.")),
            "row 3 (A/B/1): error[speech-placeholder]: `{z}` … Not imported."
        );
        let outside = Diagnostic::error(
            crate::DiagnosticCode::BadValue,
            &crate::Pos::new("acts.yaml", 1, 3),
            "",
        );
        assert!(written_text_of(&outside, &files, &written).is_none());
    }
}
