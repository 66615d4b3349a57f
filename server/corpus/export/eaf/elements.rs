//! The fixed parts of an EAF as ELAN writes them, and the elements written over and over:
//! linguistic types, the language and constraints, the controlled vocabulary, one annotation;
//! with the text and date forms XML and ELAN need.

use std::io;

use quick_xml::events::BytesText;

use super::Out;

/// The one language of the vocabulary: undetermined.
const LANGUAGE: &str = "und";
/// The vocabulary of act labels.
const ACT_LABELS: &str = "act-labels";
/// Linguistic types: utterances, act labels, commands and pages, touches and marks. Named
/// apart from every tier, since all names may share one `xsd:ID` space.
pub(super) const UTTERANCE_TYPE: &str = "utterance";
pub(super) const LABEL_TYPE: &str = "act-label";
pub(super) const EVENT_TYPE: &str = "event";
pub(super) const INSTANT_TYPE: &str = "instant";

/// The four constraints ELAN writes into every file, with its own descriptions.
const CONSTRAINTS: [(&str, &str); 4] = [
    (
        "Time_Subdivision",
        "Time subdivision of parent annotation's time interval, no time gaps allowed within \
         this interval",
    ),
    (
        "Symbolic_Subdivision",
        "Symbolic subdivision of a parent annotation. Annotations refering to the same parent \
         are ordered",
    ),
    (
        "Symbolic_Association",
        "1-1 association with a parent annotation",
    ),
    (
        "Included_In",
        "Time alignable annotations within the parent annotation's time interval, gaps are \
         allowed",
    ),
];

/// The language of the vocabulary, and the four constraints ELAN always writes.
pub(super) fn language_and_constraints(w: &mut Out) -> io::Result<()> {
    w.create_element("LANGUAGE")
        .with_attributes([
            ("LANG_DEF", "http://cdb.iso.org/lg/CDB-00130975-001"),
            ("LANG_ID", LANGUAGE),
            ("LANG_LABEL", "undetermined (und)"),
        ])
        .write_empty()?;
    for (stereotype, description) in CONSTRAINTS {
        w.create_element("CONSTRAINT")
            .with_attributes([("DESCRIPTION", description), ("STEREOTYPE", stereotype)])
            .write_empty()?;
    }
    Ok(())
}

/// `<ANNOTATION><KIND ...><ANNOTATION_VALUE>value</ANNOTATION_VALUE></KIND></ANNOTATION>`
pub(super) fn annotation(
    w: &mut Out,
    kind: &str,
    attributes: &[(&str, String)],
    value: &str,
) -> io::Result<()> {
    w.create_element("ANNOTATION").write_inner_content(|w| {
        let attributes = attributes.iter().map(|(k, v)| (*k, v.as_str()));
        w.create_element(kind)
            .with_attributes(attributes)
            .write_inner_content(|w| {
                w.create_element("ANNOTATION_VALUE")
                    .write_text_content(BytesText::new(value))?;
                Ok(())
            })?;
        Ok(())
    })?;
    Ok(())
}

/// The linguistic type of a codebook tier's annotations, and its vocabulary: named apart from
/// every tier (`codebook.rs` keeps tier names off these prefixes).
pub(super) fn coded_type(tier: &str) -> String {
    format!("coded-{tier}")
}

/// The vocabulary of a codebook tier's codes.
pub(super) fn coded_vocabulary(tier: &str) -> String {
    format!("codebook-{tier}")
}

/// The id of a codebook tier's `n`th code (from 1).
pub(super) fn coded_entry(tier: &str, n: usize) -> String {
    format!("cveid_{tier}_{n}")
}

/// The linguistic types of the codebook tiers: time-aligned, each with its vocabulary.
pub(super) fn coded_types<'a>(w: &mut Out, tiers: impl Iterator<Item = &'a str>) -> io::Result<()> {
    for tier in tiers {
        w.create_element("LINGUISTIC_TYPE")
            .with_attributes([
                ("CONTROLLED_VOCABULARY_REF", coded_vocabulary(tier).as_str()),
                ("GRAPHIC_REFERENCES", "false"),
                ("LINGUISTIC_TYPE_ID", coded_type(tier).as_str()),
                ("TIME_ALIGNABLE", "true"),
            ])
            .write_empty()?;
    }
    Ok(())
}

/// A codebook tier's vocabulary: its codes.
pub(super) fn coded_codes(w: &mut Out, tier: &str, codes: &[String]) -> io::Result<()> {
    let entries = (codes.iter().enumerate()).map(|(n, code)| (coded_entry(tier, n + 1), code));
    let description = format!("The codes of the codebook tier {tier} (docent.yaml)");
    vocabulary(w, &coded_vocabulary(tier), &description, entries)
}

fn vocabulary<'a>(
    w: &mut Out,
    id: &str,
    description: &str,
    entries: impl Iterator<Item = (String, &'a String)>,
) -> io::Result<()> {
    w.create_element("CONTROLLED_VOCABULARY")
        .with_attribute(("CV_ID", id))
        .write_inner_content(|w| {
            w.create_element("DESCRIPTION")
                .with_attribute(("LANG_REF", LANGUAGE))
                .write_text_content(BytesText::new(description))?;
            for (entry, value) in entries {
                w.create_element("CV_ENTRY_ML")
                    .with_attribute(("CVE_ID", entry.as_str()))
                    .write_inner_content(|w| {
                        w.create_element("CVE_VALUE")
                            .with_attribute(("LANG_REF", LANGUAGE))
                            .write_text_content(BytesText::new(value))?;
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

pub(super) fn linguistic_types(w: &mut Out) -> io::Result<()> {
    for id in [UTTERANCE_TYPE, LABEL_TYPE, EVENT_TYPE, INSTANT_TYPE] {
        let mut element = w.create_element("LINGUISTIC_TYPE");
        if id == LABEL_TYPE {
            element = element.with_attributes([
                ("CONSTRAINTS", "Symbolic_Association"),
                ("CONTROLLED_VOCABULARY_REF", ACT_LABELS),
            ]);
        }
        let alignable = if id == LABEL_TYPE { "false" } else { "true" };
        element
            .with_attributes([
                ("GRAPHIC_REFERENCES", "false"),
                ("LINGUISTIC_TYPE_ID", id),
                ("TIME_ALIGNABLE", alignable),
            ])
            .write_empty()?;
    }
    Ok(())
}

pub(super) fn controlled_vocabulary(w: &mut Out, entries: &[String]) -> io::Result<()> {
    let entries =
        (entries.iter().enumerate()).map(|(n, label)| (format!("cveid_{}", n + 1), label));
    let description = "The labels of the acts of the session's bundle (docent)";
    vocabulary(w, ACT_LABELS, description, entries)
}

/// The manifest's `2026-11-22T21:38:37.629Z` as ELAN writes a date: `2026-11-22T21:38:37+00:00`.
pub(super) fn eaf_date(time: &str) -> String {
    let seconds = time.get(..19).unwrap_or("1970-01-01T00:00:00");
    format!("{seconds}+00:00")
}

/// `text` with the characters XML 1.0 cannot hold (control characters other than tab, line
/// feed and carriage return; U+FFFE, U+FFFF) replaced by U+FFFD, counted in `replaced`.
pub(super) fn xml_text(text: &str, replaced: &mut usize) -> String {
    let forbidden = |c: char| {
        (c < ' ' && !matches!(c, '\t' | '\n' | '\r')) || matches!(c, '\u{FFFE}' | '\u{FFFF}')
    };
    if !text.contains(forbidden) {
        return text.to_owned();
    }
    text.chars()
        .map(|c| {
            if forbidden(c) {
                *replaced += 1;
                '\u{FFFD}'
            } else {
                c
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn characters_xml_cannot_hold_are_replaced_and_counted() {
        let mut replaced = 0;
        assert_eq!(xml_text("tab\tand\nline", &mut replaced), "tab\tand\nline");
        assert_eq!(
            xml_text("bell\u{7} and \u{FFFF}", &mut replaced),
            "bell\u{FFFD} and \u{FFFD}"
        );
        assert_eq!(replaced, 2);
    }

    #[test]
    fn the_date_is_the_sessions_start_as_elan_writes_dates() {
        assert_eq!(
            eaf_date("2026-11-22T21:38:37.629Z"),
            "2026-11-22T21:38:37+00:00"
        );
    }
}
