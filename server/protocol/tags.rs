//! The tags of an enum tagged by `type`, asked of serde's derived `Deserialize` itself: it is
//! given an object whose `type` is no tag (empty), and answers that the variant is unknown,
//! listing those it expects. So a list of type names is never written a second time beside
//! the enum (the corpus readers' event types, the frame types a client may send).

use std::fmt;

use serde::de::value::MapDeserializer;

/// The tags `read` (an enum's derived deserializer, given a probe) expects.
pub(crate) fn tags_of(read: fn(Probing<'_>) -> Result<(), Probe>) -> &'static [&'static str] {
    match read(MapDeserializer::new(std::iter::once(("type", "")))) {
        Err(Probe::UnknownType(tags)) => tags,
        _ => &[],
    }
}

/// An object holding only a `type`, for [`tags_of`].
pub(crate) type Probing<'a> = MapDeserializer<'a, std::iter::Once<(&'a str, &'a str)>, Probe>;

/// What a probe of a type name found: the tags serde expected, or anything else.
#[derive(Debug)]
pub(crate) enum Probe {
    /// The enum has no variant of that name; these are its tags.
    UnknownType(&'static [&'static str]),
    /// Anything else.
    Other,
}

impl fmt::Display for Probe {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Probe::UnknownType(_) => "unknown type",
            Probe::Other => "a known type",
        })
    }
}

impl std::error::Error for Probe {}

impl serde::de::Error for Probe {
    fn custom<T: fmt::Display>(_: T) -> Self {
        Probe::Other
    }

    fn unknown_variant(_: &str, expected: &'static [&'static str]) -> Self {
        Probe::UnknownType(expected)
    }
}
