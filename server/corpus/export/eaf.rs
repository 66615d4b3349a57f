//! ELAN's EAF 3.0, written as ELAN 6.9 writes it (`shared/notes/corpus-formats.md`): the
//! schema's element order (`HEADER`, `TIME_ORDER`, `TIER`s, `LINGUISTIC_TYPE`s, `LANGUAGE`,
//! the four `CONSTRAINT`s ELAN always writes, `CONTROLLED_VOCABULARY`), times in milliseconds
//! on the session clock, one `xsd:ID` space (time slots `ts1`..., annotations `a1`...,
//! vocabulary entries `cveid_1`..., the language `und`, each kind of name distinct from the
//! others). The `act` tiers are `Symbolic_Association` children of their `speech` tier: one
//! `REF_ANNOTATION` per utterance, its `CVE_REF` naming the act's label in the vocabulary.
//! Points (touches, marks) are 1 ms annotations, since ELAN has no point tiers. No media yet:
//! the `HEADER` has no `MEDIA_DESCRIPTOR`.

use std::io;

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesText, Event};

use crate::corpus::export::tiers::{Annotation, MIN_INTERVAL_US, Tiers};

/// The schema ELAN names in every file it writes.
const SCHEMA: &str = "http://www.mpi.nl/tools/elan/EAFv3.0.xsd";
/// The one language of the vocabulary: undetermined.
const LANGUAGE: &str = "und";
/// The vocabulary of act labels.
const ACT_LABELS: &str = "act-labels";
/// Linguistic types: utterances, act labels, commands and pages, touches and marks. Named
/// apart from every tier, since all names may share one `xsd:ID` space.
const UTTERANCE_TYPE: &str = "utterance";
const LABEL_TYPE: &str = "act-label";
const EVENT_TYPE: &str = "event";
const INSTANT_TYPE: &str = "instant";

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

/// What the header says about the session.
pub struct Header<'a> {
    /// The session's start (RFC 3339), the document's `DATE`: the same session gives the same
    /// file.
    pub date: &'a str,
    /// The session's name.
    pub session: &'a str,
    /// The Docent that recorded it.
    pub docent: &'a str,
}

/// An annotation that has its own times, in file order.
struct Aligned<'a> {
    tier: usize,
    start_ms: u64,
    end_ms: u64,
    value: &'a str,
}

/// A tier in file order.
struct TierOut<'a> {
    name: &'a str,
    kind: &'a str,
    /// The parent of an act tier, with its labels.
    parent: Option<(&'a str, &'a [String])>,
}

/// The EAF of `tiers`, with `vocabulary` (sorted act labels); and how many characters that
/// XML cannot hold were replaced.
pub fn write(tiers: &Tiers, vocabulary: &[String], header: &Header) -> (Vec<u8>, usize) {
    let (out_tiers, aligned) = layout(tiers);
    let mut replaced = 0;
    let mut clean = |text: &str| xml_text(text, &mut replaced);
    // ELAN numbers time slots in time order.
    let mut order: Vec<usize> = (0..2 * aligned.len()).collect();
    let boundary = |i: usize| match i % 2 {
        0 => aligned[i / 2].start_ms,
        _ => aligned[i / 2].end_ms,
    };
    order.sort_by_key(|&i| boundary(i));
    let mut slot = vec![0; order.len()];
    for (n, &i) in order.iter().enumerate() {
        slot[i] = n + 1;
    }
    let labels = tiers.speech.iter().map(|s| s.labels.len()).sum::<usize>();
    let last_id = aligned.len() + labels;
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 4);
    let written: io::Result<()> = (|| {
        w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
        let root = w.create_element("ANNOTATION_DOCUMENT").with_attributes([
            ("AUTHOR", ""),
            ("DATE", &eaf_date(header.date)),
            ("FORMAT", "3.0"),
            ("VERSION", "3.0"),
            ("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance"),
            ("xsi:noNamespaceSchemaLocation", SCHEMA),
        ]);
        root.write_inner_content(|w| {
            let head = [("MEDIA_FILE", ""), ("TIME_UNITS", "milliseconds")];
            w.create_element("HEADER")
                .with_attributes(head)
                .write_inner_content(|w| {
                    let properties = [
                        ("docent-session", clean(header.session)),
                        ("docent-version", clean(header.docent)),
                        ("lastUsedAnnotationId", last_id.to_string()),
                    ];
                    for (name, value) in properties {
                        w.create_element("PROPERTY")
                            .with_attribute(("NAME", name))
                            .write_text_content(BytesText::new(&value))?;
                    }
                    Ok(())
                })?;
            w.create_element("TIME_ORDER").write_inner_content(|w| {
                for (n, &i) in order.iter().enumerate() {
                    w.create_element("TIME_SLOT")
                        .with_attribute(("TIME_SLOT_ID", format!("ts{}", n + 1).as_str()))
                        .with_attribute(("TIME_VALUE", boundary(i).to_string().as_str()))
                        .write_empty()?;
                }
                Ok(())
            })?;
            let mut next_aligned = 0;
            let mut next_ref = aligned.len();
            for (t, tier) in out_tiers.iter().enumerate() {
                let mut element = w.create_element("TIER");
                element = element.with_attribute(("LINGUISTIC_TYPE_REF", tier.kind));
                if let Some((parent, _)) = tier.parent {
                    element = element.with_attribute(("PARENT_REF", parent));
                }
                let element = element.with_attribute(("TIER_ID", tier.name));
                let first = next_aligned;
                let mine = aligned[first..].iter().take_while(|a| a.tier == t).count();
                let refs = tier.parent.map_or(0, |(_, labels)| labels.len());
                if mine + refs == 0 {
                    element.write_empty()?;
                    continue;
                }
                element.write_inner_content(|w| {
                    for (i, a) in aligned[first..first + mine].iter().enumerate() {
                        let id = first + i;
                        let attributes = [
                            ("ANNOTATION_ID", format!("a{}", id + 1)),
                            ("TIME_SLOT_REF1", format!("ts{}", slot[2 * id])),
                            ("TIME_SLOT_REF2", format!("ts{}", slot[2 * id + 1])),
                        ];
                        annotation(w, "ALIGNABLE_ANNOTATION", &attributes, &clean(a.value))?;
                    }
                    if let Some((_, labels)) = tier.parent {
                        // The parent's annotations are the ones just before this tier.
                        let parents = first - labels.len();
                        for (i, label) in labels.iter().enumerate() {
                            next_ref += 1;
                            let cve = vocabulary.binary_search(label).map_or(0, |n| n + 1);
                            let attributes = [
                                ("ANNOTATION_ID", format!("a{next_ref}")),
                                ("ANNOTATION_REF", format!("a{}", parents + i + 1)),
                                ("CVE_REF", format!("cveid_{cve}")),
                            ];
                            annotation(w, "REF_ANNOTATION", &attributes, &clean(label))?;
                        }
                    }
                    Ok(())
                })?;
                next_aligned += mine;
            }
            linguistic_types(w)?;
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
            let entries: Vec<String> = vocabulary.iter().map(|l| clean(l)).collect();
            controlled_vocabulary(w, &entries)
        })?;
        Ok(())
    })();
    // Writing into a Vec cannot fail.
    debug_assert!(written.is_ok(), "{written:?}");
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    (bytes, replaced)
}

/// The tiers in file order, and every time-aligned annotation in file order.
fn layout(tiers: &Tiers) -> (Vec<TierOut<'_>>, Vec<Aligned<'_>>) {
    let mut out = Vec::new();
    let mut aligned = Vec::new();
    for s in &tiers.speech {
        let name = s.speech.name.as_str();
        add(
            &mut out,
            &mut aligned,
            name,
            UTTERANCE_TYPE,
            None,
            spans(&s.speech.annotations),
        );
        let parent = Some((name, s.labels.as_slice()));
        add(
            &mut out,
            &mut aligned,
            &s.act,
            LABEL_TYPE,
            parent,
            Vec::new(),
        );
    }
    for tier in tiers.commands.iter().chain(&tiers.pages) {
        add(
            &mut out,
            &mut aligned,
            &tier.name,
            EVENT_TYPE,
            None,
            spans(&tier.annotations),
        );
    }
    for tier in tiers.point_tiers() {
        let points = (tier.points.iter())
            .map(|p| (p.at_us, p.at_us + MIN_INTERVAL_US, p.value.as_str()))
            .collect();
        add(
            &mut out,
            &mut aligned,
            &tier.name,
            INSTANT_TYPE,
            None,
            points,
        );
    }
    (out, aligned)
}

/// An annotation's start, end and value, in microseconds.
type Span<'a> = (u64, u64, &'a str);

fn spans(annotations: &[Annotation]) -> Vec<Span<'_>> {
    (annotations.iter())
        .map(|a| (a.start_us, a.end_us, a.value.as_str()))
        .collect()
}

/// Adds a tier and its annotations, in milliseconds (rounded down: a 1 ms interval stays one).
fn add<'a>(
    out: &mut Vec<TierOut<'a>>,
    aligned: &mut Vec<Aligned<'a>>,
    name: &'a str,
    kind: &'a str,
    parent: Option<(&'a str, &'a [String])>,
    spans: Vec<Span<'a>>,
) {
    let tier = out.len();
    out.push(TierOut { name, kind, parent });
    aligned.extend(spans.into_iter().map(|(start_us, end_us, value)| Aligned {
        tier,
        start_ms: start_us / 1000,
        end_ms: end_us / 1000,
        value,
    }));
}

/// `<ANNOTATION><KIND ...><ANNOTATION_VALUE>value</ANNOTATION_VALUE></KIND></ANNOTATION>`
fn annotation(
    w: &mut Writer<Vec<u8>>,
    kind: &str,
    attributes: &[(&str, String); 3],
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

fn linguistic_types(w: &mut Writer<Vec<u8>>) -> io::Result<()> {
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

fn controlled_vocabulary(w: &mut Writer<Vec<u8>>, entries: &[String]) -> io::Result<()> {
    w.create_element("CONTROLLED_VOCABULARY")
        .with_attribute(("CV_ID", ACT_LABELS))
        .write_inner_content(|w| {
            w.create_element("DESCRIPTION")
                .with_attribute(("LANG_REF", LANGUAGE))
                .write_text_content(BytesText::new(
                    "The labels of the acts of the session's bundle (docent)",
                ))?;
            for (n, label) in entries.iter().enumerate() {
                w.create_element("CV_ENTRY_ML")
                    .with_attribute(("CVE_ID", format!("cveid_{}", n + 1).as_str()))
                    .write_inner_content(|w| {
                        w.create_element("CVE_VALUE")
                            .with_attribute(("LANG_REF", LANGUAGE))
                            .write_text_content(BytesText::new(label))?;
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

/// The manifest's `2026-11-22T21:38:37.629Z` as ELAN writes a date: `2026-11-22T21:38:37+00:00`.
fn eaf_date(time: &str) -> String {
    let seconds = time.get(..19).unwrap_or("1970-01-01T00:00:00");
    format!("{seconds}+00:00")
}

/// `text` with the characters XML 1.0 cannot hold (control characters other than tab, line
/// feed and carriage return; U+FFFE, U+FFFF) replaced by U+FFFD, counted in `replaced`.
fn xml_text(text: &str, replaced: &mut usize) -> String {
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
