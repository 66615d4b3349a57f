//! The serde side of the located tree: a visitor that accepts any YAML node with its
//! `Spanned` positions, then a conversion into [`Node`] that turns serde-saphyr's `Location`
//! into our `Pos` and recovers the text of type-guessed scalars from the source.

use std::fmt;
use std::sync::Arc;

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_saphyr::{Location, Spanned};

use super::{Kind, Node};
use crate::model::Pos;

/// A node as serde-saphyr hands it over.
pub(super) enum Raw {
    Str(String),
    /// A guessed scalar, formatted by us: only used when the source text is unavailable.
    Guessed(String),
    Null,
    Seq(Vec<Spanned<Raw>>),
    Map(Vec<(Spanned<Raw>, Spanned<Raw>)>),
}

impl<'de> Deserialize<'de> for Raw {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(RawVisitor)
    }
}

struct RawVisitor;

impl<'de> Visitor<'de> for RawVisitor {
    type Value = Raw;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any YAML value")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Raw, E> {
        Ok(Raw::Str(v.to_owned()))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Raw, E> {
        Ok(Raw::Str(v))
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Raw, E> {
        Ok(Raw::Guessed(v.to_string()))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Raw, E> {
        Ok(Raw::Guessed(v.to_string()))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Raw, E> {
        Ok(Raw::Guessed(v.to_string()))
    }

    fn visit_i128<E: de::Error>(self, v: i128) -> Result<Raw, E> {
        Ok(Raw::Guessed(v.to_string()))
    }

    fn visit_u128<E: de::Error>(self, v: u128) -> Result<Raw, E> {
        Ok(Raw::Guessed(v.to_string()))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Raw, E> {
        Ok(Raw::Guessed(v.to_string()))
    }

    fn visit_unit<E: de::Error>(self) -> Result<Raw, E> {
        Ok(Raw::Null)
    }

    fn visit_none<E: de::Error>(self) -> Result<Raw, E> {
        Ok(Raw::Null)
    }

    fn visit_some<D: Deserializer<'de>>(self, deserializer: D) -> Result<Raw, D::Error> {
        Raw::deserialize(deserializer)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Raw, A::Error> {
        let mut items = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1024));
        while let Some(item) = seq.next_element()? {
            items.push(item);
        }
        Ok(Raw::Seq(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Raw, A::Error> {
        let mut entries = Vec::new();
        while let Some(entry) = map.next_entry()? {
            entries.push(entry);
        }
        Ok(Raw::Map(entries))
    }
}

/// Our position for a serde-saphyr location in `file`.
pub(super) fn pos(file: &Arc<str>, location: &Location) -> Pos {
    let clamp = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
    Pos::new(
        file.clone(),
        clamp(location.line()),
        clamp(location.column()),
    )
}

/// Where a parsed text starts in its file: a top-level item parsed on its own starts some
/// lines and bytes in.
#[derive(Clone, Copy)]
pub(super) struct Origin {
    /// Lines before the text.
    pub line: u32,
    /// Bytes before the text.
    pub byte: usize,
}

impl Origin {
    /// The whole file.
    pub const START: Origin = Origin { line: 0, byte: 0 };
}

/// Converts the serde tree into ours. `source` is the text that was parsed, which starts at
/// `origin` in the file. Recursion depth is bounded by the parser budget.
pub(super) fn into_node(
    spanned: Spanned<Raw>,
    file: &Arc<str>,
    source: &str,
    origin: Origin,
) -> Node {
    let range = byte_range(&spanned.defined);
    let written = || range.clone().and_then(|r| source.get(r));
    let is_scalar = matches!(spanned.value, Raw::Str(_) | Raw::Guessed(_));
    let kind = match spanned.value {
        Raw::Str(value) => {
            let verbatim_at = written().and_then(|w| verbatim_offset(w, &value));
            Kind::Str { value, verbatim_at }
        }
        Raw::Guessed(formatted) => Kind::Guessed(written().map_or(formatted, str::to_owned)),
        Raw::Null => Kind::Null,
        Raw::Seq(items) => Kind::Seq(
            items
                .into_iter()
                .map(|i| into_node(i, file, source, origin))
                .collect(),
        ),
        Raw::Map(entries) => Kind::Map(
            entries
                .into_iter()
                .map(|(k, v)| {
                    (
                        into_node(k, file, source, origin),
                        into_node(v, file, source, origin),
                    )
                })
                .collect(),
        ),
    };
    let mut pos = pos(file, &spanned.referenced);
    pos.line = pos.line.saturating_add(origin.line);
    let span = range
        .filter(|_| is_scalar)
        .map(|r| r.start + origin.byte..r.end + origin.byte);
    Node { pos, span, kind }
}

/// The bytes of the parsed text a node was read from, when the parser reported them.
fn byte_range(location: &Location) -> Option<std::ops::Range<usize>> {
    let span = location.span();
    let start = usize::try_from(span.byte_offset()?).ok()?;
    let len = usize::try_from(span.byte_len()?).ok()?;
    Some(start..start.checked_add(len)?)
}

/// Where `value` starts inside `written` when it appears there unchanged on one line:
/// 0 for plain text, 1 inside quotes.
pub(super) fn verbatim_offset(written: &str, value: &str) -> Option<u32> {
    if written.contains('\n') {
        return None;
    }
    if written == value {
        return Some(0);
    }
    let inner = written
        .strip_prefix('"')
        .and_then(|w| w.strip_suffix('"'))
        .or_else(|| {
            written
                .strip_prefix('\'')
                .and_then(|w| w.strip_suffix('\''))
        })?;
    (inner == value).then_some(1)
}
