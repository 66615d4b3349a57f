//! The fast reader: builds the located [`Node`] tree straight from granit-parser's events,
//! skipping serde-saphyr's serde layer (about three quarters of the parse time on a large
//! acts file).
//!
//! It handles only the plain shape of our files: one document of scalars, lists and keyed
//! maps, without anchors, aliases, tags or merge keys. On anything else (and on every parse
//! error) it gives up with `None`, and the serde-saphyr path reads the file instead, so every
//! error message and position stays exactly as before. The tree it builds is the one the
//! serde path builds (a differential test in `fast_tests.rs` holds it to that).

use std::sync::Arc;

use granit_parser::{Event, Parser, ScalarStyle, Span, StrInput};

use super::raw::{self, Raw};
use super::{Kind, Node};
use crate::model::Pos;

/// Deeper nesting is left to serde-saphyr, whose budget refuses more than 64 levels.
const MAX_DEPTH: usize = 60;
/// Stay well inside the budget in `options()` (10,000,000 events, 4,000,000 nodes), so a
/// file near a limit goes through serde-saphyr and gets its exact error.
const MAX_EVENTS: usize = 9_000_000;
const MAX_NODES: usize = 3_500_000;
/// serde-saphyr's budget stops at 64 MiB of scalar text.
const MAX_SCALAR_BYTES: usize = 32 * 1024 * 1024;

/// The tree of `source` (the whole content of `file`), or `None` when the serde-saphyr path
/// must read it (an error, or a feature this reader does not handle).
pub(super) fn read(file: &Arc<str>, source: &str) -> Option<Node> {
    let mut reader = Reader {
        events: Parser::with_options(StrInput::new(source), parser_options()),
        file,
        source,
        events_seen: 0,
        nodes: 0,
        scalar_bytes: 0,
    };
    let Event::StreamStart = reader.next()?.0 else {
        return None;
    };
    // An empty stream gets a null placed by serde-saphyr's own bookkeeping: leave it to it.
    let Event::DocumentStart(..) = reader.next()?.0 else {
        return None;
    };
    let (event, span) = reader.next()?;
    let root = reader.node(event, &span, 0)?;
    let Event::DocumentEnd = reader.next()?.0 else {
        return None;
    };
    // A second document is an error for serde-saphyr.
    let Event::StreamEnd = reader.next()?.0 else {
        return None;
    };
    reader.events.next().is_none().then_some(root)
}

/// The parser settings serde-saphyr derives from the budget in `options()`, so both readers
/// accept and refuse the same texts.
fn parser_options() -> granit_parser::Options {
    let mut options = granit_parser::Options::default();
    options.simple_key_max_lookahead = 1024;
    options.flow_nesting_limit = 255;
    options.block_nesting_limit = options.block_nesting_limit.max(65);
    options.emit_comments = false;
    options.strict_indentation = false;
    options
}

struct Reader<'a> {
    events: Parser<'a, StrInput<'a>>,
    file: &'a Arc<str>,
    source: &'a str,
    events_seen: usize,
    nodes: usize,
    scalar_bytes: usize,
}

impl<'a> Reader<'a> {
    /// The next event, or `None` on a parse error, the end, or past the event limit.
    fn next(&mut self) -> Option<(Event<'a>, Span)> {
        let item = self.events.next()?.ok()?;
        self.events_seen += 1;
        (self.events_seen <= MAX_EVENTS).then_some(item)
    }

    /// Counts a node against the limits.
    fn count_node(&mut self) -> Option<()> {
        self.nodes += 1;
        (self.nodes <= MAX_NODES).then_some(())
    }

    fn pos(&self, span: &Span) -> Pos {
        let clamp = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        Pos::new(
            self.file.clone(),
            clamp(span.start.line()),
            clamp(span.start.col().saturating_add(1)),
        )
    }

    /// The node that starts with `event`, read to its end.
    fn node(&mut self, event: Event<'a>, span: &Span, depth: usize) -> Option<Node> {
        match event {
            Event::Scalar(value, style, 0, None) => {
                self.count_node()?;
                self.scalar_bytes = self.scalar_bytes.saturating_add(value.len());
                if self.scalar_bytes > MAX_SCALAR_BYTES {
                    return None;
                }
                let range = span.start.byte_offset()?..span.end.byte_offset()?;
                let written = self.source.get(range.clone())?;
                let kind = scalar_kind(value.as_ref(), style, written)?;
                let bytes = match kind {
                    Kind::Null => None,
                    _ => Some(range),
                };
                Some(Node {
                    pos: self.pos(span),
                    span: bytes,
                    kind,
                })
            }
            Event::SequenceStart(_, 0, None) if depth < MAX_DEPTH => {
                self.count_node()?;
                let pos = self.pos(span);
                let mut items = Vec::new();
                loop {
                    let (event, span) = self.next()?;
                    if let Event::SequenceEnd = event {
                        break;
                    }
                    items.push(self.node(event, &span, depth + 1)?);
                }
                Some(Node {
                    pos,
                    span: None,
                    kind: Kind::Seq(items),
                })
            }
            Event::MappingStart(_, 0, None) if depth < MAX_DEPTH => {
                self.count_node()?;
                let pos = self.pos(span);
                let mut entries = Vec::new();
                loop {
                    let (event, span) = self.next()?;
                    if let Event::MappingEnd = event {
                        break;
                    }
                    // Merge keys and keys that are lists or maps are serde-saphyr's to judge.
                    match &event {
                        Event::Scalar(key, ScalarStyle::Plain, ..) if key == "<<" => return None,
                        Event::Scalar(..) => {}
                        _ => return None,
                    }
                    let key = self.node(event, &span, depth + 1)?;
                    let (event, span) = self.next()?;
                    let value = self.node(event, &span, depth + 1)?;
                    entries.push((key, value));
                }
                Some(Node {
                    pos,
                    span: None,
                    kind: Kind::Map(entries),
                })
            }
            // Anchors, aliases, tags, too deep, or an event out of place.
            _ => None,
        }
    }
}

/// What a scalar is, as serde-saphyr's `deserialize_any` decides it; `written` is its text in
/// the source. `None` when in doubt.
fn scalar_kind(value: &str, style: ScalarStyle, written: &str) -> Option<Kind> {
    if style != ScalarStyle::Plain {
        return Some(Kind::Str {
            value: value.to_owned(),
            verbatim_at: raw::verbatim_offset(written, value),
        });
    }
    if matches!(value, "" | "~" | "null" | "Null" | "NULL") {
        return Some(Kind::Null);
    }
    if !may_be_typed(value) {
        return Some(Kind::Str {
            value: value.to_owned(),
            verbatim_at: raw::verbatim_offset(written, value),
        });
    }
    // Rare (numbers, yes/no): let serde-saphyr type the text itself, so its rules (octal,
    // underscores, overflow, infinities) hold exactly.
    match serde_saphyr::from_str_with_options::<Raw>(value, super::options()).ok()? {
        Raw::Guessed(_) => Some(Kind::Guessed(written.to_owned())),
        Raw::Str(text) if text == value => Some(Kind::Str {
            verbatim_at: raw::verbatim_offset(written, &text),
            value: text,
        }),
        _ => None,
    }
}

/// Whether YAML could take a plain scalar for a boolean or a number: numbers start with a
/// digit, a sign or a dot (`.inf`); booleans are a handful of words.
fn may_be_typed(value: &str) -> bool {
    let starts_like_number = value
        .as_bytes()
        .first()
        .is_some_and(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.'));
    starts_like_number
        || ["y", "yes", "n", "no", "true", "false", "on", "off"]
            .iter()
            .any(|word| value.eq_ignore_ascii_case(word))
}
