//! The table as XLIFF 1.2, the version most CAT tools and translate-toolkit read: one
//! `<trans-unit>` per text, its `id` the stable key, `<source>` the default language's text,
//! `<target state="translated">` the translation (or an empty one with
//! `state="needs-translation"`), and a `<note>` saying where the original is written.
//!
//! Read back, only each unit's own `<source>` and `<target>` count (not those of
//! `<alt-trans>` suggestions); a target holding inline markup (`<g>`, `<x/>`) is reported,
//! since a spoken text cannot carry it. A target's `state` that says it is unfinished (1.2's
//! `new`, `needs-translation`, ...) is kept for the import to refuse (`refuse.rs`). XLIFF 2.0
//! is read too (`<unit>`, its `<segment>`'s `state`, `srcLang`/`trgLang` on the root).
//!
//! Reading takes time in proportion to the file's size: each byte's line is counted once, as
//! the reader goes (`Lines`), never from the start again for every element (which made a
//! 2 MB file take 49 s), and elements nest at most [`MAX_DEPTH`] deep, so the walk's look at
//! the open elements stays short (a file nested deeper is refused, not read).

use std::cell::Cell;
use std::io::{self, Write};

use quick_xml::events::{BytesDecl, BytesStart, BytesText, Event};
use quick_xml::{Reader, Writer, XmlVersion};

use crate::Language;

use super::table::Row;
use super::{Entry, Place, ReadError, ReadTable, line_of};

/// How deep elements may nest. A file Docent writes nests 5 deep (`xliff`, `file`, `body`,
/// `trans-unit`, `target`); CAT tools add `group`s and inline markup, never dozens.
pub const MAX_DEPTH: usize = 64;

/// XLIFF 1.2's namespace.
const NAMESPACE: &str = "urn:oasis:names:tc:xliff:document:1.2";

/// The first text of `rows` holding a character XML 1.0 cannot carry (a control character
/// other than tab, line feed and carriage return): its key and the character.
pub fn unwritable(rows: &[Row]) -> Option<(String, char)> {
    let bad = |c: char| c.is_control() && !matches!(c, '\t' | '\n' | '\r' | '\u{85}');
    rows.iter().find_map(|row| {
        let texts = std::iter::once(&row.source).chain(&row.translation);
        let c = texts.flat_map(|t| t.chars()).find(|&c| bad(c))?;
        Some((row.key.to_string(), c))
    })
}

/// Writes `rows` as one XLIFF `<file>` named `original` (the bundle's folder name). Check
/// [`unwritable`] first.
pub fn write_xliff(
    rows: &[Row],
    source: &Language,
    target: &Language,
    original: &str,
    out: &mut dyn Write,
) -> io::Result<()> {
    let mut w = Writer::new_with_indent(out, b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    w.create_element("xliff")
        .with_attributes([("version", "1.2"), ("xmlns", NAMESPACE)])
        .write_inner_content(|w| {
            w.create_element("file")
                .with_attributes([
                    ("original", original),
                    ("source-language", source.as_str()),
                    ("target-language", target.as_str()),
                    ("datatype", "plaintext"),
                ])
                .write_inner_content(|w| {
                    w.create_element("body")
                        .write_inner_content(|w| rows.iter().try_for_each(|row| unit(w, row)))?;
                    Ok(())
                })?;
            Ok(())
        })?;
    w.get_mut().write_all(b"\n")
}

fn unit<W: Write>(w: &mut Writer<W>, row: &Row) -> io::Result<()> {
    let id = row.key.to_string();
    w.create_element("trans-unit")
        .with_attributes([("id", id.as_str()), ("xml:space", "preserve")])
        .write_inner_content(|w| {
            w.create_element("source")
                .write_text_content(text(&row.source))?;
            let (state, translation) = match &row.translation {
                Some(t) => ("translated", t.as_str()),
                None => ("needs-translation", ""),
            };
            w.create_element("target")
                .with_attribute(("state", state))
                .write_text_content(text(translation))?;
            w.create_element("note")
                .with_attribute(("from", "docent"))
                .write_text_content(BytesText::new(&row.place))?;
            Ok(())
        })?;
    Ok(())
}

/// A text escaped for XML, a carriage return as a reference (a literal one would be read
/// back as a line feed).
fn text(value: &str) -> BytesText<'static> {
    let escaped = quick_xml::escape::escape(value).replace('\r', "&#13;");
    BytesText::from_escaped(escaped)
}

/// Reads an XLIFF 1.2 file back. `wanted` is the language asked for; without it the file's
/// `target-language` is taken.
pub fn read_xliff(
    bytes: &[u8],
    default: &Language,
    wanted: Option<&Language>,
) -> Result<ReadTable, ReadError> {
    read_counting(bytes, default, wanted, &mut 0)
}

/// [`read_xliff`], adding to `work` the bytes and open elements it looked at (what its time
/// grows with), so a test can tell linear from quadratic without a clock.
fn read_counting(
    bytes: &[u8],
    default: &Language,
    wanted: Option<&Language>,
    work: &mut u64,
) -> Result<ReadTable, ReadError> {
    let text = std::str::from_utf8(bytes).map_err(|e| ReadError::NotUtf8 {
        line: line_of(bytes, e.valid_up_to()),
    })?;
    let mut reader = Reader::from_str(text);
    let mut walk = Walk::default();
    let mut lines = Lines::new(bytes);
    let result = loop {
        let at = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
        let line = lines.at(at);
        let event = match reader.read_event() {
            Ok(event) => event,
            Err(e) => {
                break Err(ReadError::Shape(format!(
                    "the XLIFF file is not well-formed XML at line {line}: {e}"
                )));
            }
        };
        if let Err(e) = walk.event(event, line) {
            break Err(e);
        }
        if walk.ended {
            break Ok(());
        }
    };
    *work += lines.scanned + walk.looked.get();
    result?;
    walk.finish(default, wanted)
}

/// The line of a byte offset, counted as the reader goes: offsets asked for never go back,
/// so each byte is looked at once.
struct Lines<'a> {
    bytes: &'a [u8],
    offset: usize,
    line: usize,
    /// Bytes counted so far.
    scanned: u64,
}

impl<'a> Lines<'a> {
    fn new(bytes: &'a [u8]) -> Lines<'a> {
        Lines {
            bytes,
            offset: 0,
            line: 1,
            scanned: 0,
        }
    }

    /// The 1-based line of byte `offset` (at or after the last one asked for).
    fn at(&mut self, offset: usize) -> usize {
        let end = offset.min(self.bytes.len());
        if end > self.offset {
            let new = &self.bytes[self.offset..end];
            self.line += new.iter().filter(|&&b| b == b'\n').count();
            self.scanned += new.len() as u64;
            self.offset = end;
        }
        self.line
    }
}

impl Walk {
    /// Takes one event of the document at `line`.
    fn event(&mut self, event: Event<'_>, line: usize) -> Result<(), ReadError> {
        match event {
            Event::Start(e) => self.open(&e, line)?,
            Event::Empty(e) => {
                self.open(&e, line)?;
                self.close();
            }
            Event::End(_) => self.close(),
            Event::Text(t) => self.text(&t.xml10_content()),
            Event::CData(t) => self.text(&t.xml10_content()),
            Event::GeneralRef(r) => {
                let resolved = match r.resolve_char_ref() {
                    Ok(Some(c)) => Some(c.to_string()),
                    _ => quick_xml::escape::resolve_predefined_entity(&r).map(str::to_owned),
                };
                let Some(resolved) = resolved else {
                    return Err(ReadError::Shape(format!(
                        "line {line}: `&{};` is not a character XML knows",
                        &*r
                    )));
                };
                self.text(&resolved);
            }
            Event::Eof => self.ended = true,
            _ => {}
        }
        Ok(())
    }
}

/// The state of the walk through the document.
#[derive(Default)]
struct Walk {
    /// The names of the open elements.
    open: Vec<String>,
    source_language: Option<String>,
    target_language: Option<String>,
    /// The unit being read.
    unit: Option<Unit>,
    table: Vec<Entry>,
    notes: Vec<String>,
    /// The end of the document was read.
    ended: bool,
    /// Open elements looked at, for [`read_counting`].
    looked: Cell<u64>,
}

/// A `<trans-unit>` being read.
struct Unit {
    line: usize,
    id: String,
    source: Option<String>,
    target: Option<String>,
    /// The inline element found in the target, if any.
    markup: Option<String>,
    /// The target's (or XLIFF 2 segment's) `state`, when it says the target is unfinished.
    unfinished: Option<String>,
}

/// The `state`s that say a target is not translated yet: XLIFF 1.2's `new` and `needs-*`
/// (but not `needs-review-*`, which are translations to review), XLIFF 2's `initial`.
const UNFINISHED: [&str; 5] = [
    "new",
    "needs-translation",
    "needs-adaptation",
    "needs-l10n",
    "initial",
];

impl Walk {
    fn open(&mut self, e: &BytesStart<'_>, line: usize) -> Result<(), ReadError> {
        if self.open.len() >= MAX_DEPTH {
            return Err(ReadError::Shape(format!(
                "line {line}: elements are nested more than {MAX_DEPTH} deep, which no XLIFF \
                 file of translations needs (Docent's nest 5 deep); export the table again and \
                 fill that in"
            )));
        }
        let name = e.local_name().as_ref().to_owned();
        // Without quick-xml's duplicate check, which compares every attribute with every
        // other: an element with very many attributes would take the square of their number.
        let attribute = |wanted: &str| {
            e.attributes().with_checks(false).flatten().find_map(|a| {
                (a.key.local_name().as_ref() == wanted)
                    .then(|| a.normalized_value(XmlVersion::Implicit1_0).ok())
                    .flatten()
                    .map(|v| v.into_owned())
            })
        };
        let parent = self.open.last().map(String::as_str);
        match (parent, name.as_str()) {
            (_, "file") => {
                let target = attribute("target-language");
                if let (Some(before), Some(now)) = (&self.target_language, &target)
                    && !before.eq_ignore_ascii_case(now)
                {
                    return Err(ReadError::Shape(format!(
                        "line {line}: this <file> is in `{now}`, an earlier one in `{before}`; \
                         import one language at a time"
                    )));
                }
                self.target_language = target.or(self.target_language.take());
                self.source_language = attribute("source-language").or(self.source_language.take());
            }
            // XLIFF 2 names the languages on the root element.
            (None, "xliff") => {
                self.target_language = attribute("trgLang");
                self.source_language = attribute("srcLang");
            }
            (_, "trans-unit" | "unit") => {
                self.unit = Some(Unit {
                    line,
                    id: attribute("id").unwrap_or_default(),
                    source: None,
                    target: None,
                    markup: None,
                    unfinished: None,
                });
            }
            (Some("unit"), "segment") => self.note_state(attribute("state")),
            (Some("trans-unit" | "segment"), "source") => {
                if let Some(unit) = &mut self.unit {
                    unit.source.get_or_insert_default();
                }
            }
            (Some("trans-unit" | "segment"), "target") => {
                self.note_state(attribute("state"));
                if let Some(unit) = &mut self.unit {
                    unit.target.get_or_insert_default();
                }
            }
            (Some("target"), _) if self.in_unit_part("target") => {
                if let Some(unit) = &mut self.unit {
                    unit.markup.get_or_insert(format!("<{name}>"));
                }
            }
            _ => {}
        }
        self.open.push(name);
        Ok(())
    }

    /// Keeps a target's `state` when it says the target is unfinished.
    fn note_state(&mut self, state: Option<String>) {
        let unfinished = state.filter(|s| UNFINISHED.contains(&s.trim()));
        if let (Some(unit), Some(state)) = (&mut self.unit, unfinished) {
            unit.unfinished = Some(state);
        }
    }

    /// Whether the innermost open `part` (`source`, `target`) is the unit's own.
    fn in_unit_part(&self, part: &str) -> bool {
        let n = self.open.len();
        self.looked.set(self.looked.get() + n as u64);
        let found = self.open.iter().rposition(|name| name == part);
        let parent = |i: usize| matches!(self.open[i - 1].as_str(), "trans-unit" | "segment");
        found.is_some_and(|i| i > 0 && parent(i) && i < n)
    }

    fn text(&mut self, text: &str) {
        let source = self.in_unit_part("source");
        let target = self.in_unit_part("target");
        let Some(unit) = &mut self.unit else { return };
        let part = match (self.open.last().map(String::as_str), source, target) {
            (Some("source"), true, _) => unit.source.as_mut(),
            (Some("target"), _, true) => unit.target.as_mut(),
            // Text inside inline markup: kept so a reader sees the words, reported anyway.
            (_, _, true) => unit.target.as_mut(),
            (_, true, _) => unit.source.as_mut(),
            _ => None,
        };
        if let Some(part) = part {
            part.push_str(text);
        }
    }

    fn close(&mut self) {
        if matches!(self.open.pop().as_deref(), Some("trans-unit" | "unit"))
            && let Some(unit) = self.unit.take()
        {
            let key = unit.id.trim().to_owned();
            if let Some(markup) = &unit.markup {
                self.notes.push(format!(
                    "line {} ({key}): the target contains markup ({markup}), which a spoken \
                     text cannot hold; it is not imported. Write it as plain text.",
                    unit.line
                ));
                return;
            }
            self.table.push(Entry {
                place: Place::Line(unit.line),
                line: unit.line,
                columns: None,
                unfinished: unit.unfinished,
                key,
                source: unit.source,
                translation: unit.target.unwrap_or_default(),
            });
        }
    }

    fn finish(self, default: &Language, wanted: Option<&Language>) -> Result<ReadTable, ReadError> {
        let mut notes = self.notes;
        let language = match (wanted, self.target_language) {
            (Some(wanted), Some(written)) if Language::parse(&written).as_ref() != Some(wanted) => {
                return Err(ReadError::Shape(format!(
                    "the XLIFF file's translations are in `{written}` (target-language), not \
                     `{wanted}` as --language says"
                )));
            }
            (_, Some(written)) => written,
            (Some(wanted), None) => wanted.to_string(),
            (None, None) => {
                return Err(ReadError::Shape(
                    "the XLIFF file names no target-language: say which language its \
                     translations are in with --language"
                        .to_owned(),
                ));
            }
        };
        if let Some(source) = self.source_language
            && Language::parse(&source).as_ref() != Some(default)
        {
            notes.push(format!(
                "The file's source-language is `{source}`, but the bundle's originals are in \
                 `{default}`: each changed original is reported below."
            ));
        }
        Ok(ReadTable {
            language,
            entries: self.table,
            notes,
        })
    }
}

#[cfg(test)]
#[path = "xliff_tests.rs"]
mod tests;
