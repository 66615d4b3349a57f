//! The days of an `open:` entry (`Mon-Fri`, `Sat, Sun`, `[Mon, Wed]`, `daily`): the one
//! grammar of weekdays, and what a museum author writes instead (`Mon to Fri`, `Mo-Fr`,
//! `weekdays`, a word processor's `–`) recognised so that the hint is the whole fix, never a
//! part of it (`Did you mean Mon?` for `Mon to Fri` would open on Mondays only).

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::diagnostic::Diagnostic;
use crate::model::Pos;
use crate::schedule::WEEKDAYS;
use crate::suggest::did_you_mean;

use super::{DAYS_USAGE, Reader, split_at_commas};

/// Dashes a word processor puts where the author typed `-`.
pub(super) const WORD_PROCESSOR_DASHES: [char; 4] = ['–', '—', '−', '‒'];

/// Words joining the first and last day of a range in prose (`Mon to Fri`, `Mo bis Fr`).
const RANGE_WORDS: [&str; 6] = [" to ", " till ", " until ", " through ", " thru ", " bis "];

impl Reader {
    /// `Mon-Fri`, `Sat, Sun`, `[Mon, Wed]`, `daily`: the weekday indexes, Monday 0.
    pub(super) fn days(&mut self, node: &Node) -> Option<Vec<usize>> {
        let parts: Vec<(String, Pos)> = match &node.kind {
            Kind::Seq(items) => (items.iter())
                .map(|item| {
                    let text = item.as_text().unwrap_or_default().to_owned();
                    (text, item.pos.clone())
                })
                .collect(),
            _ => match node.as_text() {
                Some(text) => split_at_commas(node, text),
                None => {
                    self.bad(node, DAYS_USAGE);
                    return None;
                }
            },
        };
        let mut days = Vec::new();
        for (part, pos) in parts {
            let part = part.trim();
            match days_of(part) {
                Some(some) => days.extend(some),
                None => {
                    let message = format!("{} {DAYS_USAGE}", mistake(part));
                    self.bad_at(&pos, &message, part);
                    return None;
                }
            }
        }
        days.sort_unstable();
        days.dedup();
        Some(days)
    }
}

/// The days of an entry as its author wrote them, for messages: `every day` for `daily`.
pub(super) fn days_as_written(node: &Node) -> String {
    let written = match &node.kind {
        Kind::Seq(items) => {
            let texts: Vec<&str> = items.iter().filter_map(Node::as_text).collect();
            texts.join(", ")
        }
        _ => node.as_text().unwrap_or_default().trim().to_owned(),
    };
    if written.eq_ignore_ascii_case("daily") {
        "every day".to_owned()
    } else {
        written
    }
}

/// One comma-separated part: `daily`, a day, or a range (which may run over the weekend:
/// `Fri-Mon` is Friday to Monday).
fn days_of(part: &str) -> Option<Vec<usize>> {
    if part.eq_ignore_ascii_case("daily") {
        return Some((0..7).collect());
    }
    let (first, last) = part.split_once('-').unwrap_or((part, part));
    let (first, last) = (weekday(first)?, weekday(last)?);
    let mut days = vec![first];
    let mut day = first;
    while day != last {
        day = (day + 1) % 7;
        days.push(day);
    }
    Some(days)
}

/// The first sentence of the message for a part that is no days: what was meant, whole.
fn mistake(part: &str) -> String {
    if let Some(dash) = part.chars().find(|c| WORD_PROCESSOR_DASHES.contains(c)) {
        let fixed = part.replace(WORD_PROCESSOR_DASHES, "-");
        let fix = canonical(&fixed).unwrap_or(fixed);
        return format!(
            "`{dash}` is a dash from a word processor, not the plain minus sign `-` (the key \
             next to 0) that joins a range of days: write `{fix}`."
        );
    }
    let lower = part.to_lowercase();
    let named = match lower.as_str() {
        "weekdays" | "weekday" | "workdays" | "working days" | "werktags" => Some("Mon-Fri"),
        "weekends" | "weekend" | "wochenende" => Some("Sat, Sun"),
        "everyday" | "every day" | "all days" | "all week" | "always" | "täglich" => Some("daily"),
        _ => None,
    };
    if let Some(fix) = named {
        return format!("Write `{fix}` for `{part}`: days are named one by one or as a range.");
    }
    let words = RANGE_WORDS.iter().find_map(|w| {
        let at = lower.find(w)?;
        Some((&part[..at], &part[at + w.len()..]))
    });
    if let Some((first, last)) = words
        && let (Some(first), Some(last)) = (any_day(first), any_day(last))
    {
        return format!(
            "Write a range of days with a hyphen: `{}-{}`.",
            WEEKDAYS[first], WEEKDAYS[last]
        );
    }
    if let Some(fix) = canonical(part) {
        return format!("Days are written by their first three English letters: `{fix}`.");
    }
    let (first, last) = part.split_once('-').unwrap_or((part, part));
    let word = [first, last].into_iter().find(|w| weekday(w).is_none());
    let hint = did_you_mean(&day_like(word.unwrap_or(part)), WEEKDAYS);
    format!("`{part}` is not a day Docent knows.{hint}")
}

/// `Mo-Fr`, `Montag`, `Sa`: the same days written as Docent reads them (`Mon-Fri`, `Mon`,
/// `Sat`), when every day in `part` is one [`any_day`] knows.
fn canonical(part: &str) -> Option<String> {
    match part.split_once('-') {
        Some((first, last)) => {
            let (first, last) = (any_day(first)?, any_day(last)?);
            Some(format!("{}-{}", WEEKDAYS[first], WEEKDAYS[last]))
        }
        None => any_day(part).map(|d| WEEKDAYS[d].to_owned()),
    }
}

/// A day as Docent reads it, or as people write it: the two-letter abbreviations (`Mo`, `Tu`,
/// `Di`, `Mi`, `Do`, `So`) and the German names.
fn any_day(word: &str) -> Option<usize> {
    if let Some(day) = weekday(word) {
        return Some(day);
    }
    let word = word.trim().to_lowercase();
    let table: [&[&str]; 7] = [
        &["mo", "montag"],
        &["tu", "di", "dienstag"],
        &["we", "mi", "mittwoch"],
        &["th", "do", "donnerstag"],
        &["fr", "freitag"],
        &["sa", "samstag", "sonnabend"],
        &["su", "so", "sonntag"],
    ];
    table
        .iter()
        .position(|names| names.contains(&word.as_str()))
}

impl Reader {
    /// `{ days: Sat, Sun, hours: ... }`: inside braces the comma ends the setting, so YAML
    /// made `days: Sat` and a setting `Sun`. The generic "not a setting" said of a day is
    /// replaced by what happened and the fix (quotes, or the entry on several lines).
    pub(super) fn explain_days_split_by_braces(&mut self, entry: &Node) {
        let Kind::Map(entries) = &entry.kind else {
            return;
        };
        for (key, value) in entries {
            let name = key.as_text().unwrap_or_default();
            if !matches!(value.kind, Kind::Null) || weekday(name).is_none() {
                continue;
            }
            let at_key = |d: &Diagnostic| {
                d.code == DiagnosticCode::ConfigUnknownKey
                    && *d.file == *key.pos.file
                    && (d.line, d.column) == (key.pos.line, key.pos.column)
            };
            let Some(found) = self.diagnostics.iter_mut().find(|d| at_key(d)) else {
                continue;
            };
            found.message = format!(
                "`{name}` is a day, but here it became a setting of its own: inside `{{ }}` a \
                 comma separates settings, so the days ended before `{name}`. Put the days in \
                 quotes, e.g. `days: \"Sat, Sun\"`, or write them as a list: `days: [Sat, Sun]`."
            );
        }
    }
}

/// `Mon` … `Sun` (any case, or the full English name): 0 for Monday.
fn weekday(word: &str) -> Option<usize> {
    let word = word.trim().to_ascii_lowercase();
    let short = word.get(..3)?;
    let full = [
        "monday",
        "tuesday",
        "wednesday",
        "thursday",
        "friday",
        "saturday",
        "sunday",
    ];
    let day = WEEKDAYS
        .iter()
        .position(|d| d.eq_ignore_ascii_case(short))?;
    (word.len() == 3 || word == full[day]).then_some(day)
}

/// A misspelt day as its first three letters, capitalised (`frday` → `Frd`), to be compared
/// with the day names.
fn day_like(word: &str) -> String {
    let mut letters = word.trim().chars().take(3);
    let first = letters.next().map(|c| c.to_ascii_uppercase());
    first
        .into_iter()
        .chain(letters.map(|c| c.to_ascii_lowercase()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_authors_write_instead_is_answered_with_the_whole_fix() {
        for (written, says) in [
            ("Mon to Fri", "with a hyphen: `Mon-Fri`"),
            ("mo bis fr", "with a hyphen: `Mon-Fri`"),
            ("Mon–Fri", "`–` is a dash from a word processor"),
            ("Mo-Fr", "`Mon-Fri`"),
            ("Sa", "`Sat`"),
            ("weekdays", "`Mon-Fri`"),
            ("Weekends", "`Sat, Sun`"),
            ("everyday", "`daily`"),
            ("Frday", "Did you mean `Fri`?"),
        ] {
            assert_eq!(days_of(written), None, "{written}");
            let message = mistake(written);
            assert!(message.contains(says), "{written}: {message}");
        }
        assert!(!mistake("Mon to Fri").contains("`Mon`"));
        assert!(mistake("Mon–Fri").contains("`Mon-Fri`"));
        assert_eq!(days_of("Fri-Mon"), Some(vec![4, 5, 6, 0]));
        assert_eq!(days_of("DAILY").map(|d| d.len()), Some(7));
    }
}
