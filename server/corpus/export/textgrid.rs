//! Praat's TextGrid, in the long text format Praat itself writes, UTF-8 without a byte-order
//! mark (a BOM breaks tgt, UTF-16 breaks pympi): the interval tiers (`speech`, `act`,
//! `commands`, `pages`) tiled from the session's start to its end with empty intervals between
//! the labelled ones, as Praat keeps them; `touches` and `marks` as point tiers (`TextTier`).
//! Then each codebook tier's annotations: its intervals, then its points (`situation-points`).
//! Times are seconds on the session clock, written exactly to the microsecond; a `"` in a
//! label is doubled, as Praat escapes it.

use std::fmt::Write;

use crate::export::tiers::{Annotation, IntervalTier, PointTier, Tiers};

/// The TextGrid of `tiers`.
pub fn write(tiers: &Tiers) -> Vec<u8> {
    let end = seconds(tiers.end_us);
    let count = 2 * tiers.speech.len() + tiers.commands.len() + tiers.pages.len();
    let coded: usize = (tiers.coded.iter())
        .map(|c| c.intervals.len() + c.points.len())
        .sum();
    let count = count + tiers.point_tiers().count() + coded;
    let mut out = String::with_capacity(4096);
    out.push_str("File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\n");
    let _ = write!(
        out,
        "xmin = 0 \nxmax = {end} \ntiers? <exists> \nsize = {count} \nitem []: \n"
    );
    let mut item = 0;
    let mut next = || {
        item += 1;
        item
    };
    for speech in &tiers.speech {
        interval_tier(&mut out, next(), &speech.speech, tiers.end_us);
        let labelled = (speech.speech.annotations.iter().zip(&speech.labels))
            .map(|(a, label)| Annotation {
                value: label.clone(),
                ..a.clone()
            })
            .collect();
        let act = IntervalTier {
            name: speech.act.clone(),
            annotations: labelled,
        };
        interval_tier(&mut out, next(), &act, tiers.end_us);
    }
    for tier in tiers.commands.iter().chain(&tiers.pages) {
        interval_tier(&mut out, next(), tier, tiers.end_us);
    }
    for tier in tiers.point_tiers() {
        point_tier(&mut out, next(), tier, &end);
    }
    for coded in &tiers.coded {
        for tier in &coded.intervals {
            interval_tier(&mut out, next(), tier, tiers.end_us);
        }
        for tier in &coded.points {
            point_tier(&mut out, next(), tier, &end);
        }
    }
    out.into_bytes()
}

/// Microseconds as seconds, exactly: `12.5`, `0.000528`, `3`.
pub fn seconds(us: u64) -> String {
    let (whole, fraction) = (us / 1_000_000, us % 1_000_000);
    if fraction == 0 {
        return whole.to_string();
    }
    let fraction = format!("{fraction:06}");
    format!("{whole}.{}", fraction.trim_end_matches('0'))
}

/// A text as Praat writes it: in double quotes, each `"` doubled.
fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// One interval tier, its gaps filled with empty intervals from 0 to `end_us`.
fn interval_tier(out: &mut String, item: usize, tier: &IntervalTier, end_us: u64) {
    let mut tiled: Vec<(u64, u64, &str)> = Vec::with_capacity(2 * tier.annotations.len() + 1);
    let mut cursor = 0;
    for a in &tier.annotations {
        if a.start_us > cursor {
            tiled.push((cursor, a.start_us, ""));
        }
        tiled.push((a.start_us, a.end_us, &a.value));
        cursor = a.end_us;
    }
    if cursor < end_us {
        tiled.push((cursor, end_us, ""));
    }
    let _ = write!(
        out,
        "    item [{item}]:\n        class = \"IntervalTier\" \n        name = {} \n        \
         xmin = 0 \n        xmax = {} \n        intervals: size = {} \n",
        quoted(&tier.name),
        seconds(end_us),
        tiled.len()
    );
    for (n, (start, end, text)) in tiled.into_iter().enumerate() {
        let _ = write!(
            out,
            "        intervals [{}]:\n            xmin = {} \n            xmax = {} \n            \
             text = {} \n",
            n + 1,
            seconds(start),
            seconds(end),
            quoted(text)
        );
    }
}

/// One point tier.
fn point_tier(out: &mut String, item: usize, tier: &PointTier, end: &str) {
    let _ = write!(
        out,
        "    item [{item}]:\n        class = \"TextTier\" \n        name = {} \n        \
         xmin = 0 \n        xmax = {end} \n        points: size = {} \n",
        quoted(&tier.name),
        tier.points.len()
    );
    for (n, point) in tier.points.iter().enumerate() {
        let _ = write!(
            out,
            "        points [{}]:\n            number = {} \n            mark = {} \n",
            n + 1,
            seconds(point.at_us),
            quoted(&point.value)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::timeline::{Timeline, Touch, Touched, Utterance};

    #[test]
    fn seconds_are_exact_to_the_microsecond() {
        assert_eq!(seconds(0), "0");
        assert_eq!(seconds(3_000_000), "3");
        assert_eq!(seconds(12_500_000), "12.5");
        assert_eq!(seconds(528), "0.000528");
    }

    #[test]
    fn interval_tiers_are_tiled_and_quotes_doubled() {
        let utterance = Utterance {
            start_us: 1_000_000,
            end_us: 2_000_000,
            text: "Say \"cheese\"".into(),
            label: "PHOTO".into(),
            source: docent_protocol::events::Source::Kiosk,
            variant: None,
            alternative: None,
            outcome: crate::export::timeline::Outcome::Done,
        };
        let touch = Touch {
            at_us: 500_000,
            what: Touched::Act {
                label: "PHOTO".into(),
            },
        };
        let timeline = Timeline {
            end_us: 3_000_000,
            utterances: vec![utterance],
            touches: vec![touch],
            ..Timeline::default()
        };
        let text = String::from_utf8(write(&Tiers::of(&timeline))).unwrap();
        assert!(text.starts_with("File type = \"ooTextFile\"\n"), "no BOM");
        assert!(
            text.contains("size = 6 \n"),
            "speech, act, commands, pages, touches, marks"
        );
        let speech = "        name = \"speech\" \n        xmin = 0 \n        xmax = 3 \n        \
                      intervals: size = 3 \n        intervals [1]:\n            xmin = 0 \n            \
                      xmax = 1 \n            text = \"\" \n        intervals [2]:\n            \
                      xmin = 1 \n            xmax = 2 \n            text = \"Say \"\"cheese\"\"\" \n";
        assert!(text.contains(speech), "{text}");
        assert!(
            text.contains("number = 0.5 \n            mark = \"PHOTO\" \n"),
            "{text}"
        );
    }
}
