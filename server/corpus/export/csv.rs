//! The CSV of a session's utterances and touches, one row each, for a spreadsheet, R or
//! pandas (and ELAN's CSV import): `start_s,end_s,source,act,variant,alternative,text,kind`,
//! times in seconds on the session clock (exact to the microsecond), sorted by start. The
//! researchers' annotations are rows too: source `annotation`, the code as `text`, the
//! codebook tier as `kind` (a point's end is its start). RFC 4180:
//! UTF-8 without a byte-order mark, lines ended by CRLF, a field with a comma, a quote or a
//! line break in double quotes with each `"` doubled. A cell that a spreadsheet would run as a
//! formula (a kiosk's refused label `=HYPERLINK(...)`) is written with a `'` before it
//! (`docent_content::spreadsheet`).

use crate::annotations::Annotation;
use crate::export::textgrid::seconds;
use crate::export::timeline::{Timeline, Touched};
use docent_content::spreadsheet::neutralise;

/// The header row.
pub const HEADER: [&str; 8] = [
    "start_s",
    "end_s",
    "source",
    "act",
    "variant",
    "alternative",
    "text",
    "kind",
];

/// The CSV of `timeline`'s utterances and touches, and of the `annotations`.
pub fn write(timeline: &Timeline, annotations: &[Annotation]) -> Vec<u8> {
    let mut rows: Vec<(u64, u8, [String; 8])> = Vec::new();
    for u in &timeline.utterances {
        let row = [
            seconds(u.start_us),
            seconds(u.end_us),
            u.source.as_str().to_owned(),
            u.label.clone(),
            u.variant.clone().unwrap_or_default(),
            u.alternative.map(|n| n.to_string()).unwrap_or_default(),
            u.text.clone(),
            "utterance".to_owned(),
        ];
        rows.push((u.start_us, 0, row));
    }
    for t in &timeline.touches {
        let (act, text) = match &t.what {
            Touched::Act { label } => (label.clone(), String::new()),
            Touched::Refused { label, code } => (label.clone(), format!("refused: {code}")),
            Touched::Page { page } => (String::new(), format!("page: {page}")),
        };
        let at = seconds(t.at_us);
        let none = String::new;
        let row = [
            at.clone(),
            at,
            "kiosk".to_owned(),
            act,
            none(),
            none(),
            text,
            "touch".to_owned(),
        ];
        rows.push((t.at_us, 1, row));
    }
    for a in annotations {
        let none = String::new;
        let row = [
            seconds(a.start_us),
            seconds(a.end_us),
            "annotation".to_owned(),
            none(),
            none(),
            none(),
            a.code.clone(),
            a.tier.clone(),
        ];
        rows.push((a.start_us, 2, row));
    }
    rows.sort_by_key(|(at, kind, _)| (*at, *kind));
    let mut out = String::with_capacity(64 * (rows.len() + 1));
    push_row(&mut out, HEADER.iter().copied());
    for (_, _, row) in &rows {
        push_row(&mut out, row.iter().map(String::as_str));
    }
    out.into_bytes()
}

fn push_row<'a>(out: &mut String, fields: impl Iterator<Item = &'a str>) {
    for (n, field) in fields.enumerate() {
        if n > 0 {
            out.push(',');
        }
        let field = neutralise(field);
        if field.contains([',', '"', '\n', '\r']) {
            out.push('"');
            out.push_str(&field.replace('"', "\"\""));
            out.push('"');
        } else {
            out.push_str(&field);
        }
    }
    out.push_str("\r\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::timeline::{Outcome, Touch, Utterance};

    #[test]
    fn rows_are_quoted_as_rfc_4180_says_and_sorted_by_start() {
        let utterance = Utterance {
            start_us: 2_000_000,
            end_us: 3_250_000,
            text: "Hello, \"friends\"\nand all".into(),
            label: "WELCOME".into(),
            source: docent_protocol::events::Source::Kiosk,
            variant: Some("Text".into()),
            alternative: Some(1),
            outcome: Outcome::Done,
        };
        let touch = Touch {
            at_us: 1_999_000,
            what: Touched::Act {
                label: "WELCOME".into(),
            },
        };
        let timeline = Timeline {
            utterances: vec![utterance],
            touches: vec![touch],
            ..Timeline::default()
        };
        let text = String::from_utf8(write(&timeline, &[])).unwrap();
        assert_eq!(
            text,
            "start_s,end_s,source,act,variant,alternative,text,kind\r\n\
             1.999,1.999,kiosk,WELCOME,,,,touch\r\n\
             2,3.25,kiosk,WELCOME,Text,1,\"Hello, \"\"friends\"\"\nand all\",utterance\r\n"
        );
    }
}
