//! ELAN's EAF 3.0, written as ELAN 6.9 writes it (`shared/notes/corpus-formats.md`): the
//! schema's element order (`HEADER`, `TIME_ORDER`, `TIER`s, `LINGUISTIC_TYPE`s, `LANGUAGE`,
//! the four `CONSTRAINT`s ELAN always writes, `CONTROLLED_VOCABULARY`), times in milliseconds
//! on the session clock, one `xsd:ID` space (time slots `ts1`..., annotations `a1`...,
//! vocabulary entries `cveid_1`..., the language `und`, each kind of name distinct from the
//! others). The `act` tiers are `Symbolic_Association` children of their `speech` tier: one
//! `REF_ANNOTATION` per utterance, its `CVE_REF` naming the act's label in the vocabulary.
//! Points (touches, marks) are 1 ms annotations, since ELAN has no point tiers. Each codebook
//! tier's annotations (its intervals, then its points) have a linguistic type `coded-TIER`
//! whose controlled vocabulary `codebook-TIER` is the tier's codes, and each annotation names
//! its code by `CVE_REF`. The `HEADER` links each recording's WAV copy (`wav.rs`) by a
//! `MEDIA_DESCRIPTOR`: `MEDIA_URL` absolute, `RELATIVE_MEDIA_URL` beside the EAF, no
//! `TIME_ORIGIN` (the copy starts at session time 0), `EXTRACTED_FROM` the WebM. The WebMs
//! themselves are not linked: a video's origin would be negative (`docs/CORPUS.md`).

mod elements;

use std::io;

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesText, Event};

use crate::export::tiers::{Annotation, CodedTier, MIN_INTERVAL_US, Point, Tiers};
use elements::{
    EVENT_TYPE, INSTANT_TYPE, LABEL_TYPE, UTTERANCE_TYPE, annotation, coded_codes, coded_entry,
    coded_type, coded_types, controlled_vocabulary, eaf_date, language_and_constraints,
    linguistic_types, xml_text,
};

/// The schema ELAN names in every file it writes.
const SCHEMA: &str = "http://www.mpi.nl/tools/elan/EAFv3.0.xsd";
/// What the header says about the session.
pub struct Header<'a> {
    /// The session's start (RFC 3339), the document's `DATE`: the same session gives the same
    /// file.
    pub date: &'a str,
    /// The session's name.
    pub session: &'a str,
    /// The Docent that recorded it.
    pub docent: &'a str,
    /// The media ELAN plays with it.
    pub media: &'a [MediaLink],
}

/// A `MEDIA_DESCRIPTOR`: a WAV copy of a recording, starting at session time 0.
pub struct MediaLink {
    /// `file://` and the WAV's absolute path.
    pub url: String,
    /// `./NAME.audio-1.wav`: the WAV beside the EAF.
    pub relative: String,
    /// The recording it was made from, relative to the EAF's folder.
    pub extracted_from: String,
}

/// An annotation that has its own times, in file order.
struct Aligned<'a> {
    tier: usize,
    start_ms: u64,
    end_ms: u64,
    value: &'a str,
    /// The vocabulary entry its value is (codebook tiers).
    cve: Option<String>,
}

/// A tier in file order.
struct TierOut<'a> {
    name: &'a str,
    kind: String,
    /// The parent of an act tier, with its labels.
    parent: Option<(&'a str, &'a [String])>,
}

/// The EAF of `tiers`, with `vocabulary` (sorted act labels); and how many characters that
/// XML cannot hold were replaced. (Written into memory: an error is quick-xml's own.)
pub fn write(
    tiers: &Tiers,
    vocabulary: &[String],
    header: &Header,
) -> io::Result<(Vec<u8>, usize)> {
    let (out, aligned) = layout(tiers);
    // ELAN numbers time slots in time order; boundary `2i` starts annotation `i`, `2i+1` ends it.
    let boundary = |i: usize| match i % 2 {
        0 => aligned[i / 2].start_ms,
        _ => aligned[i / 2].end_ms,
    };
    let mut order: Vec<usize> = (0..2 * aligned.len()).collect();
    order.sort_by_key(|&i| boundary(i));
    let mut slot = vec![0; order.len()];
    for (n, &i) in order.iter().enumerate() {
        slot[i] = n + 1;
    }
    let times = order.iter().map(|&i| boundary(i)).collect();
    let mut doc = Document {
        out,
        aligned,
        times,
        slot,
        vocabulary,
        coded: &tiers.coded,
        header,
        replaced: 0,
    };
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 4);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    w.create_element("ANNOTATION_DOCUMENT")
        .with_attributes([
            ("AUTHOR", ""),
            ("DATE", &eaf_date(header.date)),
            ("FORMAT", "3.0"),
            ("VERSION", "3.0"),
            ("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance"),
            ("xsi:noNamespaceSchemaLocation", SCHEMA),
        ])
        .write_inner_content(|w| doc.body(w))?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    Ok((bytes, doc.replaced))
}

/// What the document is written from.
struct Document<'a> {
    out: Vec<TierOut<'a>>,
    aligned: Vec<Aligned<'a>>,
    /// The time slots' values, in order (`ts1` first).
    times: Vec<u64>,
    /// The time slot of each boundary (`2i` the start of annotation `i`, `2i+1` its end).
    slot: Vec<usize>,
    vocabulary: &'a [String],
    /// The codebook tiers, for their types and vocabularies.
    coded: &'a [CodedTier],
    header: &'a Header<'a>,
    replaced: usize,
}

/// The XML being written.
pub(super) type Out = Writer<Vec<u8>>;

impl Document<'_> {
    /// `text` as XML can hold it (counting what had to be replaced).
    fn clean(&mut self, text: &str) -> String {
        xml_text(text, &mut self.replaced)
    }

    /// Everything inside `ANNOTATION_DOCUMENT`, in the schema's order.
    fn body(&mut self, w: &mut Out) -> io::Result<()> {
        self.head(w)?;
        w.create_element("TIME_ORDER").write_inner_content(|w| {
            for (n, time) in self.times.iter().enumerate() {
                w.create_element("TIME_SLOT")
                    .with_attribute(("TIME_SLOT_ID", format!("ts{}", n + 1).as_str()))
                    .with_attribute(("TIME_VALUE", time.to_string().as_str()))
                    .write_empty()?;
            }
            Ok(())
        })?;
        self.tiers(w)?;
        linguistic_types(w)?;
        coded_types(w, self.coded.iter().map(|c| c.name.as_str()))?;
        language_and_constraints(w)?;
        let entries: Vec<String> = (self.vocabulary.iter()).map(|l| self.clean(l)).collect();
        controlled_vocabulary(w, &entries)?;
        for coded in self.coded {
            let codes: Vec<String> = coded.codes.iter().map(|c| self.clean(c)).collect();
            coded_codes(w, &coded.name, &codes)?;
        }
        Ok(())
    }

    fn head(&mut self, w: &mut Out) -> io::Result<()> {
        let labels: usize = self
            .out
            .iter()
            .map(|t| t.parent.map_or(0, |p| p.1.len()))
            .sum();
        let properties = [
            ("docent-session", self.clean(self.header.session)),
            ("docent-version", self.clean(self.header.docent)),
            (
                "lastUsedAnnotationId",
                (self.aligned.len() + labels).to_string(),
            ),
        ];
        let head = [("MEDIA_FILE", ""), ("TIME_UNITS", "milliseconds")];
        w.create_element("HEADER")
            .with_attributes(head)
            .write_inner_content(|w| {
                for link in self.header.media {
                    w.create_element("MEDIA_DESCRIPTOR")
                        .with_attributes([
                            ("MEDIA_URL", link.url.as_str()),
                            ("MIME_TYPE", "audio/x-wav"),
                            ("RELATIVE_MEDIA_URL", link.relative.as_str()),
                            ("EXTRACTED_FROM", link.extracted_from.as_str()),
                        ])
                        .write_empty()?;
                }
                for (name, value) in properties {
                    w.create_element("PROPERTY")
                        .with_attribute(("NAME", name))
                        .write_text_content(BytesText::new(&value))?;
                }
                Ok(())
            })?;
        Ok(())
    }

    /// The tiers: time-aligned annotations numbered first (`a1`...), in file order, then the
    /// act labels that refer to them.
    fn tiers(&mut self, w: &mut Out) -> io::Result<()> {
        let mut next_aligned = 0;
        let mut next_ref = self.aligned.len();
        for t in 0..self.out.len() {
            let tier = &self.out[t];
            let (name, kind, parent) = (tier.name, tier.kind.clone(), tier.parent);
            let mut element = w.create_element("TIER");
            element = element.with_attribute(("LINGUISTIC_TYPE_REF", kind.as_str()));
            if let Some((parent, _)) = parent {
                element = element.with_attribute(("PARENT_REF", parent));
            }
            let element = element.with_attribute(("TIER_ID", name));
            let first = next_aligned;
            let mine = (self.aligned[first..].iter())
                .take_while(|a| a.tier == t)
                .count();
            next_aligned += mine;
            let labels = parent.map_or(&[][..], |(_, labels)| labels);
            if mine + labels.len() == 0 {
                element.write_empty()?;
                continue;
            }
            element.write_inner_content(|w| {
                for id in first..first + mine {
                    let mut attributes = vec![
                        ("ANNOTATION_ID", format!("a{}", id + 1)),
                        ("TIME_SLOT_REF1", format!("ts{}", self.slot[2 * id])),
                        ("TIME_SLOT_REF2", format!("ts{}", self.slot[2 * id + 1])),
                    ];
                    if let Some(cve) = &self.aligned[id].cve {
                        attributes.push(("CVE_REF", cve.clone()));
                    }
                    let value = self.clean(self.aligned[id].value);
                    annotation(w, "ALIGNABLE_ANNOTATION", &attributes, &value)?;
                }
                // The parent's annotations are the ones just before this tier.
                let parents = first - labels.len();
                for (i, label) in labels.iter().enumerate() {
                    next_ref += 1;
                    let cve = self.vocabulary.binary_search(label).map_or(0, |n| n + 1);
                    let attributes = [
                        ("ANNOTATION_ID", format!("a{next_ref}")),
                        ("ANNOTATION_REF", format!("a{}", parents + i + 1)),
                        ("CVE_REF", format!("cveid_{cve}")),
                    ];
                    let value = self.clean(label);
                    annotation(w, "REF_ANNOTATION", &attributes, &value)?;
                }
                Ok(())
            })?;
        }
        Ok(())
    }
}

/// The tiers in file order, and every time-aligned annotation in file order.
fn layout(tiers: &Tiers) -> (Vec<TierOut<'_>>, Vec<Aligned<'_>>) {
    let mut out = Vec::new();
    let mut aligned = Vec::new();
    for s in &tiers.speech {
        let name = s.speech.name.as_str();
        let utterances = spans(&s.speech.annotations);
        add(
            &mut out,
            &mut aligned,
            name,
            UTTERANCE_TYPE,
            None,
            utterances,
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
        let events = spans(&tier.annotations);
        add(&mut out, &mut aligned, &tier.name, EVENT_TYPE, None, events);
    }
    for tier in tiers.point_tiers() {
        let points = point_spans(&tier.points);
        add(
            &mut out,
            &mut aligned,
            &tier.name,
            INSTANT_TYPE,
            None,
            points,
        );
    }
    for coded in &tiers.coded {
        let kind = coded_type(&coded.name);
        let intervals = (coded.intervals.iter()).map(|t| (&t.name, spans(&t.annotations)));
        let points = (coded.points.iter()).map(|t| (&t.name, point_spans(&t.points)));
        for (name, spans) in intervals.chain(points) {
            let first = aligned.len();
            add(&mut out, &mut aligned, name, &kind, None, spans);
            // Each annotation names its code in the tier's vocabulary.
            for a in &mut aligned[first..] {
                let n = coded
                    .codes
                    .iter()
                    .position(|c| c == a.value)
                    .map_or(0, |n| n + 1);
                a.cve = Some(coded_entry(&coded.name, n));
            }
        }
    }
    (out, aligned)
}

/// Points as the 1 ms annotations ELAN draws them as.
fn point_spans(points: &[Point]) -> Vec<Span<'_>> {
    (points.iter())
        .map(|p| (p.at_us, p.at_us + MIN_INTERVAL_US, p.value.as_str()))
        .collect()
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
    kind: &str,
    parent: Option<(&'a str, &'a [String])>,
    spans: Vec<Span<'a>>,
) {
    let tier = out.len();
    let kind = kind.to_owned();
    out.push(TierOut { name, kind, parent });
    aligned.extend(spans.into_iter().map(|(start_us, end_us, value)| Aligned {
        tier,
        start_ms: start_us / 1000,
        end_ms: end_us / 1000,
        value,
        cve: None,
    }));
}
